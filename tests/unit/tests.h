/* tests: the list of unit tests, one X(name) per test function. Each file
 * tests/unit/test_*.c defines the functions it lists here. */
#ifndef PM_TESTS_H
#define PM_TESTS_H

#define TEST_LIST(X)                   \
    X(kdtree_matches_brute_force)      \
    X(kdtree_edge_cases)               \
    X(kdtree_nearest_if)               \
    X(kdtree_query_matches_brute_force) \
    X(kdtree_query_hints)              \
    X(kdtree_query_history_independent) \
    X(kdtree_query_state)              \
    X(kdtree_query_avx2)               \
    X(kdtree_build_memory)             \
    X(kdtree_select_base)              \
    X(kdtree_select_avx2)              \
    X(sphere_hits)                     \
    X(rect_hits)                       \
    X(rect_aligned_path_is_exact)      \
    X(fresnel_energy_and_tir)          \
    X(refract_snell)                   \
    X(cosine_sampling_mean)            \
    X(rng_streams)                     \
    X(scene_parses_cornell)            \
    X(scene_errors)                    \
    X(photon_power_closed_box)         \
    X(furnace_sphere)                  \
    X(diffuse_plane_matches_analytic)  \
    X(cornell_finite_and_deterministic)\
    X(exr_round_trip)                  \
    X(precomputed_equals_conventional_on_uniform_plane) \
    X(precomputed_converges_on_cornell) \
    X(precomputed_normal_test_at_corner) \
    X(precomputed_extremes)            \
    X(precomputed_rep_count)           \
    X(precomputed_dump_reps)           \
    X(stability_nn_one_and_at_stored_count) \
    X(stability_coincident_photons)    \
    X(stability_few_or_no_photons_in_range) \
    X(stability_no_agreeing_representative) \
    X(stability_photon_counts)         \
    X(stability_light_power_extremes)  \
    X(stability_scene_scale)           \
    X(stability_grazing_rays)          \
    X(stability_camera_inside_glass)   \
    X(stability_tir_depth_limit)       \
    X(stability_exr_round_trip_of_renders) \
    X(stability_parser_degenerate_sizes) \
    X(bvh_matches_brute_force)         \
    X(bvh_degenerate_sets)             \
    X(bvh_scene_switch)                \
    X(bvh_parser_stays_linear)

#define TEST_DECLARE(name) void test_##name(void);
TEST_LIST(TEST_DECLARE)

#endif

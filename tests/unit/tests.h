/* tests: the list of unit tests, one X(name) per test function. Each file
 * tests/unit/test_*.c defines the functions it lists here. */
#ifndef PM_TESTS_H
#define PM_TESTS_H

#define TEST_LIST(X) \
    /* test_kdtree.c */ \
    X(kdtree_matches_brute_force) \
    X(kdtree_edge_cases) \
    X(kdtree_nearest_if) \
    X(kdtree_nearest_if_hints) \
    X(kdtree_query_matches_brute_force) \
    X(kdtree_query_hints) \
    X(kdtree_query_history_independent) \
    X(kdtree_query_state) \
    X(kdtree_query_avx2) \
    X(kdtree_build_memory) \
    X(kdtree_build_threads) \
    /* test_mem.c */ \
    X(mem_round) \
    X(mem_buffers) \
    /* test_scale.c */ \
    X(kdtree_build_items) \
    X(photons_map_matches_plain_build) \
    X(photons_peak_memory) \
    /* test_kdtree_stream.c */ \
    X(kdtree_stream_base) \
    X(kdtree_stream_avx2) \
    /* test_kdtree_select.c */ \
    X(kdtree_select_base) \
    X(kdtree_select_avx2) \
    /* test_shapes.c */ \
    X(sphere_hits) \
    X(rect_hits) \
    X(rect_aligned_path_is_exact) \
    /* test_material.c */ \
    X(fresnel_energy_and_tir) \
    X(refract_snell) \
    X(cosine_sampling_mean) \
    /* test_rng.c */ \
    X(rng_streams) \
    /* test_scene.c */ \
    X(scene_parses_cornell) \
    X(scene_errors) \
    X(stability_parser_degenerate_sizes) \
    /* test_photons.c */ \
    X(photon_power_closed_box) \
    /* test_estimate.c */ \
    X(stability_nn_one_and_at_stored_count) \
    X(stability_coincident_photons) \
    X(stability_floor_stops_at_the_extent) \
    X(stability_few_or_no_photons_in_range) \
    /* test_reps.c */ \
    X(precomputed_equals_conventional_on_uniform_plane) \
    X(precomputed_normal_test_at_corner) \
    X(precomputed_rep_count) \
    X(precomputed_dump_reps) \
    X(stability_no_agreeing_representative) \
    X(reps_lazy_equals_eager) \
    X(reps_plane_gate) \
    /* test_render.c */ \
    X(furnace_sphere) \
    X(diffuse_plane_matches_analytic) \
    X(cornell_finite_and_deterministic) \
    X(stability_photon_counts) \
    X(stability_light_power_extremes) \
    X(stability_scene_scale) \
    X(stability_grazing_rays) \
    X(stability_camera_inside_glass) \
    X(stability_tir_depth_limit) \
    X(stability_exr_round_trip_of_renders) \
    X(precomputed_converges_on_cornell) \
    X(precomputed_extremes) \
    /* test_cli.c */ \
    X(cli_render_given) \
    X(cli_parses_every_kind) \
    X(cli_usage_lists_defaults_and_ranges) \
    /* test_config.c */ \
    X(config_defaults) \
    X(config_check) \
    /* test_outfile.c */ \
    X(outfile_whole_or_nothing) \
    /* test_utf8.c */ \
    X(utf8_sequences) \
    /* test_status.c */ \
    X(status_codes) \
    /* test_image.c */ \
    X(exr_round_trip) \
    /* test_bvh.c */ \
    X(bvh_matches_brute_force) \
    X(bvh_degenerate_sets) \
    X(bvh_scene_switch) \
    X(bvh_parser_stays_linear) \
    /* test_work.c */ \
    X(work_kdtree_by_hand) \
    X(work_one_photon_by_hand) \
    X(work_same_for_any_thread_count) \
    X(repeat_same_bits) \
    X(repeat_rule) \
    /* test_gather.c */ \
    X(gather_strata) \
    X(gather_directions) \
    X(gather_furnace) \
    X(gather_threads_and_shared_rays) \
    X(gather_maps)

#define TEST_DECLARE(name) void test_##name(void);
TEST_LIST(TEST_DECLARE)

#endif

/* test_work: the work counters (work.h) on cases small enough to count by
 * hand, and their independence of the thread count. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "helpers.h"
#include "kdtree.h"
#include "render.h"
#include "tests.h"
#include "work.h"

/* 32 points at x = 0 .. 31 on the x axis, leaves of 4: 8 leaves, 3 levels
 * of splits along x, and a tree small enough that the k-nearest search
 * scans from the root (scan_h = 3): it compares q with the root's split and
 * scans both halves (16 points each), or the near one when the far half is
 * out of reach. */
static void line_tree(kd_tree *t)
{
    float pts[32 * 3];
    for (int i = 0; i < 32; i++) {
        pts[3 * i] = (float)i;
        pts[3 * i + 1] = 0.0f;
        pts[3 * i + 2] = 0.0f;
    }
    CHECK(kd_build(t, pts, 32, 4, NULL, 1) == PM_OK);
    CHECK(t->nleaves == 8 && t->scan_h == 3 && t->leaf_start[4] == 16);
}

void test_work_kdtree_by_hand(void)
{
    kd_tree t;
    line_tree(&t);
    const float q[3] = {-1.0f, 0.0f, 0.0f};
    uint32_t idx[3];
    float d2[3], r2;
    for (int simd = KD_SIMD_BASE; simd <= KD_SIMD_AVX2; simd++) {
        kd_query s;
        CHECK(kd_query_init(&s, 3) == PM_OK);
        kd_query_simd(&s, (kd_simd)simd);
        /* no starting radius: the root (1 node), then both halves as one
         * range (1 node, 32 points) */
        CHECK(kd_query_knn(&t, &s, q, 3, INFINITY, idx, d2, &r2) == 3 && r2 == 9.0f);
        CHECK(s.queries == 1 && s.work.nodes == 2 && s.work.points == 32);
        /* from the last radius: r2 = 9 * (1 + 2.5 / sqrt 3) < 22, the far
         * half (from x = 15.5) is out of reach: the root and the near half
         * (16 points), one pass (x = 0..3 lie within) */
        CHECK(kd_query_knn(&t, &s, q, 3, INFINITY, idx, d2, &r2) == 3 && r2 == 9.0f);
        CHECK(s.queries == 2 && s.passes == 2 && s.work.nodes == 4 && s.work.points == 48);
        /* forgotten: as the first query again */
        kd_query_forget(&s);
        CHECK(kd_query_knn(&t, &s, q, 3, INFINITY, idx, d2, &r2) == 3);
        CHECK(s.queries == 3 && s.work.nodes == 6 && s.work.points == 80);
        /* a cap that leaves the root's box out of reach: nothing visited */
        CHECK(kd_query_knn(&t, &s, q, 3, 0.5f, idx, d2, &r2) == 0);
        CHECK(s.work.nodes == 6 && s.work.points == 80);
        kd_query_free(&s);
    }
    /* the nearest with a predicate: no hint, the descent compares 3 splits
     * and scans the first leaf (x = 0..3, 4 points); every deferred cell is
     * then beyond the distance 1 found */
    kd_work w = {0, 0};
    float d;
    uint32_t i0 = kd_nearest_if_counted(&t, q, INFINITY, NULL, NULL, KD_NONE, &d, &w);
    float p[3];
    kd_point(&t, i0, p);
    CHECK(p[0] == 0.0f && d == 1.0f);
    CHECK(w.nodes == 4 && w.points == 4);
    /* with the answer as the hint: its distance (1 point), the path to its
     * leaf (3 splits) and the leaf (1 node, 4 points) */
    w.nodes = w.points = 0;
    CHECK(kd_nearest_if_counted(&t, q, INFINITY, NULL, NULL, i0, &d, &w) == i0);
    CHECK(w.nodes == 4 && w.points == 5);
    kd_free(&t);
}

/* A closed black sphere around the light and the camera: every photon and
 * every eye ray hits it once (one shape, tested linearly), each photon is
 * stored where it lands and absorbed there (rho 0). */
static scene *black_sphere(void)
{
    return helper_scene("camera position 0 0 0 look_at 0 0 -1 up 0 1 0 fov 60\n"
                        "light point position 0 0 0 power 1 1 1\n"
                        "material black lambert rho 0 0 0\n"
                        "sphere center 0 0 0 radius 1 material black\n");
}

static config_render tiny_config(config_method method)
{
    config_render cfg = config_defaults();
    cfg.method = method;
    cfg.photons = 1;
    cfg.nn = 2;
    cfg.width = 2;
    cfg.height = 2;
    cfg.subpixels = 1;
    cfg.rep_every = 1;
    cfg.normal_cos = -1.0; /* every representative agrees */
    cfg.max_radius = 10.0; /* the one photon is always within reach */
    return cfg;
}

void test_work_one_photon_by_hand(void)
{
    scene *sc = black_sphere();
    image im;
    stats_run st;
    /* conventional: 1 photon traced, 1 ray, 1 shape test, 1 stored, a
     * tree of 1 point; 4 eye rays (one 2x2 tile), 4 shape tests, 4 kNN
     * queries of 1 pass each, each the root's one range: 1 node, 1 point */
    config_render cfg = tiny_config(CONFIG_METHOD_CONVENTIONAL);
    CHECK(helper_render(sc, &cfg, 1, &im, &st) == PM_OK);
    const work_phases *w = &st.work;
    CHECK(w->trace.traced_photons == 1 && w->trace.stored_photons == 1);
    CHECK(w->trace.rays == 1 && w->trace.shape_tests == 1);
    CHECK(w->build.tree_points == 1 && w->build.rep_chosen == 0);
    CHECK(w->precompute.knn_queries == 0 && w->precompute.rep_evaluations == 0);
    CHECK(w->render.rays == 4 && w->render.shape_tests == 4);
    CHECK(w->render.knn_queries == 4 && w->render.map_nodes == 4 && w->render.map_points == 4);
    CHECK(w->render.rep_lookups == 0 && w->render.rep_nodes == 0 && w->render.rep_points == 0);
    image_free(&im);
    /* precomputed, the photon its own representative: the precompute builds
     * a tree of 1 point and makes 1 query (1 node, 1 point) for 1
     * evaluation; the eye pass makes 4 lookups: the first without a hint
     * (the leaf: 1 node, 1 point), the other 3 with the first's answer as
     * the hint (1 point) and its leaf (1 node, 1 point) */
    cfg = tiny_config(CONFIG_METHOD_PRECOMPUTED);
    CHECK(helper_render(sc, &cfg, 1, &im, &st) == PM_OK);
    CHECK(w->build.rep_chosen == 1 && w->trace.rep_chosen == 0); /* chosen in the build, not the photon pass */
    CHECK(w->precompute.tree_points == 1 && w->precompute.knn_queries == 1);
    CHECK(w->precompute.map_nodes == 1 && w->precompute.map_points == 1);
    CHECK(w->precompute.rep_evaluations == 1);
    CHECK(w->render.rays == 4 && w->render.shape_tests == 4 && w->render.knn_queries == 0);
    CHECK(w->render.rep_lookups == 4 && w->render.rep_nodes == 4 && w->render.rep_points == 7);
    CHECK(w->render.rep_evaluations == 0);
    /* shadow rays: one more ray and shape test per diffuse hit */
    cfg.direct = CONFIG_DIRECT_SHADOW_RAYS;
    cfg.photons = 0;
    image_free(&im);
    cfg.method = CONFIG_METHOD_CONVENTIONAL;
    CHECK(helper_render(sc, &cfg, 1, &im, &st) == PM_OK);
    CHECK(w->trace.rays == 0 && w->render.rays == 8 && w->render.shape_tests == 8);
    image_free(&im);
    scene_free(sc);
}

/* Every counter of every phase, for the Cornell box at a small size, is
 * the same on 1 and 2 threads, for each method and variant; the photon
 * pass's are the same for both methods. */
void test_work_same_for_any_thread_count(void)
{
    scene *sc = NULL;
    char err[512];
    CHECK_MSG(scene_load("scenes/cornell.scene", &sc, err, sizeof err) == PM_OK, "%s", err);
    if (!sc)
        return;
    work_counts conv_trace;
    memset(&conv_trace, 0, sizeof conv_trace);
    for (int variant = 0; variant < 5; variant++) {
        config_render cfg = config_defaults();
        cfg.photons = 20000;
        cfg.width = 64;
        cfg.height = 48;
        cfg.method = variant ? CONFIG_METHOD_PRECOMPUTED : CONFIG_METHOD_CONVENTIONAL;
        cfg.rep_tree = variant == 2 ? CONFIG_REP_TREE_SHARED : CONFIG_REP_TREE_SEPARATE;
        cfg.rep_gate = variant == 3 ? CONFIG_REP_GATE_PLANE : CONFIG_REP_GATE_NONE;
        cfg.direct = variant == 4 ? CONFIG_DIRECT_SHADOW_RAYS : CONFIG_DIRECT_PHOTONS;
        image a, b;
        stats_run sa, sb;
        CHECK(helper_render(sc, &cfg, 1, &a, &sa) == PM_OK);
        CHECK(helper_render(sc, &cfg, 2, &b, &sb) == PM_OK);
        CHECK_MSG(work_equal(&sa.work, &sb.work), "variant %d", variant);
        /* the photon pass does the same in both methods (the drift control):
         * every trace counter equals the conventional render's (variants 1-3
         * light as it does); the representatives are chosen in the build
         * (every 4th of the stored) */
        if (variant == 0)
            conv_trace = sa.work.trace;
        else if (variant < 4)
            CHECK_MSG(!memcmp(&sa.work.trace, &conv_trace, sizeof conv_trace), "variant %d: trace work differs", variant);
        CHECK(sa.work.build.rep_chosen == (variant ? (sa.work.trace.stored_photons + 3) / 4 : 0));
        CHECK(sa.work.render.rays > 0 && sa.work.trace.shape_tests > 0);
        CHECK(variant == 0 ? sa.work.render.map_points > 0 : sa.work.render.rep_points > 0);
        image_free(&a);
        image_free(&b);
    }
    scene_free(sc);
}

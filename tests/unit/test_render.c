/* test_render: whole-pipeline checks against analytic answers: photon power
 * conservation, the furnace, a lit plane, and determinism across threads. */
#include <stdlib.h>
#include <string.h>

#include "camera.h"
#include "check.h"
#include "helpers.h"
#include "photons.h"
#include "render.h"
#include "tests.h"

/* A closed diffuse box with the light inside. */
static const char *closed_box =
    "camera position 0 1 1.5 look_at 0 1 0 up 0 1 0 fov 60\n"
    "light point position 0.1 1.2 -0.3 power 3 2 1\n"
    "material w lambert rho 0.5 0.5 0.5\n"
    "rect corner -1 0 -2 edge1 0 0 4 edge2 0 2 0 material w\n"
    "rect corner 1 0 -2 edge1 0 2 0 edge2 0 0 4 material w\n"
    "rect corner -1 0 -2 edge1 2 0 0 edge2 0 2 0 material w\n"
    "rect corner -1 0 2 edge1 0 2 0 edge2 2 0 0 material w\n"
    "rect corner -1 0 -2 edge1 0 0 4 edge2 2 0 0 material w\n"
    "rect corner -1 2 -2 edge1 2 0 0 edge2 0 0 4 material w\n";

void test_photon_power_closed_box(void)
{
    scene *sc = helper_scene(closed_box);
    photons_params pp = {100003, 1, 64, 1}; /* P_e not a multiple of the chunk size */
    photons_list l;
    CHECK(photons_trace(sc, &pp, 2, NULL, &l) == 0);
    double sum[3] = {0, 0, 0};
    uint64_t first = 0;
    for (uint64_t i = 0; i < l.count; i++) {
        if (l.ph[i].flags & PHOTONS_FLAG_DIRECT) {
            first++;
            for (int c = 0; c < 3; c++)
                sum[c] += l.ph[i].power[c] * (c == 0 ? l.unit.x : c == 1 ? l.unit.y : l.unit.z);
        }
    }
    CHECK(first == pp.photons); /* every photon's first hit is diffuse and stored */
    CHECK(l.escaped == 0);
    CHECK_REL(sum[0], 3.0, 1e-6);
    CHECK_REL(sum[1], 2.0, 1e-6);
    CHECK_REL(sum[2], 1.0, 1e-6);
    /* albedo 0.5: on average 1/(1-0.5) = 2 stored photons per emitted one */
    CHECK_NEAR((double)l.count / pp.photons, 2.0, 0.02);
    photons_list_free(&l);
    /* shadow-ray mode stores no first hits */
    pp.store_first_hits = 0;
    CHECK(photons_trace(sc, &pp, 1, NULL, &l) == 0);
    uint64_t direct = 0;
    for (uint64_t i = 0; i < l.count; i++)
        direct += (l.ph[i].flags & PHOTONS_FLAG_DIRECT) != 0;
    CHECK(direct == 0 && l.count > 0);
    photons_list_free(&l);
    scene_free(sc);
}

void test_furnace_sphere(void)
{
    /* closed diffuse sphere r=1, albedo 0.5, light of intensity pi at the
     * centre: E = pi / (1 - 0.5) everywhere, so L = 0.5/pi * 2 pi = 1. A ball
     * of radius r about a point of a sphere cuts out a cap of area exactly
     * pi r^2 (Archimedes), so the kNN estimate has no curvature bias here and
     * the tolerance is set by noise alone: 1/sqrt(n) per estimate. */
    scene *sc = helper_scene("camera position 0 0 0 look_at 0.3 -0.2 -1 up 0 1 0 fov 90\n"
                             "light point position 0 0 0 power 39.47841760435743 39.47841760435743 39.47841760435743\n"
                             "material g lambert rho 0.5 0.5 0.5\n"
                             "sphere center 0 0 0 radius 1 material g\n");
    for (int method = 0; method < 2; method++) {
        config_render cfg = config_defaults();
        cfg.photons = 400000;
        cfg.nn = 4000; /* relative noise 1/sqrt(n) = 1.6% per estimate */
        cfg.width = 32;
        cfg.height = 24;
        cfg.method = method ? CONFIG_METHOD_PRECOMPUTED : CONFIG_METHOD_CONVENTIONAL;
        cfg.rep_every = 64;
        image im;
        stats_run st;
        CHECK(helper_render(sc, &cfg, 2, &im, &st) == 0);
        double mean = 0, worst = 0;
        size_t n = (size_t)cfg.width * cfg.height * 3;
        for (size_t i = 0; i < n; i++) {
            mean += im.rgb[i];
            worst = fmax(worst, fabs(im.rgb[i] - 1.0));
        }
        mean /= (double)n;
        CHECK_NEAR(mean, 1.0, 0.02);
        CHECK_MSG(worst < 0.07, "method %d: worst pixel off by %.3f", method, worst);
        CHECK(st.nonfinite_pixels == 0 && st.empty_estimates == 0);
        image_free(&im);
    }
    scene_free(sc);
}

void test_diffuse_plane_matches_analytic(void)
{
    /* an open scene: a large diffuse floor under the light; photons that
     * leave it escape, so the map holds direct light only */
    scene *sc = helper_scene("camera position 0 3 0 look_at 0 0 0 up 0 0 -1 fov 60\n"
                             "light point position 0.2 1 0.1 power 10 10 10\n"
                             "material w lambert rho 0.6 0.6 0.6\n"
                             "rect corner -5 0 -5 edge1 10 0 0 edge2 0 0 10 material w\n");
    double I = 10.0 / (4.0 * VEC_PI);
    for (int mode = 0; mode < 2; mode++) {
        config_render cfg = config_defaults();
        cfg.photons = mode ? 1000 : 1000000;
        cfg.nn = 400;
        cfg.width = 48;
        cfg.height = 36;
        cfg.direct = mode ? CONFIG_DIRECT_SHADOW_RAYS : CONFIG_DIRECT_PHOTONS;
        image im;
        stats_run st;
        CHECK(helper_render(sc, &cfg, 2, &im, &st) == 0);
        double sum_ratio = 0, worst = 0;
        int count = 0;
        for (uint32_t y = 0; y < cfg.height; y++) {
            for (uint32_t x = 0; x < cfg.width; x++) {
                /* analytic value averaged over the same 2x2 subpixels */
                double want = 0;
                for (int s = 0; s < 4; s++) {
                    double u = (x + (s % 2 + 0.5) / 2) / cfg.width, v = (y + (s / 2 + 0.5) / 2) / cfg.height;
                    shape_ray r = camera_ray(sc, (double)cfg.height / cfg.width, u, v);
                    double t = -r.origin.y / r.dir.y;
                    vec3 p = vec_madd(r.origin, r.dir, t);
                    vec3 to = vec_sub(sc->light.position, p);
                    double d2 = vec_len2(to);
                    want += 0.6 / VEC_PI * I * (to.y / sqrt(d2)) / d2 / 4.0;
                }
                double got = im.rgb[((size_t)y * cfg.width + x) * 3 + 1];
                double ratio = got / want;
                sum_ratio += ratio;
                worst = fmax(worst, fabs(ratio - 1.0));
                count++;
            }
        }
        if (mode == 1) {
            CHECK_MSG(worst < 1e-5, "shadow rays: worst relative error %.3g", worst); /* exact, float output */
            CHECK(st.photons_stored == 0);
        } else {
            CHECK_NEAR(sum_ratio / count, 1.0, 0.015);
            CHECK_MSG(worst < 0.25, "photons: worst relative error %.3f", worst);
        }
        image_free(&im);
    }
    scene_free(sc);
}

void test_cornell_finite_and_deterministic(void)
{
    char err[512];
    scene *sc = NULL;
    CHECK_MSG(scene_load("scenes/cornell.scene", &sc, err, sizeof err) == PM_OK, "%s", err);
    if (!sc)
        return;
    for (int method = 0; method < 2; method++) {
        config_render cfg = config_defaults();
        cfg.photons = 20000;
        cfg.nn = 20;
        cfg.width = 64;
        cfg.height = 48;
        cfg.seed = 99;
        cfg.method = method ? CONFIG_METHOD_PRECOMPUTED : CONFIG_METHOD_CONVENTIONAL;
        image a, b, c;
        stats_run sa, sb, sc3;
        CHECK(helper_render(sc, &cfg, 1, &a, &sa) == 0);
        CHECK(helper_render(sc, &cfg, 2, &b, &sb) == 0);
        CHECK(helper_render(sc, &cfg, 3, &c, &sc3) == 0);
        size_t bytes = (size_t)cfg.width * cfg.height * 3 * sizeof(float);
        CHECK_MSG(memcmp(a.rgb, b.rgb, bytes) == 0, "method %d: 1 vs 2 threads differ", method);
        CHECK_MSG(memcmp(a.rgb, c.rgb, bytes) == 0, "method %d: 1 vs 3 threads differ", method);
        CHECK(sa.photons_stored == sb.photons_stored && sa.photons_stored == sc3.photons_stored);
        CHECK(sa.nonfinite_pixels == 0 && image_count_nonfinite(&a) == 0);
        CHECK(sa.photons_escaped == 0); /* the room is closed */
        double mean = 0;
        for (size_t i = 0; i < (size_t)cfg.width * cfg.height * 3; i++)
            mean += a.rgb[i];
        CHECK(mean > 0.0);
        /* another seed gives another image */
        cfg.seed = 100;
        image d;
        stats_run sd;
        CHECK(helper_render(sc, &cfg, 2, &d, &sd) == 0);
        CHECK(memcmp(a.rgb, d.rgb, bytes) != 0);
        image_free(&a);
        image_free(&b);
        image_free(&c);
        image_free(&d);
    }
    scene_free(sc);
}

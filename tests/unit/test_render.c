/* test_render: the whole pipeline (render_run) against analytic answers
 * (the furnace, a lit plane), its determinism across threads, its
 * extremes, and the precomputed method end to end. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "camera.h"
#include "check.h"
#include "helpers.h"
#include "image.h"
#include "photons.h"
#include "render.h"
#include "tests.h"

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

/* ---- the pipeline at its extremes: P_e = 1 and 0, light power 1e-30 /
 * 1e30, the Cornell scene scaled by 1e-3 / 1e3 (and 1e-15), grazing rays, a
 * camera inside the glass sphere, total internal reflection chains cut at
 * the depth limit, EXR round trips of real renders (small images and photon
 * counts: this file also runs under ASan+UBSan; results/stability.md
 * tabulates the same cases at the CLI) ---- */

/* ---- helpers ---- */

/* The Cornell scene of scenes/cornell.scene with every length times s, light
 * power p per channel and the camera at cam looking at look (both x s). */
static scene *cornell_scene(double s, double p, vec3 cam, vec3 look)
{
    static const char *fmt =
        "camera position %.17g %.17g %.17g look_at %.17g %.17g %.17g up 0 1 0 fov 65\n"
        "light point position 0 %.17g 0 power %.17g %.17g %.17g\n"
        "material white lambert rho 0.75 0.75 0.75\n"
        "material red lambert rho 0.63 0.065 0.05\n"
        "material mirror mirror reflectance 0.9 0.9 0.9\n"
        "material glass glass ior 1.5\n"
        "rect corner %.17g 0 %.17g edge1 0 0 %.17g edge2 0 %.17g 0 material red\n"
        "rect corner %.17g 0 %.17g edge1 0 %.17g 0 edge2 0 0 %.17g material mirror\n"
        "rect corner %.17g 0 %.17g edge1 %.17g 0 0 edge2 0 %.17g 0 material white\n"
        "rect corner %.17g 0 %.17g edge1 0 0 %.17g edge2 %.17g 0 0 material white\n"
        "rect corner %.17g %.17g %.17g edge1 %.17g 0 0 edge2 0 0 %.17g material white\n"
        "rect corner %.17g 0 %.17g edge1 0 %.17g 0 edge2 %.17g 0 0 material white\n"
        "sphere center %.17g %.17g %.17g radius %.17g material white\n"
        "sphere center %.17g %.17g %.17g radius %.17g material mirror\n"
        "sphere center %.17g %.17g %.17g radius %.17g material glass\n";
    char text[4096];
    int n = snprintf(text, sizeof text, fmt, cam.x * s, cam.y * s, cam.z * s, look.x * s, look.y * s,
                     look.z * s, 1.75 * s, p, p, p,                  /* camera, light */
                     -s, -s, 3.5 * s, 2 * s,                         /* left */
                     s, -s, 2 * s, 3.5 * s,                          /* right */
                     -s, -s, 2 * s, 2 * s,                           /* back */
                     -s, -s, 3.5 * s, 2 * s,                         /* floor */
                     -s, 2 * s, -s, 2 * s, 3.5 * s,                  /* ceiling */
                     -s, 2.5 * s, 2 * s, 2 * s,                      /* front */
                     -0.5 * s, 0.35 * s, -0.45 * s, 0.35 * s,        /* diffuse sphere */
                     0.5 * s, 0.35 * s, -0.5 * s, 0.35 * s,          /* mirror sphere */
                     0.05 * s, 0.3 * s, 0.35 * s, 0.3 * s);          /* glass sphere */
    if (n < 0 || (size_t)n >= sizeof text)
        abort();
    return helper_scene(text);
}

static scene *cornell(double s, double p)
{
    return cornell_scene(s, p, vec_make(0, 1, 2.4), vec_make(0, 1, 0));
}

static config_render small_cfg(uint64_t photons, uint32_t nn)
{
    config_render c = config_defaults();
    c.photons = photons;
    c.nn = nn;
    c.width = 32;
    c.height = 24;
    c.subpixels = 1;
    return c;
}

static double mean_radiance(const image *im)
{
    double s = 0.0;
    size_t n = (size_t)im->width * im->height * 3;
    for (size_t i = 0; i < n; i++)
        s += im->rgb[i];
    return s / (double)n;
}

/* ---- whole renders ---- */

void test_stability_photon_counts(void)
{
    scene *sc = cornell(1.0, 12.566371);
    for (int method = 0; method < 2; method++) {
        config_method meth = method ? CONFIG_METHOD_PRECOMPUTED : CONFIG_METHOD_CONVENTIONAL;
        image im;
        stats_run st;
        /* n = 1 */
        config_render c = small_cfg(4000, 1);
        c.method = meth;
        CHECK(helper_render(sc, &c, 2, &im, &st) == 0);
        CHECK(st.nonfinite_pixels == 0 && mean_radiance(&im) > 0.0);
        image_free(&im);
        /* P_e = 1: a handful of stored photons, n far beyond them */
        c = small_cfg(1, 50);
        c.method = meth;
        CHECK(helper_render(sc, &c, 2, &im, &st) == 0);
        CHECK(st.photons_stored >= 1 && st.photons_stored < 50);
        CHECK(st.nonfinite_pixels == 0);
        CHECK(st.empty_estimates > 0);
        image_free(&im);
        /* n = and > the stored count: r = R everywhere a photon is in range */
        c = small_cfg(20, 1);
        c.method = meth;
        CHECK(helper_render(sc, &c, 2, &im, &st) == 0);
        uint32_t stored = (uint32_t)st.photons_stored;
        image_free(&im);
        for (uint32_t extra = 0; extra < 2; extra++) {
            c = small_cfg(20, stored + extra * 1000);
            c.method = meth;
            CHECK(helper_render(sc, &c, 2, &im, &st) == 0);
            CHECK(st.photons_stored == stored && st.nonfinite_pixels == 0);
            image_free(&im);
        }
        /* P_e = 0: documented black image (photons, shadow-ray direct light aside) */
        c = small_cfg(0, 50);
        c.method = meth;
        CHECK(helper_render(sc, &c, 2, &im, &st) == 0);
        CHECK(st.photons_stored == 0 && st.nonfinite_pixels == 0);
        CHECK(mean_radiance(&im) == 0.0);
        CHECK(st.empty_estimates > 0);
        image_free(&im);
        c.direct = CONFIG_DIRECT_SHADOW_RAYS;
        CHECK(helper_render(sc, &c, 2, &im, &st) == 0);
        CHECK(st.nonfinite_pixels == 0 && mean_radiance(&im) > 0.0); /* direct light only */
        image_free(&im);
    }
    scene_free(sc);
}

/* Renders and returns the image (caller frees) with stats. */
static void render_small(const scene *sc, const config_render *c, image *im, stats_run *st)
{
    CHECK(helper_render(sc, c, 2, im, st) == 0);
    CHECK_MSG(st->nonfinite_pixels == 0, "%llu non-finite pixels", (unsigned long long)st->nonfinite_pixels);
}

void test_stability_light_power_extremes(void)
{
    const double p0 = 12.566371;
    scene *sc = cornell(1.0, p0);
    config_render c = small_cfg(4000, 20);
    image ref;
    stats_run st;
    render_small(sc, &c, &ref, &st);
    scene_free(sc);
    const double powers[] = {1e-30, 1e30};
    for (int k = 0; k < 2; k++) {
        sc = cornell(1.0, powers[k]);
        image im;
        render_small(sc, &c, &im, &st);
        double ratio = powers[k] / p0, worst = 0.0;
        size_t n = (size_t)im.width * im.height * 3;
        for (size_t i = 0; i < n; i++) {
            if (ref.rgb[i] > 0.0f) {
                double d = fabs(im.rgb[i] / (ratio * ref.rgb[i]) - 1.0);
                worst = d > worst ? d : worst;
            } else {
                CHECK(im.rgb[i] == 0.0f);
            }
        }
        /* linear up to float rounding of the photon powers and the pixels */
        CHECK_MSG(worst < 1e-5, "power %g: worst relative deviation %g", powers[k], worst);
        image_free(&im);
        scene_free(sc);
    }
    image_free(&ref);
}

void test_stability_scene_scale(void)
{
    /* radiance scales as 1/s^2 at fixed power: L s^2 must match scale 1 */
    config_render c = small_cfg(4000, 20);
    scene *sc = cornell(1.0, 12.566371);
    image ref;
    stats_run st;
    render_small(sc, &c, &ref, &st);
    double mref = mean_radiance(&ref), rref = st.max_radius;
    CHECK(mref > 0.0);
    scene_free(sc);
    const double scales[] = {1e-3, 1e3, 1e-15};
    for (int k = 0; k < 3; k++) {
        double s = scales[k];
        sc = cornell(s, 12.566371);
        image im;
        render_small(sc, &c, &im, &st);
        CHECK_REL(st.max_radius, s * rref, 1e-6);
        CHECK_REL(mean_radiance(&im) * s * s, mref, 1e-3);
        /* per pixel: the same photon paths; rare pixels may differ by an
         * epsilon decision, so compare the fraction of pixels that differ */
        size_t n = (size_t)im.width * im.height * 3, off = 0;
        for (size_t i = 0; i < n; i++)
            off += fabs(im.rgb[i] * s * s - ref.rgb[i]) > 1e-3 * (fabs(ref.rgb[i]) + 1e-3);
        CHECK_MSG(off < n / 100, "scale %g: %zu of %zu channels differ", s, off, n);
        image_free(&im);
        scene_free(sc);
    }
    image_free(&ref);
}

void test_stability_grazing_rays(void)
{
    /* camera and light in the plane of the floor: camera rays and photons
     * run parallel to it or graze it; a sphere's silhouette is grazed too */
    scene *sc = helper_scene("camera position 0 0 3 look_at 0 0 0 up 0 1 0 fov 90\n"
                             "light point position 0.3 0 1 power 10 10 10\n"
                             "material w lambert rho 0.8 0.8 0.8\n"
                             "material g glass ior 1.5\n"
                             "material m mirror reflectance 1 1 1\n"
                             "rect corner -2 0 -2 edge1 0 0 4 edge2 4 0 0 material w\n"
                             "rect corner -2 0 -2 edge1 4 0 0 edge2 0 2 0 material m\n"
                             "sphere center 0.5 0.5 0 radius 0.5 material g\n"
                             "sphere center -0.6 0.4 0 radius 0.4 material w\n");
    for (int method = 0; method < 2; method++) {
        config_render c = small_cfg(4000, 20);
        c.method = method ? CONFIG_METHOD_PRECOMPUTED : CONFIG_METHOD_CONVENTIONAL;
        c.subpixels = 3;
        image im;
        stats_run st;
        render_small(sc, &c, &im, &st);
        CHECK(mean_radiance(&im) > 0.0);
        image_free(&im);
    }
    scene_free(sc);
}

void test_stability_camera_inside_glass(void)
{
    /* the camera at the glass sphere's centre (0.05, 0.3, 0.35), then near its
     * surface: every camera ray starts inside the glass */
    const vec3 cams[2] = {{0.05, 0.3, 0.35}, {0.05, 0.3, 0.1}};
    for (int k = 0; k < 2; k++) {
        scene *sc = cornell_scene(1.0, 12.566371, cams[k], vec_make(0.05, 0.3, -1.0));
        config_render c = small_cfg(4000, 20);
        image im;
        stats_run st;
        render_small(sc, &c, &im, &st);
        CHECK(mean_radiance(&im) > 0.0);
        image_free(&im);
        scene_free(sc);
    }
}

void test_stability_tir_depth_limit(void)
{
    /* a camera inside a glass ball of ior 10 (critical angle 5.7 deg) near
     * its rim: rays are trapped by total internal reflection and cut at the
     * eye depth; the cut is counted, the image stays finite */
    scene *sc = helper_scene("camera position 0 0.95 0 look_at 1 0.95 0 up 0 1 0 fov 60\n"
                             "light point position 0 3 0 power 10 10 10\n"
                             "material w lambert rho 0.5 0.5 0.5\n"
                             "material g glass ior 10\n"
                             "sphere center 0 0 0 radius 1 material g\n"
                             "sphere center 0 0 0 radius 5 material w\n");
    const uint32_t depths[] = {0, 16, 1000};
    for (int k = 0; k < 3; k++) {
        config_render c = small_cfg(2000, 10);
        c.width = 16;
        c.height = 12;
        c.eye_depth = depths[k];
        c.photon_depth = 2; /* photons through the ball need more: truncated */
        image im;
        stats_run st;
        render_small(sc, &c, &im, &st);
        CHECK_MSG(st.eye_depth_limit_hits > 0, "eye depth %u: no depth-limit hit", depths[k]);
        if (k == 0)
            CHECK(st.eye_depth_limit_hits == st.samples); /* every camera ray hits glass first */
        CHECK(st.photon_paths_truncated > 0);
        image_free(&im);
    }
    scene_free(sc);
}

void test_stability_exr_round_trip_of_renders(void)
{
    /* Real renders round-trip through EXR. Rows 16-31 of this render make a
     * ZIP chunk whose compressed size equals its raw size, which image.c
     * must store raw (readers would take it as raw and read NaN/1e38). */
    scene *sc = cornell(1.0, 12.566371);
    config_render c = config_defaults();
    c.photons = 20000;
    c.nn = 20;
    c.width = 64;
    c.height = 48;
    image im, back;
    stats_run st;
    render_small(sc, &c, &im, &st);
    char path[64], err[256];
    snprintf(path, sizeof path, "/tmp/pm-stability-%ld.exr", (long)getpid());
    CHECK_MSG(image_write_exr(&im, path, err, sizeof err) == 0, "%s", err);
    CHECK_MSG(image_read_exr(&back, path, err, sizeof err) == 0, "%s", err);
    if (back.rgb) {
        CHECK(back.width == im.width && back.height == im.height);
        CHECK(memcmp(back.rgb, im.rgb, sizeof(float) * 3 * im.width * im.height) == 0);
        image_free(&back);
    }
    remove(path);
    image_free(&im);
    scene_free(sc);
}

/* ---- the precomputed method through the whole pipeline ---- */

/* Relative RMSE between two images (over pixels the reference lights). */
static double rel_rmse(const image *a, const image *ref)
{
    double num = 0, den = 0;
    size_t n = (size_t)a->width * a->height * 3;
    for (size_t i = 0; i < n; i++) {
        num += (a->rgb[i] - ref->rgb[i]) * (double)(a->rgb[i] - ref->rgb[i]);
        den += ref->rgb[i] * (double)ref->rgb[i];
    }
    return sqrt(num / den);
}

/* At a fixed n the two methods differ by a fixed relative amount whatever
 * P_e: the representatives' spacing and the kNN radius both scale as
 * P_e^-1/2 (measured at 128x96, n=100: relative RMSE 0.029, 0.027, 0.027 at
 * 50k, 100k, 500k). The difference shrinks when the kNN radius grows
 * relative to the representatives' spacing: with n, or with P_e at a fixed
 * radius (n proportional to P_e), the paper's Fig. 3 sequence. */
void test_precomputed_converges_on_cornell(void)
{
    char err[512];
    scene *sc = NULL;
    CHECK_MSG(scene_load("scenes/cornell.scene", &sc, err, sizeof err) == PM_OK, "%s", err);
    if (!sc)
        return;
    double diff[3];
    const uint64_t counts[3] = {50000, 500000, 50000};
    const uint32_t nns[3] = {10, 100, 100};
    for (int i = 0; i < 3; i++) {
        config_render cfg = config_defaults();
        cfg.photons = counts[i];
        cfg.nn = nns[i];
        cfg.width = 48;
        cfg.height = 36;
        image conv, pre;
        stats_run st;
        CHECK(helper_render(sc, &cfg, 2, &conv, &st) == 0);
        cfg.method = CONFIG_METHOD_PRECOMPUTED;
        CHECK(helper_render(sc, &cfg, 2, &pre, &st) == 0);
        CHECK(st.representatives > 0 && st.nonfinite_pixels == 0);
        diff[i] = rel_rmse(&pre, &conv);
        image_free(&conv);
        image_free(&pre);
    }
    /* measured: 0.18 at (50k, 10), 0.024 at (500k, 100) and at (50k, 100) */
    CHECK_MSG(diff[1] < 0.33 * diff[0], "relative RMSE %.4f at (50k, 10), %.4f at (500k, 100)", diff[0], diff[1]);
    CHECK_MSG(diff[2] < 0.33 * diff[0], "relative RMSE %.4f at n=10, %.4f at n=100", diff[0], diff[2]);
    scene_free(sc);
}

void test_precomputed_extremes(void)
{
    char err[512];
    scene *sc = NULL;
    CHECK_MSG(scene_load("scenes/cornell.scene", &sc, err, sizeof err) == PM_OK, "%s", err);
    if (!sc)
        return;
    config_render cfg = config_defaults();
    cfg.method = CONFIG_METHOD_PRECOMPUTED;
    cfg.photons = 5000;
    cfg.width = 32;
    cfg.height = 24;
    image im;
    stats_run st;
    /* one representative in the whole map */
    cfg.rep_every = 1000000000u;
    CHECK(helper_render(sc, &cfg, 2, &im, &st) == 0);
    CHECK(st.representatives == 1 && st.nonfinite_pixels == 0);
    CHECK(st.empty_estimates > 0); /* almost every point has no representative in range: black */
    image_free(&im);
    /* n larger than the stored photon count */
    cfg.rep_every = 4;
    cfg.nn = 100000;
    cfg.photons = 2000;
    CHECK(helper_render(sc, &cfg, 2, &im, &st) == 0);
    CHECK(st.photons_stored < cfg.nn && st.nonfinite_pixels == 0);
    image_free(&im);
    /* a normal threshold no representative can meet: defined black image */
    cfg.nn = 10;
    cfg.normal_cos = 1.0;
    CHECK(helper_render(sc, &cfg, 2, &im, &st) == 0);
    CHECK(st.nonfinite_pixels == 0);
    double sum = 0;
    for (size_t i = 0; i < (size_t)cfg.width * cfg.height * 3; i++)
        sum += im.rgb[i];
    CHECK(sum == 0.0);
    image_free(&im);
    scene_free(sc);
}

/* The smallest machine memory (to 1/1000) in which render_check_memory
 * lets cfg render, by bisection. */
static double least_memory(const scene *sc, const config_render *cfg)
{
    char err[512];
    double lo = 1.0, hi = 1e12;
    while (hi / lo > 1.001) {
        double mid = sqrt(lo * hi);
        if (render_check_memory(sc, cfg, (uint64_t)mid, err, sizeof err) == PM_OK)
            hi = mid;
        else
            lo = mid;
    }
    return hi;
}

/* With more than one repeat the memory check asks for the peak of repeats
 * that hand no page back and keep freed ones (mem_keep): four times the
 * single render's while that stays under CONFIG_REPEAT_KEEP_BYTES; the
 * refusal names --repeats 1 as a way out, and a single render's does not. */
void test_render_check_memory_repeats(void)
{
    scene *sc = cornell(1.0, 1.0);
    config_render one = small_cfg(100000, 50), three = one;
    three.repeats = 3;
    double m1 = least_memory(sc, &one), m3 = least_memory(sc, &three);
    CHECK_MSG(m3 > 3.9 * m1 && m3 < 4.1 * m1, "single %.0f bytes, three repeats %.0f", m1, m3);
    char err[512];
    CHECK(render_check_memory(sc, &three, (uint64_t)(0.9 * m3), err, sizeof err) == PM_ERR_INPUT);
    CHECK_MSG(strstr(err, "--repeats 1") != NULL, "%s", err);
    CHECK(render_check_memory(sc, &one, (uint64_t)(0.9 * m1), err, sizeof err) == PM_ERR_INPUT);
    CHECK_MSG(strstr(err, "--repeats 1") == NULL, "%s", err);
    scene_free(sc);
}

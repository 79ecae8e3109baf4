/* test_stability: the estimates and the whole pipeline at the extremes
 * where floating point and counting break first: n = 1, n at and beyond the stored count, P_e = 1 and 0,
 * coincident photons, too few or no photons in range, no agreeing
 * representative, light power 1e-30 / 1e30, the Cornell scene scaled by
 * 1e-3 / 1e3 (and 1e-15), grazing rays, a camera inside the glass sphere,
 * total internal reflection chains cut at the depth limit, and EXR round
 * trips of real renders. Small images and photon counts: the file also runs
 * under ASan+UBSan. results/stability.md tabulates the same cases at the CLI. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "check.h"
#include "estimate.h"
#include "helpers.h"
#include "image.h"
#include "photons.h"
#include "render.h"
#include "tests.h"

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

/* A photon map of `count` photons at pos[], each travelling along dir onto a
 * surface of normal `normal`, power `power` per channel, flags as given. */
static void make_map(photons_map *m, const float (*pos)[3], uint32_t count, vec3 dir, vec3 normal, float power,
                     unsigned flags)
{
    photons_list l;
    memset(&l, 0, sizeof l);
    l.count = count;
    l.pos = malloc(sizeof(double) * 3 * (count ? count : 1));
    l.ph = calloc(count ? count : 1, sizeof(photons_record));
    if (!l.pos || !l.ph)
        abort();
    for (uint32_t i = 0; i < count; i++) {
        for (int a = 0; a < 3; a++)
            l.pos[3 * i + (uint32_t)a] = pos[i][a];
        for (int c = 0; c < 3; c++)
            l.ph[i].power[c] = power;
        photons_pack_dir(dir.x, dir.y, dir.z, l.ph[i].dir);
        photons_pack_dir(normal.x, normal.y, normal.z, l.ph[i].normal);
        l.ph[i].flags = (uint8_t)flags;
    }
    l.unit = vec_make(1, 1, 1);
    CHECK(photons_build_map(&l, 0, m, NULL) == 0);
}

/* est_irradiance with a gather of nn photons within max_r scene units. */
static vec3 irr(const photons_map *m, vec3 x, vec3 n, uint32_t nn, double max_r, est_scratch *s, uint32_t *found)
{
    est_gather g = est_gather_make(m, nn, max_r, 0);
    return est_irradiance(m, x, n, &g, s, found);
}

static const vec3 down = {0, -1, 0}, up_n = {0, 1, 0};

/* ---- the estimator's conventions (renderer/estimate.h) ---- */

void test_stability_nn_one_and_at_stored_count(void)
{
    /* 4 photons on the floor at distances 0.1, 0.2, 0.3, 0.4 from the origin */
    const float pos[4][3] = {{0.1f, 0, 0}, {0, 0, 0.2f}, {-0.3f, 0, 0}, {0, 0, -0.4f}};
    photons_map m;
    make_map(&m, pos, 4, down, up_n, 1.0f, 0);
    est_scratch *s = est_scratch_new(1, 10);
    CHECK(s != NULL);
    const double R = 1.0, R2 = R * R;
    uint32_t found;
    vec3 x = vec_make(0, 0, 0);
    /* n = 1: r = distance to the nearest photons_record */
    vec3 e = irr(&m, x, up_n, 1, R, s, &found);
    CHECK(found == 1);
    CHECK_REL(e.x, 1.0 / (VEC_PI * 0.1f * 0.1f), 1e-5);
    /* n = stored count: r = distance to the farthest */
    e = irr(&m, x, up_n, 4, R, s, &found);
    CHECK(found == 4);
    CHECK_REL(e.y, 4.0 / (VEC_PI * 0.4f * 0.4f), 1e-5);
    /* n > stored count: fewer than n in range, r = R */
    e = irr(&m, x, up_n, 10, R, s, &found);
    CHECK(found == 4);
    CHECK_REL(e.z, 4.0 / (VEC_PI * R2), 1e-12);
    CHECK(isfinite(e.x) && isfinite(e.y) && isfinite(e.z));
    /* back side: photons travelling down do not light a surface facing down */
    e = irr(&m, x, down, 4, R, s, &found);
    CHECK(found == 4 && e.x == 0.0);
    est_scratch_delete(s, 1);
    photons_map_free(&m);
}

void test_stability_coincident_photons(void)
{
    /* 8 photons at exactly the query point: r = 0, clamped to 1e-3 R */
    float pos[8][3];
    for (int i = 0; i < 8; i++)
        pos[i][0] = 0.25f, pos[i][1] = 0.0f, pos[i][2] = -0.5f;
    photons_map m;
    make_map(&m, (const float(*)[3])pos, 8, down, up_n, 2.0f, 0);
    est_scratch *s = est_scratch_new(1, 8);
    CHECK(s != NULL);
    const double R = 0.05;
    const double floor2 = R * R * EST_MIN_RADIUS_FRAC * EST_MIN_RADIUS_FRAC;
    uint32_t found;
    vec3 x = vec_make(0.25, 0, -0.5);
    for (uint32_t nn = 1; nn <= 8; nn *= 2) {
        vec3 e = irr(&m, x, up_n, nn, R, s, &found);
        CHECK(found == nn);
        CHECK(isfinite(e.x));
        CHECK_REL(e.x, 2.0 * nn / (VEC_PI * floor2), 1e-9);
    }
    est_scratch_delete(s, 1);
    photons_map_free(&m);
}

void test_stability_few_or_no_photons_in_range(void)
{
    /* 3 photons at 0.5 R, 5 more at 2 R */
    const double R = 0.1;
    float pos[8][3];
    for (int i = 0; i < 8; i++) {
        double a = i * 0.7, d = i < 3 ? 0.5 * R : 2.0 * R;
        pos[i][0] = (float)(d * cos(a));
        pos[i][1] = 0.0f;
        pos[i][2] = (float)(d * sin(a));
    }
    photons_map m;
    make_map(&m, (const float(*)[3])pos, 8, down, up_n, 1.0f, 0);
    est_scratch *s = est_scratch_new(1, 50);
    CHECK(s != NULL);
    uint32_t found;
    /* fewer in range than n: the disc's density, r = R */
    vec3 e = irr(&m, vec_make(0, 0, 0), up_n, 50, R, s, &found);
    CHECK(found == 3);
    CHECK_REL(e.x, 3.0 / (VEC_PI * R * R), 1e-12);
    /* a point with no photon within R: 0, found = 0 */
    e = irr(&m, vec_make(10, 0, 10), up_n, 50, R, s, &found);
    CHECK(found == 0 && e.x == 0.0 && e.y == 0.0 && e.z == 0.0);
    /* an empty map */
    photons_map_free(&m);
    make_map(&m, NULL, 0, down, up_n, 1.0f, 0);
    e = irr(&m, vec_make(0, 0, 0), up_n, 50, R, s, &found);
    CHECK(found == 0 && e.x == 0.0);
    est_scratch_delete(s, 1);
    photons_map_free(&m);
}

void test_stability_no_agreeing_representative(void)
{
    /* representatives on a floor (normal +y); a lookup on a surface facing
     * -y (the floor's underside) or sideways finds none: 0 */
    float pos[16][3];
    for (int i = 0; i < 16; i++)
        pos[i][0] = (float)(0.01 * (i % 4)), pos[i][1] = 0.0f, pos[i][2] = (float)(0.01 * (i / 4));
    photons_map m;
    make_map(&m, (const float(*)[3])pos, 16, down, up_n, 1.0f, PHOTONS_FLAG_REP);
    for (int layout = 0; layout < 2; layout++) {
        reps_set r;
        est_gather g = est_gather_make(&m, 4, 0.1, 0);
        est_scratch *ls = est_scratch_new(1, 4);
        CHECK(helper_reps(&m, &g, layout ? CONFIG_REP_TREE_SHARED : CONFIG_REP_TREE_SEPARATE, 2, &r) == 0);
        CHECK(r.count == 16);
        int found = -1;
        vec3 e = reps_lookup(&r, &m, vec_make(0.01, 0, 0.01), down, 0.9, &g, ls, &found);
        CHECK(found == 0 && e.x == 0.0 && e.y == 0.0 && e.z == 0.0);
        e = reps_lookup(&r, &m, vec_make(0.01, 0, 0.01), vec_make(1, 0, 0), 0.9, &g, ls, &found);
        CHECK(found == 0 && e.x == 0.0);
        /* the agreeing side finds one, finite and positive */
        e = reps_lookup(&r, &m, vec_make(0.01, 0, 0.01), up_n, 0.9, &g, ls, &found);
        CHECK(found == 1 && isfinite(e.x) && e.x > 0.0);
        /* none in range */
        e = reps_lookup(&r, &m, vec_make(5, 0, 5), up_n, 0.9, &g, ls, &found);
        CHECK(found == 0 && e.x == 0.0);
        reps_free(&r);
        est_scratch_delete(ls, 1);
    }
    photons_map_free(&m);
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
    /* Regression: OpenEXRCore wrote a ZIP chunk whose compressed size equals
     * its raw size as compressed; readers took it as raw (rows 16-31 of this
     * exact render came back NaN/1e38). Real renders must round-trip. */
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

void test_stability_parser_degenerate_sizes(void)
{
    /* fuzz_scene findings (tests/fuzz/corpus/finding-*.scene): lengths whose
     * squares underflow gave a rect an infinite 1/|edge|^2 and a NaN normal,
     * a scene of no extent got a zero epsilon and radius; hex floats were
     * taken though the format is decimal. Each is now an input error. */
    static const char *head = "camera position 1 1 1 look_at 1 1 0 up 0 1 0 fov 60\n"
                              "light point position 0 1 0 power 1 1 1\n"
                              "material w lambert rho 1 1 1\n";
    static const struct {
        const char *shape, *where, *what;
    } bad[] = {
        {"rect corner 1 0 0 edge1 1e-160 0 0 edge2 0 1e-160 0 material w\n", "t:4:25:", "shorter than"},
        {"rect corner 1 0 0 edge1 1 0 0 edge2 0 0 1e-60 material w\n", "t:4:37:", "shorter than"},
        {"sphere center 1 0 0 radius 1e-320 material w\n", "t:4:28:", "at least"},
        {"sphere center 0x10 0 0 radius 1 material w\n", "t:4:15:", "expected a number"},
    };
    char text[512], err[512];
    scene *s;
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        snprintf(text, sizeof text, "%s%s", head, bad[i].shape);
        int rc = scene_parse_buffer("t", text, strlen(text), &s, err, sizeof err);
        CHECK_MSG(rc == PM_ERR_INPUT && s == NULL, "case %zu parsed", i);
        CHECK_MSG(strncmp(err, bad[i].where, strlen(bad[i].where)) == 0 && strstr(err, bad[i].what), "case %zu: %s",
                  i, err);
    }
    const char *flat = "camera position 1 1 1 look_at 1 1 0 up 0 1 0 fov 60\n"
                       "light point position 1e15 1e15 1e15 power 1 1 1\n"
                       "material w lambert rho 1 1 1\n"
                       "sphere center 1e15 1e15 1e15 radius 1e-40 material w\n";
    CHECK(scene_parse_buffer("t", flat, strlen(flat), &s, err, sizeof err) == PM_ERR_INPUT);
    CHECK_MSG(strstr(err, "t:4:1:") == err && strstr(err, "no extent"), "%s", err);
    /* just above the limit: a usable rect with a unit normal */
    snprintf(text, sizeof text, "%srect corner 1 0 0 edge1 1e-49 0 0 edge2 0 1e-49 0 material w\n", head);
    CHECK(scene_parse_buffer("t", text, strlen(text), &s, err, sizeof err) == PM_OK);
    if (s) {
        const shape *r = &s->shapes[0];
        CHECK(isfinite(r->inv_len2_1) && isfinite(r->inv_len2_2));
        CHECK_NEAR(vec_len(r->normal), 1.0, 1e-12);
        CHECK(s->scale > 0.0 && isfinite(s->scale));
        scene_free(s);
    }
}

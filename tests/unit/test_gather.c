/* test_gather: final gathering (gather.h): its strata and cosine-weighted
 * directions, the analytic sphere with both methods (a t-test over seeds,
 * with scaled images as its permanent negative control), images that do
 * not depend on the thread count, rays shared by both methods, and which
 * photons the global and caustic maps hold. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "gather.h"
#include "helpers.h"
#include "image.h"
#include "render.h"
#include "tests.h"

void test_gather_strata(void)
{
    for (uint32_t n = 1; n <= 300; n++) {
        uint32_t u, v;
        gather_strata(n, &u, &v);
        CHECK_MSG(u >= 1 && v >= u && (uint64_t)u * v <= n, "n = %u: %u x %u", n, u, v);
        /* what is left over is less than a row: the grid covers nearly all */
        CHECK_MSG(n - u * v < u, "n = %u: %u x %u leaves %u", n, u, v, n - u * v);
    }
    uint32_t u, v;
    gather_strata(32, &u, &v);
    CHECK(u == 4 && v == 8);
    gather_strata(16, &u, &v);
    CHECK(u == 4 && v == 4);
    gather_strata(5, &u, &v); /* 1 x 5 is too long: 2 x 2 and one uniform ray */
    CHECK(u == 2 && v == 2);
    gather_strata(0, &u, &v);
    CHECK(u == 0 && v == 0);
}

/* The directions of gather ray i for streams 0..streams-1 on a normal n:
 * the mean of cos(theta) (2/3 for the cosine-weighted pdf cos/pi; 1/2 for
 * a uniform hemisphere) and of the tangential components (0). */
static void direction_moments(const gather_params *g, vec3 n, uint32_t streams, double *mean_cos, double *mean_t,
                              double *worst_len)
{
    vec3 t, b;
    vec_basis(n, &t, &b);
    double sc = 0, st = 0;
    *worst_len = 0;
    for (uint32_t s = 0; s < streams; s++) {
        rng_stream rs = gather_stream(7, s);
        for (uint32_t i = 0; i < g->rays; i++) {
            double xi1 = rng_next_double(&rs), xi2 = rng_next_double(&rs);
            vec3 d = gather_direction(g, i, xi1, xi2, n, t, b);
            sc += vec_dot(d, n);
            st += vec_dot(d, t) + vec_dot(d, b);
            *worst_len = fmax(*worst_len, fabs(vec_len2(d) - 1.0));
            if (vec_dot(d, n) < 0.0)
                *worst_len = 1.0; /* below the surface */
        }
    }
    *mean_cos = sc / ((double)streams * g->rays);
    *mean_t = st / ((double)streams * g->rays);
}

void test_gather_directions(void)
{
    gather_params g;
    memset(&g, 0, sizeof g);
    vec3 n = vec_norm(vec_make(0.3, -0.5, 0.8));
    uint32_t sizes[] = {1, 5, 32, 64};
    for (size_t k = 0; k < sizeof sizes / sizeof sizes[0]; k++) {
        g.rays = sizes[k];
        gather_strata(g.rays, &g.strata_u, &g.strata_v);
        double mc, mt, worst;
        direction_moments(&g, n, 4000, &mc, &mt, &worst);
        /* cos(theta) has standard deviation sqrt(1/2 - 4/9) = 0.236 per ray; over
         * >= 4000 rays the mean is within 0.02 by more than 5 sigma (stratified: closer) */
        CHECK_MSG(fabs(mc - 2.0 / 3.0) < 0.02, "%u rays: mean cos %.4f, want 2/3", g.rays, mc);
        CHECK_MSG(fabs(mt) < 0.03, "%u rays: mean tangential %.4f", g.rays, mt);
        CHECK(worst < 1e-12);
    }
    /* stratified: with all xi = 0.5 the 32 rays are 32 distinct cell centres,
     * whose mean cos(theta) is already close to 2/3 */
    g.rays = 32;
    gather_strata(32, &g.strata_u, &g.strata_v);
    vec3 t, b;
    vec_basis(n, &t, &b);
    double sc = 0;
    for (uint32_t i = 0; i < 32; i++)
        sc += vec_dot(gather_direction(&g, i, 0.5, 0.5, n, t, b), n);
    CHECK_NEAR(sc / 32, 2.0 / 3.0, 0.01);
}

/* ---- the analytic sphere ---- */

/* scenes/furnace.scene: a closed grey sphere (rho 0.5, radius 1), a point
 * light at its centre; L = 1 in every pixel, of which 0.5 is direct light
 * (shadow rays: exact) and 0.5 the gather's. */
static const char *const furnace_text =
    "camera position 0 0 0.3 look_at 0.3 -0.2 -1 up 0 1 0 fov 90\n"
    "light point position 0 0 0 power 39.47841760435743 39.47841760435743 39.47841760435743\n"
    "material wall lambert rho 0.5 0.5 0.5\n"
    "sphere center 0 0 0 radius 1 material wall\n";

#define FURNACE_SEEDS 8
/* Student's t quantile, 7 degrees of freedom, two-sided 0.999: a correct
 * renderer fails the test one time in a thousand */
#define FURNACE_T 5.408

/* The t-test of the analytic sphere: the means m[k] of `seeds` independent
 * images (seeds), each an unbiased estimate of L = 1 (--bias-correction),
 * agree with 1 when their mean is within t s / sqrt(seeds), s their
 * standard deviation: the noise of everything that differs between seeds
 * (the photons, the gather rays), the part all pixels share included.
 * Returns 1 when they agree, and the mean and tolerance. */
static int furnace_agrees(const double *m, int seeds, double *mean, double *tol)
{
    double s1 = 0, s2 = 0;
    for (int k = 0; k < seeds; k++)
        s1 += m[k];
    *mean = s1 / seeds;
    for (int k = 0; k < seeds; k++)
        s2 += (m[k] - *mean) * (m[k] - *mean);
    double sd = sqrt(s2 / (seeds - 1));
    *tol = FURNACE_T * sd / sqrt((double)seeds);
    return fabs(*mean - 1.0) <= *tol;
}

/* The mean over an image's channels after the gather's part (the image
 * minus the exact direct 0.5) is scaled by k: k = 1 the image itself. */
static double scaled_mean(const image *im, double k)
{
    size_t n = (size_t)im->width * im->height * 3;
    double sum = 0;
    for (size_t i = 0; i < n; i++)
        sum += 0.5 + k * (im->rgb[i] - 0.5);
    return sum / (double)n;
}

void test_gather_furnace(void)
{
    scene *sc = helper_scene(furnace_text);
    for (int method = 0; method < 2; method++) {
        /* k: 1, the render; 2/3, each ray weighted by an extra cos(theta) (its
         * mean under the cosine pdf); 1/2 and 2, the gather count off by 2 */
        const double ks[] = {1.0, 2.0 / 3.0, 0.5, 2.0};
        double m[4][FURNACE_SEEDS];
        double pixel_sd = 0;
        for (int seed = 0; seed < FURNACE_SEEDS; seed++) {
            config_render cfg = config_defaults();
            cfg.method = method ? CONFIG_METHOD_PRECOMPUTED : CONFIG_METHOD_CONVENTIONAL;
            cfg.direct = CONFIG_DIRECT_SHADOW_RAYS;
            cfg.gather = 16;
            cfg.bias_correction = 1;
            cfg.photons = 20000;
            cfg.nn = 20;
            cfg.width = 32;
            cfg.height = 24;
            cfg.subpixels = 1;
            cfg.seed = 1000 + (uint64_t)seed;
            image im;
            stats_run st;
            CHECK(helper_render(sc, &cfg, 2, &im, &st) == PM_OK);
            CHECK(st.caustic_photons == 0 && st.bytes_caustic_map == 0); /* no mirror or glass */
            CHECK(st.gather_rays == (uint64_t)cfg.width * cfg.height * cfg.gather);
            CHECK(st.gather_lookups == st.gather_rays && st.gather_empty == 0 && st.gather_missed == 0);
            for (size_t k = 0; k < 4; k++)
                m[k][seed] = scaled_mean(&im, ks[k]);
            size_t n = (size_t)cfg.width * cfg.height * 3;
            double s2 = 0;
            for (size_t i = 0; i < n; i++)
                s2 += (im.rgb[i] - m[0][seed]) * (im.rgb[i] - m[0][seed]);
            pixel_sd += sqrt(s2 / (double)(n - 1)) / FURNACE_SEEDS;
            image_free(&im);
        }
        double mean, tol;
        int ok = furnace_agrees(m[0], FURNACE_SEEDS, &mean, &tol);
        printf("  furnace, --gather 16, %s: mean %.5f over %d seeds, tolerance %.5f (pixel sd %.4f)\n",
               method ? "precomputed" : "conventional", mean, FURNACE_SEEDS, tol, pixel_sd);
        CHECK_MSG(ok, "method %d: mean %.5f, tolerance %.5f", method, mean, tol);
        /* the test has power: the noise it allows is far below the errors it
         * must catch (a tolerance of 3% would pass an extra cos weight) */
        CHECK_MSG(tol < 0.01, "method %d: tolerance %.4f", method, tol);
        /* the negative controls: the same test on the wrong gathers fails */
        for (size_t k = 1; k < 4; k++) {
            double mk, tk;
            CHECK_MSG(!furnace_agrees(m[k], FURNACE_SEEDS, &mk, &tk), "control k = %.3f passes: mean %.4f", ks[k],
                      mk);
        }
    }
    scene_free(sc);
}

/* ---- the Cornell box: threads, shared rays, the maps ---- */

void test_gather_threads_and_shared_rays(void)
{
    char err[512];
    scene *sc = NULL;
    CHECK_MSG(scene_load("scenes/cornell.scene", &sc, err, sizeof err) == PM_OK, "%s", err);
    if (!sc)
        return;
    stats_run first[2];
    for (int method = 0; method < 2; method++) {
        config_render cfg = config_defaults();
        cfg.method = method ? CONFIG_METHOD_PRECOMPUTED : CONFIG_METHOD_CONVENTIONAL;
        cfg.direct = CONFIG_DIRECT_SHADOW_RAYS;
        cfg.gather = 5;
        cfg.photons = 10000;
        cfg.nn = 20;
        cfg.width = 24;
        cfg.height = 18;
        image a, b;
        stats_run sa, sb;
        CHECK(helper_render(sc, &cfg, 1, &a, &sa) == PM_OK);
        CHECK(helper_render(sc, &cfg, 3, &b, &sb) == PM_OK);
        size_t bytes = (size_t)cfg.width * cfg.height * 3 * sizeof(float);
        CHECK_MSG(memcmp(a.rgb, b.rgb, bytes) == 0, "method %d: 1 vs 3 threads differ", method);
        CHECK(sa.gather_rays == sb.gather_rays && sa.gather_lookups == sb.gather_lookups &&
              sa.caustic_nodes == sb.caustic_nodes && work_equal(&sa.work, &sb.work));
        CHECK(sa.nonfinite_pixels == 0 && sa.gather_rays > 0);
        /* the glass and mirror spheres: caustic photons, specular gather paths */
        CHECK(sa.caustic_photons > 0 && sa.caustic_photons < sa.photons_stored && sa.caustic_lookups > 0);
        CHECK(sa.gather_specular > 0);
        first[method] = sa;
        if (method == 1) {
            /* lazy evaluation at the gather hits: the eager image bit for bit */
            cfg.rep_eval = CONFIG_REP_EVAL_LAZY;
            image l;
            stats_run sl;
            CHECK(helper_render(sc, &cfg, 2, &l, &sl) == PM_OK);
            CHECK_MSG(memcmp(a.rgb, l.rgb, bytes) == 0, "lazy differs from eager under --gather");
            CHECK(sl.reps_evaluated > 0 && sl.reps_evaluated <= sa.reps_evaluated);
            image_free(&l);
        }
        image_free(&a);
        image_free(&b);
    }
    /* both methods cast the same rays: only the estimate at y differs */
    CHECK(first[0].gather_rays == first[1].gather_rays && first[0].gather_specular == first[1].gather_specular &&
          first[0].gather_lookups == first[1].gather_lookups && first[0].gather_missed == first[1].gather_missed &&
          first[0].work.render.rays == first[1].work.render.rays &&
          first[0].work.render.shape_tests == first[1].work.render.shape_tests);
    CHECK(first[0].caustic_photons == first[1].caustic_photons && first[0].caustic_nodes == first[1].caustic_nodes);
    CHECK(first[0].work.render.knn_queries == first[0].gather_lookups && first[0].work.render.rep_lookups == 0);
    CHECK(first[1].work.render.rep_lookups == first[1].gather_lookups && first[1].work.render.knn_queries == 0);
    scene_free(sc);
}

void test_gather_config(void)
{
    config_render cfg = config_defaults();
    cfg.gather = 8;
    const char *why = config_check(&cfg); /* --direct photons, the default without --gather */
    CHECK(why && strstr(why, "--gather") && strstr(why, "--direct photons"));
    cfg.direct = CONFIG_DIRECT_SHADOW_RAYS;
    CHECK(config_check(&cfg) == NULL);
    cfg.gather = 0;
    cfg.direct = CONFIG_DIRECT_PHOTONS;
    CHECK(config_check(&cfg) == NULL);
}

/* Photons at pos, every one a representative, lit from -z with normals
 * `normal`, into m; cfg: the precomputed method, n = 8, 4 gather rays;
 * reps: their own tree, evaluated. Returns the estimate's gather
 * parameters. */
static est_gather plane_reps(photons_map *m, const float (*pos)[3], uint32_t n, vec3 normal, config_render *cfg,
                             reps_set *reps)
{
    helper_map(m, pos, n, vec_make(0, 0, -1), normal, 1.0f, PHOTONS_FLAG_REP);
    *cfg = config_defaults();
    cfg->method = CONFIG_METHOD_PRECOMPUTED;
    cfg->nn = 8;
    cfg->gather = 4;
    est_gather g0 = est_gather_make(m, cfg->nn, 0.05, 0);
    CHECK(helper_reps(m, &g0, CONFIG_REP_TREE_SEPARATE, 1, reps) == PM_OK);
    return g0;
}

void test_gather_lookup_bounded(void)
{
    /* 64 x 64 representatives on the plane z = 0, normal +z; a gather hit
     * on that plane whose normal is -z (the plane's other face) has no
     * agreeing representative anywhere: within the cap the lookup visits a
     * few nodes (two searches: the first radius's, reps.h, then the cap's),
     * without one it walks the whole tree */
    enum { SIDE = 64 };
    static float pos[SIDE * SIDE][3];
    for (int i = 0; i < SIDE * SIDE; i++) {
        pos[i][0] = (float)(i % SIDE) / SIDE;
        pos[i][1] = (float)(i / SIDE) / SIDE;
        pos[i][2] = 0.0f;
    }
    photons_map m;
    config_render cfg;
    reps_set reps;
    (void)plane_reps(&m, (const float(*)[3])pos, SIDE * SIDE, vec_make(0, 0, 1), &cfg, &reps);
    est_scratch *s = est_scratch_new(1, cfg.nn);
    CHECK(s != NULL);
    if (!s)
        return;
    uint64_t nodes[2];
    for (int capped = 0; capped < 2; capped++) {
        gather_params gp = gather_params_make(NULL, &cfg, &m, &reps, NULL, capped ? 0.05 : 1e30);
        gather_counts c = {0};
        est_scratch_forget(s);
        s->rep_work.nodes = 0;
        vec3 e = gather_estimate(&gp, vec_make(0.5, 0.5, 0), vec_make(0, 0, -1), s, &c);
        CHECK(e.x == 0.0 && c.lookups == 1 && c.empty == 1);
        nodes[capped] = s->rep_work.nodes;
        /* the front face: found */
        c = (gather_counts){0};
        e = gather_estimate(&gp, vec_make(0.5, 0.5, 0), vec_make(0, 0, 1), s, &c);
        CHECK(e.x > 0.0 && c.empty == 0);
    }
    printf("  lookup with no agreeing representative: %llu nodes uncapped, %llu within the cap\n",
           (unsigned long long)nodes[0], (unsigned long long)nodes[1]);
    CHECK_MSG(nodes[1] < 128 && nodes[0] > 8 * nodes[1], "nodes: uncapped %llu, capped %llu",
              (unsigned long long)nodes[0], (unsigned long long)nodes[1]);
    est_scratch_delete(s, 1);
    reps_free(&reps);
    photons_map_free(&m);
}

void test_gather_maps(void)
{
    char err[512];
    scene *sc = NULL;
    CHECK_MSG(scene_load("scenes/cornell.scene", &sc, err, sizeof err) == PM_OK, "%s", err);
    if (!sc)
        return;
    /* the global map holds every diffuse hit, the first included: as many
     * photons as the map that gives direct light (--direct photons) */
    config_render cfg = config_defaults();
    cfg.photons = 5000;
    cfg.width = 8;
    cfg.height = 6;
    image im;
    stats_run direct, shadow, gathered;
    CHECK(helper_render(sc, &cfg, 2, &im, &direct) == PM_OK);
    image_free(&im);
    cfg.direct = CONFIG_DIRECT_SHADOW_RAYS;
    CHECK(helper_render(sc, &cfg, 2, &im, &shadow) == PM_OK);
    image_free(&im);
    cfg.gather = 2;
    CHECK(helper_render(sc, &cfg, 2, &im, &gathered) == PM_OK);
    image_free(&im);
    CHECK(gathered.photons_stored == direct.photons_stored && shadow.photons_stored < direct.photons_stored);
    CHECK(direct.caustic_photons == 0 && shadow.caustic_photons == 0); /* no caustic map without --gather */
    CHECK(gathered.caustic_photons > 0 && gathered.bytes_caustic_map > 0);

    /* L S+ D only: the photons of the caustic map arrived by mirror and
     * glass alone; a light under a mirror over a floor stores each photon's
     * first floor hit as direct (down) or caustic (up, then mirrored) */
    scene *ms = helper_scene("camera position 0 3 0 look_at 0 0 0 up 0 0 -1 fov 60\n"
                             "light point position 0 1 0 power 10 10 10\n"
                             "material w lambert rho 0 0 0\n"
                             "material m mirror reflectance 1 1 1\n"
                             "rect corner -50 0 -50 edge1 100 0 0 edge2 0 0 100 material w\n"
                             "rect corner -50 2 -50 edge1 0 0 100 edge2 100 0 0 material m\n");
    photons_params pp = {20000, 3, 64, 1};
    photons_list l;
    CHECK(photons_trace(ms, &pp, 2, NULL, &l) == PM_OK);
    uint64_t caustic = 0, direct_hits = 0;
    for (uint64_t i = 0; i < l.count; i++) {
        unsigned f = l.ph[i].flags;
        caustic += (f & PHOTONS_FLAG_CAUSTIC) != 0;
        direct_hits += (f & PHOTONS_FLAG_DIRECT) != 0;
        CHECK(!((f & PHOTONS_FLAG_CAUSTIC) && (f & PHOTONS_FLAG_DIRECT)));
    }
    /* rho 0: no photon bounces off the floor, so every stored photon is
     * one or the other, about half each (those that leave sideways escape) */
    CHECK(caustic + direct_hits == l.count);
    CHECK(caustic > l.count / 3 && direct_hits > l.count / 3);
    photons_list sel;
    CHECK(photons_list_select(&l, PHOTONS_FLAG_CAUSTIC, &sel) == PM_OK);
    CHECK(sel.count == caustic);
    for (uint64_t i = 0; i < sel.count; i++)
        CHECK(sel.ph[i].flags & PHOTONS_FLAG_CAUSTIC);
    photons_list_free(&sel);
    photons_list_free(&l);
    scene_free(ms);
    scene_free(sc);
}

void test_gather_lookup_first_radius(void)
{
    /* reps_lookup's first radius (reps.h) changes no answer: against a brute
     * force over every representative (the nearest agreeing one within the
     * cap by squared distance, as the tree computes it, then by index), on
     * random points of the plane z = 0 whose representatives' normals are
     * +z only in the strip x < 0.25, queried with either normal: the strip's
     * edge needs the search within the cap after the first radius's found
     * nothing, and the far side finds nothing at all */
    enum { COUNT = 6000, QUERIES = 4000 };
    static float pos[COUNT][3];
    rng_stream g = rng_make(11, 0);
    for (int i = 0; i < COUNT; i++) {
        pos[i][0] = (float)rng_next_double(&g);
        pos[i][1] = (float)rng_next_double(&g);
        pos[i][2] = 0.0f;
    }
    photons_map m;
    config_render cfg;
    reps_set reps;
    est_gather g0 = plane_reps(&m, (const float(*)[3])pos, COUNT, vec_make(0, 0, -1), &cfg, &reps);
    float max_r2 = (float)g0.max_r2;
    CHECK_MSG(reps.first_r2 > 0.0f && reps.first_r2 < max_r2 / 4, "first_r2 %g, cap %g", reps.first_r2, max_r2);
    for (uint32_t i = 0; i < reps.count; i++) {
        float p[3];
        kd_point(&reps.own, i, p);
        if (m.centre.x + m.scale * p[0] < 0.25)
            reps.value[i].normal[2] = 1.0f;
    }
    est_scratch *s = est_scratch_new(1, cfg.nn);
    CHECK(s != NULL);
    if (!s)
        return;
    gather_params gp = gather_params_make(NULL, &cfg, &m, &reps, NULL, 0.05);
    uint32_t differ = 0, beyond_first = 0, none = 0;
    for (int k = 0; k < QUERIES; k++) {
        /* half near the strip's edge */
        double x = k % 2 ? 0.2 + 0.15 * rng_next_double(&g) : rng_next_double(&g);
        vec3 y = vec_make(x, rng_next_double(&g), 0.0);
        vec3 n = vec_make(0, 0, rng_next_u64(&g) & 1 ? 1 : -1);
        float q[3];
        photons_map_point(&m, y, q);
        uint32_t best = KD_NONE;
        float best_d2 = 0.0f;
        for (uint32_t i = 0; i < reps.count; i++) {
            float p[3];
            kd_point(&reps.own, i, p);
            float dx = p[0] - q[0], dy = p[1] - q[1], dz = p[2] - q[2];
            float d = dx * dx + dy * dy + dz * dz;
            const float *nv = reps.value[i].normal;
            if (d <= max_r2 && nv[0] * n.x + nv[1] * n.y + nv[2] * n.z > reps.normal_cos &&
                (best == KD_NONE || d < best_d2)) {
                best = i;
                best_d2 = d;
            }
        }
        gather_counts c = {0};
        gather_estimate(&gp, y, n, s, &c);
        differ += s->last_rep != best;
        none += best == KD_NONE;
        beyond_first += best != KD_NONE && best_d2 > reps.first_r2;
    }
    printf("  first radius %g of the cap %g: %u of %d answers beyond it, %u none, %u differ\n",
           sqrt((double)reps.first_r2), sqrt((double)max_r2), beyond_first, QUERIES, none, differ);
    CHECK(differ == 0);
    CHECK(beyond_first > 10 && none > 10);
    est_scratch_delete(s, 1);
    reps_free(&reps);
    photons_map_free(&m);
}

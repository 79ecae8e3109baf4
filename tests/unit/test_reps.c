/* test_reps: the representatives (reps.h): the precompute and lookup
 * against the conventional estimate on a uniform plane, both layouts, the
 * normal test at a corner, no agreeing representative, the fixed-count rule
 * and the CSV dump. Synthetic photon maps give exact expectations. */
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "check.h"
#include "estimate.h"
#include "helpers.h"
#include "photons.h"
#include "mem.h"
#include "render.h"
#include "reps.h"
#include "rng.h"
#include "tests.h"

/* Appends n photons uniformly on the square [x0,x0+w] x [y0,y0+w] of the
 * plane given by (origin, e1, e2) with normal nrm, arriving along -nrm. */
static void add_square(photons_list *l, uint64_t n, vec3 origin, vec3 e1, vec3 e2, vec3 nrm, float power,
                       uint64_t seed)
{
    l->pos = mem_realloc(l->pos, sizeof(double) * 3 * (l->count + n));
    l->ph = mem_realloc(l->ph, sizeof(photons_record) * (l->count + n));
    rng_stream s = rng_make(seed, 0);
    for (uint64_t i = 0; i < n; i++) {
        vec3 p = vec_add(origin, vec_add(vec_scale(e1, rng_next_double(&s)), vec_scale(e2, rng_next_double(&s))));
        double *q = l->pos + 3 * (l->count + i);
        q[0] = p.x;
        q[1] = p.y;
        q[2] = p.z;
        photons_record *ph = &l->ph[l->count + i];
        memset(ph, 0, sizeof *ph);
        ph->power[0] = ph->power[1] = ph->power[2] = power;
        photons_pack_dir(-nrm.x, -nrm.y, -nrm.z, ph->dir);
        photons_pack_dir(nrm.x, nrm.y, nrm.z, ph->normal);
    }
    l->count += n;
    l->unit = vec_make(1, 1, 1);
}

static void flag_every(photons_list *l, uint64_t k)
{
    for (uint64_t i = 0; i < l->count; i += k)
        l->ph[i].flags |= PHOTONS_FLAG_REP;
}

void test_precomputed_equals_conventional_on_uniform_plane(void)
{
    /* 200k photons of 1e-5 W on a 2x2 square: E = 200000 * 1e-5 / 4 = 0.5 */
    photons_list l = {0};
    add_square(&l, 200000, vec_make(-1, 0, -1), vec_make(2, 0, 0), vec_make(0, 0, 2), vec_make(0, 1, 0), 1e-5f, 1);
    flag_every(&l, 1);
    photons_map m;
    CHECK(photons_build_map(&l, 0, 2, &m, NULL) == 0);
    reps_set reps;
    const uint32_t nn = 100;
    est_gather g = est_gather_make(&m, nn, 0.2, 0);
    CHECK(helper_reps(&m, &g, CONFIG_REP_TREE_SEPARATE, 2, &reps) == 0);
    CHECK(reps.count == 200000);
    est_scratch *s = est_scratch_new(1, nn);
    CHECK(s != NULL);
    rng_stream q = rng_make(2, 0);
    double sum_c = 0, sum_p = 0, sum_d2 = 0;
    int N = 400;
    for (int i = 0; i < N; i++) {
        vec3 x = vec_make(rng_next_double(&q) - 0.5, 0, rng_next_double(&q) - 0.5); /* away from the edges */
        uint32_t found;
        int ok;
        vec3 ec = est_irradiance(&m, x, vec_make(0, 1, 0), &g, s, &found);
        vec3 ep = reps_lookup(&reps, &m, x, vec_make(0, 1, 0), &g, s, &ok);
        CHECK(found == nn && ok);
        sum_c += ec.y;
        sum_p += ep.y;
        sum_d2 += (ec.y - ep.y) * (ec.y - ep.y);
    }
    /* both unbiased to the noise of n = 100 photons (10% per estimate) */
    CHECK_NEAR(sum_c / N, 0.5, 0.5 * 0.03);
    CHECK_NEAR(sum_p / N, 0.5, 0.5 * 0.03);
    /* per point they differ by estimator noise only: rms below ~2 x 10% */
    CHECK_MSG(sqrt(sum_d2 / N) < 0.5 * 0.2, "rms difference %.4f", sqrt(sum_d2 / N));
    /* the same with representatives found in the photon tree by flag */
    reps_set shared;
    CHECK(helper_reps(&m, &g, CONFIG_REP_TREE_SHARED, 1, &shared) == 0);
    est_scratch *s2 = est_scratch_new(1, nn); /* the two layouts' indices differ: a scratch each */
    for (int i = 0; i < 50; i++) {
        vec3 x = vec_make(rng_next_double(&q) - 0.5, 0, rng_next_double(&q) - 0.5);
        int a, b;
        vec3 e1 = reps_lookup(&reps, &m, x, vec_make(0, 1, 0), &g, s, &a);
        vec3 e2 = reps_lookup(&shared, &m, x, vec_make(0, 1, 0), &g, s2, &b);
        CHECK(a && b && e1.y == e2.y);
    }
    reps_free(&shared);
    est_scratch_delete(s2, 1);
    est_scratch_delete(s, 1);
    reps_free(&reps);
    photons_map_free(&m);
}

void test_precomputed_normal_test_at_corner(void)
{
    /* floor y=0 (normal +y) with dense dim photons, back wall z=0 (normal +z)
     * with sparse bright ones: a floor point next to the corner is nearer to
     * wall representatives, yet must take a floor value */
    photons_list l = {0};
    add_square(&l, 40000, vec_make(-1, 0, 0), vec_make(2, 0, 0), vec_make(0, 0, 2), vec_make(0, 1, 0), 1e-5f, 3);
    add_square(&l, 4000, vec_make(-1, 0, 0), vec_make(2, 0, 0), vec_make(0, 2, 0), vec_make(0, 0, 1), 1e-2f, 4);
    flag_every(&l, 3);
    photons_map m;
    CHECK(photons_build_map(&l, 0, 2, &m, NULL) == 0);
    reps_set reps;
    est_gather g = est_gather_make(&m, 50, 0.3, 0);
    CHECK(helper_reps(&m, &g, CONFIG_REP_TREE_SEPARATE, 1, &reps) == 0);
    est_scratch *s = est_scratch_new(1, 1);
    /* floor E ~ 40000*1e-5/4 = 0.1; wall E ~ 4000*1e-2/4 = 10 */
    rng_stream q = rng_make(9, 0);
    int floor_ok = 1, wall_ok = 1;
    for (int i = 0; i < 500; i++) {
        double t = rng_next_double(&q) * 0.01, u = rng_next_double(&q) - 0.5;
        int f1, f2;
        vec3 on_floor = reps_lookup(&reps, &m, vec_make(u, 0, t), vec_make(0, 1, 0), &g, s, &f1);
        vec3 on_wall = reps_lookup(&reps, &m, vec_make(u, t, 0), vec_make(0, 0, 1), &g, s, &f2);
        floor_ok &= f1 && on_floor.y < 1.0;
        wall_ok &= f2 && on_wall.y > 1.0;
    }
    CHECK(floor_ok);
    CHECK(wall_ok);
    /* a tilted normal that agrees with neither (cos 0.707 < 0.9): defined zero */
    int f;
    vec3 e = reps_lookup(&reps, &m, vec_make(0, 0.001, 0.001), vec_norm(vec_make(0, 1, 1)), &g, s, &f);
    CHECK(!f && e.x == 0.0 && e.y == 0.0 && e.z == 0.0);
    reps_free(&reps);
    est_scratch_delete(s, 1);
    photons_map_free(&m);
}

/* --rep-count: exactly min(N, stored) representatives, spread evenly over
 * the trace order (gaps of floor or ceil of stored / N), all when N is at
 * or above the stored count. */
void test_precomputed_rep_count(void)
{
    char err[512];
    scene *sc = NULL;
    CHECK_MSG(scene_load("scenes/cornell.scene", &sc, err, sizeof err) == PM_OK, "%s", err);
    if (!sc)
        return;
    const uint64_t counts[4] = {1, 777, 5000, 1000000};
    for (int c = 0; c < 4; c++) {
        photons_params pp = {20000, 3, 64, 1};
        reps_params rp = {.rep_every = 4, .rep_count = counts[c], .rep_tree = CONFIG_REP_TREE_SEPARATE,
                          .bias_correction = 0, .normal_cos = CONFIG_DEFAULT_NORMAL_COS};
        photons_list l;
        CHECK(photons_trace(sc, &pp, 2, NULL, &l) == 0);
        uint64_t chosen = reps_choose(&rp, &l);
        uint64_t want = counts[c] < l.count ? counts[c] : l.count, got = 0, last = 0, gap_lo = UINT64_MAX, gap_hi = 0;
        for (uint64_t i = 0; i < l.count; i++) {
            if (!(l.ph[i].flags & PHOTONS_FLAG_REP))
                continue;
            if (got > 0) {
                gap_lo = i - last < gap_lo ? i - last : gap_lo;
                gap_hi = i - last > gap_hi ? i - last : gap_hi;
            }
            last = i;
            got++;
        }
        CHECK_MSG(got == want, "rep_count %llu: %llu representatives of %llu stored", (unsigned long long)counts[c],
                  (unsigned long long)got, (unsigned long long)l.count);
        CHECK(chosen == got); /* what it returns is what it flagged */
        CHECK(l.count > 5000 && (l.ph[0].flags & PHOTONS_FLAG_REP));
        if (got > 1)
            CHECK_MSG(gap_lo >= l.count / want && gap_hi <= (l.count + want - 1) / want,
                      "gaps %llu..%llu for %llu of %llu", (unsigned long long)gap_lo, (unsigned long long)gap_hi,
                      (unsigned long long)want, (unsigned long long)l.count);
        photons_list_free(&l);
    }
    scene_free(sc);
}

/* reps_write_csv (--dump-reps): one line per representative with its
 * position, normal and precomputed irradiance, in scene units; a lookup at
 * a dumped position returns the dumped irradiance (the representative is
 * its own nearest), in both layouts, on a plane far from the origin. */
void test_precomputed_dump_reps(void)
{
    photons_list l = {0};
    add_square(&l, 20000, vec_make(99, 5, -1), vec_make(2, 0, 0), vec_make(0, 0, 2), vec_make(0, 1, 0), 1e-5f, 5);
    flag_every(&l, 8);
    photons_map m;
    CHECK(photons_build_map(&l, 0, 2, &m, NULL) == 0);
    est_gather g = est_gather_make(&m, 50, 0.3, 0);
    for (int layout = 0; layout < 2; layout++) {
        reps_set reps;
        CHECK(helper_reps(&m, &g, layout ? CONFIG_REP_TREE_SHARED : CONFIG_REP_TREE_SEPARATE, 2, &reps) == 0);
        FILE *f = tmpfile();
        CHECK(f != NULL);
        if (!f)
            break;
        CHECK(reps_write_csv(&reps, &m, f) == 0);
        rewind(f);
        char line[512];
        CHECK(fgets(line, sizeof line, f) && !strcmp(line, "x,y,z,nx,ny,nz,e_r,e_g,e_b\n"));
        uint32_t rows = 0, bad = 0, lookups_equal = 0;
        double sum_e = 0;
        double v[9];
        while (fscanf(f, "%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf", &v[0], &v[1], &v[2], &v[3], &v[4], &v[5], &v[6],
                      &v[7], &v[8]) == 9) {
            rows++;
            /* on the plane y = 5 inside the square, normal +y, E about 20000 * 1e-5 / 4 = 0.05 */
            bad += !(v[0] >= 99 && v[0] <= 101 && fabs(v[1] - 5) < 1e-5 && v[2] >= -1 && v[2] <= 1 &&
                     fabs(v[4] - 1) < 0.01 && v[6] > 0 && v[6] == v[7] && v[7] == v[8]);
            sum_e += v[7];
            if (rows % 97 == 0) {
                int found;
                est_scratch *ls = est_scratch_new(1, 1);
                vec3 e = reps_lookup(&reps, &m, vec_make(v[0], v[1], v[2]), vec_make(0, 1, 0), &g, ls, &found);
                est_scratch_delete(ls, 1);
                lookups_equal += found && fabs(e.y - v[7]) <= 1e-6 * v[7];
            }
        }
        CHECK_MSG(rows == reps.count && rows == 2500, "%u rows, %u representatives", rows, reps.count);
        CHECK_MSG(bad == 0, "%u rows off the plane or with a wrong normal or irradiance", bad);
        CHECK_NEAR(sum_e / rows, 0.05, 0.05 * 0.05); /* edges lose up to half of the disc */
        CHECK_MSG(lookups_equal == rows / 97, "%u of %u lookups at a dumped position gave its irradiance",
                  lookups_equal, rows / 97);
        fclose(f);
        reps_free(&reps);
    }
    photons_map_free(&m);
}

static const vec3 down = {0, -1, 0}, up_n = {0, 1, 0};

void test_stability_no_agreeing_representative(void)
{
    /* representatives on a floor (normal +y); a lookup on a surface facing
     * -y (the floor's underside) or sideways finds none: 0 */
    float pos[16][3];
    for (int i = 0; i < 16; i++)
        pos[i][0] = (float)(0.01 * (i % 4)), pos[i][1] = 0.0f, pos[i][2] = (float)(0.01 * (i / 4));
    photons_map m;
    helper_map(&m, (const float(*)[3])pos, 16, down, up_n, 1.0f, PHOTONS_FLAG_REP);
    for (int layout = 0; layout < 2; layout++) {
        reps_set r;
        est_gather g = est_gather_make(&m, 4, 0.1, 0);
        est_scratch *ls = est_scratch_new(1, 4);
        CHECK(helper_reps(&m, &g, layout ? CONFIG_REP_TREE_SHARED : CONFIG_REP_TREE_SEPARATE, 2, &r) == 0);
        CHECK(r.count == 16);
        int found = -1;
        vec3 e = reps_lookup(&r, &m, vec_make(0.01, 0, 0.01), down, &g, ls, &found);
        CHECK(found == 0 && e.x == 0.0 && e.y == 0.0 && e.z == 0.0);
        e = reps_lookup(&r, &m, vec_make(0.01, 0, 0.01), vec_make(1, 0, 0), &g, ls, &found);
        CHECK(found == 0 && e.x == 0.0);
        /* the agreeing side finds one, finite and positive */
        e = reps_lookup(&r, &m, vec_make(0.01, 0, 0.01), up_n, &g, ls, &found);
        CHECK(found == 1 && isfinite(e.x) && e.x > 0.0);
        /* none in range */
        e = reps_lookup(&r, &m, vec_make(5, 0, 5), up_n, &g, ls, &found);
        CHECK(found == 0 && e.x == 0.0);
        reps_free(&r);
        est_scratch_delete(ls, 1);
    }
    photons_map_free(&m);
}

/* The representatives of map m with the variants' settings (the flagged
 * photons, all in the tree), evaluated on `threads` threads. */
static void variant_reps(const photons_map *m, const est_gather *g, config_rep_tree tree, config_rep_eval eval,
                         config_rep_gate gate, double tau, unsigned threads, reps_set *out)
{
    reps_params p = {.rep_every = 0, .rep_count = 0, .rep_tree = tree, .bias_correction = 0, .rep_eval = eval,
                     .rep_gate = gate, .rep_gate_tau = tau, .normal_cos = CONFIG_DEFAULT_NORMAL_COS};
    CHECK(reps_collect(&p, m, NULL, out) == PM_OK);
    CHECK(reps_evaluate(out, m, g, threads, NULL) == PM_OK);
}

/* A corner (floor y = 0 and wall z = 0, 40k photons each, every 3rd a
 * representative) and lookup points on both near the edge. */
#define LAZY_POINTS 3000
static void corner_map(photons_map *m, vec3 *pts, vec3 *nrm)
{
    photons_list l = {0};
    add_square(&l, 40000, vec_make(-1, 0, 0), vec_make(2, 0, 0), vec_make(0, 0, 1), vec_make(0, 1, 0), 1e-5f, 11);
    add_square(&l, 40000, vec_make(-1, 0, 0), vec_make(2, 0, 0), vec_make(0, 1, 0), vec_make(0, 0, 1), 2e-5f, 12);
    flag_every(&l, 3);
    CHECK(photons_build_map(&l, 0, 2, m, NULL) == 0);
    rng_stream q = rng_make(13, 0);
    for (int i = 0; i < LAZY_POINTS; i++) {
        double u = rng_next_double(&q) * 1.8 - 0.9, t = rng_next_double(&q) * 0.2;
        pts[i] = i % 2 ? vec_make(u, 0, t) : vec_make(u, t, 0);
        nrm[i] = i % 2 ? vec_make(0, 1, 0) : vec_make(0, 0, 1);
    }
}

typedef struct {
    const reps_set *r;
    const photons_map *m;
    const est_gather *g;
    const vec3 *pts, *nrm;
    vec3 *out;
    int *found;
    int reverse;
} lazy_job;

static void *lazy_worker(void *arg)
{
    lazy_job *j = arg;
    est_scratch *s = est_scratch_new(1, j->g->nn);
    CHECK(s != NULL);
    for (int k = 0; k < LAZY_POINTS; k++) {
        int i = j->reverse ? LAZY_POINTS - 1 - k : k;
        j->out[i] = reps_lookup(j->r, j->m, j->pts[i], j->nrm[i], j->g, s, &j->found[i]);
    }
    est_scratch_delete(s, 1);
    return NULL;
}

/* Lookups of rs from two threads at once (one forwards, one backwards, so
 * they race for the same representatives); both must match want. */
static void check_two_threads(const reps_set *rs, const photons_map *m, const est_gather *g, const vec3 *pts,
                              const vec3 *nrm, const vec3 *want, const int *want_found)
{
    static vec3 out[2][LAZY_POINTS];
    static int found[2][LAZY_POINTS];
    lazy_job jobs[2];
    pthread_t th[2];
    for (int t = 0; t < 2; t++) {
        jobs[t] = (lazy_job){rs, m, g, pts, nrm, out[t], found[t], t};
        CHECK(pthread_create(&th[t], NULL, lazy_worker, &jobs[t]) == 0);
    }
    for (int t = 0; t < 2; t++)
        pthread_join(th[t], NULL);
    for (int t = 0; t < 2; t++) {
        CHECK(memcmp(out[t], want, sizeof out[t]) == 0);
        CHECK(memcmp(found[t], want_found, sizeof found[t]) == 0);
    }
}

void test_reps_lazy_equals_eager(void)
{
    /* lazy computes a representative on its first selection with the same
     * gather as the eager precompute: every lookup the same bits, from one
     * thread or two racing, in both layouts and with the plane gate; only
     * the selected ones are computed */
    static vec3 pts[LAZY_POINTS], nrm[LAZY_POINTS], want[LAZY_POINTS], got[LAZY_POINTS];
    static int want_found[LAZY_POINTS], got_found[LAZY_POINTS];
    photons_map m;
    corner_map(&m, pts, nrm);
    const uint32_t nn = 40;
    est_gather g = est_gather_make(&m, nn, 0.2, 0);
    est_scratch *s = est_scratch_new(1, nn);
    CHECK(s != NULL);
    for (int v = 0; v < 3; v++) {
        config_rep_tree tree = v == 1 ? CONFIG_REP_TREE_SHARED : CONFIG_REP_TREE_SEPARATE;
        config_rep_gate gate = v == 2 ? CONFIG_REP_GATE_PLANE : CONFIG_REP_GATE_NONE;
        reps_set eager, lazy, lazy2;
        variant_reps(&m, &g, tree, CONFIG_REP_EVAL_EAGER, gate, 0.1, 2, &eager);
        variant_reps(&m, &g, tree, CONFIG_REP_EVAL_LAZY, gate, 0.1, 2, &lazy);
        variant_reps(&m, &g, tree, CONFIG_REP_EVAL_LAZY, gate, 0.1, 1, &lazy2);
        CHECK(reps_evaluated(&eager) == eager.count && reps_evaluated(&lazy) == 0);
        for (int i = 0; i < LAZY_POINTS; i++) {
            want[i] = reps_lookup(&eager, &m, pts[i], nrm[i], &g, s, &want_found[i]);
            got[i] = reps_lookup(&lazy, &m, pts[i], nrm[i], &g, s, &got_found[i]);
        }
        CHECK(memcmp(want, got, sizeof want) == 0 && memcmp(want_found, got_found, sizeof want_found) == 0);
        uint64_t evaluated = reps_evaluated(&lazy);
        CHECK(evaluated > 0 && evaluated < lazy.count);
        /* a second pass computes nothing more and answers the same */
        for (int i = 0; i < LAZY_POINTS; i++)
            got[i] = reps_lookup(&lazy, &m, pts[i], nrm[i], &g, s, &got_found[i]);
        CHECK(memcmp(want, got, sizeof want) == 0 && reps_evaluated(&lazy) == evaluated);
        check_two_threads(&lazy2, &m, &g, pts, nrm, want, want_found);
        CHECK(reps_evaluated(&lazy2) == evaluated);
        /* negative control: a lazy set on another gather differs */
        if (v == 0) {
            est_gather g2 = est_gather_make(&m, nn / 2, 0.2, 0);
            reps_set other;
            variant_reps(&m, &g2, tree, CONFIG_REP_EVAL_LAZY, gate, 0.1, 1, &other);
            for (int i = 0; i < LAZY_POINTS; i++)
                got[i] = reps_lookup(&other, &m, pts[i], nrm[i], &g, s, &got_found[i]);
            CHECK(memcmp(want, got, sizeof want) != 0);
            reps_free(&other);
        }
        reps_free(&eager);
        reps_free(&lazy);
        reps_free(&lazy2);
    }
    est_scratch_delete(s, 1);
    photons_map_free(&m);
}

void test_reps_plane_gate(void)
{
    /* the gate's height: 0 for two points of one sphere of any radius (a
     * small one seen from 0.02 away, where the tangent plane alone puts
     * the other point 0.004 off, the negative control), the offset for a
     * parallel face, infinite for opposite normals */
    {
        double R = 0.05, a = 0.4; /* radians apart on the sphere */
        vec3 n1 = vec_make(0, 1, 0), n2 = vec_make(sin(a), cos(a), 0);
        vec3 d = vec_scale(vec_sub(n2, n1), R);
        CHECK(est_surface_height(d, n1, n2) < 1e-15);
        CHECK(fabs(vec_dot(d, n1)) > 0.003);
        CHECK(est_surface_height(vec_scale(vec_sub(n2, n1), -R), n1, n2) < 1e-15); /* the inside */
        CHECK_NEAR(est_surface_height(vec_make(0.01, 0.003, 0.02), n1, vec_scale(n1, 0.9)), 0.003, 1e-15);
        CHECK(isinf(est_surface_height(vec_make(0.01, 0, 0), n1, vec_scale(n1, -1.0))));
    }
    const uint32_t nn = 100;
    est_scratch *s = est_scratch_new(1, nn);
    CHECK(s != NULL);
    rng_stream q = rng_make(21, 0);
    /* a uniform plane: no representative fails the gate, so it changes
     * nothing, bit for bit, and never falls back */
    {
        photons_list l = {0};
        add_square(&l, 200000, vec_make(-1, 0, -1), vec_make(2, 0, 0), vec_make(0, 0, 2), vec_make(0, 1, 0), 1e-5f, 22);
        flag_every(&l, 4);
        photons_map m;
        CHECK(photons_build_map(&l, 0, 2, &m, NULL) == 0);
        est_gather g = est_gather_make(&m, nn, 0.2, 0);
        reps_set plain, gated;
        variant_reps(&m, &g, CONFIG_REP_TREE_SEPARATE, CONFIG_REP_EVAL_EAGER, CONFIG_REP_GATE_NONE, 0.1, 2, &plain);
        variant_reps(&m, &g, CONFIG_REP_TREE_SEPARATE, CONFIG_REP_EVAL_EAGER, CONFIG_REP_GATE_PLANE, 0.1, 2, &gated);
        int same = 1, fallbacks = 0;
        for (int i = 0; i < 2000; i++) {
            vec3 x = vec_make(rng_next_double(&q) * 1.9 - 0.95, 0, rng_next_double(&q) * 1.9 - 0.95);
            int f1, f2;
            vec3 a = reps_lookup(&plain, &m, x, vec_make(0, 1, 0), &g, s, &f1);
            vec3 b = reps_lookup(&gated, &m, x, vec_make(0, 1, 0), &g, s, &f2);
            same &= memcmp(&a, &b, sizeof a) == 0 && f1 == f2;
            fallbacks += (f2 & REPS_FALLBACK) != 0;
        }
        CHECK(same && fallbacks == 0);
        /* a point 0.02 above the plane (a surface with no representative of
         * its own): every candidate is off its tangent plane, so the gate
         * falls back to the conventional estimate there, the same bits */
        vec3 x = vec_make(0.1, 0.02, 0.1);
        int f;
        uint32_t k;
        vec3 e = reps_lookup(&gated, &m, x, vec_make(0, 1, 0), &g, s, &f);
        vec3 c = est_irradiance(&m, x, vec_make(0, 1, 0), &g, s, &k);
        CHECK(f == (REPS_FALLBACK | REPS_FOUND) && memcmp(&e, &c, sizeof e) == 0);
        /* negative control: ungated, a representative of the plane answers */
        e = reps_lookup(&plain, &m, x, vec_make(0, 1, 0), &g, s, &f);
        CHECK(f == REPS_FOUND && memcmp(&e, &c, sizeof e) != 0);
        reps_free(&plain);
        reps_free(&gated);
        photons_map_free(&m);
    }
    /* a thin slab: two parallel lit faces 0.01 apart, facing the same way
     * (E = 0.25 each), closer than the kNN radius r (about 0.025): the
     * paper's precompute counts both faces' photons (the ball cuts the
     * other face in a disc of radius sqrt(r^2 - 0.01^2): E about 0.46) and
     * its lookup takes the other face's representatives; the gate keeps
     * each face to itself */
    {
        photons_list l = {0};
        add_square(&l, 100000, vec_make(-1, 0, -1), vec_make(2, 0, 0), vec_make(0, 0, 2), vec_make(0, 1, 0), 1e-5f, 23);
        add_square(&l, 100000, vec_make(-1, 0.01, -1), vec_make(2, 0, 0), vec_make(0, 0, 2), vec_make(0, 1, 0), 1e-5f,
                   24);
        flag_every(&l, 4);
        photons_map m;
        CHECK(photons_build_map(&l, 0, 2, &m, NULL) == 0);
        est_gather g = est_gather_make(&m, nn, 0.2, 0);
        reps_set plain, gated;
        variant_reps(&m, &g, CONFIG_REP_TREE_SEPARATE, CONFIG_REP_EVAL_EAGER, CONFIG_REP_GATE_NONE, 0.1, 2, &plain);
        variant_reps(&m, &g, CONFIG_REP_TREE_SEPARATE, CONFIG_REP_EVAL_LAZY, CONFIG_REP_GATE_PLANE, 0.1, 2, &gated);
        double sum_p = 0, sum_g = 0;
        int N = 1000, fallbacks = 0;
        for (int i = 0; i < N; i++) {
            vec3 x = vec_make(rng_next_double(&q) - 0.5, i % 2 ? 0.0 : 0.01, rng_next_double(&q) - 0.5);
            int f1, f2;
            sum_p += reps_lookup(&plain, &m, x, vec_make(0, 1, 0), &g, s, &f1).y;
            sum_g += reps_lookup(&gated, &m, x, vec_make(0, 1, 0), &g, s, &f2).y;
            CHECK((f1 & REPS_FOUND) && (f2 & REPS_FOUND));
            fallbacks += (f2 & REPS_FALLBACK) != 0;
        }
        CHECK(sum_p / N > 0.25 * 1.6);
        CHECK_NEAR(sum_g / N, 0.25, 0.25 * 0.05);
        CHECK(fallbacks < N / 10);
        /* plane-lookup: the same lookup gate on the paper's precompute,
         * whose values still count both faces */
        reps_set lookup_only;
        variant_reps(&m, &g, CONFIG_REP_TREE_SEPARATE, CONFIG_REP_EVAL_EAGER, CONFIG_REP_GATE_PLANE_LOOKUP, 0.1, 2,
                     &lookup_only);
        double sum_l = 0;
        for (int i = 0; i < N; i++) {
            vec3 x = vec_make(rng_next_double(&q) - 0.5, i % 2 ? 0.0 : 0.01, rng_next_double(&q) - 0.5);
            int f;
            sum_l += reps_lookup(&lookup_only, &m, x, vec_make(0, 1, 0), &g, s, &f).y;
        }
        CHECK(sum_l / N > 0.25 * 1.6);
        reps_free(&lookup_only);
        reps_free(&plain);
        reps_free(&gated);
        photons_map_free(&m);
    }
    est_scratch_delete(s, 1);
}

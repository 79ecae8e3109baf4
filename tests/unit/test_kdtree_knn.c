/* test_kdtree_knn: the k-nearest search (kd_query_knn) against brute
 * force: single queries, walks with the state carried along, its hints
 * and history, and the eye pass's own query stream. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "helpers.h"
#include "rng.h"
#include "tests.h"

static int cmp_float(const void *a, const void *b)
{
    float x = *(const float *)a, y = *(const float *)b;
    return (x > y) - (x < y);
}

static float dist2(const float *p, const float q[3])
{
    float dx = p[0] - q[0], dy = p[1] - q[1], dz = p[2] - q[2];
    return dx * dx + dy * dy + dz * dz;
}

/* Checks helper_knn against brute force for one query; returns failures. */
static void check_query(const kd_tree *t, const float *pts, const uint32_t *perm, uint32_t n, const float q[3],
                        uint32_t k, float max_d2)
{
    uint32_t *idx = malloc(sizeof(uint32_t) * (k + 1));
    float *d2 = malloc(sizeof(float) * (k + 1));
    float *all = malloc(sizeof(float) * (n + 1));
    float r2;
    uint32_t got = helper_knn(t, q, k, max_d2, idx, d2, &r2);
    uint32_t in_range = 0;
    for (uint32_t i = 0; i < n; i++) {
        float d = dist2(pts + 3 * i, q);
        if (d <= max_d2)
            all[in_range++] = d;
    }
    qsort(all, in_range, sizeof(float), cmp_float);
    uint32_t want = in_range < k ? in_range : k;
    CHECK_MSG(got == want, "n=%u k=%u: got %u neighbours, brute force %u", n, k, got, want);
    if (got == want) {
        /* distances reported must be the true distances of the reported points */
        for (uint32_t j = 0; j < got; j++) {
            uint32_t orig = perm[idx[j]];
            CHECK(d2[j] == dist2(pts + 3 * orig, q));
        }
        qsort(d2, got, sizeof(float), cmp_float);
        int same = 1;
        for (uint32_t j = 0; j < got; j++)
            same &= d2[j] == all[j];
        CHECK_MSG(same, "n=%u k=%u: neighbour distances differ from brute force", n, k);
        CHECK(got == 0 ? r2 == 0.0f : r2 == all[got - 1]);
        /* no duplicates */
        for (uint32_t a = 0; a < got; a++)
            for (uint32_t b = a + 1; b < got; b++)
                CHECK(idx[a] != idx[b]);
    }
    free(idx);
    free(d2);
    free(all);
}

static float *random_points(uint32_t n, uint64_t seed, int clustered)
{
    float *p = malloc(sizeof(float) * 3 * (n + 1));
    rng_stream s = rng_make(seed, 0);
    for (uint32_t i = 0; i < 3 * n; i++) {
        double u = rng_next_double(&s);
        p[i] = clustered ? (float)floor(u * 4.0) * 0.25f : (float)(u * 2.0 - 1.0);
    }
    return p;
}

void test_kdtree_matches_brute_force(void)
{
    const uint32_t sizes[] = {2, 7, 12, 13, 100, 1000, 4099};
    const uint32_t ks[] = {1, 2, 5, 10, 16, 17, 20, 50, 100};
    for (size_t si = 0; si < sizeof sizes / sizeof sizes[0]; si++) {
        for (int clustered = 0; clustered < 2; clustered++) {
            uint32_t n = sizes[si];
            float *pts = random_points(n, 1000 + n, clustered);
            uint32_t *perm = malloc(sizeof(uint32_t) * n);
            kd_tree t;
            CHECK(kd_build(&t, pts, n, KD_DEFAULT_LEAF, perm, 1) == PM_OK);
            rng_stream s = rng_make(7, n);
            for (int qi = 0; qi < 20; qi++) {
                float q[3];
                for (int a = 0; a < 3; a++)
                    q[a] = (float)(rng_next_double(&s) * 3.0 - 1.5);
                if (qi == 0)
                    memcpy(q, pts, sizeof q); /* exactly on a point */
                for (size_t ki = 0; ki < sizeof ks / sizeof ks[0]; ki++) {
                    check_query(&t, pts, perm, n, q, ks[ki], INFINITY);
                    check_query(&t, pts, perm, n, q, ks[ki], 0.05f);
                }
            }
            kd_free(&t);
            free(perm);
            free(pts);
        }
    }
}

void test_kdtree_edge_cases(void)
{
    kd_tree t;
    float q[3] = {0, 0, 0};
    uint32_t idx[8];
    float d2[8], r2 = -1.0f;
    /* N = 0 */
    CHECK(kd_build(&t, NULL, 0, KD_DEFAULT_LEAF, NULL, 1) == PM_OK);
    CHECK(helper_knn(&t, q, 5, INFINITY, idx, d2, &r2) == 0);
    CHECK(r2 == 0.0f);
    kd_free(&t);
    /* N = 1, k > N */
    float one[3] = {1, 2, 3};
    uint32_t perm1[1];
    CHECK(kd_build(&t, one, 1, KD_DEFAULT_LEAF, perm1, 1) == PM_OK);
    CHECK(helper_knn(&t, q, 5, INFINITY, idx, d2, &r2) == 1);
    CHECK(d2[0] == 14.0f && r2 == 14.0f && perm1[idx[0]] == 0);
    CHECK(helper_knn(&t, q, 5, 13.9f, idx, d2, &r2) == 0); /* radius cap excludes it */
    kd_free(&t);
    /* all points identical (r = 0 for the query on them), k > N */
    enum { NDUP = 300 };
    float *dup = malloc(sizeof(float) * 3 * NDUP);
    for (int i = 0; i < 3 * NDUP; i++)
        dup[i] = 0.5f;
    uint32_t *perm = malloc(sizeof(uint32_t) * NDUP);
    CHECK(kd_build(&t, dup, NDUP, KD_DEFAULT_LEAF, perm, 1) == PM_OK);
    float on[3] = {0.5f, 0.5f, 0.5f};
    check_query(&t, dup, perm, NDUP, on, 100, INFINITY);
    check_query(&t, dup, perm, NDUP, on, NDUP + 10, INFINITY);
    check_query(&t, dup, perm, NDUP, q, 7, INFINITY);
    CHECK(helper_knn(&t, on, 7, INFINITY, idx, d2, &r2) == 7 && r2 == 0.0f);
    kd_free(&t);
    free(dup);
    free(perm);
    /* leaf size 1 and huge leaves give the same answers */
    float *pts = random_points(500, 3, 0);
    uint32_t *p2 = malloc(sizeof(uint32_t) * 500);
    const uint32_t leaves[] = {1, 3, 1000};
    for (size_t li = 0; li < 3; li++) {
        CHECK(kd_build(&t, pts, 500, leaves[li], p2, 1) == PM_OK);
        check_query(&t, pts, p2, 500, q, 30, INFINITY);
        check_query(&t, pts, p2, 500, q, 3, 0.01f);
        kd_free(&t);
    }
    free(pts);
    free(p2);
}

/* ---- kd_query_knn: every path against brute force ----
 * The answer to a query is the k smallest (squared distance, leaf-order
 * index) pairs within the cap, so it can be compared exactly, ties
 * included, whatever path produced it. */

typedef struct {
    float d;
    uint32_t i;
} kd_pair;

static int cmp_pair(const void *a, const void *b)
{
    const kd_pair *x = a, *y = b;
    if (x->d != y->d)
        return (x->d > y->d) - (x->d < y->d);
    return (x->i > y->i) - (x->i < y->i);
}

/* Every point's (squared distance, leaf index) pair for q, sorted; computed
 * from the input points through perm, as the tree's arithmetic does it. */
static kd_pair *brute_sorted(const float *pts, const uint32_t *perm, uint32_t n, const float q[3])
{
    kd_pair *all = malloc(sizeof(kd_pair) * (n + 1));
    for (uint32_t i = 0; i < n; i++) {
        all[i].d = dist2(pts + 3 * (size_t)perm[i], q);
        all[i].i = i;
    }
    qsort(all, n, sizeof(kd_pair), cmp_pair);
    return all;
}

/* Checks one answer against the sorted brute-force pairs; returns 1 when it
 * matches (the first few mismatches are reported). */
static int check_answer(const kd_pair *all, uint32_t n, uint32_t k, float cap, uint32_t got, const uint32_t *idx,
                        const float *d2, float r2, const char *what)
{
    uint32_t want = 0;
    while (want < n && want < k && all[want].d <= cap)
        want++;
    int ok = got == want && r2 == (want ? all[want - 1].d : 0.0f);
    if (ok && got) {
        kd_pair *mine = malloc(sizeof(kd_pair) * got);
        for (uint32_t j = 0; j < got; j++) {
            mine[j].d = d2[j];
            mine[j].i = idx[j];
        }
        qsort(mine, got, sizeof(kd_pair), cmp_pair);
        for (uint32_t j = 0; j < got && ok; j++)
            ok = mine[j].d == all[j].d && mine[j].i == all[j].i;
        free(mine);
    }
    static int reported;
    if (!ok && reported++ < 10)
        fprintf(stderr, "  %s: n=%u k=%u cap=%g: got %u (r2 %g), want %u (r2 %g)\n", what, n, k, (double)cap, got,
                (double)r2, want, want ? (double)all[want - 1].d : 0.0);
    return ok;
}

/* Point sets: 0 uniform in a cube, 1 on five axis-aligned "walls" (the photon
 * maps' case), 2 on 64 positions only (duplicates, equal distances), 3 a
 * 24 x 24 integer grid in a plane (many exact ties). */
static float *point_set(int kind, uint32_t n, uint64_t seed)
{
    float *p = malloc(sizeof(float) * 3 * (n + 1));
    rng_stream s = rng_make(seed, (uint64_t)kind);
    for (uint32_t i = 0; i < n; i++) {
        float *o = p + 3 * (size_t)i;
        double u = rng_next_double(&s), v = rng_next_double(&s), w = rng_next_double(&s);
        switch (kind) {
        case 0:
            o[0] = (float)(2 * u - 1), o[1] = (float)(2 * v - 1), o[2] = (float)(2 * w - 1);
            break;
        case 1: {
            int wall = (int)(rng_next_double(&s) * 5);
            float a = (float)(2 * u - 1), b = (float)(2 * v - 1);
            o[0] = wall == 0 ? -1.0f : (wall == 1 ? 1.0f : a);
            o[1] = wall == 2 ? -1.0f : (wall == 3 ? 1.0f : (wall < 2 ? a : b));
            o[2] = wall == 4 ? -1.0f : b;
            break;
        }
        case 2:
            o[0] = (float)floor(u * 4) * 0.25f, o[1] = (float)floor(v * 4) * 0.25f, o[2] = (float)floor(w * 4) * 0.25f;
            break;
        default:
            o[0] = (float)(i % 24), o[1] = (float)(i / 24 % 24), o[2] = 0.0f;
            break;
        }
    }
    return p;
}

/* A query walk around the set: small steps (coherent, like the eye pass),
 * a jump every 8th query, every 5th exactly on a point, some outside. */
static void query_walk(const float *pts, uint32_t n, int kind, uint32_t nq, uint64_t seed, float *q)
{
    rng_stream s = rng_make(seed, 99);
    float scale = kind == 3 ? 24.0f : 2.0f, step = scale * 0.01f;
    float cur[3] = {0, 0, 0};
    for (uint32_t i = 0; i < nq; i++) {
        if (i % 8 == 0)
            for (int a = 0; a < 3; a++)
                cur[a] = (float)((rng_next_double(&s) * 1.4 - 0.2) * scale - (kind == 3 ? 0 : scale / 2));
        else
            for (int a = 0; a < 3; a++)
                cur[a] += (float)((rng_next_double(&s) * 2 - 1) * step);
        if (i % 5 == 4 && n > 0)
            memcpy(cur, pts + 3 * (size_t)(rng_next_u64(&s) % n), sizeof cur);
        memcpy(q + 3 * (size_t)i, cur, sizeof cur);
    }
}

enum { KQ_NQ = 24 };

/* Runs the walk for every k and cap on one tree and one instruction set:
 * a state carried along the walk, a fresh state per query, and helper_knn
 * must all give the brute-force answer. */
static void check_walk(const kd_tree *t, uint32_t n, const float *q, kd_pair **all, kd_simd simd)
{
    const uint32_t ks[] = {1, 2, 5, 10, 16, 17, 31, 32, 33, 64, 100, 128, 129, 200, 300};
    const float caps[] = {INFINITY, 0.05f, 1e-4f, 0.0f, 30.0f};
    uint32_t *idx = malloc(sizeof(uint32_t) * 301);
    float *d2 = malloc(sizeof(float) * 301);
    kd_query carried;
    CHECK(kd_query_init(&carried, 16) == PM_OK);
    CHECK(kd_query_simd(&carried, simd) == simd);
    int bad = 0;
    for (size_t ci = 0; ci < sizeof caps / sizeof caps[0]; ci++)
        for (size_t ki = 0; ki < sizeof ks / sizeof ks[0]; ki++)
            for (uint32_t i = 0; i < KQ_NQ; i++) {
                const float *qi = q + 3 * (size_t)i;
                uint32_t k = ks[ki];
                float cap = caps[ci], r2 = -1.0f;
                uint32_t got = kd_query_knn(t, &carried, qi, k, cap, idx, d2, &r2);
                bad += !check_answer(all[i], n, k, cap, got, idx, d2, r2, "carried state");
                kd_query fresh;
                CHECK(kd_query_init(&fresh, k) == PM_OK);
                kd_query_simd(&fresh, simd);
                got = kd_query_knn(t, &fresh, qi, k, cap, idx, d2, &r2);
                bad += !check_answer(all[i], n, k, cap, got, idx, d2, r2, "fresh state");
                kd_query_free(&fresh);
                got = helper_knn(t, qi, k, cap, idx, d2, &r2);
                bad += !check_answer(all[i], n, k, cap, got, idx, d2, r2, "helper_knn");
            }
    CHECK_MSG(bad == 0, "%d answers differ from brute force", bad);
    kd_query_free(&carried);
    free(idx);
    free(d2);
}

/* Every k, cap, leaf size and point set against brute force, with the
 * leaf scans of `simd`. */
static void query_matches_brute_force(kd_simd simd)
{
    const uint32_t sizes[] = {1, 7, 13, 600, 4099};
    const uint32_t leaves[] = {1, 3, KD_DEFAULT_LEAF, 1000};
    for (int kind = 0; kind < 4; kind++)
        for (size_t si = 0; si < sizeof sizes / sizeof sizes[0]; si++) {
            uint32_t n = kind == 3 ? 576 : sizes[si];
            if (kind == 3 && si != 3)
                continue;
            float *pts = point_set(kind, n, 77 + n);
            float q[3 * KQ_NQ];
            query_walk(pts, n, kind, KQ_NQ, 5 + n, q);
            for (size_t li = 0; li < sizeof leaves / sizeof leaves[0]; li++) {
                if (n < 600 && li != 2)
                    continue;
                uint32_t *perm = malloc(sizeof(uint32_t) * n);
                kd_tree t;
                CHECK(kd_build(&t, pts, n, leaves[li], perm, 1) == PM_OK);
                kd_pair *all[KQ_NQ];
                for (uint32_t i = 0; i < KQ_NQ; i++)
                    all[i] = brute_sorted(pts, perm, n, q + 3 * (size_t)i);
                check_walk(&t, n, q, all, simd);
                for (uint32_t i = 0; i < KQ_NQ; i++)
                    free(all[i]);
                kd_free(&t);
                free(perm);
            }
            free(pts);
        }
}

void test_kdtree_query_matches_brute_force(void)
{
    kd_query probe;
    CHECK(kd_query_init(&probe, 1) == PM_OK);
    CHECK(kd_query_simd(&probe, KD_SIMD_BASE) == KD_SIMD_BASE);
    kd_query_free(&probe);
    query_matches_brute_force(KD_SIMD_BASE);
}

/* Whatever starting radius a state holds (none, zero, tiny, too small, too
 * large, infinite, not a number, from another k), the answer is the same;
 * too small takes more passes, too large fills the buffer. */
static void query_hints(kd_simd simd)
{
    const uint32_t n = 20000;
    float *pts = point_set(1, n, 3);
    uint32_t *perm = malloc(sizeof(uint32_t) * n);
    kd_tree t;
    CHECK(kd_build(&t, pts, n, KD_DEFAULT_LEAF, perm, 1) == PM_OK);
    const float hints[] = {0.0f, 1e-30f, 1e-7f, 1e-4f, 0.01f, 1.0f, 1e30f, INFINITY, NAN};
    const uint32_t hint_ks[] = {1, 10, 300};
    const uint32_t ks[] = {1, 10, 100};
    const float caps[] = {INFINITY, 0.05f};
    uint32_t idx[100];
    float d2[100];
    int bad = 0;
    kd_query s;
    CHECK(kd_query_init(&s, 100) == PM_OK);
    CHECK(kd_query_simd(&s, simd) == simd);
    float q[3] = {0.3f, -1.0f, 0.2f}; /* on the floor wall */
    kd_pair *all = brute_sorted(pts, perm, n, q);
    for (size_t hi = 0; hi < sizeof hints / sizeof hints[0]; hi++)
        for (size_t hk = 0; hk < sizeof hint_ks / sizeof hint_ks[0]; hk++)
            for (size_t ki = 0; ki < sizeof ks / sizeof ks[0]; ki++)
                for (size_t ci = 0; ci < sizeof caps / sizeof caps[0]; ci++) {
                    s.hint_k = hint_ks[hk];
                    s.hint_r2 = hints[hi];
                    float r2;
                    uint32_t got = kd_query_knn(&t, &s, q, ks[ki], caps[ci], idx, d2, &r2);
                    bad += !check_answer(all, n, ks[ki], caps[ci], got, idx, d2, r2, "forced hint");
                }
    free(all);
    CHECK_MSG(bad == 0, "%d answers differ from brute force", bad);
    CHECK(s.passes > s.queries); /* the too-small hints were widened */
    kd_query_free(&s);
    kd_free(&t);
    free(perm);
    free(pts);
}

void test_kdtree_query_hints(void)
{
    query_hints(KD_SIMD_BASE);
}

/* The result of a query does not depend on the queries before it: the same
 * query after different histories (and on a grid, where many points tie at
 * the k-th distance) gives the same set, and that set is brute force's. */
static void query_history_independent(kd_simd simd)
{
    const uint32_t n = 576;
    float *pts = point_set(3, n, 1);
    uint32_t *perm = malloc(sizeof(uint32_t) * n);
    kd_tree t;
    CHECK(kd_build(&t, pts, n, KD_DEFAULT_LEAF, perm, 1) == PM_OK);
    float target[3] = {11.0f, 12.0f, 0.0f}, other[3] = {2.5f, 20.0f, 0.0f}, far[3] = {500.0f, 0.0f, 0.0f};
    kd_pair *all = brute_sorted(pts, perm, n, target);
    const uint32_t ks[] = {1, 4, 5, 9, 13, 21, 25, 50, 100};
    int bad = 0;
    for (size_t ki = 0; ki < sizeof ks / sizeof ks[0]; ki++) {
        uint32_t k = ks[ki];
        uint32_t ref_idx[100], idx[100];
        float ref_d2[100], d2[100], ref_r2, r2;
        uint32_t ref = helper_knn(&t, target, k, INFINITY, ref_idx, ref_d2, &ref_r2);
        bad += !check_answer(all, n, k, INFINITY, ref, ref_idx, ref_d2, ref_r2, "grid");
        const float *before[] = {other, far, target, pts};
        for (size_t b = 0; b < 4; b++)
            for (uint32_t pk = 1; pk <= 64; pk *= 4) {
                kd_query s;
                CHECK(kd_query_init(&s, 1) == PM_OK);
                CHECK(kd_query_simd(&s, simd) == simd);
                float pr2;
                kd_query_knn(&t, &s, before[b], pk, INFINITY, idx, d2, &pr2);
                uint32_t got = kd_query_knn(&t, &s, target, k, INFINITY, idx, d2, &r2);
                bad += !check_answer(all, n, k, INFINITY, got, idx, d2, r2, "after another query");
                kd_query_free(&s);
            }
    }
    CHECK_MSG(bad == 0, "%d answers differ", bad);
    free(all);
    kd_free(&t);
    free(perm);
    free(pts);
}

void test_kdtree_query_history_independent(void)
{
    query_history_independent(KD_SIMD_BASE);
}

/* The three query tests above with the AVX2 leaf scans, selection and
 * output (kdtree_simd.c); skipped on a CPU without AVX2. */
void test_kdtree_query_avx2(void)
{
    kd_query probe;
    CHECK(kd_query_init(&probe, 1) == PM_OK);
    int have_avx2 = kd_query_simd(&probe, KD_SIMD_AVX2) == KD_SIMD_AVX2;
    kd_query_free(&probe);
    if (!have_avx2) {
        CHECK_SKIP("this CPU has no AVX2");
        return;
    }
    query_matches_brute_force(KD_SIMD_AVX2);
    query_hints(KD_SIMD_AVX2);
    query_history_independent(KD_SIMD_AVX2);
}

/* State life cycle: k_max 0, growing past k_max, a state without a buffer
 * (as after a failed init), queries that find nothing. */
void test_kdtree_query_state(void)
{
    const uint32_t n = 3000;
    float *pts = point_set(0, n, 9);
    uint32_t *perm = malloc(sizeof(uint32_t) * n);
    kd_tree t, empty;
    CHECK(kd_build(&t, pts, n, KD_DEFAULT_LEAF, perm, 1) == PM_OK);
    CHECK(kd_build(&empty, NULL, 0, KD_DEFAULT_LEAF, NULL, 1) == PM_OK);
    float q[3] = {0.1f, 0.2f, -0.3f}, nanq[3] = {NAN, 0.0f, 0.0f};
    kd_pair *all = brute_sorted(pts, perm, n, q);
    uint32_t idx[400];
    float d2[400], r2;
    kd_query s;
    CHECK(kd_query_init(&s, 0) == PM_OK);
    int bad = 0;
    for (uint32_t k = 1; k <= 400; k = k * 3 + 1) { /* grows the buffer each time */
        uint32_t got = kd_query_knn(&t, &s, q, k, INFINITY, idx, d2, &r2);
        bad += !check_answer(all, n, k, INFINITY, got, idx, d2, r2, "growing");
    }
    r2 = -1.0f;
    CHECK(kd_query_knn(&t, &s, q, 0, INFINITY, idx, d2, &r2) == 0 && r2 == 0.0f);
    CHECK(kd_query_knn(&empty, &s, q, 5, INFINITY, idx, d2, &r2) == 0 && r2 == 0.0f);
    CHECK(kd_query_knn(&t, &s, nanq, 5, INFINITY, idx, d2, &r2) == 0 && r2 == 0.0f);
    CHECK(kd_query_knn(&t, &s, q, 5, -1.0f, idx, d2, &r2) == 0 && r2 == 0.0f);
    CHECK(kd_query_knn(&t, &s, q, 5, NAN, idx, d2, &r2) == 0 && r2 == 0.0f);
    CHECK(helper_knn(&t, nanq, 5, INFINITY, idx, d2, &r2) == 0 && r2 == 0.0f);
    kd_query_free(&s);
    CHECK(s.buf == NULL && s.cap == 0);
    /* a state with no buffer (as kd_query_init leaves it on failure) grows one and answers */
    memset(&s, 0, sizeof s);
    s.simd = KD_SIMD_BASE;
    for (uint32_t k = 1; k <= 400; k = k * 3 + 1) {
        uint32_t got = kd_query_knn(&t, &s, q, k, 0.3f, idx, d2, &r2);
        bad += !check_answer(all, n, k, 0.3f, got, idx, d2, r2, "no buffer");
        free(s.buf); /* drop it again: each k starts from an empty state */
        s.buf = NULL;
        s.cap = 0;
    }
    CHECK_MSG(bad == 0, "%d answers differ", bad);
    free(all);
    kd_free(&t);
    kd_free(&empty);
    free(perm);
    free(pts);
}

/* kd_query_knn on the eye pass's own query stream against brute force. The eye pass asks, pixel after pixel, for the k
 * nearest photons of each of a pixel's four subpixel hits, which lie a
 * fraction of a photon spacing apart; the query state is carried from each
 * to the next, so its starting radius is always a neighbour's. Every
 * answer must be exactly brute force's k smallest (squared distance,
 * leaf-order index) pairs and its radius the k-th; the checker itself is
 * shown to reject a wrong set and a wrong radius (negative controls). */
typedef struct {
    float d;
    uint32_t i;
} st_pair;

static int st_cmp(const void *a, const void *b)
{
    const st_pair *x = a, *y = b;
    if (x->d != y->d)
        return (x->d > y->d) - (x->d < y->d);
    return (x->i > y->i) - (x->i < y->i);
}

/* Every point's (squared distance, leaf index) pair for q, sorted, with the
 * tree's arithmetic ((dx dx + dy dy) + dz dz in float). */
static st_pair *st_brute(const kd_tree *t, const float q[3])
{
    st_pair *all = malloc(sizeof(st_pair) * (t->n + 1));
    for (uint32_t i = 0; i < t->n; i++) {
        float p[3];
        kd_point(t, i, p);
        float dx = p[0] - q[0], dy = p[1] - q[1], dz = p[2] - q[2];
        all[i].d = dx * dx + dy * dy + dz * dz;
        all[i].i = i;
    }
    qsort(all, t->n, sizeof(st_pair), st_cmp);
    return all;
}

/* 1 when (got, idx, d2, r2) is exactly the k smallest pairs of `all`
 * within cap, with r2 the largest of them (0 when none). */
static int st_same(const st_pair *all, uint32_t n, uint32_t k, float cap, uint32_t got, const uint32_t *idx,
                   const float *d2, float r2)
{
    uint32_t want = 0;
    while (want < n && want < k && all[want].d <= cap)
        want++;
    if (got != want || r2 != (want ? all[want - 1].d : 0.0f))
        return 0;
    st_pair *mine = malloc(sizeof(st_pair) * (got + 1));
    for (uint32_t j = 0; j < got; j++) {
        mine[j].d = d2[j];
        mine[j].i = idx[j];
    }
    qsort(mine, got, sizeof(st_pair), st_cmp);
    int ok = 1;
    for (uint32_t j = 0; j < got && ok; j++)
        ok = mine[j].d == all[j].d && mine[j].i == all[j].i;
    free(mine);
    return ok;
}

/* Photon-like points: on the five walls of a unit box, n of them. */
static float *st_walls(uint32_t n, uint64_t seed)
{
    float *p = malloc(sizeof(float) * 3 * (n + 1));
    rng_stream s = rng_make(seed, 5);
    for (uint32_t i = 0; i < n; i++) {
        float a = (float)rng_next_double(&s), b = (float)rng_next_double(&s);
        int wall = (int)(rng_next_double(&s) * 5);
        float *o = p + 3 * (size_t)i;
        o[0] = wall == 0 ? 0.0f : (wall == 1 ? 1.0f : a);
        o[1] = wall == 2 ? 0.0f : (wall == 3 ? 1.0f : (wall < 2 ? a : b));
        o[2] = wall == 4 ? 0.0f : b;
    }
    return p;
}

/* The eye pass's stream on the back wall (z = 0): 8 rows of a 16-pixel-wide
 * tile, pixel by pixel, each pixel's four subpixel points a quarter pixel from its
 * centre; `pix` is the pixel's size (a fraction of the photon spacing). */
static uint32_t st_stream(float pix, float x0, float y0, float *q)
{
    uint32_t m = 0;
    for (uint32_t y = 0; y < 8; y++)
        for (uint32_t x = 0; x < 16; x++)
            for (uint32_t sub = 0; sub < 4; sub++) {
                float *o = q + 3 * (size_t)m++;
                o[0] = x0 + ((float)x + 0.25f + 0.5f * (float)(sub % 2)) * pix;
                o[1] = y0 + ((float)y + 0.25f + 0.5f * (float)(sub / 2)) * pix;
                o[2] = 0.0f;
            }
    return m;
}

static void stream_matches_brute_force(kd_simd simd)
{
    const uint32_t n = 10000, nq = 8 * 16 * 4;
    const uint32_t ks[] = {1, 2, 10, 50, 100};
    const float caps[] = {INFINITY, 4e-4f};
    float *pts = st_walls(n, 11), *q = malloc(sizeof(float) * 3 * nq);
    kd_tree t;
    CHECK(kd_build(&t, pts, n, KD_DEFAULT_LEAF, NULL, 1) == PM_OK);
    /* a photon spacing on a wall is about sqrt(5 / n) = 0.022: pixels of
     * a tenth and of twice that */
    const float pixs[] = {0.0022f, 0.044f};
    uint32_t idx[100];
    float d2[100];
    int bad = 0, checked = 0;
    for (size_t pi = 0; pi < sizeof pixs / sizeof pixs[0]; pi++) {
        st_stream(pixs[pi], 0.2f, 0.3f, q);
        st_pair **all = malloc(sizeof(st_pair *) * nq);
        for (uint32_t i = 0; i < nq; i++)
            all[i] = st_brute(&t, q + 3 * (size_t)i);
        for (size_t ki = 0; ki < sizeof ks / sizeof ks[0]; ki++)
            for (size_t ci = 0; ci < sizeof caps / sizeof caps[0]; ci++) {
                kd_query s;
                CHECK(kd_query_init(&s, ks[ki]) == PM_OK);
                CHECK(kd_query_simd(&s, simd) == simd);
                for (uint32_t i = 0; i < nq; i++) {
                    float r2 = -1.0f;
                    uint32_t got = kd_query_knn(&t, &s, q + 3 * (size_t)i, ks[ki], caps[ci], idx, d2, &r2);
                    int ok = st_same(all[i], n, ks[ki], caps[ci], got, idx, d2, r2);
                    if (!ok && bad < 5)
                        fprintf(stderr, "  stream: pix=%g k=%u cap=%g query %u differs from brute force\n",
                                (double)pixs[pi], ks[ki], (double)caps[ci], i);
                    bad += !ok;
                    checked++;
                    /* negative controls, on the first query of each run: the checker rejects the
                     * answer with its farthest neighbour swapped for the next one out (when
                     * that is farther), and with its radius nudged up */
                    if (i == 0 && ok && got == ks[ki] && got < n && all[i][got].d > all[i][got - 1].d) {
                        uint32_t far = 0;
                        for (uint32_t j = 1; j < got; j++)
                            far = d2[j] > d2[far] ? j : far;
                        uint32_t keep_i = idx[far];
                        float keep_d = d2[far];
                        idx[far] = all[i][got].i;
                        d2[far] = all[i][got].d;
                        CHECK(!st_same(all[i], n, ks[ki], caps[ci], got, idx, d2, all[i][got].d));
                        idx[far] = keep_i;
                        d2[far] = keep_d;
                        CHECK(st_same(all[i], n, ks[ki], caps[ci], got, idx, d2, r2));
                        CHECK(!st_same(all[i], n, ks[ki], caps[ci], got, idx, d2, nextafterf(r2, INFINITY)));
                    }
                }
                CHECK(s.queries == nq && s.passes >= s.queries);
                kd_query_free(&s);
            }
        for (uint32_t i = 0; i < nq; i++)
            free(all[i]);
        free(all);
    }
    CHECK_MSG(bad == 0, "%d of %d stream answers differ from brute force", bad, checked);
    kd_free(&t);
    free(pts);
    free(q);
}

void test_kdtree_stream_base(void)
{
    stream_matches_brute_force(KD_SIMD_BASE);
}

void test_kdtree_stream_avx2(void)
{
    kd_query s;
    if (kd_query_init(&s, 1) != PM_OK || kd_query_simd(&s, KD_SIMD_AVX2) != KD_SIMD_AVX2) {
        kd_query_free(&s);
        CHECK_SKIP("the CPU has no AVX2");
        return;
    }
    kd_query_free(&s);
    stream_matches_brute_force(KD_SIMD_AVX2);
}

/* Packets (kd_query_knn_packet): every neighbour set of every query of a
 * packet against brute force, on both leaf scans, with the state carried
 * from packet to packet as the eye pass does; packets of 1 to 4 queries,
 * close together (subpixel samples), equal, or one far from the rest, a NaN
 * among them, caps that cut answers short. */
static int packet_round(const kd_tree *t, kd_query *s, const float *pts, const uint32_t *perm, uint32_t n,
                        rng_stream *rs, uint32_t k, float cap, int kind)
{
    float q[KD_PACKET][3];
    uint32_t idxs[KD_PACKET][128], found[KD_PACKET];
    float d2s[KD_PACKET][128], r2[KD_PACKET];
    uint32_t *idx[KD_PACKET] = {idxs[0], idxs[1], idxs[2], idxs[3]};
    float *d2[KD_PACKET] = {d2s[0], d2s[1], d2s[2], d2s[3]};
    uint32_t m = 1 + (uint32_t)(rng_next_double(rs) * KD_PACKET);
    float c[3], spread = (float)(rng_next_double(rs) < 0.5 ? 0.01 : 0.2);
    for (int a = 0; a < 3; a++)
        c[a] = (float)(rng_next_double(rs) * 2.4 - 1.2);
    if (kind == 3)
        c[0] = c[0] * 10.0f + 12.0f, c[1] = c[1] * 10.0f + 12.0f, spread *= 10.0f;
    int shape = (int)(rng_next_double(rs) * 4);
    for (uint32_t j = 0; j < m; j++)
        for (int a = 0; a < 3; a++)
            q[j][a] = shape == 1 ? c[a] : c[a] + spread * (float)(rng_next_double(rs) - 0.5);
    if (shape == 2 && m > 1)
        q[m - 1][0] += 2.0f; /* one query far from the others */
    int nan_at = shape == 3 && m > 1 ? (int)(m - 1) : -1;
    if (nan_at >= 0)
        q[nan_at][1] = NAN;
    kd_query_knn_packet(t, s, (const float(*)[3])q, m, k, cap, idx, d2, found, r2);
    int bad = 0;
    for (uint32_t j = 0; j < m; j++) {
        if ((int)j == nan_at) {
            bad += found[j] != 0 || r2[j] != 0.0f;
            continue;
        }
        kd_pair *all = brute_sorted(pts, perm, n, q[j]);
        bad += !check_answer(all, n, k, cap, found[j], idx[j], d2[j], r2[j], "packet");
        free(all);
    }
    return bad;
}

void test_kdtree_packet_matches_brute_force(void)
{
    const uint32_t n = 3000;
    const uint32_t ks[] = {1, 2, 3, 10, 50, 100};
    const float caps[] = {INFINITY, 0.05f};
    int bad = 0;
    for (int kind = 0; kind < 4; kind++) {
        float *pts = point_set(kind, n, 41);
        uint32_t *perm = malloc(sizeof(uint32_t) * n);
        kd_tree t;
        CHECK(kd_build(&t, pts, n, KD_DEFAULT_LEAF, perm, 1) == PM_OK);
        for (kd_simd want = KD_SIMD_BASE; want <= KD_SIMD_AVX2; want++) {
            kd_query s;
            CHECK(kd_query_init(&s, 8) == PM_OK); /* grows for larger k */
            kd_query_simd(&s, want);
            rng_stream rs = rng_make(123, (uint64_t)kind);
            for (size_t ki = 0; ki < sizeof ks / sizeof ks[0]; ki++)
                for (size_t ci = 0; ci < sizeof caps / sizeof caps[0]; ci++)
                    for (int round = 0; round < 25; round++)
                        bad += packet_round(&t, &s, pts, perm, n, &rs, ks[ki], caps[ci], kind);
            kd_query_free(&s);
        }
        kd_free(&t);
        free(perm);
        free(pts);
    }
    /* a tree of one leaf and an empty tree */
    float few[3 * 5] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1, 1};
    uint32_t perm5[5];
    kd_tree t5, empty;
    CHECK(kd_build(&t5, few, 5, KD_DEFAULT_LEAF, perm5, 1) == PM_OK);
    CHECK(kd_build(&empty, NULL, 0, KD_DEFAULT_LEAF, NULL, 1) == PM_OK);
    kd_query s;
    CHECK(kd_query_init(&s, 4) == PM_OK);
    rng_stream rs = rng_make(5, 5);
    for (int round = 0; round < 20; round++)
        bad += packet_round(&t5, &s, few, perm5, 5, &rs, 1 + (uint32_t)round % 7, INFINITY, 0);
    float q[2][3] = {{0, 0, 0}, {1, 1, 1}};
    uint32_t i0[4], i1[4], found[2] = {9, 9};
    float e0[4], e1[4], r2[2] = {-1, -1};
    uint32_t *idx[2] = {i0, i1};
    float *d2[2] = {e0, e1};
    kd_query_knn_packet(&empty, &s, (const float(*)[3])q, 2, 3, INFINITY, idx, d2, found, r2);
    CHECK(found[0] == 0 && found[1] == 0 && r2[0] == 0.0f && r2[1] == 0.0f);
    kd_query_free(&s);
    kd_free(&t5);
    kd_free(&empty);
    CHECK_MSG(bad == 0, "%d packet answers differ from brute force", bad);
}

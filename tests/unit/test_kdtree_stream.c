/* test_kdtree_stream: kd_query_knn on the eye pass's own query stream
 * against brute force. The eye pass asks, pixel after pixel, for the k
 * nearest photons of each of a pixel's four subpixel hits, which lie a
 * fraction of a photon spacing apart; the query state is carried from each
 * to the next, so its starting radius is always a neighbour's. Every
 * answer must be exactly brute force's k smallest (squared distance,
 * leaf-order index) pairs and its radius the k-th; the checker itself is
 * shown to reject a wrong set and a wrong radius (negative controls). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "kdtree.h"
#include "rng.h"
#include "tests.h"

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
    if (kd_query_init(&s, 1) != 0 || kd_query_simd(&s, KD_SIMD_AVX2) != KD_SIMD_AVX2) {
        kd_query_free(&s);
        CHECK_SKIP("the CPU has no AVX2");
        return;
    }
    kd_query_free(&s);
    stream_matches_brute_force(KD_SIMD_AVX2);
}

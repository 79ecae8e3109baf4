/* test_kdtree: the photon map's kd-tree against brute force. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "kdtree.h"
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

/* Checks kd_knn against brute force for one query; returns failures. */
static void check_query(const kd_tree *t, const float *pts, const uint32_t *perm, uint32_t n, const float q[3],
                        uint32_t k, float max_d2)
{
    uint32_t *idx = malloc(sizeof(uint32_t) * (k + 1));
    float *d2 = malloc(sizeof(float) * (k + 1));
    float *all = malloc(sizeof(float) * (n + 1));
    float r2;
    uint32_t got = kd_knn(t, q, k, max_d2, idx, d2, &r2);
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
            CHECK(kd_build(&t, pts, n, KD_DEFAULT_LEAF, perm) == 0);
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
    CHECK(kd_build(&t, NULL, 0, KD_DEFAULT_LEAF, NULL) == 0);
    CHECK(kd_knn(&t, q, 5, INFINITY, idx, d2, &r2) == 0);
    CHECK(r2 == 0.0f);
    kd_free(&t);
    /* N = 1, k > N */
    float one[3] = {1, 2, 3};
    uint32_t perm1[1];
    CHECK(kd_build(&t, one, 1, KD_DEFAULT_LEAF, perm1) == 0);
    CHECK(kd_knn(&t, q, 5, INFINITY, idx, d2, &r2) == 1);
    CHECK(d2[0] == 14.0f && r2 == 14.0f && perm1[idx[0]] == 0);
    CHECK(kd_knn(&t, q, 5, 13.9f, idx, d2, &r2) == 0); /* radius cap excludes it */
    kd_free(&t);
    /* all points identical (r = 0 for the query on them), k > N */
    enum { NDUP = 300 };
    float *dup = malloc(sizeof(float) * 3 * NDUP);
    for (int i = 0; i < 3 * NDUP; i++)
        dup[i] = 0.5f;
    uint32_t *perm = malloc(sizeof(uint32_t) * NDUP);
    CHECK(kd_build(&t, dup, NDUP, KD_DEFAULT_LEAF, perm) == 0);
    float on[3] = {0.5f, 0.5f, 0.5f};
    check_query(&t, dup, perm, NDUP, on, 100, INFINITY);
    check_query(&t, dup, perm, NDUP, on, NDUP + 10, INFINITY);
    check_query(&t, dup, perm, NDUP, q, 7, INFINITY);
    CHECK(kd_knn(&t, on, 7, INFINITY, idx, d2, &r2) == 7 && r2 == 0.0f);
    kd_free(&t);
    free(dup);
    free(perm);
    /* leaf size 1 and huge leaves give the same answers */
    float *pts = random_points(500, 3, 0);
    uint32_t *p2 = malloc(sizeof(uint32_t) * 500);
    const uint32_t leaves[] = {1, 3, 1000};
    for (size_t li = 0; li < 3; li++) {
        CHECK(kd_build(&t, pts, 500, leaves[li], p2) == 0);
        check_query(&t, pts, p2, 500, q, 30, INFINITY);
        check_query(&t, pts, p2, 500, q, 3, 0.01f);
        kd_free(&t);
    }
    free(pts);
    free(p2);
}

static int pred_even_orig(uint32_t i, const void *ctx)
{
    const uint32_t *perm = ctx;
    return perm[i] % 2 == 0;
}

void test_kdtree_nearest_if(void)
{
    uint32_t n = 2000;
    float *pts = random_points(n, 11, 0);
    uint32_t *perm = malloc(sizeof(uint32_t) * n);
    kd_tree t;
    CHECK(kd_build(&t, pts, n, KD_DEFAULT_LEAF, perm) == 0);
    rng_stream s = rng_make(5, 5);
    for (int qi = 0; qi < 200; qi++) {
        float q[3];
        for (int a = 0; a < 3; a++)
            q[a] = (float)(rng_next_double(&s) * 2.4 - 1.2);
        float cap = qi % 2 ? INFINITY : 0.01f;
        float best = INFINITY;
        uint32_t best_i = KD_NONE;
        for (uint32_t i = 0; i < n; i += 2) {
            float d = dist2(pts + 3 * i, q);
            if (d <= cap && d < best) {
                best = d;
                best_i = i;
            }
        }
        float d2;
        uint32_t got = kd_nearest_if(&t, q, cap, pred_even_orig, perm, &d2);
        CHECK(got == KD_NONE ? best_i == KD_NONE : (perm[got] % 2 == 0 && d2 == best));
        /* without predicate: the plain nearest */
        uint32_t idx;
        float dd, r2;
        uint32_t k = kd_knn(&t, q, 1, cap, &idx, &dd, &r2);
        uint32_t g2 = kd_nearest_if(&t, q, cap, NULL, NULL, &d2);
        CHECK(k == (g2 != KD_NONE) && (k == 0 || d2 == dd));
    }
    kd_free(&t);
    free(perm);
    free(pts);
}

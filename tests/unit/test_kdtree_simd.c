/* test_kdtree_simd: the instruction-set specific leaf scans. The base set
 * is always there; where the CPU has AVX2, its scans give the base scans'
 * answers bit for bit (the same (squared distance, index) pairs, which
 * come in no particular order, and the same radius) for small and large k,
 * with and without a radius cap. */
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
} simd_pair;

static int simd_cmp(const void *a, const void *b)
{
    const simd_pair *x = a, *y = b;
    if (x->d != y->d)
        return (x->d > y->d) - (x->d < y->d);
    return (x->i > y->i) - (x->i < y->i);
}

/* 1 when the n answers (idx, d2) and (ib, db) are the same set of pairs. */
static int same_answers(uint32_t n, const uint32_t *ia, const float *da, const uint32_t *ib, const float *db)
{
    simd_pair a[300], b[300];
    for (uint32_t j = 0; j < n; j++) {
        a[j] = (simd_pair){da[j], ia[j]};
        b[j] = (simd_pair){db[j], ib[j]};
    }
    qsort(a, n, sizeof a[0], simd_cmp);
    qsort(b, n, sizeof b[0], simd_cmp);
    for (uint32_t j = 0; j < n; j++)
        if (a[j].d != b[j].d || a[j].i != b[j].i)
            return 0;
    return 1;
}

void test_kdtree_simd_avx2_matches_base(void)
{
    kd_query base, fast;
    CHECK(kd_query_init(&base, 8) == PM_OK && kd_query_init(&fast, 8) == PM_OK);
    CHECK(kd_query_simd(&base, KD_SIMD_BASE) == KD_SIMD_BASE);
    if (kd_query_simd(&fast, KD_SIMD_AVX2) != KD_SIMD_AVX2) {
        kd_query_free(&base);
        kd_query_free(&fast);
        CHECK_SKIP("this CPU has no AVX2");
        return;
    }
    const uint32_t n = 5000;
    float *pts = malloc(sizeof(float) * 3 * n);
    rng_stream rs = rng_make(11, 0);
    for (uint32_t i = 0; i < 3 * n; i++) /* a third on a coarse grid: ties */
        pts[i] = i % 3 == 0 ? (float)(rng_next_u64(&rs) % 16) / 16.0f : (float)rng_next_double(&rs);
    kd_tree t;
    CHECK(kd_build(&t, pts, n, KD_DEFAULT_LEAF, NULL, 1) == PM_OK);
    const uint32_t ks[] = {1, 5, 50, 300};
    const float caps[] = {INFINITY, 0.01f};
    uint32_t ia[300], ib[300];
    float da[300], db[300];
    int differ = 0;
    for (size_t c = 0; c < 2; c++)
        for (size_t ki = 0; ki < sizeof ks / sizeof ks[0]; ki++)
            for (int q = 0; q < 200; q++) {
                float x[3] = {(float)rng_next_double(&rs), (float)rng_next_double(&rs), (float)rng_next_double(&rs)};
                float ra, rb;
                uint32_t na = kd_query_knn(&t, &base, x, ks[ki], caps[c], ia, da, &ra);
                uint32_t nb = kd_query_knn(&t, &fast, x, ks[ki], caps[c], ib, db, &rb);
                differ += na != nb || ra != rb || !same_answers(na, ia, da, ib, db);
            }
    CHECK_MSG(differ == 0, "%d queries answered differently by AVX2 and base", differ);
    /* negative control: the comparison sees one index changed */
    uint32_t one = ia[0] + 1;
    CHECK(!same_answers(1, ia, da, &one, da));
    kd_free(&t);
    free(pts);
    kd_query_free(&base);
    kd_query_free(&fast);
}

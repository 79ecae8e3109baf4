/* test_kdtree_select: the selection of the k nearest candidates
 * (kdtree_select.c) with each instruction set's kd_ops (kdtree_simd.c),
 * against a full sort. */
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "kdtree_impl.h"
#include "rng.h"
#include "tests.h"

static int cmp_key(const void *a, const void *b)
{
    uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
    return (x > y) - (x < y);
}

/* m distinct keys: squared distances uniform in [0, 1) (kind 0), all equal
 * (1), or a few distinct values (2), above their indices. Returns the
 * largest distance in *hi. */
static void make_keys(uint64_t *a, uint32_t m, int kind, uint64_t seed, float *hi)
{
    rng_stream s = rng_make(seed, 0);
    *hi = 0.0f;
    for (uint32_t i = 0; i < m; i++) {
        double u = rng_next_double(&s);
        float d = kind == 0 ? (float)u : kind == 1 ? 0.25f : (float)(uint32_t)(u * 4.0) * 0.125f;
        *hi = d > *hi ? d : *hi;
        a[i] = pack_key(d, (uint32_t)(m - 1 - i)); /* distinct: one index each, descending */
    }
}

/* kd_select_k and kd_select_keys with `ops` over sizes around the rank
 * limit and the buffer's, every kind of distances; returns the failures. */
static int select_all(const kd_ops *ops)
{
    const uint32_t sizes[] = {1, 2, 3, 17, KD_RANK_MAX, KD_RANK_MAX + 1, 100, 257, 3000};
    int bad = 0;
    for (size_t si = 0; si < sizeof sizes / sizeof sizes[0]; si++)
        for (int kind = 0; kind < 3; kind++) {
            uint32_t m = sizes[si];
            uint64_t *a = malloc(sizeof(uint64_t) * (m + 8)), *b = malloc(sizeof(uint64_t) * (m + 8));
            uint64_t *c = malloc(sizeof(uint64_t) * (m + 8)), *sorted = malloc(sizeof(uint64_t) * m);
            float hi;
            make_keys(sorted, m, kind, 11 + m, &hi);
            qsort(sorted, m, sizeof(uint64_t), cmp_key);
            const uint32_t ks[] = {1, 2, m / 3 + 1, m / 2 + 1, m - 1 > 0 ? m - 1 : 1, m};
            for (size_t ki = 0; ki < sizeof ks / sizeof ks[0]; ki++) {
                uint32_t k = ks[ki] < m ? ks[ki] : m;
                for (int which = 0; which < 2; which++) {
                    make_keys(a, m, kind, 11 + m, &hi);
                    if (which == 0) {
                        kd_select_k(a, b, c, m, k, hi, ops);
                    } else {
                        kd_select_keys(a, m, k);
                        bad += a[k - 1] != sorted[k - 1]; /* the k-th in its place */
                    }
                    qsort(a, k, sizeof(uint64_t), cmp_key);
                    if (memcmp(a, sorted, sizeof(uint64_t) * k) != 0) {
                        fprintf(stderr, "  m=%u kind=%d k=%u: %s kept other keys\n", m, kind, k,
                                which == 0 ? "kd_select_k" : "kd_select_keys");
                        bad++;
                    }
                }
            }
            free(a);
            free(b);
            free(c);
            free(sorted);
        }
    return bad;
}

void test_kdtree_select_base(void)
{
    int bad = select_all(&kd_ops_base);
    CHECK_MSG(bad == 0, "%d selections differ from the sort", bad);
}

/* The same with the AVX2 kd_ops; skipped on a CPU without AVX2. */
void test_kdtree_select_avx2(void)
{
#if KD_HAVE_AVX2
    if (kd_simd_best() == KD_SIMD_AVX2) {
        int bad = select_all(&kd_ops_avx2);
        CHECK_MSG(bad == 0, "%d selections differ from the sort", bad);
        return;
    }
#endif
    CHECK_SKIP("this CPU has no AVX2");
}

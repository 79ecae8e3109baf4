/* kdtree_simd: everything of the k-nearest search that differs between
 * instruction sets, including every AVX2 function of the tree
 * (renderer/README.md). */
#include "kdtree_impl.h"

#include <assert.h>
#include <math.h>
#include <string.h>
#if KD_HAVE_AVX2
#include <immintrin.h>
#endif

/* ---- base leaf scans ----
 * The squared distances of the KD_CHUNK points from c (chunk_mask, in
 * kdtree_impl.h) and the keys of those within r2 appended to buf[n..] one
 * by one (those from `end` on are not points of the range); returns the
 * new count. */
static inline uint32_t chunk_base(const float *x, const float *y, const float *z, uint32_t c, uint32_t end,
                                  kd_qbase *qv, uint64_t *buf, uint32_t n, uint32_t k)
{
    (void)k;
    uint32_t bits[KD_CHUNK];
    uint32_t m = chunk_mask(x, y, z, c, qv, bits);
    if (end - c < KD_CHUNK)
        m &= (1u << (end - c)) - 1u;
    while (m) {
        uint32_t j = (uint32_t)__builtin_ctz(m);
        m &= m - 1u;
        buf[n++] = (uint64_t)bits[j] << 32 | (c + j);
    }
    return n;
}

/* The small-k leaf scan: the keys within r2 go into the ascending
 * buf[0..n) kept to at most k, and once k are held the radius drops to
 * the k-th. */
static inline uint32_t insert_sorted(uint64_t *buf, uint32_t n, uint32_t k, uint64_t key)
{
    if (n == k && key >= buf[k - 1])
        return n;
    uint32_t i = n < k ? n++ : k - 1;
    while (i > 0 && buf[i - 1] > key) {
        buf[i] = buf[i - 1];
        i--;
    }
    buf[i] = key;
    return n;
}

static inline uint32_t chunk_small_base(const float *x, const float *y, const float *z, uint32_t c, uint32_t end,
                                        kd_qbase *qv, uint64_t *buf, uint32_t n, uint32_t k)
{
    uint32_t bits[KD_CHUNK];
    uint32_t m = chunk_mask(x, y, z, c, qv, bits);
    if (end - c < KD_CHUNK)
        m &= (1u << (end - c)) - 1u;
    if (!m)
        return n;
    while (m) {
        uint32_t j = (uint32_t)__builtin_ctz(m);
        m &= m - 1u;
        n = insert_sorted(buf, n, k, (uint64_t)bits[j] << 32 | (c + j));
    }
    if (n == k)
        KD_QBASE_SETR2(*qv, key_d2(buf[k - 1]));
    return n;
}

#define KD_GATHER_NAME kd_gather_base
#define KD_GATHER_ATTR
#define KD_GATHER_Q kd_qbase
#define KD_GATHER_QINIT KD_QBASE_INIT
#define KD_GATHER_CHUNK chunk_base
#define KD_GATHER_SHRINK 0
#include "kdtree_gather.inc"

#define KD_GATHER_NAME kd_gather_small_base
#define KD_GATHER_ATTR
#define KD_GATHER_Q kd_qbase
#define KD_GATHER_QINIT KD_QBASE_INIT
#define KD_GATHER_CHUNK chunk_small_base
#define KD_GATHER_SHRINK 1
#include "kdtree_gather.inc"

/* ---- selection and output, base ---- */

static void split3_base(const uint64_t *src, uint32_t n, uint64_t p1, uint64_t p2, uint64_t *lt, uint64_t *mid,
                        uint64_t *ge, uint32_t cnt[3])
{
    uint32_t nl = 0, nm = 0, ng = 0;
    for (uint32_t i = 0; i < n; i++) {
        uint64_t v = src[i];
        uint32_t a = v < p1, b = v < p2;
        lt[nl] = v;
        mid[nm] = v;
        ge[ng] = v;
        nl += a;
        nm += b - a;
        ng += 1 - b;
    }
    cnt[0] = nl;
    cnt[1] = nm;
    cnt[2] = ng;
}

static void smallest_base(uint64_t *cand, uint32_t mc, uint32_t need, uint64_t *out)
{
    kd_select_keys(cand, mc, need);
    if (out != cand)
        memmove(out, cand, sizeof(uint64_t) * need);
}

static float output_base(const uint64_t *keys, uint32_t n, uint32_t *idx, float *d2)
{
    float top = 0.0f;
    for (uint32_t j = 0; j < n; j++) {
        idx[j] = (uint32_t)keys[j];
        d2[j] = key_d2(keys[j]);
        top = d2[j] > top ? d2[j] : top;
    }
    return top;
}

const kd_ops kd_ops_base = {split3_base, smallest_base, output_base};

#define KD_GATHER_NAME kd_packet_base
#define KD_GATHER_ATTR 
#define KD_GATHER_Q kd_qbase
#define KD_GATHER_QINIT KD_QBASE_INIT
#define KD_GATHER_CHUNK chunk_base
#define KD_GATHER_SHRINK 0
#include "kdtree_packet.inc"

#define KD_GATHER_NAME kd_packet_small_base
#define KD_GATHER_ATTR 
#define KD_GATHER_Q kd_qbase
#define KD_GATHER_QINIT KD_QBASE_INIT
#define KD_GATHER_CHUNK chunk_small_base
#define KD_GATHER_SHRINK 1
#include "kdtree_packet.inc"

/* ---- AVX2 leaf scans ---- */
#if KD_HAVE_AVX2
typedef struct {
    __m256 x, y, z, r2;
    float r2s;
} kd_qavx2;
#define KD_QAVX2_INIT(v, q, rr)                                                                              \
    ((v).x = _mm256_set1_ps((q)[0]), (v).y = _mm256_set1_ps((q)[1]), (v).z = _mm256_set1_ps((q)[2]),         \
     (v).r2 = _mm256_set1_ps(rr), (v).r2s = (rr))
#define KD_QAVX2_SETR2(v, rr) ((v).r2s = (rr), (v).r2 = _mm256_set1_ps((v).r2s))

/* The squared distances of the chunk's points from the query (in *d) and
 * the mask of those within the current radius, lanes past `end` cleared. */
__attribute__((target("avx2"))) static inline uint32_t chunk_mask_avx2(const float *x, const float *y,
                                                                       const float *z, uint32_t c, uint32_t end,
                                                                       const kd_qavx2 *qv, __m256 *d)
{
    __m256 dx = _mm256_sub_ps(_mm256_loadu_ps(x + c), qv->x);
    __m256 dy = _mm256_sub_ps(_mm256_loadu_ps(y + c), qv->y);
    __m256 dz = _mm256_sub_ps(_mm256_loadu_ps(z + c), qv->z);
    *d = _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(dx, dx), _mm256_mul_ps(dy, dy)), _mm256_mul_ps(dz, dz));
    uint32_t m = (uint32_t)_mm256_movemask_ps(_mm256_cmp_ps(*d, qv->r2, _CMP_LE_OQ));
    if (end - c < KD_CHUNK)
        m &= (1u << (end - c)) - 1u;
    return m;
}

/* The AVX2 leaf scan appends the chunk's keys itself: the distances' bits
 * and indices are interleaved into two vectors of four 64-bit keys (lanes
 * 0,1,4,5 and 2,3,6,7), and each is left-packed by a permutation looked up
 * from its 4-bit lane mask, so a chunk costs the same however many points
 * it keeps, none included: there is no branch on the mask, and the two
 * stores always write buf[n .. n+8), which the gathering traversal keeps
 * free (it selects before n passes cap - KD_CHUNK). Returns the new count. */
static const uint32_t kd_pack4[16][8] = {
    {0, 1, 2, 3, 4, 5, 6, 7}, {0, 1, 2, 3, 4, 5, 6, 7}, {2, 3, 0, 1, 4, 5, 6, 7}, {0, 1, 2, 3, 4, 5, 6, 7},
    {4, 5, 0, 1, 2, 3, 6, 7}, {0, 1, 4, 5, 2, 3, 6, 7}, {2, 3, 4, 5, 0, 1, 6, 7}, {0, 1, 2, 3, 4, 5, 6, 7},
    {6, 7, 0, 1, 2, 3, 4, 5}, {0, 1, 6, 7, 2, 3, 4, 5}, {2, 3, 6, 7, 0, 1, 4, 5}, {0, 1, 2, 3, 6, 7, 4, 5},
    {4, 5, 6, 7, 0, 1, 2, 3}, {0, 1, 4, 5, 6, 7, 2, 3}, {2, 3, 4, 5, 6, 7, 0, 1}, {0, 1, 2, 3, 4, 5, 6, 7},
};

__attribute__((target("avx2"))) static inline uint32_t chunk_avx2(const float *x, const float *y, const float *z,
                                                                  uint32_t c, uint32_t end, kd_qavx2 *qv,
                                                                  uint64_t *buf, uint32_t n, uint32_t k)
{
    (void)k;
    __m256 d;
    uint32_t m = chunk_mask_avx2(x, y, z, c, end, qv, &d);
    __m256i ids = _mm256_add_epi32(_mm256_set1_epi32((int)c), _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7));
    __m256i bits = _mm256_castps_si256(d);
    __m256i lo = _mm256_unpacklo_epi32(ids, bits), hi = _mm256_unpackhi_epi32(ids, bits);
    uint32_t mlo = (m & 3u) | (m >> 2 & 12u), mhi = (m >> 2 & 3u) | (m >> 4 & 12u);
    __m256i plo = _mm256_loadu_si256((const __m256i *)(const void *)kd_pack4[mlo]);
    __m256i phi = _mm256_loadu_si256((const __m256i *)(const void *)kd_pack4[mhi]);
    _mm256_storeu_si256((__m256i *)(void *)(buf + n), _mm256_permutevar8x32_epi32(lo, plo));
    n += (uint32_t)__builtin_popcount(mlo);
    _mm256_storeu_si256((__m256i *)(void *)(buf + n), _mm256_permutevar8x32_epi32(hi, phi));
    return n + (uint32_t)__builtin_popcount(mhi);
}

__attribute__((target("avx2"))) static inline uint32_t chunk_small_avx2(const float *x, const float *y,
                                                                        const float *z, uint32_t c, uint32_t end,
                                                                        kd_qavx2 *qv, uint64_t *buf, uint32_t n,
                                                                        uint32_t k)
{
    __m256 d;
    uint32_t m = chunk_mask_avx2(x, y, z, c, end, qv, &d);
    if (!m)
        return n;
    uint32_t bits[KD_CHUNK];
    _mm256_storeu_si256((__m256i *)(void *)bits, _mm256_castps_si256(d));
    while (m) {
        uint32_t j = (uint32_t)__builtin_ctz(m);
        m &= m - 1u;
        n = insert_sorted(buf, n, k, (uint64_t)bits[j] << 32 | (c + j));
    }
    if (n == k)
        KD_QAVX2_SETR2(*qv, key_d2(buf[k - 1]));
    return n;
}

#define KD_GATHER_NAME kd_gather_avx2
#define KD_GATHER_ATTR __attribute__((target("avx2")))
#define KD_GATHER_Q kd_qavx2
#define KD_GATHER_QINIT KD_QAVX2_INIT
#define KD_GATHER_CHUNK chunk_avx2
#define KD_GATHER_SHRINK 0
#include "kdtree_gather.inc"

#define KD_GATHER_NAME kd_gather_small_avx2
#define KD_GATHER_ATTR __attribute__((target("avx2")))
#define KD_GATHER_Q kd_qavx2
#define KD_GATHER_QINIT KD_QAVX2_INIT
#define KD_GATHER_CHUNK chunk_small_avx2
#define KD_GATHER_SHRINK 1
#include "kdtree_gather.inc"

#define KD_GATHER_NAME kd_packet_avx2
#define KD_GATHER_ATTR __attribute__((target("avx2")))
#define KD_GATHER_Q kd_qavx2
#define KD_GATHER_QINIT KD_QAVX2_INIT
#define KD_GATHER_CHUNK chunk_avx2
#define KD_GATHER_SHRINK 0
#include "kdtree_packet.inc"

#define KD_GATHER_NAME kd_packet_small_avx2
#define KD_GATHER_ATTR __attribute__((target("avx2")))
#define KD_GATHER_Q kd_qavx2
#define KD_GATHER_QINIT KD_QAVX2_INIT
#define KD_GATHER_CHUNK chunk_small_avx2
#define KD_GATHER_SHRINK 1
#include "kdtree_packet.inc"

/* split3 with AVX2: four keys per step, each part left-packed by kd_pack4. */
__attribute__((target("avx2"))) static void split3_avx2(const uint64_t *src, uint32_t n, uint64_t p1, uint64_t p2,
                                                        uint64_t *lt, uint64_t *mid, uint64_t *ge, uint32_t cnt[3])
{
    __m256i v1 = _mm256_set1_epi64x((long long)p1), v2 = _mm256_set1_epi64x((long long)p2);
    uint32_t nl = 0, nm = 0, ng = 0;
    for (uint32_t i = 0; i < n; i += 4) {
        __m256i v = _mm256_loadu_si256((const __m256i *)(const void *)(src + i));
        uint32_t valid = n - i >= 4 ? 15u : (1u << (n - i)) - 1u;
        /* keys are below 2^63, so the signed compare orders them */
        uint32_t a = (uint32_t)_mm256_movemask_pd(_mm256_castsi256_pd(_mm256_cmpgt_epi64(v1, v))) & valid;
        uint32_t b = (uint32_t)_mm256_movemask_pd(_mm256_castsi256_pd(_mm256_cmpgt_epi64(v2, v))) & valid;
        uint32_t mm = b & ~a, mg = valid & ~b;
        __m256i pl = _mm256_loadu_si256((const __m256i *)(const void *)kd_pack4[a]);
        __m256i pm = _mm256_loadu_si256((const __m256i *)(const void *)kd_pack4[mm]);
        __m256i pg = _mm256_loadu_si256((const __m256i *)(const void *)kd_pack4[mg]);
        _mm256_storeu_si256((__m256i *)(void *)(lt + nl), _mm256_permutevar8x32_epi32(v, pl));
        _mm256_storeu_si256((__m256i *)(void *)(mid + nm), _mm256_permutevar8x32_epi32(v, pm));
        _mm256_storeu_si256((__m256i *)(void *)(ge + ng), _mm256_permutevar8x32_epi32(v, pg));
        nl += (uint32_t)__builtin_popcount(a);
        nm += (uint32_t)__builtin_popcount(mm);
        ng += (uint32_t)__builtin_popcount(mg);
    }
    cnt[0] = nl;
    cnt[1] = nm;
    cnt[2] = ng;
}

/* smallest with AVX2: a key's rank is the count of smaller keys; eight
 * candidates are ranked at a time against each key in turn, and those of
 * rank < need are left-packed to out. */
__attribute__((target("avx2"))) static void smallest_avx2(uint64_t *cand, uint32_t mc, uint32_t need,
                                                          uint64_t *out)
{
    assert(mc <= KD_RANK_MAX && need < mc);
    uint64_t keys[KD_RANK_MAX + 8];
    memcpy(keys, cand, sizeof(uint64_t) * mc);
    for (uint32_t j = mc; j < mc + 8; j++)
        keys[j] = (uint64_t)INT64_MAX; /* ranks mc: never kept */
    const __m256i lim = _mm256_set1_epi64x((long long)need);
    uint32_t n = 0;
    for (uint32_t i = 0; i < mc; i += 8) {
        __m256i c0 = _mm256_loadu_si256((const __m256i *)(const void *)(keys + i));
        __m256i c1 = _mm256_loadu_si256((const __m256i *)(const void *)(keys + i + 4));
        __m256i r0 = _mm256_setzero_si256(), r1 = _mm256_setzero_si256();
        for (uint32_t j = 0; j < mc; j++) {
            __m256i b = _mm256_set1_epi64x((long long)keys[j]);
            r0 = _mm256_sub_epi64(r0, _mm256_cmpgt_epi64(c0, b));
            r1 = _mm256_sub_epi64(r1, _mm256_cmpgt_epi64(c1, b));
        }
        uint32_t m0 = (uint32_t)_mm256_movemask_pd(_mm256_castsi256_pd(_mm256_cmpgt_epi64(lim, r0)));
        uint32_t m1 = (uint32_t)_mm256_movemask_pd(_mm256_castsi256_pd(_mm256_cmpgt_epi64(lim, r1)));
        __m256i p0 = _mm256_loadu_si256((const __m256i *)(const void *)kd_pack4[m0]);
        __m256i p1 = _mm256_loadu_si256((const __m256i *)(const void *)kd_pack4[m1]);
        _mm256_storeu_si256((__m256i *)(void *)(out + n), _mm256_permutevar8x32_epi32(c0, p0));
        n += (uint32_t)__builtin_popcount(m0);
        _mm256_storeu_si256((__m256i *)(void *)(out + n), _mm256_permutevar8x32_epi32(c1, p1));
        n += (uint32_t)__builtin_popcount(m1);
    }
    assert(n == need);
}

/* output with AVX2: four keys at a time, indices to the low half. */
__attribute__((target("avx2"))) static float output_avx2(const uint64_t *keys, uint32_t n, uint32_t *idx,
                                                         float *d2)
{
    __m128 top = _mm_setzero_ps();
    const __m256i order = _mm256_setr_epi32(0, 2, 4, 6, 1, 3, 5, 7);
    uint32_t j = 0;
    for (; j + 4 <= n; j += 4) {
        __m256i v = _mm256_permutevar8x32_epi32(_mm256_loadu_si256((const __m256i *)(const void *)(keys + j)), order);
        __m128i d = _mm256_extracti128_si256(v, 1);
        _mm_storeu_si128((__m128i *)(void *)(idx + j), _mm256_castsi256_si128(v));
        _mm_storeu_si128((__m128i *)(void *)(d2 + j), d);
        top = _mm_max_ps(top, _mm_castsi128_ps(d));
    }
    top = _mm_max_ps(top, _mm_movehl_ps(top, top));
    top = _mm_max_ss(top, _mm_shuffle_ps(top, top, 1));
    float t = _mm_cvtss_f32(top);
    for (; j < n; j++) {
        idx[j] = (uint32_t)keys[j];
        d2[j] = key_d2(keys[j]);
        t = d2[j] > t ? d2[j] : t;
    }
    return t;
}

const kd_ops kd_ops_avx2 = {split3_avx2, smallest_avx2, output_avx2};
#endif


/* ---- which set ---- */

kd_simd kd_simd_best(void)
{
#if KD_HAVE_AVX2
    if (__builtin_cpu_supports("avx2")) /* libgcc initialises the CPU model before main */
        return KD_SIMD_AVX2;
#endif
    return KD_SIMD_BASE;
}

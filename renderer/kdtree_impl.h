/* kdtree_impl: what the kdtree_*.c files share and nothing outside them
 * reads (renderer/README.md). */
#ifndef PM_KDTREE_IMPL_H
#define PM_KDTREE_IMPL_H

#include "kdtree.h"

#include <assert.h>
#include <string.h>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif
#if defined(__x86_64__) && defined(__GNUC__)
#define KD_HAVE_AVX2 1
#else
#define KD_HAVE_AVX2 0
#endif

#define KD_CHUNK 8u     /* leaf points per distance batch; padding of the coordinate arrays */
#define KD_STACK 64     /* > tree depth (nleaves <= 2^32) */
#define KD_SMALL_K 2u   /* k up to this keeps the k nearest sorted as it goes, shrinking the radius */
#define KD_RANK_MAX 32u /* kd_ops.smallest: candidates it ranks at most */

/* ---- traversal ---- */

/* Cells are pruned against the radius times (1 + KD_PRUNE_SLACK): the
 * incremental cell distances carry a few float roundings, and a cell must
 * never be dropped while a point in it can still be within the radius. */
#define KD_PRUNE_SLACK 0x1p-12f

static inline float prune_bound(float r2)
{
    return r2 + r2 * KD_PRUNE_SLACK;
}

/* A deferred far cell: its node, squared distance and per-axis offsets. */
typedef struct {
    uint32_t node;
    float rd;
    float off[3];
} kd_frame;

/* Squared distance from q to the box of all points, and its per-axis parts. */
static inline float root_offsets(const kd_tree *t, const float q[3], float off[3])
{
    float rd = 0.0f;
    for (int a = 0; a < 3; a++) {
        float c = q[a] < t->lo[a] ? t->lo[a] : q[a];
        c = c > t->hi[a] ? t->hi[a] : c;
        off[a] = q[a] - c;
        rd += off[a] * off[a];
    }
    return rd;
}

/* Squared distances from (qx, qy, qz) to the KD_CHUNK points from index i
 * (a fixed-length loop the compiler vectorises; may read the padding). The
 * sum is ((dx dx + dy dy) + dz dz) on every path, so all paths agree to the
 * bit. */
static inline void chunk_d2(const kd_tree *t, uint32_t i, float qx, float qy, float qz, float *out)
{
    const float *x = t->x + i, *y = t->y + i, *z = t->z + i;
    for (uint32_t j = 0; j < KD_CHUNK; j++) {
        float dx = x[j] - qx, dy = y[j] - qy, dz = z[j] - qz;
        out[j] = dx * dx + dy * dy + dz * dz;
    }
}

/* Descends from *node to a leaf, nearer child first, pushing each far child
 * whose cell lies within `bound`. Returns the leaf number. */
static inline uint32_t descend(const kd_tree *t, uint32_t node, const float q[3], float rd, float off[3],
                               float bound, kd_frame *stack, int *sp)
{
    uint32_t first_leaf = t->nleaves - 1;
    while (node < first_leaf) {
        int a = t->axis[node];
        float diff = q[a] - t->split[node];
        uint32_t near = 2 * node + 1 + (diff >= 0.0f);
        float old = off[a];
        float nrd = rd - old * old + diff * diff;
        if (nrd <= bound) {
            assert(*sp < KD_STACK);
            kd_frame *f = &stack[(*sp)++];
            f->node = 4 * node + 3 - near; /* the sibling: 2n+1 <-> 2n+2 */
            f->rd = nrd;
            f->off[0] = off[0];
            f->off[1] = off[1];
            f->off[2] = off[2];
            f->off[a] = diff;
        }
        node = near;
    }
    return node - first_leaf;
}

/* The inner nodes descend compares on its way from node to a leaf: the
 * leaves all lie at depth log2(nleaves). */
static inline uint32_t descent_length(const kd_tree *t, uint32_t node)
{
    return (uint32_t)__builtin_ctz(t->nleaves) - (31u - (uint32_t)__builtin_clz(node + 1));
}

/* Pops the next deferred cell within `bound` into node/rd/off; returns 0
 * when none is left. */
static inline int pop(kd_frame *stack, int *sp, float bound, uint32_t *node, float *rd, float off[3])
{
    while (*sp > 0) {
        const kd_frame *f = &stack[--*sp];
        if (f->rd <= bound) {
            *node = f->node;
            *rd = f->rd;
            off[0] = f->off[0];
            off[1] = f->off[1];
            off[2] = f->off[2];
            return 1;
        }
    }
    return 0;
}

/* ---- packets ----
 * A cell of the packet traversal: its node and its box (the tree's bounds
 * cut by the splits above it). */
typedef struct {
    uint32_t node;
    float lo[3], hi[3];
} kd_pcell;

/* Squared distance from the box [blo, bhi] to the cell c. */
static inline float pcell_gap(const kd_pcell *c, const float blo[3], const float bhi[3])
{
    float d = 0.0f;
    for (int a = 0; a < 3; a++) {
        float g = c->lo[a] - bhi[a], g2 = blo[a] - c->hi[a];
        g = g > g2 ? g : g2;
        g = g > 0.0f ? g : 0.0f;
        d += g * g;
    }
    return d;
}

/* Squared distance from the point q to the cell c. */
static inline float pcell_dist(const kd_pcell *c, const float q[3])
{
    return pcell_gap(c, q, q);
}

/* ---- k nearest: keys ----
 * A candidate is one 64-bit key, its squared distance's bits above its
 * leaf-order index: non-negative floats order as their bit patterns, so keys
 * order by distance, then index, and the k smallest keys are one
 * well-defined set whatever order the points were met in. */
static inline uint64_t pack_key(float d, uint32_t i)
{
    uint32_t b;
    memcpy(&b, &d, sizeof b);
    return (uint64_t)b << 32 | i;
}

static inline float key_d2(uint64_t key)
{
    uint32_t b = (uint32_t)(key >> 32);
    float d;
    memcpy(&d, &b, sizeof d);
    return d;
}

/* ---- the base leaf scan's query and mask ----
 * The query point and radius broadcast for the scan, and the mask of the
 * KD_CHUNK points from c within the radius (their squared distances' bits
 * to bits[]); lanes past the range's end are the caller's to clear. SSE2 on
 * x86-64, portable C elsewhere. */
#if defined(__SSE2__)
typedef struct {
    __m128 x, y, z, r2;
    float r2s;
} kd_qbase;
#define KD_QBASE_INIT(v, q, rr)                                                                              \
    ((v).x = _mm_set1_ps((q)[0]), (v).y = _mm_set1_ps((q)[1]), (v).z = _mm_set1_ps((q)[2]),                 \
     (v).r2 = _mm_set1_ps(rr), (v).r2s = (rr))
#define KD_QBASE_SETR2(v, rr) ((v).r2s = (rr), (v).r2 = _mm_set1_ps((v).r2s))

static inline uint32_t chunk_mask(const float *x, const float *y, const float *z, uint32_t c, const kd_qbase *qv,
                                  uint32_t *bits)
{
    uint32_t mask = 0;
    for (uint32_t j = 0; j < KD_CHUNK; j += 4) {
        __m128 dx = _mm_sub_ps(_mm_loadu_ps(x + c + j), qv->x);
        __m128 dy = _mm_sub_ps(_mm_loadu_ps(y + c + j), qv->y);
        __m128 dz = _mm_sub_ps(_mm_loadu_ps(z + c + j), qv->z);
        __m128 d = _mm_add_ps(_mm_add_ps(_mm_mul_ps(dx, dx), _mm_mul_ps(dy, dy)), _mm_mul_ps(dz, dz));
        _mm_storeu_si128((__m128i *)(void *)(bits + j), _mm_castps_si128(d));
        mask |= (uint32_t)_mm_movemask_ps(_mm_cmple_ps(d, qv->r2)) << j;
    }
    return mask;
}
#else
typedef struct {
    float x, y, z, r2, r2s;
} kd_qbase;
#define KD_QBASE_INIT(v, q, rr) ((v).x = (q)[0], (v).y = (q)[1], (v).z = (q)[2], (v).r2 = (rr), (v).r2s = (rr))
#define KD_QBASE_SETR2(v, rr) ((v).r2s = (rr), (v).r2 = (v).r2s)

static inline uint32_t chunk_mask(const float *x, const float *y, const float *z, uint32_t c, const kd_qbase *qv,
                                  uint32_t *bits)
{
    uint32_t mask = 0;
    for (uint32_t j = 0; j < KD_CHUNK; j++) {
        float dx = x[c + j] - qv->x, dy = y[c + j] - qv->y, dz = z[c + j] - qv->z;
        float d = dx * dx + dy * dy + dz * dz;
        memcpy(&bits[j], &d, sizeof d);
        mask |= (uint32_t)(d <= qv->r2) << j;
    }
    return mask;
}
#endif

/* ---- between the files ---- */

/* The parts of selection and output that differ between instruction sets
 * (kdtree_simd.c defines both tables). */
typedef struct {
    /* Splits the n keys of src around p1 <= p2 into lt (< p1), mid ([p1, p2))
     * and ge, their counts to cnt; any output may be src (each is written at
     * or behind the read position); reads and writes up to 4 keys past ends. */
    void (*split3)(const uint64_t *src, uint32_t n, uint64_t p1, uint64_t p2, uint64_t *lt, uint64_t *mid,
                   uint64_t *ge, uint32_t cnt[3]);
    /* Writes the need < mc smallest of the mc <= KD_RANK_MAX distinct keys
     * of cand to out, which may overlap cand and is written up to 8 keys past
     * need; cand may be reordered. */
    void (*smallest)(uint64_t *cand, uint32_t mc, uint32_t need, uint64_t *out);
    /* Splits n keys into idx and d2; returns the largest d2 (0 if n = 0). */
    float (*output)(const uint64_t *keys, uint32_t n, uint32_t *idx, float *d2);
} kd_ops;

/* kdtree_simd.c: the operation tables (kd_ops_avx2 only where
 * KD_HAVE_AVX2) and the best set this CPU has. */
extern const kd_ops kd_ops_base;
#if KD_HAVE_AVX2
extern const kd_ops kd_ops_avx2;
#endif
kd_simd kd_simd_best(void);

/* kdtree_simd.c: one gathering pass (kdtree_gather.inc says what it does)
 * with the base or the AVX2 leaf scan, appending (the plain ones) or
 * keeping the k nearest sorted (the _small ones, for k <= KD_SMALL_K).
 * Each returns the count of keys in buf, lowers *r2p to the radius it
 * ended with and adds the nodes and points it visited to *w; cap >= k +
 * 2 KD_CHUNK. */
uint32_t kd_gather_base(const kd_tree *t, const float q[3], uint32_t k, uint64_t *buf, uint32_t cap, float *r2p,
                        kd_work *w);
uint32_t kd_gather_small_base(const kd_tree *t, const float q[3], uint32_t k, uint64_t *buf, uint32_t cap,
                              float *r2p, kd_work *w);
#if KD_HAVE_AVX2
uint32_t kd_gather_avx2(const kd_tree *t, const float q[3], uint32_t k, uint64_t *buf, uint32_t cap, float *r2p,
                        kd_work *w);
uint32_t kd_gather_small_avx2(const kd_tree *t, const float q[3], uint32_t k, uint64_t *buf, uint32_t cap,
                              float *r2p, kd_work *w);
#endif

/* kdtree_simd.c: one packet pass over m <= KD_PACKET queries
 * (kdtree_packet.inc says what it does): query j's keys to bufs[j], their
 * count to np[j], its radius r2p[j] lowered to the one it ended with; the
 * _small ones keep each buffer sorted and at most k long (k <=
 * KD_SMALL_K). Adds the nodes and points visited to *w; cap >= k + 2
 * KD_CHUNK. */
void kd_packet_base(const kd_tree *t, const float (*q)[3], uint32_t m, uint32_t k, uint64_t *const *bufs,
                    uint32_t cap, float *r2p, uint32_t *np, kd_work *w);
void kd_packet_small_base(const kd_tree *t, const float (*q)[3], uint32_t m, uint32_t k, uint64_t *const *bufs,
                          uint32_t cap, float *r2p, uint32_t *np, kd_work *w);
#if KD_HAVE_AVX2
void kd_packet_avx2(const kd_tree *t, const float (*q)[3], uint32_t m, uint32_t k, uint64_t *const *bufs,
                    uint32_t cap, float *r2p, uint32_t *np, kd_work *w);
void kd_packet_small_avx2(const kd_tree *t, const float (*q)[3], uint32_t m, uint32_t k, uint64_t *const *bufs,
                          uint32_t cap, float *r2p, uint32_t *np, kd_work *w);
#endif

/* kdtree_select.c: reorders the n distinct keys a[0..n) so that a[k-1] is
 * the k-th smallest and a[0..k-1) are the smaller ones (1 <= k <= n). */
void kd_select_keys(uint64_t *a, uint32_t n, uint32_t k);
/* kdtree_select.c: leaves in a[0..k) the k smallest of the m distinct keys
 * in a[0..m), in any order (1 <= k <= m); b and c are scratch of m + 8
 * keys, a has 8 keys of slack, hi >= every key's distance. */
void kd_select_k(uint64_t *a, uint64_t *b, uint64_t *c, uint32_t m, uint32_t k, float hi, const kd_ops *ops);

#endif

/* kdtree: build by recursive median split on the widest axis (quickselect
 * on a contiguous working copy of the points),
 * search by iterative depth-first descent (explicit stack) with the
 * incremental cell distance of Arya & Mount (each cell's squared distance is
 * updated per axis, so far cells are pruned without storing boxes). Leaves
 * are scanned KD_CHUNK points at a time (the coordinate arrays carry
 * KD_CHUNK floats of padding, so a chunk may run past the last point).
 * Results: small k keeps a sorted array, larger k a max-heap (packed
 * 64-bit keys on the stack up to KD_PACK_K). */
#include "kdtree.h"

#include <assert.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#define KD_SMALL_K 16u  /* k up to this: sorted insertion */
#define KD_PACK_K 256u  /* k up to this: packed 64-bit max-heap on the stack; above: two-array heap */
#define KD_CHUNK 8u     /* leaf points per distance batch; padding of the coordinate arrays */
#define KD_STACK 64     /* > tree depth (nleaves <= 2^32) */

/* ---- build ---- */

/* The build partitions a working copy of the points with their input
 * indices (16 bytes each), so every pass reads memory in order. */
typedef struct {
    float p[3];
    uint32_t id;
} kd_item;

typedef struct {
    kd_item *it;
    kd_tree *t;
} kd_builder;

static float coord(const kd_builder *b, uint32_t i, int axis)
{
    return b->it[i].p[axis];
}

/* Reorders it[lo..hi) so that the element at position k is the one a full
 * sort by `axis` would put there, with smaller-or-equal ones before it. */
static void select_kth(kd_builder *b, uint32_t lo, uint32_t hi, uint32_t k, int axis)
{
    kd_item *p = b->it;
    while (hi - lo > 1) {
        /* median of three pivot */
        uint32_t mid = lo + (hi - lo) / 2;
        float a = coord(b, lo, axis), m = coord(b, mid, axis), c = coord(b, hi - 1, axis);
        float pivot = a < m ? (m < c ? m : (a < c ? c : a)) : (a < c ? a : (m < c ? c : m));
        /* three-way partition: < pivot | == pivot | > pivot */
        uint32_t lt = lo, i = lo, gt = hi;
        while (i < gt) {
            float v = coord(b, i, axis);
            if (v < pivot) {
                kd_item tmp = p[lt]; p[lt] = p[i]; p[i] = tmp;
                lt++; i++;
            } else if (v > pivot) {
                gt--;
                kd_item tmp = p[gt]; p[gt] = p[i]; p[i] = tmp;
            } else {
                i++;
            }
        }
        if (k < lt)
            hi = lt;
        else if (k >= gt)
            lo = gt;
        else
            return;
    }
}

static void build_node(kd_builder *b, uint32_t node, uint32_t lo, uint32_t hi, uint32_t level_leaves)
{
    kd_tree *t = b->t;
    if (level_leaves == 1) {
        uint32_t leaf = node - (t->nleaves - 1);
        t->leaf_start[leaf] = lo;
        return;
    }
    float mn[3] = {INFINITY, INFINITY, INFINITY}, mx[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (uint32_t i = lo; i < hi; i++) {
        for (int a = 0; a < 3; a++) {
            float v = coord(b, i, a);
            mn[a] = v < mn[a] ? v : mn[a];
            mx[a] = v > mx[a] ? v : mx[a];
        }
    }
    int axis = 0;
    for (int a = 1; a < 3; a++)
        if (mx[a] - mn[a] > mx[axis] - mn[axis])
            axis = a;
    uint32_t mid = lo + (hi - lo) / 2;
    if (hi > lo) {
        select_kth(b, lo, hi, mid, axis);
        t->split[node] = mid < hi ? coord(b, mid, axis) : mx[axis];
    } else {
        t->split[node] = 0.0f;
    }
    t->axis[node] = (uint8_t)axis;
    build_node(b, 2 * node + 1, lo, mid, level_leaves / 2);
    build_node(b, 2 * node + 2, mid, hi, level_leaves / 2);
}

int kd_build(kd_tree *t, const float *pts, uint32_t n, uint32_t leaf_size, uint32_t *perm)
{
    memset(t, 0, sizeof *t);
    if (leaf_size == 0)
        leaf_size = KD_DEFAULT_LEAF;
    uint32_t nleaves = 1;
    while ((uint64_t)nleaves * leaf_size < n)
        nleaves *= 2;
    t->n = n;
    t->nleaves = nleaves;
    kd_item *it = malloc(sizeof(kd_item) * (n ? n : 1));
    t->split = malloc(sizeof(float) * nleaves);
    t->axis = malloc(nleaves);
    t->leaf_start = malloc(sizeof(uint32_t) * (nleaves + 1));
    t->x = calloc((size_t)n + KD_CHUNK, sizeof(float));
    t->y = calloc((size_t)n + KD_CHUNK, sizeof(float));
    t->z = calloc((size_t)n + KD_CHUNK, sizeof(float));
    if (!it || !t->split || !t->axis || !t->leaf_start || !t->x || !t->y || !t->z) {
        free(it);
        kd_free(t);
        return -1;
    }
    for (uint32_t i = 0; i < n; i++) {
        it[i].p[0] = pts[3 * (size_t)i];
        it[i].p[1] = pts[3 * (size_t)i + 1];
        it[i].p[2] = pts[3 * (size_t)i + 2];
        it[i].id = i;
    }
    kd_builder b = {it, t};
    build_node(&b, 0, 0, n, nleaves);
    t->leaf_start[nleaves] = n;
    for (int a = 0; a < 3; a++) {
        t->lo[a] = INFINITY;
        t->hi[a] = -INFINITY;
    }
    for (uint32_t i = 0; i < n; i++) {
        const float *p = it[i].p;
        if (perm)
            perm[i] = it[i].id;
        t->x[i] = p[0];
        t->y[i] = p[1];
        t->z[i] = p[2];
        for (int a = 0; a < 3; a++) {
            t->lo[a] = p[a] < t->lo[a] ? p[a] : t->lo[a];
            t->hi[a] = p[a] > t->hi[a] ? p[a] : t->hi[a];
        }
    }
    free(it);
    return 0;
}

void kd_free(kd_tree *t)
{
    free(t->split);
    free(t->axis);
    free(t->leaf_start);
    free(t->x);
    free(t->y);
    free(t->z);
    memset(t, 0, sizeof *t);
}

size_t kd_bytes(const kd_tree *t)
{
    size_t pts = (size_t)t->n + (t->x ? KD_CHUNK : 0);
    return pts * 3 * sizeof(float) + (size_t)t->nleaves * (sizeof(float) + 1 + sizeof(uint32_t)) + sizeof(uint32_t);
}

/* ---- search helpers ---- */

/* A deferred far cell: its node, squared distance and per-axis offsets. */
typedef struct {
    uint32_t node;
    float rd;
    float off[3];
} kd_frame;

/* Squared distance from q to the box of all points, and its per-axis parts. */
static float root_offsets(const kd_tree *t, const float q[3], float off[3])
{
    float rd = 0.0f;
    for (int a = 0; a < 3; a++) {
        float o = q[a] < t->lo[a] ? q[a] - t->lo[a] : (q[a] > t->hi[a] ? q[a] - t->hi[a] : 0.0f);
        off[a] = o;
        rd += o * o;
    }
    return rd;
}

/* Squared distances from (qx, qy, qz) to the KD_CHUNK points from index i
 * (a fixed-length loop the compiler vectorises; may read the padding). */
static inline void chunk_d2(const kd_tree *t, uint32_t i, float qx, float qy, float qz, float *out)
{
    const float *x = t->x + i, *y = t->y + i, *z = t->z + i;
    for (uint32_t j = 0; j < KD_CHUNK; j++) {
        float dx = x[j] - qx, dy = y[j] - qy, dz = z[j] - qz;
        out[j] = dx * dx + dy * dy + dz * dz;
    }
}

/* chunk_d2, and a bit mask of the lanes with distance <= worst. */
static inline uint32_t chunk_within(const kd_tree *t, uint32_t i, const float q[3], float worst, float *out)
{
#if defined(__SSE2__)
    __m128 qx = _mm_set1_ps(q[0]), qy = _mm_set1_ps(q[1]), qz = _mm_set1_ps(q[2]), w = _mm_set1_ps(worst);
    uint32_t mask = 0;
    for (uint32_t j = 0; j < KD_CHUNK; j += 4) {
        __m128 dx = _mm_sub_ps(_mm_loadu_ps(t->x + i + j), qx);
        __m128 dy = _mm_sub_ps(_mm_loadu_ps(t->y + i + j), qy);
        __m128 dz = _mm_sub_ps(_mm_loadu_ps(t->z + i + j), qz);
        __m128 d = _mm_add_ps(_mm_add_ps(_mm_mul_ps(dx, dx), _mm_mul_ps(dy, dy)), _mm_mul_ps(dz, dz));
        _mm_storeu_ps(out + j, d);
        mask |= (uint32_t)_mm_movemask_ps(_mm_cmple_ps(d, w)) << j;
    }
    return mask;
#else
    chunk_d2(t, i, q[0], q[1], q[2], out);
    uint32_t mask = 0;
    for (uint32_t j = 0; j < KD_CHUNK; j++)
        mask |= (uint32_t)(out[j] <= worst) << j;
    return mask;
#endif
}

/* Descends from *node to a leaf, nearer child first, pushing each far child
 * whose cell lies within `worst`. Returns the leaf number. */
static inline uint32_t descend(const kd_tree *t, uint32_t node, const float q[3], float rd, float off[3],
                               float worst, kd_frame *stack, int *sp)
{
    uint32_t first_leaf = t->nleaves - 1;
    while (node < first_leaf) {
        int a = t->axis[node];
        float diff = q[a] - t->split[node];
        uint32_t near = 2 * node + 1 + (diff >= 0.0f);
        float old = off[a];
        float nrd = rd - old * old + diff * diff;
        if (nrd <= worst) {
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

/* Pops the next deferred cell still within `worst` into node/rd/off;
 * returns 0 when none is left. */
static inline int pop(kd_frame *stack, int *sp, float worst, uint32_t *node, float *rd, float off[3])
{
    while (*sp > 0) {
        const kd_frame *f = &stack[--*sp];
        if (f->rd <= worst) {
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

/* ---- k nearest: results ----
 * Both kinds live in the caller's idx/d2 arrays, take the current count in
 * *np and return the new acceptance threshold: the cap until k are held,
 * then the k-th distance. Callers add a point when d <= threshold and
 * (d < threshold or fewer than k are held). */

/* sorted insertion, ascending (k <= KD_SMALL_K) */
static inline float sorted_add(uint32_t *restrict ri, float *restrict rd2, uint32_t k, uint32_t *np, uint32_t i,
                               float d, float cap)
{
    uint32_t n = *np;
    uint32_t j = n < k ? n++ : k - 1;
    while (j > 0 && rd2[j - 1] > d) {
        rd2[j] = rd2[j - 1];
        ri[j] = ri[j - 1];
        j--;
    }
    rd2[j] = d;
    ri[j] = i;
    *np = n;
    return n == k ? rd2[k - 1] : cap;
}

/* max-heap on d2 (k > KD_SMALL_K) */
static inline float heap_add(uint32_t *restrict hi, float *restrict hd, uint32_t k, uint32_t *np, uint32_t i,
                             float d, float cap)
{
    uint32_t n = *np;
    if (n < k) {
        uint32_t j = n;
        while (j > 0) {
            uint32_t parent = (j - 1) / 2;
            float dp = hd[parent];
            if (dp >= d)
                break;
            hd[j] = dp;
            hi[j] = hi[parent];
            j = parent;
        }
        hd[j] = d;
        hi[j] = i;
        *np = n + 1;
        return n + 1 == k ? hd[0] : cap;
    }
    /* replace the root and sift down */
    uint32_t j = 0;
    for (;;) {
        uint32_t c = 2 * j + 1;
        if (c >= k)
            break;
        float dc = hd[c];
        if (c + 1 < k) {
            float dc1 = hd[c + 1];
            if (dc1 > dc) {
                dc = dc1;
                c++;
            }
        }
        if (dc <= d)
            break;
        hd[j] = dc;
        hi[j] = hi[c];
        j = c;
    }
    hd[j] = d;
    hi[j] = i;
    return hd[0];
}

/* Packed max-heap (KD_SMALL_K < k <= KD_PACK_K): one 64-bit key per
 * entry, the squared distance's bits above the index (non-negative floats
 * order as their bit patterns), so a move is one load and one store. The
 * first k points are appended and heapified at once; an extra zero key at
 * h[k] lets the sift-down read a right child without a bounds test. */
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

static inline void sift_down(uint64_t *h, uint32_t k, uint32_t j, uint64_t key)
{
    uint32_t c;
    while ((c = 2 * j + 1) < k) {
        uint64_t hc = h[c], hc1 = h[c + 1];
        if (hc1 > hc) {
            hc = hc1;
            c++;
        }
        if (hc <= key)
            break;
        h[j] = hc;
        j = c;
    }
    h[j] = key;
}

static inline float packed_add(uint64_t *h, uint32_t k, uint32_t *np, uint32_t i, float d, float cap)
{
    uint32_t n = *np;
    if (n < k) {
        h[n++] = pack_key(d, i);
        *np = n;
        if (n < k)
            return cap;
        for (uint32_t j = k / 2; j-- > 0;)
            sift_down(h, k, j, h[j]);
        return key_d2(h[0]);
    }
    sift_down(h, k, 0, pack_key(d, i));
    return key_d2(h[0]);
}

/* ---- k nearest: search ---- */

/* The search loop, instantiated once per result kind (ADD). */
#define KD_KNN_SEARCH(ADD)                                                                                      \
    do {                                                                                                        \
        kd_frame stack[KD_STACK];                                                                               \
        int sp = 0;                                                                                             \
        float off[3];                                                                                           \
        float rd = root_offsets(t, q, off);                                                                     \
        uint32_t node = 0;                                                                                      \
        if (rd > worst)                                                                                         \
            break;                                                                                              \
        do {                                                                                                    \
            uint32_t leaf = descend(t, node, q, rd, off, worst, stack, &sp);                                    \
            uint32_t beg = t->leaf_start[leaf], end = t->leaf_start[leaf + 1];                                 \
            for (uint32_t c = beg; c < end; c += KD_CHUNK) {                                                    \
                float dd[KD_CHUNK];                                                                             \
                uint32_t mask = chunk_within(t, c, q, worst, dd);                                               \
                if (end - c < KD_CHUNK)                                                                         \
                    mask &= (1u << (end - c)) - 1u;                                                             \
                while (mask) {                                                                                  \
                    uint32_t j = (uint32_t)__builtin_ctz(mask);                                                 \
                    mask &= mask - 1u;                                                                          \
                    float d = dd[j];                                                                            \
                    if (d <= worst && (d < worst || n < k))                                                     \
                        worst = ADD(c + j, d);                                                                  \
                }                                                                                               \
            }                                                                                                   \
        } while (pop(stack, &sp, worst, &node, &rd, off));                                                      \
    } while (0)

uint32_t kd_knn(const kd_tree *t, const float q[3], uint32_t k, float max_d2, uint32_t *idx, float *d2, float *r2)
{
    *r2 = 0.0f;
    if (k == 0 || t->n == 0)
        return 0;
    uint32_t n = 0;
    float worst = max_d2;
    if (k <= KD_SMALL_K) {
#define ADD_SORTED(i, d) sorted_add(idx, d2, k, &n, (i), (d), max_d2)
        KD_KNN_SEARCH(ADD_SORTED);
#undef ADD_SORTED
        if (n > 0)
            *r2 = d2[n - 1];
    } else if (k <= KD_PACK_K) {
        uint64_t h[KD_PACK_K + 1];
        h[k] = 0;
#define ADD_PACKED(i, d) packed_add(h, k, &n, (i), (d), max_d2)
        KD_KNN_SEARCH(ADD_PACKED);
#undef ADD_PACKED
        uint64_t top = 0;
        for (uint32_t j = 0; j < n; j++) {
            idx[j] = (uint32_t)h[j];
            d2[j] = key_d2(h[j]);
            top = h[j] > top ? h[j] : top;
        }
        *r2 = n > 0 ? key_d2(top) : 0.0f;
    } else {
#define ADD_HEAP(i, d) heap_add(idx, d2, k, &n, (i), (d), max_d2)
        KD_KNN_SEARCH(ADD_HEAP);
#undef ADD_HEAP
        if (n > 0)
            *r2 = d2[0];
    }
    return n;
}

/* ---- nearest with a predicate ---- */

uint32_t kd_nearest_if(const kd_tree *t, const float q[3], float max_d2, kd_pred pred, const void *ctx, float *d2)
{
    uint32_t best = KD_NONE;
    float best_d2 = max_d2;
    if (t->n > 0) {
        kd_frame stack[KD_STACK];
        int sp = 0;
        float off[3];
        float rd = root_offsets(t, q, off);
        uint32_t node = 0;
        if (rd <= max_d2) {
            do {
                uint32_t leaf = descend(t, node, q, rd, off, best_d2, stack, &sp);
                uint32_t beg = t->leaf_start[leaf], end = t->leaf_start[leaf + 1];
                for (uint32_t c = beg; c < end; c += KD_CHUNK) {
                    float dd[KD_CHUNK];
                    chunk_d2(t, c, q[0], q[1], q[2], dd);
                    uint32_t m = end - c < KD_CHUNK ? end - c : KD_CHUNK;
                    for (uint32_t j = 0; j < m; j++) {
                        float d = dd[j];
                        if (d <= best_d2 && (best == KD_NONE || d < best_d2) && (!pred || pred(c + j, ctx))) {
                            best = c + j;
                            best_d2 = d;
                        }
                    }
                }
            } while (pop(stack, &sp, best_d2, &node, &rd, off));
        }
    }
    *d2 = best == KD_NONE ? 0.0f : best_d2;
    return best;
}

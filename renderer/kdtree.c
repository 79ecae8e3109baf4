/* kdtree: build by recursive median split on the widest axis (quickselect
 * on a contiguous working copy of the points), search by iterative
 * depth-first descent (explicit stack) with the incremental cell distance of
 * Arya & Mount (each cell's squared distance is updated per axis, so far
 * cells are pruned without storing boxes). Leaves are scanned KD_CHUNK
 * points at a time (the coordinate arrays carry KD_CHUNK floats of padding,
 * so a chunk may run past the last point), with SSE2 or, where the CPU has
 * it, AVX2 (chosen at run time per kd_query).
 *
 * k nearest gathers rather than ranks: a pass collects every point within a
 * radius into a buffer of (distance, index) keys and selects the k smallest
 * at the end (select_k), so no heap is kept per point. The radius starts
 * from the previous query's k-th distance (kd_query); when that proves too
 * small the pass is repeated wider, and when the buffer fills, its k
 * smallest are kept and the radius shrinks to their largest. For k <=
 * KD_SMALL_K the pass keeps the k nearest sorted instead and shrinks the
 * radius as soon as it holds k. The traversal stops KD_SCAN_POINTS-sized
 * subtrees above the leaves and scans their points as one range. */
#include "kdtree.h"

#include <assert.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif
#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#define KD_HAVE_AVX2 1
#else
#define KD_HAVE_AVX2 0
#endif

#define KD_CHUNK 8u     /* leaf points per distance batch; padding of the coordinate arrays */
#define KD_STACK 64     /* > tree depth (nleaves <= 2^32) */
#define KD_LOCAL_K 128u /* kd_knn: k up to this gathers in a stack buffer; above, a heap in the output */
#define KD_SMALL_K 2u   /* k up to this keeps the k nearest sorted as it goes, shrinking the radius */
#define KD_MAX_BUF_K (1u << 24) /* kd_query: larger k (16M) takes the heap in the output, no buffer */

/* ---- build ---- */

/* The height above the leaves at which the k-nearest traversal stops and
 * scans contiguous ranges: 0 for a single leaf, else the largest h >= 1
 * (below the root) whose half-subtrees, of 2^(h-1) leaves, hold at most
 * KD_SCAN_POINTS points. Subtrees of one level differ in size by at most
 * one point, so the largest of height g holds ceil(n / 2^(depth-g)).
 * Scanning a few chunks costs less than descending to each leaf: with the
 * branch-free AVX2 scan, 8 chunks (ranges of up to 64-128 points) beat 4
 * and 16 at k = 10 and k = 100 on the 500k Cornell map (experiments/bench:
 * 7.1-7.4x nanoflann at k = 10 against 6.0x with 4 chunks, 28x against 22x
 * at k = 100; 16 chunks lose at k = 1 and k = 10). */
#define KD_SCAN_POINTS (8 * KD_CHUNK)

static uint32_t scan_height(uint32_t n, uint32_t nleaves)
{
    uint32_t depth = (uint32_t)__builtin_ctz(nleaves), h = depth > 0;
    while (h < depth && ((((uint64_t)n - 1) >> (depth - h)) + 1) <= KD_SCAN_POINTS)
        h++;
    return h;
}

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

/* The k-th smallest (from 0) of the n floats v[] (reordered). */
static float select_float(float *v, uint32_t n, uint32_t k)
{
    assert(k < n);
    uint32_t lo = 0, hi = n;
    while (hi - lo > 1) {
        float pivot = v[lo + (hi - lo) / 2];
        uint32_t lt = lo, i = lo, gt = hi;
        while (i < gt) {
            float x = v[i];
            if (x < pivot) {
                v[i++] = v[lt];
                v[lt++] = x;
            } else if (x > pivot) {
                v[i] = v[--gt];
                v[gt] = x;
            } else {
                i++;
            }
        }
        if (k < lt)
            hi = lt;
        else if (k >= gt)
            lo = gt;
        else
            return pivot;
    }
    return v[lo];
}

/* Moves the items of p[lo..hi) whose `axis` coordinate is below v (strict)
 * or at most v (!strict) to the front, the rest after them; returns where
 * the rest begins. Branch-free (Lomuto's scheme with an unconditional swap):
 * the comparison only decides how far the front grows, so the loop runs at
 * the same speed whatever the data (a branch per item mispredicts half the
 * time on unordered points). */
static uint32_t partition2(kd_item *p, uint32_t lo, uint32_t hi, int axis, float v, int strict)
{
    uint32_t front = lo;
    for (uint32_t i = lo; i < hi; i++) {
        kd_item x = p[i];
        float c = x.p[axis];
        p[i] = p[front];
        p[front] = x;
        front += strict ? c < v : c <= v;
    }
    return front;
}

/* Three-way partition of it[lo..hi) by `axis`: below p1 | from p1 to p2 |
 * above p2, as two branch-free passes. Sets *lt and *gt to the bounds of
 * the middle part. */
static void partition3(kd_item *p, uint32_t lo, uint32_t hi, int axis, float p1, float p2, uint32_t *lt_out,
                       uint32_t *gt_out)
{
    uint32_t lt = partition2(p, lo, hi, axis, p1, 1);
    *lt_out = lt;
    *gt_out = partition2(p, lt, hi, axis, p2, 0);
}

/* Reorders it[lo..hi) so that the element at position k is the one a full
 * sort by `axis` would put there, with smaller-or-equal ones before it.
 * Long ranges are first split around two values that a sample of them
 * places just below and just above the k-th (Floyd & Rivest), so that the
 * quickselect after works on a small middle part instead of half the
 * range each pass. */
#define KD_SAMPLE_MIN 4096u /* ranges at least this long are sampled */
#define KD_SAMPLE_MAX 1023u

static void select_kth(kd_builder *b, uint32_t lo, uint32_t hi, uint32_t k, int axis)
{
    kd_item *p = b->it;
    assert(lo <= k && k < hi);
    if (hi - lo >= KD_SAMPLE_MIN) {
        uint32_t len = hi - lo, ns = len / 64 < KD_SAMPLE_MAX ? len / 64 : KD_SAMPLE_MAX;
        float sample[KD_SAMPLE_MAX];
        for (uint32_t j = 0; j < ns; j++)
            sample[j] = p[lo + (uint32_t)((uint64_t)len * (2 * j + 1) / (2 * ns))].p[axis];
        /* the k-th's rank in the sample, give or take 3 standard deviations */
        uint32_t at = (uint32_t)((uint64_t)(k - lo) * ns / len), d = (uint32_t)(1.5f * sqrtf((float)ns)) + 1;
        float p1 = select_float(sample, ns, at > d ? at - d : 0);
        float p2 = select_float(sample, ns, at + d < ns ? at + d : ns - 1);
        uint32_t lt, gt;
        partition3(p, lo, hi, axis, p1, p2, &lt, &gt);
        if (k < lt)
            hi = lt;
        else if (k >= gt)
            lo = gt;
        else {
            lo = lt;
            hi = gt;
        }
    }
    while (hi - lo > 1) {
        /* median of three pivot */
        uint32_t mid = lo + (hi - lo) / 2;
        float a = coord(b, lo, axis), m = coord(b, mid, axis), c = coord(b, hi - 1, axis);
        float pivot = a < m ? (m < c ? m : (a < c ? c : a)) : (a < c ? a : (m < c ? c : m));
        uint32_t lt, gt;
        partition3(p, lo, hi, axis, pivot, pivot, &lt, &gt);
        if (k < lt)
            hi = lt;
        else if (k >= gt)
            lo = gt;
        else
            return;
    }
}

/* Bounds of it[lo..hi) (lo < hi). */
static void bounds(const kd_item *it, uint32_t lo, uint32_t hi, float mn[3], float mx[3])
{
#if defined(__SSE2__)
    __m128 vmn = _mm_loadu_ps(it[lo].p), vmx = vmn; /* lane 3 holds the id's bits: ignored */
    for (uint32_t i = lo + 1; i < hi; i++) {
        __m128 v = _mm_loadu_ps(it[i].p);
        vmn = _mm_min_ps(v, vmn); /* v < mn ? v : mn */
        vmx = _mm_max_ps(v, vmx); /* v > mx ? v : mx */
    }
    float a[4], c[4];
    _mm_storeu_ps(a, vmn);
    _mm_storeu_ps(c, vmx);
    for (int k = 0; k < 3; k++) {
        mn[k] = a[k];
        mx[k] = c[k];
    }
#else
    for (int a = 0; a < 3; a++)
        mn[a] = mx[a] = it[lo].p[a];
    for (uint32_t i = lo + 1; i < hi; i++)
        for (int a = 0; a < 3; a++) {
            float v = it[i].p[a];
            mn[a] = v < mn[a] ? v : mn[a];
            mx[a] = v > mx[a] ? v : mx[a];
        }
#endif
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
    if (hi > lo)
        bounds(b->it, lo, hi, mn, mx);
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
    t->scan_h = scan_height(n, nleaves);
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

/* Reorders the n distinct keys a[0..n) so that a[k-1] is the k-th smallest
 * and a[0..k-1) are the smaller ones (1 <= k <= n). */
static void select_keys(uint64_t *a, uint32_t n, uint32_t k)
{
    assert(k >= 1 && k <= n);
    uint32_t lo = 0, hi = n - 1, want = k - 1;
    while (hi - lo > 16) {
        uint32_t mid = lo + (hi - lo) / 2;
        uint64_t x = a[lo], y = a[mid], z = a[hi];
        uint64_t pivot = x < y ? (y < z ? y : (x < z ? z : x)) : (x < z ? x : (y < z ? z : y));
        uint32_t i = lo, j = hi;
        for (;;) {
            while (a[i] < pivot)
                i++;
            while (a[j] > pivot)
                j--;
            if (i >= j)
                break;
            uint64_t tmp = a[i];
            a[i] = a[j];
            a[j] = tmp;
            i++;
            j--;
        }
        /* now a[lo..j] <= pivot <= a[j+1..hi] */
        if (want <= j)
            hi = j;
        else
            lo = j + 1;
    }
    for (uint32_t i = lo + 1; i <= hi; i++) {
        uint64_t v = a[i];
        uint32_t j = i;
        while (j > lo && a[j - 1] > v) {
            a[j] = a[j - 1];
            j--;
        }
        a[j] = v;
    }
}

/* The parts of selection and output that differ between instruction sets:
 *
 * split3: splits the n keys src[0..n) around p1 <= p2: keys < p1 to lt,
 * keys in [p1, p2) to mid, the rest to ge; cnt[] receives the three counts.
 * Any one output may be src itself (each is written at or behind the read
 * position); arrays are read and written up to 4 keys past their ends.
 *
 * smallest: writes the need < mc smallest of the mc <= KD_RANK_MAX distinct
 * keys cand[0..mc) to out[0..need) (out may overlap cand and may be
 * written up to 8 keys past need; cand may be reordered).
 *
 * output: splits n keys into idx[] and d2[]; returns the largest d2 (0 if
 * n = 0). */
#define KD_RANK_MAX 32u

typedef struct {
    void (*split3)(const uint64_t *src, uint32_t n, uint64_t p1, uint64_t p2, uint64_t *lt, uint64_t *mid,
                   uint64_t *ge, uint32_t cnt[3]);
    void (*smallest)(uint64_t *cand, uint32_t mc, uint32_t need, uint64_t *out);
    float (*output)(const uint64_t *keys, uint32_t n, uint32_t *idx, float *d2);
} kd_ops;

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
    select_keys(cand, mc, need);
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

static const kd_ops kd_ops_base = {split3_base, smallest_base, output_base};

/* Leaves in a[0..k) the k smallest of the m distinct keys in a[0..m), in
 * any order (1 <= k <= m). b and c are scratch of m + 8 keys, a has 8
 * keys of slack. hi >= every key's distance. Each pass splits the
 * candidates three ways around two distances guessed to bracket the k-th
 * (squared distances of points on a surface around the query are close to
 * uniform between the bounds known so far), keeps the part below, and goes
 * on with the one part that holds the k-th, until few are left; a guess
 * that splits nothing off (equal distances) hands over to quickselect. */
static void select_k(uint64_t *a, uint64_t *b, uint64_t *c, uint32_t m, uint32_t k, float hi, const kd_ops *ops)
{
    assert(k >= 1 && k <= m);
    uint32_t nacc = 0, need = k, mc = m;
    uint64_t *cand = a; /* candidates cand[0..mc): at a + nacc, in b or in c */
    float lo = 0.0f;
    while (need < mc) {
        if (mc <= KD_RANK_MAX) {
            ops->smallest(cand, mc, need, a + nacc);
            return;
        }
        float span = hi - lo, w = 2.0f * sqrtf((float)need * (float)(mc - need) / (float)mc) + 1.0f;
        float t1 = lo + span * ((float)need - w) / (float)mc, t2 = lo + span * ((float)need + w) / (float)mc;
        t1 = t1 > lo ? t1 : lo;
        t2 = t2 < hi ? t2 : hi;
        /* below t1 joins the result at a + nacc; [t1, t2) goes to b, the rest to c
         * (b or c may be cand itself: each is written behind the read position) */
        uint32_t cnt[3], before = mc;
        ops->split3(cand, mc, pack_key(t1, 0), pack_key(t2, 0), a + nacc, b, c, cnt);
        assert(cnt[0] + cnt[1] + cnt[2] == mc);
        if (cnt[0] > need) { /* the k-th is below t1 */
            cand = a + nacc;
            mc = cnt[0];
            hi = t1;
        } else if (cnt[0] + cnt[1] >= need) { /* in [t1, t2) */
            nacc += cnt[0];
            need -= cnt[0];
            cand = b;
            mc = cnt[1];
            lo = t1;
            hi = t2;
        } else { /* at or above t2 */
            memcpy(a + nacc + cnt[0], b, sizeof(uint64_t) * cnt[1]);
            nacc += cnt[0] + cnt[1];
            need -= cnt[0] + cnt[1];
            cand = c;
            mc = cnt[2];
            lo = t2;
        }
        if (need == 0)
            return;
        if (mc == before) { /* the guess split nothing off */
            select_keys(cand, mc, need);
            break;
        }
    }
    if (cand != a + nacc)
        memmove(a + nacc, cand, sizeof(uint64_t) * need);
}

/* ---- k nearest: the gathering traversal ----
 * One pass appends to buf the key of every point with squared distance
 * <= *r2 in the cells within it. When buf fills (cap entries, >= k +
 * 2 KD_CHUNK), the k smallest keys are kept and *r2 drops to the k-th
 * distance, so a pass costs about the same whatever radius it starts from.
 * Returns the count. Cells are descended nearer child first down to
 * t->scan_h levels above the leaves; there the node's points (or its near
 * half's, when the far half is out of reach) are scanned as one contiguous
 * range. CHUNK, the scan of KD_CHUNK points, is the only part that differs
 * between instruction sets; with SHRINK it keeps buf sorted and at most k
 * long, lowering the radius (QTYPE's r2s) as it goes. */
#define KD_GATHER_FN(NAME, ATTR, QTYPE, QINIT, CHUNK, SHRINK)                                                   \
    ATTR static uint32_t NAME(const kd_tree *t, const float q[3], uint32_t k, uint64_t *buf, uint32_t cap,         \
                              float *r2p)                                                                      \
    {                                                                                                          \
        float r2 = *r2p, bound = prune_bound(r2), off[3];                                                      \
        float rd = root_offsets(t, q, off);                                                                    \
        uint32_t n = 0;                                                                                        \
        assert(cap >= k + 2 * KD_CHUNK);                                                                       \
        if (!(rd <= bound))                                                                                    \
            return 0;                                                                                          \
        QTYPE qv;                                                                                              \
        QINIT(qv, q, r2);                                                                                      \
        kd_frame stack[KD_STACK];                                                                              \
        int sp = 0;                                                                                            \
        const uint32_t nl = t->nleaves, h = t->scan_h, first_scan = (nl >> h) - 1, half = (1u << h) >> 1;      \
        const uint32_t *ls = t->leaf_start;                                                                    \
        const float *x = t->x, *y = t->y, *z = t->z, *split = t->split;                                        \
        const uint8_t *axis = t->axis;                                                                         \
        uint32_t node = 0;                                                                                     \
        for (;;) {                                                                                             \
            uint32_t beg = 0, end = t->n;                                                                      \
            if (h > 0) {                                                                                       \
                int a;                                                                                         \
                float diff, nrd;                                                                               \
                uint32_t near;                                                                                 \
                for (;;) {                                                                                     \
                    a = axis[node];                                                                            \
                    diff = q[a] - split[node];                                                                 \
                    /* a branch, not a flag: the CPU runs ahead on the predicted side, where a             \
                     * computed child would wait for the loads and the compare at every level */         \
                    if (__builtin_expect(diff >= 0.0f, 1))                                                     \
                        near = 2 * node + 2;                                                                   \
                    else                                                                                       \
                        near = 2 * node + 1;                                                                   \
                    nrd = rd - off[a] * off[a] + diff * diff;                                                  \
                    if (node >= first_scan)                                                                    \
                        break;                                                                                 \
                    /* the far child is written at the top of the stack and kept only when its cell \
                     * is within reach: no branch to mispredict on the data-dependent test */             \
                    assert(sp < KD_STACK);                                                                     \
                    kd_frame *f = &stack[sp];                                                                  \
                    f->node = 4 * node + 3 - near;                                                             \
                    f->rd = nrd;                                                                               \
                    f->off[0] = off[0];                                                                        \
                    f->off[1] = off[1];                                                                        \
                    f->off[2] = off[2];                                                                        \
                    f->off[a] = diff;                                                                          \
                    sp += nrd <= bound;                                                                        \
                    node = near;                                                                               \
                }                                                                                              \
                /* node is h levels above the leaves: scan both halves, or the near one */                    \
                uint32_t first = ((node + 1) << h) - nl;                                                       \
                if (nrd <= bound) {                                                                            \
                    beg = ls[first];                                                                           \
                    end = ls[first + 2 * half];                                                                \
                } else {                                                                                       \
                    first += (near & 1u) ? 0 : half;                                                           \
                    beg = ls[first];                                                                           \
                    end = ls[first + half];                                                                    \
                }                                                                                              \
            }                                                                                                  \
            if ((uint64_t)n + (end - beg) + KD_CHUNK <= cap) { /* room for the whole range */                \
                for (uint32_t c = beg; c < end; c += KD_CHUNK)                                                 \
                    n = CHUNK(x, y, z, c, end, &qv, buf, n, k);                                                \
            } else { /* chunk by chunk, keeping the k smallest when full */                                    \
                for (uint32_t c = beg; c < end; c += KD_CHUNK) {                                               \
                    if (n > cap - KD_CHUNK) {                                                                  \
                        select_keys(buf, n, k);                                                                \
                        n = k;                                                                                 \
                        r2 = key_d2(buf[k - 1]);                                                               \
                        bound = prune_bound(r2);                                                               \
                        QINIT(qv, q, r2);                                                                      \
                    }                                                                                          \
                    n = CHUNK(x, y, z, c, end, &qv, buf, n, k);                                                \
                }                                                                                              \
            }                                                                                                  \
            if (SHRINK) {                                                                                      \
                r2 = qv.r2s;                                                                                   \
                bound = prune_bound(r2);                                                                       \
            }                                                                                                  \
            if (!pop(stack, &sp, bound, &node, &rd, off))                                                      \
                break;                                                                                         \
        }                                                                                                      \
        *r2p = r2;                                                                                             \
        return n;                                                                                              \
    }

/* The base leaf scan: squared distances of the KD_CHUNK points from c, and
 * the keys of those within r2 appended to buf[n..] one by one (those from
 * `end` on are not points of the range); returns the new count. */
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

KD_GATHER_FN(gather_base, , kd_qbase, KD_QBASE_INIT, chunk_base, 0)
KD_GATHER_FN(gather_small_base, , kd_qbase, KD_QBASE_INIT, chunk_small_base, 1)

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

KD_GATHER_FN(gather_avx2, __attribute__((target("avx2"))), kd_qavx2, KD_QAVX2_INIT, chunk_avx2, 0)
KD_GATHER_FN(gather_small_avx2, __attribute__((target("avx2"))), kd_qavx2, KD_QAVX2_INIT, chunk_small_avx2, 1)

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

static const kd_ops kd_ops_avx2 = {split3_avx2, smallest_avx2, output_avx2};
#endif

/* ---- k nearest: without a buffer ----
 * When no candidate buffer is at hand (k beyond kd_knn's stack buffer, or
 * no memory for a state's), a max-heap of keys lives in idx/d2 themselves.
 * Slower, same result. */
static inline uint64_t heap_key(const uint32_t *hi, const float *hd, uint32_t j)
{
    return pack_key(hd[j], hi[j]);
}

static uint32_t knn_heap(const kd_tree *t, const float q[3], uint32_t k, float max_d2, uint32_t *hi, float *hd,
                         float *r2)
{
    uint32_t n = 0;
    float worst = max_d2, bound = prune_bound(worst);
    kd_frame stack[KD_STACK];
    int sp = 0;
    float off[3];
    float rd = root_offsets(t, q, off);
    uint32_t node = 0;
    if (rd <= bound) {
        do {
            uint32_t leaf = descend(t, node, q, rd, off, bound, stack, &sp);
            uint32_t beg = t->leaf_start[leaf], end = t->leaf_start[leaf + 1];
            for (uint32_t c = beg; c < end; c += KD_CHUNK) {
                float dd[KD_CHUNK];
                chunk_d2(t, c, q[0], q[1], q[2], dd);
                uint32_t m = end - c < KD_CHUNK ? end - c : KD_CHUNK;
                for (uint32_t j = 0; j < m; j++) {
                    float d = dd[j];
                    if (!(d <= worst))
                        continue;
                    uint64_t key = pack_key(d, c + j);
                    uint32_t at;
                    if (n < k) { /* sift up from the end */
                        at = n++;
                        while (at > 0 && heap_key(hi, hd, (at - 1) / 2) < key) {
                            uint32_t parent = (at - 1) / 2;
                            hd[at] = hd[parent];
                            hi[at] = hi[parent];
                            at = parent;
                        }
                    } else { /* replace the root, sift down */
                        if (key >= heap_key(hi, hd, 0))
                            continue;
                        at = 0;
                        for (;;) {
                            uint32_t ch = 2 * at + 1;
                            if (ch >= k)
                                break;
                            if (ch + 1 < k && heap_key(hi, hd, ch + 1) > heap_key(hi, hd, ch))
                                ch++;
                            if (heap_key(hi, hd, ch) <= key)
                                break;
                            hd[at] = hd[ch];
                            hi[at] = hi[ch];
                            at = ch;
                        }
                    }
                    hd[at] = d;
                    hi[at] = c + j;
                    if (n == k) {
                        worst = hd[0];
                        bound = prune_bound(worst);
                    }
                }
            }
        } while (pop(stack, &sp, bound, &node, &rd, off));
    }
    *r2 = n > 0 ? hd[0] : 0.0f;
    return n;
}

/* ---- k nearest: entry points ---- */

/* Candidate buffer entries for k (see KD_GATHER_FN: at least k + 2 chunks;
 * twice k so that a full buffer's selection is paid for by k appends). The
 * buffer is three regions of buf_entries(k) + KD_CHUNK keys: the gathered
 * candidates and select_k's two scratch areas, each with slack for the
 * vector stores. */
static uint32_t buf_entries(uint32_t k)
{
    return 2 * k + 4 * KD_CHUNK;
}

static size_t buf_keys(uint32_t cap)
{
    return 3 * ((size_t)cap + KD_CHUNK);
}

/* How much wider than the last query's k-th radius (squared) to start: the
 * k-th distance of neighbouring queries varies about as 1/sqrt(k). */
static float start_slack(uint32_t k)
{
    return 1.0f + 2.5f / sqrtf((float)k);
}

/* The search with a buffer of s->cap >= buf_entries(k) entries; k <= t->n. */
static uint32_t knn_run(const kd_tree *t, kd_query *s, const float q[3], uint32_t k, float max_d2, uint32_t *idx,
                        float *d2, float *r2)
{
    assert(k >= 1 && k <= t->n && s->cap >= buf_entries(k));
    float r = max_d2;
    if (s->hint_k) {
        float g = s->hint_r2 * ((float)k / (float)s->hint_k) * start_slack(k);
        r = g < r ? g : r;
    }
    const kd_ops *ops = &kd_ops_base;
#if KD_HAVE_AVX2
    if (s->simd == KD_SIMD_AVX2)
        ops = &kd_ops_avx2;
#endif
    uint64_t *buf = s->buf;
    uint32_t n;
    int small = k <= KD_SMALL_K;
    for (int pass = 0;; pass++) {
        float used = r;
#if KD_HAVE_AVX2
        if (s->simd == KD_SIMD_AVX2)
            n = small ? gather_small_avx2(t, q, k, buf, s->cap, &r) : gather_avx2(t, q, k, buf, s->cap, &r);
        else
#endif
            n = small ? gather_small_base(t, q, k, buf, s->cap, &r) : gather_base(t, q, k, buf, s->cap, &r);
        s->passes++;
        if (n >= k || !(used < max_d2))
            break;
        /* too few within r: widen (2-d density: count ~ r2), at most 3 times before the cap */
        float g = n > 0 ? used * 1.5f * (float)k / (float)n : used * 4.0f;
        r = (pass < 3 && g > used && g < max_d2) ? g : max_d2;
    }
    s->queries++;
    if (n > k) {
        uint32_t stride = s->cap + KD_CHUNK;
        select_k(buf, buf + stride, buf + 2 * (size_t)stride, n, k, r, ops);
        n = k;
    }
    float top = ops->output(buf, n, idx, d2);
    *r2 = top;
    s->hint_k = k;
    s->hint_r2 = n == k ? top : max_d2;
    return n;
}

static kd_simd best_simd(void)
{
#if KD_HAVE_AVX2
    if (__builtin_cpu_supports("avx2")) /* libgcc initialises the CPU model before main */
        return KD_SIMD_AVX2;
#endif
    return KD_SIMD_BASE;
}

int kd_query_init(kd_query *s, uint32_t k_max)
{
    memset(s, 0, sizeof *s);
    s->simd = best_simd();
    uint32_t cap = buf_entries(k_max == 0 ? 1 : (k_max < KD_MAX_BUF_K ? k_max : KD_MAX_BUF_K));
    s->buf = malloc(sizeof(uint64_t) * buf_keys(cap));
    if (!s->buf)
        return -1;
    s->cap = cap;
    return 0;
}

void kd_query_free(kd_query *s)
{
    free(s->buf);
    memset(s, 0, sizeof *s);
}

kd_simd kd_query_simd(kd_query *s, kd_simd want)
{
    kd_simd best = best_simd();
    s->simd = want < best ? KD_SIMD_BASE : best;
    return s->simd;
}

uint32_t kd_query_knn(const kd_tree *t, kd_query *s, const float q[3], uint32_t k, float max_d2, uint32_t *idx,
                      float *d2, float *r2)
{
    *r2 = 0.0f;
    if (k == 0 || t->n == 0 || !(max_d2 >= 0.0f))
        return 0;
    k = k < t->n ? k : t->n;
    if (k > KD_MAX_BUF_K)
        return knn_heap(t, q, k, max_d2, idx, d2, r2);
    if (s->cap < buf_entries(k)) {
        uint64_t *b = realloc(s->buf, sizeof(uint64_t) * buf_keys(buf_entries(k)));
        if (!b)
            return knn_heap(t, q, k, max_d2, idx, d2, r2);
        s->buf = b;
        s->cap = buf_entries(k);
    }
    return knn_run(t, s, q, k, max_d2, idx, d2, r2);
}

uint32_t kd_knn(const kd_tree *t, const float q[3], uint32_t k, float max_d2, uint32_t *idx, float *d2, float *r2)
{
    *r2 = 0.0f;
    if (k == 0 || t->n == 0 || !(max_d2 >= 0.0f))
        return 0;
    k = k < t->n ? k : t->n;
    if (k > KD_LOCAL_K)
        return knn_heap(t, q, k, max_d2, idx, d2, r2);
    uint64_t local[3 * (2 * KD_LOCAL_K + 5 * KD_CHUNK)];
    kd_query s;
    memset(&s, 0, sizeof s);
    s.simd = best_simd();
    s.buf = local;
    s.cap = buf_entries(k);
    return knn_run(t, &s, q, k, max_d2, idx, d2, r2);
}

/* ---- nearest with a predicate ---- */

uint32_t kd_nearest_if(const kd_tree *t, const float q[3], float max_d2, kd_pred pred, const void *ctx, uint32_t hint,
                       float *d2)
{
    uint32_t best = KD_NONE;
    float best_d2 = max_d2;
    if (hint < t->n) {
        float dx = t->x[hint] - q[0], dy = t->y[hint] - q[1], dz = t->z[hint] - q[2];
        float d = dx * dx + dy * dy + dz * dz; /* as chunk_d2 computes it */
        if (d <= max_d2 && (!pred || pred(hint, ctx))) {
            best = hint;
            best_d2 = d;
        }
    }
    if (t->n > 0) {
        kd_frame stack[KD_STACK];
        int sp = 0;
        float off[3];
        float rd = root_offsets(t, q, off);
        uint32_t node = 0;
        if (rd <= prune_bound(max_d2)) {
            kd_qbase qv;
            KD_QBASE_INIT(qv, q, best_d2);
            do {
                uint32_t leaf = descend(t, node, q, rd, off, prune_bound(best_d2), stack, &sp);
                uint32_t beg = t->leaf_start[leaf], end = t->leaf_start[leaf + 1];
                for (uint32_t c = beg; c < end; c += KD_CHUNK) {
                    /* only the lanes within the best distance so far */
                    uint32_t bits[KD_CHUNK];
                    uint32_t m = chunk_mask(t->x, t->y, t->z, c, &qv, bits);
                    if (end - c < KD_CHUNK)
                        m &= (1u << (end - c)) - 1u;
                    while (m) {
                        uint32_t j = (uint32_t)__builtin_ctz(m);
                        m &= m - 1u;
                        float d;
                        memcpy(&d, &bits[j], sizeof d);
                        if (d <= best_d2 && (best == KD_NONE || d < best_d2 || c + j < best) &&
                            (!pred || pred(c + j, ctx))) {
                            best = c + j;
                            best_d2 = d;
                            KD_QBASE_SETR2(qv, best_d2);
                        }
                    }
                }
            } while (pop(stack, &sp, prune_bound(best_d2), &node, &rd, off));
        }
    }
    *d2 = best == KD_NONE ? 0.0f : best_d2;
    return best;
}

/* kdtree_build: the tree's construction and its memory: kd_build (a
 * recursive median split on the widest axis, each median found by a
 * Floyd-Rivest sampled quickselect on a contiguous working copy of the
 * points), the height at which searches switch to range scans, kd_free,
 * kd_bytes and kd_build_peak_bytes.
 *
 * Threads: a node's split depends only on the items of its own range and
 * their order, and every node's range follows from n alone (each splits at
 * lo + (hi - lo) / 2), so nodes of disjoint ranges can be split at the same
 * time without changing the tree. The top levels are split one level at a
 * time (a parallel loop over each level's nodes), then the subtrees below
 * them are built in parallel; the copies in and out run over blocks. The
 * tree is the same for any thread count. */
#include "kdtree_impl.h"
#include "mem.h"
#include "parallel.h"

#include <assert.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* The height above the leaves at which the k-nearest traversal stops and
 * scans contiguous ranges: 0 for a single leaf, else the largest h >= 1
 * (below the root) whose half-subtrees, of 2^(h-1) leaves, hold at most
 * KD_SCAN_POINTS points. Subtrees of one level differ in size by at most
 * one point, so the largest of height g holds ceil(n / 2^(depth-g)).
 * Scanning a few chunks costs less than descending to each leaf, whose
 * every level is a dependent load and a compare, while the branch-free
 * scan of a chunk costs the same however many of its points it keeps; too
 * long a range scans points far outside the radius at small k. 8 chunks
 * (ranges of up to 64-128 points) measured best of 4, 8 and 16 at k = 1,
 * 10 and 100 (results/bench.md has the figures). */
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

/* Splits inner node `node` over it[lo..hi): its axis and split value, the
 * range reordered so that [lo, mid) and [mid, hi) are its children's. */
static void split_node(kd_builder *b, uint32_t node, uint32_t lo, uint32_t hi)
{
    kd_tree *t = b->t;
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
}

static void build_node(kd_builder *b, uint32_t node, uint32_t lo, uint32_t hi, uint32_t level_leaves)
{
    kd_tree *t = b->t;
    if (level_leaves == 1) {
        uint32_t leaf = node - (t->nleaves - 1);
        t->leaf_start[leaf] = lo;
        return;
    }
    split_node(b, node, lo, hi);
    uint32_t mid = lo + (hi - lo) / 2;
    build_node(b, 2 * node + 1, lo, mid, level_leaves / 2);
    build_node(b, 2 * node + 2, mid, hi, level_leaves / 2);
}

/* The range of node j (from 0, left to right) of level `level` in a tree
 * over n points: the halvings from the root that build_node makes. */
static void node_range(uint32_t n, uint32_t level, uint64_t j, uint32_t *lo_out, uint32_t *hi_out)
{
    uint32_t lo = 0, hi = n;
    for (uint32_t d = level; d > 0; d--) {
        uint32_t mid = lo + (hi - lo) / 2;
        if ((j >> (d - 1)) & 1u)
            lo = mid;
        else
            hi = mid;
    }
    *lo_out = lo;
    *hi_out = hi;
}

#define KD_BLOCK 65536u /* items per block of the parallel copies */

typedef struct {
    kd_builder *b;
    const float *pts;
    uint32_t *perm;
    uint32_t n;
    uint32_t level;         /* the level being split, or the subtrees' level */
    float (*box)[2][3];     /* per block of the copy-out: min, max */
} kd_par;

static void fill_block(uint64_t blk, unsigned thread, void *arg)
{
    (void)thread;
    kd_par *kp = arg;
    kd_item *it = kp->b->it;
    uint32_t lo = (uint32_t)(blk * KD_BLOCK), hi = kp->n - lo < KD_BLOCK ? kp->n : lo + KD_BLOCK;
    for (uint32_t i = lo; i < hi; i++) {
        it[i].p[0] = kp->pts[3 * (size_t)i];
        it[i].p[1] = kp->pts[3 * (size_t)i + 1];
        it[i].p[2] = kp->pts[3 * (size_t)i + 2];
        it[i].id = i;
    }
}

/* Writes perm, x, y, z of one block and the block's bounds (min and max by
 * strict comparisons in item order, so blocks merged in block order give
 * what one pass over all items gives). */
static void out_block(uint64_t blk, unsigned thread, void *arg)
{
    (void)thread;
    kd_par *kp = arg;
    const kd_item *it = kp->b->it;
    kd_tree *t = kp->b->t;
    uint32_t lo = (uint32_t)(blk * KD_BLOCK), hi = kp->n - lo < KD_BLOCK ? kp->n : lo + KD_BLOCK;
    float mn[3] = {INFINITY, INFINITY, INFINITY}, mx[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (uint32_t i = lo; i < hi; i++) {
        const float *p = it[i].p;
        if (kp->perm)
            kp->perm[i] = it[i].id;
        t->x[i] = p[0];
        t->y[i] = p[1];
        t->z[i] = p[2];
        for (int a = 0; a < 3; a++) {
            mn[a] = p[a] < mn[a] ? p[a] : mn[a];
            mx[a] = p[a] > mx[a] ? p[a] : mx[a];
        }
    }
    memcpy(kp->box[blk][0], mn, sizeof mn);
    memcpy(kp->box[blk][1], mx, sizeof mx);
}

static void split_level_node(uint64_t j, unsigned thread, void *arg)
{
    (void)thread;
    kd_par *kp = arg;
    uint32_t lo, hi;
    node_range(kp->n, kp->level, j, &lo, &hi);
    split_node(kp->b, (uint32_t)((1u << kp->level) - 1 + j), lo, hi);
}

static void build_subtree(uint64_t j, unsigned thread, void *arg)
{
    (void)thread;
    kd_par *kp = arg;
    uint32_t lo, hi;
    node_range(kp->n, kp->level, j, &lo, &hi);
    build_node(kp->b, (uint32_t)((1u << kp->level) - 1 + j), lo, hi, kp->b->t->nleaves >> kp->level);
}

int kd_build(kd_tree *t, const float *pts, uint32_t n, uint32_t leaf_size, uint32_t *perm, unsigned threads)
{
    memset(t, 0, sizeof *t);
    if (leaf_size == 0)
        leaf_size = KD_DEFAULT_LEAF;
    if (threads == 0)
        threads = 1;
    uint32_t nleaves = 1;
    while ((uint64_t)nleaves * leaf_size < n)
        nleaves *= 2;
    t->n = n;
    t->nleaves = nleaves;
    t->scan_h = scan_height(n, nleaves);
    uint64_t nblocks = ((uint64_t)n + KD_BLOCK - 1) / KD_BLOCK;
    kd_item *it = mem_alloc(sizeof(kd_item) * (n ? n : 1));
    float(*box)[2][3] = malloc(sizeof *box * (nblocks ? nblocks : 1));
    t->split = mem_alloc(sizeof(float) * nleaves);
    t->axis = mem_alloc(nleaves);
    t->leaf_start = mem_alloc(sizeof(uint32_t) * (nleaves + 1));
    t->x = mem_zalloc(((size_t)n + KD_CHUNK) * sizeof(float));
    t->y = mem_zalloc(((size_t)n + KD_CHUNK) * sizeof(float));
    t->z = mem_zalloc(((size_t)n + KD_CHUNK) * sizeof(float));
    if (!it || !box || !t->split || !t->axis || !t->leaf_start || !t->x || !t->y || !t->z) {
        mem_free(it);
        free(box);
        kd_free(t);
        return -1;
    }
    kd_builder b = {it, t};
    kd_par kp = {&b, pts, perm, n, 0, box};
    parallel_for(threads, nblocks, fill_block, &kp);
    uint32_t depth = (uint32_t)__builtin_ctz(nleaves);
    if (threads == 1 || depth == 0) {
        build_node(&b, 0, 0, n, nleaves);
    } else {
        /* 2^top subtrees: eight or more per thread, for balance */
        uint32_t top = 3;
        while ((1u << (top - 3)) < threads && top < 16)
            top++;
        top = top < depth ? top : depth;
        for (kp.level = 0; kp.level < top; kp.level++)
            parallel_for(threads, (uint64_t)1 << kp.level, split_level_node, &kp);
        kp.level = top;
        parallel_for(threads, (uint64_t)1 << top, build_subtree, &kp);
    }
    t->leaf_start[nleaves] = n;
    parallel_for(threads, nblocks, out_block, &kp);
    for (int a = 0; a < 3; a++) {
        t->lo[a] = INFINITY;
        t->hi[a] = -INFINITY;
    }
    for (uint64_t k = 0; k < nblocks; k++)
        for (int a = 0; a < 3; a++) {
            t->lo[a] = box[k][0][a] < t->lo[a] ? box[k][0][a] : t->lo[a];
            t->hi[a] = box[k][1][a] > t->hi[a] ? box[k][1][a] : t->hi[a];
        }
    free(box);
    mem_free(it);
    return 0;
}

void kd_free(kd_tree *t)
{
    mem_free(t->split);
    mem_free(t->axis);
    mem_free(t->leaf_start);
    mem_free(t->x);
    mem_free(t->y);
    mem_free(t->z);
    memset(t, 0, sizeof *t);
}

size_t kd_bytes(const kd_tree *t)
{
    size_t pts = (size_t)t->n + (t->x ? KD_CHUNK : 0);
    return pts * 3 * sizeof(float) + (size_t)t->nleaves * (sizeof(float) + 1 + sizeof(uint32_t)) + sizeof(uint32_t);
}

/* What kd_bytes reports for a tree over n points: the coordinates with
 * their padding and the nodes. A double, like kd_build_peak_bytes. */
double kd_tree_bytes(double n, uint32_t leaf_size)
{
    if (leaf_size == 0)
        leaf_size = KD_DEFAULT_LEAF;
    double nleaves = 1.0;
    while (nleaves * leaf_size < n)
        nleaves *= 2.0;
    return (n + KD_CHUNK) * 3.0 * sizeof(float) + nleaves * (sizeof(float) + 1 + sizeof(uint32_t)) +
           sizeof(uint32_t);
}

/* kd_build's peak: its working copy of the points (kd_item, at least one)
 * beside the tree's arrays. */
double kd_build_peak_bytes(double n, uint32_t leaf_size)
{
    return (n > 1.0 ? n : 1.0) * (double)sizeof(kd_item) + kd_tree_bytes(n, leaf_size);
}

/* kdtree_build: the tree's construction (kd_build, kd_build_items), its
 * scan height and its memory (renderer/README.md). */
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

/* kd_build partitions a working copy of the points with their input
 * indices (16 bytes each), so every pass reads memory in order;
 * kd_build_items partitions the caller's items in place. */
typedef struct {
    float p[3];
    uint32_t id;
} kd_item;

#define KD_T kd_item
#define KD_S(name) name##_id
#include "kdtree_build.inc"
#undef KD_T
#undef KD_S

#define KD_T kd_build_item
#define KD_S(name) name##_items
#include "kdtree_build.inc"
#undef KD_T
#undef KD_S

#define KD_BLOCK 65536u /* items per block of the parallel copies */

typedef struct {
    const float *pts;    /* kd_build's input points */
    kd_item *it;         /* kd_build's working copy */
    const char *items;   /* the items in leaf order (either kind) */
    size_t stride;       /* bytes from one item to the next */
    uint32_t *perm;      /* kd_build's perm, or NULL */
    kd_tree *t;
    uint32_t n;
    float (*box)[2][3];  /* per block of the copy-out: min, max */
} kd_par;

static void fill_block(uint64_t blk, unsigned thread, void *arg)
{
    (void)thread;
    kd_par *kp = arg;
    kd_item *it = kp->it;
    uint32_t lo = (uint32_t)(blk * KD_BLOCK), hi = kp->n - lo < KD_BLOCK ? kp->n : lo + KD_BLOCK;
    for (uint32_t i = lo; i < hi; i++) {
        it[i].p[0] = kp->pts[3 * (size_t)i];
        it[i].p[1] = kp->pts[3 * (size_t)i + 1];
        it[i].p[2] = kp->pts[3 * (size_t)i + 2];
        it[i].id = i;
    }
}

/* Writes x, y, z (and perm, for kd_build) of one block and the block's
 * bounds (min and max by strict comparisons in item order, so blocks
 * merged in block order give what one pass over all items gives). */
static void out_block(uint64_t blk, unsigned thread, void *arg)
{
    (void)thread;
    kd_par *kp = arg;
    kd_tree *t = kp->t;
    uint32_t lo = (uint32_t)(blk * KD_BLOCK), hi = kp->n - lo < KD_BLOCK ? kp->n : lo + KD_BLOCK;
    float mn[3] = {INFINITY, INFINITY, INFINITY}, mx[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (uint32_t i = lo; i < hi; i++) {
        const float *p = (const float *)(const void *)(kp->items + (size_t)i * kp->stride);
        if (kp->perm)
            kp->perm[i] = kp->it[i].id;
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

/* Sets up t for n points (its shape and arrays) and kp's block bounds.
 * Returns PM_OK, or PM_ERR_NOMEM (t is then empty). */
static pm_status tree_begin(kd_tree *t, uint32_t n, uint32_t leaf_size, kd_par *kp)
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
    uint64_t nblocks = ((uint64_t)n + KD_BLOCK - 1) / KD_BLOCK;
    kp->t = t;
    kp->n = n;
    kp->box = mem_alloc(sizeof *kp->box * (nblocks ? nblocks : 1));
    t->split = mem_alloc(sizeof(float) * nleaves);
    t->axis = mem_alloc(nleaves);
    t->leaf_start = mem_alloc(sizeof(uint32_t) * (nleaves + 1));
    t->x = mem_zalloc(((size_t)n + KD_CHUNK) * sizeof(float));
    t->y = mem_zalloc(((size_t)n + KD_CHUNK) * sizeof(float));
    t->z = mem_zalloc(((size_t)n + KD_CHUNK) * sizeof(float));
    if (!kp->box || !t->split || !t->axis || !t->leaf_start || !t->x || !t->y || !t->z) {
        mem_free(kp->box);
        kp->box = NULL;
        kd_free(t);
        return PM_ERR_NOMEM;
    }
    return PM_OK;
}

/* Copies the points (in leaf order in kp->items) out to the tree's arrays
 * and sets its bounds; frees kp's block bounds. */
static void tree_end(kd_par *kp, unsigned threads)
{
    kd_tree *t = kp->t;
    uint64_t nblocks = ((uint64_t)kp->n + KD_BLOCK - 1) / KD_BLOCK;
    parallel_for(threads, nblocks, out_block, kp);
    for (int a = 0; a < 3; a++) {
        t->lo[a] = INFINITY;
        t->hi[a] = -INFINITY;
    }
    for (uint64_t k = 0; k < nblocks; k++)
        for (int a = 0; a < 3; a++) {
            t->lo[a] = kp->box[k][0][a] < t->lo[a] ? kp->box[k][0][a] : t->lo[a];
            t->hi[a] = kp->box[k][1][a] > t->hi[a] ? kp->box[k][1][a] : t->hi[a];
        }
    mem_free(kp->box);
    kp->box = NULL;
}

pm_status kd_build(kd_tree *t, const float *pts, uint32_t n, uint32_t leaf_size, uint32_t *perm, unsigned threads)
{
    kd_par kp = {pts, NULL, NULL, sizeof(kd_item), perm, t, n, NULL};
    pm_status rc;
    if ((rc = tree_begin(t, n, leaf_size, &kp)) != PM_OK)
        return rc;
    kp.it = mem_alloc(sizeof(kd_item) * (n ? n : 1));
    if (!kp.it) {
        mem_free(kp.box);
        kd_free(t);
        return PM_ERR_NOMEM;
    }
    kp.items = (const char *)kp.it;
    threads = threads ? threads : 1;
    parallel_for(threads, ((uint64_t)n + KD_BLOCK - 1) / KD_BLOCK, fill_block, &kp);
    builder_id b = {kp.it, t};
    build_all_id(&b, n, threads);
    tree_end(&kp, threads);
    mem_free(kp.it);
    return PM_OK;
}

pm_status kd_build_items(kd_tree *t, kd_build_item *items, uint32_t n, uint32_t leaf_size, unsigned threads)
{
    assert(items || n == 0);
    kd_par kp = {NULL, NULL, (const char *)items, sizeof(kd_build_item), NULL, t, n, NULL};
    pm_status rc;
    if ((rc = tree_begin(t, n, leaf_size, &kp)) != PM_OK)
        return rc;
    threads = threads ? threads : 1;
    builder_items b = {items, t};
    build_all_items(&b, n, threads);
    tree_end(&kp, threads);
    return PM_OK;
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

/* kdtree: build by recursive median split on the widest axis (quickselect),
 * search by depth-first descent with the incremental cell distance of Arya &
 * Mount (each cell's squared distance is updated per axis, so far cells are
 * pruned without storing boxes). Small k keeps a sorted array, large k a
 * max-heap. */
#include "kdtree.h"

#include <assert.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define KD_SMALL_K 16u
#define KD_MAX_DEPTH 40

/* ---- build ---- */

typedef struct {
    const float *pts;
    uint32_t *perm;
    kd_tree *t;
} kd_builder;

static float coord(const kd_builder *b, uint32_t i, int axis)
{
    return b->pts[3 * (size_t)b->perm[i] + axis];
}

/* Reorders perm[lo..hi) so that the element at position k is the one a full
 * sort by `axis` would put there, with smaller-or-equal ones before it. */
static void select_kth(kd_builder *b, uint32_t lo, uint32_t hi, uint32_t k, int axis)
{
    uint32_t *p = b->perm;
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
                uint32_t tmp = p[lt]; p[lt] = p[i]; p[i] = tmp;
                lt++; i++;
            } else if (v > pivot) {
                gt--;
                uint32_t tmp = p[gt]; p[gt] = p[i]; p[i] = tmp;
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
    uint32_t *own = perm ? perm : malloc(sizeof(uint32_t) * (n ? n : 1));
    t->split = malloc(sizeof(float) * nleaves);
    t->axis = malloc(nleaves);
    t->leaf_start = malloc(sizeof(uint32_t) * (nleaves + 1));
    t->x = malloc(sizeof(float) * (n ? n : 1));
    t->y = malloc(sizeof(float) * (n ? n : 1));
    t->z = malloc(sizeof(float) * (n ? n : 1));
    if (!own || !t->split || !t->axis || !t->leaf_start || !t->x || !t->y || !t->z) {
        if (!perm)
            free(own);
        kd_free(t);
        return -1;
    }
    for (uint32_t i = 0; i < n; i++)
        own[i] = i;
    kd_builder b = {pts, own, t};
    build_node(&b, 0, 0, n, nleaves);
    t->leaf_start[nleaves] = n;
    for (int a = 0; a < 3; a++) {
        t->lo[a] = INFINITY;
        t->hi[a] = -INFINITY;
    }
    for (uint32_t i = 0; i < n; i++) {
        const float *p = pts + 3 * (size_t)own[i];
        t->x[i] = p[0];
        t->y[i] = p[1];
        t->z[i] = p[2];
        for (int a = 0; a < 3; a++) {
            t->lo[a] = p[a] < t->lo[a] ? p[a] : t->lo[a];
            t->hi[a] = p[a] > t->hi[a] ? p[a] : t->hi[a];
        }
    }
    if (!perm)
        free(own);
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
    return (size_t)t->n * 3 * sizeof(float) + (size_t)t->nleaves * (sizeof(float) + 1 + sizeof(uint32_t)) +
           sizeof(uint32_t);
}

/* ---- k nearest ---- */

typedef struct {
    uint32_t k, n;
    float worst; /* the k-th distance when full, else the cap */
    uint32_t *idx;
    float *d2;
} kd_result;

static inline void result_add(kd_result *r, uint32_t i, float d)
{
    if (r->k <= KD_SMALL_K) {
        /* sorted insertion, ascending */
        uint32_t j = r->n < r->k ? r->n++ : r->k - 1;
        while (j > 0 && r->d2[j - 1] > d) {
            r->d2[j] = r->d2[j - 1];
            r->idx[j] = r->idx[j - 1];
            j--;
        }
        r->d2[j] = d;
        r->idx[j] = i;
        if (r->n == r->k)
            r->worst = r->d2[r->k - 1];
        return;
    }
    /* max-heap on d2 */
    if (r->n < r->k) {
        uint32_t j = r->n++;
        while (j > 0) {
            uint32_t parent = (j - 1) / 2;
            if (r->d2[parent] >= d)
                break;
            r->d2[j] = r->d2[parent];
            r->idx[j] = r->idx[parent];
            j = parent;
        }
        r->d2[j] = d;
        r->idx[j] = i;
        if (r->n == r->k)
            r->worst = r->d2[0];
        return;
    }
    /* replace the root and sift down */
    uint32_t j = 0, n = r->n;
    for (;;) {
        uint32_t c = 2 * j + 1;
        if (c >= n)
            break;
        if (c + 1 < n && r->d2[c + 1] > r->d2[c])
            c++;
        if (r->d2[c] <= d)
            break;
        r->d2[j] = r->d2[c];
        r->idx[j] = r->idx[c];
        j = c;
    }
    r->d2[j] = d;
    r->idx[j] = i;
    r->worst = r->d2[0];
}

static void knn_node(const kd_tree *t, uint32_t node, const float q[3], float rd, float off[3], kd_result *r)
{
    uint32_t first_leaf = t->nleaves - 1;
    if (node >= first_leaf) {
        uint32_t leaf = node - first_leaf;
        uint32_t end = t->leaf_start[leaf + 1];
        for (uint32_t i = t->leaf_start[leaf]; i < end; i++) {
            float dx = t->x[i] - q[0], dy = t->y[i] - q[1], dz = t->z[i] - q[2];
            float d = dx * dx + dy * dy + dz * dz;
            if (r->n < r->k ? d <= r->worst : d < r->worst)
                result_add(r, i, d);
        }
        return;
    }
    int a = t->axis[node];
    float diff = q[a] - t->split[node];
    uint32_t near = diff < 0.0f ? 2 * node + 1 : 2 * node + 2;
    uint32_t far = diff < 0.0f ? 2 * node + 2 : 2 * node + 1;
    knn_node(t, near, q, rd, off, r);
    float old = off[a];
    float nrd = rd - old * old + diff * diff;
    if (nrd <= r->worst) {
        off[a] = diff;
        knn_node(t, far, q, nrd, off, r);
        off[a] = old;
    }
}

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

uint32_t kd_knn(const kd_tree *t, const float q[3], uint32_t k, float max_d2, uint32_t *idx, float *d2, float *r2)
{
    *r2 = 0.0f;
    if (k == 0 || t->n == 0)
        return 0;
    kd_result r = {k, 0, max_d2, idx, d2};
    float off[3];
    float rd = root_offsets(t, q, off);
    if (rd <= max_d2)
        knn_node(t, 0, q, rd, off, &r);
    if (r.n > 0)
        *r2 = k <= KD_SMALL_K ? r.d2[r.n - 1] : r.d2[0];
    return r.n;
}

/* ---- nearest with a predicate ---- */

typedef struct {
    kd_pred pred;
    const void *ctx;
    uint32_t best;
    float best_d2;
} kd_nearest;

static void nearest_node(const kd_tree *t, uint32_t node, const float q[3], float rd, float off[3], kd_nearest *s)
{
    uint32_t first_leaf = t->nleaves - 1;
    if (node >= first_leaf) {
        uint32_t leaf = node - first_leaf;
        uint32_t end = t->leaf_start[leaf + 1];
        for (uint32_t i = t->leaf_start[leaf]; i < end; i++) {
            float dx = t->x[i] - q[0], dy = t->y[i] - q[1], dz = t->z[i] - q[2];
            float d = dx * dx + dy * dy + dz * dz;
            if (d <= s->best_d2 && (s->best == KD_NONE || d < s->best_d2) && (!s->pred || s->pred(i, s->ctx))) {
                s->best = i;
                s->best_d2 = d;
            }
        }
        return;
    }
    int a = t->axis[node];
    float diff = q[a] - t->split[node];
    uint32_t near = diff < 0.0f ? 2 * node + 1 : 2 * node + 2;
    uint32_t far = diff < 0.0f ? 2 * node + 2 : 2 * node + 1;
    nearest_node(t, near, q, rd, off, s);
    float old = off[a];
    float nrd = rd - old * old + diff * diff;
    if (nrd <= s->best_d2) {
        off[a] = diff;
        nearest_node(t, far, q, nrd, off, s);
        off[a] = old;
    }
}

uint32_t kd_nearest_if(const kd_tree *t, const float q[3], float max_d2, kd_pred pred, const void *ctx, float *d2)
{
    kd_nearest s = {pred, ctx, KD_NONE, max_d2};
    if (t->n > 0) {
        float off[3];
        float rd = root_offsets(t, q, off);
        if (rd <= max_d2)
            nearest_node(t, 0, q, rd, off, &s);
    }
    *d2 = s.best == KD_NONE ? 0.0f : s.best_d2;
    return s.best;
}

/* bvh: building and walking the bounding-volume hierarchy
 * (renderer/README.md, "Ray casting"). */
#include "bvh.h"

#include <assert.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/* Centroid bins of the surface-area heuristic, and the cost of visiting an
 * inner node relative to one shape test. */
#define BVH_BINS 16
#define BVH_COST_NODE 1.0

typedef struct {
    double lo[3], hi[3]; /* padded bounds of everything below */
    uint32_t index;      /* leaf: first entry in prims; inner: the second child */
    uint32_t count;      /* leaf: how many shapes (> 0); inner: 0 */
    uint32_t axis;       /* inner: the split axis (the nearer child is visited first) */
} bvh_node;

struct bvh {
    bvh_node *nodes;
    size_t nnodes;
    uint32_t *prims;  /* shape indices, leaf by leaf */
    size_t nprims;
    double reach;     /* ray origins with a larger |coordinate| take the linear loop */
    size_t depth, leaves, max_leaf;
};

/* An axis-aligned box. */
typedef struct {
    double lo[3], hi[3];
} box;

static void box_empty(box *b)
{
    for (int k = 0; k < 3; k++) {
        b->lo[k] = INFINITY;
        b->hi[k] = -INFINITY;
    }
}

static void box_grow(box *b, const box *a)
{
    for (int k = 0; k < 3; k++) {
        b->lo[k] = fmin(b->lo[k], a->lo[k]);
        b->hi[k] = fmax(b->hi[k], a->hi[k]);
    }
}

static double box_area(const box *b)
{
    double d[3];
    for (int k = 0; k < 3; k++)
        d[k] = b->hi[k] > b->lo[k] ? b->hi[k] - b->lo[k] : 0.0;
    return 2.0 * (d[0] * d[1] + d[1] * d[2] + d[2] * d[0]);
}

/* What the build works on: each shape's box and centre. */
typedef struct {
    box *boxes;
    double (*centre)[3];
    uint32_t *prims;
    bvh_node *nodes;
    size_t nnodes, cap;
    double pad;
    size_t depth, leaves, max_leaf;
} builder;

static void make_leaf(builder *bd, size_t node, size_t begin, size_t end, size_t depth)
{
    bvh_node *nd = &bd->nodes[node];
    nd->index = (uint32_t)begin;
    nd->count = (uint32_t)(end - begin);
    nd->axis = 0;
    assert(nd->count > 0);
    bd->leaves++;
    if (end - begin > bd->max_leaf)
        bd->max_leaf = end - begin;
    if (depth > bd->depth)
        bd->depth = depth;
}

/* The bin of centre c along an axis whose centres span [lo, lo + BVH_BINS /
 * scale); NaN (never expected: scale is finite) goes to bin 0. */
static int bin_of(double c, double lo, double scale)
{
    double f = (c - lo) * scale;
    if (!(f >= 0.0))
        return 0;
    return f >= BVH_BINS - 1 ? BVH_BINS - 1 : (int)f;
}

/* Builds the subtree of prims[begin, end) into node `node` (already
 * allocated), at depth `depth` (the root is 1). */
static void build_node(builder *bd, size_t node, size_t begin, size_t end, size_t depth)
{
    assert(begin < end && node < bd->nnodes);
    box bounds, cbounds;
    box_empty(&bounds);
    box_empty(&cbounds);
    for (size_t i = begin; i < end; i++) {
        uint32_t s = bd->prims[i];
        box_grow(&bounds, &bd->boxes[s]);
        box c = {{bd->centre[s][0], bd->centre[s][1], bd->centre[s][2]},
                 {bd->centre[s][0], bd->centre[s][1], bd->centre[s][2]}};
        box_grow(&cbounds, &c);
    }
    bvh_node *nd = &bd->nodes[node];
    for (int k = 0; k < 3; k++) {
        nd->lo[k] = bounds.lo[k] - bd->pad;
        nd->hi[k] = bounds.hi[k] + bd->pad;
    }
    size_t n = end - begin;
    if (n == 1 || depth >= BVH_MAX_DEPTH) {
        make_leaf(bd, node, begin, end, depth);
        return;
    }

    /* the best split over all three axes by the binned surface-area heuristic */
    double best_cost = INFINITY, parent_area = box_area(&bounds);
    int best_axis = -1, best_split = 0;
    double best_scale = 0.0;
    for (int k = 0; k < 3; k++) {
        double extent = cbounds.hi[k] - cbounds.lo[k];
        double scale = BVH_BINS / extent * (1.0 - 1e-9);
        /* no spread, or one so small (subnormal) that its reciprocal
         * overflows: nothing to split along this axis */
        if (!(extent > 0.0) || !isfinite(scale))
            continue;
        box bin_box[BVH_BINS];
        size_t bin_n[BVH_BINS] = {0};
        for (int j = 0; j < BVH_BINS; j++)
            box_empty(&bin_box[j]);
        for (size_t i = begin; i < end; i++) {
            uint32_t s = bd->prims[i];
            int j = bin_of(bd->centre[s][k], cbounds.lo[k], scale);
            bin_n[j]++;
            box_grow(&bin_box[j], &bd->boxes[s]);
        }
        /* areas and counts left of each of the BVH_BINS - 1 planes */
        double left_area[BVH_BINS];
        size_t left_n[BVH_BINS];
        box acc;
        box_empty(&acc);
        size_t cnt = 0;
        for (int j = 0; j < BVH_BINS - 1; j++) {
            box_grow(&acc, &bin_box[j]);
            cnt += bin_n[j];
            left_area[j] = box_area(&acc);
            left_n[j] = cnt;
        }
        box_empty(&acc);
        cnt = 0;
        for (int j = BVH_BINS - 1; j >= 1; j--) {
            box_grow(&acc, &bin_box[j]);
            cnt += bin_n[j];
            size_t nl = left_n[j - 1];
            if (nl == 0 || cnt == 0)
                continue;
            double cost = BVH_COST_NODE +
                          (parent_area > 0.0 ? (left_area[j - 1] * (double)nl + box_area(&acc) * (double)cnt) / parent_area
                                             : (double)n);
            if (cost < best_cost) {
                best_cost = cost;
                best_axis = k;
                best_split = j; /* bins [0, j) go left */
                best_scale = scale;
            }
        }
    }
    /* a leaf when no split exists (all centres equal) or when a small node
     * is cheaper to test whole */
    if (best_axis < 0 || (n <= BVH_LEAF_MAX && best_cost >= (double)n)) {
        make_leaf(bd, node, begin, end, depth);
        return;
    }

    /* partition in place: bins [0, best_split) first */
    size_t mid = begin;
    for (size_t i = begin; i < end; i++) {
        uint32_t s = bd->prims[i];
        if (bin_of(bd->centre[s][best_axis], cbounds.lo[best_axis], best_scale) < best_split) {
            bd->prims[i] = bd->prims[mid];
            bd->prims[mid++] = s;
        }
    }
    assert(mid > begin && mid < end);
    /* children: the first right after this node (depth-first order), the
     * second after the first's subtree */
    assert(bd->nnodes + 1 <= bd->cap);
    size_t first = bd->nnodes++;
    assert(first == node + 1);
    build_node(bd, first, begin, mid, depth + 1);
    assert(bd->nnodes + 1 <= bd->cap);
    size_t second = bd->nnodes++;
    build_node(bd, second, mid, end, depth + 1);
    nd = &bd->nodes[node];
    nd->index = (uint32_t)second;
    nd->count = 0;
    nd->axis = (uint32_t)best_axis;
}

bvh *bvh_build(const shape *shapes, size_t n, double reach)
{
    assert(shapes && n >= 1 && n <= UINT32_MAX && reach >= 0.0);
    bvh *b = calloc(1, sizeof *b);
    builder bd;
    memset(&bd, 0, sizeof bd);
    bd.cap = 2 * n - 1; /* a binary tree with at most n leaves */
    if (b) {
        bd.boxes = malloc(n * sizeof *bd.boxes);
        bd.centre = malloc(n * sizeof *bd.centre);
        bd.prims = malloc(n * sizeof *bd.prims);
        bd.nodes = malloc(bd.cap * sizeof *bd.nodes);
    }
    if (!b || !bd.boxes || !bd.centre || !bd.prims || !bd.nodes) {
        free(bd.boxes);
        free(bd.centre);
        free(bd.prims);
        free(bd.nodes);
        free(b);
        return NULL;
    }
    double magnitude = reach;
    for (size_t i = 0; i < n; i++) {
        vec3 lo, hi;
        shape_bounds(&shapes[i], &lo, &hi);
        bd.boxes[i] = (box){{lo.x, lo.y, lo.z}, {hi.x, hi.y, hi.z}};
        for (int k = 0; k < 3; k++) {
            bd.centre[i][k] = 0.5 * bd.boxes[i].lo[k] + 0.5 * bd.boxes[i].hi[k];
            magnitude = fmax(magnitude, fmax(fabs(bd.boxes[i].lo[k]), fabs(bd.boxes[i].hi[k])));
        }
        bd.prims[i] = (uint32_t)i;
    }
    assert(isfinite(magnitude));
    bd.pad = BVH_PAD_REL * magnitude;
    bd.nnodes = 1;
    build_node(&bd, 0, 0, n, 1);
    assert(bd.nnodes <= bd.cap && bd.leaves >= 1);
    free(bd.boxes);
    free(bd.centre);
    b->nodes = bd.nodes;
    b->nnodes = bd.nnodes;
    b->prims = bd.prims;
    b->nprims = n;
    /* spawned rays start a hair off the outermost surfaces */
    b->reach = magnitude * (1.0 + 1e-6);
    b->depth = bd.depth;
    b->leaves = bd.leaves;
    b->max_leaf = bd.max_leaf;
    return b;
}

void bvh_free(bvh *b)
{
    if (!b)
        return;
    free(b->nodes);
    free(b->prims);
    free(b);
}

bvh_info bvh_describe(const bvh *b)
{
    bvh_info info = {b->nprims, b->nnodes, b->leaves, b->depth, b->max_leaf};
    return info;
}

/* ---- queries ---- */

/* A ray prepared for box tests: per axis the reciprocal direction, or
 * `parallel` when the direction is 0 (or so small that its reciprocal
 * overflows: the ray then moves less than 2^-1000 of its length along the
 * axis, far below any box padding). */
typedef struct {
    double o[3], inv[3];
    int parallel[3];
} prepared;

static prepared prepare(const shape_ray *r)
{
    prepared p;
    double d[3] = {r->dir.x, r->dir.y, r->dir.z};
    p.o[0] = r->origin.x;
    p.o[1] = r->origin.y;
    p.o[2] = r->origin.z;
    for (int k = 0; k < 3; k++) {
        p.inv[k] = 1.0 / d[k];
        p.parallel[k] = d[k] == 0.0 || !isfinite(p.inv[k]);
    }
    return p;
}

/* Whether the ray meets the node's box at some t in [0, tfar]. Inclusive at
 * both ends: a shape tying the best t so far must still be visited. */
static int box_hit(const bvh_node *nd, const prepared *p, double tfar)
{
    double t0 = 0.0, t1 = tfar;
    for (int k = 0; k < 3; k++) {
        if (p->parallel[k]) {
            if (p->o[k] < nd->lo[k] || p->o[k] > nd->hi[k])
                return 0;
            continue;
        }
        double ta = (nd->lo[k] - p->o[k]) * p->inv[k];
        double tb = (nd->hi[k] - p->o[k]) * p->inv[k];
        if (ta > tb) {
            double tmp = ta;
            ta = tb;
            tb = tmp;
        }
        t0 = ta > t0 ? ta : t0;
        t1 = tb < t1 ? tb : t1;
        if (t0 > t1)
            return 0;
    }
    return 1;
}

static double max_abs3(vec3 v)
{
    return fmax(fabs(v.x), fmax(fabs(v.y), fabs(v.z)));
}

/* The linear loop the tree must agree with (also the answer for origins
 * beyond the reach). */
static int linear_intersect(const shape *shapes, size_t n, const shape_ray *r, double tmax, double *t)
{
    int best = -1;
    double tt;
    for (size_t i = 0; i < n; i++)
        if (shape_intersect(&shapes[i], r, 0.0, tmax, &tt)) {
            tmax = tt;
            best = (int)i;
        }
    if (best >= 0)
        *t = tmax;
    return best;
}

int bvh_intersect_counted(const bvh *b, const shape *shapes, const shape_ray *r, double tmax, double *t,
                          uint64_t *tests)
{
    assert(b && shapes && r && t && tests);
    if (!(max_abs3(r->origin) <= b->reach)) {
        *tests += b->nprims;
        return linear_intersect(shapes, b->nprims, r, tmax, t);
    }
    uint64_t n = 0;
    prepared p = prepare(r);
    uint32_t stack[BVH_MAX_DEPTH + 1];
    int top = 0;
    uint32_t node = 0;
    int best = -1;
    double best_t = tmax;
    for (;;) {
        const bvh_node *nd = &b->nodes[node];
        if (box_hit(nd, &p, best_t)) {
            if (nd->count == 0) {
                /* nearer child first: the first child holds the smaller centres */
                uint32_t first = node + 1, second = nd->index;
                int flip = p.inv[nd->axis] < 0.0;
                assert(top < BVH_MAX_DEPTH);
                stack[top++] = flip ? first : second;
                node = flip ? second : first;
                continue;
            }
            n += nd->count;
            for (uint32_t j = 0; j < nd->count; j++) {
                uint32_t s = b->prims[nd->index + j];
                /* a hit at best_t itself may win the tie by a lower index */
                double limit = best < 0 ? tmax : nextafter(best_t, INFINITY);
                double tt;
                if (shape_intersect(&shapes[s], r, 0.0, limit, &tt) &&
                    (best < 0 || tt < best_t || (tt == best_t && (int)s < best))) {
                    best = (int)s;
                    best_t = tt;
                }
            }
        }
        if (top == 0)
            break;
        node = stack[--top];
    }
    if (best >= 0)
        *t = best_t;
    *tests += n;
    return best;
}

int bvh_intersect(const bvh *b, const shape *shapes, const shape_ray *r, double tmax, double *t)
{
    uint64_t tests = 0;
    return bvh_intersect_counted(b, shapes, r, tmax, t, &tests);
}

int bvh_occluded_counted(const bvh *b, const shape *shapes, const shape_ray *r, double tmax, uint64_t *tests)
{
    assert(b && shapes && r && tests);
    double tt;
    if (!(max_abs3(r->origin) <= b->reach)) {
        *tests += b->nprims;
        return linear_intersect(shapes, b->nprims, r, tmax, &tt) >= 0;
    }
    uint64_t n = 0;
    prepared p = prepare(r);
    uint32_t stack[BVH_MAX_DEPTH + 1];
    int top = 0;
    uint32_t node = 0;
    for (;;) {
        const bvh_node *nd = &b->nodes[node];
        if (box_hit(nd, &p, tmax)) {
            if (nd->count == 0) {
                assert(top < BVH_MAX_DEPTH);
                stack[top++] = nd->index;
                node = node + 1;
                continue;
            }
            for (uint32_t j = 0; j < nd->count; j++) {
                n++;
                if (shape_intersect(&shapes[b->prims[nd->index + j]], r, 0.0, tmax, &tt)) {
                    *tests += n;
                    return 1;
                }
            }
        }
        if (top == 0) {
            *tests += n;
            return 0;
        }
        node = stack[--top];
    }
}

int bvh_occluded(const bvh *b, const shape *shapes, const shape_ray *r, double tmax)
{
    uint64_t tests = 0;
    return bvh_occluded_counted(b, shapes, r, tmax, &tests);
}

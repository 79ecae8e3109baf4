/* bvh: a bounding-volume hierarchy over a scene's shapes (boxes and a
 * permutation; the shapes stay in the scene). Its answers are exactly the
 * linear loop's (renderer/README.md, "Ray casting"). */
#ifndef PM_BVH_H
#define PM_BVH_H

#include <stddef.h>
#include <stdint.h>

#include "shapes.h"

typedef struct bvh bvh;

/* At most this many shapes in a leaf (fewer when the split pays). */
#define BVH_LEAF_MAX 4
/* The tree is at most this deep; a node that would go deeper is a leaf. */
#define BVH_MAX_DEPTH 60
/* Box padding, relative to the largest |coordinate| of the shapes and ray
 * origins (2^-36: some 2^16 times the rounding of a hit point). */
#define BVH_PAD_REL 0x1p-36

/* Builds the tree over shapes[0..n) (1 <= n <= UINT32_MAX); `reach` bounds
 * the |coordinates| of ray origins it serves by box tests. Pass the same
 * array to the queries. Returns NULL when memory runs out. */
bvh *bvh_build(const shape *shapes, size_t n, double reach);
/* Frees the tree; NULL is fine. */
void bvh_free(bvh *b);

/* Returns the index of the nearest shape r hits in (0, tmax) (lowest index
 * on ties) and sets *t, or -1 on a miss. */
int bvh_intersect(const bvh *b, const shape *shapes, const shape_ray *r, double tmax, double *t);
/* 1 if any shape has a hit of r in (0, tmax), else 0. */
int bvh_occluded(const bvh *b, const shape *shapes, const shape_ray *r, double tmax);
/* The same, adding the shape tests made (shape_intersect calls) to *tests. */
int bvh_intersect_counted(const bvh *b, const shape *shapes, const shape_ray *r, double tmax, double *t,
                          uint64_t *tests);
int bvh_occluded_counted(const bvh *b, const shape *shapes, const shape_ray *r, double tmax, uint64_t *tests);

/* For tests and reports: the number of shapes, nodes, leaves, the depth
 * (a single leaf has depth 1), and the most shapes in one leaf. */
typedef struct {
    size_t shapes, nodes, leaves, depth, max_leaf;
} bvh_info;
bvh_info bvh_describe(const bvh *b);

#endif

/* bvh: a bounding-volume hierarchy over a scene's shapes, so that a ray
 * meets O(log n) shapes instead of all n. It owns only the tree (boxes and a
 * permutation of shape indices); the shapes stay in the scene's array.
 *
 * Exactness contract: bvh_intersect returns exactly what a linear loop over
 * the shapes in index order returns (the shape with the smallest t that
 * shape_intersect finds in (0, tmax), the lowest index among equal t), and
 * bvh_occluded returns 1 exactly when some shape has such a t. The boxes are
 * padded (BVH_PAD_REL of the coordinates' magnitude) far beyond the rounding
 * of a hit point, so a box never culls a hit its shape test would report;
 * a ray whose origin lies beyond the `reach` given at build time (where that
 * argument does not hold) is answered by the linear loop. */
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

/* Builds the tree over shapes[0..n) (n >= 1, at most UINT32_MAX). `reach`
 * bounds |coordinate| of the ray origins the tree will serve exactly by box
 * tests (the scene passes the largest of its bounds and its camera); it sets
 * the padding. Returns NULL when memory runs out. The tree does not keep a
 * pointer to shapes; pass the same array to the queries. Time O(n log n). */
bvh *bvh_build(const shape *shapes, size_t n, double reach);
/* Frees the tree; NULL is fine. */
void bvh_free(bvh *b);

/* The nearest hit of r in (0, tmax) among the n shapes the tree was built
 * over: returns the shape's index and sets *t, or -1 on a miss. */
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

/* kdtree: a static 3-d kd-tree over float points with exact k-nearest and
 * nearest-with-predicate queries. It knows points only, not photons: the
 * build returns the leaf-order permutation so the caller can lay its own
 * payload out in the same order (index i of the tree = index i of payload).
 *
 * Layout: a complete binary tree in implicit heap order (node i has children
 * 2i+1, 2i+2), pointer-free inner nodes (split value + axis), leaves of at
 * most `leaf_size` points stored contiguously as x[], y[], z[] arrays. */
#ifndef PM_KDTREE_H
#define PM_KDTREE_H

#include <stddef.h>
#include <stdint.h>

#define KD_DEFAULT_LEAF 12u
#define KD_NONE UINT32_MAX

typedef struct {
    uint32_t n;           /* points */
    uint32_t nleaves;     /* a power of two (1 when n <= leaf size) */
    float *split;         /* nleaves-1 inner nodes */
    uint8_t *axis;        /* nleaves-1 inner nodes */
    uint32_t *leaf_start; /* nleaves+1 offsets into x, y, z */
    float *x, *y, *z;     /* points in leaf order (+ padding, see kdtree.c) */
    float lo[3], hi[3];   /* bounds of all points */
} kd_tree;

/* Builds a tree over n points (xyz triples in pts). If perm is not NULL it
 * receives n entries: perm[i] = input index of the point at leaf position i.
 * Returns 0, or -1 when memory runs out (the tree is then empty and safe to
 * kd_free). n may be 0. */
int kd_build(kd_tree *t, const float *pts, uint32_t n, uint32_t leaf_size, uint32_t *perm);
/* Frees the tree's arrays; the struct is left empty. A zeroed tree is fine. */
void kd_free(kd_tree *t);
/* Bytes of memory the tree holds. */
size_t kd_bytes(const kd_tree *t);

/* The k nearest points to q with squared distance <= max_d2 (INFINITY: no
 * cap). Writes up to k leaf-order indices and squared distances to idx/d2
 * (in no particular order) and returns how many it found; *r2 receives the
 * largest squared distance among them (0 if none). Exact. */
uint32_t kd_knn(const kd_tree *t, const float q[3], uint32_t k, float max_d2, uint32_t *idx, float *d2,
                float *r2);

/* Predicate for kd_nearest_if: nonzero when leaf-order point i qualifies. */
typedef int (*kd_pred)(uint32_t i, const void *ctx);

/* The nearest qualifying point within max_d2 of q: returns its leaf-order
 * index and sets *d2, or returns KD_NONE when none qualifies. Exact. */
uint32_t kd_nearest_if(const kd_tree *t, const float q[3], float max_d2, kd_pred pred, const void *ctx,
                       float *d2);

#endif

/* kdtree: a static 3-d kd-tree over float points (implicit heap order,
 * leaves of x[], y[], z[] arrays) with exact k-nearest and
 * nearest-with-predicate queries. It knows points only: the build returns
 * the leaf-order permutation for the caller's payload. A k-nearest answer
 * is the k smallest (squared distance, leaf-order index) pairs, so it never
 * depends on earlier queries or on the instruction set. The files:
 * renderer/README.md. */
#ifndef PM_KDTREE_H
#define PM_KDTREE_H

#include <assert.h>
#include <stddef.h>
#include <stdint.h>

#include "status.h"

#define KD_DEFAULT_LEAF 12u
#define KD_NONE UINT32_MAX

typedef struct {
    uint32_t n;           /* points */
    uint32_t nleaves;     /* a power of two (1 when n <= leaf size) */
    float *split;         /* nleaves-1 inner nodes */
    uint8_t *axis;        /* nleaves-1 inner nodes */
    uint32_t *leaf_start; /* nleaves+1 offsets into x, y, z */
    float *x, *y, *z;     /* points in leaf order (+ padding); read them with kd_point */
    float lo[3], hi[3];   /* bounds of all points */
    uint32_t scan_h;      /* k nearest scans whole subtrees this high (see kdtree_build.c) */
} kd_tree;

/* Builds a tree over n points (xyz triples in pts) on `threads` threads (0
 * or 1: the calling thread only); the tree is the same for any thread
 * count. If perm is not NULL it receives n entries: perm[i] = input index
 * of the point at leaf position i. Returns PM_OK, or PM_ERR_NOMEM
 * (the tree is then empty and safe to kd_free). n may be 0. */
pm_status kd_build(kd_tree *t, const float *pts, uint32_t n, uint32_t leaf_size, uint32_t *perm, unsigned threads);
/* An item of kd_build_items: a point and 20 bytes that are the caller's,
 * which move with it (32 bytes in all). */
typedef struct {
    float p[3];
    unsigned char payload[20];
} kd_build_item;

/* As kd_build over the items' points in their order (the same tree), but
 * in place: the items are reordered into the tree's leaf order (item i
 * holds leaf-order point i and its payload), and the build holds no
 * memory beyond the items and the tree's own arrays (kd_tree_bytes).
 * Returns PM_OK, or PM_ERR_NOMEM (the tree is then empty and the items
 * untouched). n may be 0. */
pm_status kd_build_items(kd_tree *t, kd_build_item *items, uint32_t n, uint32_t leaf_size, unsigned threads);
/* Frees the tree's arrays; the struct is left empty. A zeroed tree is fine. */
void kd_free(kd_tree *t);
/* Bytes of memory the tree holds. */
size_t kd_bytes(const kd_tree *t);
/* Peak bytes kd_build holds while it builds a tree over n points with
 * leaf_size (0: KD_DEFAULT_LEAF): its working copy and the tree's arrays,
 * not the caller's pts and perm. A double, so that a count can be sized
 * (and refused) before its points exist. Never fails. */
double kd_build_peak_bytes(double n, uint32_t leaf_size);
/* The bytes a tree over n points with leaf_size holds once built (what
 * kd_bytes will report), a double for the same reason. Never fails. */
double kd_tree_bytes(double n, uint32_t leaf_size);

/* The coordinates of leaf-order point i (i < t->n) to out. */
static inline void kd_point(const kd_tree *t, uint32_t i, float out[3])
{
    assert(i < t->n);
    out[0] = t->x[i];
    out[1] = t->y[i];
    out[2] = t->z[i];
}

/* Instruction sets of the k-nearest leaf scans. KD_SIMD_BASE is SSE2 on
 * x86-64 (portable C elsewhere); KD_SIMD_AVX2 needs the CPU to have it. */
typedef enum { KD_SIMD_BASE = 1, KD_SIMD_AVX2 = 2 } kd_simd;

/* The work of searches, counted exactly (work.h): nodes visited (each
 * inner node whose split was compared with the query point, plus each
 * point range scanned: a leaf, or a subtree the k-nearest search scans
 * whole) and points examined (points whose distance to the query was
 * computed, padding not counted). */
typedef struct {
    uint64_t nodes, points;
} kd_work;

/* One thread's k-nearest query state: the squared radius that held the
 * last query's k nearest (a starting guess for the next search; it changes
 * the cost of a query, never its result) and the candidate buffer. Not
 * shared between threads; any number may be used on one tree. */
typedef struct {
    uint64_t *buf;     /* candidates: squared distance bits << 32 | index */
    uint32_t cap;      /* candidates one pass may hold (buf is three such regions, with slack) */
    uint32_t hint_k;   /* k of the last query; 0: no guess yet */
    float hint_r2;     /* its k-th squared distance (its cap if it found fewer) */
    kd_simd simd;      /* leaf scan in use */
    uint64_t queries;  /* kd_query_knn calls that searched the tree */
    uint64_t passes;   /* tree traversals they made (>= queries; more when a guess was too small) */
    kd_work work;      /* the nodes and points those traversals visited */
} kd_query;

/* Prepares s for queries of up to k_max neighbours (larger k grows the
 * buffer on demand) with the best instruction set this CPU has. Returns
 * PM_OK, or PM_ERR_NOMEM (s is then empty and safe to kd_query_free;
 * kd_query_knn still works with it, more slowly). */
pm_status kd_query_init(kd_query *s, uint32_t k_max);
/* Frees the buffer; the struct is left empty. */
void kd_query_free(kd_query *s);
/* Drops s's starting radius, so that the next query's cost does not depend
 * on the queries before it (a tile's first query; the result never
 * depends on it). Never fails. */
void kd_query_forget(kd_query *s);
/* Restricts s's leaf scans to `want` or the best set below it that the CPU
 * has; returns the set now in use (the tests run every path with it). */
kd_simd kd_query_simd(kd_query *s, kd_simd want);

/* The k nearest points to q with squared distance <= max_d2 (INFINITY: no
 * cap): writes up to k leaf-order indices and squared distances to idx/d2
 * (in no particular order) and returns how many it found; *r2 receives the
 * largest squared distance among them (0 if none). Exact: the k smallest
 * (squared distance, index) pairs within the cap. Uses and updates s's
 * starting radius; the result is the same whatever s held. */
uint32_t kd_query_knn(const kd_tree *t, kd_query *s, const float q[3], uint32_t k, float max_d2, uint32_t *idx,
                      float *d2, float *r2);

/* Predicate for kd_nearest_if: nonzero when leaf-order point i qualifies. */
typedef int (*kd_pred)(uint32_t i, const void *ctx);

/* The nearest qualifying point within max_d2 of q: returns its leaf-order
 * index and sets *d2, or returns KD_NONE when none qualifies. Exact; of
 * points at the same distance the one of lowest index, so the result does
 * not depend on `hint`: a point (KD_NONE: none) tried first, whose distance,
 * if it qualifies, bounds the search from the start (the previous query's
 * answer, for coherent queries). */
uint32_t kd_nearest_if(const kd_tree *t, const float q[3], float max_d2, kd_pred pred, const void *ctx, uint32_t hint,
                       float *d2);
/* kd_nearest_if that adds the nodes and points it visited to *w (the
 * hint's distance counts as one point). */
uint32_t kd_nearest_if_counted(const kd_tree *t, const float q[3], float max_d2, kd_pred pred, const void *ctx,
                               uint32_t hint, float *d2, kd_work *w);

#endif

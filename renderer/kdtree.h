/* kdtree: a static 3-d kd-tree over float points with exact k-nearest and
 * nearest-with-predicate queries; it knows points only, the caller keeps
 * the payload in leaf order. Its files: renderer/README.md. */
#ifndef PM_KDTREE_H
#define PM_KDTREE_H

#include <assert.h>
#include <stddef.h>
#include <stdint.h>

#include "status.h"

#define KD_DEFAULT_LEAF 12u
#define KD_NONE UINT32_MAX

/* A built tree: inner nodes in heap order, points in leaf order. */
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

/* Builds a tree over n xyz points (n may be 0) on `threads` threads, the
 * same tree for any count; perm, if not NULL, receives the input index of
 * each leaf-order point. Returns PM_ERR_NOMEM when memory runs out (the
 * tree is then empty). */
pm_status kd_build(kd_tree *t, const float *pts, uint32_t n, uint32_t leaf_size, uint32_t *perm, unsigned threads);
/* An item of kd_build_items: a point and 20 caller bytes that move with it. */
typedef struct {
    float p[3];
    unsigned char payload[20];
} kd_build_item;

/* kd_build in place: reorders the items into leaf order, using no memory
 * beyond them and the tree's arrays. Returns PM_ERR_NOMEM when memory runs
 * out (the tree is then empty and the items untouched). */
pm_status kd_build_items(kd_tree *t, kd_build_item *items, uint32_t n, uint32_t leaf_size, unsigned threads);
/* Frees the tree's arrays; the struct is left empty. A zeroed tree is fine. */
void kd_free(kd_tree *t);
/* Bytes of memory the tree holds. Never fails. */
size_t kd_bytes(const kd_tree *t);
/* Peak bytes kd_build holds for n points (its copy and the tree, not pts
 * or perm), as a double so a count can be refused before it exists. Never
 * fails. */
double kd_build_peak_bytes(double n, uint32_t leaf_size);
/* What kd_bytes will report for a tree over n points. Never fails. */
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

/* The nodes and points searches visited, as work.h's map_nodes and
 * map_points. */
typedef struct {
    uint64_t nodes, points;
} kd_work;

/* One thread's k-nearest state: the candidate buffer and the last query's
 * radius, which starts the next search (it changes cost, never results). */
typedef struct {
    uint64_t *buf;     /* candidates: squared distance bits << 32 | index */
    uint64_t *pbuf;    /* packets: KD_PACKET candidate regions of cap + KD_CHUNK keys (NULL until the first) */
    uint32_t pcap;     /* the cap pbuf was made for */
    uint32_t cap;      /* candidates one pass may hold (buf is three such regions, with slack) */
    uint32_t hint_k;   /* k of the last query; 0: no guess yet */
    float hint_r2;     /* its k-th squared distance (its cap if it found fewer) */
    kd_simd simd;      /* leaf scan in use */
    uint64_t queries;  /* kd_query_knn calls that searched the tree */
    uint64_t passes;   /* tree traversals they made (>= queries; more when a guess was too small) */
    kd_work work;      /* the nodes and points those traversals visited */
} kd_query;

/* Prepares s for queries of up to k_max neighbours with the CPU's best
 * leaf scan. Returns PM_ERR_NOMEM when memory runs out (s then still
 * works, more slowly). */
pm_status kd_query_init(kd_query *s, uint32_t k_max);
/* Frees the buffer; the struct is left empty. Never fails. */
void kd_query_free(kd_query *s);
/* Drops s's starting radius, so the next query's cost does not depend on
 * earlier ones. Never fails. */
void kd_query_forget(kd_query *s);
/* Restricts s's leaf scans to `want` or the best set below it that the CPU
 * has; returns the set now in use (the tests run every path with it). */
kd_simd kd_query_simd(kd_query *s, kd_simd want);

/* Writes the k smallest (squared distance, index) pairs within max_d2 of q
 * to idx/d2, unordered, and returns how many; *r2 receives the largest
 * (0 if none). Never fails. */
uint32_t kd_query_knn(const kd_tree *t, kd_query *s, const float q[3], uint32_t k, float max_d2, uint32_t *idx,
                      float *d2, float *r2);

/* Queries a packet serves with one traversal at most. */
#define KD_PACKET 4u

/* kd_query_knn for the m <= KD_PACKET queries q[0..m) with one traversal
 * of the tree: query j's answer to idx[j]/d2[j] (k entries each), its
 * count to found[j] and its largest squared distance to r2[j], the same
 * sets as kd_query_knn gives (unordered). Coherent queries (the subpixel
 * samples of a pixel) share the walk. Never fails. */
void kd_query_knn_packet(const kd_tree *t, kd_query *s, const float (*q)[3], uint32_t m, uint32_t k, float max_d2,
                         uint32_t *const *idx, float *const *d2, uint32_t *found, float *r2);

/* Predicate for kd_nearest_if: nonzero when leaf-order point i qualifies. */
typedef int (*kd_pred)(uint32_t i, const void *ctx);

/* Returns the leaf-order index of the nearest qualifying point within
 * max_d2 of q (lowest index on ties) and sets *d2, or KD_NONE if none
 * qualifies. `hint` (or KD_NONE) is tried first; it never changes the
 * result. */
uint32_t kd_nearest_if(const kd_tree *t, const float q[3], float max_d2, kd_pred pred, const void *ctx, uint32_t hint,
                       float *d2);
/* kd_nearest_if that adds the nodes and points it visited to *w. */
uint32_t kd_nearest_if_counted(const kd_tree *t, const float q[3], float max_d2, kd_pred pred, const void *ctx,
                               uint32_t hint, float *d2, kd_work *w);

#endif

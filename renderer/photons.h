/* photons: the photon pass, which stores a photon at every diffuse hit,
 * and the photon map, a kd-tree in the map's frame (renderer/README.md)
 * with the payload in leaf order. */
#ifndef PM_PHOTONS_H
#define PM_PHOTONS_H

#include <stddef.h>
#include <stdint.h>

#include "kdtree.h"
#include "progress.h"
#include "scene.h"
#include "status.h"
#include "vec.h"

#define PHOTONS_FLAG_REP 1u    /* a representative of the precomputed method (set by reps_choose) */
#define PHOTONS_FLAG_DIRECT 2u /* arrived straight from the light, no bounce before */
#define PHOTONS_FLAG_CAUSTIC 4u /* arrived by mirror and glass only, at least one (L S+ D: the caustic map's) */

/* A stored photon's 20-byte payload; its position lives in the kd-tree.
 * Directions are quantised to signed bytes (x127), good to about half a
 * degree. */
typedef struct {
    float power[3];   /* x photons_map.unit watts */
    int8_t dir[3];    /* direction of travel when it arrived */
    uint8_t flags;    /* PHOTONS_FLAG_* */
    int8_t normal[3]; /* surface normal on the side it arrived from */
    uint8_t pad;
} photons_record;

/* What the photon pass is asked to do. */
typedef struct {
    uint64_t photons;      /* P_e: photons emitted from the light */
    uint64_t seed;         /* photon i draws from random stream (seed, i) */
    uint32_t photon_depth; /* bounces before a path is cut (--photon-depth) */
    int store_first_hits;  /* 0: direct light comes from shadow rays, store bounced light only */
} photons_params;

/* The photon pass's output in trace order, positions in world coordinates.
 * pos and ph are mem_alloc buffers (mem.h), also when a caller fills a list. */
typedef struct {
    uint64_t count;
    double *pos;         /* 3 * count */
    photons_record *ph;  /* count */
    vec3 unit;           /* the emitted photon's power: records' power is relative to it */
    uint64_t truncated, escaped;
    uint64_t rays, shape_tests; /* rays the photon paths cast, and their ray-shape tests */
} photons_list;

/* The photon map: the tree, its payload and its frame. */
typedef struct {
    kd_tree tree;           /* positions in the map frame */
    photons_record *ph;     /* payload, tree leaf order */
    uint32_t count;         /* photons in the tree */
    uint64_t stored;        /* photons stored by the pass (count + those left out) */
    vec3 unit;              /* watts of power 1.0 in a record */
    vec3 centre;            /* world = centre + scale * map */
    double scale;           /* a power of two; 1 when the map is empty */
    double extent;          /* diagonal of all stored photons' bounding box, scene units (0: fewer than 2 places) */
} photons_map;

/* Bytes of memory one stored photon costs in a built map (payload + position). */
#define PHOTONS_BYTES_PER_STORED (sizeof(photons_record) + 3 * sizeof(float))

/* Quantises a unit vector to 3 signed bytes, and back. Neither fails. */
void photons_pack_dir(double x, double y, double z, int8_t out[3]);
vec3 photons_unpack_dir(const int8_t d[3]);

/* Emits p->photons photons from the light and traces them into out, the
 * same list for any thread count. Returns PM_ERR_NOMEM when memory runs
 * out (out is then empty). */
pm_status photons_trace(const scene *sc, const photons_params *p, unsigned threads, progress *prog, photons_list *out);
/* Frees a list; a zeroed list is fine. */
void photons_list_free(photons_list *l);
/* Copies the photons of l whose flags meet `mask` into *out, in order.
 * Returns PM_ERR_NOMEM when memory runs out (out is then empty). */
pm_status photons_list_select(const photons_list *l, uint8_t mask, photons_list *out);
/* Builds the map from l, which it consumes, the same map for any thread
 * count; photons whose flags meet `leave_out` go to *left instead (NULL
 * when the mask is 0) but still count in m->stored and the frame. Returns
 * PM_ERR_NOMEM when memory runs out or l exceeds 2^32-1 photons (m and
 * *left are then empty). */
pm_status photons_build_map(photons_list *l, uint8_t leave_out, unsigned threads, photons_map *m, photons_list *left);
/* Frees a map; a zeroed map is fine. */
void photons_map_free(photons_map *m);
/* Writes world point x in the map frame, as the tree's floats. */
void photons_map_point(const photons_map *m, vec3 x, float q[3]);
/* Bytes the map holds (tree and payload). */
size_t photons_map_bytes(const photons_map *m);

/* Peak bytes of a photon pass and map build that store `stored` photons
 * on two threads (renderer/README.md). Never fails. */
double photons_peak_bytes(double stored);
/* Traces a pilot of at most 4096 photons and sets *per to the photons
 * stored per emitted photon. Returns PM_ERR_NOMEM when memory runs out. */
pm_status photons_stored_per_emitted(const scene *sc, const photons_params *p, double *per);

#endif

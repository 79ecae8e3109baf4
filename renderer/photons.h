/* photons: the photon pass (emit from the point light, trace through
 * mirror and glass, store at every diffuse hit) and the photon map: a
 * kd-tree over the positions in the map's frame (floats relative to the
 * photons' box centre over a power of two near its size: renderer/README.md)
 * and the payload in leaf order. Flagged photons can be kept out. */
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

/* A stored photon's payload; its position lives in the kd-tree. 20 bytes:
 * power as floats relative to the emitted photon's power (photons_map.unit),
 * directions quantised to 3 signed bytes (x127), which keeps the front-side
 * and normal tests accurate to about half a degree. */
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

/* The photon pass's output: positions in world coordinates (double), in
 * trace order. pos and ph are mem_alloc buffers (mem.h), which is how a
 * caller that fills a list itself must allocate them. */
typedef struct {
    uint64_t count;
    double *pos;         /* 3 * count */
    photons_record *ph;  /* count */
    vec3 unit;           /* the emitted photon's power: records' power is relative to it */
    uint64_t truncated, escaped;
    uint64_t rays, shape_tests; /* rays the photon paths cast, and their ray-shape tests */
} photons_list;

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

/* Quantises a unit vector to 3 signed bytes and back. */
void photons_pack_dir(double x, double y, double z, int8_t out[3]);
vec3 photons_unpack_dir(const int8_t d[3]);

/* Emits p->photons photons from the scene's light and traces them into out
 * (the list is the same for any thread count). Returns PM_OK, or
 * PM_ERR_NOMEM when memory runs out (out is then empty). */
pm_status photons_trace(const scene *sc, const photons_params *p, unsigned threads, progress *prog, photons_list *out);
/* Frees a list; a zeroed list is fine. */
void photons_list_free(photons_list *l);
/* Copies the photons of l whose flags meet `mask` into *out, in trace
 * order, with l's unit (the caustic map's list: PHOTONS_FLAG_CAUSTIC); l
 * is unchanged. Returns PM_OK, or PM_ERR_NOMEM (out is then empty). */
pm_status photons_list_select(const photons_list *l, uint8_t mask, photons_list *out);
/* Builds the map from a list, which it consumes and frees, on `threads`
 * threads (the map is the same for any count). The photons
 * whose flags meet the mask `leave_out` stay out of the tree (they still
 * count in m->stored and in the map's frame); they are moved, in trace
 * order, into *left (which may be NULL when the mask is 0). Returns PM_OK,
 * or PM_ERR_NOMEM when memory runs out or the list exceeds 2^32-1 photons
 * (render_check_memory refuses those up front; m and *left are then empty). */
pm_status photons_build_map(photons_list *l, uint8_t leave_out, unsigned threads, photons_map *m, photons_list *left);
/* Frees a map; a zeroed map is fine. */
void photons_map_free(photons_map *m);
/* x (world) in the map frame, as the tree's floats. */
void photons_map_point(const photons_map *m, vec3 x, float q[3]);
/* Bytes the map holds (tree and payload). */
size_t photons_map_bytes(const photons_map *m);

/* Peak bytes of a photon pass and map build that store `stored` photons
 * on two threads: the trace's chunks and the joined list (each chunk freed
 * as it is joined), then the list handed back as it is converted into the
 * tree's items, then the items (built in place) beside the tree's arrays.
 * About 45 bytes a stored photon; never fails. */
double photons_peak_bytes(double stored);
/* Traces a pilot of min(p->photons, 4096) photons on one thread and sets
 * *per to the photons stored per emitted photon (0 for no photons).
 * Returns PM_OK, or PM_ERR_NOMEM. */
pm_status photons_stored_per_emitted(const scene *sc, const photons_params *p, double *per);

#endif

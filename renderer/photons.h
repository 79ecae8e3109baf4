/* photons: emitting photons from the point light, tracing them through
 * mirror and glass, storing one at every diffuse hit, flagging
 * representatives, and the built photon map (kd-tree + payload in the
 * tree's leaf order). */
#ifndef PM_PHOTONS_H
#define PM_PHOTONS_H

#include <stddef.h>
#include <stdint.h>

#include "config.h"
#include "kdtree.h"
#include "progress.h"
#include "scene.h"

#define PHOTON_FLAG_REP 1u    /* a representative (precomputed method) */
#define PHOTON_FLAG_DIRECT 2u /* arrived straight from the light, no bounce before */

/* A stored photon's payload; its position lives in the kd-tree. 20 bytes:
 * power as floats (any light power from 1e-30 to 1e30 W stays representable),
 * directions quantised to 3 signed bytes (x127), which keeps the front-side
 * and normal tests accurate to about half a degree. */
typedef struct {
    float power[3];   /* watts */
    int8_t dir[3];    /* direction of travel when it arrived */
    uint8_t flags;    /* PHOTON_FLAG_* */
    int8_t normal[3]; /* surface normal on the side it arrived from */
    uint8_t pad;
} photon;

/* Bytes of memory one stored photon costs in a built map (payload + position). */
#define PHOTON_BYTES_PER_STORED (sizeof(photon) + 3 * sizeof(float))

typedef struct {
    uint64_t count;
    float *pos;  /* 3 * count, in trace order */
    photon *ph;  /* count */
    uint64_t truncated, escaped;
} photon_list;

typedef struct {
    kd_tree tree; /* positions */
    photon *ph;   /* payload, tree leaf order */
    uint32_t count;
    uint32_t reps; /* photons flagged PHOTON_FLAG_REP */
} photon_map;

/* Quantises a unit vector to 3 signed bytes and back. */
void photon_pack_dir(double x, double y, double z, int8_t out[3]);
vec3 photon_unpack_dir(const int8_t d[3]);

/* Emits cfg->photons photons from the scene's light and traces them (seeded
 * by cfg->seed, photon i drawing from stream i, so the list is the same for
 * any thread count). Stores at every diffuse hit (not the first one when
 * cfg->direct is DIRECT_SHADOW_RAYS) and flags every cfg->rep_every-th stored
 * photon as a representative when cfg->method is METHOD_PRECOMPUTED.
 * Returns 0, or -1 when memory runs out (out is then empty). */
int photons_trace(const scene *sc, const render_config *cfg, unsigned threads, progress *prog,
                  photon_list *out);
/* Frees a list; a zeroed list is fine. */
void photons_list_free(photon_list *l);
/* Builds the map from a list (which it consumes and frees) and counts its
 * representatives. Returns 0, or -1
 * when memory runs out or the list exceeds 2^32-1 photons. */
int photons_build_map(photon_list *l, photon_map *m);
/* Frees a map; a zeroed map is fine. */
void photons_map_free(photon_map *m);

#endif

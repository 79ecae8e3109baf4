/* estimate: the two radiance estimates of the paper. Both give the
 * irradiance E at a diffuse point; the caller multiplies by rho/pi.
 *  - conventional (eq. 1): E = sum of front-side photon powers among the n
 *    nearest, over pi r^2;
 *  - precomputed (eq. 2, Christensen 2000): E was computed the same way at
 *    representative photons before the eye pass; a lookup returns the E of
 *    the single nearest representative whose normal agrees with the point's.
 *
 * Conventions (documented in README): r^2 is the squared distance to the
 * farthest of the n photons found; when fewer than n photons lie within the
 * maximum radius R, r = R (the disc's density); r is clamped below at
 * R * EST_MIN_RADIUS_FRAC so coincident photons give a large finite value.
 * No photon in range, or no agreeing representative in range, gives E = 0.
 * Radii here are in the photon map's frame (photons.h). */
#ifndef PM_ESTIMATE_H
#define PM_ESTIMATE_H

#include <stdint.h>
#include <stdio.h>

#include "kdtree.h"
#include "photons.h"
#include "progress.h"
#include "vec.h"

#define EST_MIN_RADIUS_FRAC 1e-3

/* A gather: how many photons, the squared radius cap in the map's frame
 * (est_gather_make converts from scene units), and which estimate: the
 * paper's (all n photons over pi r^2, r the n-th one's distance) or the
 * corrected one (only the photons strictly inside r, which is unbiased for a
 * uniform density: the paper's follows n/(n-1)), times `boost` = photons
 * stored / photons in the tree, which restores the density when the map
 * leaves the representatives out. */
typedef struct {
    uint32_t nn;
    double max_r2;
    int corrected;
    double boost;
} est_gather;

/* The gather of nn photons within max_radius scene units on map m. */
est_gather est_gather_make(const photons_map *m, uint32_t nn, double max_radius, int corrected);

typedef struct {
    float irradiance[3]; /* relative to photons_map.unit / scale^2 */
    float normal[3];     /* unit */
} est_rep;

typedef enum { EST_REPS_SEPARATE = 0, EST_REPS_SHARED = 1 } est_rep_layout;

typedef struct {
    est_rep_layout layout;
    uint32_t count;
    kd_tree tree;     /* separate: the representatives' own tree */
    est_rep *rep;     /* separate: in that tree's leaf order; shared: by rep_of */
    uint32_t *rep_of; /* shared: photon tree index -> rep index or KD_NONE */
} est_reps;

/* One thread's buffers for kNN queries of up to nn photons, and its query
 * state (the last query's radius starts the next search: cheaper, never a
 * different result). */
typedef struct {
    uint32_t cap;
    uint32_t *idx;
    float *d2;
    kd_query query;
    uint32_t last_rep; /* the last lookup's answer (a tree index), tried first by the next one */
    char pad[64];      /* threads' scratch structs share no cache line */
} est_scratch;

/* Scratch for `threads` workers, each for queries of up to nn photons.
 * Returns the array, or NULL when memory runs out. */
est_scratch *est_scratch_new(unsigned threads, uint32_t nn);
/* Frees what est_scratch_new returned; NULL is fine. */
void est_scratch_delete(est_scratch *s, unsigned threads);

/* Conventional irradiance (W per unit^2 of the scene) at world point x for
 * unit normal n (facing the side seen). *found receives how many photons
 * were gathered (front side or not). */
vec3 est_irradiance(const photons_map *m, vec3 x, vec3 n, const est_gather *g, est_scratch *s, uint32_t *found);

/* Precomputes irradiance at every representative of m (m->reps of them)
 * from its g->nn nearest photons of the map, on `threads` threads,
 * deterministically. The shared layout needs the representatives in the
 * photon tree (asserted). Returns 0, or -1 when memory runs out (out is
 * then empty). */
int est_precompute(const photons_map *m, const est_gather *g, est_rep_layout layout, unsigned threads,
                   progress *prog, est_reps *out);
/* Irradiance (W per unit^2) of the nearest representative within the
 * gather's radius cap of world point x whose normal has cosine > cos_min
 * with n (of equally near ones, the first in tree order, so the answer does
 * not depend on s, whose last answer only starts the search). Returns 0 and
 * sets *found = 0 when none qualifies. */
vec3 est_lookup(const est_reps *r, const photons_map *m, vec3 x, vec3 n, double cos_min, const est_gather *g,
                est_scratch *s, int *found);
/* Writes the representatives as CSV to f: the header
 * "x,y,z,nx,ny,nz,e_r,e_g,e_b", then one line per representative: its
 * position in scene units, its unit normal and its precomputed irradiance
 * in W per scene unit^2 (what est_lookup returns for it). Returns 0, or -1
 * on a write error. */
int est_reps_write_csv(const est_reps *r, const photons_map *m, FILE *f);
/* Bytes the representatives hold. */
size_t est_reps_bytes(const est_reps *r, const photons_map *m);
/* Frees the representatives; a zeroed struct is fine. */
void est_reps_free(est_reps *r);

#endif

/* estimate: the two radiance estimates of the paper. Both return an
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
 * No photon in range, or no agreeing representative in range, gives E = 0. */
#ifndef PM_ESTIMATE_H
#define PM_ESTIMATE_H

#include <stdint.h>

#include "config.h"
#include "kdtree.h"
#include "photons.h"
#include "progress.h"
#include "vec.h"

#define EST_MIN_RADIUS_FRAC 1e-3

typedef struct {
    float irradiance[3];
    float normal[3]; /* unit */
} est_rep;

typedef enum { EST_REPS_SEPARATE = 0, EST_REPS_SHARED = 1 } est_rep_layout;

typedef struct {
    est_rep_layout layout;
    uint32_t count;
    kd_tree tree;     /* separate: the representatives' own tree */
    est_rep *rep;     /* separate: in that tree's leaf order; shared: by rep_of */
    uint32_t *rep_of; /* shared: photon index -> rep index or KD_NONE */
} est_reps;

/* Per-thread buffers for kNN queries of up to nn photons. */
typedef struct {
    uint32_t cap;
    uint32_t *idx;
    float *d2;
} est_scratch;

/* Returns 0, or -1 when memory runs out. */
int est_scratch_init(est_scratch *s, uint32_t nn);
void est_scratch_free(est_scratch *s);

/* Conventional irradiance at x for unit normal n (facing the side seen),
 * from the nn nearest photons within sqrt(max_r2). *found receives how many
 * photons were gathered (front side or not). */
vec3 est_irradiance(const photon_map *m, vec3 x, vec3 n, uint32_t nn, double max_r2, est_scratch *s,
                    uint32_t *found);

/* Precomputes irradiance at every representative (PHOTON_FLAG_REP; m->reps
 * of them, as photons_build_map counted) of m with
 * est_irradiance, on `threads` threads, deterministically. Returns 0, or -1
 * when memory runs out (out is then empty). */
int est_precompute(const photon_map *m, uint32_t nn, double max_r2, est_rep_layout layout, unsigned threads,
                   progress *prog, est_reps *out);
/* Irradiance of the nearest representative within sqrt(max_r2) of x whose
 * normal has cosine > cos_min with n. Returns 0 and sets *found = 0 when none
 * qualifies. */
vec3 est_lookup(const est_reps *r, const photon_map *m, vec3 x, vec3 n, double cos_min, double max_r2,
                int *found);
/* Bytes the representatives hold. */
size_t est_reps_bytes(const est_reps *r, const photon_map *m);
void est_reps_free(est_reps *r);

#endif

/* gather: final gathering (--gather N) at an eye path's first diffuse hit:
 * gather rays to the global map and the caustic map's estimate
 * (renderer/README.md, "Final gathering"). */
#ifndef PM_GATHER_H
#define PM_GATHER_H

#include <stdint.h>

#include "config.h"
#include "estimate.h"
#include "photons.h"
#include "reps.h"
#include "rng.h"
#include "scene.h"
#include "vec.h"

/* The gather streams' indices: GATHER_STREAM_BASE + the eye sample's index
 * (photon i draws from stream i < 2^31, so no stream is shared). */
#define GATHER_STREAM_BASE (1ull << 63)

/* What the gathers of one thread did, counted exactly (the image's order
 * of work does not change them). */
typedef struct {
    uint64_t rays;            /* gather rays cast from eye hits */
    uint64_t specular;        /* rays spawned at mirror and glass along gather paths */
    uint64_t lookups;         /* radiance estimates at the gather paths' diffuse hits y */
    uint64_t empty;           /* of those, with no photon (no agreeing representative) within the cap */
    uint64_t fallbacks;       /* of those, sent by the plane gate to the conventional estimate at y */
    uint64_t missed;          /* gather paths that left the scene */
    uint64_t depth_hits;      /* gather paths cut at --eye-depth */
    uint64_t caustic_lookups; /* caustic-map estimates at eye hits */
    uint64_t shape_tests;     /* ray-shape tests of the gather rays and their continuations */
} gather_counts;

/* What a gather reads. */
typedef struct {
    const scene *sc;
    const photons_map *global;  /* every stored photon */
    const reps_set *reps;       /* the precomputed method's representatives; NULL: the conventional estimate */
    const photons_map *caustic; /* the L S+ D photons; NULL: no caustic map (no caustic photon was stored) */
    est_gather global_gather;   /* nn, the cap, the estimate (--bias-correction), on the global map */
    est_gather caustic_gather;  /* the same on the caustic map */
    uint32_t rays;              /* N: gather rays per eye hit */
    uint32_t strata_u, strata_v; /* the first strata_u x strata_v rays are stratified, any rest uniform */
    uint32_t depth;             /* specular bounces a gather path may make (--eye-depth) */
} gather_params;

/* The gather of cfg (cfg->gather rays) on the global map (its
 * representatives `reps` for the precomputed method, else NULL) and the
 * caustic map (NULL: none), with the radius cap max_radius in scene units.
 * Never fails. */
gather_params gather_params_make(const scene *sc, const config_render *cfg, const photons_map *global,
                                 const reps_set *reps, const photons_map *caustic, double max_radius);

/* The strata of n gather rays: strata_u x strata_v = n, strata_v >= strata_u,
 * from the divisor of n nearest below sqrt(n) when the grid is no more than
 * 4 times as long as wide, else floor(sqrt(n)) x floor(n / floor(sqrt(n)))
 * and the rest of the n rays uniform. Never fails. */
void gather_strata(uint32_t n, uint32_t *strata_u, uint32_t *strata_v);

/* The gather stream of eye sample `sample` (its index in the image's
 * sample order) for seed; never fails. */
rng_stream gather_stream(uint64_t seed, uint64_t sample);

/* The unit direction of gather ray i at a point of normal n with tangents
 * t and b (vec_basis), from the uniform numbers xi1 and xi2: cosine-weighted
 * over the hemisphere, in ray i's stratum. Never fails. */
vec3 gather_direction(const gather_params *g, uint32_t i, double xi1, double xi2, vec3 n, vec3 t, vec3 b);

/* The irradiance (W per unit^2) the global map gives at diffuse point y
 * of unit normal n, per --method (g->reps: the nearest agreeing
 * representative, else the n-nearest estimate), searching within the cap
 * only; 0 when nothing qualifies there (counted in c->empty). s is the
 * thread's search state. Never fails. */
vec3 gather_estimate(const gather_params *g, vec3 y, vec3 n, est_scratch *s, gather_counts *c);

/* The indirect irradiance at diffuse hit x (W per unit^2, the caller
 * multiplies by rho/pi) by g->rays gather rays drawing from rs: pi times the
 * mean radiance they bring back. s is the thread's search state on the
 * global map; the work is added to c. Never fails. */
vec3 gather_indirect(const gather_params *g, const scene_hit *x, rng_stream *rs, est_scratch *s, gather_counts *c);

/* The caustic irradiance at diffuse hit x (W per unit^2) from the caustic
 * map by the conventional estimate, s the thread's search state on it; 0
 * without a caustic map. Never fails. */
vec3 gather_caustic(const gather_params *g, const scene_hit *x, est_scratch *s, gather_counts *c);

/* Adds every counter of b to a; never fails. */
void gather_counts_add(gather_counts *a, const gather_counts *b);

#endif

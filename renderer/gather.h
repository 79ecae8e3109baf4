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

/* What one thread's gathers did, counted exactly. */
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

/* The gather cfg asks for on the global map (with `reps` for the
 * precomputed method) and the caustic map (NULL: none). Never fails. */
gather_params gather_params_make(const scene *sc, const config_render *cfg, const photons_map *global,
                                 const reps_set *reps, const photons_map *caustic, double max_radius);

/* The strata grid of n gather rays, strata_u <= strata_v, by the rule of
 * renderer/README.md ("Final gathering"). Never fails. */
void gather_strata(uint32_t n, uint32_t *strata_u, uint32_t *strata_v);

/* The gather stream of eye sample `sample` (its index in the image's
 * sample order) for seed; never fails. */
rng_stream gather_stream(uint64_t seed, uint64_t sample);

/* Gather ray i's cosine-weighted unit direction in its stratum, about
 * normal n with tangents t and b, from uniforms xi1, xi2. Never fails. */
vec3 gather_direction(const gather_params *g, uint32_t i, double xi1, double xi2, vec3 n, vec3 t, vec3 b);

/* The global map's irradiance at diffuse point y with unit normal n, per
 * --method, within the cap only; 0 when nothing qualifies (counted in
 * c->empty). Never fails. */
vec3 gather_estimate(const gather_params *g, vec3 y, vec3 n, est_scratch *s, gather_counts *c);

/* The indirect irradiance at diffuse hit x from g->rays gather rays drawn
 * from rs (pi times their mean radiance); adds the work to c. Never fails. */
vec3 gather_indirect(const gather_params *g, const scene_hit *x, rng_stream *rs, est_scratch *s, gather_counts *c);

/* The caustic map's conventional estimate at diffuse hit x; 0 without a
 * caustic map. Never fails. */
vec3 gather_caustic(const gather_params *g, const scene_hit *x, est_scratch *s, gather_counts *c);

/* Adds every counter of b to a; never fails. */
void gather_counts_add(gather_counts *a, const gather_counts *b);

#endif

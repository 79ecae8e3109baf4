/* estimate: equation 1 of the paper, E = the front-side photon powers
 * among the n nearest over pi r^2 (the caller multiplies by rho/pi), and
 * the gather conventions both methods share (renderer/README.md): r is at
 * most the cap R (fewer than n photons: r = R), at least
 * EST_MIN_RADIUS_FRAC of R or of the photons' extent when R is larger; no
 * photon in range gives 0. Radii are in the photon map's frame. */
#ifndef PM_ESTIMATE_H
#define PM_ESTIMATE_H

#include <stdint.h>

#include "kdtree.h"
#include "photons.h"
#include "vec.h"
#include "work.h"

#define EST_MIN_RADIUS_FRAC 1e-3

/* A gather: how many photons, the squared radius cap in the map's frame
 * (est_gather_make converts from scene units), and which estimate: the
 * paper's (all n photons over pi r^2, r the n-th one's distance) or the
 * bias-corrected one (--bias-correction: only the photons strictly inside r, unbiased for a
 * uniform density: the paper's follows n/(n-1)), times `boost` = photons
 * stored / photons in the tree, which restores the density when the map
 * leaves the representatives out. */
typedef struct {
    uint32_t nn;
    double max_r2;
    double min_r2; /* the floor of r^2, map frame */
    int bias_correction;
    double boost;
} est_gather;

/* The gather of nn photons within max_radius scene units on map m. */
est_gather est_gather_make(const photons_map *m, uint32_t nn, double max_radius, int bias_correction);

/* One thread's buffers for kNN queries of up to nn photons, and its query
 * state (the last query's radius starts the next search: cheaper, never a
 * different result). */
typedef struct {
    uint32_t cap;
    uint32_t *idx;
    float *d2;
    kd_query query;    /* its queries and work: the photon map's (work.h's knn_queries, map_nodes, map_points) */
    uint32_t last_rep; /* reps_lookup's last answer (a tree index), tried first by its next one */
    /* the representatives' lookups (reps.c): their count, nodes and points, and the
     * representatives whose irradiance this thread computed */
    uint64_t rep_lookups, rep_evaluations;
    kd_work rep_work;
    char pad[64];      /* threads' scratch structs share no cache line */
} est_scratch;

/* Scratch for `threads` workers, each for queries of up to nn photons.
 * Returns the array, or NULL when memory runs out. */
est_scratch *est_scratch_new(unsigned threads, uint32_t nn);
/* Frees what est_scratch_new returned; NULL is fine. */
void est_scratch_delete(est_scratch *s, unsigned threads);
/* Drops what s carries from one query to the next (the k-nearest starting
 * radius, the lookup's last answer), so that the work of the queries that
 * follow does not depend on those before (each tile and chunk starts so).
 * Results never depend on it. Never fails. */
void est_scratch_forget(est_scratch *s);
/* Adds the work counted by the `threads` scratch structs s to w: the
 * photon map's queries, nodes and points, the representatives' lookups,
 * nodes and points, and their evaluations. Never fails. */
void est_scratch_work(const est_scratch *s, unsigned threads, work_counts *w);

/* Conventional irradiance (W per unit^2 of the scene) at world point x for
 * unit normal n (facing the side seen). *found receives how many photons
 * were gathered (front side or not). */
vec3 est_irradiance(const photons_map *m, vec3 x, vec3 n, const est_gather *g, est_scratch *s, uint32_t *found);
/* The same at map-frame point q, relative to m->unit / m->scale^2 (the
 * precompute's form, reps.h). */
vec3 est_irradiance_at(const photons_map *m, const float q[3], vec3 n, const est_gather *g, est_scratch *s,
                       uint32_t *found);
/* The plane gate's height of a point at offset d from x, x with unit
 * normal n and the point with normal nj (not necessarily unit): the
 * distance of d from the plane through x whose normal is the mean of n and
 * nj. For two points of one plane (nj = n) it is the distance from x's
 * tangent plane; for two points of one sphere, whatever its radius, it is
 * 0 (their chord is perpendicular to n + nj), so the gate sees no curvature
 * there; a parallel surface (a thin slab's other face, a shelf) lies at its
 * offset. INFINITY for opposite normals. */
double est_surface_height(vec3 d, vec3 n, vec3 nj);
/* est_irradiance_at with the plane gate's test (the representatives' gated
 * precompute, reps.h): a gathered photon counts only when its height
 * (est_surface_height, with the normal of the surface it landed on) is at
 * most rep_gate_tau times the disc's radius r (rep_gate_tau <= 0: no test, the same result as
 * est_irradiance_at). *r2 receives the squared radius the estimate divides
 * by (map frame). */
vec3 est_irradiance_plane_at(const photons_map *m, const float q[3], vec3 n, const est_gather *g, double rep_gate_tau,
                             est_scratch *s, uint32_t *found, double *r2);
/* The factor from irradiance in map units to W per scene unit^2. */
vec3 est_world_factor(const photons_map *m);


#endif

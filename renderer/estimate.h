/* estimate: the paper's equation 1 (front-side photon power among the n
 * nearest over pi r^2) and the radius conventions both methods share
 * (renderer/README.md). Radii are in the photon map's frame. */
#ifndef PM_ESTIMATE_H
#define PM_ESTIMATE_H

#include <stdint.h>

#include "kdtree.h"
#include "photons.h"
#include "vec.h"
#include "work.h"

#define EST_MIN_RADIUS_FRAC 1e-3

/* A gather: photon count, squared radius cap and floor (map frame), the
 * estimate (paper's, or --bias-correction's photons strictly inside r) and
 * `boost`, photons stored / photons in the tree. */
typedef struct {
    uint32_t nn;
    double max_r2;
    double min_r2; /* the floor of r^2, map frame */
    int bias_correction;
    double boost;
} est_gather;

/* The gather of nn photons within max_radius scene units on map m. */
est_gather est_gather_make(const photons_map *m, uint32_t nn, double max_radius, int bias_correction);

/* One thread's kNN buffers, query state and work counters. */
typedef struct {
    uint32_t cap;
    uint32_t *idx;
    float *d2;
    kd_query query;    /* its queries and work: the photon map's (work.h's knn_queries, map_nodes, map_points) */
    uint32_t last_rep; /* reps_lookup's last answer (a tree index), tried first by its next one */
    /* the representatives' lookups and evaluations (reps.c) */
    uint64_t rep_lookups, rep_evaluations;
    kd_work rep_work;
    char pad[64];      /* threads' scratch structs share no cache line */
} est_scratch;

/* Scratch for `threads` workers, each for queries of up to nn photons.
 * Returns the array, or NULL when memory runs out. */
est_scratch *est_scratch_new(unsigned threads, uint32_t nn);
/* Frees what est_scratch_new returned; NULL is fine. */
void est_scratch_delete(est_scratch *s, unsigned threads);
/* Drops the starting radius and lookup hint carried between queries, so
 * that later work counts do not depend on earlier queries. Never fails. */
void est_scratch_forget(est_scratch *s);
/* Adds the work counted in the `threads` scratch structs s to w. Never
 * fails. */
void est_scratch_work(const est_scratch *s, unsigned threads, work_counts *w);

/* Conventional irradiance (W per scene unit^2) at world point x with unit
 * normal n; *found receives the photons gathered. Never fails. */
vec3 est_irradiance(const photons_map *m, vec3 x, vec3 n, const est_gather *g, est_scratch *s, uint32_t *found);
/* The same at map-frame point q, relative to m->unit / m->scale^2 (the
 * precompute's form, reps.h). */
vec3 est_irradiance_at(const photons_map *m, const float q[3], vec3 n, const est_gather *g, est_scratch *s,
                       uint32_t *found);
/* The plane gate's height of offset d from x (unit normal n) to a point
 * with normal nj: d's distance from the plane through x normal to n + nj
 * (renderer/README.md). Returns INFINITY for opposite normals. */
double est_surface_height(vec3 d, vec3 n, vec3 nj);
/* est_irradiance_at counting only photons whose est_surface_height is at
 * most rep_gate_tau times r (<= 0: no test); *r2 receives the squared
 * radius it divides by. Never fails. */
vec3 est_irradiance_plane_at(const photons_map *m, const float q[3], vec3 n, const est_gather *g, double rep_gate_tau,
                             est_scratch *s, uint32_t *found, double *r2);
/* The factor from irradiance in map units to W per scene unit^2. */
vec3 est_world_factor(const photons_map *m);


#endif

/* work: what a render did, counted exactly, per phase (photon pass, build,
 * precompute, eye pass). The counts depend only on the scene and the
 * settings, never on the thread count or the machine: each worker counts
 * into its own counters (in locals within a query or a ray, added once at
 * its end), the phase sums the workers' counters, and the search state
 * that carries over from one query to the next (kd_query's starting radius,
 * the representatives' lookup hint) is reset at the start of every tile and
 * chunk, so a tile costs the same whichever thread runs it after whichever
 * tile. The one exception: with --rep-eval lazy on more than one thread, a
 * representative's irradiance is computed by whichever tile first needs
 * it, from that thread's starting radius, so the eye pass's map_nodes and
 * map_points may vary by scheduling (rep_evaluations does not).
 *
 * What each counter holds (README.md's stats table says the same):
 *  traced_photons   photon paths started at the light
 *  stored_photons   photons stored on diffuse surfaces
 *  rays             rays cast: photon path segments, eye rays and their
 *                   specular children, shadow rays
 *  shape_tests      ray-shape intersection tests those rays made
 *  tree_points      points put into a kd-tree (the photon map in the
 *                   build, the representatives' own tree in the precompute)
 *  knn_queries      k-nearest queries on the photon map
 *  map_nodes        kd-tree nodes those queries visited: each inner node
 *                   whose split was compared with the query point, plus
 *                   each point range scanned (a leaf, or a subtree scanned
 *                   whole); every pass of a query counts
 *  map_points       points whose distance to the query was computed
 *  rep_lookups      representative lookups (one per diffuse eye hit of the
 *                   precomputed method)
 *  rep_nodes        nodes those lookups visited, as map_nodes (in the
 *                   representatives' tree, or in the photon map for
 *                   --rep-tree shared)
 *  rep_points       points they examined, as map_points (a lookup's hint
 *                   counts as one)
 *  rep_evaluations  representatives whose irradiance was computed */
#ifndef PM_WORK_H
#define PM_WORK_H

#include <stdint.h>
#include <stdio.h>

#include "status.h"

/* The counters, in the order of the JSON object and of WORK_FIELDS. */
typedef struct {
    uint64_t traced_photons, stored_photons;
    uint64_t rays, shape_tests;
    uint64_t tree_points;
    uint64_t knn_queries, map_nodes, map_points;
    uint64_t rep_lookups, rep_nodes, rep_points;
    uint64_t rep_evaluations;
} work_counts;

/* X(name) for every counter of work_counts, in its order. */
#define WORK_FIELDS(X)                                                                                       \
    X(traced_photons) X(stored_photons) X(rays) X(shape_tests) X(tree_points) X(knn_queries) X(map_nodes)   \
        X(map_points) X(rep_lookups) X(rep_nodes) X(rep_points) X(rep_evaluations)

/* The phases of a render, as in its times. */
typedef struct {
    work_counts trace, build, precompute, render;
} work_phases;

/* Adds every counter of b to a. Never fails. */
void work_add(work_counts *a, const work_counts *b);
/* 1 when every counter of a and b is equal, else 0. */
int work_equal(const work_phases *a, const work_phases *b);
/* Writes w as the JSON object {"trace": {...}, "build": ..., "precompute":
 * ..., "render": ...}, every counter of each phase, indented for a stats
 * file's top level. Returns PM_OK, or PM_ERR_IO on a write error. */
pm_status work_write_json(FILE *f, const work_phases *w);

#endif

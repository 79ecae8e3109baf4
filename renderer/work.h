/* work: what a render did per phase, counted exactly and the same for any
 * thread count; renderer/README.md ("Work counters") defines each counter. */
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
    uint64_t rep_chosen;
} work_counts;

/* X(name) for every counter of work_counts, in its order. */
#define WORK_FIELDS(X)                                                                                       \
    X(traced_photons) X(stored_photons) X(rays) X(shape_tests) X(tree_points) X(knn_queries) X(map_nodes)   \
        X(map_points) X(rep_lookups) X(rep_nodes) X(rep_points) X(rep_evaluations) X(rep_chosen)

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

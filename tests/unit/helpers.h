/* helpers: small shared pieces of the unit tests (scenes from text, renders,
 * synthetic photon maps and their representatives). */
#ifndef PM_TEST_HELPERS_H
#define PM_TEST_HELPERS_H

#include "config.h"
#include "estimate.h"
#include "image.h"
#include "kdtree.h"
#include "photons.h"
#include "reps.h"
#include "scene.h"
#include "stats.h"

/* Parses scene text or aborts the test run with the parser's message. */
scene *helper_scene(const char *text);
/* render_run without progress; prints render_run's message when it fails.
 * Returns render_run's result. */
pm_status helper_render(const scene *sc, const config_render *cfg, unsigned threads, image *out, stats_run *st);

/* A photon map of `count` photons at pos[] (world units), each travelling
 * along dir onto a surface of normal `normal`, power `power` per channel,
 * flags as given; aborts the test run when memory runs out. */
void helper_map(photons_map *m, const float (*pos)[3], uint32_t count, vec3 dir, vec3 normal, float power,
                unsigned flags);
/* The representatives of map m (its flagged photons, all in the tree) in
 * layout `tree`, evaluated with gather g on `threads` threads. Returns PM_OK,
 * or PM_ERR_NOMEM (out is then empty). */
pm_status helper_reps(const photons_map *m, const est_gather *g, config_rep_tree tree, unsigned threads,
                      reps_set *out);
/* kd_query_knn with a fresh state (no buffer, no starting radius): the k
 * nearest without any history. Never fails. */
uint32_t helper_knn(const kd_tree *t, const float q[3], uint32_t k, float max_d2, uint32_t *idx, float *d2,
                    float *r2);
/* 1 when a and b are the same tree to the bit (shape, nodes, points),
 * else 0. */
int helper_trees_equal(const kd_tree *a, const kd_tree *b);

#endif

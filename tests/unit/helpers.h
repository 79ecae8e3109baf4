/* helpers: small shared pieces of the unit tests (scenes from text, renders,
 * synthetic photon maps and their representatives). */
#ifndef PM_TEST_HELPERS_H
#define PM_TEST_HELPERS_H

#include "config.h"
#include "estimate.h"
#include "image.h"
#include "photons.h"
#include "reps.h"
#include "scene.h"
#include "stats.h"

/* Parses scene text or aborts the test run with the parser's message. */
scene *helper_scene(const char *text);
/* render_run without progress; prints render_run's message when it fails.
 * Returns render_run's result (PM_OK = 0). */
int helper_render(const scene *sc, const config_render *cfg, unsigned threads, image *out, stats_run *st);

/* A photon map of `count` photons at pos[] (world units), each travelling
 * along dir onto a surface of normal `normal`, power `power` per channel,
 * flags as given; aborts the test run when memory runs out. */
void helper_map(photons_map *m, const float (*pos)[3], uint32_t count, vec3 dir, vec3 normal, float power,
                unsigned flags);
/* The representatives of map m (its flagged photons, all in the tree) in
 * layout `tree`, evaluated with gather g on `threads` threads. Returns 0, or
 * -1 when memory runs out (out is then empty). */
int helper_reps(const photons_map *m, const est_gather *g, config_rep_tree tree, unsigned threads, reps_set *out);

#endif

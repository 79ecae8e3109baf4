/* render: one render's pipeline (the paper's Fig. 1), run in order and
 * timed, with the checks between its steps; it writes no file. */
#ifndef PM_RENDER_H
#define PM_RENDER_H

#include <stddef.h>
#include <stdint.h>

#include "config.h"
#include "image.h"
#include "photons.h"
#include "reps.h"
#include "scene.h"
#include "stats.h"
#include "status.h"

/* Returns the radius cap in scene units: cfg->max_radius if set, else
 * cfg->max_radius_frac of the photons' extent (of the scene's box diagonal
 * when they lie at fewer than two places). Never fails. */
double render_max_radius(const scene *sc, const config_render *cfg, const photons_map *m);

/* The smallest span of the lit scene, relative to its distance from the
 * origin, that renders within 0.5% of the same scene at the origin (2^-38:
 * about 16,000 doubles across the span; results/stability/stability.md). */
#define RENDER_MIN_RELATIVE_EXTENT 0x1p-38

/* Builds (or drops) sc's BVH for cfg->accel. Returns PM_ERR_NOMEM with the
 * reason in err when memory runs out (sc then uses the linear loop). */
pm_status render_prepare(scene *sc, const config_render *cfg, char *err, size_t errlen);

/* Estimates from a pilot whether the photon map fits in mem bytes (0: no
 * limit) and in 2^32-1 photons; with more than one repeat, as the peak of
 * repeats that keep freed memory (mem_keep). Returns PM_ERR_INPUT with the
 * reason in err when it does not, PM_ERR_NOMEM when the pilot runs out of
 * memory. */
pm_status render_check_memory(const scene *sc, const config_render *cfg, uint64_t mem, char *err, size_t errlen);

/* What render_run made. */
typedef struct {
    image img;
    stats_run st;
    /* with cfg->dump_reps: the representatives and the map whose frame
     * places them (render_write_reps); otherwise empty */
    photons_map map;
    reps_set reps;
} render_result;

/* Renders sc with cfg into *out on `threads` workers (>= 1). Returns
 * PM_ERR_NOMEM, or PM_ERR_INPUT for a scene or setting it cannot render
 * faithfully, with the reason in err (out is then empty). */
pm_status render_run(const scene *sc, const config_render *cfg, unsigned threads, int show_progress, render_result *out,
               char *err, size_t errlen);
/* Writes the representatives of r as CSV to f (reps_write_csv). Returns
 * PM_OK, or PM_ERR_IO on a write error. */
pm_status render_write_reps(const render_result *r, FILE *f);
/* Frees what render_run made; a zeroed result is fine. */
void render_result_free(render_result *r);

#endif

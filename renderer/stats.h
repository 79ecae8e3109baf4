/* stats: the monotonic clock, what a render measured (times per phase and
 * counts), and its JSON form. */
#ifndef PM_STATS_H
#define PM_STATS_H

#include <stdint.h>
#include <stdio.h>

#include "config.h"
#include "status.h"

typedef struct {
    /* seconds, monotonic clock */
    double trace, build, precompute, render, total;
    /* photon pass */
    uint64_t photons_emitted, photons_stored, photon_paths_truncated, photons_escaped;
    uint64_t representatives;
    /* eye pass */
    uint64_t samples;             /* eye rays from the camera */
    uint64_t eye_depth_limit_hits;/* specular chains cut at the depth limit */
    uint64_t empty_estimates;     /* diffuse hits with no photon / no agreeing representative in range */
    double mean_radiance[3];      /* over all pixels, per channel (linear, as in the image) */
    uint64_t nonfinite_pixels;
    uint64_t underflow_pixels;    /* a non-zero radiance below the smallest normal float (stored as 0 or subnormal) */
    double max_radius;            /* search radius cap used, scene units */
    uint64_t bytes_photon_map;    /* photon map (tree + payload) */
    uint64_t bytes_representatives;
    /* precomputed, beyond the paper (reps.h) */
    uint64_t reps_evaluated;      /* representatives whose irradiance was computed (all but for --rep-eval lazy) */
    uint64_t rep_fallbacks;       /* eye samples the plane gate sent to the conventional estimate */
} stats_run;

/* Monotonic time in nanoseconds. */
int64_t stats_now_ns(void);
/* Writes the run as one JSON object to f. Returns PM_OK, or PM_ERR_IO on a
 * write error. */
pm_status stats_write_json(FILE *f, const char *scene_path, const config_render *cfg, unsigned threads,
                     const stats_run *st);

#endif

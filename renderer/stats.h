/* stats: what a render measured (times per phase and counts) and its JSON
 * form. */
#ifndef PM_STATS_H
#define PM_STATS_H

#include <stdint.h>
#include <stdio.h>

#include "config.h"
#include "provenance.h"
#include "status.h"
#include "work.h"

/* The timed phases and their total, in the order of stats_repeats' rows. */
enum { STATS_TRACE, STATS_BUILD, STATS_PRECOMPUTE, STATS_RENDER, STATS_TOTAL, STATS_PHASES };

/* Every repeat's times (repeat.h), seconds: t[i][phase] for repeat i, and
 * the minor page faults the process took during repeat i (getrusage's
 * count, every thread's: the fresh pages the repeat touched). */
typedef struct {
    uint32_t n; /* repeats done; 0: one render, whose times are stats_run's */
    double t[CONFIG_MAX_REPEATS][STATS_PHASES];
    uint64_t faults[CONFIG_MAX_REPEATS];
} stats_repeats;

/* What a render measured: the stats file's times and counts. */
typedef struct {
    /* seconds, monotonic clock; over repeats, each phase's minimum and the
     * smallest total (not the sum of the phases' minima) */
    double trace, build, precompute, render, total;
    stats_repeats repeats;
    /* photon pass */
    uint64_t photons_emitted, photons_stored, photon_paths_truncated, photons_escaped;
    uint64_t representatives;
    /* eye pass */
    uint64_t samples;             /* eye rays from the camera */
    uint64_t eye_depth_limit_hits;/* specular chains cut at the depth limit */
    uint64_t empty_estimates;     /* diffuse hits with no photon / no agreeing representative in range */
    double mean_radiance[3];      /* over all pixels, per channel (linear, as in the image) */
    uint64_t nonfinite_pixels;
    uint64_t underflow_pixels;    /* pixels with a channel whose non-zero radiance is below the smallest normal
                                     float (stored as 0 or subnormal) */
    uint64_t flushed_values;      /* such channel values, over all pixels (up to 3 per pixel) */
    double peak_radiance;         /* the largest channel value of any pixel, before its conversion to float
                                     (NaN is not counted: nonfinite_pixels) */
    double max_radius;            /* search radius cap used, scene units */
    double photons_extent;        /* diagonal of the stored photons' bounding box, scene units (0: fewer than
                                     two places) */
    uint64_t bytes_photon_map;    /* photon map (tree + payload) */
    uint64_t bytes_representatives;
    /* precomputed, beyond the paper (reps.h) */
    uint64_t reps_evaluated;      /* representatives whose irradiance was computed (all but for --rep-eval lazy) */
    uint64_t rep_fallbacks;       /* eye samples the plane gate sent to the conventional estimate */
    /* final gathering (--gather, gather.h); zero without it */
    uint64_t caustic_photons;     /* photons in the caustic map (0: none built) */
    uint64_t bytes_caustic_map;   /* the caustic map (tree + payload) */
    uint64_t gather_rays, gather_specular, gather_lookups, gather_empty, gather_fallbacks, gather_missed,
        gather_depth_limit_hits;  /* gather_counts' (gather.h) */
    uint64_t caustic_lookups, caustic_nodes, caustic_points; /* the caustic map's estimates and their kNN work */
    double gather_thread_s;       /* seconds the threads spent casting gather rays and estimating at y, summed */
    double render_thread_s;       /* seconds the threads spent on the eye pass's tiles, summed */
    work_phases work;             /* what each phase did, counted exactly (work.h) */
    provenance_info provenance;   /* the binary and the machine (its strings NULL: "unknown") */
} stats_run;

/* Writes the run as one JSON object to f: "status" is "ok", or "refused"
 * with the reason in "reason" when `refused` is not NULL (the run made no
 * image). Returns PM_OK, or PM_ERR_IO on a write error. */
pm_status stats_write_json(FILE *f, const char *scene_path, const config_render *cfg, unsigned threads,
                           const stats_run *st, const char *refused);
/* Writes s as a JSON string: valid UTF-8 as is, control characters
 * escaped, and each byte that is not valid UTF-8 (a path may hold any bytes)
 * as U+FFFD, so the file always parses. Errors stay in f's error flag. */
void stats_json_string(FILE *f, const char *s);

#endif

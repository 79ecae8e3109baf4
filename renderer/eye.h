/* eye: the eye pass, the integrator that turns the photon map into an
 * image: camera rays on an SxS subpixel grid per pixel (box filter), mirror
 * and glass recursion (both glass branches, weighted by Fresnel), and the
 * radiance estimate at the first diffuse hit (the conventional estimate,
 * or the representatives' lookup), plus direct light by shadow rays when
 * asked; with --gather, final gathering there instead (gather.h). No
 * randomness but the gather's counter-based streams: each pixel depends
 * only on its coordinates, so images are identical for any thread count. */
#ifndef PM_EYE_H
#define PM_EYE_H

#include "config.h"
#include "gather.h"
#include "image.h"
#include "photons.h"
#include "reps.h"
#include "scene.h"
#include "stats.h"
#include "status.h"

/* What the eye pass reads. */
typedef struct {
    const scene *sc;
    const config_render *cfg;
    const photons_map *map;
    const reps_set *reps; /* the precomputed method's, evaluated; unused by the conventional one */
    double max_radius;    /* the gather's radius cap, scene units */
    const photons_map *caustic; /* --gather: the caustic map; NULL: none */
} eye_input;

/* Renders in->cfg's image into *out (allocated here) on `threads` workers
 * (>= 1), a progress bar on stderr if show_progress, and sets st's eye-pass
 * fields (render time, samples, depth-limit hits, empty estimates,
 * underflow and non-finite pixels, mean radiance, the gather's counters). Returns PM_OK, or
 * PM_ERR_NOMEM when memory runs out (out may then hold an image to
 * image_free). */
pm_status eye_render(const eye_input *in, unsigned threads, int show_progress, image *out, stats_run *st);

#endif

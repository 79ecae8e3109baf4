/* eye: the eye pass, which turns the photon map into an image by estimating
 * radiance at each camera path's first diffuse hit (renderer/README.md). */
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
 * (>= 1) and sets st's eye-pass fields. Returns PM_ERR_NOMEM when memory
 * runs out (out may then hold an image to image_free). */
pm_status eye_render(const eye_input *in, unsigned threads, int show_progress, image *out, stats_run *st);

#endif

/* render: the whole pipeline of one render (photon pass, photon map build,
 * precompute for the precomputed method, eye pass) and the eye pass itself:
 * pinhole camera rays on an SxS subpixel grid per pixel (box filter), mirror
 * and glass recursion, the radiance estimate at the first diffuse hit. No
 * randomness in the eye pass: each pixel depends only on its coordinates, so
 * images are identical for any thread count. */
#ifndef PM_RENDER_H
#define PM_RENDER_H

#include <stddef.h>

#include "config.h"
#include "image.h"
#include "photons.h"
#include "scene.h"
#include "stats.h"

/* The pinhole camera's basis for one image aspect, computed once per render. */
typedef struct {
    vec3 origin;
    vec3 fwd;   /* unit view direction */
    vec3 right; /* tan(hfov/2) x the unit right vector */
    vec3 up;    /* tan(hfov/2) x aspect x the unit up vector */
} render_camera;

/* The camera of sc for images of height/width = aspect_h_over_w. */
render_camera render_camera_make(const scene *sc, double aspect_h_over_w);
/* The ray through image-plane point (u, v) in [0,1]^2, v down. */
shape_ray render_camera_at(const render_camera *cam, double u, double v);
/* Both in one call (for tests and tools; the eye pass makes the camera once). */
shape_ray render_camera_ray(const scene *sc, double aspect_h_over_w, double u, double v);

/* The search radius cap in scene units: cfg->max_radius if set, else
 * cfg->max_radius_frac of the photon map's extent (of the scene's
 * bounding-box diagonal when the photons lie at fewer than two places), so
 * that geometry no photon reaches does not change it. */
double render_max_radius(const scene *sc, const config_render *cfg, const photons_map *m);

/* The smallest span of the lit scene, relative to its distance from the
 * origin, that renders within 0.5% of the same scene at the origin (2^-38:
 * about 16,000 doubles across the span; measured in results/stability.md). */
#define RENDER_MIN_RELATIVE_EXTENT 0x1p-38

/* Results of render_run: done, out of memory, a scene or setting the
 * renderer cannot render faithfully (a user input error), or a file it was
 * asked to write (cfg->dump_reps) could not be written. */
enum { RENDER_OK = 0, RENDER_ERR_MEMORY = 1, RENDER_ERR_INPUT = 2, RENDER_ERR_IO = 3 };

/* Renders sc with cfg into *out (allocated here; image_free it) and fills
 * *st; with cfg->dump_reps also writes the representatives there (after the
 * eye pass, outside the times in *st). `threads` workers (>= 1); progress bars on stderr if show_progress.
 * Returns RENDER_OK, or RENDER_ERR_MEMORY / RENDER_ERR_INPUT /
 * RENDER_ERR_IO with the reason in err (out is then empty). */
int render_run(const scene *sc, const config_render *cfg, unsigned threads, int show_progress, image *out,
               stats_run *st, char *err, size_t errlen);

#endif

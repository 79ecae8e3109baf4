/* render: the whole pipeline of one render (photon pass, photon map build,
 * precompute for the precomputed method, eye pass) and the eye pass itself:
 * pinhole camera rays on an SxS subpixel grid per pixel (box filter), mirror
 * and glass recursion, the radiance estimate at the first diffuse hit. No
 * randomness in the eye pass: each pixel depends only on its coordinates, so
 * images are identical for any thread count. */
#ifndef PM_RENDER_H
#define PM_RENDER_H

#include "config.h"
#include "image.h"
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

/* The search radius cap in scene units for cfg on sc. */
double render_max_radius(const scene *sc, const config_render *cfg);

/* Renders sc with cfg into *out (allocated here; image_free it) and fills
 * *st. `threads` workers (>= 1); progress bars on stderr if show_progress.
 * Returns 0, or -1 when memory runs out (out is then empty). */
int render_run(const scene *sc, const config_render *cfg, unsigned threads, int show_progress, image *out,
               stats_run *st);

#endif

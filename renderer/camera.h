/* camera: the pinhole camera of a scene: its basis for one image aspect and
 * the ray through a point of the image plane. */
#ifndef PM_CAMERA_H
#define PM_CAMERA_H

#include "scene.h"
#include "shapes.h"
#include "vec.h"

/* The pinhole camera's basis for one image aspect, computed once per render. */
typedef struct {
    vec3 origin;
    vec3 fwd;   /* unit view direction */
    vec3 right; /* tan(hfov/2) x the unit right vector */
    vec3 up;    /* tan(hfov/2) x aspect x the unit up vector */
} camera;

/* The camera of sc for images of height/width = aspect_h_over_w; never fails. */
camera camera_make(const scene *sc, double aspect_h_over_w);
/* The ray through image-plane point (u, v) in [0,1]^2, v down. */
shape_ray camera_at(const camera *cam, double u, double v);
/* Both in one call (for tests and tools; the eye pass makes the camera once). */
shape_ray camera_ray(const scene *sc, double aspect_h_over_w, double u, double v);

#endif

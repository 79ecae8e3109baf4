/* camera: pinhole camera rays (camera.h). */
#include "camera.h"

#include <math.h>

camera camera_make(const scene *sc, double aspect_h_over_w)
{
    const scene_camera *c = &sc->camera;
    camera cam;
    cam.origin = c->position;
    cam.fwd = vec_norm(vec_sub(c->look_at, c->position));
    vec3 right = vec_norm(vec_cross(cam.fwd, c->up));
    vec3 up = vec_cross(right, cam.fwd);
    double hw = tan(0.5 * c->hfov_deg * VEC_PI / 180.0);
    cam.right = vec_scale(right, hw);
    cam.up = vec_scale(up, hw * aspect_h_over_w);
    return cam;
}

shape_ray camera_at(const camera *cam, double u, double v)
{
    vec3 d = vec_add(cam->fwd, vec_add(vec_scale(cam->right, 2.0 * u - 1.0), vec_scale(cam->up, 1.0 - 2.0 * v)));
    shape_ray r = {cam->origin, vec_norm(d)};
    return r;
}

shape_ray camera_ray(const scene *sc, double aspect_h_over_w, double u, double v)
{
    camera cam = camera_make(sc, aspect_h_over_w);
    return camera_at(&cam, u, v);
}

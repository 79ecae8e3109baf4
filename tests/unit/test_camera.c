/* test_camera: the pinhole camera. The ray through the image centre leaves
 * the camera along the view direction; the image's corners are symmetric
 * about it, left/right and up/down (v grows downwards); camera_ray is
 * camera_make then camera_at. */
#include <math.h>

#include "camera.h"
#include "check.h"
#include "helpers.h"
#include "tests.h"

static const char *camera_scene = "camera position 1 2 3 look_at 1 2 0 up 0 1 0 fov 90\n"
                                  "light point position 0 1 0 power 1 1 1\n"
                                  "material w lambert rho 0.5 0.5 0.5\n"
                                  "sphere center 1 2 -1 radius 0.5 material w\n";

void test_camera_centre_ray_along_view(void)
{
    scene *sc = helper_scene(camera_scene);
    camera cam = camera_make(sc, 0.75);
    shape_ray r = camera_at(&cam, 0.5, 0.5);
    CHECK(r.origin.x == 1.0 && r.origin.y == 2.0 && r.origin.z == 3.0);
    vec3 d = vec_norm(r.dir);
    CHECK_NEAR(d.x, 0.0, 1e-15);
    CHECK_NEAR(d.y, 0.0, 1e-15);
    CHECK_NEAR(d.z, -1.0, 1e-15); /* towards look_at */
    /* negative control: an off-centre ray is not along the view */
    CHECK(fabs(vec_norm(camera_at(&cam, 0.9, 0.5).dir).x) > 0.1);
    scene_free(sc);
}

void test_camera_corners_symmetric(void)
{
    scene *sc = helper_scene(camera_scene);
    camera cam = camera_make(sc, 0.75);
    vec3 tl = vec_norm(camera_at(&cam, 0.0, 0.0).dir), br = vec_norm(camera_at(&cam, 1.0, 1.0).dir);
    vec3 tr = vec_norm(camera_at(&cam, 1.0, 0.0).dir);
    CHECK(tl.x < 0.0 && tl.y > 0.0); /* u = 0 is left, v = 0 is up */
    CHECK(br.x > 0.0 && br.y < 0.0);
    CHECK_NEAR(tl.x, -br.x, 1e-15);
    CHECK_NEAR(tl.y, -br.y, 1e-15);
    CHECK_NEAR(tr.x, -tl.x, 1e-15);
    /* fov 90 is horizontal: the edge's half-angle is 45 degrees */
    vec3 right = vec_norm(camera_at(&cam, 1.0, 0.5).dir);
    CHECK_NEAR(right.x, -right.z, 1e-15);
    /* the aspect sets the vertical extent: 0.75 of the horizontal */
    vec3 top = camera_at(&cam, 0.5, 0.0).dir;
    CHECK_NEAR(top.y / -top.z, 0.75, 1e-15);
    shape_ray a = camera_ray(sc, 0.75, 0.3, 0.7), b = camera_at(&cam, 0.3, 0.7);
    CHECK(a.dir.x == b.dir.x && a.dir.y == b.dir.y && a.dir.z == b.dir.z);
    scene_free(sc);
}

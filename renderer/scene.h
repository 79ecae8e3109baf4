/* scene: the scene model (camera, one point light, materials, shapes) and
 * its parser for the line-oriented .scene format documented in
 * scenes/README.md. Parse errors name file:line:col. */
#ifndef PM_SCENE_H
#define PM_SCENE_H

#include <stddef.h>
#include <stdint.h>

#include "bvh.h"
#include "material.h"
#include "shapes.h"
#include "status.h"
#include "vec.h"

/* The pinhole camera as the scene file gives it. */
typedef struct {
    vec3 position, look_at, up;
    double hfov_deg; /* horizontal field of view, degrees */
} scene_camera;

/* The one point light. */
typedef struct {
    vec3 position;
    vec3 power; /* RGB watts; intensity = power / (4 pi) W/sr */
} scene_light;

/* A parsed scene; scene_free frees it. */
typedef struct {
    scene_camera camera;
    scene_light light;
    material *materials;
    size_t nmaterials;
    shape *shapes;
    size_t nshapes;
    int *material_lines;       /* the scene file's line of each material, or NULL (a scene not parsed) */
    int *shape_lines;          /* the scene file's line of each shape, or NULL (a scene not parsed) */
    vec3 bounds_lo, bounds_hi; /* of all shapes and the light */
    double scale;              /* bounding-box diagonal: the unit for epsilons and radii */
    bvh *accel;                /* the shapes' BVH, or NULL: rays test every shape (scene_set_accel; the
                                  parser builds none) */
} scene;

/* How rays find the shapes: a BVH when the scene has at least
 * SCENE_BVH_MIN_SHAPES shapes (auto), always, or never (a linear loop over
 * the shapes). Every mode gives bit-identical results (bvh.h). */
typedef enum { SCENE_ACCEL_AUTO = 0, SCENE_ACCEL_BVH = 1, SCENE_ACCEL_LINEAR = 2 } scene_accel;
/* Below this many shapes the linear loop is faster than the BVH (measured:
 * README.md, "Ray casting"). The text form is for the usage line. */
#define SCENE_BVH_MIN_SHAPES 24
#define SCENE_BVH_MIN_SHAPES_TEXT "24"

/* Parses len bytes of scene text; name is used in messages. On success
 * returns PM_OK with *out owned by the caller (scene_free). On failure
 * returns PM_ERR_INPUT (err holds "name:line:col: message") or
 * PM_ERR_NOMEM (err says so), and *out = NULL. */
pm_status scene_parse_buffer(const char *name, const char *text, size_t len, scene **out, char *err, size_t errlen);
/* Reads and parses a file; same contract as scene_parse_buffer, and an
 * unreadable file is PM_ERR_IO with "path: reason" in err. */
pm_status scene_load(const char *path, scene **out, char *err, size_t errlen);
/* Builds (or drops) the scene's BVH for `mode` (the parser leaves a scene
 * without one; the render pipeline calls this first). Returns PM_OK, or
 * PM_ERR_NOMEM when memory runs out (the scene then has no BVH and still
 * works, by the linear loop). */
pm_status scene_set_accel(scene *s, scene_accel mode);
/* Frees a scene; NULL is fine. */
void scene_free(scene *s);
/* The index of the first opaque (not glass) sphere of s that encloses
 * exactly one of the points a and b (spheres are the model's one closed
 * shape: rectangles enclose nothing by themselves), so that no light path
 * joins them, or SCENE_NO_SHAPE when none does; never fails. */
#define SCENE_NO_SHAPE (-1)
int scene_sphere_between(const scene *s, vec3 a, vec3 b);

/* A ray's hit: the shape, where, and the normal facing the side the ray
 * came from. */
typedef struct {
    int shape;   /* index into scene.shapes */
    double t;    /* distance along the ray */
    vec3 p;      /* the point */
    vec3 n;      /* unit normal on the ray's side */
    int front;   /* 1 when the ray met the geometric normal's side (outside of a sphere) */
    double eps;  /* how far a spawned ray's origin moves off the surface (scene_spawn) */
} scene_hit;

/* The nearest hit of r closer than tmax: returns 1 and fills *h, or 0 on a
 * miss. */
int scene_intersect(const scene *s, const shape_ray *r, double tmax, scene_hit *h);
/* 1 if any shape blocks r closer than tmax, else 0; stops at the first hit
 * (shadow rays need no nearest hit). */
int scene_occluded(const scene *s, const shape_ray *r, double tmax);
/* scene_intersect and scene_occluded that add the ray-shape tests they
 * made (shape_intersect calls) to *tests. */
int scene_intersect_counted(const scene *s, const shape_ray *r, double tmax, scene_hit *h, uint64_t *tests);
int scene_occluded_counted(const scene *s, const shape_ray *r, double tmax, uint64_t *tests);
/* A ray leaving the hit h in direction dir: from the side it came from
 * (same_side = 1: reflection) or through the surface (0: refraction), its
 * origin moved off the surface by h->eps so it cannot hit the surface it
 * leaves again (inline: every gather ray and bounce spawns one). */
static inline shape_ray scene_spawn(const scene_hit *h, vec3 dir, int same_side)
{
    shape_ray r = {vec_madd(h->p, h->n, same_side ? h->eps : -h->eps), dir};
    return r;
}

#endif

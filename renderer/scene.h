/* scene: the scene model (camera, one point light, materials, shapes) and
 * its parser for the line-oriented .scene format documented in
 * scenes/README.md. Parse errors name file:line:col. */
#ifndef PM_SCENE_H
#define PM_SCENE_H

#include <stddef.h>

#include "material.h"
#include "shapes.h"
#include "vec.h"

typedef struct {
    vec3 position, look_at, up;
    double hfov_deg; /* horizontal field of view, degrees */
} scene_camera;

typedef struct {
    vec3 position;
    vec3 power; /* RGB watts; intensity = power / (4 pi) W/sr */
} scene_light;

typedef struct {
    scene_camera camera;
    scene_light light;
    material *materials;
    size_t nmaterials;
    shape *shapes;
    size_t nshapes;
    vec3 bounds_lo, bounds_hi; /* of all shapes and the light */
    double scale;              /* bounding-box diagonal: the unit for epsilons and radii */
} scene;

/* Result codes of the parser: SCENE_OK, a user input error (exit 2), or a
 * runtime failure such as I/O or memory (exit 1). */
enum { SCENE_OK = 0, SCENE_ERR_RUNTIME = 1, SCENE_ERR_INPUT = 2 };

/* Parses len bytes of scene text; name is used in messages. On success
 * returns SCENE_OK with *out owned by the caller (scene_free). On failure
 * returns SCENE_ERR_INPUT or SCENE_ERR_RUNTIME, *out = NULL, and err holds
 * "name:line:col: message". */
int scene_parse_buffer(const char *name, const char *text, size_t len, scene **out, char *err, size_t errlen);
/* Reads and parses a file; same contract as scene_parse_buffer (an unreadable
 * file is SCENE_ERR_RUNTIME with "path: reason"). */
int scene_load(const char *path, scene **out, char *err, size_t errlen);
/* Frees a scene; NULL is fine. */
void scene_free(scene *s);

/* Nearest hit along r in (tmin, tmax): returns the shape index and sets *t,
 * or returns -1 on a miss. */
int scene_intersect(const scene *s, const ray *r, double tmin, double tmax, double *t);
/* 1 if any shape blocks r in (tmin, tmax), else 0; stops at the first hit
 * (shadow rays need no nearest hit). */
int scene_occluded(const scene *s, const ray *r, double tmin, double tmax);
/* The self-intersection epsilon for this scene (relative to its size). */
double scene_epsilon(const scene *s);

#endif

/* shapes: the two primitives the scenes need, spheres and planar rectangles,
 * and ray intersection against them. Both are two-sided: a ray from inside a
 * sphere hits its far wall. */
#ifndef PM_SHAPES_H
#define PM_SHAPES_H

#include "vec.h"

typedef enum { SHAPE_SPHERE = 0, SHAPE_RECT = 1 } shape_kind;

typedef struct {
    shape_kind kind;
    int material;        /* index into scene.materials */
    /* sphere */
    vec3 center;
    double radius;
    /* rectangle: corner + u*edge1 + v*edge2, u, v in [0,1] */
    vec3 corner, edge1, edge2;
    vec3 normal;         /* rectangle: unit edge1 x edge2 */
    double inv_len2_1;   /* 1/|edge1|^2 */
    double inv_len2_2;   /* 1/|edge2|^2 */
    double magnitude;    /* largest |coordinate| of the shape's bounds: the scale of its rounding errors */
} shape;

typedef struct {
    vec3 origin;
    vec3 dir; /* unit length */
} shape_ray;

/* A sphere; radius > 0 (asserted). */
shape shape_sphere(vec3 center, double radius, int material);
/* A rectangle from a corner and two perpendicular non-zero edges (asserted). */
shape shape_rect(vec3 corner, vec3 edge1, vec3 edge2, int material);

/* Nearest hit of r with s at distance t in (tmin, tmax). Returns 1 and sets *t
 * on a hit, 0 on a miss (including a ray exactly parallel to a rectangle). */
int shape_intersect(const shape *s, const shape_ray *r, double tmin, double tmax, double *t);
/* The point at distance t along r on s, moved onto the surface (the sphere
 * or the rectangle's plane) so that its error does not grow along chains of
 * reflections. */
vec3 shape_hit_point(const shape *s, const shape_ray *r, double t);
/* Unit geometric normal of s at point p on it: outward for spheres, edge1 x
 * edge2 for rectangles (not oriented to any ray). */
vec3 shape_normal(const shape *s, vec3 p);
/* Axis-aligned bounds of s. */
void shape_bounds(const shape *s, vec3 *lo, vec3 *hi);

#endif

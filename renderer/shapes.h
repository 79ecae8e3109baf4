/* shapes: the two primitives the scenes need, spheres and planar rectangles,
 * and ray intersection against them. Both are two-sided: a ray from inside a
 * sphere hits its far wall. */
#ifndef PM_SHAPES_H
#define PM_SHAPES_H

#include "vec.h"

typedef enum { SHAPE_SPHERE = 0, SHAPE_RECT = 1 } shape_kind;

#define SHAPE_NO_AXIS (-1) /* shape.axis of a shape that is not an axis-aligned rectangle */

/* A sphere or a rectangle, with values precomputed for its hit test. */
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
    int axis[3];         /* rectangle: the one axis of its normal, edge1, edge2 when each has only one
                            non-zero component (an axis-aligned rectangle), else SHAPE_NO_AXIS */
    struct {             /* axis-aligned rectangle: the components its hit test reads (a = axis[0], a1 = axis[1], */
        double na;       /*   a2 = axis[2]): normal[a] */
        double c0;       /*   corner[a] */
        double c1;       /*   corner[a1] */
        double c2;       /*   corner[a2] */
        double e1;       /*   edge1[a1] */
        double e2;       /*   edge2[a2] */
    } aligned;
} shape;

/* A ray: origin and unit direction. */
typedef struct {
    vec3 origin;
    vec3 dir; /* unit length */
} shape_ray;

/* A ray's origin and direction as arrays, read by component index in the
 * axis-aligned rectangle's test (shape_ray_axes_of makes it once per ray). */
typedef struct {
    double o[3];
    double d[3];
} shape_ray_axes;

/* A sphere; radius > 0 (asserted). */
shape shape_sphere(vec3 center, double radius, int material);
/* A rectangle from a corner and two perpendicular non-zero edges (asserted). */
shape shape_rect(vec3 corner, vec3 edge1, vec3 edge2, int material);

/* The point at distance t along r on s, moved onto the surface (the sphere
 * or the rectangle's plane) so that its error does not grow along chains of
 * reflections (inline, as shape_normal: every hit computes both). */
static inline vec3 shape_hit_point(const shape *s, const shape_ray *r, double t)
{
    vec3 p = vec_madd(r->origin, r->dir, t);
    if (s->kind == SHAPE_SPHERE) {
        vec3 d = vec_sub(p, s->center);
        double len = vec_len(d);
        return len > 0.0 ? vec_madd(s->center, d, s->radius / len) : p;
    }
    return vec_madd(p, s->normal, -vec_dot(vec_sub(p, s->corner), s->normal));
}

/* Unit geometric normal of s at point p on it: outward for spheres, edge1 x
 * edge2 for rectangles (not oriented to any ray). */
static inline vec3 shape_normal(const shape *s, vec3 p)
{
    if (s->kind == SHAPE_SPHERE)
        return vec_scale(vec_sub(p, s->center), 1.0 / s->radius);
    return s->normal;
}

/* Axis-aligned bounds of s. */
void shape_bounds(const shape *s, vec3 *lo, vec3 *hi);

/* ---- ray/shape intersection: inline, since the scene's loop and the BVH
 * run it for every shape a ray meets (sphere: the numerically careful
 * quadratic of Haines et al., "Precision improvements for ray/sphere
 * intersection", Ray Tracing Gems ch. 7) ---- */

/* Sphere and rectangle cases of shape_intersect (the same contract). */
static inline int shape_sphere_intersect_(const shape *s, const shape_ray *r, double tmin, double tmax, double *t)
{
    vec3 oc = vec_sub(r->origin, s->center);
    double b = vec_dot(oc, r->dir);
    double r2 = s->radius * s->radius;
    double c = vec_len2(oc) - r2;
    /* outside (c > 0) and moving away (b > 0): both roots are negative (their
     * product is c, their sum -2b); the full computation below would find the
     * same, only later */
    if (c > 0.0 && b > 0.0)
        return 0;
    vec3 f = vec_madd(oc, r->dir, -b);          /* oc minus its projection on dir */
    double disc = r2 - vec_len2(f);
    if (disc < 0.0)
        return 0;
    double q = -b - copysign(sqrt(disc), b);
    double t0, t1;
    if (q == 0.0) { /* ray through the centre's tangent point: one double root */
        t0 = t1 = -b;
    } else {
        t0 = c / q;
        t1 = q;
    }
    if (t0 > t1) {
        double tmp = t0;
        t0 = t1;
        t1 = tmp;
    }
    if (t0 > tmin && t0 < tmax) {
        *t = t0;
        return 1;
    }
    if (t1 > tmin && t1 < tmax) {
        *t = t1;
        return 1;
    }
    return 0;
}

static inline shape_ray_axes shape_ray_axes_of(const shape_ray *r)
{
    shape_ray_axes a = {{r->origin.x, r->origin.y, r->origin.z}, {r->dir.x, r->dir.y, r->dir.z}};
    return a;
}

/* An axis-aligned rectangle: each dot product with its normal or an edge is
 * one product, exactly what the general code computes (the other terms are
 * products with exact zeros, which add nothing but the sign of a zero, and
 * no test below tells +0 from -0), so the result is the same to the bit. */
static inline int shape_rect_aligned_intersect_(const shape *s, const shape_ray_axes *r, double tmin, double tmax,
                                                double *t)
{
    int a = s->axis[0], a1 = s->axis[1], a2 = s->axis[2];
    double na = s->aligned.na;
    double denom = r->d[a] * na;
    if (denom == 0.0)
        return 0;
    double num = (s->aligned.c0 - r->o[a]) * na;
    if (tmin >= 0.0 && !(num > 0.0 ? denom > 0.0 : num < 0.0 && denom < 0.0))
        return 0;
    double th = num / denom;
    if (!(th > tmin && th < tmax))
        return 0;
    double d1 = r->o[a1] + r->d[a1] * th - s->aligned.c1;
    double u = d1 * s->aligned.e1 * s->inv_len2_1;
    if (u < 0.0 || u > 1.0)
        return 0;
    double d2 = r->o[a2] + r->d[a2] * th - s->aligned.c2;
    double v = d2 * s->aligned.e2 * s->inv_len2_2;
    if (v < 0.0 || v > 1.0)
        return 0;
    *t = th;
    return 1;
}

/* A rectangle that is not axis-aligned. */
static inline int shape_rect_intersect_(const shape *s, const shape_ray *r, double tmin, double tmax, double *t)
{
    double denom = vec_dot(r->dir, s->normal);
    if (denom == 0.0)
        return 0;
    double num = vec_dot(vec_sub(s->corner, r->origin), s->normal);
    /* th = num / denom <= 0 unless both have the same sign: no division
     * (only valid while tmin >= 0, as every caller passes) */
    if (tmin >= 0.0 && !(num > 0.0 ? denom > 0.0 : num < 0.0 && denom < 0.0))
        return 0;
    double th = num / denom;
    if (!(th > tmin && th < tmax))
        return 0;
    vec3 d = vec_sub(vec_madd(r->origin, r->dir, th), s->corner);
    double u = vec_dot(d, s->edge1) * s->inv_len2_1;
    double v = vec_dot(d, s->edge2) * s->inv_len2_2;
    if (u < 0.0 || u > 1.0 || v < 0.0 || v > 1.0)
        return 0;
    *t = th;
    return 1;
}

/* Nearest hit of r with s at distance t in (tmin, tmax). Returns 1 and sets *t
 * on a hit, 0 on a miss (including a ray exactly parallel to a rectangle). */
static inline int shape_intersect(const shape *s, const shape_ray *r, double tmin, double tmax, double *t)
{
    if (s->kind == SHAPE_SPHERE)
        return shape_sphere_intersect_(s, r, tmin, tmax, t);
    if (s->axis[0] != SHAPE_NO_AXIS) {
        shape_ray_axes ra = shape_ray_axes_of(r);
        return shape_rect_aligned_intersect_(s, &ra, tmin, tmax, t);
    }
    return shape_rect_intersect_(s, r, tmin, tmax, t);
}

/* shape_intersect with r's components also given as ra (shape_ray_axes_of(r)),
 * for loops that test one ray against many shapes (inlined always: the
 * ray's values stay in registers across the loop). */
static inline __attribute__((always_inline)) int shape_intersect_axes(const shape *s, const shape_ray *r, const shape_ray_axes *ra, double tmin,
                                       double tmax, double *t)
{
    if (s->axis[0] != SHAPE_NO_AXIS) /* only axis-aligned rectangles have axes */
        return shape_rect_aligned_intersect_(s, ra, tmin, tmax, t);
    if (s->kind == SHAPE_SPHERE)
        return shape_sphere_intersect_(s, r, tmin, tmax, t);
    return shape_rect_intersect_(s, r, tmin, tmax, t);
}


#endif

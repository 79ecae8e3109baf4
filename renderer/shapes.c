/* shapes: ray/sphere (numerically careful quadratic, Haines et al., "Precision
 * improvements for ray/sphere intersection", Ray Tracing Gems ch. 7) and
 * ray/rectangle intersection. */
#include "shapes.h"

#include <assert.h>

/* Largest |coordinate| of s's bounds. */
static double bounds_magnitude(const shape *s)
{
    vec3 lo, hi;
    shape_bounds(s, &lo, &hi);
    return fmax(fmax(fmax(fabs(lo.x), fabs(lo.y)), fmax(fabs(lo.z), fabs(hi.x))), fmax(fabs(hi.y), fabs(hi.z)));
}

shape shape_sphere(vec3 center, double radius, int material)
{
    assert(radius > 0.0 && isfinite(radius));
    shape s = {0};
    s.kind = SHAPE_SPHERE;
    s.material = material;
    s.center = center;
    s.radius = radius;
    s.magnitude = bounds_magnitude(&s);
    return s;
}

shape shape_rect(vec3 corner, vec3 edge1, vec3 edge2, int material)
{
    double l1 = vec_len2(edge1), l2 = vec_len2(edge2);
    assert(l1 > 0.0 && l2 > 0.0);
    shape s = {0};
    s.kind = SHAPE_RECT;
    s.material = material;
    s.corner = corner;
    s.edge1 = edge1;
    s.edge2 = edge2;
    s.normal = vec_norm(vec_cross(edge1, edge2));
    s.inv_len2_1 = 1.0 / l1;
    s.inv_len2_2 = 1.0 / l2;
    s.magnitude = bounds_magnitude(&s);
    return s;
}

static int sphere_intersect(const shape *s, const shape_ray *r, double tmin, double tmax, double *t)
{
    vec3 oc = vec_sub(r->origin, s->center);
    double b = vec_dot(oc, r->dir);
    vec3 f = vec_madd(oc, r->dir, -b);          /* oc minus its projection on dir */
    double r2 = s->radius * s->radius;
    double disc = r2 - vec_len2(f);
    if (disc < 0.0)
        return 0;
    double c = vec_len2(oc) - r2;
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

static int rect_intersect(const shape *s, const shape_ray *r, double tmin, double tmax, double *t)
{
    double denom = vec_dot(r->dir, s->normal);
    if (denom == 0.0)
        return 0;
    double th = vec_dot(vec_sub(s->corner, r->origin), s->normal) / denom;
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

int shape_intersect(const shape *s, const shape_ray *r, double tmin, double tmax, double *t)
{
    return s->kind == SHAPE_SPHERE ? sphere_intersect(s, r, tmin, tmax, t)
                                   : rect_intersect(s, r, tmin, tmax, t);
}

vec3 shape_hit_point(const shape *s, const shape_ray *r, double t)
{
    vec3 p = vec_madd(r->origin, r->dir, t);
    if (s->kind == SHAPE_SPHERE) {
        vec3 d = vec_sub(p, s->center);
        double len = vec_len(d);
        return len > 0.0 ? vec_madd(s->center, d, s->radius / len) : p;
    }
    return vec_madd(p, s->normal, -vec_dot(vec_sub(p, s->corner), s->normal));
}

vec3 shape_normal(const shape *s, vec3 p)
{
    if (s->kind == SHAPE_SPHERE)
        return vec_scale(vec_sub(p, s->center), 1.0 / s->radius);
    return s->normal;
}

void shape_bounds(const shape *s, vec3 *lo, vec3 *hi)
{
    if (s->kind == SHAPE_SPHERE) {
        vec3 r = vec_make(s->radius, s->radius, s->radius);
        *lo = vec_sub(s->center, r);
        *hi = vec_add(s->center, r);
        return;
    }
    vec3 p[4] = {s->corner, vec_add(s->corner, s->edge1), vec_add(s->corner, s->edge2),
                 vec_add(vec_add(s->corner, s->edge1), s->edge2)};
    *lo = *hi = p[0];
    for (int i = 1; i < 4; i++) {
        *lo = vec_make(fmin(lo->x, p[i].x), fmin(lo->y, p[i].y), fmin(lo->z, p[i].z));
        *hi = vec_make(fmax(hi->x, p[i].x), fmax(hi->y, p[i].y), fmax(hi->z, p[i].z));
    }
}

/* shapes: constructors and bounds of the two shapes (hit points, normals
 * and the ray intersections are inline in shapes.h). */
#include "shapes.h"

#include <assert.h>

/* Largest |coordinate| of s's bounds. */
static double bounds_magnitude(const shape *s)
{
    vec3 lo, hi;
    shape_bounds(s, &lo, &hi);
    return fmax(fmax(fmax(fabs(lo.x), fabs(lo.y)), fmax(fabs(lo.z), fabs(hi.x))), fmax(fabs(hi.y), fabs(hi.z)));
}

/* The axis of v's only non-zero component, or SHAPE_NO_AXIS. */
static int single_axis(vec3 v)
{
    int nonzero = (v.x != 0.0) + (v.y != 0.0) + (v.z != 0.0);
    if (nonzero != 1)
        return SHAPE_NO_AXIS;
    return v.x != 0.0 ? 0 : v.y != 0.0 ? 1 : 2;
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
    s.axis[0] = s.axis[1] = s.axis[2] = SHAPE_NO_AXIS;
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
    vec3 v[3] = {s.normal, edge1, edge2};
    for (int i = 0; i < 3; i++)
        s.axis[i] = single_axis(v[i]);
    if (s.axis[0] == SHAPE_NO_AXIS || s.axis[1] == SHAPE_NO_AXIS || s.axis[2] == SHAPE_NO_AXIS)
        s.axis[0] = s.axis[1] = s.axis[2] = SHAPE_NO_AXIS;
    if (s.axis[0] != SHAPE_NO_AXIS) {
        double n[3] = {s.normal.x, s.normal.y, s.normal.z}, c[3] = {corner.x, corner.y, corner.z};
        double e1[3] = {edge1.x, edge1.y, edge1.z}, e2[3] = {edge2.x, edge2.y, edge2.z};
        s.aligned.na = n[s.axis[0]];
        s.aligned.c0 = c[s.axis[0]];
        s.aligned.c1 = c[s.axis[1]];
        s.aligned.c2 = c[s.axis[2]];
        s.aligned.e1 = e1[s.axis[1]];
        s.aligned.e2 = e2[s.axis[2]];
    }
    return s;
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

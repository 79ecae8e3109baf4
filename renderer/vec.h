/* vec: 3-vectors (also used as linear RGB) and the small inline math the
 * renderer shares. Everything here is pure and header-only. */
#ifndef PM_VEC_H
#define PM_VEC_H

#include <math.h>

typedef struct {
    double x, y, z;
} vec3;

#define VEC_PI 3.14159265358979323846

static inline vec3 vec_make(double x, double y, double z) { vec3 v = {x, y, z}; return v; }
static inline vec3 vec_add(vec3 a, vec3 b) { return vec_make(a.x + b.x, a.y + b.y, a.z + b.z); }
static inline vec3 vec_sub(vec3 a, vec3 b) { return vec_make(a.x - b.x, a.y - b.y, a.z - b.z); }
static inline vec3 vec_mul(vec3 a, vec3 b) { return vec_make(a.x * b.x, a.y * b.y, a.z * b.z); }
static inline vec3 vec_scale(vec3 a, double s) { return vec_make(a.x * s, a.y * s, a.z * s); }
static inline vec3 vec_neg(vec3 a) { return vec_make(-a.x, -a.y, -a.z); }
static inline double vec_dot(vec3 a, vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
static inline vec3 vec_cross(vec3 a, vec3 b)
{
    return vec_make(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}
static inline double vec_len2(vec3 a) { return vec_dot(a, a); }
static inline double vec_len(vec3 a) { return sqrt(vec_dot(a, a)); }
/* Unit vector along a; a must not be zero. */
static inline vec3 vec_norm(vec3 a) { return vec_scale(a, 1.0 / vec_len(a)); }
/* a + b*s */
static inline vec3 vec_madd(vec3 a, vec3 b, double s) { return vec_make(a.x + b.x * s, a.y + b.y * s, a.z + b.z * s); }
/* max and min of two finite numbers, without libm's NaN handling (fmax is a
 * library call the compiler cannot inline) */
static inline double vec_max2(double a, double b) { return a > b ? a : b; }
static inline double vec_min2(double a, double b) { return a < b ? a : b; }
static inline double vec_maxc(vec3 a) { return vec_max2(a.x, vec_max2(a.y, a.z)); }
/* Largest |component| of a. */
static inline double vec_max_abs(vec3 a) { return vec_max2(fabs(a.x), vec_max2(fabs(a.y), fabs(a.z))); }

/* An orthonormal basis (t, b) completing the unit vector n (Duff et al. 2017). */
static inline void vec_basis(vec3 n, vec3 *t, vec3 *b)
{
    double sign = copysign(1.0, n.z);
    double a = -1.0 / (sign + n.z);
    double c = n.x * n.y * a;
    *t = vec_make(1.0 + sign * n.x * n.x * a, sign * c, -sign * n.x);
    *b = vec_make(c, sign + n.y * n.y * a, -n.y);
}

#endif

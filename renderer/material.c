/* material: reflect, refract, exact unpolarised Fresnel, cosine sampling. */
#include "material.h"

#include <assert.h>

const char *material_kind_name(material_kind k)
{
    switch (k) {
    case MATERIAL_LAMBERT: return "lambert";
    case MATERIAL_MIRROR: return "mirror";
    case MATERIAL_GLASS: return "glass";
    }
    return "?";
}

vec3 material_reflect(vec3 d, vec3 n)
{
    return vec_madd(d, n, -2.0 * vec_dot(d, n));
}

double material_glass_split(vec3 d, vec3 n, int front, double ior, vec3 *refr, int *can_refract)
{
    double n1 = front ? 1.0 : ior, n2 = front ? ior : 1.0;
    double fr = material_fresnel(-vec_dot(d, n), n1, n2);
    *can_refract = material_refract(d, n, n1 / n2, refr);
    return *can_refract ? fr : 1.0;
}

double material_fresnel(double cos_i, double n1, double n2)
{
    assert(n1 > 0.0 && n2 > 0.0);
    cos_i = vec_min2(vec_max2(cos_i, 0.0), 1.0);
    double sin_t = n1 / n2 * sqrt(vec_max2(0.0, 1.0 - cos_i * cos_i));
    if (sin_t >= 1.0)
        return 1.0;
    double cos_t = sqrt(vec_max2(0.0, 1.0 - sin_t * sin_t));
    double rs = (n1 * cos_i - n2 * cos_t) / (n1 * cos_i + n2 * cos_t);
    double rp = (n1 * cos_t - n2 * cos_i) / (n1 * cos_t + n2 * cos_i);
    return 0.5 * (rs * rs + rp * rp);
}

int material_refract(vec3 d, vec3 n, double eta, vec3 *out)
{
    double cos_i = -vec_dot(d, n);
    double k = 1.0 - eta * eta * (1.0 - cos_i * cos_i);
    if (k < 0.0)
        return 0;
    *out = vec_norm(vec_add(vec_scale(d, eta), vec_scale(n, eta * cos_i - sqrt(k))));
    return 1;
}

vec3 material_sample_cosine(vec3 n, double u1, double u2)
{
    double r = sqrt(u1), phi = 2.0 * VEC_PI * u2;
    double x = r * cos(phi), y = r * sin(phi), z = sqrt(vec_max2(0.0, 1.0 - u1));
    vec3 t, b;
    vec_basis(n, &t, &b);
    return vec_norm(vec_add(vec_add(vec_scale(t, x), vec_scale(b, y)), vec_scale(n, z)));
}

/* test_material: Fresnel reflectance (energy, total internal reflection),
 * Snell refraction and cosine-weighted sampling. */
#include <math.h>

#include "check.h"
#include "material.h"
#include "rng.h"
#include "tests.h"

/* Transmittance from the Fresnel transmission amplitudes, independent of R. */
static double fresnel_t(double cos_i, double n1, double n2)
{
    double sin_t = n1 / n2 * sqrt(1.0 - cos_i * cos_i);
    if (sin_t >= 1.0)
        return 0.0;
    double cos_t = sqrt(1.0 - sin_t * sin_t);
    double ts = 2 * n1 * cos_i / (n1 * cos_i + n2 * cos_t);
    double tp = 2 * n1 * cos_i / (n2 * cos_i + n1 * cos_t);
    return (n2 * cos_t) / (n1 * cos_i) * 0.5 * (ts * ts + tp * tp);
}

void test_fresnel_energy_and_tir(void)
{
    CHECK_NEAR(material_fresnel(1.0, 1.0, 1.5), 0.04, 1e-12);
    CHECK_NEAR(material_fresnel(1.0, 1.5, 1.0), 0.04, 1e-12);
    for (int i = 1; i <= 100; i++) {
        double c = i / 100.0;
        CHECK_NEAR(material_fresnel(c, 1.0, 1.5) + fresnel_t(c, 1.0, 1.5), 1.0, 1e-12);
        if (fresnel_t(c, 1.5, 1.0) > 0.0)
            CHECK_NEAR(material_fresnel(c, 1.5, 1.0) + fresnel_t(c, 1.5, 1.0), 1.0, 1e-12);
    }
    /* critical angle of glass to air: asin(1/1.5) = 41.81 degrees */
    double crit = asin(1.0 / 1.5);
    double past = cos(crit + 1e-6), before = cos(crit - 1e-3);
    CHECK(material_fresnel(past, 1.5, 1.0) == 1.0);
    CHECK(material_fresnel(before, 1.5, 1.0) < 1.0);
    vec3 n = vec_make(0, 0, 1), out;
    vec3 d_past = vec_make(sin(crit + 1e-6), 0, -cos(crit + 1e-6));
    CHECK(!material_refract(d_past, n, 1.5, &out));
    vec3 d_before = vec_make(sin(crit - 1e-3), 0, -cos(crit - 1e-3));
    CHECK(material_refract(d_before, n, 1.5, &out));
    CHECK(material_fresnel(0.0, 1.0, 1.5) == 1.0); /* grazing from outside: total reflection */
}

void test_refract_snell(void)
{
    vec3 n = vec_make(0, 1, 0), out;
    for (int i = 0; i < 9; i++) {
        double a = i * 10.0 * VEC_PI / 180.0;
        vec3 d = vec_make(sin(a), -cos(a), 0);
        CHECK(material_refract(d, n, 1.0 / 1.5, &out));
        double sin_t = sqrt(out.x * out.x + out.z * out.z);
        CHECK_NEAR(sin(a), 1.5 * sin_t, 1e-12);
        CHECK(out.y < 0 && fabs(vec_len(out) - 1.0) < 1e-12);
    }
    vec3 r = material_reflect(vec_norm(vec_make(1, -1, 0)), n);
    CHECK_NEAR(r.x, sqrt(0.5), 1e-15);
    CHECK_NEAR(r.y, sqrt(0.5), 1e-15);
}

void test_cosine_sampling_mean(void)
{
    vec3 n = vec_norm(vec_make(0.3, -0.5, 0.8));
    rng_stream s = rng_make(3, 9);
    double sum = 0.0, sum2 = 0.0;
    int below = 0, N = 200000;
    for (int i = 0; i < N; i++) {
        double u1 = rng_next_double(&s), u2 = rng_next_double(&s);
        vec3 d = material_sample_cosine(n, u1, u2);
        double c = vec_dot(d, n);
        below += c < 0.0;
        sum += c;
        sum2 += c * c;
    }
    CHECK(below == 0);
    CHECK_NEAR(sum / N, 2.0 / 3.0, 0.005); /* E[cos] = 2/3 for a cosine density */
    CHECK_NEAR(sum2 / N, 0.5, 0.005);      /* E[cos^2] = 1/2 */
}

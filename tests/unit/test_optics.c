/* test_optics: ray/shape intersection, Fresnel, refraction, sampling, rng. */
#include <math.h>

#include "check.h"
#include "material.h"
#include "rng.h"
#include "shapes.h"
#include "tests.h"

void test_sphere_hits(void)
{
    shape s = shape_sphere(vec_make(0, 0, 5), 1.0, 0);
    double t;
    shape_ray r = {vec_make(0, 0, 0), vec_make(0, 0, 1)};
    CHECK(shape_intersect(&s, &r, 1e-9, INFINITY, &t) && fabs(t - 4.0) < 1e-12); /* outside */
    shape_ray in = {vec_make(0, 0, 5), vec_make(0, 1, 0)};
    CHECK(shape_intersect(&s, &in, 1e-9, INFINITY, &t) && fabs(t - 1.0) < 1e-12); /* inside */
    vec3 p = vec_madd(in.origin, in.dir, t);
    CHECK_NEAR(vec_dot(shape_normal(&s, p), vec_make(0, 1, 0)), 1.0, 1e-12);
    shape_ray behind = {vec_make(0, 0, 0), vec_make(0, 0, -1)};
    CHECK(!shape_intersect(&s, &behind, 1e-9, INFINITY, &t)); /* sphere behind the shape_ray */
    shape_ray graze_in = {vec_make(1.0 - 1e-9, 0, 0), vec_make(0, 0, 1)};
    CHECK(shape_intersect(&s, &graze_in, 1e-9, INFINITY, &t) && fabs(t - 5.0) < 1e-3); /* grazing, inside */
    shape_ray graze_out = {vec_make(1.0 + 1e-9, 0, 0), vec_make(0, 0, 1)};
    CHECK(!shape_intersect(&s, &graze_out, 1e-9, INFINITY, &t)); /* grazing, just outside */
    CHECK(!shape_intersect(&s, &r, 1e-9, 3.9, &t));               /* beyond tmax */
    /* far away ray, small sphere: precise root */
    shape small = shape_sphere(vec_make(0, 0, 1e6), 1e-3, 0);
    CHECK(shape_intersect(&small, &r, 1e-9, INFINITY, &t) && fabs(t - (1e6 - 1e-3)) < 1e-7);
}

void test_rect_hits(void)
{
    shape q = shape_rect(vec_make(-1, 0, -1), vec_make(2, 0, 0), vec_make(0, 0, 2), 0); /* floor, normal -y */
    CHECK_NEAR(q.normal.y, -1.0, 1e-15);
    double t;
    shape_ray down = {vec_make(0.5, 3, 0.5), vec_make(0, -1, 0)};
    CHECK(shape_intersect(&q, &down, 1e-9, INFINITY, &t) && fabs(t - 3.0) < 1e-12); /* from the front */
    shape_ray up = {vec_make(0.5, -2, 0.5), vec_make(0, 1, 0)};
    CHECK(shape_intersect(&q, &up, 1e-9, INFINITY, &t) && fabs(t - 2.0) < 1e-12); /* from behind: two-sided */
    shape_ray away = {vec_make(0.5, 3, 0.5), vec_make(0, 1, 0)};
    CHECK(!shape_intersect(&q, &away, 1e-9, INFINITY, &t)); /* plane behind the shape_ray */
    shape_ray miss = {vec_make(1.5, 3, 0.5), vec_make(0, -1, 0)};
    CHECK(!shape_intersect(&q, &miss, 1e-9, INFINITY, &t)); /* outside the rectangle */
    shape_ray parallel = {vec_make(0, 0, 0), vec_make(1, 0, 0)};
    CHECK(!shape_intersect(&q, &parallel, 1e-9, INFINITY, &t)); /* in the plane, parallel */
    vec3 g = vec_norm(vec_make(1, -1e-6, 0));
    shape_ray grazing = {vec_make(-0.5, 1e-6, 0.5), g};
    CHECK(shape_intersect(&q, &grazing, 1e-9, INFINITY, &t) && fabs(t - 1.0) < 1e-6); /* grazing */
    shape_ray edge = {vec_make(1.0, 1, 1.0), vec_make(0, -1, 0)};
    CHECK(shape_intersect(&q, &edge, 1e-9, INFINITY, &t)); /* exactly on the corner */
}

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

void test_rng_streams(void)
{
    rng_stream a = rng_make(42, 7), b = rng_make(42, 7), c = rng_make(42, 8), d = rng_make(43, 7);
    int same = 1, diff_c = 0, diff_d = 0;
    double mean = 0.0;
    for (int i = 0; i < 1000; i++) {
        uint64_t x = rng_next_u64(&a);
        same &= x == rng_next_u64(&b);
        diff_c += x != rng_next_u64(&c);
        diff_d += x != rng_next_u64(&d);
    }
    CHECK(same && diff_c == 1000 && diff_d == 1000);
    rng_stream e = rng_make(1, 1);
    for (int i = 0; i < 100000; i++) {
        double u = rng_next_double(&e);
        CHECK(u >= 0.0 && u < 1.0);
        mean += u;
    }
    CHECK_NEAR(mean / 100000, 0.5, 0.005);
}

void test_rect_aligned_path_is_exact(void)
{
    /* every axis-aligned rectangle of cornell.scene's kind, and some of other
     * sizes: the aligned path and the general one (the same shape with the
     * axes cleared) agree on every ray, hit or miss and t to the bit */
    const vec3 corners[3] = {{-1, 0, -1}, {0.25, -3, 7}, {-1e3, 2e3, -5e2}};
    const vec3 e[6][2] = {{{0, 0, 3.5}, {0, 2, 0}}, {{0, 2, 0}, {0, 0, 3.5}}, {{2, 0, 0}, {0, 2, 0}},
                          {{0, 0, 3.5}, {2, 0, 0}}, {{-0.5, 0, 0}, {0, 0, 1e-3}}, {{0, 7, 0}, {-3, 0, 0}}};
    rng_stream s = rng_make(5, 0);
    uint32_t rays = 0, hits = 0, differ = 0;
    for (int c = 0; c < 3; c++) {
        for (int k = 0; k < 6; k++) {
            shape fast = shape_rect(corners[c], e[k][0], e[k][1], 0);
            CHECK(fast.axis[0] >= 0 && fast.axis[1] >= 0 && fast.axis[2] >= 0);
            shape slow = fast;
            slow.axis[0] = slow.axis[1] = slow.axis[2] = -1;
            for (int i = 0; i < 20000; i++) {
                /* origins around the rectangle, directions uniform, some exactly along an axis */
                vec3 o = vec_add(corners[c], vec_make(8 * rng_next_double(&s) - 4, 8 * rng_next_double(&s) - 4,
                                                      8 * rng_next_double(&s) - 4));
                vec3 d = vec_norm(vec_make(rng_next_double(&s) - 0.5, rng_next_double(&s) - 0.5,
                                           rng_next_double(&s) - 0.5));
                if (i % 7 == 0)
                    d = vec_make(0, i % 2 ? 1 : -1, 0);
                if (i % 3 == 0) { /* aimed at the border: u or v exactly 0 or 1 there */
                    double a = rng_next_double(&s), b = (double)(rng_next_u64(&s) & 1);
                    if (rng_next_u64(&s) & 1) {
                        double tmp = a;
                        a = b, b = tmp;
                    }
                    vec3 target = vec_add(corners[c], vec_add(vec_scale(e[k][0], a), vec_scale(e[k][1], b)));
                    d = vec_norm(vec_sub(target, o));
                }
                shape_ray r = {o, d};
                double ta = -1, tb = -1;
                int ha = shape_intersect(&fast, &r, 0.0, INFINITY, &ta);
                int hb = shape_intersect(&slow, &r, 0.0, INFINITY, &tb);
                rays++;
                hits += (uint32_t)ha;
                differ += ha != hb || (ha && ta != tb);
            }
        }
    }
    CHECK_MSG(differ == 0, "%u of %u rays differ", differ, rays);
    CHECK_MSG(hits > rays / 50, "only %u hits in %u rays: the test sees too few", hits, rays);
    /* a rectangle that is not axis-aligned takes the general path */
    shape tilted = shape_rect(vec_make(0, 0, 0), vec_make(1, 1, 0), vec_make(0, 0, 1), 0);
    CHECK(tilted.axis[0] == -1);
}

/* test_shapes: ray/sphere and ray/rectangle intersection, and the exact
 * path of axis-aligned rectangles. */
#include <math.h>

#include "check.h"
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

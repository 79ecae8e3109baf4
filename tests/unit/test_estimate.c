/* test_estimate: equation 1 (est_irradiance) where floating point and
 * counting break first: n = 1 and n at and beyond the stored count,
 * coincident photons, too few or no photons in range. Synthetic photon maps
 * give exact expectations. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "estimate.h"
#include "helpers.h"
#include "photons.h"
#include "tests.h"

/* est_irradiance with a gather of nn photons within max_r scene units. */
static vec3 irr(const photons_map *m, vec3 x, vec3 n, uint32_t nn, double max_r, est_scratch *s, uint32_t *found)
{
    est_gather g = est_gather_make(m, nn, max_r, 0);
    return est_irradiance(m, x, n, &g, s, found);
}

static const vec3 down = {0, -1, 0}, up_n = {0, 1, 0};

/* ---- the estimator's conventions (renderer/estimate.h) ---- */

void test_stability_nn_one_and_at_stored_count(void)
{
    /* 4 photons on the floor at distances 0.1, 0.2, 0.3, 0.4 from the origin */
    const float pos[4][3] = {{0.1f, 0, 0}, {0, 0, 0.2f}, {-0.3f, 0, 0}, {0, 0, -0.4f}};
    photons_map m;
    helper_map(&m, pos, 4, down, up_n, 1.0f, 0);
    est_scratch *s = est_scratch_new(1, 10);
    CHECK(s != NULL);
    const double R = 1.0, R2 = R * R;
    uint32_t found;
    vec3 x = vec_make(0, 0, 0);
    /* n = 1: r = distance to the nearest photons_record */
    vec3 e = irr(&m, x, up_n, 1, R, s, &found);
    CHECK(found == 1);
    CHECK_REL(e.x, 1.0 / (VEC_PI * 0.1f * 0.1f), 1e-5);
    /* n = stored count: r = distance to the farthest */
    e = irr(&m, x, up_n, 4, R, s, &found);
    CHECK(found == 4);
    CHECK_REL(e.y, 4.0 / (VEC_PI * 0.4f * 0.4f), 1e-5);
    /* n > stored count: fewer than n in range, r = R */
    e = irr(&m, x, up_n, 10, R, s, &found);
    CHECK(found == 4);
    CHECK_REL(e.z, 4.0 / (VEC_PI * R2), 1e-12);
    CHECK(isfinite(e.x) && isfinite(e.y) && isfinite(e.z));
    /* back side: photons travelling down do not light a surface facing down */
    e = irr(&m, x, down, 4, R, s, &found);
    CHECK(found == 4 && e.x == 0.0);
    est_scratch_delete(s, 1);
    photons_map_free(&m);
}

void test_stability_floor_stops_at_the_extent(void)
{
    /* 8 coincident photons and 8 more 0.5 away: a map of extent 0.5. The
     * floor of r is 1e-3 of the cap while the cap is within the extent, and
     * 1e-3 of the extent beyond it (a cap of 1e30 must not floor r at 1e27) */
    float pos[16][3];
    for (int i = 0; i < 16; i++)
        pos[i][0] = i < 8 ? 0.25f : 0.75f, pos[i][1] = 0.0f, pos[i][2] = -0.5f;
    photons_map m;
    helper_map(&m, (const float(*)[3])pos, 16, down, up_n, 2.0f, 0);
    m.extent = 0.5;
    est_scratch *s = est_scratch_new(1, 8);
    CHECK(s != NULL);
    uint32_t found;
    vec3 x = vec_make(0.25, 0, -0.5);
    const double caps[] = {0.05, 0.5, 1e3, 1e30};
    for (int i = 0; i < 4; i++) {
        double f = fmin(caps[i], m.extent) * EST_MIN_RADIUS_FRAC;
        vec3 e = irr(&m, x, up_n, 8, caps[i], s, &found);
        CHECK(found == 8);
        CHECK_MSG(fabs(e.x / (2.0 * 8 / (VEC_PI * f * f)) - 1.0) < 1e-6, "cap %g: E %g", caps[i], e.x);
    }
    est_scratch_delete(s, 1);
    photons_map_free(&m);
}

void test_stability_coincident_photons(void)
{
    /* 8 photons at exactly the query point: r = 0, clamped to 1e-3 R */
    float pos[8][3];
    for (int i = 0; i < 8; i++)
        pos[i][0] = 0.25f, pos[i][1] = 0.0f, pos[i][2] = -0.5f;
    photons_map m;
    helper_map(&m, (const float(*)[3])pos, 8, down, up_n, 2.0f, 0);
    est_scratch *s = est_scratch_new(1, 8);
    CHECK(s != NULL);
    const double R = 0.05;
    const double floor2 = R * R * EST_MIN_RADIUS_FRAC * EST_MIN_RADIUS_FRAC;
    uint32_t found;
    vec3 x = vec_make(0.25, 0, -0.5);
    for (uint32_t nn = 1; nn <= 8; nn *= 2) {
        vec3 e = irr(&m, x, up_n, nn, R, s, &found);
        CHECK(found == nn);
        CHECK(isfinite(e.x));
        CHECK_REL(e.x, 2.0 * nn / (VEC_PI * floor2), 1e-9);
    }
    est_scratch_delete(s, 1);
    photons_map_free(&m);
}

void test_stability_few_or_no_photons_in_range(void)
{
    /* 3 photons at 0.5 R, 5 more at 2 R */
    const double R = 0.1;
    float pos[8][3];
    for (int i = 0; i < 8; i++) {
        double a = i * 0.7, d = i < 3 ? 0.5 * R : 2.0 * R;
        pos[i][0] = (float)(d * cos(a));
        pos[i][1] = 0.0f;
        pos[i][2] = (float)(d * sin(a));
    }
    photons_map m;
    helper_map(&m, (const float(*)[3])pos, 8, down, up_n, 1.0f, 0);
    est_scratch *s = est_scratch_new(1, 50);
    CHECK(s != NULL);
    uint32_t found;
    /* fewer in range than n: the disc's density, r = R */
    vec3 e = irr(&m, vec_make(0, 0, 0), up_n, 50, R, s, &found);
    CHECK(found == 3);
    CHECK_REL(e.x, 3.0 / (VEC_PI * R * R), 1e-12);
    /* a point with no photon within R: 0, found = 0 */
    e = irr(&m, vec_make(10, 0, 10), up_n, 50, R, s, &found);
    CHECK(found == 0 && e.x == 0.0 && e.y == 0.0 && e.z == 0.0);
    /* an empty map */
    photons_map_free(&m);
    helper_map(&m, NULL, 0, down, up_n, 1.0f, 0);
    e = irr(&m, vec_make(0, 0, 0), up_n, 50, R, s, &found);
    CHECK(found == 0 && e.x == 0.0);
    est_scratch_delete(s, 1);
    photons_map_free(&m);
}

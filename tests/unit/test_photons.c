/* test_photons: the photon pass: power is conserved in a closed diffuse box
 * (every emitted watt is stored or absorbed), whatever the chunking. */
#include <math.h>
#include <string.h>

#include "check.h"
#include "helpers.h"
#include "photons.h"
#include "tests.h"

/* A closed diffuse box with the light inside. */
static const char *closed_box =
    "camera position 0 1 1.5 look_at 0 1 0 up 0 1 0 fov 60\n"
    "light point position 0.1 1.2 -0.3 power 3 2 1\n"
    "material w lambert rho 0.5 0.5 0.5\n"
    "rect corner -1 0 -2 edge1 0 0 4 edge2 0 2 0 material w\n"
    "rect corner 1 0 -2 edge1 0 2 0 edge2 0 0 4 material w\n"
    "rect corner -1 0 -2 edge1 2 0 0 edge2 0 2 0 material w\n"
    "rect corner -1 0 2 edge1 0 2 0 edge2 2 0 0 material w\n"
    "rect corner -1 0 -2 edge1 0 0 4 edge2 2 0 0 material w\n"
    "rect corner -1 2 -2 edge1 2 0 0 edge2 0 0 4 material w\n";

void test_photon_power_closed_box(void)
{
    scene *sc = helper_scene(closed_box);
    photons_params pp = {100003, 1, 64, 1}; /* P_e not a multiple of the chunk size */
    photons_list l;
    CHECK(photons_trace(sc, &pp, 2, NULL, &l) == 0);
    double sum[3] = {0, 0, 0};
    uint64_t first = 0;
    for (uint64_t i = 0; i < l.count; i++) {
        if (l.ph[i].flags & PHOTONS_FLAG_DIRECT) {
            first++;
            for (int c = 0; c < 3; c++)
                sum[c] += l.ph[i].power[c] * (c == 0 ? l.unit.x : c == 1 ? l.unit.y : l.unit.z);
        }
    }
    CHECK(first == pp.photons); /* every photon's first hit is diffuse and stored */
    CHECK(l.escaped == 0);
    CHECK_REL(sum[0], 3.0, 1e-6);
    CHECK_REL(sum[1], 2.0, 1e-6);
    CHECK_REL(sum[2], 1.0, 1e-6);
    /* albedo 0.5: on average 1/(1-0.5) = 2 stored photons per emitted one */
    CHECK_NEAR((double)l.count / pp.photons, 2.0, 0.02);
    photons_list_free(&l);
    /* shadow-ray mode stores no first hits */
    pp.store_first_hits = 0;
    CHECK(photons_trace(sc, &pp, 1, NULL, &l) == 0);
    uint64_t direct = 0;
    for (uint64_t i = 0; i < l.count; i++)
        direct += (l.ph[i].flags & PHOTONS_FLAG_DIRECT) != 0;
    CHECK(direct == 0 && l.count > 0);
    photons_list_free(&l);
    scene_free(sc);
}

/* test_eye: the eye pass on its own, over a hand-made photon map. Every
 * pixel gets S x S samples, the image is the same bits on 1 and 3 threads,
 * a lit floor is bright and finite; a camera facing a mirror with
 * --eye-depth 0 cuts every path at the limit (counted) and is black. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "eye.h"
#include "helpers.h"
#include "tests.h"

static const char *floor_scene(int mirror)
{
    return mirror ? "camera position 0 1 0 look_at 0 0 0 up 0 0 -1 fov 60\n"
                    "light point position 0 2 0 power 1 1 1\n"
                    "material m mirror reflectance 0.9 0.9 0.9\n"
                    "rect corner -100 0 -100 edge1 0 0 200 edge2 200 0 0 material m\n"
                  : "camera position 0 1 0 look_at 0 0 0 up 0 0 -1 fov 60\n"
                    "light point position 0 2 0 power 1 1 1\n"
                    "material w lambert rho 0.5 0.5 0.5\n"
                    "rect corner -100 0 -100 edge1 0 0 200 edge2 200 0 0 material w\n";
}

/* The eye pass of sc over map m on `threads` threads into *img, *st. */
static pm_status eye_run(const scene *sc, const config_render *cfg, const photons_map *m, unsigned threads,
                         image *img, stats_run *st)
{
    memset(st, 0, sizeof *st);
    eye_input in = {sc, cfg, m, NULL, 0.5, NULL};
    return eye_render(&in, threads, 0, img, st);
}

void test_eye_threads_and_samples(void)
{
    scene *sc = helper_scene(floor_scene(0));
    static float pos[1600][3];
    for (int i = 0; i < 1600; i++) {
        pos[i][0] = -1.0f + 2.0f * (float)(i % 40) / 39.0f;
        pos[i][1] = 0.0f;
        pos[i][2] = -1.0f + 2.0f * (float)(i / 40) / 39.0f;
    }
    photons_map m;
    helper_map(&m, (const float(*)[3])pos, 1600, vec_make(0, -1, 0), vec_make(0, 1, 0), 1.0f, 0);
    config_render cfg = config_defaults();
    cfg.width = 16;
    cfg.height = 12;
    cfg.nn = 8;
    image a, b;
    stats_run sa, sb;
    CHECK(eye_run(sc, &cfg, &m, 1, &a, &sa) == PM_OK);
    CHECK(eye_run(sc, &cfg, &m, 3, &b, &sb) == PM_OK);
    CHECK(sa.samples == 16u * 12u * cfg.subpixels * cfg.subpixels && sb.samples == sa.samples);
    CHECK(memcmp(a.rgb, b.rgb, sizeof(float) * 3 * 16 * 12) == 0);
    int bad = 0;
    for (size_t i = 0; i < 3 * 16 * 12; i++)
        bad += !(isfinite(a.rgb[i]) && a.rgb[i] > 0.0f);
    CHECK_MSG(bad == 0, "%d channels not finite and positive on a lit floor", bad);
    CHECK(sa.empty_estimates == 0 && sa.eye_depth_limit_hits == 0 && sa.mean_radiance[0] > 0.0);
    image_free(&a);
    image_free(&b);
    photons_map_free(&m);
    scene_free(sc);
}

void test_eye_depth_limit(void)
{
    scene *sc = helper_scene(floor_scene(1));
    photons_map m;
    helper_map(&m, NULL, 0, vec_make(0, -1, 0), vec_make(0, 1, 0), 1.0f, 0);
    config_render cfg = config_defaults();
    cfg.width = 8;
    cfg.height = 6;
    cfg.eye_depth = 0;
    image img;
    stats_run st;
    CHECK(eye_run(sc, &cfg, &m, 2, &img, &st) == PM_OK);
    CHECK(st.samples == 8u * 6u * cfg.subpixels * cfg.subpixels);
    CHECK(st.eye_depth_limit_hits == st.samples);
    CHECK(st.mean_radiance[0] == 0.0 && st.mean_radiance[1] == 0.0 && st.mean_radiance[2] == 0.0);
    image_free(&img);
    /* negative control: with depth left, no path is cut */
    cfg.eye_depth = 4;
    CHECK(eye_run(sc, &cfg, &m, 2, &img, &st) == PM_OK);
    CHECK(st.eye_depth_limit_hits == 0);
    image_free(&img);
    photons_map_free(&m);
    scene_free(sc);
}

/* test_pbrt: the pbrt-v3 export. The text names the integrator and its
 * depth (bounces + 1), the film size and the camera; pbrt_check refuses
 * what pbrt would render differently (a glass rectangle, --min-bounces
 * with an integrator other than path, or not below --bounces). */
#include <stdio.h>
#include <string.h>

#include "check.h"
#include "helpers.h"
#include "pbrt.h"
#include "tests.h"

static const char *pbrt_scene = "camera position 0 1 2 look_at 0 1 0 up 0 1 0 fov 60\n"
                                "light point position 0 1.5 0 power 1 1 1\n"
                                "material w lambert rho 0.5 0.5 0.5\n"
                                "material g glass ior 1.5\n"
                                "rect corner -1 0 -1 edge1 0 0 2 edge2 2 0 0 material w\n"
                                "sphere center 0 0.5 0 radius 0.2 material g\n";

/* pbrt_write's text into buf. */
static pm_status pbrt_text(const scene *sc, const pbrt_options *o, char *buf, size_t cap)
{
    buf[0] = '\0';
    FILE *f = tmpfile();
    if (!f)
        return PM_ERR_IO;
    pm_status rc = pbrt_write(f, sc, "t.scene", o);
    rewind(f);
    size_t n = fread(buf, 1, cap - 1, f);
    buf[n] = '\0';
    fclose(f);
    return rc;
}

void test_pbrt_writes_settings(void)
{
    static char buf[16384];
    scene *sc = helper_scene(pbrt_scene);
    pbrt_options o = pbrt_defaults();
    o.width = 64;
    o.height = 48;
    o.bounces = 3;
    char err[256];
    CHECK(pbrt_check(sc, &o, err, sizeof err) == PM_OK);
    CHECK(pbrt_text(sc, &o, buf, sizeof buf) == PM_OK);
    CHECK(strstr(buf, "Integrator \"bdpt\" \"integer maxdepth\" [ 4 ]") != NULL);
    CHECK(strstr(buf, "\"integer xresolution\" [ 64 ] \"integer yresolution\" [ 48 ]") != NULL);
    CHECK(strstr(buf, "LookAt") != NULL && strstr(buf, "t.scene") != NULL);
    o.integrator = PBRT_INTEGRATOR_PATH;
    o.min_bounces = 1;
    CHECK(pbrt_check(sc, &o, err, sizeof err) == PM_OK);
    CHECK(pbrt_text(sc, &o, buf, sizeof buf) == PM_OK);
    CHECK(strstr(buf, "Integrator \"path\"") && strstr(buf, "\"integer mindepth\" [ 2 ]"));
    for (int i = 0; pbrt_integrator_names[i]; i++)
        CHECK(!strcmp(pbrt_integrator_name((pbrt_integrator)i), pbrt_integrator_names[i]));
    scene_free(sc);
}

void test_pbrt_refusals(void)
{
    char err[256];
    scene *sc = helper_scene(pbrt_scene);
    pbrt_options o = pbrt_defaults();
    o.min_bounces = 1; /* bdpt has no minimum depth */
    CHECK(pbrt_check(sc, &o, err, sizeof err) == PM_ERR_INPUT && strstr(err, "--min-bounces"));
    o.integrator = PBRT_INTEGRATOR_PATH;
    o.bounces = 2;
    o.min_bounces = 2;
    CHECK(pbrt_check(sc, &o, err, sizeof err) == PM_ERR_INPUT && strstr(err, "below --bounces"));
    scene_free(sc);
    sc = helper_scene("camera position 0 1 2 look_at 0 1 0 up 0 1 0 fov 60\n"
                      "light point position 0 1.5 0 power 1 1 1\n"
                      "material g glass ior 1.5\n"
                      "rect corner -1 0 -1 edge1 0 0 2 edge2 2 0 0 material g\n");
    o = pbrt_defaults();
    CHECK(pbrt_check(sc, &o, err, sizeof err) == PM_ERR_INPUT);
    scene_free(sc);
}

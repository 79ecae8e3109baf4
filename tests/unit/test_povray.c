/* test_povray: the POV-Ray SDL export. The text holds the camera, the
 * light, radiosity and photons as asked (and not when turned off), the
 * bounces as radiosity's recursion_limit, and the quality's name. */
#include <stdio.h>
#include <string.h>

#include "check.h"
#include "helpers.h"
#include "povray.h"
#include "tests.h"

/* povray_write's text into buf. */
static pm_status pov_text(const scene *sc, const povray_options *o, char *buf, size_t cap)
{
    buf[0] = '\0';
    FILE *f = tmpfile();
    if (!f)
        return PM_ERR_IO;
    pm_status rc = povray_write(f, sc, "t.scene", o);
    rewind(f);
    size_t n = fread(buf, 1, cap - 1, f);
    buf[n] = '\0';
    fclose(f);
    return rc;
}

void test_povray_writes_settings(void)
{
    static char buf[32768];
    scene *sc = helper_scene("camera position 0 1 2 look_at 0 1 0 up 0 1 0 fov 60\n"
                             "light point position 0 1.5 0 power 1 1 1\n"
                             "material w lambert rho 0.5 0.5 0.5\n"
                             "material g glass ior 1.5\n"
                             "rect corner -1 0 -1 edge1 0 0 2 edge2 2 0 0 material w\n"
                             "sphere center 0 0.5 0 radius 0.2 material g\n");
    povray_options o = povray_defaults();
    o.bounces = 5;
    CHECK(pov_text(sc, &o, buf, sizeof buf) == PM_OK);
    CHECK(strstr(buf, "#version 3.7;") && strstr(buf, "camera {") && strstr(buf, "light_source {"));
    CHECK(strstr(buf, "radiosity {") && strstr(buf, "recursion_limit 5") && strstr(buf, "photons {"));
    CHECK(strstr(buf, "quality fast") && strstr(buf, "t.scene"));
    o.radiosity = 0;
    o.photons = 0;
    o.quality = POVRAY_QUALITY_REFERENCE;
    CHECK(pov_text(sc, &o, buf, sizeof buf) == PM_OK);
    CHECK(!strstr(buf, "radiosity {") && !strstr(buf, "recursion_limit"));
    CHECK(strstr(buf, "quality reference") && strstr(buf, "radiosity off") && strstr(buf, "photons off"));
    for (int i = 0; povray_quality_names[i]; i++)
        CHECK(!strcmp(povray_quality_name((povray_quality)i), povray_quality_names[i]));
    scene_free(sc);
}

/* test_info: `photonmap info --json`'s writer. The basis it prints is
 * camera_make's for the asked size, each number reading back to the same
 * double; shapes and materials carry their scene file lines; a scene built
 * without the parser has null lines. */
#include <stdlib.h>
#include <string.h>

#include "camera.h"
#include "check.h"
#include "helpers.h"
#include "info.h"
#include "tests.h"

static const char *info_scene = "# a comment line\n"
                                "camera position 0.3 1.1 2.4 look_at -0.1 0.9 0 up 0.1 1 0 fov 61\n"
                                "light point position 0 1.8 1 power 10 20 30\n"
                                "material w lambert rho 0.5 0.5 0.5\n"
                                "\n"
                                "material g glass ior 1.5\n"
                                "sphere center 1 2 -1 radius 0.5 material g\n"
                                "rect corner -1 0 -1 edge1 2 0 0 edge2 0 2 0 material w\n";

/* The JSON of sc at w x h as a string (malloc'd). */
static char *info_text(const scene *sc, unsigned w, unsigned h)
{
    FILE *f = tmpfile();
    CHECK(f != NULL);
    if (!f)
        return NULL;
    CHECK(info_write_json(f, sc, "x.scene", w, h) == PM_OK);
    long n = ftell(f);
    rewind(f);
    char *buf = calloc((size_t)n + 1, 1);
    CHECK(buf && fread(buf, 1, (size_t)n, f) == (size_t)n);
    fclose(f);
    return buf;
}

/* The three numbers after `"key": [` following `after` in text. */
static vec3 read_vec(const char *text, const char *after, const char *key)
{
    vec3 v = {0, 0, 0};
    const char *p = strstr(text, after);
    p = p ? strstr(p, key) : NULL;
    CHECK(p != NULL);
    if (!p)
        return v;
    p = strchr(p, '[') + 1;
    char *end;
    v.x = strtod(p, &end);
    v.y = strtod(end + 1, &end);
    v.z = strtod(end + 1, &end);
    return v;
}

void test_info_basis_is_camera_make(void)
{
    scene *sc = helper_scene(info_scene);
    char *t = info_text(sc, 96, 54);
    camera cam = camera_make(sc, 54.0 / 96.0);
    vec3 r = read_vec(t, "\"basis\"", "\"right\""), u = read_vec(t, "\"basis\"", "\"up\"");
    vec3 fw = read_vec(t, "\"basis\"", "\"forward\"");
    CHECK(r.x == cam.right.x && r.y == cam.right.y && r.z == cam.right.z);
    CHECK(u.x == cam.up.x && u.y == cam.up.y && u.z == cam.up.z);
    CHECK(fw.x == cam.fwd.x && fw.y == cam.fwd.y && fw.z == cam.fwd.z);
    /* negative control: the square image's up differs */
    camera sq = camera_make(sc, 1.0);
    CHECK(u.y != sq.up.y);
    CHECK(strstr(t, "\"width\": 96, \"height\": 54") != NULL);
    free(t);
    scene_free(sc);
}

void test_info_lines_and_facts(void)
{
    scene *sc = helper_scene(info_scene);
    char *t = info_text(sc, 8, 8);
    CHECK(strstr(t, "{\"name\": \"w\", \"kind\": \"lambert\", \"rho\": [0.5, 0.5, 0.5], \"line\": 4}") != NULL);
    CHECK(strstr(t, "{\"name\": \"g\", \"kind\": \"glass\", \"ior\": 1.5, \"line\": 6}") != NULL);
    CHECK(strstr(t, "{\"kind\": \"sphere\", \"center\": [1, 2, -1], \"radius\": 0.5, \"material\": \"g\", "
                    "\"material_kind\": \"glass\", \"line\": 7}") != NULL);
    CHECK(strstr(t, "\"material\": \"w\", \"material_kind\": \"lambert\", \"line\": 8}") != NULL);
    CHECK(strstr(t, "\"power\": [10, 20, 30]") != NULL);
    CHECK(strstr(t, "\"fov_deg\": 61") != NULL);
    free(t);
    /* a scene whose lines nobody recorded prints null */
    int *lines = sc->shape_lines;
    sc->shape_lines = NULL;
    t = info_text(sc, 8, 8);
    CHECK(strstr(t, "\"material_kind\": \"glass\", \"line\": null}") != NULL);
    free(t);
    sc->shape_lines = lines;
    scene_free(sc);
}

/* test_scene: the .scene parser, good input and every class of bad input. */
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "scene.h"
#include "tests.h"

void test_scene_parses_cornell(void)
{
    char err[512];
    scene *s = NULL;
    int rc = scene_load("scenes/cornell.scene", &s, err, sizeof err);
    CHECK_MSG(rc == PM_OK, "%s", err);
    if (!s)
        return;
    CHECK(s->nmaterials == 4 && s->nshapes == 9);
    CHECK_NEAR(s->camera.hfov_deg, 65.0, 0);
    CHECK_NEAR(s->light.power.x, 4.0 * VEC_PI, 1e-5);
    int lambert = 0, mirror = 0, glass = 0;
    for (size_t i = 0; i < s->nshapes; i++) {
        material_kind k = s->materials[s->shapes[i].material].kind;
        lambert += k == MATERIAL_LAMBERT;
        mirror += k == MATERIAL_MIRROR;
        glass += k == MATERIAL_GLASS;
    }
    CHECK(lambert == 6 && mirror == 2 && glass == 1);
    CHECK_NEAR(s->bounds_lo.x, -1, 0);
    CHECK_NEAR(s->bounds_hi.z, 2.5, 0);
    scene_free(s);
}

#define HEAD "camera position 0 1 2 look_at 0 1 0 up 0 1 0 fov 60\nlight point position 0 1 0 power 1 1 1\n"
#define MAT "material w lambert rho 0.5 0.5 0.5\n"

typedef struct {
    const char *text;
    const char *where;   /* expected "test.scene:L:C:" */
    const char *message; /* expected substring */
} bad_case;

void test_scene_errors(void)
{
    static const bad_case cases[] = {
        {"", "test.scene:1:1:", "no camera"},
        {"# only a comment\n", "test.scene:1:1:", "no camera"},
        {HEAD MAT "sphere center 0 0 0 radius 1 material whte\n", "test.scene:4:39:", "unknown material 'whte'"},
        {HEAD "bogus 1 2 3\n", "test.scene:3:1:", "unknown keyword 'bogus'"},
        {HEAD MAT "sphere center 0 0 radius 1 material w\n", "test.scene:4:19:", "expected a number, got 'radius'"},
        {HEAD MAT "sphere center 0 0 0 radius nan material w\n", "test.scene:4:28:", "expected a number"},
        {HEAD MAT "sphere center 0 0 0 radius inf material w\n", "test.scene:4:28:", "expected a number"},
        {HEAD MAT "sphere center 0 0 1e400 radius 1 material w\n", "test.scene:4:19:", "not finite"},
        {HEAD MAT "sphere center 0 0 0 radius -1 material w\n", "test.scene:4:28:", "out of range"},
        {HEAD MAT "sphere center 0 0 0 radius 0 material w\n", "test.scene:4:28:", "must be positive"},
        {HEAD MAT "sphere center 0 0 0 radius 1\n", "test.scene:4:1:", "missing field 'material'"},
        {HEAD MAT "sphere center 0 0 0 radius 1 radius 2 material w\n", "test.scene:4:30:", "given twice"},
        {HEAD MAT "sphere center 0 0 0 radius\n", "test.scene:4:27:", "needs 1 value"},
        {HEAD MAT MAT, "test.scene:4:10:", "already defined on line 3"},
        {"light point position 0 1 0 power 1 1 1\n" MAT "sphere center 0 0 0 radius 1 material w\n",
         "test.scene:3:1:", "no camera"},
        {"camera position 0 1 2 look_at 0 1 0 up 0 1 0 fov 60\n" MAT "sphere center 0 0 0 radius 1 material w\n",
         "test.scene:3:1:", "no light"},
        {HEAD MAT, "test.scene:3:1:", "no shapes"},
        {HEAD "light point position 0 1 0 power 1 1 1\n", "test.scene:3:1:", "second light"},
        {HEAD "light point position 0 1 0 power -1 1 1\n", "test.scene:3:1:", "second light"},
        {"light point position 0 1 0 power -1 1 1\n", "test.scene:1:34:", "out of range"},
        {"camera position 0 1 2 look_at 0 1 2 up 0 1 0 fov 60\n", "test.scene:1:31:", "look_at equals"},
        {"camera position 0 1 2.41e-300 look_at 0 1 0 up 0 1 0 fov 60\n", "test.scene:1:39:", "too close to its position"},
        {"camera position 0 1 2 look_at 0 1 0 up 0 1e-300 0 fov 60\n", "test.scene:1:40:", "up vector is zero"},
        {"camera position 0 1 2 look_at 0 1 0 up 0 0 1 fov 60\n", "test.scene:1:40:", "parallel"},
        {"camera position 0 1 2 look_at 0 1 0 up 0 1 0 fov 180\n", "test.scene:1:50:", "out of range"},
        {HEAD "material w plastic rho 1 1 1\n", "test.scene:3:12:", "unknown material kind 'plastic'"},
        {HEAD "material w lambert rho 1.5 1 1\n", "test.scene:3:24:", "out of range"},
        {HEAD "material w glass ior 0.5\n", "test.scene:3:22:", "out of range"},
        {HEAD "material 9w lambert rho 1 1 1\n", "test.scene:3:10:", "bad material name"},
        {HEAD MAT "rect corner 0 0 0 edge1 1 0 0 edge2 1 1 0 material w\n", "test.scene:4:37:", "not perpendicular"},
        {HEAD MAT "rect corner 0 0 0 edge1 0 0 0 edge2 1 1 0 material w\n", "test.scene:4:25:", "edge1 is zero"},
        {HEAD MAT "sphere center 0 0 0 radius 1 material w colour 1\n", "test.scene:4:41:", "unknown sphere field"},
        {HEAD "\x01\x02\x03\n", "test.scene:3:1:", "control byte"},
        {HEAD "sph\xc3\xa9re\n", "test.scene:3:4:", "non-ASCII byte 0xc3"},
        {HEAD "# caf\xe9\n", "test.scene:3:6:", "invalid UTF-8"},
        {HEAD MAT "sphere center 0 0 0 radius 1 mat", "test.scene:4:30:", "unknown sphere field 'mat'"},
        {HEAD "light", "test.scene:3:1:", "second light"},
        {"camera position 0 1 2 look_at 0 1 0 up 0 1 0 fov 60\nlight point position 0 1 0 power 1 1", "test.scene:2:37:",
         "needs 3 values"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        char err[512];
        scene *s = (scene *)1;
        int rc = scene_parse_buffer("test.scene", cases[i].text, strlen(cases[i].text), &s, err, sizeof err);
        CHECK_MSG(rc == PM_ERR_INPUT && s == NULL, "case %zu: rc %d", i, rc);
        CHECK_MSG(strncmp(err, cases[i].where, strlen(cases[i].where)) == 0, "case %zu: '%s', want '%s'", i, err,
                  cases[i].where);
        CHECK_MSG(strstr(err, cases[i].message) != NULL, "case %zu: '%s', want '%s'", i, err, cases[i].message);
    }
    /* a 10 MB line and binary junk: errors, not crashes */
    size_t big = 10u << 20;
    char *line = malloc(big + 64);
    memset(line, 'a', big);
    line[big] = '\n';
    line[big + 1] = '\0';
    char err[512];
    scene *s;
    CHECK(scene_parse_buffer("test.scene", line, big + 1, &s, err, sizeof err) == PM_ERR_INPUT);
    CHECK_MSG(strstr(err, "test.scene:1:1: token longer") != NULL, "%s", err);
    for (size_t i = 0; i < big; i++)
        line[i] = (char)(i * 2654435761u >> 13);
    CHECK(scene_parse_buffer("test.scene", line, big, &s, err, sizeof err) == PM_ERR_INPUT);
    CHECK_MSG(strncmp(err, "test.scene:", 11) == 0, "%s", err);
    free(line);
    /* a missing file is a runtime error naming the path */
    CHECK(scene_load("no/such/file.scene", &s, err, sizeof err) == PM_ERR_IO);
    CHECK(strstr(err, "no/such/file.scene") != NULL);
}

void test_stability_parser_degenerate_sizes(void)
{
    /* Input errors (tests/fuzz/corpus/finding-*.scene): lengths whose
     * squares underflow (a rect's 1/|edge|^2 would be infinite, its normal
     * NaN), a scene of no extent (zero epsilon and radius), hex floats (the
     * format is decimal). */
    static const char *head = "camera position 1 1 1 look_at 1 1 0 up 0 1 0 fov 60\n"
                              "light point position 0 1 0 power 1 1 1\n"
                              "material w lambert rho 1 1 1\n";
    static const struct {
        const char *shape, *where, *what;
    } bad[] = {
        {"rect corner 1 0 0 edge1 1e-160 0 0 edge2 0 1e-160 0 material w\n", "t:4:25:", "shorter than"},
        {"rect corner 1 0 0 edge1 1 0 0 edge2 0 0 1e-60 material w\n", "t:4:37:", "shorter than"},
        {"sphere center 1 0 0 radius 1e-320 material w\n", "t:4:28:", "at least"},
        {"sphere center 0x10 0 0 radius 1 material w\n", "t:4:15:", "expected a number"},
    };
    char text[512], err[512];
    scene *s;
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        snprintf(text, sizeof text, "%s%s", head, bad[i].shape);
        int rc = scene_parse_buffer("t", text, strlen(text), &s, err, sizeof err);
        CHECK_MSG(rc == PM_ERR_INPUT && s == NULL, "case %zu parsed", i);
        CHECK_MSG(strncmp(err, bad[i].where, strlen(bad[i].where)) == 0 && strstr(err, bad[i].what), "case %zu: %s",
                  i, err);
    }
    const char *flat = "camera position 1 1 1 look_at 1 1 0 up 0 1 0 fov 60\n"
                       "light point position 1e15 1e15 1e15 power 1 1 1\n"
                       "material w lambert rho 1 1 1\n"
                       "sphere center 1e15 1e15 1e15 radius 1e-40 material w\n";
    CHECK(scene_parse_buffer("t", flat, strlen(flat), &s, err, sizeof err) == PM_ERR_INPUT);
    CHECK_MSG(strstr(err, "t:4:1:") == err && strstr(err, "no extent"), "%s", err);
    /* just above the limit: a usable rect with a unit normal */
    snprintf(text, sizeof text, "%srect corner 1 0 0 edge1 1e-49 0 0 edge2 0 1e-49 0 material w\n", head);
    CHECK(scene_parse_buffer("t", text, strlen(text), &s, err, sizeof err) == PM_OK);
    if (s) {
        const shape *r = &s->shapes[0];
        CHECK(isfinite(r->inv_len2_1) && isfinite(r->inv_len2_2));
        CHECK_NEAR(vec_len(r->normal), 1.0, 1e-12);
        CHECK(s->scale > 0.0 && isfinite(s->scale));
        scene_free(s);
    }
}

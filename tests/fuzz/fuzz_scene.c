/* fuzz_scene: libFuzzer target for the .scene parser. Any input
 * must either parse into a scene that every later stage can use (finite
 * numbers, unit normals, a positive finite size, valid material indices) or
 * fail with "fuzz.scene:LINE:COL: message" and no scene. Anything else, and
 * any sanitizer report, is a finding: abort() so libFuzzer saves the input.
 * Build and run: `make fuzz` (tests/fuzz/fuzz.mk); tests/fuzz.test.sh runs it
 * briefly in `make test`. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static void finding(const char *what)
{
    fprintf(stderr, "fuzz_scene: %s\n", what);
    abort();
}

static int vec_finite(vec3 v)
{
    return isfinite(v.x) && isfinite(v.y) && isfinite(v.z);
}

static void check_scene(const scene *s)
{
    if (!s)
        finding("PM_OK without a scene");
    if (!(isfinite(s->scale) && s->scale > 0.0))
        finding("scene size is zero or not finite");
    const scene_camera *c = &s->camera;
    if (!vec_finite(c->position) || !vec_finite(c->look_at) || !vec_finite(c->up) || !isfinite(c->hfov_deg))
        finding("camera not finite");
    vec3 fwd = vec_norm(vec_sub(c->look_at, c->position));
    vec3 right = vec_norm(vec_cross(fwd, c->up));
    if (!vec_finite(fwd) || !vec_finite(right))
        finding("camera basis not finite");
    if (!vec_finite(s->light.position) || !vec_finite(s->light.power))
        finding("light not finite");
    if (s->nshapes == 0)
        finding("no shapes");
    for (size_t i = 0; i < s->nshapes; i++) {
        const shape *sh = &s->shapes[i];
        if (sh->material < 0 || (size_t)sh->material >= s->nmaterials)
            finding("material index out of range");
        if (sh->kind == SHAPE_SPHERE) {
            if (!vec_finite(sh->center) || !(isfinite(sh->radius) && sh->radius > 0.0))
                finding("bad sphere");
        } else {
            if (!vec_finite(sh->corner) || !vec_finite(sh->edge1) || !vec_finite(sh->edge2) ||
                !vec_finite(sh->normal) || !isfinite(sh->inv_len2_1) || !isfinite(sh->inv_len2_2))
                finding("rect not finite");
            if (fabs(vec_len(sh->normal) - 1.0) > 1e-6)
                finding("rect normal not unit");
        }
    }
    for (size_t i = 0; i < s->nmaterials; i++) {
        const material *m = &s->materials[i];
        if (!vec_finite(m->color) || !isfinite(m->ior) || m->ior < 1.0)
            finding("bad material");
        if (memchr(m->name, '\0', sizeof m->name) == NULL)
            finding("material name not terminated");
    }
}

/* The BVH must answer every ray exactly as the loop over the shapes does,
 * at any scale and position the parser accepts: rays from the camera and the
 * light towards each shape's corner or centre and a little beside it. */
static void check_bvh(scene *s)
{
    if (scene_set_accel(s, SCENE_ACCEL_BVH))
        return; /* out of memory: the scene still works by the loop */
    size_t n = s->nshapes < 32 ? s->nshapes : 32;
    for (size_t i = 0; i < 2 * n; i++) {
        const shape *sh = &s->shapes[i % n];
        vec3 target = sh->kind == SHAPE_SPHERE ? sh->center : vec_madd(sh->corner, vec_add(sh->edge1, sh->edge2), 0.5);
        if (i >= n) /* beside it: grazing the sphere, beyond the rectangle's edge */
            target = sh->kind == SHAPE_SPHERE ? vec_add(target, vec_make(sh->radius, 0, 0)) : vec_add(sh->corner, sh->edge1);
        vec3 from[2] = {s->camera.position, s->light.position};
        for (int k = 0; k < 2; k++) {
            vec3 d = vec_sub(target, from[k]);
            double len = vec_len(d);
            if (!(len > 0.0 && isfinite(len)))
                continue;
            shape_ray r = {from[k], vec_scale(d, 1.0 / len)};
            if (!vec_finite(r.dir))
                continue;
            scene_hit hb, hl;
            int ab = scene_intersect(s, &r, INFINITY, &hb);
            int ob = scene_occluded(s, &r, len);
            bvh *keep = s->accel;
            s->accel = NULL; /* the loop, same scene */
            int al = scene_intersect(s, &r, INFINITY, &hl);
            int ol = scene_occluded(s, &r, len);
            s->accel = keep;
            if (ab != al || ob != ol || (al && (hb.shape != hl.shape || hb.t != hl.t)))
                finding("the BVH and the loop over the shapes disagree");
        }
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char err[512];
    scene *s = (scene *)(uintptr_t)1; /* must be set to NULL on failure */
    int rc = scene_parse_buffer("fuzz.scene", (const char *)data, size, &s, err, sizeof err);
    if (rc == PM_OK) {
        check_scene(s);
        check_bvh(s);
        scene_free(s);
        return 0;
    }
    if (s != NULL)
        finding("failure left a scene");
    if (rc == PM_ERR_INPUT) {
        int line = 0, col = 0, n = 0;
        if (sscanf(err, "fuzz.scene:%d:%d: %n", &line, &col, &n) != 2 || n == 0 || line < 1 || col < 1 ||
            err[n] == '\0')
            finding("input error without fuzz.scene:line:col: message");
    } else if (rc != PM_ERR_NOMEM) { /* a buffer parse reads no file: PM_ERR_IO cannot happen */
        finding("unknown result code");
    }
    return 0;
}

/* info: a parsed scene's facts as JSON (info.h). */
#include "info.h"

#include <assert.h>
#include <inttypes.h>

#include "camera.h"
#include "material.h"
#include "numfmt.h"
#include "stats.h"

static void put_vec(FILE *f, vec3 v)
{
    fputc('[', f);
    numfmt_put_exact(f, v.x);
    fputs(", ", f);
    numfmt_put_exact(f, v.y);
    fputs(", ", f);
    numfmt_put_exact(f, v.z);
    fputc(']', f);
}

/* `"key": value` for a vector and a number, after `sep`. */
static void key_vec(FILE *f, const char *sep, const char *key, vec3 v)
{
    fprintf(f, "%s\"%s\": ", sep, key);
    put_vec(f, v);
}

static void key_num(FILE *f, const char *sep, const char *key, double x)
{
    fprintf(f, "%s\"%s\": ", sep, key);
    numfmt_put_exact(f, x);
}

/* A line number, or null when the scene did not come from a file. */
static void key_line(FILE *f, const int *lines, size_t i)
{
    if (lines)
        fprintf(f, ", \"line\": %d", lines[i]);
    else
        fputs(", \"line\": null", f);
}

pm_status info_write_json(FILE *f, const scene *sc, const char *scene_path, uint32_t width, uint32_t height)
{
    assert(width > 0 && height > 0);
    const scene_camera *c = &sc->camera;
    camera cam = camera_make(sc, (double)height / (double)width);
    fputs("{\n  \"scene\": ", f);
    stats_json_string(f, scene_path);
    fputs(",\n  \"camera\": {", f);
    key_vec(f, "", "position", c->position);
    key_vec(f, ", ", "look_at", c->look_at);
    key_vec(f, ", ", "up", c->up);
    key_num(f, ", ", "fov_deg", c->hfov_deg);
    fprintf(f, ",\n    \"basis\": {\"width\": %" PRIu32 ", \"height\": %" PRIu32, width, height);
    key_vec(f, ", ", "origin", cam.origin);
    key_vec(f, ",\n              ", "forward", cam.fwd);
    key_vec(f, ", ", "right", cam.right);
    key_vec(f, ", ", "up", cam.up);
    fputs("}},\n  \"lights\": [{\"kind\": \"point\"", f);
    key_vec(f, ", ", "position", sc->light.position);
    key_vec(f, ", ", "power", sc->light.power);
    fputs("}],\n  \"materials\": [", f);
    for (size_t i = 0; i < sc->nmaterials; i++) {
        const material *m = &sc->materials[i];
        fprintf(f, "%s\n    {\"name\": ", i ? "," : "");
        stats_json_string(f, m->name);
        fprintf(f, ", \"kind\": \"%s\"", material_kind_name(m->kind));
        if (m->kind == MATERIAL_GLASS)
            key_num(f, ", ", "ior", m->ior);
        else
            key_vec(f, ", ", m->kind == MATERIAL_LAMBERT ? "rho" : "reflectance", m->color);
        key_line(f, sc->material_lines, i);
        fputc('}', f);
    }
    fputs("],\n  \"shapes\": [", f);
    for (size_t i = 0; i < sc->nshapes; i++) {
        const shape *s = &sc->shapes[i];
        const material *m = &sc->materials[s->material];
        fprintf(f, "%s\n    {\"kind\": \"%s\"", i ? "," : "", s->kind == SHAPE_SPHERE ? "sphere" : "rect");
        if (s->kind == SHAPE_SPHERE) {
            key_vec(f, ", ", "center", s->center);
            key_num(f, ", ", "radius", s->radius);
        } else {
            key_vec(f, ", ", "corner", s->corner);
            key_vec(f, ", ", "edge1", s->edge1);
            key_vec(f, ", ", "edge2", s->edge2);
        }
        fputs(", \"material\": ", f);
        stats_json_string(f, m->name);
        fprintf(f, ", \"material_kind\": \"%s\"", material_kind_name(m->kind));
        key_line(f, sc->shape_lines, i);
        fputc('}', f);
    }
    fputs("],\n  \"bounds\": {", f);
    key_vec(f, "", "lo", sc->bounds_lo);
    key_vec(f, ", ", "hi", sc->bounds_hi);
    key_num(f, ", ", "diagonal", sc->scale);
    fputs("}\n}\n", f);
    return ferror(f) ? PM_ERR_IO : PM_OK;
}

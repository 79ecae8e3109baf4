/* pbrt: writing a scene as a pbrt-v3 scene that renders the same radiance,
 * with the mapping of units and conventions (renderer/README.md). */
#include "pbrt.h"

#include <assert.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "config.h"
#include "material.h"
#include "numfmt.h"
#include "vec.h"

const char *const pbrt_integrator_names[] = {"bdpt", "path", "directlighting", NULL};

const char *pbrt_integrator_name(pbrt_integrator i)
{
    assert(i >= PBRT_INTEGRATOR_BDPT && i <= PBRT_INTEGRATOR_DIRECTLIGHTING);
    return pbrt_integrator_names[i];
}

pbrt_options pbrt_defaults(void)
{
    pbrt_options o;
    o.width = CONFIG_DEFAULT_WIDTH;
    o.height = CONFIG_DEFAULT_HEIGHT;
    o.integrator = PBRT_INTEGRATOR_BDPT;
    o.bounces = PBRT_BOUNCES;
    o.min_bounces = 0;
    o.spp = PBRT_SPP;
    o.fixed_subpixels = 0;
    return o;
}

/* Formats into err; returns PM_ERR_INPUT. */
static pm_status refuse(char *err, size_t errlen, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(err, errlen, fmt, ap);
    va_end(ap);
    return PM_ERR_INPUT;
}

/* 1 when p lies strictly inside sphere s. */
static int inside_sphere(const shape *s, vec3 p) { return vec_len2(vec_sub(p, s->center)) < s->radius * s->radius; }

pm_status pbrt_check(const scene *sc, const pbrt_options *o, char *err, size_t errlen)
{
    assert(sc && o && err && errlen > 0);
    for (size_t i = 0; i < sc->nshapes; i++) {
        const shape *s = &sc->shapes[i];
        assert(s->material >= 0 && (size_t)s->material < sc->nmaterials);
        const material *m = &sc->materials[s->material];
        if (m->kind != MATERIAL_GLASS)
            continue;
        if (s->kind == SHAPE_RECT)
            return refuse(err, errlen,
                          "shape %zu: glass rectangle (material '%s'): pbrt scales radiance by eta^2 at each "
                          "refraction and our renderer does not; the two agree only through closed glass bodies",
                          i + 1, m->name);
        if (inside_sphere(s, sc->camera.position))
            return refuse(err, errlen,
                          "shape %zu: the camera is inside a glass sphere (material '%s'): pbrt's eta^2 radiance "
                          "scaling would not cancel",
                          i + 1, m->name);
        if (inside_sphere(s, sc->light.position))
            return refuse(err, errlen,
                          "shape %zu: the light is inside a glass sphere (material '%s'): pbrt's eta^2 radiance "
                          "scaling would not cancel",
                          i + 1, m->name);
    }
    if (o->min_bounces > 0 && o->integrator != PBRT_INTEGRATOR_PATH)
        return refuse(err, errlen, "--min-bounces: only the path integrator has a minimum depth (not %s)",
                      pbrt_integrator_name(o->integrator));
    if (o->min_bounces > 0 && o->min_bounces >= o->bounces)
        return refuse(err, errlen, "--min-bounces %u: must be below --bounces (%u)", o->min_bounces, o->bounces);
    return PM_OK;
}

/* Writes "x y z". */
static void put_vec(FILE *f, vec3 v)
{
    numfmt_put_exact(f, v.x);
    fputc(' ', f);
    numfmt_put_exact(f, v.y);
    fputc(' ', f);
    numfmt_put_exact(f, v.z);
}

/* Writes s inside a # comment: bytes other than printable ASCII become '?'. */
static void put_comment_text(FILE *f, const char *s)
{
    for (; *s; s++)
        fputc(*s >= 0x20 && *s < 0x7f ? *s : '?', f);
}

/* The `fov` pbrt needs: the angle of the shorter image axis, degrees. */
static double shorter_axis_fov(const scene_camera *c, uint32_t w, uint32_t h)
{
    if (w <= h)
        return c->hfov_deg;
    double half = c->hfov_deg * VEC_PI / 360.0;
    return atan(tan(half) * (double)h / (double)w) * 360.0 / VEC_PI;
}

static void put_header(FILE *f, const scene *sc, const char *scene_name, const pbrt_options *o)
{
    fputs("# pbrt-v3 scene exported by `photonmap export-pbrt` from ", f);
    put_comment_text(f, scene_name);
    fprintf(f, "\n# settings: %ux%u, integrator %s, %u indirect bounces (maxdepth %u)", o->width, o->height,
            pbrt_integrator_name(o->integrator), o->bounces, o->bounces + 1);
    if (o->min_bounces > 0)
        fprintf(f, ", only paths of more than %u (mindepth %u: needs the local change of reference/pbrt)",
                o->min_bounces, o->min_bounces + 1);
    fprintf(f, ", %u spp%s\n", o->spp, o->fixed_subpixels ? " at fixed subpixel points" : "");
    fputs("# Render: pbrt --outfile OUT.exr THIS.pbrt (linear RGB, one-pixel box filter).\n", f);
    fputs("# Units: point light I = power/(4 pi); Scale -1 1 1 makes pbrt's left-handed camera\n", f);
    fputs("# right-handed; fov is the shorter image axis's.\n", f);
    fprintf(f, "# Scene bounds diagonal %g.\n\n", sc->scale);
}

static void put_camera(FILE *f, const scene *sc, const pbrt_options *o)
{
    const scene_camera *c = &sc->camera;
    fprintf(f, "# horizontal fov %g degrees\nScale -1 1 1\nLookAt ", c->hfov_deg);
    put_vec(f, c->position);
    fputs("  ", f);
    put_vec(f, c->look_at);
    fputs("  ", f);
    put_vec(f, c->up);
    fputs("\nCamera \"perspective\" \"float fov\" [ ", f);
    numfmt_put_exact(f, shorter_axis_fov(c, o->width, o->height));
    fputs(" ]\n", f);
    uint32_t side = (uint32_t)ceil(sqrt((double)o->spp));
    while (side * side < o->spp)
        side++;
    fprintf(f, "Sampler \"stratified\" \"integer xsamples\" [ %u ] \"integer ysamples\" [ %u ] \"bool jitter\" \"%s\"\n",
            side, side, o->fixed_subpixels ? "false" : "true");
    fputs("PixelFilter \"box\" \"float xwidth\" [ 0.5 ] \"float ywidth\" [ 0.5 ]\n", f);
    fprintf(f, "Film \"image\" \"integer xresolution\" [ %u ] \"integer yresolution\" [ %u ] \"string filename\" \"pbrt.exr\"\n",
            o->width, o->height);
    fprintf(f, "Integrator \"%s\" \"integer maxdepth\" [ %u ]", pbrt_integrator_name(o->integrator), o->bounces + 1);
    if (o->integrator == PBRT_INTEGRATOR_DIRECTLIGHTING)
        fputs(" \"string strategy\" \"all\"", f);
    if (o->min_bounces > 0)
        fprintf(f, " \"integer mindepth\" [ %u ]", o->min_bounces + 1);
    fputs("\n\nWorldBegin\n\n", f);
}

static void put_light(FILE *f, const scene *sc)
{
    vec3 intensity = vec_scale(sc->light.power, 1.0 / (4.0 * VEC_PI));
    fputs("# point light: power ", f);
    put_vec(f, sc->light.power);
    fputs(" W, intensity power/(4 pi) W/sr\nLightSource \"point\" \"point from\" [ ", f);
    put_vec(f, sc->light.position);
    fputs(" ] \"rgb I\" [ ", f);
    put_vec(f, intensity);
    fputs(" ]\n\n", f);
}

static void put_materials(FILE *f, const scene *sc)
{
    for (size_t i = 0; i < sc->nmaterials; i++) {
        const material *m = &sc->materials[i];
        fputs("# material '", f);
        put_comment_text(f, m->name);
        fprintf(f, "' (%s)\nMakeNamedMaterial \"pm_mat%zu\" ", material_kind_name(m->kind), i);
        switch (m->kind) {
        case MATERIAL_LAMBERT:
            fputs("\"string type\" \"matte\" \"float sigma\" [ 0 ] \"rgb Kd\" [ ", f);
            put_vec(f, m->color);
            break;
        case MATERIAL_MIRROR:
            fputs("\"string type\" \"mirror\" \"rgb Kr\" [ ", f);
            put_vec(f, m->color);
            break;
        case MATERIAL_GLASS:
            fputs("\"string type\" \"glass\" \"rgb Kr\" [ 1 1 1 ] \"rgb Kt\" [ 1 1 1 ] \"float eta\" [ ", f);
            numfmt_put_exact(f, m->ior);
            break;
        }
        fputs(" ]\n", f);
    }
    fputc('\n', f);
}

static void put_shapes(FILE *f, const scene *sc)
{
    for (size_t i = 0; i < sc->nshapes; i++) {
        const shape *s = &sc->shapes[i];
        fprintf(f, "# shape %zu\nAttributeBegin\n  NamedMaterial \"pm_mat%d\"\n", i + 1, s->material);
        if (s->kind == SHAPE_SPHERE) {
            fputs("  Translate ", f);
            put_vec(f, s->center);
            fputs("\n  Shape \"sphere\" \"float radius\" [ ", f);
            numfmt_put_exact(f, s->radius);
            fputs(" ]\n", f);
        } else {
            vec3 p[4] = {s->corner, vec_add(s->corner, s->edge1), vec_add(vec_add(s->corner, s->edge1), s->edge2),
                         vec_add(s->corner, s->edge2)};
            fputs("  Shape \"trianglemesh\" \"integer indices\" [ 0 1 2 0 2 3 ] \"point P\" [", f);
            for (int k = 0; k < 4; k++) {
                fputs("  ", f);
                put_vec(f, p[k]);
            }
            fputs(" ]\n", f);
        }
        fputs("AttributeEnd\n", f);
    }
}

pm_status pbrt_write(FILE *f, const scene *sc, const char *scene_name, const pbrt_options *o)
{
    assert(f && sc && scene_name && o && o->width > 0 && o->height > 0 && o->spp > 0);
    assert(o->bounces >= 1 && o->bounces <= PBRT_BOUNCES_MAX);
    assert(o->min_bounces == 0 || (o->integrator == PBRT_INTEGRATOR_PATH && o->min_bounces < o->bounces));
    put_header(f, sc, scene_name, o);
    put_camera(f, sc, o);
    put_light(f, sc);
    put_materials(f, sc);
    put_shapes(f, sc);
    fputs("\nWorldEnd\n", f);
    return ferror(f) ? PM_ERR_IO : PM_OK;
}

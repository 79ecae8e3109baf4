/* povray: writing a scene as POV-Ray 3.7 SDL that renders the same
 * radiance, with the mapping of units and conventions (renderer/README.md). */
#include "povray.h"

#include <assert.h>
#include <errno.h>
#include <inttypes.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "config.h"
#include "outfile.h"
#include "scene.h"
#include "numfmt.h"
#include "vec.h"

/* fade_distance in scene units: the light's 2/(1+(d/D)^2) is 2 D^2/d^2 to a
 * relative error (D/d)^2, far below half-float precision at room scale. */
#define POV_FADE_DISTANCE 1e-3
/* Relative shrink of the shadow-only proxy of a glass sphere (photons off). */
#define POV_PROXY_SHRINK 1e-4

/* Returns "fast" or "reference". */
const char *const povray_quality_names[] = {"fast", "reference", NULL};

const char *povray_quality_name(povray_quality q)
{
    assert(q == POVRAY_QUALITY_FAST || q == POVRAY_QUALITY_REFERENCE);
    return povray_quality_names[q];
}

povray_options povray_defaults(void)
{
    povray_options o;
    o.width = CONFIG_DEFAULT_WIDTH;
    o.height = CONFIG_DEFAULT_HEIGHT;
    o.quality = POVRAY_QUALITY_FAST;
    o.radiosity = 1;
    o.photons = 1;
    o.glass_caustics = 1;
    o.rect_thickness = POVRAY_RECT_THICKNESS;
    o.bounces = POVRAY_BOUNCES;
    return o;
}

/* Writes <x, y, z> as is (colours, or vectors already in POV coordinates). */
static void put_triple(FILE *f, vec3 v)
{
    fputc('<', f);
    numfmt_put_exact(f, v.x);
    fputs(", ", f);
    numfmt_put_exact(f, v.y);
    fputs(", ", f);
    numfmt_put_exact(f, v.z);
    fputc('>', f);
}

/* A point or direction of the scene in POV-Ray's left-handed coordinates. */
static vec3 pov_coords(vec3 v) { return vec_make(v.x, v.y, -v.z); }

static void put_point(FILE *f, vec3 v) { put_triple(f, pov_coords(v)); }

/* 1 when v has exactly one non-zero component. */
static int axis_aligned(vec3 v) { return (v.x != 0.0) + (v.y != 0.0) + (v.z != 0.0) == 1; }

/* Writes s inside a // comment: bytes other than printable ASCII become '?'. */
static void put_comment_text(FILE *f, const char *s)
{
    for (; *s; s++)
        fputc(*s >= 0x20 && *s < 0x7f ? *s : '?', f);
}

static void put_header(FILE *f, const scene *sc, const char *scene_name, const povray_options *o)
{
    fprintf(f, "// POV-Ray 3.7 SDL exported by `photonmap export-pov` from ");
    put_comment_text(f, scene_name);
    fputc('\n', f);
    fprintf(f, "// settings: %ux%u, quality %s, radiosity %s, photons %s\n", o->width, o->height,
            povray_quality_name(o->quality), o->radiosity ? "on" : "off", o->photons ? "on" : "off");
    fprintf(f, "// Render single-threaded for reproducibility, linear OpenEXR, no antialiasing:\n");
    fprintf(f, "//   povray +I<this> +O<out>.exr +FE +W%u +H%u -A -J +WT1 -D -V +GS\n", o->width, o->height);
    fprintf(f, "// (for the renderer's 2x2 subpixels render at 2W x 2H and box-downsample by 2).\n");
    fprintf(f, "// Units: z negated (left-handed); light colour = I/(2 pi D^2) with fade_distance D,\n");
    fprintf(f, "// fade_power 2, so that colour x 2/(1+(d/D)^2) x diffuse 1 = I/(pi d^2).\n");
    fprintf(f, "// Scene bounds diagonal %g.\n", sc->scale);
    if (o->rect_thickness != POVRAY_RECT_THICKNESS) /* (the default's line predates the option) */
        fprintf(f, "// Rectangles are boxes %g of the diagonal thick (--rect-thickness).\n", o->rect_thickness);
    if (o->radiosity && o->bounces != POVRAY_BOUNCES)
        fprintf(f, "// %u indirect bounces (--bounces): compare with render --photon-depth %u.\n", o->bounces,
                o->bounces + 1);
    fputc('\n', f);
    fprintf(f, "#version 3.7;\n\n");
    fprintf(f, "global_settings {\n");
    fprintf(f, "  assumed_gamma 1.0\n");
    fprintf(f, "  ambient_light rgb 0\n");
    fprintf(f, "  max_trace_level 32\n");
    fprintf(f, "  adc_bailout 1e-4\n");
    if (o->radiosity) {
        int ref = o->quality == POVRAY_QUALITY_REFERENCE;
        fprintf(f, "  radiosity {\n");
        fprintf(f, "    pretrace_start 0.08\n");
        fprintf(f, "    pretrace_end 0.02\n");
        fprintf(f, "    count %d\n", ref ? 300 : 100);
        fprintf(f, "    error_bound %s\n", ref ? "0.3" : "0.5");
        fprintf(f, "    nearest_count %d\n", ref ? 8 : 5);
        fprintf(f, "    recursion_limit %u\n", o->bounces);
        fprintf(f, "    low_error_factor 0.5\n");
        fprintf(f, "    gray_threshold 0\n");
        fprintf(f, "    minimum_reuse 0.015\n");
        fprintf(f, "    brightness 1\n");
        fprintf(f, "    adc_bailout 0.001\n");
        fprintf(f, "    always_sample off\n");
        fprintf(f, "    normal off\n");
        fprintf(f, "    media off\n");
        fprintf(f, "  }\n");
    }
    if (o->photons) {
        fprintf(f, "  photons {\n");
        /* The gather count, not the photon count, sets the noise; and here
         * POV-Ray's photon pass slowed down pathologically with count 1e6 (no
         * progress in minutes), so both qualities use the same photons. */
        fprintf(f, "    count 200000\n");
        fprintf(f, "    gather 20, 100\n");
        fprintf(f, "    autostop 0\n");
        fprintf(f, "    max_trace_level 32\n");
        fprintf(f, "    adc_bailout 1e-4\n");
        fprintf(f, "    media off\n");
        fprintf(f, "  }\n");
    }
    fprintf(f, "}\n\n");
    fprintf(f, "#default { finish { ambient 0 emission 0 diffuse 1 brilliance 1 specular 0 phong 0 } }\n\n");
}

static void put_camera(FILE *f, const scene *sc, const povray_options *o)
{
    const scene_camera *c = &sc->camera;
    fprintf(f, "camera {\n  perspective\n  location ");
    put_point(f, c->position);
    fprintf(f, "\n  right x*");
    numfmt_put_exact(f, (double)o->width / (double)o->height);
    fprintf(f, "\n  up y\n  sky ");
    put_point(f, c->up);
    fprintf(f, "\n  angle ");
    numfmt_put_exact(f, c->hfov_deg);
    fprintf(f, "\n  look_at ");
    put_point(f, c->look_at);
    fprintf(f, "\n}\n\n");
}

static void put_light(FILE *f, const scene *sc, const povray_options *o)
{
    const double d = POV_FADE_DISTANCE;
    vec3 intensity = vec_scale(sc->light.power, 1.0 / (4.0 * VEC_PI));
    vec3 colour = vec_scale(intensity, 1.0 / (2.0 * VEC_PI * d * d));
    fprintf(f, "// intensity ");
    put_triple(f, intensity);
    fprintf(f, " W/sr\nlight_source {\n  ");
    put_point(f, sc->light.position);
    fprintf(f, "\n  color rgb ");
    put_triple(f, colour);
    fprintf(f, "\n  fade_distance ");
    numfmt_put_exact(f, d);
    fprintf(f, "\n  fade_power 2\n");
    if (o->photons)
        fprintf(f, "  photons { reflection on refraction on }\n");
    fprintf(f, "}\n\n");
}

static void put_materials(FILE *f, const scene *sc)
{
    for (size_t i = 0; i < sc->nmaterials; i++) {
        const material *m = &sc->materials[i];
        fprintf(f, "// material '%s' (%s)\n#declare PM_Mat%zu = material {\n", m->name, material_kind_name(m->kind), i);
        switch (m->kind) {
        case MATERIAL_LAMBERT:
            fprintf(f, "  texture { pigment { rgb ");
            put_triple(f, m->color);
            fprintf(f, " } finish { diffuse 1 brilliance 1 ambient 0 } }\n");
            break;
        case MATERIAL_MIRROR:
            fprintf(f, "  texture { pigment { rgb 0 } finish { diffuse 0 ambient 0 reflection { rgb ");
            put_triple(f, m->color);
            fprintf(f, " } } }\n");
            break;
        case MATERIAL_GLASS:
            fprintf(f, "  texture { pigment { rgbf <1, 1, 1, 1> }\n");
            fprintf(f, "            finish { diffuse 0 ambient 0 reflection { 0, 1 fresnel on } conserve_energy } }\n");
            fprintf(f, "  interior { ior ");
            numfmt_put_exact(f, m->ior);
            fprintf(f, " }\n");
            break;
        }
        fprintf(f, "}\n");
    }
    fputc('\n', f);
}

/* The object-level photons block for a shape of material kind k (none for
 * glass without its caustic: a comment says so). */
static void put_photon_block(FILE *f, material_kind k, const povray_options *o)
{
    if (k == MATERIAL_MIRROR)
        fprintf(f, "  photons { target reflection on refraction off collect off }\n");
    else if (k == MATERIAL_GLASS && o->glass_caustics)
        fprintf(f, "  photons { target reflection on refraction on collect off }\n");
    else if (k == MATERIAL_GLASS)
        fprintf(f, "  // glass caustic removed (negative control)\n");
}

/* A rectangle as a thin box whose face toward the light lies exactly in the
 * rectangle's plane (so directly lit surfaces are exact). The box spans the
 * depths [lo, hi] x thickness behind that face: (0, 1) for the surface, a
 * range strictly inside for a shadow proxy. Writes "box {" and the shape and
 * leaves the object open. */
static void put_rect(FILE *f, const scene *sc, const shape *s, double lo, double hi, double thickness)
{
    assert(0.0 <= lo && lo < hi && hi <= 1.0 && thickness > 0.0);
    double side = vec_dot(s->normal, vec_sub(sc->light.position, s->corner));
    double thick = (side > 0.0 ? -1.0 : 1.0) * thickness * sc->scale;
    vec3 depth = vec_scale(s->normal, thick * (hi - lo));
    vec3 corner = vec_madd(s->corner, s->normal, thick * lo);
    fprintf(f, "box {\n  ");
    if (axis_aligned(s->edge1) && axis_aligned(s->edge2)) {
        vec3 a = pov_coords(corner);
        vec3 b = pov_coords(vec_add(vec_add(vec_add(corner, s->edge1), s->edge2), depth));
        put_triple(f, vec_make(fmin(a.x, b.x), fmin(a.y, b.y), fmin(a.z, b.z)));
        fprintf(f, ", ");
        put_triple(f, vec_make(fmax(a.x, b.x), fmax(a.y, b.y), fmax(a.z, b.z)));
        fprintf(f, "\n");
    } else {
        /* unit box mapped by x -> edge1, y -> edge2, z -> depth, then moved */
        vec3 rows[4] = {pov_coords(s->edge1), pov_coords(s->edge2), pov_coords(depth), pov_coords(corner)};
        fprintf(f, "<0, 0, 0>, <1, 1, 1>\n  matrix <");
        for (int r = 0; r < 4; r++) {
            numfmt_put_exact(f, rows[r].x);
            fputs(", ", f);
            numfmt_put_exact(f, rows[r].y);
            fputs(", ", f);
            numfmt_put_exact(f, rows[r].z);
            fputs(r < 3 ? ",  " : ">\n", f);
        }
    }
}

/* Writes "sphere {" or "box {" and the geometry of s, leaving it open; a
 * proxy is the same shape shrunk strictly inside it. */
static void put_geometry(FILE *f, const scene *sc, const shape *s, int proxy, double thickness)
{
    if (s->kind == SHAPE_SPHERE) {
        fprintf(f, "sphere {\n  ");
        put_point(f, s->center);
        fprintf(f, ", ");
        numfmt_put_exact(f, proxy ? s->radius * (1.0 - POV_PROXY_SHRINK) : s->radius);
        fprintf(f, "\n");
    } else if (proxy) {
        put_rect(f, sc, s, 0.25, 0.75, thickness);
    } else {
        put_rect(f, sc, s, 0.0, 1.0, thickness);
    }
}

/* The shadow-only proxy of glass shape s. Without photons POV-Ray lets
 * direct light straight through glass; the renderer treats light through
 * glass as a caustic (photons only). An opaque twin just inside, invisible
 * to camera, refracted, reflected and radiosity rays, casts the shadow the
 * renderer's shadow rays see. */
static void put_glass_proxy(FILE *f, const scene *sc, const shape *s, const povray_options *o)
{
    fprintf(f, "// shadow-only proxy of the glass above (photons off)\n");
    put_geometry(f, sc, s, 1, o->rect_thickness);
    fprintf(f, "  pigment { rgb 0 } finish { diffuse 0 ambient 0 }\n");
    fprintf(f, "  no_image no_reflection no_radiosity\n}\n");
}

static void put_shapes(FILE *f, const scene *sc, const povray_options *o)
{
    for (size_t i = 0; i < sc->nshapes; i++) {
        const shape *s = &sc->shapes[i];
        assert(s->material >= 0 && (size_t)s->material < sc->nmaterials);
        const material *m = &sc->materials[s->material];
        put_geometry(f, sc, s, 0, o->rect_thickness);
        fprintf(f, "  material { PM_Mat%d }  // %s\n", s->material, m->name);
        put_photon_block(f, m->kind, o);
        fprintf(f, "}\n");
        if (m->kind == MATERIAL_GLASS && !o->photons)
            put_glass_proxy(f, sc, s, o);
    }
    /* without the glass caustic (photons on), the proxies follow all the
     * shapes */
    for (size_t i = 0; i < sc->nshapes && o->photons && !o->glass_caustics; i++)
        if (sc->materials[sc->shapes[i].material].kind == MATERIAL_GLASS)
            put_glass_proxy(f, sc, &sc->shapes[i], o);
}

pm_status povray_write(FILE *f, const scene *sc, const char *scene_name, const povray_options *o)
{
    assert(f && sc && scene_name && o && o->width > 0 && o->height > 0);
    assert(o->rect_thickness >= POVRAY_RECT_THICKNESS_MIN && o->rect_thickness <= POVRAY_RECT_THICKNESS_MAX);
    assert(o->bounces >= 1 && o->bounces <= POVRAY_BOUNCES_MAX);
    put_header(f, sc, scene_name, o);
    put_camera(f, sc, o);
    put_light(f, sc, o);
    put_materials(f, sc);
    put_shapes(f, sc, o);
    return ferror(f) ? PM_ERR_IO : PM_OK;
}

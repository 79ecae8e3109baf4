/* cli: the subcommands' option tables and the one parser that reads them
 * (cli.h). */
#include "cli.h"

#include <assert.h>
#include <errno.h>
#include <inttypes.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#include "scene.h"

pm_status cli_error(const cli_command *cmd, const char *fmt, ...)
{
    va_list ap;
    fprintf(stderr, "photonmap: ");
    va_start(ap, fmt);
    vfprintf(stderr, fmt, ap);
    va_end(ap);
    fprintf(stderr, "\n(run 'photonmap %s --help' for usage)\n", cmd->name);
    return PM_ERR_INPUT;
}

/* "a, b or c" (bar = 0) or "a|b|c" (bar = 1) for a NULL-terminated list,
 * into buf. */
static const char *choice_list(const char *const *choices, int bar, char *buf, size_t cap)
{
    buf[0] = '\0';
    size_t n = 0;
    while (choices[n])
        n++;
    for (size_t i = 0; i < n; i++) {
        const char *sep = i == 0 ? "" : bar ? "|" : (i + 1 == n ? " or " : ", ");
        strncat(buf, sep, cap - strlen(buf) - 1);
        strncat(buf, choices[i], cap - strlen(buf) - 1);
    }
    return buf;
}

/* Parses v as option o's value into args. Returns PM_OK, or PM_ERR_INPUT
 * after printing why. */
static pm_status parse_value(const cli_command *cmd, const cli_option *o, const char *v, void *args)
{
    char *dst = (char *)args + o->offset;
    char buf[256];
    switch (o->kind) {
    case CLI_U32:
    case CLI_U64: {
        const char *p = v[0] == '+' ? v + 1 : v;
        char *end = NULL;
        unsigned long long x = 0;
        errno = 0;
        if (*p >= '0' && *p <= '9')
            x = strtoull(p, &end, 10);
        if (!(*p >= '0' && *p <= '9') || *end != '\0' || errno == ERANGE || x < o->ulo || x > o->uhi)
            return cli_error(cmd, "%s: expected an integer in [%" PRIu64 ", %" PRIu64 "], got '%s'", o->name, o->ulo,
                             o->uhi, v);
        if (o->kind == CLI_U32) {
            uint32_t u = (uint32_t)x;
            memcpy(dst, &u, sizeof u);
        } else {
            uint64_t u = (uint64_t)x;
            memcpy(dst, &u, sizeof u);
        }
        return PM_OK;
    }
    case CLI_REAL: {
        char *end = NULL;
        errno = 0;
        double x = strtod(v, &end);
        /* decimal only: strtod also reads hex floats, "inf" and "nan" */
        int decimal = strpbrk(v, "xXnN") == NULL;
        if (end == v || *end != '\0' || !decimal || !isfinite(x) || x < o->rlo || x > o->rhi)
            return cli_error(cmd, "%s: expected a number in [%g, %g], got '%s'", o->name, o->rlo, o->rhi, v);
        memcpy(dst, &x, sizeof x);
        return PM_OK;
    }
    case CLI_CHOICE:
        for (int i = 0; o->choices[i]; i++) {
            if (!strcmp(v, o->choices[i])) {
                memcpy(dst, &i, sizeof i);
                return PM_OK;
            }
        }
        return cli_error(cmd, "%s: expected %s, got '%s'", o->name, choice_list(o->choices, 0, buf, sizeof buf), v);
    case CLI_STRING:
        if (v[0] == '\0')
            return cli_error(cmd, "%s: expected a non-empty value", o->name);
        memcpy(dst, &v, sizeof v);
        return PM_OK;
    case CLI_FLAG:
        break;
    }
    assert(!"parse_value: a flag has no value");
    return PM_ERR_INPUT;
}

pm_status cli_parse(const cli_command *cmd, int argc, char **argv, int first, void *args, cli_given *given)
{
    assert(cmd->noptions <= CLI_MAX_OPTIONS);
    if (given)
        memset(given, 0, sizeof *given);
    const char *positional = NULL;
    for (int i = first; i < argc; i++) {
        const char *a = argv[i];
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            cli_usage(stdout, cmd, args); /* args holds the defaults here */
            return PM_DONE;
        }
    }
    for (int i = first; i < argc; i++) {
        const char *a = argv[i];
        if (a[0] != '-' || !strcmp(a, "-")) {
            if (positional)
                return cli_error(cmd, "unexpected argument '%s' (%s already given: '%s')", a, cmd->positional,
                                 positional);
            positional = a;
            continue;
        }
        const cli_option *o = NULL;
        for (size_t k = 0; k < cmd->noptions; k++)
            if (!strcmp(a, cmd->options[k].name))
                o = &cmd->options[k];
        if (!o)
            return cli_error(cmd, "unknown option '%s'", a);
        if (given)
            given->given[o - cmd->options] = 1;
        if (o->kind == CLI_FLAG) {
            memcpy((char *)args + o->offset, &o->flag_value, sizeof(int));
            continue;
        }
        if (i + 1 >= argc)
            return cli_error(cmd, "%s needs a value", a);
        pm_status rc = parse_value(cmd, o, argv[++i], args);
        if (rc != PM_OK)
            return rc;
    }
    if (!positional)
        return cli_error(cmd, "%s needs a %s", cmd->name, cmd->positional_what);
    memcpy((char *)args + cmd->positional_offset, &positional, sizeof positional);
    return PM_OK;
}

int cli_was_given(const cli_command *cmd, const cli_given *given, const char *name)
{
    for (size_t k = 0; k < cmd->noptions; k++)
        if (!strcmp(cmd->options[k].name, name))
            return given->given[k];
    assert(!"cli_was_given: no such option");
    return 0;
}

/* The value of o in `defaults` as text, into buf. */
static const char *default_value(const cli_option *o, const void *defaults, char *buf, size_t cap)
{
    if (o->default_text)
        return o->default_text;
    if (!defaults)
        return NULL;
    const char *src = (const char *)defaults + o->offset;
    switch (o->kind) {
    case CLI_U32: {
        uint32_t u;
        memcpy(&u, src, sizeof u);
        snprintf(buf, cap, "%" PRIu32, u);
        return buf;
    }
    case CLI_U64: {
        uint64_t u;
        memcpy(&u, src, sizeof u);
        snprintf(buf, cap, "%" PRIu64, u);
        return buf;
    }
    case CLI_REAL: {
        double x;
        memcpy(&x, src, sizeof x);
        snprintf(buf, cap, "%g", x);
        return buf;
    }
    case CLI_CHOICE: {
        int i;
        memcpy(&i, src, sizeof i);
        return o->choices[i];
    }
    case CLI_STRING: {
        const char *s;
        memcpy(&s, src, sizeof s);
        return s ? s : "none";
    }
    case CLI_FLAG: {
        int f;
        memcpy(&f, src, sizeof f);
        return f == o->flag_value ? "on" : "off";
    }
    }
    return NULL;
}

void cli_usage(FILE *f, const cli_command *cmd, const void *defaults)
{
    char buf[256], def[64], range[128];
    fprintf(f, "usage: photonmap %s %s [options]\n  %s\n\noptions:\n", cmd->name, cmd->positional, cmd->summary);
    for (size_t k = 0; k < cmd->noptions; k++) {
        const cli_option *o = &cmd->options[k];
        const char *meta = o->metavar ? o->metavar : "";
        if (o->kind == CLI_CHOICE)
            meta = choice_list(o->choices, 1, buf, sizeof buf);
        range[0] = '\0';
        if (o->kind == CLI_U32 || o->kind == CLI_U64)
            snprintf(range, sizeof range, "; an integer in [%" PRIu64 ", %" PRIu64 "]", o->ulo, o->uhi);
        else if (o->kind == CLI_REAL)
            snprintf(range, sizeof range, "; a number in [%g, %g]", o->rlo, o->rhi);
        const char *d = default_value(o, defaults, def, sizeof def);
        fprintf(f, "  %s%s%s\n      %s (default: %s%s)\n", o->name, meta[0] ? " " : "", meta, o->help,
                d ? d : "none", range);
    }
    fprintf(f, "  --help\n      this text\n");
}

/* ---- render ---- */

/* the tables write choices as ints into enum fields */
_Static_assert(sizeof(config_method) == sizeof(int) && sizeof(config_direct) == sizeof(int) &&
                   sizeof(config_rep_tree) == sizeof(int) && sizeof(config_rep_eval) == sizeof(int) &&
                   sizeof(config_rep_gate) == sizeof(int) && sizeof(scene_accel) == sizeof(int) &&
                   sizeof(povray_quality) == sizeof(int) && sizeof(pbrt_integrator) == sizeof(int),
               "the enums of the option tables are int-sized");

#define RO(field) offsetof(cli_render_args, field)
#define RC(field) offsetof(cli_render_args, cfg.field)
static const cli_option render_options[] = {
    {.name = "--method", .kind = CLI_CHOICE, .offset = RC(method), .choices = config_method_names,
     .help = "radiance estimate: the paper's eq. 1 or eq. 2"},
    {.name = "--photons", .kind = CLI_U64, .metavar = "N", .offset = RC(photons), .uhi = CONFIG_MAX_PHOTONS,
     .help = "photons emitted from the light, P_e (0: none; a black image, or direct light only by shadow rays)"},
    {.name = "--nn", .kind = CLI_U32, .metavar = "N", .offset = RC(nn), .ulo = CONFIG_MIN_NN, .uhi = CONFIG_MAX_NN,
     .help = "nearest photons per estimate and per precompute, n (precomputed: 3 or more without --bias-correction)"},
    {.name = "--bias-correction", .kind = CLI_FLAG, .offset = RC(bias_correction), .flag_value = 1,
     .help = "the unbiased estimate: only the photons strictly inside r; precomputed: from the non-representatives"},
    {.name = "--width", .kind = CLI_U32, .metavar = "W", .offset = RC(width), .ulo = 1, .uhi = CONFIG_MAX_SIDE,
     .help = "image width in pixels"},
    {.name = "--height", .kind = CLI_U32, .metavar = "H", .offset = RC(height), .ulo = 1, .uhi = CONFIG_MAX_SIDE,
     .help = "image height in pixels"},
    {.name = "--subpixels", .kind = CLI_U32, .metavar = "S", .offset = RC(subpixels), .ulo = 1,
     .uhi = CONFIG_MAX_SUBPIXELS, .help = "SxS subpixel samples per pixel, box filtered"},
    {.name = "--threads", .kind = CLI_U32, .metavar = "T", .offset = RC(threads), .uhi = CONFIG_MAX_THREADS,
     .help = "worker threads, 0 = all cores (the image does not depend on it)"},
    {.name = "--seed", .kind = CLI_U64, .metavar = "S", .offset = RC(seed), .uhi = UINT64_MAX,
     .help = "names every random stream"},
    {.name = "--rep-every", .kind = CLI_U32, .metavar = "K", .offset = RC(rep_every), .ulo = 1, .uhi = UINT32_MAX,
     .help = "precomputed: every K-th stored photon is a representative"},
    {.name = "--rep-count", .kind = CLI_U64, .metavar = "N", .offset = RC(rep_count), .uhi = CONFIG_MAX_REP_COUNT,
     .help = "precomputed: N representatives spread evenly over the stored photons instead (0: --rep-every)"},
    {.name = "--normal-cos", .kind = CLI_REAL, .metavar = "C", .offset = RC(normal_cos), .rlo = -1.0, .rhi = 1.0,
     .help = "precomputed: a representative's normal must agree above this cosine"},
    {.name = "--rep-tree", .kind = CLI_CHOICE, .offset = RC(rep_tree), .choices = config_rep_tree_names,
     .help = "precomputed: the representatives' own kd-tree, or the photon tree by flag"},
    {.name = "--rep-eval", .kind = CLI_CHOICE, .offset = RC(rep_eval), .choices = config_rep_eval_names,
     .help = "precomputed: every representative's irradiance before the eye pass, or each on first use "
             "(the same image; renderer/README.md)"},
    {.name = "--rep-gate", .kind = CLI_CHOICE, .offset = RC(rep_gate), .choices = config_rep_gate_names,
     .help = "precomputed: the nearest agreeing representative, or one near x's tangent plane, else the "
             "conventional estimate (renderer/README.md)"},
    {.name = "--rep-gate-tau", .kind = CLI_REAL, .metavar = "T", .offset = RC(rep_gate_tau),
     .rlo = CONFIG_MIN_REP_GATE_TAU, .rhi = CONFIG_MAX_REP_GATE_TAU,
     .help = "--rep-gate plane or plane-lookup: the largest distance from the tangent plane, in kNN radii"},
    {.name = "--max-radius", .kind = CLI_REAL, .metavar = "R", .offset = RC(max_radius), .rlo = 1e-30, .rhi = 1e30,
     .help = "search radius cap in scene units",
     .default_text = CONFIG_DEFAULT_MAX_RADIUS_FRAC_TEXT " x the diagonal of the photons' bounding box"},
    {.name = "--direct", .kind = CLI_CHOICE, .offset = RC(direct), .choices = config_direct_names,
     .help = "direct light from the photon map (the paper) or by shadow rays",
     .default_text = "photons; with --gather shadow-rays, its only choice"},
    {.name = "--gather", .kind = CLI_U32, .metavar = "N", .offset = RC(gather), .uhi = CONFIG_MAX_GATHER,
     .help = "final gathering: N gather rays per first diffuse eye hit (renderer/README.md); 0: the map seen directly"},
    {.name = "--photon-depth", .kind = CLI_U32, .metavar = "D", .offset = RC(photon_depth), .ulo = 1,
     .uhi = CONFIG_MAX_DEPTH, .help = "maximum bounces of a photon path"},
    {.name = "--eye-depth", .kind = CLI_U32, .metavar = "D", .offset = RC(eye_depth), .uhi = CONFIG_MAX_DEPTH,
     .help = "maximum specular bounces of an eye path"},
    {.name = "--accel", .kind = CLI_CHOICE, .offset = RC(accel), .choices = config_accel_names,
     .help = "ray casting: a BVH from " SCENE_BVH_MIN_SHAPES_TEXT " shapes on, always, or never (the same image)"},
    {.name = "-o", .kind = CLI_STRING, .metavar = "FILE.exr", .offset = RO(exr), .help = "linear float RGB OpenEXR"},
    {.name = "--png", .kind = CLI_STRING, .metavar = "FILE.png", .offset = RO(png), .help = "sRGB 8-bit preview"},
    {.name = "--exposure", .kind = CLI_REAL, .metavar = "E", .offset = RO(exposure), .rlo = 0.0, .rhi = 1e30,
     .help = "scale of the PNG preview"},
    {.name = "--stats", .kind = CLI_STRING, .metavar = "FILE.json", .offset = RO(stats),
     .help = "run statistics as JSON"},
    {.name = "--dump-reps", .kind = CLI_STRING, .metavar = "FILE.csv", .offset = RC(dump_reps),
     .help = "precomputed: the representatives as CSV (position, normal, irradiance), outside the times"},
    {.name = "--allow-nonfinite", .kind = CLI_FLAG, .offset = RC(allow_nonfinite), .flag_value = 1,
     .help = "keep an image whose radiance leaves the float range (otherwise exit 2, no image)"},
    {.name = "--quiet", .kind = CLI_FLAG, .offset = RO(quiet), .flag_value = 1,
     .help = "no progress bar and no summary line"},
    {.name = "--repeats", .kind = CLI_STRING, .metavar = "R|auto", .offset = RO(repeats),
     .help = "run the timed pipeline R times, the same image each time; the stats give minima, medians, the "
             "cold time and every repeat's (auto: " CONFIG_REPEATS_AUTO_TEXT ")",
     .default_text = CONFIG_DEFAULT_REPEATS_TEXT},
    {.name = "--no-output", .kind = CLI_FLAG, .offset = RO(no_output), .flag_value = 1,
     .help = "write no file, only the summary line's times (a render otherwise needs an output)"},
};
#undef RO
#undef RC

const cli_command cli_render = {.name = "render",
                                .summary = "renders SCENE by photon mapping (see README.md)",
                                .positional = "SCENE",
                                .positional_what = "scene file",
                                .positional_offset = offsetof(cli_render_args, scene),
                                .options = render_options,
                                .noptions = sizeof render_options / sizeof render_options[0]};

cli_render_args cli_render_defaults(void)
{
    cli_render_args a;
    memset(&a, 0, sizeof a);
    a.cfg = config_defaults();
    a.exposure = CONFIG_DEFAULT_EXPOSURE;
    return a;
}

void cli_render_resolve(cli_render_args *a)
{
    if (a->cfg.gather > 0 && !cli_was_given(&cli_render, &a->given, "--direct"))
        a->cfg.direct = CONFIG_DIRECT_SHADOW_RAYS;
}

pm_status cli_render_check(const cli_render_args *a)
{
    const config_render *c = &a->cfg;
    if (cli_was_given(&cli_render, &a->given, "--rep-count") && cli_was_given(&cli_render, &a->given, "--rep-every"))
        return cli_error(&cli_render,
                         "--rep-count and --rep-every are two rules for choosing the representatives: give one");
    if (cli_was_given(&cli_render, &a->given, "--rep-gate-tau") && c->rep_gate == CONFIG_REP_GATE_NONE)
        return cli_error(&cli_render,
                         "--rep-gate-tau is the plane gate's tolerance: use it with --rep-gate plane or plane-lookup");
    const char *why = config_check(c);
    if (why)
        return cli_error(&cli_render, "%s", why);
    if ((uint64_t)c->width * c->height > CONFIG_MAX_PIXELS)
        return cli_error(&cli_render, "an image of %ux%u pixels is too large (at most %llu pixels)", c->width,
                         c->height, (unsigned long long)CONFIG_MAX_PIXELS);
    return PM_OK;
}

/* ---- export-pov ---- */

#define PO(field) offsetof(cli_pov_args, field)
static const cli_option pov_options[] = {
    {.name = "--width", .kind = CLI_U32, .metavar = "W", .offset = PO(pov.width), .ulo = 1, .uhi = CONFIG_MAX_SIDE,
     .help = "the image width POV-Ray will render (sets the aspect ratio)"},
    {.name = "--height", .kind = CLI_U32, .metavar = "H", .offset = PO(pov.height), .ulo = 1, .uhi = CONFIG_MAX_SIDE,
     .help = "the image height POV-Ray will render"},
    {.name = "--quality", .kind = CLI_CHOICE, .offset = PO(pov.quality), .choices = povray_quality_names,
     .help = "radiosity and photon settings (reference/README.md)"},
    {.name = "--no-radiosity", .kind = CLI_FLAG, .offset = PO(pov.radiosity),
     .help = "no indirect diffuse light (radiosity on unless given)"},
    {.name = "--no-photons", .kind = CLI_FLAG, .offset = PO(pov.photons),
     .help = "no caustics; glass still shadows direct light (photons on unless given)"},
    {.name = "--no-glass-caustics", .kind = CLI_FLAG, .offset = PO(pov.glass_caustics),
     .help = "glass casts no caustic but still shadows; mirror caustics and radiosity stay (a negative control)"},
    {.name = "--rect-thickness", .kind = CLI_REAL, .metavar = "F", .offset = PO(pov.rect_thickness),
     .rlo = POVRAY_RECT_THICKNESS_MIN, .rhi = POVRAY_RECT_THICKNESS_MAX,
     .help = "a rectangle becomes a box this fraction of the scene's diagonal thick, behind its lit face"},
    {.name = "--bounces", .kind = CLI_U32, .metavar = "B", .offset = PO(pov.bounces), .ulo = 1,
     .uhi = POVRAY_BOUNCES_MAX,
     .help = "indirect diffuse bounces of the radiosity: the light paths of render --photon-depth B+1"},
    {.name = "-o", .kind = CLI_STRING, .metavar = "FILE.pov", .offset = PO(out), .help = "where to write the SDL",
     .default_text = "standard output"},
};
#undef PO

const cli_command cli_export_pov = {.name = "export-pov",
                                    .summary = "writes SCENE as POV-Ray 3.7 SDL radiometrically matched to the renderer",
                                    .positional = "SCENE",
                                    .positional_what = "scene file",
                                    .positional_offset = offsetof(cli_pov_args, scene),
                                    .options = pov_options,
                                    .noptions = sizeof pov_options / sizeof pov_options[0]};

cli_pov_args cli_pov_defaults(void)
{
    cli_pov_args a;
    memset(&a, 0, sizeof a);
    a.pov = povray_defaults();
    return a;
}

/* ---- export-pbrt ---- */

#define PB(field) offsetof(cli_pbrt_args, field)
static const cli_option pbrt_options_table[] = {
    {.name = "--width", .kind = CLI_U32, .metavar = "W", .offset = PB(pbrt.width), .ulo = 1, .uhi = CONFIG_MAX_SIDE,
     .help = "the film width"},
    {.name = "--height", .kind = CLI_U32, .metavar = "H", .offset = PB(pbrt.height), .ulo = 1, .uhi = CONFIG_MAX_SIDE,
     .help = "the film height"},
    {.name = "--integrator", .kind = CLI_CHOICE, .offset = PB(pbrt.integrator), .choices = pbrt_integrator_names,
     .help = "pbrt's integrator: bidirectional, path tracing, or direct light only (reference/pbrt/README.md)"},
    {.name = "--bounces", .kind = CLI_U32, .metavar = "B", .offset = PB(pbrt.bounces), .ulo = 1,
     .uhi = PBRT_BOUNCES_MAX,
     .help = "indirect bounces: pbrt's maxdepth B+1, the light paths of render --photon-depth B+1"},
    {.name = "--min-bounces", .kind = CLI_U32, .metavar = "M", .offset = PB(pbrt.min_bounces), .ulo = 0,
     .uhi = PBRT_BOUNCES_MAX,
     .help = "path only: keep paths of more than M indirect bounces (mindepth M+1, a local change to pbrt; 0: all)"},
    {.name = "--spp", .kind = CLI_U32, .metavar = "N", .offset = PB(pbrt.spp), .ulo = 1, .uhi = PBRT_SPP_MAX,
     .help = "samples per pixel (a stratified square grid: rounded up to a square)"},
    {.name = "--fixed-subpixels", .kind = CLI_FLAG, .offset = PB(pbrt.fixed_subpixels), .flag_value = 1,
     .help = "samples at fixed grid points, not jittered: the renderer's --subpixels sqrt(N) rays"},
    {.name = "-o", .kind = CLI_STRING, .metavar = "FILE.pbrt", .offset = PB(out), .help = "where to write the scene",
     .default_text = "standard output"},
};
#undef PB

const cli_command cli_export_pbrt = {.name = "export-pbrt",
                                     .summary = "writes SCENE as a pbrt-v3 scene radiometrically matched to the renderer",
                                     .positional = "SCENE",
                                     .positional_what = "scene file",
                                     .positional_offset = offsetof(cli_pbrt_args, scene),
                                     .options = pbrt_options_table,
                                     .noptions = sizeof pbrt_options_table / sizeof pbrt_options_table[0]};

cli_pbrt_args cli_pbrt_defaults(void)
{
    cli_pbrt_args a;
    memset(&a, 0, sizeof a);
    a.pbrt = pbrt_defaults();
    return a;
}

/* ---- info ---- */

#define IN(field) offsetof(cli_info_args, field)
static const cli_option info_options[] = {
    {.name = "--json", .kind = CLI_FLAG, .offset = IN(json), .flag_value = 1,
     .help = "the facts as one JSON object on standard output (the one format; required)"},
    {.name = "--width", .kind = CLI_U32, .metavar = "W", .offset = IN(width), .ulo = 1, .uhi = CONFIG_MAX_SIDE,
     .help = "the image width whose camera basis the JSON gives (render's --width)"},
    {.name = "--height", .kind = CLI_U32, .metavar = "H", .offset = IN(height), .ulo = 1, .uhi = CONFIG_MAX_SIDE,
     .help = "the image height whose camera basis the JSON gives (render's --height)"},
};
#undef IN

const cli_command cli_info = {.name = "info",
                              .summary = "prints SCENE's facts, read by the renderer's parser: camera and its basis, "
                                         "light, materials, shapes with their lines, bounds",
                              .positional = "SCENE",
                              .positional_what = "scene file",
                              .positional_offset = offsetof(cli_info_args, scene),
                              .options = info_options,
                              .noptions = sizeof info_options / sizeof info_options[0]};

cli_info_args cli_info_defaults(void)
{
    cli_info_args a;
    memset(&a, 0, sizeof a);
    config_render c = config_defaults();
    a.width = c.width;
    a.height = c.height;
    return a;
}

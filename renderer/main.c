/* main: the command line. `photonmap render SCENE [options]` renders;
 * `photonmap export-pov SCENE [options]` writes POV-Ray SDL;
 * `photonmap export-pbrt SCENE [options]` writes a pbrt-v3 scene. Each
 * subcommand's options are one table (cli.h) that drives parsing, range
 * errors and `--help`. main writes every output file. Every step returns a
 * pm_status; the exit code is pm_status_exit's (status.h): 0 success, 1
 * runtime failure (I/O, memory), 2 user input error (bad option or scene
 * file, with file:line:col, or an image whose radiance leaves the float
 * range). */
#include <assert.h>
#include <ctype.h>
#include <errno.h>
#include <float.h>
#include <inttypes.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cli.h"
#include "config.h"
#include "image.h"
#include "outfile.h"
#include "parallel.h"
#include "pbrt.h"
#include "povray.h"
#include "provenance.h"
#include "render.h"
#include "repeat.h"
#include "scene.h"
#include "stats.h"
#include "status.h"

/* ---- render ---- */

typedef struct {
    config_render cfg;
    const char *scene;
    const char *exr, *png, *stats;
    double exposure;
    int quiet;
    int no_output; /* --no-output: a render for its times only, no file */
    const char *repeats; /* --repeats: "auto" or a count (repeat_parse); NULL: the default */
} render_args;

static const char *const method_names[] = {"conventional", "precomputed", NULL};
static const char *const direct_names[] = {"photons", "shadow-rays", NULL};
static const char *const rep_tree_names[] = {"separate", "shared", NULL};
static const char *const rep_eval_names[] = {"eager", "lazy", NULL};
static const char *const rep_gate_names[] = {"none", "plane", "plane-lookup", NULL};
_Static_assert(sizeof(config_rep_eval) == sizeof(int) && sizeof(config_rep_gate) == sizeof(int),
               "config_rep_eval and config_rep_gate are int-sized");
/* in the order of scene_accel */
static const char *const accel_names[] = {"auto", "bvh", "linear", NULL};
/* the table writes these choices as ints into enum fields */
_Static_assert(sizeof(config_method) == sizeof(int), "config_method is int-sized");
_Static_assert(sizeof(config_direct) == sizeof(int), "config_direct is int-sized");
_Static_assert(sizeof(config_rep_tree) == sizeof(int), "config_rep_tree is int-sized");
_Static_assert(sizeof(scene_accel) == sizeof(int), "scene_accel is int-sized");
_Static_assert(SCENE_ACCEL_AUTO == 0 && SCENE_ACCEL_BVH == 1 && SCENE_ACCEL_LINEAR == 2, "accel_names order");

#define RO(field) offsetof(render_args, field)
#define RC(field) offsetof(render_args, cfg.field)
static const cli_option render_options[] = {
    {.name = "--method", .kind = CLI_CHOICE, .offset = RC(method), .choices = method_names,
     .help = "radiance estimate: the paper's eq. 1 or eq. 2"},
    {.name = "--photons", .kind = CLI_U64, .metavar = "N", .offset = RC(photons), .uhi = CONFIG_MAX_PHOTONS,
     .help = "photons emitted from the light, P_e; 0: no photon map (a black image, or direct light only "
             "with --direct shadow-rays)"},
    {.name = "--nn", .kind = CLI_U32, .metavar = "N", .offset = RC(nn), .ulo = CONFIG_MIN_NN, .uhi = CONFIG_MAX_NN,
     .help = "nearest photons per estimate / per precompute, n (n = 1 has no finite mean; the precomputed method "
             "needs n >= 3 without --bias-correction)"},
    {.name = "--bias-correction", .kind = CLI_FLAG, .offset = RC(bias_correction), .flag_value = 1,
     .help = "the unbiased estimate instead of the paper's: count only the photons strictly inside r (the paper's "
             "follows n/(n-1)); precomputed: estimate at representatives from the other, non-representative photons"},
    {.name = "--width", .kind = CLI_U32, .metavar = "W", .offset = RC(width), .ulo = 1, .uhi = CONFIG_MAX_SIDE,
     .help = "image width in pixels"},
    {.name = "--height", .kind = CLI_U32, .metavar = "H", .offset = RC(height), .ulo = 1, .uhi = CONFIG_MAX_SIDE,
     .help = "image height in pixels"},
    {.name = "--subpixels", .kind = CLI_U32, .metavar = "S", .offset = RC(subpixels), .ulo = 1,
     .uhi = CONFIG_MAX_SUBPIXELS,
     .help = "SxS subpixel samples per pixel, box filtered"},
    {.name = "--threads", .kind = CLI_U32, .metavar = "T", .offset = RC(threads), .uhi = CONFIG_MAX_THREADS,
     .help = "worker threads, 0 = all cores (the image does not depend on it)"},
    {.name = "--seed", .kind = CLI_U64, .metavar = "S", .offset = RC(seed), .uhi = UINT64_MAX,
     .help = "names every random stream"},
    {.name = "--rep-every", .kind = CLI_U32, .metavar = "K", .offset = RC(rep_every), .ulo = 1, .uhi = UINT32_MAX,
     .help = "precomputed: every K-th stored photon is a representative"},
    {.name = "--rep-count", .kind = CLI_U64, .metavar = "N", .offset = RC(rep_count), .uhi = CONFIG_MAX_REP_COUNT,
     .help = "precomputed: a fixed count of representatives instead of --rep-every: N stored photons spread evenly "
             "over the trace order (every stored photon when fewer are stored); 0: the --rep-every rule"},
    {.name = "--normal-cos", .kind = CLI_REAL, .metavar = "C", .offset = RC(normal_cos), .rlo = -1.0, .rhi = 1.0,
     .help = "precomputed: a representative's normal must agree above this cosine"},
    {.name = "--rep-tree", .kind = CLI_CHOICE, .offset = RC(rep_tree), .choices = rep_tree_names,
     .help = "precomputed: the representatives' own kd-tree, or the photon tree by flag"},
    /* the precomputed method beyond the paper (reps.h) */
    {.name = "--rep-eval", .kind = CLI_CHOICE, .offset = RC(rep_eval), .choices = rep_eval_names,
     .help = "precomputed: compute every representative's irradiance before the eye pass (the paper), or each "
             "the first time a lookup selects it, once (the same image bit for bit; time_s.precompute then holds "
             "only the representatives' tree, their cost is in time_s.render; not with --dump-reps)"},
    {.name = "--rep-gate", .kind = CLI_CHOICE, .offset = RC(rep_gate), .choices = rep_gate_names,
     .help = "precomputed: accept the nearest representative whose normal agrees (the paper), or the first of "
             "the 4 nearest that also lies within tau r of x's tangent plane, r its kNN radius, "
             "else the conventional estimate at x (rep_fallbacks); plane: its precompute also counts only the "
             "photons within tau r of its tangent plane (darker at concave edges: the adjacent face's photons "
             "no longer make up for the cut disc); plane-lookup: the paper's precompute. The plane is through "
             "the mean of the two normals: x's tangent plane on a flat surface, none of a sphere's own points "
             "fails; assumes a surface smooth within r; needs --rep-tree separate"},
    {.name = "--rep-gate-tau", .kind = CLI_REAL, .metavar = "T", .offset = RC(rep_gate_tau),
     .rlo = CONFIG_MIN_REP_GATE_TAU, .rhi = CONFIG_MAX_REP_GATE_TAU,
     .help = "--rep-gate plane or plane-lookup: the largest distance from the tangent plane, in kNN radii"},
    {.name = "--max-radius", .kind = CLI_REAL, .metavar = "R", .offset = RC(max_radius), .rlo = 1e-30, .rhi = 1e30,
     .help = "search radius cap in scene units (r is floored at 1e-3 of it, or of the photons' extent when the cap "
             "is larger: a cap beyond the photons finds what a cap at their extent finds)",
     .default_text = CONFIG_DEFAULT_MAX_RADIUS_FRAC_TEXT " x the diagonal of the photons' bounding box"},
    {.name = "--direct", .kind = CLI_CHOICE, .offset = RC(direct), .choices = direct_names,
     .help = "direct light from the photon map (the paper) or by shadow rays"},
    {.name = "--photon-depth", .kind = CLI_U32, .metavar = "D", .offset = RC(photon_depth), .ulo = 1,
     .uhi = CONFIG_MAX_DEPTH,
     .help = "maximum bounces of a photon path"},
    {.name = "--eye-depth", .kind = CLI_U32, .metavar = "D", .offset = RC(eye_depth), .uhi = CONFIG_MAX_DEPTH,
     .help = "maximum specular bounces of an eye path"},
    {.name = "--accel", .kind = CLI_CHOICE, .offset = RC(accel), .choices = accel_names,
     .help = "ray casting: a BVH over the shapes from " SCENE_BVH_MIN_SHAPES_TEXT " shapes on (auto), always, or a loop over "
             "every shape; the image does not depend on it"},
    {.name = "-o", .kind = CLI_STRING, .metavar = "FILE.exr", .offset = RO(exr),
     .help = "linear float RGB OpenEXR"},
    {.name = "--png", .kind = CLI_STRING, .metavar = "FILE.png", .offset = RO(png),
     .help = "sRGB 8-bit preview"},
    {.name = "--exposure", .kind = CLI_REAL, .metavar = "E", .offset = RO(exposure), .rlo = 0.0, .rhi = 1e30,
     .help = "scale of the PNG preview"},
    {.name = "--stats", .kind = CLI_STRING, .metavar = "FILE.json", .offset = RO(stats),
     .help = "run statistics as JSON"},
    {.name = "--dump-reps", .kind = CLI_STRING, .metavar = "FILE.csv", .offset = RC(dump_reps),
     .help = "precomputed: the representatives as CSV (x,y,z, normal nx,ny,nz, precomputed irradiance e_r,e_g,e_b "
             "in W per scene unit^2), written after the render, outside its times"},
    {.name = "--allow-nonfinite", .kind = CLI_FLAG, .offset = RC(allow_nonfinite), .flag_value = 1,
     .help = "keep an image whose radiance leaves the float range (Inf, or below the smallest normal float; "
             "otherwise exit 2, no image)"},
    {.name = "--quiet", .kind = CLI_FLAG, .offset = RO(quiet), .flag_value = 1,
     .help = "no progress bar and no summary line"},
    {.name = "--repeats", .kind = CLI_STRING, .metavar = "R|auto", .offset = RO(repeats),
     .help = "run the timed pipeline R times (same seed, the same image): the stats give each phase's minimum, "
             "median and every repeat's time, the first as the cold time; auto: " CONFIG_REPEATS_AUTO_TEXT,
     .default_text = CONFIG_DEFAULT_REPEATS_TEXT},
    {.name = "--no-output", .kind = CLI_FLAG, .offset = RO(no_output), .flag_value = 1,
     .help = "write no file, only the summary line's times (benchmarks); without it a render needs -o, --png, "
             "--stats or --dump-reps"},
};
#undef RO
#undef RC

static const cli_command render_command = {
    .name = "render",
    .summary = "renders SCENE by photon mapping (see README.md)",
    .positional = "SCENE",
    .positional_what = "scene file",
    .positional_offset = offsetof(render_args, scene),
    .options = render_options,
    .noptions = sizeof render_options / sizeof render_options[0]};

static render_args render_defaults(void)
{
    render_args a;
    memset(&a, 0, sizeof a);
    a.cfg = config_defaults();
    a.exposure = 1.0;
    return a;
}

static uint64_t physical_memory(void)
{
    long pages = sysconf(_SC_PHYS_PAGES), size = sysconf(_SC_PAGESIZE);
    return pages > 0 && size > 0 ? (uint64_t)pages * (uint64_t)size : 0;
}

/* 1 when path ends in ext (".exr"), ignoring case, else 0. */
static int has_extension(const char *path, const char *ext)
{
    size_t n = strlen(path), e = strlen(ext);
    if (n <= e)
        return 0;
    for (size_t i = 0; i < e; i++)
        if (tolower((unsigned char)path[n - e + i]) != ext[i])
            return 0;
    return 1;
}

/* Refuses an output whose name's extension is not its format's, and a
 * render that writes nothing unless --no-output says so (and --no-output
 * with an output). Returns PM_OK, or PM_ERR_INPUT after printing why. */
static pm_status check_outputs(const render_args *a, const char *const *paths, const char *const *names,
                               const char *const *exts, const char *const *formats, int n)
{
    int any = 0;
    for (int i = 0; i < n; i++) {
        if (!paths[i])
            continue;
        any = 1;
        if (!has_extension(paths[i], exts[i]))
            return cli_error(&render_command, "%s: '%s' does not end in %s: %s writes %s", names[i], paths[i], exts[i],
                             names[i], formats[i]);
    }
    if (any && a->no_output)
        return cli_error(&render_command, "--no-output contradicts the output options given");
    if (!any && !a->no_output)
        return cli_error(&render_command,
                         "no output: give -o FILE.exr, --png FILE.png, --stats FILE.json or --dump-reps FILE.csv, or "
                         "--no-output for a render whose times are all that is wanted");
    return PM_OK;
}

/* Claims every output path now, so that an unwritable one fails before the
 * work, and refuses two outputs on one file. `names` are the options that
 * gave them. Returns PM_OK, PM_ERR_INPUT (two on one file) or PM_ERR_IO. */
static pm_status claim_outputs(const cli_command *cmd, const char *const *paths, const char *const *names, int n)
{
    char err[1024];
    for (int i = 0; i < n; i++)
        for (int j = i + 1; j < n; j++)
            if (paths[i] && paths[j] && outfile_same_target(paths[i], paths[j]))
                return cli_error(cmd, "%s and %s name the same file '%s'; each output needs its own", names[i],
                                 names[j], paths[j]);
    for (int i = 0; i < n; i++) {
        if (!paths[i])
            continue;
        outfile probe;
        pm_status rc = outfile_begin(&probe, paths[i], 0, err, sizeof err);
        if (rc != PM_OK) {
            fprintf(stderr, "photonmap: %s\n", err);
            return rc;
        }
        outfile_abort(&probe);
    }
    return PM_OK;
}

/* Loads a scene, printing the parser's message on failure. Returns
 * scene_load's result. */
static pm_status load_scene(const char *path, scene **sc)
{
    char err[1024];
    pm_status rc = scene_load(path, sc, err, sizeof err);
    if (rc != PM_OK)
        fprintf(stderr, "%s\n", err);
    return rc;
}

/* --dump-reps: the representatives as CSV, through a temporary file.
 * Returns PM_OK, or PM_ERR_IO after printing why. */
static pm_status write_reps(const char *path, const render_result *r)
{
    char err[1024];
    outfile f;
    pm_status rc;
    if ((rc = outfile_begin(&f, path, 1, err, sizeof err)) == PM_OK) {
        if ((rc = render_write_reps(r, f.f)) == PM_OK) {
            if ((rc = outfile_commit(&f, err, sizeof err)) == PM_OK)
                return PM_OK;
        } else {
            snprintf(err, sizeof err, "%s: %s", path, pm_status_message(rc));
            outfile_abort(&f);
        }
    }
    fprintf(stderr, "photonmap: %s\n", err);
    return rc;
}

/* Why the image of a finished render cannot be written, into why (the
 * message's text after "SCENE: "), or "" when it can: a pixel beyond the
 * largest float, or an image whose largest radiance is below the smallest
 * normal float (no pixel of it could be stored but as 0 or a subnormal).
 * Single channels that underflow next to representable ones are no reason:
 * they are stored as 0 or subnormal and counted (flushed_values). */
static void refusal_reason(const render_args *a, const stats_run *st, char *why, size_t len)
{
    why[0] = '\0';
    if (a->cfg.allow_nonfinite)
        return;
    /* radiance scales as power / size^2: a scene whose radiance leaves the
     * float range of the image is refused rather than written wrong */
    if (st->nonfinite_pixels > 0)
        snprintf(why, len,
                 "%" PRIu64 " pixels' radiance is beyond the largest float (%g): the light is too strong for the "
                 "scene's size (radiance ~ power / size^2); scale the power down. No image written "
                 "(--allow-nonfinite keeps it)",
                 st->nonfinite_pixels, (double)FLT_MAX);
    else if (st->peak_radiance > 0.0 && st->peak_radiance < FLT_MIN && a->cfg.max_radius > 0.0 &&
             st->photons_extent > 0.0 && a->cfg.max_radius > st->photons_extent)
        /* a cap beyond the photons: an estimate with fewer than n photons in
         * range spreads them over the cap's disc, whatever the light */
        snprintf(why, len,
                 "the image's largest radiance, %.3g, is below the smallest normal float (%g): --max-radius %g is "
                 "%.3g times the photons' extent (%.3g), and an estimate with fewer than n = %u photons within it "
                 "spreads them over a disc of that radius (radiance ~ 1 / R^2); lower --max-radius or raise "
                 "--photons. No image written (--allow-nonfinite keeps it)",
                 st->peak_radiance, (double)FLT_MIN, a->cfg.max_radius, a->cfg.max_radius / st->photons_extent,
                 st->photons_extent, a->cfg.nn);
    else if (st->peak_radiance > 0.0 && st->peak_radiance < FLT_MIN)
        snprintf(why, len,
                 "the image's largest radiance, %.3g, is below the smallest normal float (%g): the light is too "
                 "weak for the scene's size (radiance ~ power / size^2); scale the power up. No image written "
                 "(--allow-nonfinite keeps it)",
                 st->peak_radiance, (double)FLT_MIN);
}

/* Writes what a finished render produced: the stats (with the refusal,
 * if any), then the image unless it is refused. Returns PM_OK;
 * PM_ERR_INPUT when the image's radiance leaves the float range (no image
 * written, after printing why); PM_ERR_IO when a file could not be written
 * (after printing why). */
static pm_status write_outputs(const render_args *a, unsigned threads, const render_result *r)
{
    char err[1024], why[1024];
    pm_status exit_code = PM_OK;
    const image *img = &r->img;
    const stats_run *st = &r->st;
    refusal_reason(a, st, why, sizeof why);
    if (a->stats) {
        outfile f;
        pm_status rc = outfile_begin(&f, a->stats, 1, err, sizeof err);
        if (rc == PM_OK &&
            (rc = stats_write_json(f.f, a->scene, &a->cfg, threads, st, why[0] ? why : NULL)) != PM_OK) {
            snprintf(err, sizeof err, "%s: %s", a->stats, pm_status_message(rc));
            outfile_abort(&f);
        } else if (rc == PM_OK) {
            rc = outfile_commit(&f, err, sizeof err);
        }
        if (rc != PM_OK) {
            fprintf(stderr, "photonmap: %s\n", err);
            exit_code = rc;
        }
    }
    if (why[0]) {
        fprintf(stderr, "%s: %s\n", a->scene, why);
        return PM_ERR_INPUT;
    }
    pm_status rc;
    if (a->exr && (rc = image_write_exr(img, a->exr, err, sizeof err)) != PM_OK) {
        fprintf(stderr, "photonmap: %s\n", err);
        exit_code = rc;
    }
    if (a->png && (rc = image_write_png(img, a->png, a->exposure, err, sizeof err)) != PM_OK) {
        fprintf(stderr, "photonmap: %s\n", err);
        exit_code = rc;
    }
    return exit_code;
}

/* Warns on stderr about a closed shape (an opaque sphere) around the
 * camera or the light but not both: no light path joins them, and the
 * image is black (a furnace, camera and light in one sphere, is fine). */
static void warn_camera(const char *path, const scene *sc)
{
    vec3 c = sc->camera.position;
    int i = scene_sphere_between(sc, c, sc->light.position);
    if (i == SCENE_NO_SHAPE)
        return;
    const shape *s = &sc->shapes[i];
    int cam_in = vec_len2(vec_sub(c, s->center)) < s->radius * s->radius;
    fprintf(stderr,
            "%s: warning: the %s (%g %g %g) is inside the opaque sphere of centre (%g %g %g) and radius %g (shape "
            "%d of the scene) and the %s is not: no light reaches the camera through it\n",
            path, cam_in ? "camera" : "light", cam_in ? c.x : sc->light.position.x,
            cam_in ? c.y : sc->light.position.y, cam_in ? c.z : sc->light.position.z, s->center.x, s->center.y,
            s->center.z, s->radius, i + 1, cam_in ? "light" : "camera");
}

/* Warns on stderr about what a finished render measured that is likely
 * not what was meant: photons lost through an open scene, eye paths cut at
 * the depth limit (config.h has the thresholds). */
static void warn_run(const char *path, const config_render *cfg, const stats_run *st)
{
    if (st->photons_emitted > 0 &&
        (double)st->photons_escaped > CONFIG_WARN_ESCAPED_SHARE * (double)st->photons_emitted)
        fprintf(stderr,
                "%s: warning: %.1f%% of the emitted photons (%" PRIu64 " of %" PRIu64 ") left the scene without "
                "hitting anything: is it open, or the light outside it? (above %g%%; the project's scenes are closed "
                "and lose none)\n",
                path, 100.0 * (double)st->photons_escaped / (double)st->photons_emitted, st->photons_escaped,
                st->photons_emitted, 100.0 * CONFIG_WARN_ESCAPED_SHARE);
    if (st->samples > 0 && (double)st->eye_depth_limit_hits > CONFIG_WARN_DEPTH_LIMIT_SHARE * (double)st->samples)
        fprintf(stderr,
                "%s: warning: %" PRIu64 " eye paths were cut at the eye-depth limit (--eye-depth %u), %.1f%% of the "
                "%" PRIu64 " samples (above %g%%): those paths are black; a camera between mirrors, or a depth too "
                "low?\n",
                path, st->eye_depth_limit_hits, cfg->eye_depth,
                100.0 * (double)st->eye_depth_limit_hits / (double)st->samples, st->samples,
                100.0 * CONFIG_WARN_DEPTH_LIMIT_SHARE);
}

/* `photonmap render`. Returns the first failure's status (printed). */
static pm_status cmd_render(int argc, char **argv)
{
    render_args a = render_defaults();
    pm_status rc = cli_parse(&render_command, argc, argv, 2, &a);
    if (rc != PM_OK)
        return rc;
    const config_render *cfg = &a.cfg;
    const char *paths[4] = {a.exr, a.png, a.stats, cfg->dump_reps};
    const char *names[4] = {"-o", "--png", "--stats", "--dump-reps"};
    const char *exts[4] = {".exr", ".png", ".json", ".csv"};
    const char *formats[4] = {"OpenEXR", "PNG", "JSON", "CSV"};
    char err[1024];
    if (a.repeats && repeat_parse(a.repeats, &a.cfg.repeats, err, sizeof err))
        return cli_error(&render_command, "%s", err);
    const char *why = config_check(cfg);
    if (why)
        return cli_error(&render_command, "%s", why);
    if ((uint64_t)cfg->width * cfg->height > CONFIG_MAX_PIXELS)
        return cli_error(&render_command, "an image of %ux%u pixels is too large (at most %llu pixels)", cfg->width,
                         cfg->height, (unsigned long long)CONFIG_MAX_PIXELS);
    scene *sc = NULL;
    if ((rc = load_scene(a.scene, &sc)) != PM_OK)
        return rc;
    if ((rc = check_outputs(&a, paths, names, exts, formats, 4)) != PM_OK) {
        scene_free(sc);
        return rc;
    }
    warn_camera(a.scene, sc);
    if ((rc = render_prepare(sc, cfg, err, sizeof err)) != PM_OK) {
        fprintf(stderr, "photonmap: %s: %s\n", a.scene, err);
        scene_free(sc);
        return rc;
    }
    if ((rc = render_check_memory(sc, cfg, physical_memory(), err, sizeof err)) != PM_OK) {
        fprintf(stderr, "photonmap: %s\n", err);
        scene_free(sc);
        return rc;
    }
    if ((rc = claim_outputs(&render_command, paths, names, 4)) != PM_OK) {
        scene_free(sc);
        return rc;
    }
    unsigned threads = cfg->threads ? cfg->threads : parallel_cores();
    int show = !a.quiet && isatty(STDERR_FILENO);
    provenance_info prov;
    provenance_collect(&prov); /* the load average before the render */
    render_result res;
    if ((rc = repeat_render(sc, cfg, threads, show, &res, err, sizeof err)) != PM_OK) {
        if (rc == PM_ERR_INPUT)
            fprintf(stderr, "%s: %s\n", a.scene, err);
        else
            fprintf(stderr, "photonmap: %s\n", err);
        scene_free(sc);
        return rc;
    }
    res.st.provenance = prov;
    warn_run(a.scene, cfg, &res.st);
    /* the representatives first: when they cannot be written, nothing else is */
    if (cfg->dump_reps && (rc = write_reps(cfg->dump_reps, &res)) != PM_OK) {
        render_result_free(&res);
        scene_free(sc);
        return rc;
    }
    rc = write_outputs(&a, threads, &res);
    const stats_run *st = &res.st;
    if (!a.quiet)
        fprintf(stderr,
                "%s: %s, %" PRIu64 " photons emitted, %" PRIu64 " stored, n=%u, %ux%u, %u threads: "
                "trace %.2fs build %.2fs precompute %.2fs render %.2fs total %.2fs\n",
                a.scene, config_method_name(cfg->method), st->photons_emitted, st->photons_stored, cfg->nn,
                cfg->width, cfg->height, threads, st->trace, st->build, st->precompute, st->render, st->total);
    render_result_free(&res);
    scene_free(sc);
    return rc;
}

/* ---- export-pov ---- */

typedef struct {
    povray_options pov;
    const char *scene, *out;
} pov_args;

static const char *const quality_names[] = {"fast", "reference", NULL};
_Static_assert(sizeof(povray_quality) == sizeof(int), "povray_quality is int-sized");

#define PO(field) offsetof(pov_args, field)
static const cli_option pov_options_table[] = {
    {.name = "--width", .kind = CLI_U32, .metavar = "W", .offset = PO(pov.width), .ulo = 1, .uhi = CONFIG_MAX_SIDE,
     .help = "the image width POV-Ray will render (sets the aspect ratio)"},
    {.name = "--height", .kind = CLI_U32, .metavar = "H", .offset = PO(pov.height), .ulo = 1, .uhi = CONFIG_MAX_SIDE,
     .help = "the image height POV-Ray will render"},
    {.name = "--quality", .kind = CLI_CHOICE, .offset = PO(pov.quality), .choices = quality_names,
     .help = "radiosity and photon settings (reference/README.md)"},
    {.name = "--no-radiosity", .kind = CLI_FLAG, .offset = PO(pov.radiosity),
     .help = "no indirect diffuse light (radiosity on unless given)"},
    {.name = "--no-photons", .kind = CLI_FLAG, .offset = PO(pov.photons),
     .help = "no caustics; glass still shadows direct light (photons on unless given)"},
    {.name = "--no-glass-caustics", .kind = CLI_FLAG, .offset = PO(pov.glass_caustics),
     .help = "glass casts no caustic (it is no photon target; a shadow-only proxy still blocks direct light), "
             "mirror caustics and radiosity stay: the caustic-missing negative control of the POV-Ray checks"},
    {.name = "--rect-thickness", .kind = CLI_REAL, .metavar = "F", .offset = PO(pov.rect_thickness),
     .rlo = POVRAY_RECT_THICKNESS_MIN, .rhi = POVRAY_RECT_THICKNESS_MAX,
     .help = "a rectangle becomes a box this fraction of the scene's diagonal thick, behind its lit face; thin "
             "geometry needs less"},
    {.name = "--bounces", .kind = CLI_U32, .metavar = "B", .offset = PO(pov.bounces), .ulo = 1,
     .uhi = POVRAY_BOUNCES_MAX,
     .help = "indirect diffuse bounces of the radiosity (its recursion_limit); the same light paths as "
             "render --photon-depth B+1"},
    {.name = "-o", .kind = CLI_STRING, .metavar = "FILE.pov", .offset = PO(out),
     .help = "where to write the SDL",
     .default_text = "standard output"},
};
#undef PO

static const cli_command pov_command = {
    .name = "export-pov",
    .summary = "writes SCENE as POV-Ray 3.7 SDL radiometrically matched to the renderer",
    .positional = "SCENE",
    .positional_what = "scene file",
    .positional_offset = offsetof(pov_args, scene),
    .options = pov_options_table,
    .noptions = sizeof pov_options_table / sizeof pov_options_table[0]};

static pov_args pov_defaults_args(void)
{
    pov_args a;
    memset(&a, 0, sizeof a);
    a.pov = povray_defaults();
    return a;
}

/* An exporter's writer: the scene to f in its format. */
typedef pm_status (*export_writer)(FILE *f, const scene *sc, const char *scene_name, const void *opts);

static pm_status pov_writer(FILE *f, const scene *sc, const char *scene_name, const void *opts)
{
    return povray_write(f, sc, scene_name, opts);
}

static pm_status pbrt_writer(FILE *f, const scene *sc, const char *scene_name, const void *opts)
{
    return pbrt_write(f, sc, scene_name, opts);
}

/* Writes the export to out (NULL: standard output) by a temporary name
 * renamed when complete. Returns PM_OK, or PM_ERR_IO (printed) when the file
 * cannot be created, written or renamed (it then leaves no file). */
static pm_status export_write(const char *out, export_writer write, const scene *sc,
                              const char *scene_name, const void *opts)
{
    if (!out) {
        if (write(stdout, sc, scene_name, opts) || fflush(stdout)) {
            fprintf(stderr, "photonmap: writing standard output: %s\n", strerror(errno));
            return PM_ERR_IO;
        }
        return PM_OK;
    }
    char err[1024];
    outfile f;
    pm_status rc;
    if ((rc = outfile_begin(&f, out, 1, err, sizeof err)) != PM_OK) {
        fprintf(stderr, "photonmap: %s\n", err);
        return rc;
    }
    if ((rc = write(f.f, sc, scene_name, opts)) != PM_OK) {
        fprintf(stderr, "photonmap: %s: %s\n", out, pm_status_message(rc));
        outfile_abort(&f);
        return rc;
    }
    if ((rc = outfile_commit(&f, err, sizeof err)) != PM_OK) {
        fprintf(stderr, "photonmap: %s\n", err);
        return rc;
    }
    return PM_OK;
}

/* `photonmap export-pov`. Returns the first failure's status (printed). */
static pm_status cmd_export_pov(int argc, char **argv)
{
    pov_args a = pov_defaults_args();
    pm_status rc = cli_parse(&pov_command, argc, argv, 2, &a);
    if (rc != PM_OK)
        return rc;
    scene *sc = NULL;
    if ((rc = load_scene(a.scene, &sc)) != PM_OK)
        return rc;
    pm_status exit_code = export_write(a.out, pov_writer, sc, a.scene, &a.pov);
    scene_free(sc);
    return exit_code;
}

/* ---- export-pbrt ---- */

typedef struct {
    pbrt_options pbrt;
    const char *scene, *out;
} pbrt_args;

static const char *const pbrt_integrator_names[] = {"bdpt", "path", "directlighting", NULL};
_Static_assert(sizeof(pbrt_integrator) == sizeof(int), "pbrt_integrator is int-sized");

#define PB(field) offsetof(pbrt_args, field)
static const cli_option pbrt_options_table[] = {
    {.name = "--width", .kind = CLI_U32, .metavar = "W", .offset = PB(pbrt.width), .ulo = 1, .uhi = CONFIG_MAX_SIDE,
     .help = "the film width"},
    {.name = "--height", .kind = CLI_U32, .metavar = "H", .offset = PB(pbrt.height), .ulo = 1, .uhi = CONFIG_MAX_SIDE,
     .help = "the film height"},
    {.name = "--integrator", .kind = CLI_CHOICE, .offset = PB(pbrt.integrator), .choices = pbrt_integrator_names,
     .help = "pbrt's integrator: bidirectional, path tracing, or direct light only (reference/pbrt/README.md)"},
    {.name = "--bounces", .kind = CLI_U32, .metavar = "B", .offset = PB(pbrt.bounces), .ulo = 1,
     .uhi = PBRT_BOUNCES_MAX,
     .help = "indirect bounces: pbrt's maxdepth B+1, the same light paths as render --photon-depth B+1"},
    {.name = "--min-bounces", .kind = CLI_U32, .metavar = "M", .offset = PB(pbrt.min_bounces), .ulo = 0,
     .uhi = PBRT_BOUNCES_MAX,
     .help = "path only: keep paths of more than M indirect bounces (mindepth M+1, a local change to pbrt; "
             "0: all)"},
    {.name = "--spp", .kind = CLI_U32, .metavar = "N", .offset = PB(pbrt.spp), .ulo = 1, .uhi = PBRT_SPP_MAX,
     .help = "samples per pixel (a stratified square grid: rounded up to a square)"},
    {.name = "--fixed-subpixels", .kind = CLI_FLAG, .offset = PB(pbrt.fixed_subpixels), .flag_value = 1,
     .help = "samples at fixed grid points, not jittered: the renderer's --subpixels sqrt(N) rays"},
    {.name = "-o", .kind = CLI_STRING, .metavar = "FILE.pbrt", .offset = PB(out),
     .help = "where to write the scene",
     .default_text = "standard output"},
};
#undef PB

static const cli_command pbrt_command = {
    .name = "export-pbrt",
    .summary = "writes SCENE as a pbrt-v3 scene radiometrically matched to the renderer",
    .positional = "SCENE",
    .positional_what = "scene file",
    .positional_offset = offsetof(pbrt_args, scene),
    .options = pbrt_options_table,
    .noptions = sizeof pbrt_options_table / sizeof pbrt_options_table[0]};

static pbrt_args pbrt_defaults_args(void)
{
    pbrt_args a;
    memset(&a, 0, sizeof a);
    a.pbrt = pbrt_defaults();
    return a;
}

/* `photonmap export-pbrt`. Returns the first failure's status (printed):
 * PM_ERR_INPUT for a scene pbrt cannot render alike (pbrt_check's cause). */
static pm_status cmd_export_pbrt(int argc, char **argv)
{
    pbrt_args a = pbrt_defaults_args();
    pm_status rc = cli_parse(&pbrt_command, argc, argv, 2, &a);
    if (rc != PM_OK)
        return rc;
    scene *sc = NULL;
    if ((rc = load_scene(a.scene, &sc)) != PM_OK)
        return rc;
    char err[1024];
    pm_status exit_code = pbrt_check(sc, &a.pbrt, err, sizeof err);
    if (exit_code != PM_OK) {
        fprintf(stderr, "photonmap: export-pbrt: %s: %s\n", a.scene, err);
    } else {
        exit_code = export_write(a.out, pbrt_writer, sc, a.scene, &a.pbrt);
    }
    scene_free(sc);
    return exit_code;
}

/* ---- the program ---- */

static void print_usage(FILE *f)
{
    render_args r = render_defaults();
    pov_args p = pov_defaults_args();
    cli_usage(f, &render_command, &r);
    fputc('\n', f);
    cli_usage(f, &pov_command, &p);
    pbrt_args b = pbrt_defaults_args();
    fputc('\n', f);
    cli_usage(f, &pbrt_command, &b);
}

int main(int argc, char **argv)
{
    if (argc < 2 || !strcmp(argv[1], "--help") || !strcmp(argv[1], "-h") || !strcmp(argv[1], "help")) {
        print_usage(argc < 2 ? stderr : stdout);
        return pm_status_exit(argc < 2 ? PM_ERR_INPUT : PM_DONE);
    }
    if (!strcmp(argv[1], "render"))
        return pm_status_exit(cmd_render(argc, argv));
    if (!strcmp(argv[1], "export-pov"))
        return pm_status_exit(cmd_export_pov(argc, argv));
    if (!strcmp(argv[1], "export-pbrt"))
        return pm_status_exit(cmd_export_pbrt(argc, argv));
    fprintf(stderr, "photonmap: unknown command '%s' (expected render, export-pov or export-pbrt; see photonmap --help)\n", argv[1]);
    return pm_status_exit(PM_ERR_INPUT);
}

/* main: the command line. `photonmap render SCENE [options]` renders,
 * `export-pov` writes POV-Ray SDL, `export-pbrt` a pbrt-v3 scene, `info`
 * the scene's facts as JSON; each
 * subcommand's option table lives in cli. main chains the steps, writes
 * every output file and exits with pm_status_exit of the first failure:
 * 0 success, 1 runtime failure (I/O, memory), 2 user input error. */
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
#include "info.h"
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
static pm_status check_outputs(const cli_render_args *a, const char *const *paths, const char *const *names,
                               const char *const *exts, const char *const *formats, int n)
{
    int any = 0;
    for (int i = 0; i < n; i++) {
        if (!paths[i])
            continue;
        any = 1;
        if (!has_extension(paths[i], exts[i]))
            return cli_error(&cli_render, "%s: '%s' does not end in %s: %s writes %s", names[i], paths[i], exts[i],
                             names[i], formats[i]);
    }
    if (any && a->no_output)
        return cli_error(&cli_render, "--no-output contradicts the output options given");
    if (!any && !a->no_output)
        return cli_error(&cli_render,
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
static void refusal_reason(const cli_render_args *a, const stats_run *st, char *why, size_t len)
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
static pm_status write_outputs(const cli_render_args *a, unsigned threads, const render_result *r)
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
    cli_render_args a = cli_render_defaults();
    pm_status rc = cli_parse(&cli_render, argc, argv, 2, &a, &a.given);
    if (rc != PM_OK)
        return rc;
    char err[1024];
    if (a.repeats && repeat_parse(a.repeats, &a.cfg.repeats, err, sizeof err) != PM_OK)
        return cli_error(&cli_render, "%s", err);
    cli_render_resolve(&a);
    const config_render *cfg = &a.cfg;
    const char *paths[4] = {a.exr, a.png, a.stats, cfg->dump_reps};
    const char *names[4] = {"-o", "--png", "--stats", "--dump-reps"};
    const char *exts[4] = {".exr", ".png", ".json", ".csv"};
    const char *formats[4] = {"OpenEXR", "PNG", "JSON", "CSV"};
    if ((rc = cli_render_check(&a)) != PM_OK)
        return rc;
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
    if ((rc = claim_outputs(&cli_render, paths, names, 4)) != PM_OK) {
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
    cli_pov_args a = cli_pov_defaults();
    pm_status rc = cli_parse(&cli_export_pov, argc, argv, 2, &a, NULL);
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

/* `photonmap export-pbrt`. Returns the first failure's status (printed):
 * PM_ERR_INPUT for a scene pbrt cannot render alike (pbrt_check's cause). */
static pm_status cmd_export_pbrt(int argc, char **argv)
{
    cli_pbrt_args a = cli_pbrt_defaults();
    pm_status rc = cli_parse(&cli_export_pbrt, argc, argv, 2, &a, NULL);
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

/* ---- info ---- */

/* `photonmap info`. Returns the first failure's status (printed): a scene
 * the parser refuses is PM_ERR_INPUT with render's file:line:col message. */
static pm_status cmd_info(int argc, char **argv)
{
    cli_info_args a = cli_info_defaults();
    pm_status rc = cli_parse(&cli_info, argc, argv, 2, &a, NULL);
    if (rc != PM_OK)
        return rc;
    if (!a.json)
        return cli_error(&cli_info, "info writes JSON only: give --json");
    scene *sc = NULL;
    if ((rc = load_scene(a.scene, &sc)) != PM_OK)
        return rc;
    rc = info_write_json(stdout, sc, a.scene, a.width, a.height);
    if (rc == PM_OK && fflush(stdout))
        rc = PM_ERR_IO;
    if (rc != PM_OK)
        fprintf(stderr, "photonmap: writing standard output: %s\n", strerror(errno));
    scene_free(sc);
    return rc;
}

/* ---- the program ---- */

static void print_usage(FILE *f)
{
    cli_render_args r = cli_render_defaults();
    cli_pov_args p = cli_pov_defaults();
    cli_usage(f, &cli_render, &r);
    fputc('\n', f);
    cli_usage(f, &cli_export_pov, &p);
    cli_pbrt_args b = cli_pbrt_defaults();
    fputc('\n', f);
    cli_usage(f, &cli_export_pbrt, &b);
    cli_info_args i = cli_info_defaults();
    fputc('\n', f);
    cli_usage(f, &cli_info, &i);
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
    if (!strcmp(argv[1], "info"))
        return pm_status_exit(cmd_info(argc, argv));
    fprintf(stderr, "photonmap: unknown command '%s' (expected render, export-pov, export-pbrt or info; see photonmap --help)\n", argv[1]);
    return pm_status_exit(PM_ERR_INPUT);
}

/* main: the command line. `photonmap render SCENE [options]` renders;
 * `photonmap export-pov SCENE [options]` writes POV-Ray SDL. Exit codes:
 * 0 success, 1 runtime failure (I/O, memory, non-finite image), 2 user
 * input error (bad option or scene file, with file:line:col). */
#include <assert.h>
#include <errno.h>
#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "config.h"
#include "image.h"
#include "outfile.h"
#include "parallel.h"
#include "photons.h"
#include "povray.h"
#include "render.h"
#include "scene.h"
#include "stats.h"

#define EXIT_RUNTIME 1
#define EXIT_USAGE 2

/* Prints the usage, with the defaults of config.h, to f. */
static void print_usage(FILE *f)
{
    render_config d = config_defaults();
    fprintf(f,
            "usage: photonmap render SCENE [options]\n"
            "       photonmap export-pov SCENE [--width W] [--height H] [--quality fast|reference] [-o out.pov]\n"
            "\n"
            "render options (defaults in renderer/config.h):\n"
            "  --method conventional|precomputed  radiance estimate: paper's eq. 1 or eq. 2 (%s)\n"
            "  --photons N       photons emitted from the light, P_e (%llu); 0: no photon map, a black\n"
            "                    image (direct light only with --direct shadow-rays)\n"
            "  --nn N            nearest photons per estimate / per precompute, n (%u)\n"
            "  --width W --height H   image size (%ux%u)\n"
            "  --subpixels S     SxS subpixel samples per pixel, box filtered (%u)\n"
            "  --threads T       worker threads, 0 = all cores (%u)\n"
            "  --seed S          random seed (%llu)\n"
            "  --rep-every K     precomputed: every K-th stored photon is a representative (%u)\n"
            "  --normal-cos C    precomputed: representative normal must agree above this cosine (%g)\n"
            "  --rep-tree separate|shared   precomputed: representatives' own kd-tree, or the photon tree by flag\n"
            "  --max-radius R    search radius cap in scene units (default %g x scene diagonal)\n"
            "  --direct photons|shadow-rays  direct light from the photon map (paper) or by shadow rays (%s)\n"
            "  --photon-depth D  max photon bounces (%u);  --eye-depth D  max specular eye bounces (%u)\n"
            "  -o FILE.exr       linear float RGB OpenEXR\n"
            "  --png FILE.png    sRGB 8-bit preview;  --exposure E  preview scale (1)\n"
            "  --stats FILE.json run statistics\n"
            "  --allow-nonfinite keep an image with NaN/Inf pixels (otherwise exit 1)\n"
            "  --quiet           no progress bar\n",
            config_method_name(d.method), (unsigned long long)d.photons, d.nn, d.width, d.height, d.subpixels,
            d.threads, (unsigned long long)d.seed, d.rep_every, d.normal_cos, d.max_radius_frac,
            config_direct_name(d.direct), d.photon_depth, d.eye_depth);
}

static int usage_error(const char *fmt, const char *a, const char *b)
{
    fprintf(stderr, "photonmap: ");
    fprintf(stderr, fmt, a, b);
    fprintf(stderr, "\n(run 'photonmap --help' for usage)\n");
    return EXIT_USAGE;
}

/* Parses a decimal integer in [lo, hi]. Returns 0 or an exit code. */
static int parse_uint(const char *opt, const char *s, uint64_t lo, uint64_t hi, uint64_t *out)
{
    char range[96];
    snprintf(range, sizeof range, "an integer in [%" PRIu64 ", %" PRIu64 "]", lo, hi);
    const char *p = s;
    if (*p == '+')
        p++;
    if (*p < '0' || *p > '9') {
        fprintf(stderr, "photonmap: %s: expected %s, got '%s'\n", opt, range, s);
        return EXIT_USAGE;
    }
    errno = 0;
    char *end;
    unsigned long long v = strtoull(p, &end, 10);
    if (*end != '\0' || errno == ERANGE || v < lo || v > hi) {
        fprintf(stderr, "photonmap: %s: expected %s, got '%s'\n", opt, range, s);
        return EXIT_USAGE;
    }
    *out = v;
    return 0;
}

static int parse_real(const char *opt, const char *s, double lo, double hi, double *out)
{
    errno = 0;
    char *end;
    double v = strtod(s, &end);
    if (end == s || *end != '\0' || !isfinite(v) || v < lo || v > hi) {
        fprintf(stderr, "photonmap: %s: expected a number in [%g, %g], got '%s'\n", opt, lo, hi, s);
        return EXIT_USAGE;
    }
    *out = v;
    return 0;
}

typedef struct {
    const char *scene;
    const char *exr, *png, *stats;
    double exposure;
    int quiet;
} render_outputs;

static int parse_render_args(int argc, char **argv, render_config *cfg, render_outputs *o)
{
    uint64_t u;
    int rc;
    for (int i = 2; i < argc; i++) {
        const char *a = argv[i];
        if (a[0] != '-' || !strcmp(a, "-")) {
            if (o->scene)
                return usage_error("unexpected argument '%s' (scene already given: '%s')", a, o->scene);
            o->scene = a;
            continue;
        }
        if (!strcmp(a, "--quiet")) {
            o->quiet = 1;
            continue;
        }
        if (!strcmp(a, "--allow-nonfinite")) {
            cfg->allow_nonfinite = 1;
            continue;
        }
        static const char *const valued[] = {"--photons", "--nn", "--width", "--height", "--subpixels",
                                             "--threads", "--seed", "--rep-every", "--photon-depth", "--eye-depth",
                                             "--normal-cos", "--max-radius", "--exposure", "--method", "--direct",
                                             "--rep-tree", "-o", "--png", "--stats"};
        int known = 0;
        for (size_t k = 0; k < sizeof valued / sizeof valued[0]; k++)
            known |= !strcmp(a, valued[k]);
        if (!known)
            return usage_error("unknown option '%s'%s", a, "");
        if (i + 1 >= argc)
            return usage_error("%s needs a value%s", a, "");
        const char *v = argv[++i];
        if (!strcmp(a, "--photons")) {
            if ((rc = parse_uint(a, v, 0, CONFIG_MAX_PHOTONS, &u)))
                return rc;
            cfg->photons = u;
        } else if (!strcmp(a, "--nn")) {
            if ((rc = parse_uint(a, v, 1, CONFIG_MAX_NN, &u)))
                return rc;
            cfg->nn = (uint32_t)u;
        } else if (!strcmp(a, "--width")) {
            if ((rc = parse_uint(a, v, 1, CONFIG_MAX_SIDE, &u)))
                return rc;
            cfg->width = (uint32_t)u;
        } else if (!strcmp(a, "--height")) {
            if ((rc = parse_uint(a, v, 1, CONFIG_MAX_SIDE, &u)))
                return rc;
            cfg->height = (uint32_t)u;
        } else if (!strcmp(a, "--subpixels")) {
            if ((rc = parse_uint(a, v, 1, CONFIG_MAX_SUBPIXELS, &u)))
                return rc;
            cfg->subpixels = (uint32_t)u;
        } else if (!strcmp(a, "--threads")) {
            if ((rc = parse_uint(a, v, 0, CONFIG_MAX_THREADS, &u)))
                return rc;
            cfg->threads = (uint32_t)u;
        } else if (!strcmp(a, "--seed")) {
            if ((rc = parse_uint(a, v, 0, UINT64_MAX, &u)))
                return rc;
            cfg->seed = u;
        } else if (!strcmp(a, "--rep-every")) {
            if ((rc = parse_uint(a, v, 1, UINT32_MAX, &u)))
                return rc;
            cfg->rep_every = (uint32_t)u;
        } else if (!strcmp(a, "--photon-depth")) {
            if ((rc = parse_uint(a, v, 1, CONFIG_MAX_DEPTH, &u)))
                return rc;
            cfg->photon_depth = (uint32_t)u;
        } else if (!strcmp(a, "--eye-depth")) {
            if ((rc = parse_uint(a, v, 0, CONFIG_MAX_DEPTH, &u)))
                return rc;
            cfg->eye_depth = (uint32_t)u;
        } else if (!strcmp(a, "--normal-cos")) {
            if ((rc = parse_real(a, v, -1.0, 1.0, &cfg->normal_cos)))
                return rc;
        } else if (!strcmp(a, "--max-radius")) {
            if ((rc = parse_real(a, v, 1e-30, 1e30, &cfg->max_radius)))
                return rc;
        } else if (!strcmp(a, "--exposure")) {
            if ((rc = parse_real(a, v, 0.0, 1e30, &o->exposure)))
                return rc;
        } else if (!strcmp(a, "--method")) {
            if (!strcmp(v, "conventional"))
                cfg->method = METHOD_CONVENTIONAL;
            else if (!strcmp(v, "precomputed"))
                cfg->method = METHOD_PRECOMPUTED;
            else
                return usage_error("--method: expected conventional or precomputed, got '%s'%s", v, "");
        } else if (!strcmp(a, "--direct")) {
            if (!strcmp(v, "photons"))
                cfg->direct = DIRECT_PHOTONS;
            else if (!strcmp(v, "shadow-rays"))
                cfg->direct = DIRECT_SHADOW_RAYS;
            else
                return usage_error("--direct: expected photons or shadow-rays, got '%s'%s", v, "");
        } else if (!strcmp(a, "--rep-tree")) {
            if (!strcmp(v, "separate"))
                cfg->reps_shared = 0;
            else if (!strcmp(v, "shared"))
                cfg->reps_shared = 1;
            else
                return usage_error("--rep-tree: expected separate or shared, got '%s'%s", v, "");
        } else if (!strcmp(a, "-o")) {
            o->exr = v;
        } else if (!strcmp(a, "--png")) {
            o->png = v;
        } else if (!strcmp(a, "--stats")) {
            o->stats = v;
        } else {
            assert(!"valued[] names an option this chain does not handle");
            return usage_error("unknown option '%s'%s", a, "");
        }
    }
    if (!o->scene)
        return usage_error("render needs a scene file%s%s", "", "");
    if ((uint64_t)cfg->width * cfg->height > 64ull * 1024 * 1024)
        return usage_error("image of %s pixels is too large (at most 64 Mpixel)%s", "that many", "");
    return 0;
}

static uint64_t physical_memory(void)
{
    long pages = sysconf(_SC_PHYS_PAGES), size = sysconf(_SC_PAGESIZE);
    return pages > 0 && size > 0 ? (uint64_t)pages * (uint64_t)size : 0;
}

/* Refuses up front a photon count whose map would not fit in memory: a pilot
 * of a few thousand photons measures stores per emitted photon. */
static int check_memory(const scene *sc, const render_config *cfg)
{
    render_config pilot = *cfg;
    pilot.photons = cfg->photons < 4096 ? cfg->photons : 4096;
    if (pilot.photons == 0)
        return 0;
    photon_list l;
    if (photons_trace(sc, &pilot, 1, NULL, &l)) {
        fprintf(stderr, "photonmap: out of memory in the pilot photon pass\n");
        return EXIT_RUNTIME;
    }
    double per_emitted = (double)l.count / (double)pilot.photons;
    photons_list_free(&l);
    /* peak: chunk buffers + joined list + map + permutation */
    double stored = per_emitted * (double)cfg->photons * 1.1 + 4096.0;
    double bytes = stored * (3.0 * (double)PHOTON_BYTES_PER_STORED + sizeof(uint32_t));
    uint64_t mem = physical_memory();
    if (stored > (double)UINT32_MAX - 1.0) {
        fprintf(stderr, "photonmap: --photons %" PRIu64 " would store about %.3g photons; the map holds at most 2^32-1\n",
                cfg->photons, stored);
        return EXIT_USAGE;
    }
    if (mem > 0 && bytes > CONFIG_MEMORY_HEADROOM * (double)mem) {
        fprintf(stderr,
                "photonmap: --photons %" PRIu64 " needs about %.1f GiB (%.2f stored per emitted photon x %zu bytes each, "
                "peak x3), more than %.0f%% of this machine's %.1f GiB; use fewer photons\n",
                cfg->photons, bytes / 1073741824.0, per_emitted, (size_t)PHOTON_BYTES_PER_STORED,
                CONFIG_MEMORY_HEADROOM * 100.0, (double)mem / 1073741824.0);
        return EXIT_USAGE;
    }
    return 0;
}

static int cmd_render(int argc, char **argv)
{
    render_config cfg = config_defaults();
    render_outputs o = {NULL, NULL, NULL, NULL, 1.0, 0};
    int rc = parse_render_args(argc, argv, &cfg, &o);
    if (rc)
        return rc;
    char err[1024];
    scene *sc = NULL;
    rc = scene_load(o.scene, &sc, err, sizeof err);
    if (rc != SCENE_OK) {
        fprintf(stderr, "%s\n", err);
        return rc == SCENE_ERR_INPUT ? EXIT_USAGE : EXIT_RUNTIME;
    }
    if ((rc = check_memory(sc, &cfg))) {
        scene_free(sc);
        return rc;
    }
    /* claim every output path now, so an unwritable one fails before the work */
    outfile probe[3];
    const char *paths[3] = {o.exr, o.png, o.stats};
    int claimed[3] = {0, 0, 0};
    for (int i = 0; i < 3; i++) {
        if (!paths[i])
            continue;
        if (outfile_begin(&probe[i], paths[i], 0, err, sizeof err)) {
            fprintf(stderr, "photonmap: %s\n", err);
            for (int j = 0; j < i; j++)
                if (claimed[j])
                    outfile_abort(&probe[j]);
            scene_free(sc);
            return EXIT_RUNTIME;
        }
        claimed[i] = 1;
    }
    for (int i = 0; i < 3; i++)
        if (claimed[i])
            outfile_abort(&probe[i]);

    unsigned threads = cfg.threads ? cfg.threads : parallel_cores();
    int show = !o.quiet && isatty(STDERR_FILENO);
    image img;
    stats_run st;
    if (render_run(sc, &cfg, threads, show, &img, &st)) {
        fprintf(stderr, "photonmap: out of memory while rendering\n");
        scene_free(sc);
        return EXIT_RUNTIME;
    }
    int exit_code = 0;
    if (o.stats) {
        outfile f;
        if (outfile_begin(&f, o.stats, 1, err, sizeof err) ||
            stats_write_json(f.f, o.scene, &cfg, threads, &st) || outfile_commit(&f, err, sizeof err)) {
            fprintf(stderr, "photonmap: %s\n", err);
            exit_code = EXIT_RUNTIME;
        }
    }
    if (st.nonfinite_pixels > 0 && !cfg.allow_nonfinite) {
        fprintf(stderr, "photonmap: %" PRIu64 " pixels are not finite; no image written (--allow-nonfinite keeps it)\n",
                st.nonfinite_pixels);
        exit_code = EXIT_RUNTIME;
    } else {
        if (o.exr && image_write_exr(&img, o.exr, err, sizeof err)) {
            fprintf(stderr, "photonmap: %s\n", err);
            exit_code = EXIT_RUNTIME;
        }
        if (o.png && image_write_png(&img, o.png, o.exposure, err, sizeof err)) {
            fprintf(stderr, "photonmap: %s\n", err);
            exit_code = EXIT_RUNTIME;
        }
    }
    if (!o.quiet)
        fprintf(stderr,
                "%s: %s, %" PRIu64 " photons emitted, %" PRIu64 " stored, n=%u, %ux%u, %u threads: "
                "trace %.2fs build %.2fs precompute %.2fs render %.2fs total %.2fs\n",
                o.scene, config_method_name(cfg.method), st.photons_emitted, st.photons_stored, cfg.nn, cfg.width,
                cfg.height, threads, st.trace, st.build, st.precompute, st.render, st.total);
    image_free(&img);
    scene_free(sc);
    return exit_code;
}

int main(int argc, char **argv)
{
    if (argc < 2 || !strcmp(argv[1], "--help") || !strcmp(argv[1], "-h") || !strcmp(argv[1], "help")) {
        print_usage(argc < 2 ? stderr : stdout);
        return argc < 2 ? EXIT_USAGE : 0;
    }
    if (!strcmp(argv[1], "render"))
        return cmd_render(argc, argv);
    if (!strcmp(argv[1], "export-pov"))
        return povray_main(argc, argv);
    fprintf(stderr, "photonmap: unknown command '%s' (expected render or export-pov)\n", argv[1]);
    return EXIT_USAGE;
}

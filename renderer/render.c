/* render: the paper's pipeline (Fig. 1: trace photons, build the photon
 * map, precompute irradiance, eye pass) in render_run, step by step. */
#include "render.h"

#include <assert.h>
#include <float.h>
#include <inttypes.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "clock.h"
#include "estimate.h"
#include "eye.h"
#include "photons.h"
#include "progress.h"
#include "reps.h"

double render_max_radius(const scene *sc, const config_render *cfg, const photons_map *m)
{
    if (cfg->max_radius > 0.0)
        return cfg->max_radius;
    return cfg->max_radius_frac * (m->extent > 0.0 ? m->extent : sc->scale);
}

/* The state of one render as it goes through the pipeline. */
typedef struct {
    const scene *sc;
    const config_render *cfg;
    unsigned threads;
    int show_progress;
    stats_run *st;
    reps_params rp;
    photons_list list;
    photons_map map;
    reps_set reps;
    photons_map caustic; /* --gather: the L S+ D photons (caustic.stored 0: none, no map) */
    double max_radius; /* the radius cap, scene units */
} render_state;

/* The photon pass of cfg: the first diffuse hits are stored when the map
 * gives direct light (--direct photons) or the radiance at gather hits
 * (--gather), which must be complete. */
static photons_params photon_params_of(const config_render *cfg)
{
    photons_params pp = {cfg->photons, cfg->seed, cfg->photon_depth,
                         cfg->direct == CONFIG_DIRECT_PHOTONS || cfg->gather > 0};
    return pp;
}

/* Seconds since t0 (clock_now_ns). */
static double seconds_since(int64_t t0)
{
    return (double)(clock_now_ns() - t0) * 1e-9;
}

/* Step 1: emit and trace the photons: the same code in both methods, so
 * that this phase's time ratio measures the machine's drift (the studies'
 * drift control). Returns PM_OK, or PM_ERR_NOMEM. */
static pm_status step_trace(render_state *rs)
{
    const config_render *cfg = rs->cfg;
    photons_params pp = photon_params_of(cfg);
    progress prog;
    progress_begin(&prog, "photons", cfg->photons, rs->show_progress);
    int64_t t0 = clock_now_ns();
    pm_status rc;
    if ((rc = photons_trace(rs->sc, &pp, rs->threads, &prog, &rs->list)) != PM_OK)
        return rc;
    progress_end(&prog);
    rs->st->trace = seconds_since(t0);
    rs->st->photons_emitted = cfg->photons;
    rs->st->photons_stored = rs->list.count;
    rs->st->photon_paths_truncated = rs->list.truncated;
    rs->st->photons_escaped = rs->list.escaped;
    rs->st->work.trace.traced_photons = cfg->photons;
    rs->st->work.trace.stored_photons = rs->list.count;
    rs->st->work.trace.rays = rs->list.rays;
    rs->st->work.trace.shape_tests = rs->list.shape_tests;
    return PM_OK;
}

/* --gather: the caustic map from the list's L S+ D photons, built only
 * when there are any (a scene with a mirror or glass that photons reach).
 * Returns PM_OK, or PM_ERR_NOMEM. */
static pm_status build_caustic(render_state *rs)
{
    photons_list cl;
    pm_status rc = photons_list_select(&rs->list, PHOTONS_FLAG_CAUSTIC, &cl);
    if (rc != PM_OK)
        return rc;
    if (cl.count == 0) {
        photons_list_free(&cl);
        return PM_OK;
    }
    if ((rc = photons_build_map(&cl, 0, rs->threads, &rs->caustic, NULL)) != PM_OK)
        return rc;
    rs->st->caustic_photons = rs->caustic.count;
    rs->st->bytes_caustic_map = photons_map_bytes(&rs->caustic);
    rs->st->work.build.tree_points += rs->caustic.count;
    return PM_OK;
}

/* Step 2: choose the representatives among the stored photons (precomputed
 * method), build the photon map (kd-tree), with --gather the caustic map
 * too, and find the representatives' sites in it. Returns PM_OK, or
 * PM_ERR_NOMEM. */
static pm_status step_build(render_state *rs)
{
    int64_t t0 = clock_now_ns();
    photons_list left;
    pm_status rc;
    rs->st->work.build.rep_chosen = reps_choose(&rs->rp, &rs->list);
    if (rs->cfg->gather > 0 && (rc = build_caustic(rs)) != PM_OK)
        return rc;
    if ((rc = photons_build_map(&rs->list, reps_leave_out_mask(&rs->rp), rs->threads, &rs->map, &left)) != PM_OK)
        return rc;
    rc = reps_collect(&rs->rp, &rs->map, &left, &rs->reps);
    photons_list_free(&left);
    if (rc != PM_OK)
        return rc;
    rs->st->build = seconds_since(t0);
    rs->st->work.build.tree_points += rs->map.count;
    /* the representatives' sites count with the map, whose build finds them */
    rs->st->bytes_photon_map = photons_map_bytes(&rs->map) + reps_sites_bytes(&rs->reps);
    rs->max_radius = render_max_radius(rs->sc, rs->cfg, &rs->map);
    rs->st->max_radius = rs->max_radius;
    rs->st->photons_extent = rs->map.extent;
    return PM_OK;
}

/* Refuses a scene whose lit part is too small for double precision where it
 * is computed: the photons' bounding box (the scene's, without photons)
 * must span at least RENDER_MIN_RELATIVE_EXTENT of its own distance from
 * the origin, and of the camera's (the eye rays start there, and a hit
 * point carries the rounding of its ray's origin and length). The message
 * names which of the two limits. Returns PM_OK, or PM_ERR_INPUT with the
 * reason in err. */
static pm_status check_precision(const render_state *rs, char *err, size_t errlen)
{
    const scene *sc = rs->sc;
    double extent = rs->map.extent, far;
    if (extent > 0.0) {
        far = vec_max_abs(rs->map.centre) + 0.5 * extent;
    } else {
        extent = sc->scale;
        far = fmax(vec_max_abs(sc->bounds_lo), vec_max_abs(sc->bounds_hi));
    }
    double cam = vec_max_abs(sc->camera.position);
    if (extent >= RENDER_MIN_RELATIVE_EXTENT * fmax(far, cam))
        return PM_OK;
    if (far >= cam)
        snprintf(err, errlen,
                 "the lit part of the scene spans %.3g units but lies %.3g from the origin, where doubles are %.2g "
                 "apart; renders are exact to 0.5%% only while the span is at least 2^-38 (%.2g) of that distance: "
                 "move the scene toward the origin",
                 extent, far, far * DBL_EPSILON, RENDER_MIN_RELATIVE_EXTENT);
    else
        snprintf(err, errlen,
                 "the camera lies %.3g from the origin, where doubles are %.2g apart: the eye rays start there, "
                 "and their hits on the lit part of the scene (%.3g units across, %.3g from the origin) carry that "
                 "rounding; renders are exact to 0.5%% only while the lit part spans at least 2^-38 (%.2g) of the "
                 "camera's distance from the origin: move the camera closer to the origin and the scene",
                 cam, cam * DBL_EPSILON, extent, far, RENDER_MIN_RELATIVE_EXTENT);
    return PM_ERR_INPUT;
}

/* Step 3 (precomputed method): irradiance at the representatives (lazy:
 * their lookup and normals only; the irradiance is then computed, and
 * timed, in the eye pass). Returns PM_OK, or PM_ERR_NOMEM. */
static pm_status step_precompute(render_state *rs)
{
    const config_render *cfg = rs->cfg;
    est_gather g = est_gather_make(&rs->map, cfg->nn, rs->max_radius, cfg->bias_correction);
    progress prog;
    progress_begin(&prog, "precompute", rs->reps.count, rs->show_progress);
    int64_t t0 = clock_now_ns();
    pm_status rc;
    if ((rc = reps_evaluate(&rs->reps, &rs->map, &g, rs->threads, &prog)) != PM_OK)
        return rc;
    progress_end(&prog);
    rs->st->precompute = seconds_since(t0);
    rs->st->representatives = rs->reps.count;
    rs->st->work.precompute = rs->reps.work;
    rs->st->bytes_representatives = reps_bytes(&rs->reps, &rs->map);
    return PM_OK;
}

/* Step 4: the eye pass into *out. Returns PM_OK, or PM_ERR_NOMEM. */
static pm_status step_eye(render_state *rs, image *out)
{
    eye_input in = {rs->sc, rs->cfg, &rs->map, &rs->reps, rs->max_radius,
                    rs->caustic.stored > 0 ? &rs->caustic : NULL};
    return eye_render(&in, rs->threads, rs->show_progress, out, rs->st);
}

pm_status render_prepare(scene *sc, const config_render *cfg, char *err, size_t errlen)
{
    pm_status rc = scene_set_accel(sc, cfg->accel);
    if (rc != PM_OK)
        snprintf(err, errlen, "%s building the BVH of %zu shapes", pm_status_message(rc), sc->nshapes);
    return rc;
}

pm_status render_check_memory(const scene *sc, const config_render *cfg, uint64_t mem, char *err, size_t errlen)
{
    photons_params pp = photon_params_of(cfg);
    double per_emitted;
    pm_status rc = photons_stored_per_emitted(sc, &pp, &per_emitted);
    if (rc != PM_OK) {
        snprintf(err, errlen, "the pilot photon pass: %s", pm_status_message(rc));
        return rc;
    }
    if (per_emitted == 0.0)
        return PM_OK;
    double stored = per_emitted * (double)cfg->photons * 1.1 + 4096.0;
    double bytes = photons_peak_bytes(stored);
    if (cfg->repeats != 1) /* mem_keep: no page handed back, freed ones kept */
        bytes = 2.0 * bytes + fmin((double)CONFIG_REPEAT_KEEP_BYTES, 2.0 * bytes);
    if (stored > (double)UINT32_MAX - 1.0) {
        snprintf(err, errlen, "--photons %" PRIu64 " would store about %.3g photons; the map holds at most 2^32-1",
                 cfg->photons, stored);
        return PM_ERR_INPUT;
    }
    if (mem > 0 && bytes > CONFIG_MEMORY_HEADROOM * (double)mem) {
        snprintf(err, errlen,
                 "--photons %" PRIu64 " needs about %.1f GiB (%.2f stored per emitted photon, %.0f bytes each "
                 "at the peak%s), more than %.0f%% of this machine's %.1f GiB; use fewer photons%s",
                 cfg->photons, bytes / 1073741824.0, per_emitted, bytes / stored,
                 cfg->repeats != 1 ? ", repeats keeping freed memory for the next" : "", CONFIG_MEMORY_HEADROOM * 100.0,
                 (double)mem / 1073741824.0, cfg->repeats != 1 ? " or --repeats 1" : "");
        return PM_ERR_INPUT;
    }
    return PM_OK;
}

pm_status render_run(const scene *sc, const config_render *cfg, unsigned threads, int show_progress, render_result *out,
               char *err, size_t errlen)
{
    assert(threads >= 1 && cfg->width > 0 && cfg->height > 0 && cfg->subpixels > 0);
    memset(out, 0, sizeof *out);
    stats_run *st = &out->st;
    render_state rs;
    memset(&rs, 0, sizeof rs);
    rs.sc = sc;
    rs.cfg = cfg;
    rs.threads = threads;
    rs.show_progress = show_progress;
    rs.st = st;
    rs.rp = reps_params_of(cfg);
    int64_t t_start = clock_now_ns();
    pm_status rc = step_trace(&rs);
    if (rc == PM_OK)
        rc = reps_check_stored(cfg, rs.list.count, err, errlen);
    if (rc == PM_OK)
        rc = step_build(&rs);
    if (rc == PM_OK)
        rc = check_precision(&rs, err, errlen);
    if (rc == PM_OK && cfg->method == CONFIG_METHOD_PRECOMPUTED)
        rc = step_precompute(&rs);
    if (rc == PM_OK)
        rc = step_eye(&rs, &out->img);
    if (rc == PM_OK)
        st->reps_evaluated = reps_evaluated(&rs.reps);
    photons_list_free(&rs.list);
    photons_map_free(&rs.caustic);
    if (rc == PM_OK && cfg->dump_reps) {
        /* the caller writes them: they stay with the map that places them */
        out->map = rs.map;
        out->reps = rs.reps;
    } else {
        reps_free(&rs.reps);
        photons_map_free(&rs.map);
    }
    /* the steps that fail on input write why into err; the others do not */
    if (rc != PM_OK && rc != PM_ERR_INPUT)
        snprintf(err, errlen, "%s while rendering", pm_status_message(rc));
    if (rc != PM_OK) {
        image_free(&out->img);
        memset(out, 0, sizeof *out);
        return rc;
    }
    st->total = seconds_since(t_start);
    return PM_OK;
}

pm_status render_write_reps(const render_result *r, FILE *f)
{
    return reps_write_csv(&r->reps, &r->map, f);
}

void render_result_free(render_result *r)
{
    image_free(&r->img);
    reps_free(&r->reps);
    photons_map_free(&r->map);
    memset(r, 0, sizeof *r);
}

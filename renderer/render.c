/* render: the paper's pipeline (Fig. 1: trace photons, build the photon
 * map, precompute irradiance, eye pass) in render_run, and the eye pass
 * itself, tile by tile. */
#include "render.h"

#include <assert.h>
#include <float.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "estimate.h"
#include "material.h"
#include "outfile.h"
#include "parallel.h"
#include "photons.h"
#include "progress.h"
#include "reps.h"

#define RENDER_TILE 16u

typedef struct {
    uint64_t samples, depth_hits, empty, underflow;
    char pad[128 - 4 * sizeof(uint64_t)]; /* one per thread: no two threads' counters share a cache line */
} eye_counts;

typedef struct {
    const scene *sc;
    const config_render *cfg;
    const photons_map *map;
    const reps_set *reps;
    est_gather gather;    /* conventional: nn and the radius cap (map frame) */
    render_camera camera;
    vec3 light_intensity; /* power / 4pi, for shadow rays */
    image *img;
    uint32_t tiles_x;
    est_scratch *scratch; /* per thread */
    eye_counts *counts;   /* per thread */
    progress *prog;
} eye_ctx;

render_camera render_camera_make(const scene *sc, double aspect_h_over_w)
{
    const scene_camera *c = &sc->camera;
    render_camera cam;
    cam.origin = c->position;
    cam.fwd = vec_norm(vec_sub(c->look_at, c->position));
    vec3 right = vec_norm(vec_cross(cam.fwd, c->up));
    vec3 up = vec_cross(right, cam.fwd);
    double hw = tan(0.5 * c->hfov_deg * VEC_PI / 180.0);
    cam.right = vec_scale(right, hw);
    cam.up = vec_scale(up, hw * aspect_h_over_w);
    return cam;
}

shape_ray render_camera_at(const render_camera *cam, double u, double v)
{
    vec3 d = vec_add(cam->fwd, vec_add(vec_scale(cam->right, 2.0 * u - 1.0), vec_scale(cam->up, 1.0 - 2.0 * v)));
    shape_ray r = {cam->origin, vec_norm(d)};
    return r;
}

shape_ray render_camera_ray(const scene *sc, double aspect_h_over_w, double u, double v)
{
    render_camera cam = render_camera_make(sc, aspect_h_over_w);
    return render_camera_at(&cam, u, v);
}

double render_max_radius(const scene *sc, const config_render *cfg, const photons_map *m)
{
    if (cfg->max_radius > 0.0)
        return cfg->max_radius;
    return cfg->max_radius_frac * (m->extent > 0.0 ? m->extent : sc->scale);
}

/* Direct light at the hit h by one shadow ray. */
static vec3 direct_light(const eye_ctx *c, const scene_hit *h)
{
    vec3 to = vec_sub(c->sc->light.position, h->p);
    double d2 = vec_len2(to);
    if (!(d2 > 0.0))
        return vec_make(0, 0, 0);
    double d = sqrt(d2);
    vec3 w = vec_scale(to, 1.0 / d);
    double cosv = vec_dot(w, h->n);
    if (cosv <= 0.0)
        return vec_make(0, 0, 0);
    shape_ray sr = scene_spawn(h, w, 1);
    if (scene_occluded(c->sc, &sr, d - h->eps))
        return vec_make(0, 0, 0);
    return vec_scale(c->light_intensity, cosv / d2);
}

static vec3 radiance(const eye_ctx *c, unsigned thread, shape_ray r, uint32_t depth, double weight)
{
    const scene *sc = c->sc;
    scene_hit h;
    if (!scene_intersect(sc, &r, INFINITY, &h))
        return vec_make(0, 0, 0);
    const material *m = &sc->materials[sc->shapes[h.shape].material];
    if (m->kind == MATERIAL_LAMBERT) {
        vec3 e;
        if (c->cfg->method == CONFIG_METHOD_PRECOMPUTED) {
            int found;
            e = reps_lookup(c->reps, c->map, h.p, h.n, c->cfg->normal_cos, &c->gather, &c->scratch[thread], &found);
            c->counts[thread].empty += !found;
        } else {
            uint32_t found;
            e = est_irradiance(c->map, h.p, h.n, &c->gather, &c->scratch[thread], &found);
            c->counts[thread].empty += found == 0;
        }
        if (c->cfg->direct == CONFIG_DIRECT_SHADOW_RAYS)
            e = vec_add(e, direct_light(c, &h));
        return vec_mul(vec_scale(m->color, 1.0 / VEC_PI), e);
    }
    if (depth >= c->cfg->eye_depth) {
        c->counts[thread].depth_hits++;
        return vec_make(0, 0, 0);
    }
    if (m->kind == MATERIAL_MIRROR) {
        double w = weight * vec_maxc(m->color);
        if (w < CONFIG_EYE_MIN_THROUGHPUT)
            return vec_make(0, 0, 0);
        return vec_mul(m->color, radiance(c, thread, scene_spawn(&h, material_reflect(r.dir, h.n), 1), depth + 1, w));
    }
    /* glass: both branches, weighted by Fresnel */
    double n1 = h.front ? 1.0 : m->ior, n2 = h.front ? m->ior : 1.0;
    double fr = material_fresnel(-vec_dot(r.dir, h.n), n1, n2);
    vec3 refr;
    int can_refract = material_refract(r.dir, h.n, n1 / n2, &refr);
    if (!can_refract)
        fr = 1.0;
    vec3 L = vec_make(0, 0, 0);
    if (weight * fr >= CONFIG_EYE_MIN_THROUGHPUT) {
        shape_ray rr = scene_spawn(&h, material_reflect(r.dir, h.n), 1);
        L = vec_scale(radiance(c, thread, rr, depth + 1, weight * fr), fr);
    }
    if (can_refract && weight * (1.0 - fr) >= CONFIG_EYE_MIN_THROUGHPUT) {
        shape_ray rt = scene_spawn(&h, refr, 0);
        L = vec_madd(L, radiance(c, thread, rt, depth + 1, weight * (1.0 - fr)), 1.0 - fr);
    }
    return L;
}

static void eye_tile(uint64_t tile, unsigned thread, void *arg)
{
    eye_ctx *c = arg;
    const config_render *cfg = c->cfg;
    uint32_t tx = (uint32_t)(tile % c->tiles_x), ty = (uint32_t)(tile / c->tiles_x);
    uint32_t x0 = tx * RENDER_TILE, y0 = ty * RENDER_TILE;
    uint32_t x1 = x0 + RENDER_TILE < cfg->width ? x0 + RENDER_TILE : cfg->width;
    uint32_t y1 = y0 + RENDER_TILE < cfg->height ? y0 + RENDER_TILE : cfg->height;
    uint32_t S = cfg->subpixels;
    double inv = 1.0 / ((double)S * S);
    for (uint32_t y = y0; y < y1; y++) {
        for (uint32_t x = x0; x < x1; x++) {
            vec3 sum = vec_make(0, 0, 0);
            for (uint32_t sy = 0; sy < S; sy++) {
                for (uint32_t sx = 0; sx < S; sx++) {
                    double u = (x + (sx + 0.5) / S) / cfg->width;
                    double v = (y + (sy + 0.5) / S) / cfg->height;
                    shape_ray r = render_camera_at(&c->camera, u, v);
                    sum = vec_add(sum, radiance(c, thread, r, 0, 1.0));
                }
            }
            float *px = c->img->rgb + ((size_t)y * cfg->width + x) * 3;
            px[0] = (float)(sum.x * inv);
            px[1] = (float)(sum.y * inv);
            px[2] = (float)(sum.z * inv);
            /* a radiance the float cannot hold but as 0 or a subnormal */
            c->counts[thread].underflow += (sum.x > 0.0 && !(px[0] >= FLT_MIN)) ||
                                           (sum.y > 0.0 && !(px[1] >= FLT_MIN)) ||
                                           (sum.z > 0.0 && !(px[2] >= FLT_MIN));
        }
    }
    c->counts[thread].samples += (uint64_t)(x1 - x0) * (y1 - y0) * S * S;
    progress_add(c->prog, 1);
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
    double max_radius; /* the radius cap, scene units */
} render_state;

/* Seconds since t0 (stats_now_ns). */
static double seconds_since(int64_t t0)
{
    return (double)(stats_now_ns() - t0) * 1e-9;
}

/* Step 1: emit and trace the photons. Returns 0, or -1 out of memory. */
static int step_trace(render_state *rs)
{
    const config_render *cfg = rs->cfg;
    photons_params pp = {cfg->photons, cfg->seed, cfg->photon_depth, cfg->direct == CONFIG_DIRECT_PHOTONS};
    progress prog;
    progress_begin(&prog, "photons", cfg->photons, rs->show_progress);
    int64_t t0 = stats_now_ns();
    if (photons_trace(rs->sc, &pp, rs->threads, &prog, &rs->list))
        return -1;
    reps_choose(&rs->rp, &rs->list);
    progress_end(&prog);
    rs->st->trace = seconds_since(t0);
    rs->st->photons_emitted = cfg->photons;
    rs->st->photons_stored = rs->list.count;
    rs->st->photon_paths_truncated = rs->list.truncated;
    rs->st->photons_escaped = rs->list.escaped;
    return 0;
}

/* Step 2: build the photon map (kd-tree) and find the representatives'
 * sites in it. Returns 0, or -1 out of memory. */
static int step_build(render_state *rs)
{
    int64_t t0 = stats_now_ns();
    photons_list left;
    if (photons_build_map(&rs->list, reps_leave_out_mask(&rs->rp), &rs->map, &left))
        return -1;
    int rc = reps_collect(&rs->rp, &rs->map, &left, &rs->reps);
    photons_list_free(&left);
    if (rc)
        return -1;
    rs->st->build = seconds_since(t0);
    /* the representatives' sites count with the map, whose build finds them */
    rs->st->bytes_photon_map = photons_map_bytes(&rs->map) + reps_sites_bytes(&rs->reps);
    rs->max_radius = render_max_radius(rs->sc, rs->cfg, &rs->map);
    rs->st->max_radius = rs->max_radius;
    return 0;
}

/* Refuses a scene whose lit part is too small for double precision where it
 * sits: the photons' bounding box (the scene's, without photons) must span
 * at least RENDER_MIN_RELATIVE_EXTENT of its distance from the origin.
 * Returns RENDER_OK, or RENDER_ERR_INPUT with the reason in err. */
static int check_precision(const render_state *rs, char *err, size_t errlen)
{
    const scene *sc = rs->sc;
    double extent = rs->map.extent, far;
    if (extent > 0.0) {
        far = vec_max_abs(rs->map.centre) + 0.5 * extent;
    } else {
        extent = sc->scale;
        far = fmax(vec_max_abs(sc->bounds_lo), vec_max_abs(sc->bounds_hi));
    }
    far = fmax(far, vec_max_abs(sc->camera.position));
    if (extent >= RENDER_MIN_RELATIVE_EXTENT * far)
        return RENDER_OK;
    snprintf(err, errlen,
             "the lit part of the scene spans %.3g units but lies %.3g from the origin, where doubles are %.2g "
             "apart; renders are exact to 0.5%% only while the span is at least 2^-38 (%.2g) of that distance: "
             "move the scene toward the origin",
             extent, far, far * DBL_EPSILON, RENDER_MIN_RELATIVE_EXTENT);
    return RENDER_ERR_INPUT;
}

/* Step 3 (precomputed method): irradiance at the representatives. Returns
 * 0, or -1 out of memory. */
static int step_precompute(render_state *rs)
{
    const config_render *cfg = rs->cfg;
    est_gather g = est_gather_make(&rs->map, cfg->nn, rs->max_radius, cfg->bias_correction);
    progress prog;
    progress_begin(&prog, "precompute", rs->reps.count, rs->show_progress);
    int64_t t0 = stats_now_ns();
    if (reps_evaluate(&rs->reps, &rs->map, &g, rs->threads, &prog))
        return -1;
    progress_end(&prog);
    rs->st->precompute = seconds_since(t0);
    rs->st->representatives = rs->reps.count;
    rs->st->bytes_representatives = reps_bytes(&rs->reps, &rs->map);
    return 0;
}

/* --dump-reps: the representatives as CSV (reps_write_csv), through a
 * temporary file. Returns 0, or -1 with the reason in err. */
static int dump_reps(const render_state *rs, char *err, size_t errlen)
{
    outfile f;
    if (outfile_begin(&f, rs->cfg->dump_reps, 1, err, errlen))
        return -1;
    if (reps_write_csv(&rs->reps, &rs->map, f.f)) {
        snprintf(err, errlen, "%s: write error", rs->cfg->dump_reps);
        outfile_abort(&f);
        return -1;
    }
    return outfile_commit(&f, err, errlen);
}

/* Step 4: the eye pass into *out. Returns 0, or -1 out of memory. */
static int step_eye(render_state *rs, image *out)
{
    const config_render *cfg = rs->cfg;
    eye_ctx c;
    memset(&c, 0, sizeof c);
    c.sc = rs->sc;
    c.cfg = cfg;
    c.map = &rs->map;
    c.reps = &rs->reps;
    c.gather = est_gather_make(&rs->map, cfg->nn, rs->max_radius, cfg->bias_correction);
    c.camera = render_camera_make(rs->sc, (double)cfg->height / (double)cfg->width);
    c.light_intensity = vec_scale(rs->sc->light.power, 1.0 / (4.0 * VEC_PI));
    c.img = out;
    c.tiles_x = (cfg->width + RENDER_TILE - 1) / RENDER_TILE;
    uint64_t tiles = (uint64_t)c.tiles_x * ((cfg->height + RENDER_TILE - 1) / RENDER_TILE);
    c.scratch = est_scratch_new(rs->threads, cfg->nn);
    c.counts = calloc(rs->threads, sizeof(eye_counts));
    int rc = (!c.scratch || !c.counts || image_init(out, cfg->width, cfg->height)) ? -1 : 0;
    if (rc == 0) {
        progress prog;
        progress_begin(&prog, "render", tiles, rs->show_progress);
        c.prog = &prog;
        int64_t t0 = stats_now_ns();
        parallel_for(rs->threads, tiles, eye_tile, &c);
        rs->st->render = seconds_since(t0);
        progress_end(&prog);
        for (unsigned t = 0; t < rs->threads; t++) {
            rs->st->samples += c.counts[t].samples;
            rs->st->eye_depth_limit_hits += c.counts[t].depth_hits;
            rs->st->empty_estimates += c.counts[t].empty;
            rs->st->underflow_pixels += c.counts[t].underflow;
        }
        rs->st->nonfinite_pixels = image_count_nonfinite(out);
        image_mean(out, rs->st->mean_radiance);
    }
    est_scratch_delete(c.scratch, rs->threads);
    free(c.counts);
    return rc;
}

int render_run(const scene *sc, const config_render *cfg, unsigned threads, int show_progress, image *out,
               stats_run *st, char *err, size_t errlen)
{
    assert(threads >= 1 && cfg->width > 0 && cfg->height > 0 && cfg->subpixels > 0);
    memset(st, 0, sizeof *st);
    memset(out, 0, sizeof *out);
    render_state rs;
    memset(&rs, 0, sizeof rs);
    rs.sc = sc;
    rs.cfg = cfg;
    rs.threads = threads;
    rs.show_progress = show_progress;
    rs.st = st;
    rs.rp = reps_params_of(cfg);
    int64_t t_start = stats_now_ns();
    int rc = step_trace(&rs) ? RENDER_ERR_MEMORY : RENDER_OK;
    if (rc == RENDER_OK && reps_check_stored(cfg, rs.list.count, err, errlen))
        rc = RENDER_ERR_INPUT;
    if (rc == RENDER_OK && step_build(&rs))
        rc = RENDER_ERR_MEMORY;
    if (rc == RENDER_OK)
        rc = check_precision(&rs, err, errlen);
    if (rc == RENDER_OK && cfg->method == CONFIG_METHOD_PRECOMPUTED && step_precompute(&rs))
        rc = RENDER_ERR_MEMORY;
    if (rc == RENDER_OK && step_eye(&rs, out))
        rc = RENDER_ERR_MEMORY;
    if (rc == RENDER_OK && cfg->dump_reps) {
        /* not part of the render's time */
        int64_t t_dump = stats_now_ns();
        if (dump_reps(&rs, err, errlen))
            rc = RENDER_ERR_IO;
        t_start += stats_now_ns() - t_dump;
    }
    reps_free(&rs.reps);
    photons_map_free(&rs.map);
    photons_list_free(&rs.list);
    if (rc == RENDER_ERR_MEMORY)
        snprintf(err, errlen, "out of memory while rendering");
    if (rc != RENDER_OK) {
        image_free(out);
        return rc;
    }
    st->total = seconds_since(t_start);
    return RENDER_OK;
}

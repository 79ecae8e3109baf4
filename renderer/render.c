/* render: pipeline orchestration and the eye pass, tile by tile. */
#include "render.h"

#include <assert.h>
#include <stdlib.h>
#include <string.h>

#include "estimate.h"
#include "material.h"
#include "parallel.h"
#include "photons.h"
#include "progress.h"

#define RENDER_TILE 16u

typedef struct {
    uint64_t samples, depth_hits, empty;
    char pad[128 - 3 * sizeof(uint64_t)]; /* one per thread: no two threads' counters share a cache line */
} eye_counts;

typedef struct {
    const scene *sc;
    const render_config *cfg;
    const photon_map *map;
    const est_reps *reps;
    double max_r2, eps;
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

ray render_camera_at(const render_camera *cam, double u, double v)
{
    vec3 d = vec_add(cam->fwd, vec_add(vec_scale(cam->right, 2.0 * u - 1.0), vec_scale(cam->up, 1.0 - 2.0 * v)));
    ray r = {cam->origin, vec_norm(d)};
    return r;
}

ray render_camera_ray(const scene *sc, double aspect_h_over_w, double u, double v)
{
    render_camera cam = render_camera_make(sc, aspect_h_over_w);
    return render_camera_at(&cam, u, v);
}

double render_max_radius(const scene *sc, const render_config *cfg)
{
    return cfg->max_radius > 0.0 ? cfg->max_radius : cfg->max_radius_frac * sc->scale;
}

/* Direct light at p (normal n facing the viewer) by one shadow ray. */
static vec3 direct_light(const eye_ctx *c, vec3 p, vec3 n)
{
    vec3 to = vec_sub(c->sc->light.position, p);
    double d2 = vec_len2(to);
    if (!(d2 > 0.0))
        return vec_make(0, 0, 0);
    double d = sqrt(d2);
    vec3 w = vec_scale(to, 1.0 / d);
    double cosv = vec_dot(w, n);
    if (cosv <= 0.0)
        return vec_make(0, 0, 0);
    ray sr = {vec_madd(p, n, c->eps), w};
    if (scene_occluded(c->sc, &sr, c->eps, d - c->eps))
        return vec_make(0, 0, 0);
    return vec_scale(c->light_intensity, cosv / d2);
}

static vec3 radiance(const eye_ctx *c, unsigned thread, ray r, uint32_t depth, double weight)
{
    const scene *sc = c->sc;
    double t;
    int hit = scene_intersect(sc, &r, c->eps, INFINITY, &t);
    if (hit < 0)
        return vec_make(0, 0, 0);
    const shape *sh = &sc->shapes[hit];
    const material *m = &sc->materials[sh->material];
    vec3 p = vec_madd(r.origin, r.dir, t);
    vec3 ng = shape_normal(sh, p);
    int front = vec_dot(ng, r.dir) < 0.0;
    vec3 n = front ? ng : vec_neg(ng); /* faces the viewer */
    if (m->kind == MAT_LAMBERT) {
        vec3 e;
        if (c->cfg->method == METHOD_PRECOMPUTED) {
            int found;
            e = est_lookup(c->reps, c->map, p, n, c->cfg->normal_cos, c->max_r2, &found);
            c->counts[thread].empty += !found;
        } else {
            uint32_t found;
            e = est_irradiance(c->map, p, n, c->cfg->nn, c->max_r2, &c->scratch[thread], &found);
            c->counts[thread].empty += found == 0;
        }
        if (c->cfg->direct == DIRECT_SHADOW_RAYS)
            e = vec_add(e, direct_light(c, p, n));
        return vec_mul(vec_scale(m->color, 1.0 / VEC_PI), e);
    }
    if (depth >= c->cfg->eye_depth) {
        c->counts[thread].depth_hits++;
        return vec_make(0, 0, 0);
    }
    if (m->kind == MAT_MIRROR) {
        ray rr = {vec_madd(p, n, c->eps), material_reflect(r.dir, n)};
        double w = weight * vec_maxc(m->color);
        if (w < CONFIG_EYE_MIN_THROUGHPUT)
            return vec_make(0, 0, 0);
        return vec_mul(m->color, radiance(c, thread, rr, depth + 1, w));
    }
    /* glass: both branches, weighted by Fresnel */
    double n1 = front ? 1.0 : m->ior, n2 = front ? m->ior : 1.0;
    double fr = material_fresnel(-vec_dot(r.dir, n), n1, n2);
    vec3 refr;
    int can_refract = material_refract(r.dir, n, n1 / n2, &refr);
    if (!can_refract)
        fr = 1.0;
    vec3 L = vec_make(0, 0, 0);
    if (weight * fr >= CONFIG_EYE_MIN_THROUGHPUT) {
        ray rr = {vec_madd(p, n, c->eps), material_reflect(r.dir, n)};
        L = vec_scale(radiance(c, thread, rr, depth + 1, weight * fr), fr);
    }
    if (can_refract && weight * (1.0 - fr) >= CONFIG_EYE_MIN_THROUGHPUT) {
        ray rt = {vec_madd(p, n, -c->eps), refr};
        L = vec_madd(L, radiance(c, thread, rt, depth + 1, weight * (1.0 - fr)), 1.0 - fr);
    }
    return L;
}

static void eye_tile(uint64_t tile, unsigned thread, void *arg)
{
    eye_ctx *c = arg;
    const render_config *cfg = c->cfg;
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
                    ray r = render_camera_at(&c->camera, u, v);
                    sum = vec_add(sum, radiance(c, thread, r, 0, 1.0));
                }
            }
            float *px = c->img->rgb + ((size_t)y * cfg->width + x) * 3;
            px[0] = (float)(sum.x * inv);
            px[1] = (float)(sum.y * inv);
            px[2] = (float)(sum.z * inv);
        }
    }
    c->counts[thread].samples += (uint64_t)(x1 - x0) * (y1 - y0) * S * S;
    progress_add(c->prog, 1);
}

int render_run(const scene *sc, const render_config *cfg, unsigned threads, int show_progress, image *out,
               stats_run *st)
{
    assert(threads >= 1 && cfg->width > 0 && cfg->height > 0 && cfg->subpixels > 0);
    memset(st, 0, sizeof *st);
    memset(out, 0, sizeof *out);
    int64_t t_start = stats_now_ns();
    double max_r = render_max_radius(sc, cfg);
    st->max_radius = max_r;
    progress prog;

    /* photon pass */
    photon_list list;
    progress_begin(&prog, "photons", cfg->photons, show_progress);
    int64_t t0 = stats_now_ns();
    if (photons_trace(sc, cfg, threads, &prog, &list))
        return -1;
    progress_end(&prog);
    st->trace = (double)(stats_now_ns() - t0) * 1e-9;
    st->photons_emitted = cfg->photons;
    st->photons_stored = list.count;
    st->photon_paths_truncated = list.truncated;
    st->photons_escaped = list.escaped;

    /* photon map */
    photon_map map;
    t0 = stats_now_ns();
    if (photons_build_map(&list, &map))
        return -1;
    st->build = (double)(stats_now_ns() - t0) * 1e-9;
    st->bytes_photon_map = (uint64_t)(kd_bytes(&map.tree) + (size_t)map.count * sizeof(photon));

    /* precompute */
    est_reps reps;
    memset(&reps, 0, sizeof reps);
    if (cfg->method == METHOD_PRECOMPUTED) {
        progress_begin(&prog, "precompute", map.reps, show_progress);
        t0 = stats_now_ns();
        if (est_precompute(&map, cfg->nn, max_r * max_r, cfg->reps_shared ? EST_REPS_SHARED : EST_REPS_SEPARATE,
                           threads, &prog, &reps)) {
            photons_map_free(&map);
            return -1;
        }
        progress_end(&prog);
        st->precompute = (double)(stats_now_ns() - t0) * 1e-9;
        st->representatives = reps.count;
        st->bytes_representatives = est_reps_bytes(&reps, &map);
    }

    /* eye pass */
    eye_ctx c;
    memset(&c, 0, sizeof c);
    c.sc = sc;
    c.cfg = cfg;
    c.map = &map;
    c.reps = &reps;
    c.max_r2 = max_r * max_r;
    c.eps = scene_epsilon(sc);
    c.camera = render_camera_make(sc, (double)cfg->height / (double)cfg->width);
    c.light_intensity = vec_scale(sc->light.power, 1.0 / (4.0 * VEC_PI));
    c.img = out;
    c.tiles_x = (cfg->width + RENDER_TILE - 1) / RENDER_TILE;
    uint32_t tiles_y = (cfg->height + RENDER_TILE - 1) / RENDER_TILE;
    c.scratch = calloc(threads, sizeof(est_scratch));
    c.counts = calloc(threads, sizeof(eye_counts));
    int rc = (!c.scratch || !c.counts || image_init(out, cfg->width, cfg->height)) ? -1 : 0;
    for (unsigned t = 0; rc == 0 && t < threads; t++)
        rc = est_scratch_init(&c.scratch[t], cfg->nn + 16); /* unused tail: threads' buffers share no line */
    if (rc == 0) {
        progress_begin(&prog, "render", (uint64_t)c.tiles_x * tiles_y, show_progress);
        c.prog = &prog;
        t0 = stats_now_ns();
        parallel_for(threads, (uint64_t)c.tiles_x * tiles_y, eye_tile, &c);
        st->render = (double)(stats_now_ns() - t0) * 1e-9;
        progress_end(&prog);
        for (unsigned t = 0; t < threads; t++) {
            st->samples += c.counts[t].samples;
            st->eye_depth_limit_hits += c.counts[t].depth_hits;
            st->empty_estimates += c.counts[t].empty;
        }
        st->nonfinite_pixels = image_count_nonfinite(out);
    }
    if (c.scratch)
        for (unsigned t = 0; t < threads; t++)
            est_scratch_free(&c.scratch[t]);
    free(c.scratch);
    free(c.counts);
    est_reps_free(&reps);
    photons_map_free(&map);
    if (rc != 0) {
        image_free(out);
        return -1;
    }
    st->total = (double)(stats_now_ns() - t_start) * 1e-9;
    return 0;
}

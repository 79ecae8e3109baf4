/* eye: the eye pass, tile by tile (eye.h). */
#include "eye.h"

#include <assert.h>
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "camera.h"
#include "clock.h"
#include "estimate.h"
#include "material.h"
#include "parallel.h"
#include "progress.h"

#define EYE_TILE 16u

typedef struct {
    uint64_t samples, depth_hits, empty, underflow, flushed, fallbacks;
    uint64_t rays, shape_tests; /* work.h */
    double peak; /* the largest channel value of any pixel, before the conversion to float */
    char pad[128 - 8 * sizeof(uint64_t) - sizeof(double)]; /* one per thread: no two threads' counters share a cache line */
} eye_counts;

/* One thread's gather counters and times, on cache lines of its own. */
typedef struct {
    gather_counts g;
    int64_t gather_ns, tile_ns;
    char pad[64];
} eye_gather_counts;

typedef struct {
    const scene *sc;
    const config_render *cfg;
    const photons_map *map;
    const reps_set *reps;
    est_gather gather;    /* conventional: nn and the radius cap (map frame) */
    camera camera;
    vec3 light_intensity; /* power / 4pi, for shadow rays */
    image *img;
    uint32_t tiles_x;
    est_scratch *scratch; /* per thread */
    eye_counts *counts;   /* per thread */
    gather_params gp;     /* --gather (gp.rays > 0) */
    est_scratch *caustic_scratch; /* per thread, when there is a caustic map */
    eye_gather_counts *gcounts;   /* per thread, with --gather */
    progress *prog;
} eye_ctx;

/* Direct light at the hit h by one shadow ray. */
static vec3 direct_light(const eye_ctx *c, unsigned thread, const scene_hit *h)
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
    c->counts[thread].rays++;
    if (scene_occluded_counted(c->sc, &sr, d - h->eps, &c->counts[thread].shape_tests))
        return vec_make(0, 0, 0);
    return vec_scale(c->light_intensity, cosv / d2);
}

/* The irradiance at the first diffuse hit h by final gathering: direct
 * light by a shadow ray, caustics from the caustic map, the rest by the
 * gather rays drawing from rs. */
static vec3 final_gather(const eye_ctx *c, unsigned thread, const scene_hit *h, rng_stream *rs)
{
    eye_gather_counts *gc = &c->gcounts[thread];
    vec3 e = direct_light(c, thread, h);
    if (c->gp.caustic)
        e = vec_add(e, gather_caustic(&c->gp, h, &c->caustic_scratch[thread], &gc->g));
    int64_t t0 = clock_now_ns();
    e = vec_add(e, gather_indirect(&c->gp, h, rs, &c->scratch[thread], &gc->g));
    gc->gather_ns += clock_now_ns() - t0;
    return e;
}

/* The radiance along r; rs: the eye sample's gather stream (NULL without
 * --gather). */
static vec3 radiance(const eye_ctx *c, unsigned thread, shape_ray r, uint32_t depth, double weight, rng_stream *rs)
{
    const scene *sc = c->sc;
    scene_hit h;
    c->counts[thread].rays++;
    if (!scene_intersect_counted(sc, &r, INFINITY, &h, &c->counts[thread].shape_tests))
        return vec_make(0, 0, 0);
    const material *m = &sc->materials[sc->shapes[h.shape].material];
    if (m->kind == MATERIAL_LAMBERT) {
        if (c->gp.rays > 0)
            return vec_mul(vec_scale(m->color, 1.0 / VEC_PI), final_gather(c, thread, &h, rs));
        vec3 e;
        if (c->cfg->method == CONFIG_METHOD_PRECOMPUTED) {
            int found;
            e = reps_lookup(c->reps, c->map, h.p, h.n, &c->gather, &c->scratch[thread], &found);
            c->counts[thread].empty += !(found & REPS_FOUND);
            c->counts[thread].fallbacks += (found & REPS_FALLBACK) != 0;
        } else {
            uint32_t found;
            e = est_irradiance(c->map, h.p, h.n, &c->gather, &c->scratch[thread], &found);
            c->counts[thread].empty += found == 0;
        }
        if (c->cfg->direct == CONFIG_DIRECT_SHADOW_RAYS)
            e = vec_add(e, direct_light(c, thread, &h));
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
        return vec_mul(m->color, radiance(c, thread, scene_spawn(&h, material_reflect(r.dir, h.n), 1), depth + 1, w, rs));
    }
    /* glass: both branches, weighted by Fresnel */
    vec3 refr;
    int can_refract;
    double fr = material_glass_split(r.dir, h.n, h.front, m->ior, &refr, &can_refract);
    vec3 L = vec_make(0, 0, 0);
    if (weight * fr >= CONFIG_EYE_MIN_THROUGHPUT) {
        shape_ray rr = scene_spawn(&h, material_reflect(r.dir, h.n), 1);
        L = vec_scale(radiance(c, thread, rr, depth + 1, weight * fr, rs), fr);
    }
    if (can_refract && weight * (1.0 - fr) >= CONFIG_EYE_MIN_THROUGHPUT) {
        shape_ray rt = scene_spawn(&h, refr, 0);
        L = vec_madd(L, radiance(c, thread, rt, depth + 1, weight * (1.0 - fr), rs), 1.0 - fr);
    }
    return L;
}

static void eye_tile(uint64_t tile, unsigned thread, void *arg)
{
    eye_ctx *c = arg;
    const config_render *cfg = c->cfg;
    uint32_t tx = (uint32_t)(tile % c->tiles_x), ty = (uint32_t)(tile / c->tiles_x);
    uint32_t x0 = tx * EYE_TILE, y0 = ty * EYE_TILE;
    uint32_t x1 = x0 + EYE_TILE < cfg->width ? x0 + EYE_TILE : cfg->width;
    uint32_t y1 = y0 + EYE_TILE < cfg->height ? y0 + EYE_TILE : cfg->height;
    uint32_t S = cfg->subpixels;
    double inv = 1.0 / ((double)S * S);
    int64_t t0 = c->gcounts ? clock_now_ns() : 0;
    /* a tile's queries cost the same on any thread after any tile */
    est_scratch_forget(&c->scratch[thread]);
    if (c->caustic_scratch)
        est_scratch_forget(&c->caustic_scratch[thread]);
    for (uint32_t y = y0; y < y1; y++) {
        for (uint32_t x = x0; x < x1; x++) {
            vec3 sum = vec_make(0, 0, 0);
            for (uint32_t sy = 0; sy < S; sy++) {
                for (uint32_t sx = 0; sx < S; sx++) {
                    double u = (x + (sx + 0.5) / S) / cfg->width;
                    double v = (y + (sy + 0.5) / S) / cfg->height;
                    shape_ray r = camera_at(&c->camera, u, v);
                    if (c->gp.rays > 0) {
                        /* the sample's index in (pixel, subpixel) order names its gather stream */
                        uint64_t sample = ((uint64_t)y * cfg->width + x) * S * S + (uint64_t)sy * S + sx;
                        rng_stream rs = gather_stream(cfg->seed, sample);
                        sum = vec_add(sum, radiance(c, thread, r, 0, 1.0, &rs));
                    } else {
                        sum = vec_add(sum, radiance(c, thread, r, 0, 1.0, NULL));
                    }
                }
            }
            float *px = c->img->rgb + ((size_t)y * cfg->width + x) * 3;
            px[0] = (float)(sum.x * inv);
            px[1] = (float)(sum.y * inv);
            px[2] = (float)(sum.z * inv);
            /* a radiance the float cannot hold but as 0 or a subnormal */
            int flushed = (sum.x > 0.0 && !(px[0] >= FLT_MIN)) + (sum.y > 0.0 && !(px[1] >= FLT_MIN)) +
                          (sum.z > 0.0 && !(px[2] >= FLT_MIN));
            c->counts[thread].underflow += flushed > 0;
            c->counts[thread].flushed += (uint64_t)flushed;
            double peak = fmax(sum.x, fmax(sum.y, sum.z)) * inv;
            if (peak > c->counts[thread].peak)
                c->counts[thread].peak = peak;
        }
    }
    c->counts[thread].samples += (uint64_t)(x1 - x0) * (y1 - y0) * S * S;
    if (c->gcounts)
        c->gcounts[thread].tile_ns += clock_now_ns() - t0;
    progress_add(c->prog, 1);
}

/* Adds the threads' gather counters and times to st: the gather rays and
 * their continuations also count as the eye pass's rays. */
static void add_gather_counts(const eye_ctx *c, unsigned threads, stats_run *st)
{
    gather_counts g = {0};
    int64_t gather_ns = 0, tile_ns = 0;
    for (unsigned t = 0; t < threads; t++) {
        gather_counts_add(&g, &c->gcounts[t].g);
        gather_ns += c->gcounts[t].gather_ns;
        tile_ns += c->gcounts[t].tile_ns;
    }
    st->gather_rays = g.rays;
    st->gather_specular = g.specular;
    st->gather_lookups = g.lookups;
    st->gather_empty = g.empty;
    st->gather_fallbacks = g.fallbacks;
    st->gather_missed = g.missed;
    st->gather_depth_limit_hits = g.depth_hits;
    st->caustic_lookups = g.caustic_lookups;
    st->rep_fallbacks += g.fallbacks;
    st->gather_thread_s = (double)gather_ns * 1e-9;
    st->render_thread_s = (double)tile_ns * 1e-9;
    st->work.render.rays += g.rays + g.specular;
    st->work.render.shape_tests += g.shape_tests;
    if (c->caustic_scratch) {
        work_counts w = {0};
        est_scratch_work(c->caustic_scratch, threads, &w);
        st->caustic_nodes = w.map_nodes;
        st->caustic_points = w.map_points;
    }
}

pm_status eye_render(const eye_input *in, unsigned threads, int show_progress, image *out, stats_run *st)
{
    const config_render *cfg = in->cfg;
    assert(threads >= 1 && (cfg->method != CONFIG_METHOD_PRECOMPUTED || in->reps));
    eye_ctx c;
    memset(&c, 0, sizeof c);
    c.sc = in->sc;
    c.cfg = cfg;
    c.map = in->map;
    c.reps = in->reps;
    c.gather = est_gather_make(in->map, cfg->nn, in->max_radius, cfg->bias_correction);
    c.camera = camera_make(in->sc, (double)cfg->height / (double)cfg->width);
    c.light_intensity = vec_scale(in->sc->light.power, 1.0 / (4.0 * VEC_PI));
    c.img = out;
    c.tiles_x = (cfg->width + EYE_TILE - 1) / EYE_TILE;
    uint64_t tiles = (uint64_t)c.tiles_x * ((cfg->height + EYE_TILE - 1) / EYE_TILE);
    c.scratch = est_scratch_new(threads, cfg->nn);
    c.counts = calloc(threads, sizeof(eye_counts));
    pm_status rc = (!c.scratch || !c.counts) ? PM_ERR_NOMEM : PM_OK;
    if (rc == PM_OK && cfg->gather > 0) {
        c.gp = gather_params_make(in->sc, cfg, in->map, in->reps, in->caustic, in->max_radius);
        c.gcounts = calloc(threads, sizeof(eye_gather_counts));
        if (in->caustic)
            c.caustic_scratch = est_scratch_new(threads, cfg->nn);
        rc = (!c.gcounts || (in->caustic && !c.caustic_scratch)) ? PM_ERR_NOMEM : PM_OK;
    }
    if (rc == PM_OK)
        rc = image_init(out, cfg->width, cfg->height);
    if (rc == PM_OK) {
        progress prog;
        progress_begin(&prog, "render", tiles, show_progress);
        c.prog = &prog;
        int64_t t0 = clock_now_ns();
        parallel_for(threads, tiles, eye_tile, &c);
        st->render = (double)(clock_now_ns() - t0) * 1e-9;
        progress_end(&prog);
        for (unsigned t = 0; t < threads; t++) {
            st->samples += c.counts[t].samples;
            st->eye_depth_limit_hits += c.counts[t].depth_hits;
            st->empty_estimates += c.counts[t].empty;
            st->underflow_pixels += c.counts[t].underflow;
            st->flushed_values += c.counts[t].flushed;
            st->peak_radiance = fmax(st->peak_radiance, c.counts[t].peak);
            st->rep_fallbacks += c.counts[t].fallbacks;
            st->work.render.rays += c.counts[t].rays;
            st->work.render.shape_tests += c.counts[t].shape_tests;
        }
        est_scratch_work(c.scratch, threads, &st->work.render);
        if (c.gcounts)
            add_gather_counts(&c, threads, st);
        st->nonfinite_pixels = image_count_nonfinite(out);
        image_mean(out, st->mean_radiance);
    }
    est_scratch_delete(c.scratch, threads);
    est_scratch_delete(c.caustic_scratch, threads);
    free(c.counts);
    free(c.gcounts);
    return rc;
}

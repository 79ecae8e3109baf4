/* photons: the photon pass. Photons are traced in fixed chunks of indices,
 * each chunk into its own buffer, and the buffers are joined in chunk order,
 * so the stored list does not depend on the thread count. */
#include "photons.h"

#include <assert.h>
#include <stdlib.h>
#include <string.h>

#include "material.h"
#include "parallel.h"
#include "rng.h"

#define PHOTON_CHUNK 4096u

void photon_pack_dir(double x, double y, double z, int8_t out[3])
{
    out[0] = (int8_t)lrint(fmax(-1.0, fmin(1.0, x)) * 127.0);
    out[1] = (int8_t)lrint(fmax(-1.0, fmin(1.0, y)) * 127.0);
    out[2] = (int8_t)lrint(fmax(-1.0, fmin(1.0, z)) * 127.0);
}

vec3 photon_unpack_dir(const int8_t d[3])
{
    return vec_make(d[0] / 127.0, d[1] / 127.0, d[2] / 127.0);
}

typedef struct {
    uint64_t count, cap;
    float *pos;
    photon *ph;
    uint64_t truncated, escaped;
    int failed;
} photon_chunk;

typedef struct {
    const scene *sc;
    const render_config *cfg;
    double eps;   /* scene_epsilon(sc) */
    vec3 power;   /* each emitted photon's power: light power / cfg->photons */
    photon_chunk *chunks;
    progress *prog;
} trace_ctx;

static int chunk_store(photon_chunk *c, vec3 p, vec3 dir, vec3 power, vec3 n, unsigned flags)
{
    if (c->count == c->cap) {
        uint64_t nc = c->cap ? c->cap * 2 : PHOTON_CHUNK;
        float *np = realloc(c->pos, nc * 3 * sizeof(float));
        if (!np)
            return -1;
        c->pos = np;
        photon *nph = realloc(c->ph, nc * sizeof(photon));
        if (!nph)
            return -1;
        c->ph = nph;
        c->cap = nc;
    }
    float *q = c->pos + 3 * c->count;
    q[0] = (float)p.x;
    q[1] = (float)p.y;
    q[2] = (float)p.z;
    photon *ph = &c->ph[c->count];
    ph->power[0] = (float)power.x;
    ph->power[1] = (float)power.y;
    ph->power[2] = (float)power.z;
    photon_pack_dir(dir.x, dir.y, dir.z, ph->dir);
    photon_pack_dir(n.x, n.y, n.z, ph->normal);
    ph->flags = (uint8_t)flags;
    ph->pad = 0;
    c->count++;
    return 0;
}

/* Traces photon `index` into chunk c. Returns -1 when memory runs out. */
static int trace_one(const trace_ctx *tc, uint64_t index, photon_chunk *c)
{
    const scene *sc = tc->sc;
    const render_config *cfg = tc->cfg;
    rng_stream rs = rng_make(cfg->seed, index);
    double eps = tc->eps;
    /* isotropic emission */
    double u1 = rng_next_double(&rs), u2 = rng_next_double(&rs);
    double z = 1.0 - 2.0 * u1, s = sqrt(fmax(0.0, 1.0 - z * z)), phi = 2.0 * VEC_PI * u2;
    ray r = {sc->light.position, vec_make(s * cos(phi), s * sin(phi), z)};
    vec3 power = tc->power;
    unsigned bounces = 0;
    for (uint32_t depth = 0;; depth++) {
        if (depth >= cfg->photon_depth) {
            c->truncated++;
            return 0;
        }
        double t;
        int hit = scene_intersect(sc, &r, eps, INFINITY, &t);
        if (hit < 0) {
            c->escaped++;
            return 0;
        }
        const shape *sh = &sc->shapes[hit];
        const material *m = &sc->materials[sh->material];
        vec3 p = vec_madd(r.origin, r.dir, t);
        vec3 ng = shape_normal(sh, p);
        int front = vec_dot(ng, r.dir) < 0.0;
        vec3 n = front ? ng : vec_neg(ng); /* faces where the photon came from */
        if (m->kind == MAT_LAMBERT) {
            if (!(cfg->direct == DIRECT_SHADOW_RAYS && bounces == 0)) {
                if (chunk_store(c, p, r.dir, power, n, bounces == 0 ? PHOTON_FLAG_DIRECT : 0))
                    return -1;
            }
            double pc = vec_maxc(m->color);
            if (!(rng_next_double(&rs) < pc))
                return 0;
            power = vec_scale(vec_mul(power, m->color), 1.0 / pc);
            double v1 = rng_next_double(&rs), v2 = rng_next_double(&rs);
            r.dir = material_sample_cosine(n, v1, v2);
            r.origin = vec_madd(p, n, eps);
        } else if (m->kind == MAT_MIRROR) {
            power = vec_mul(power, m->color);
            if (vec_maxc(power) <= 0.0)
                return 0;
            r.dir = material_reflect(r.dir, n);
            r.origin = vec_madd(p, n, eps);
        } else {
            double n1 = front ? 1.0 : m->ior, n2 = front ? m->ior : 1.0;
            double cos_i = -vec_dot(r.dir, n);
            double fr = material_fresnel(cos_i, n1, n2);
            vec3 refr;
            if (rng_next_double(&rs) < fr || !material_refract(r.dir, n, n1 / n2, &refr)) {
                r.dir = material_reflect(r.dir, n);
                r.origin = vec_madd(p, n, eps);
            } else {
                r.dir = refr;
                r.origin = vec_madd(p, n, -eps);
            }
        }
        bounces++;
    }
}

static void trace_chunk(uint64_t chunk, unsigned thread, void *arg)
{
    (void)thread;
    trace_ctx *tc = arg;
    photon_chunk *c = &tc->chunks[chunk];
    uint64_t lo = chunk * PHOTON_CHUNK;
    uint64_t hi = lo + PHOTON_CHUNK < tc->cfg->photons ? lo + PHOTON_CHUNK : tc->cfg->photons;
    for (uint64_t i = lo; i < hi && !c->failed; i++) {
        if (trace_one(tc, i, c))
            c->failed = 1;
    }
    progress_add(tc->prog, hi - lo);
}

int photons_trace(const scene *sc, const render_config *cfg, unsigned threads, progress *prog, photon_list *out)
{
    memset(out, 0, sizeof *out);
    uint64_t nchunks = (cfg->photons + PHOTON_CHUNK - 1) / PHOTON_CHUNK;
    photon_chunk *chunks = calloc(nchunks ? nchunks : 1, sizeof(photon_chunk));
    if (!chunks)
        return -1;
    vec3 power = cfg->photons ? vec_scale(sc->light.power, 1.0 / (double)cfg->photons) : vec_make(0, 0, 0);
    trace_ctx tc = {sc, cfg, scene_epsilon(sc), power, chunks, prog};
    parallel_for(threads, nchunks, trace_chunk, &tc);
    int failed = 0;
    uint64_t total = 0;
    for (uint64_t i = 0; i < nchunks; i++) {
        failed |= chunks[i].failed;
        total += chunks[i].count;
        out->truncated += chunks[i].truncated;
        out->escaped += chunks[i].escaped;
    }
    if (!failed) {
        out->pos = malloc((total ? total : 1) * 3 * sizeof(float));
        out->ph = malloc((total ? total : 1) * sizeof(photon));
        failed = !out->pos || !out->ph;
    }
    uint64_t at = 0;
    for (uint64_t i = 0; i < nchunks; i++) {
        if (!failed && chunks[i].count) {
            memcpy(out->pos + 3 * at, chunks[i].pos, chunks[i].count * 3 * sizeof(float));
            memcpy(out->ph + at, chunks[i].ph, chunks[i].count * sizeof(photon));
            at += chunks[i].count;
        }
        free(chunks[i].pos);
        free(chunks[i].ph);
    }
    free(chunks);
    if (failed) {
        photons_list_free(out);
        return -1;
    }
    out->count = total;
    if (cfg->method == METHOD_PRECOMPUTED && cfg->rep_every > 0) {
        for (uint64_t i = 0; i < total; i += cfg->rep_every)
            out->ph[i].flags |= PHOTON_FLAG_REP;
    }
    return 0;
}

void photons_list_free(photon_list *l)
{
    free(l->pos);
    free(l->ph);
    memset(l, 0, sizeof *l);
}

int photons_build_map(photon_list *l, photon_map *m)
{
    memset(m, 0, sizeof *m);
    if (l->count > UINT32_MAX - 1) {
        photons_list_free(l);
        return -1;
    }
    uint32_t n = (uint32_t)l->count;
    uint32_t *perm = malloc(sizeof(uint32_t) * (n ? n : 1));
    m->ph = malloc(sizeof(photon) * (n ? n : 1));
    if (!perm || !m->ph || kd_build(&m->tree, l->pos, n, KD_DEFAULT_LEAF, perm)) {
        free(perm);
        photons_list_free(l);
        photons_map_free(m);
        return -1;
    }
    for (uint32_t i = 0; i < n; i++) {
        m->ph[i] = l->ph[perm[i]];
        m->reps += (m->ph[i].flags & PHOTON_FLAG_REP) != 0;
    }
    m->count = n;
    free(perm);
    photons_list_free(l);
    return 0;
}

void photons_map_free(photon_map *m)
{
    kd_free(&m->tree);
    free(m->ph);
    memset(m, 0, sizeof *m);
}

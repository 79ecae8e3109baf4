/* estimate: conventional kNN irradiance, the representatives' precompute and
 * their lookup. Both estimates share est_irradiance (kNN + front-side test). */
#include "estimate.h"

#include <assert.h>
#include <stdlib.h>
#include <string.h>

#include "parallel.h"

#define EST_CHUNK 1024u

int est_scratch_init(est_scratch *s, uint32_t nn)
{
    s->cap = nn ? nn : 1;
    s->idx = malloc(sizeof(uint32_t) * s->cap);
    s->d2 = malloc(sizeof(float) * s->cap);
    if (!s->idx || !s->d2) {
        est_scratch_free(s);
        return -1;
    }
    return 0;
}

void est_scratch_free(est_scratch *s)
{
    free(s->idx);
    free(s->d2);
    memset(s, 0, sizeof *s);
}

vec3 est_irradiance(const photon_map *m, vec3 x, vec3 n, uint32_t nn, double max_r2, est_scratch *s,
                    uint32_t *found)
{
    assert(nn <= s->cap);
    float q[3] = {(float)x.x, (float)x.y, (float)x.z};
    float r2f;
    uint32_t k = kd_knn(&m->tree, q, nn, (float)max_r2, s->idx, s->d2, &r2f);
    *found = k;
    if (k == 0)
        return vec_make(0, 0, 0);
    double sum[3] = {0, 0, 0};
    for (uint32_t j = 0; j < k; j++) {
        const photon *p = &m->ph[s->idx[j]];
        if (p->dir[0] * n.x + p->dir[1] * n.y + p->dir[2] * n.z < 0.0) {
            sum[0] += p->power[0];
            sum[1] += p->power[1];
            sum[2] += p->power[2];
        }
    }
    double r2 = k < nn ? max_r2 : (double)r2f;
    double floor2 = max_r2 * (EST_MIN_RADIUS_FRAC * EST_MIN_RADIUS_FRAC);
    if (r2 < floor2)
        r2 = floor2;
    double inv = 1.0 / (VEC_PI * r2);
    return vec_make(sum[0] * inv, sum[1] * inv, sum[2] * inv);
}

typedef struct {
    const photon_map *m;
    uint32_t nn;
    double max_r2;
    const uint32_t *rep_photon; /* rep index -> photon index */
    est_rep *rep;               /* by rep index */
    uint32_t count;
    est_scratch *scratch;       /* one per thread */
    progress *prog;
} precompute_ctx;

static void precompute_chunk(uint64_t chunk, unsigned thread, void *arg)
{
    precompute_ctx *c = arg;
    uint32_t lo = (uint32_t)chunk * EST_CHUNK;
    uint32_t hi = lo + EST_CHUNK < c->count ? lo + EST_CHUNK : c->count;
    for (uint32_t i = lo; i < hi; i++) {
        uint32_t pi = c->rep_photon[i];
        const photon *p = &c->m->ph[pi];
        vec3 x = vec_make(c->m->tree.x[pi], c->m->tree.y[pi], c->m->tree.z[pi]);
        vec3 n = vec_norm(photon_unpack_dir(p->normal));
        uint32_t found;
        vec3 e = est_irradiance(c->m, x, n, c->nn, c->max_r2, &c->scratch[thread], &found);
        est_rep *r = &c->rep[i];
        r->irradiance[0] = (float)e.x;
        r->irradiance[1] = (float)e.y;
        r->irradiance[2] = (float)e.z;
        r->normal[0] = (float)n.x;
        r->normal[1] = (float)n.y;
        r->normal[2] = (float)n.z;
    }
    progress_add(c->prog, hi - lo);
}

int est_precompute(const photon_map *m, uint32_t nn, double max_r2, est_rep_layout layout, unsigned threads,
                   progress *prog, est_reps *out)
{
    memset(out, 0, sizeof *out);
    out->layout = layout;
    unsigned nt = threads ? threads : 1; /* scratch buffers, one per worker */
    uint32_t count = m->reps;
    uint32_t *rep_photon = malloc(sizeof(uint32_t) * (count ? count : 1));
    est_rep *rep = malloc(sizeof(est_rep) * (count ? count : 1));
    est_scratch *scratch = calloc(nt, sizeof(est_scratch));
    int rc = (!rep_photon || !rep || !scratch) ? -1 : 0;
    for (unsigned t = 0; rc == 0 && t < nt; t++)
        rc = est_scratch_init(&scratch[t], nn);
    if (rc == 0) {
        uint32_t j = 0;
        for (uint32_t i = 0; i < m->count; i++)
            if (m->ph[i].flags & PHOTON_FLAG_REP)
                rep_photon[j++] = i;
        assert(j == count);
        precompute_ctx c = {m, nn, max_r2, rep_photon, rep, count, scratch, prog};
        parallel_for(threads, (count + EST_CHUNK - 1) / EST_CHUNK, precompute_chunk, &c);
    }
    if (rc == 0 && layout == EST_REPS_SEPARATE) {
        float *pos = malloc(sizeof(float) * 3 * (count ? count : 1));
        uint32_t *perm = malloc(sizeof(uint32_t) * (count ? count : 1));
        est_rep *ordered = malloc(sizeof(est_rep) * (count ? count : 1));
        rc = (!pos || !perm || !ordered) ? -1 : 0;
        if (rc == 0) {
            for (uint32_t i = 0; i < count; i++) {
                uint32_t pi = rep_photon[i];
                pos[3 * i] = m->tree.x[pi];
                pos[3 * i + 1] = m->tree.y[pi];
                pos[3 * i + 2] = m->tree.z[pi];
            }
            rc = kd_build(&out->tree, pos, count, KD_DEFAULT_LEAF, perm);
        }
        if (rc == 0) {
            for (uint32_t i = 0; i < count; i++)
                ordered[i] = rep[perm[i]];
            free(rep);
            rep = ordered;
            ordered = NULL;
        }
        free(pos);
        free(perm);
        free(ordered);
    } else if (rc == 0) {
        out->rep_of = malloc(sizeof(uint32_t) * (m->count ? m->count : 1));
        if (!out->rep_of) {
            rc = -1;
        } else {
            for (uint32_t i = 0; i < m->count; i++)
                out->rep_of[i] = KD_NONE;
            for (uint32_t i = 0; i < count; i++)
                out->rep_of[rep_photon[i]] = i;
        }
    }
    if (scratch)
        for (unsigned t = 0; t < nt; t++)
            est_scratch_free(&scratch[t]);
    free(scratch);
    free(rep_photon);
    out->rep = rep;
    out->count = count;
    if (rc != 0)
        est_reps_free(out);
    return rc;
}

typedef struct {
    const est_reps *r;
    vec3 n;
    double cos_min;
} lookup_ctx;

static int agrees(const est_rep *rep, const lookup_ctx *c)
{
    return rep->normal[0] * c->n.x + rep->normal[1] * c->n.y + rep->normal[2] * c->n.z > c->cos_min;
}

static int pred_separate(uint32_t i, const void *arg)
{
    const lookup_ctx *c = arg;
    return agrees(&c->r->rep[i], c);
}

static int pred_shared(uint32_t i, const void *arg)
{
    const lookup_ctx *c = arg;
    uint32_t j = c->r->rep_of[i];
    return j != KD_NONE && agrees(&c->r->rep[j], c);
}

vec3 est_lookup(const est_reps *r, const photon_map *m, vec3 x, vec3 n, double cos_min, double max_r2, int *found)
{
    float q[3] = {(float)x.x, (float)x.y, (float)x.z};
    float d2;
    lookup_ctx c = {r, n, cos_min};
    const est_rep *rep = NULL;
    if (r->layout == EST_REPS_SEPARATE) {
        uint32_t i = kd_nearest_if(&r->tree, q, (float)max_r2, pred_separate, &c, &d2);
        if (i != KD_NONE)
            rep = &r->rep[i];
    } else {
        uint32_t i = kd_nearest_if(&m->tree, q, (float)max_r2, pred_shared, &c, &d2);
        if (i != KD_NONE)
            rep = &r->rep[r->rep_of[i]];
    }
    *found = rep != NULL;
    if (!rep)
        return vec_make(0, 0, 0);
    return vec_make(rep->irradiance[0], rep->irradiance[1], rep->irradiance[2]);
}

size_t est_reps_bytes(const est_reps *r, const photon_map *m)
{
    size_t b = (size_t)r->count * sizeof(est_rep);
    if (r->layout == EST_REPS_SEPARATE)
        b += kd_bytes(&r->tree);
    else
        b += (size_t)m->count * sizeof(uint32_t);
    return b;
}

void est_reps_free(est_reps *r)
{
    kd_free(&r->tree);
    free(r->rep);
    free(r->rep_of);
    memset(r, 0, sizeof *r);
}

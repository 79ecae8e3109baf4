/* estimate: conventional kNN irradiance, the representatives' precompute and
 * their lookup. Both estimates share irradiance_at (kNN + front-side test). */
#include "estimate.h"

#include <assert.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "parallel.h"

#define EST_CHUNK 1024u
/* extra entries per thread buffer, so that two threads' buffers never share
 * a cache line */
#define EST_SCRATCH_SLACK 16u

est_scratch *est_scratch_new(unsigned threads, uint32_t nn)
{
    assert(threads >= 1);
    est_scratch *s = calloc(threads, sizeof(est_scratch));
    if (!s)
        return NULL;
    for (unsigned t = 0; t < threads; t++) {
        s[t].cap = nn ? nn : 1;
        s[t].last_rep = KD_NONE;
        s[t].idx = malloc(sizeof(uint32_t) * (s[t].cap + EST_SCRATCH_SLACK));
        s[t].d2 = malloc(sizeof(float) * (s[t].cap + EST_SCRATCH_SLACK));
        if (!s[t].idx || !s[t].d2 || kd_query_init(&s[t].query, s[t].cap)) {
            est_scratch_delete(s, threads);
            return NULL;
        }
    }
    return s;
}

void est_scratch_delete(est_scratch *s, unsigned threads)
{
    if (!s)
        return;
    for (unsigned t = 0; t < threads; t++) {
        free(s[t].idx);
        free(s[t].d2);
        kd_query_free(&s[t].query);
    }
    free(s);
}

est_gather est_gather_make(const photons_map *m, uint32_t nn, double max_radius, int corrected)
{
    double r = max_radius / m->scale;
    est_gather g = {nn, r * r, corrected, m->count > 0 ? (double)m->stored / (double)m->count : 1.0};
    return g;
}

/* Irradiance at map point q for unit normal n, relative to
 * m->unit / m->scale^2 (the estimate of eq. 1 in the map's units). */
static vec3 irradiance_at(const photons_map *m, const float q[3], vec3 n, const est_gather *g, est_scratch *s,
                          uint32_t *found)
{
    assert(g->nn <= s->cap);
    float r2f;
    uint32_t k = kd_query_knn(&m->tree, &s->query, q, g->nn, (float)g->max_r2, s->idx, s->d2, &r2f);
    *found = k;
    if (k == 0)
        return vec_make(0, 0, 0);
    /* the paper counts all k; the corrected estimate only those strictly
     * inside the radius r that the n-th photon (or the cap) defines */
    float inside = g->corrected ? (k < g->nn ? (float)g->max_r2 : r2f) : INFINITY;
    double sum[3] = {0, 0, 0};
    for (uint32_t j = 0; j < k; j++) {
        const photons_record *p = &m->ph[s->idx[j]];
        if (p->dir[0] * n.x + p->dir[1] * n.y + p->dir[2] * n.z < 0.0 && s->d2[j] < inside) {
            sum[0] += p->power[0];
            sum[1] += p->power[1];
            sum[2] += p->power[2];
        }
    }
    double r2 = k < g->nn ? g->max_r2 : (double)r2f;
    double floor2 = g->max_r2 * (EST_MIN_RADIUS_FRAC * EST_MIN_RADIUS_FRAC);
    if (r2 < floor2)
        r2 = floor2;
    double inv = g->boost / (VEC_PI * r2);
    return vec_make(sum[0] * inv, sum[1] * inv, sum[2] * inv);
}

/* The factor from irradiance in map units to W per scene unit^2. */
static vec3 world_factor(const photons_map *m)
{
    return vec_scale(m->unit, 1.0 / (m->scale * m->scale));
}

vec3 est_irradiance(const photons_map *m, vec3 x, vec3 n, const est_gather *g, est_scratch *s, uint32_t *found)
{
    float q[3];
    photons_map_point(m, x, q);
    return vec_mul(irradiance_at(m, q, n, g, s, found), world_factor(m));
}

typedef struct {
    const photons_map *m;
    const est_gather *g;
    const uint32_t *order; /* rep index i -> index into m->rep */
    est_rep *rep;          /* by rep index */
    uint32_t count;
    est_scratch *scratch;  /* one per thread */
    progress *prog;
} precompute_ctx;

static void precompute_chunk(uint64_t chunk, unsigned thread, void *arg)
{
    precompute_ctx *c = arg;
    uint32_t lo = (uint32_t)chunk * EST_CHUNK;
    uint32_t hi = lo + EST_CHUNK < c->count ? lo + EST_CHUNK : c->count;
    for (uint32_t i = lo; i < hi; i++) {
        const photons_rep *rp = &c->m->rep[c->order ? c->order[i] : i];
        vec3 n = vec_norm(photons_unpack_dir(rp->normal));
        uint32_t found;
        vec3 e = irradiance_at(c->m, rp->pos, n, c->g, &c->scratch[thread], &found);
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

int est_precompute(const photons_map *m, const est_gather *g, est_rep_layout layout, unsigned threads,
                   progress *prog, est_reps *out)
{
    memset(out, 0, sizeof *out);
    out->layout = layout;
    unsigned nt = threads ? threads : 1;
    uint32_t count = m->reps;
    uint32_t *order = NULL;
    out->rep = malloc(sizeof(est_rep) * (count ? count : 1));
    est_scratch *scratch = est_scratch_new(nt, g->nn);
    int rc = (!out->rep || !scratch) ? -1 : 0;
    if (rc == 0 && layout == EST_REPS_SEPARATE) {
        /* the representatives' own tree first: the precompute then runs in
         * its leaf order (nearby queries in a row) and stores in that order */
        float *pos = malloc(sizeof(float) * 3 * (count ? count : 1));
        order = malloc(sizeof(uint32_t) * (count ? count : 1));
        rc = (!pos || !order) ? -1 : 0;
        if (rc == 0) {
            for (uint32_t i = 0; i < count; i++)
                memcpy(pos + 3 * (size_t)i, m->rep[i].pos, 3 * sizeof(float));
            rc = kd_build(&out->tree, pos, count, KD_DEFAULT_LEAF, order);
        }
        free(pos);
    } else if (rc == 0) {
        out->rep_of = malloc(sizeof(uint32_t) * (m->count ? m->count : 1));
        rc = out->rep_of ? 0 : -1;
        if (rc == 0) {
            for (uint32_t i = 0; i < m->count; i++)
                out->rep_of[i] = KD_NONE;
            for (uint32_t i = 0; i < count; i++) {
                assert(m->rep[i].tree_index != KD_NONE);
                out->rep_of[m->rep[i].tree_index] = i;
            }
        }
    }
    if (rc == 0) {
        precompute_ctx c = {m, g, order, out->rep, count, scratch, prog};
        parallel_for(threads, (count + EST_CHUNK - 1) / EST_CHUNK, precompute_chunk, &c);
        out->count = count;
    }
    free(order);
    est_scratch_delete(scratch, nt);
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

vec3 est_lookup(const est_reps *r, const photons_map *m, vec3 x, vec3 n, double cos_min, const est_gather *g,
                est_scratch *s, int *found)
{
    float max_r2 = (float)g->max_r2;
    float q[3], d2;
    photons_map_point(m, x, q);
    lookup_ctx c = {r, n, cos_min};
    const est_rep *rep = NULL;
    if (r->layout == EST_REPS_SEPARATE) {
        uint32_t i = kd_nearest_if(&r->tree, q, max_r2, pred_separate, &c, s->last_rep, &d2);
        if (i != KD_NONE)
            rep = &r->rep[i];
        s->last_rep = i;
    } else {
        uint32_t i = kd_nearest_if(&m->tree, q, max_r2, pred_shared, &c, s->last_rep, &d2);
        if (i != KD_NONE)
            rep = &r->rep[r->rep_of[i]];
        s->last_rep = i;
    }
    *found = rep != NULL;
    if (!rep)
        return vec_make(0, 0, 0);
    return vec_mul(vec_make(rep->irradiance[0], rep->irradiance[1], rep->irradiance[2]), world_factor(m));
}

int est_reps_write_csv(const est_reps *r, const photons_map *m, FILE *f)
{
    vec3 wf = world_factor(m);
    fputs("x,y,z,nx,ny,nz,e_r,e_g,e_b\n", f);
    for (uint32_t i = 0; i < r->count; i++) {
        /* where representative i sits in the map frame: its own tree's leaf
         * i (separate layout) or the map's representative i (shared) */
        float q[3];
        if (r->layout == EST_REPS_SEPARATE) {
            kd_point(&r->tree, i, q);
        } else {
            memcpy(q, m->rep[i].pos, sizeof q);
        }
        const est_rep *e = &r->rep[i];
        fprintf(f, "%.9g,%.9g,%.9g,%.6f,%.6f,%.6f,%.9g,%.9g,%.9g\n", m->centre.x + m->scale * q[0],
                m->centre.y + m->scale * q[1], m->centre.z + m->scale * q[2], e->normal[0], e->normal[1],
                e->normal[2], e->irradiance[0] * wf.x, e->irradiance[1] * wf.y, e->irradiance[2] * wf.z);
    }
    return ferror(f) ? -1 : 0;
}

size_t est_reps_bytes(const est_reps *r, const photons_map *m)
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

/* estimate: equation 1 (kNN + front-side test), the one gather that the
 * conventional estimate and the representatives' precompute share. */
#include "estimate.h"

#include <assert.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

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
        if (!s[t].idx || !s[t].d2 || kd_query_init(&s[t].query, s[t].cap) != PM_OK) {
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

void est_scratch_forget(est_scratch *s)
{
    kd_query_forget(&s->query);
    s->last_rep = KD_NONE;
}

void est_scratch_work(const est_scratch *s, unsigned threads, work_counts *w)
{
    for (unsigned t = 0; t < threads; t++) {
        w->knn_queries += s[t].query.queries;
        w->map_nodes += s[t].query.work.nodes;
        w->map_points += s[t].query.work.points;
        w->rep_lookups += s[t].rep_lookups;
        w->rep_nodes += s[t].rep_work.nodes;
        w->rep_points += s[t].rep_work.points;
        w->rep_evaluations += s[t].rep_evaluations;
    }
}

est_gather est_gather_make(const photons_map *m, uint32_t nn, double max_radius, int bias_correction)
{
    double r = max_radius / m->scale;
    /* the floor's reference: the cap, or the photons' extent when smaller
     * (the same product as the cap's square, so a cap within the extent
     * gives the floor bit for bit as it always did) */
    double f = (m->extent > 0.0 && m->extent < max_radius ? m->extent : max_radius) / m->scale;
    est_gather g = {nn, r * r, f * f * (EST_MIN_RADIUS_FRAC * EST_MIN_RADIUS_FRAC), bias_correction,
                    m->count > 0 ? (double)m->stored / (double)m->count : 1.0};
    return g;
}

double est_surface_height(vec3 d, vec3 n, vec3 nj)
{
    vec3 m = vec_add(n, vec_norm(nj));
    double len2 = vec_len2(m);
    if (!(len2 > 1e-12))
        return INFINITY; /* opposite normals: no common surface */
    return fabs(vec_dot(d, m)) / sqrt(len2);
}

/* The gather of est_irradiance_at and est_irradiance_plane_at; inlined
 * into both, so the plain estimate keeps no test in its loop. */
static inline vec3 irradiance_core(const photons_map *m, const float q[3], vec3 n, const est_gather *g, double rep_gate_tau,
                                   est_scratch *s, uint32_t *found, double *r2_out)
{
    assert(g->nn <= s->cap);
    float r2f;
    uint32_t k = kd_query_knn(&m->tree, &s->query, q, g->nn, (float)g->max_r2, s->idx, s->d2, &r2f);
    *found = k;
    double r2 = k < g->nn ? g->max_r2 : (double)r2f;
    if (r2 < g->min_r2)
        r2 = g->min_r2;
    *r2_out = r2;
    if (k == 0)
        return vec_make(0, 0, 0);
    /* the paper counts all k; --bias-correction only those strictly
     * inside the radius r that the n-th photon (or the cap) defines */
    float inside = g->bias_correction ? (k < g->nn ? (float)g->max_r2 : r2f) : INFINITY;
    double plane = rep_gate_tau > 0.0 ? rep_gate_tau * sqrt(r2) : 0.0;
    double sum[3] = {0, 0, 0};
    for (uint32_t j = 0; j < k; j++) {
        const photons_record *p = &m->ph[s->idx[j]];
        if (p->dir[0] * n.x + p->dir[1] * n.y + p->dir[2] * n.z < 0.0 && s->d2[j] < inside) {
            if (rep_gate_tau > 0.0) {
                float pt[3];
                kd_point(&m->tree, s->idx[j], pt);
                vec3 d = vec_make((double)pt[0] - q[0], (double)pt[1] - q[1], (double)pt[2] - q[2]);
                if (!(est_surface_height(d, n, photons_unpack_dir(p->normal)) <= plane))
                    continue;
            }
            sum[0] += p->power[0];
            sum[1] += p->power[1];
            sum[2] += p->power[2];
        }
    }
    double inv = g->boost / (VEC_PI * r2);
    return vec_make(sum[0] * inv, sum[1] * inv, sum[2] * inv);
}

vec3 est_irradiance_at(const photons_map *m, const float q[3], vec3 n, const est_gather *g, est_scratch *s,
                       uint32_t *found)
{
    double r2;
    return irradiance_core(m, q, n, g, 0.0, s, found, &r2);
}

vec3 est_irradiance_plane_at(const photons_map *m, const float q[3], vec3 n, const est_gather *g, double rep_gate_tau,
                             est_scratch *s, uint32_t *found, double *r2)
{
    return irradiance_core(m, q, n, g, rep_gate_tau, s, found, r2);
}

vec3 est_world_factor(const photons_map *m)
{
    return vec_scale(m->unit, 1.0 / (m->scale * m->scale));
}

vec3 est_irradiance(const photons_map *m, vec3 x, vec3 n, const est_gather *g, est_scratch *s, uint32_t *found)
{
    float q[3];
    photons_map_point(m, x, q);
    return vec_mul(est_irradiance_at(m, q, n, g, s, found), est_world_factor(m));
}


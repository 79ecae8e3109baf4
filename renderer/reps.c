/* reps: the representatives' rule, leave-out mask, sites, layouts,
 * precompute, lookup and CSV form (reps.h). */
#include "reps.h"

#include <assert.h>
#include <math.h>
#include <sched.h>
#include <stdlib.h>
#include <string.h>

#include "mem.h"
#include "parallel.h"

#define REPS_CHUNK 1024u

reps_params reps_params_of(const config_render *cfg)
{
    int pre = cfg->method == CONFIG_METHOD_PRECOMPUTED;
    reps_params p;
    p.rep_every = pre ? cfg->rep_every : 0;
    p.rep_count = pre ? cfg->rep_count : 0;
    p.rep_tree = cfg->rep_tree;
    p.bias_correction = pre && cfg->bias_correction;
    p.rep_eval = cfg->rep_eval;
    p.rep_gate = cfg->rep_gate;
    p.rep_gate_tau = cfg->rep_gate_tau;
    p.normal_cos = cfg->normal_cos;
    return p;
}

pm_status reps_check_stored(const config_render *cfg, uint64_t stored, char *err, size_t errlen)
{
    /* config_check refuses --rep-every 1 up front; the count's share of the
     * stored photons is known only after the photon pass */
    if (!(cfg->method == CONFIG_METHOD_PRECOMPUTED && cfg->bias_correction && cfg->rep_count > 0 && stored > 0 &&
          cfg->rep_count >= stored))
        return PM_OK;
    snprintf(err, errlen,
             "--rep-count %llu flags every one of the %llu stored photons, and --bias-correction estimates at "
             "representatives from the photons that are not: use a count below the stored photons",
             (unsigned long long)cfg->rep_count, (unsigned long long)stored);
    return PM_ERR_INPUT;
}

uint64_t reps_choose(const reps_params *p, photons_list *l)
{
    uint64_t total = l->count;
    if (p->rep_count > 0 && total > 0) {
        /* a fixed count, spread evenly over the trace order: photon
         * floor(j * total / count) = j * q + floor(j * r / count), which
         * cannot overflow (j * r < count^2 and count < 2^32) */
        uint64_t count = p->rep_count < total ? p->rep_count : total;
        uint64_t q = total / count, r = total % count;
        for (uint64_t j = 0; j < count; j++)
            l->ph[j * q + j * r / count].flags |= PHOTONS_FLAG_REP;
        return count;
    }
    if (p->rep_count == 0 && p->rep_every > 0) {
        for (uint64_t i = 0; i < total; i += p->rep_every)
            l->ph[i].flags |= PHOTONS_FLAG_REP;
        return (total + p->rep_every - 1) / p->rep_every;
    }
    return 0;
}

uint8_t reps_leave_out_mask(const reps_params *p)
{
    return p->bias_correction ? PHOTONS_FLAG_REP : 0;
}

pm_status reps_collect(const reps_params *p, const photons_map *m, const photons_list *left, reps_set *out)
{
    memset(out, 0, sizeof *out);
    out->rep_tree = p->rep_tree;
    out->rep_eval = p->rep_eval;
    out->rep_gate = p->rep_gate;
    out->rep_gate_tau = p->rep_gate_tau;
    out->normal_cos = p->normal_cos;
    uint32_t nin = 0, nleft = left ? (uint32_t)left->count : 0;
    for (uint32_t i = 0; i < m->count; i++)
        nin += (m->ph[i].flags & PHOTONS_FLAG_REP) != 0;
    out->site = mem_alloc(sizeof(reps_site) * (nin + nleft ? nin + nleft : 1));
    if (!out->site)
        return PM_ERR_NOMEM;
    uint32_t r = 0;
    /* those in the tree, in its leaf order */
    for (uint32_t i = 0; i < m->count; i++) {
        const photons_record *rec = &m->ph[i];
        if (rec->flags & PHOTONS_FLAG_REP) {
            reps_site *rp = &out->site[r++];
            kd_point(&m->tree, i, rp->pos);
            memcpy(rp->normal, rec->normal, 3);
            rp->pad = 0;
            rp->tree_index = i;
        }
    }
    /* those the map left out (reps_leave_out_mask), in trace order */
    for (uint32_t i = 0; i < nleft; i++) {
        assert(left->ph[i].flags & PHOTONS_FLAG_REP);
        reps_site *rp = &out->site[r++];
        vec3 x = vec_make(left->pos[3 * (size_t)i], left->pos[3 * (size_t)i + 1], left->pos[3 * (size_t)i + 2]);
        photons_map_point(m, x, rp->pos);
        memcpy(rp->normal, left->ph[i].normal, 3);
        rp->pad = 0;
        rp->tree_index = KD_NONE;
    }
    out->count = r;
    return PM_OK;
}

size_t reps_sites_bytes(const reps_set *r)
{
    return (size_t)r->count * sizeof(reps_site);
}

/* Equation 1 at representative site rp into v's irradiance and radius
 * (with the plane gate, counting only the photons near its tangent plane).
 * The eager precompute and the lazy lookup both call it, so the two give
 * the same bits. */
static void evaluate_value(const reps_set *r, const photons_map *m, const reps_site *rp, reps_value *v,
                           est_scratch *s)
{
    vec3 n = vec_norm(photons_unpack_dir(rp->normal));
    uint32_t found;
    double r2;
    double tau = r->rep_gate == CONFIG_REP_GATE_PLANE ? r->rep_gate_tau : 0.0;
    vec3 e = est_irradiance_plane_at(m, rp->pos, n, &r->gather, tau, s, &found, &r2);
    v->irradiance[0] = (float)e.x;
    v->irradiance[1] = (float)e.y;
    v->irradiance[2] = (float)e.z;
    v->radius2 = (float)r2;
}

typedef struct {
    const reps_set *r;
    const photons_map *m;
    const uint32_t *order; /* value index i -> site index (separate layout), or NULL: the same */
    est_scratch *scratch;  /* one per thread */
    progress *prog;
} evaluate_ctx;

static void evaluate_chunk(uint64_t chunk, unsigned thread, void *arg)
{
    evaluate_ctx *c = arg;
    const reps_set *r = c->r;
    uint32_t lo = (uint32_t)chunk * REPS_CHUNK;
    uint32_t hi = lo + REPS_CHUNK < r->count ? lo + REPS_CHUNK : r->count;
    /* a chunk's queries cost the same on any thread after any chunk */
    est_scratch_forget(&c->scratch[thread]);
    for (uint32_t i = lo; i < hi; i++) {
        const reps_site *rp = &r->site[c->order ? c->order[i] : i];
        reps_value *v = &r->value[i];
        /* the normal always now: the lookup's selection reads it */
        vec3 n = vec_norm(photons_unpack_dir(rp->normal));
        v->normal[0] = (float)n.x;
        v->normal[1] = (float)n.y;
        v->normal[2] = (float)n.z;
        if (r->rep_eval == CONFIG_REP_EVAL_EAGER) {
            evaluate_value(r, c->m, rp, v, &c->scratch[thread]);
            c->scratch[thread].rep_evaluations++;
        } else {
            v->irradiance[0] = v->irradiance[1] = v->irradiance[2] = 0.0f;
            v->radius2 = 0.0f;
            atomic_init(&r->state[i], REPS_PENDING);
        }
    }
    progress_add(c->prog, hi - lo);
}

/* Frees r's lookup layout and values, keeping its sites. */
static void free_values(reps_set *r)
{
    kd_free(&r->own);
    mem_free(r->value);
    mem_free(r->rep_of);
    mem_free((void *)r->state);
    mem_free(r->site_of);
    r->value = NULL;
    r->rep_of = NULL;
    r->state = NULL;
    r->site_of = NULL;
}

typedef struct {
    const reps_set *r;
    vec3 n;
} lookup_ctx;

static int agrees(const reps_value *v, const lookup_ctx *c)
{
    return v->normal[0] * c->n.x + v->normal[1] * c->n.y + v->normal[2] * c->n.z > c->r->normal_cos;
}

/* Another representative than `self` whose normal agrees. */
typedef struct {
    lookup_ctx c;
    uint32_t self;
} other_ctx;

static int pred_other(uint32_t i, const void *arg)
{
    const other_ctx *o = arg;
    return i != o->self && agrees(&o->c.r->value[i], &o->c);
}

static int cmp_float(const void *a, const void *b)
{
    float x = *(const float *)a, y = *(const float *)b;
    return (x > y) - (x < y);
}

/* Sets r->first_r2 (reps.h, REPS_FIRST_SCALE) from its separate tree and
 * values' normals, adding the searches' work to *work; 0 when it would not
 * be below max_r2. One thread, in a fixed order: the same for any thread
 * count. */
static pm_status first_radius2(reps_set *r, float max_r2, work_counts *work)
{
    r->first_r2 = 0.0f;
    if (r->count < 2)
        return PM_OK;
    uint32_t step = (r->count + REPS_FIRST_SAMPLES - 1) / REPS_FIRST_SAMPLES, k = 0;
    float *d2s = mem_alloc(sizeof(float) * ((r->count + step - 1) / step));
    if (!d2s)
        return PM_ERR_NOMEM;
    kd_work w = {0};
    for (uint32_t i = 0; i < r->count; i += step) {
        float p[3], d2;
        kd_point(&r->own, i, p);
        const float *nv = r->value[i].normal;
        other_ctx o = {{r, vec_make(nv[0], nv[1], nv[2])}, i};
        uint32_t j = kd_nearest_if_counted(&r->own, p, max_r2, pred_other, &o, KD_NONE, &d2, &w);
        d2s[k++] = j == KD_NONE ? max_r2 : d2;
    }
    qsort(d2s, k, sizeof(float), cmp_float);
    float f = REPS_FIRST_SCALE * d2s[(uint32_t)(REPS_FIRST_QUANTILE * (double)(k - 1))];
    mem_free(d2s);
    work->rep_nodes += w.nodes;
    work->rep_points += w.points;
    if (f < max_r2)
        r->first_r2 = f;
    return PM_OK;
}

pm_status reps_evaluate(reps_set *r, const photons_map *m, const est_gather *g, unsigned threads, progress *prog)
{
    unsigned nt = threads ? threads : 1;
    uint32_t count = r->count;
    uint32_t *order = NULL;
    r->gather = *g;
    r->value = mem_alloc(sizeof(reps_value) * (count ? count : 1));
    if (r->rep_eval == CONFIG_REP_EVAL_LAZY)
        r->state = mem_alloc(sizeof(atomic_uchar) * (count ? count : 1));
    est_scratch *scratch = est_scratch_new(nt, g->nn);
    pm_status rc = (!r->value || !scratch || (r->rep_eval == CONFIG_REP_EVAL_LAZY && !r->state)) ? PM_ERR_NOMEM : PM_OK;
    if (rc == PM_OK && r->rep_tree == CONFIG_REP_TREE_SEPARATE) {
        /* the representatives' own tree first: the precompute then runs in
         * its leaf order (nearby queries in a row) and stores in that order */
        float *pos = mem_alloc(sizeof(float) * 3 * (count ? count : 1));
        order = mem_alloc(sizeof(uint32_t) * (count ? count : 1));
        rc = (!pos || !order) ? PM_ERR_NOMEM : PM_OK;
        if (rc == PM_OK) {
            for (uint32_t i = 0; i < count; i++)
                memcpy(pos + 3 * (size_t)i, r->site[i].pos, 3 * sizeof(float));
            rc = kd_build(&r->own, pos, count, KD_DEFAULT_LEAF, order, nt);
        }
        mem_free(pos);
    } else if (rc == PM_OK) {
        r->rep_of = mem_alloc(sizeof(uint32_t) * (m->count ? m->count : 1));
        rc = r->rep_of ? PM_OK : PM_ERR_NOMEM;
        if (rc == PM_OK) {
            for (uint32_t i = 0; i < m->count; i++)
                r->rep_of[i] = KD_NONE;
            for (uint32_t i = 0; i < count; i++) {
                assert(r->site[i].tree_index != KD_NONE);
                r->rep_of[r->site[i].tree_index] = i;
            }
        }
    }
    if (rc == PM_OK) {
        /* eager: every representative's irradiance, now, before the eye
         * pass (the paper's precompute); lazy: the normals only */
        evaluate_ctx c = {r, m, order, scratch, prog};
        parallel_for(threads, (count + REPS_CHUNK - 1) / REPS_CHUNK, evaluate_chunk, &c);
    }
    if (rc == PM_OK) {
        memset(&r->work, 0, sizeof r->work);
        r->work.tree_points = r->rep_tree == CONFIG_REP_TREE_SEPARATE ? count : 0;
        est_scratch_work(scratch, nt, &r->work);
        r->first_r2 = 0.0f;
        if (r->rep_tree == CONFIG_REP_TREE_SEPARATE)
            rc = first_radius2(r, (float)g->max_r2, &r->work);
    }
    if (rc == PM_OK && r->rep_eval == CONFIG_REP_EVAL_LAZY) {
        r->site_of = order; /* the lookup finds a value's site by it */
        order = NULL;
    }
    mem_free(order);
    est_scratch_delete(scratch, nt);
    if (rc != PM_OK)
        free_values(r);
    return rc;
}

static int pred_separate(uint32_t i, const void *arg)
{
    const lookup_ctx *c = arg;
    return agrees(&c->r->value[i], c);
}

static int pred_shared(uint32_t i, const void *arg)
{
    const lookup_ctx *c = arg;
    uint32_t j = c->r->rep_of[i];
    return j != KD_NONE && agrees(&c->r->value[j], c);
}

/* Lazy: computes value i's irradiance with s's buffers, once, or waits
 * while another thread does; apart from the lookup's fast path. */
static __attribute__((noinline)) void lazy_evaluate(const reps_set *r, const photons_map *m, uint32_t i,
                                                    est_scratch *s)
{
    atomic_uchar *st = &r->state[i];
    unsigned char expect = REPS_PENDING;
    if (atomic_compare_exchange_strong_explicit(st, &expect, REPS_CLAIMED, memory_order_acq_rel,
                                                memory_order_acquire)) {
        const reps_site *rp = &r->site[r->site_of ? r->site_of[i] : i];
        /* the thread's own query stream keeps its starting radius */
        uint32_t hint_k = s->query.hint_k;
        float hint_r2 = s->query.hint_r2;
        evaluate_value(r, m, rp, &r->value[i], s);
        s->query.hint_k = hint_k;
        s->query.hint_r2 = hint_r2;
        s->rep_evaluations++;
        atomic_store_explicit(st, REPS_READY, memory_order_release);
    } else {
        /* another thread computes it: one kNN query, microseconds */
        while (atomic_load_explicit(st, memory_order_acquire) != REPS_READY)
            sched_yield();
    }
}

/* Value i of r, its irradiance computed: eager, as it is; lazy, computed
 * by the first thread that claims it (with s's buffers) while any other
 * waits for it to be published. */
static const reps_value *ready_value(const reps_set *r, const photons_map *m, uint32_t i, est_scratch *s)
{
    if (r->state && atomic_load_explicit(&r->state[i], memory_order_acquire) != REPS_READY)
        lazy_evaluate(r, m, i, s);
    return &r->value[i];
}

/* The plane gate: of the REPS_GATE_CANDIDATES representatives nearest to
 * map-frame point q (within the cap), in (distance, tree order), the first
 * whose normal agrees and whose height from q (est_surface_height: from
 * q's tangent plane where both normals agree exactly) is at most tau r, r
 * its kNN radius. Returns it, or NULL. */
static const reps_value *gate_accept(const reps_set *r, const photons_map *m, const float q[3], vec3 n,
                                     float max_r2, est_scratch *s)
{
    uint32_t idx[REPS_GATE_CANDIDATES];
    float d2[REPS_GATE_CANDIDATES], top;
    /* the representatives' tree's work is the lookup's, not the photon map's */
    uint64_t queries = s->query.queries;
    kd_work before = s->query.work;
    uint32_t k = kd_query_knn(&r->own, &s->query, q, REPS_GATE_CANDIDATES, max_r2, idx, d2, &top);
    s->rep_work.nodes += s->query.work.nodes - before.nodes;
    s->rep_work.points += s->query.work.points - before.points;
    s->query.work = before;
    s->query.queries = queries;
    /* kd_query_knn answers in no particular order: sort by (d2, index) */
    for (uint32_t a = 1; a < k; a++) {
        for (uint32_t b = a; b > 0 && (d2[b] < d2[b - 1] || (d2[b] == d2[b - 1] && idx[b] < idx[b - 1])); b--) {
            float td = d2[b];
            d2[b] = d2[b - 1];
            d2[b - 1] = td;
            uint32_t ti = idx[b];
            idx[b] = idx[b - 1];
            idx[b - 1] = ti;
        }
    }
    lookup_ctx c = {r, n};
    for (uint32_t j = 0; j < k; j++) {
        uint32_t i = idx[j];
        if (!agrees(&r->value[i], &c))
            continue;
        /* no test of the distance against r itself: it would select
         * representatives by their own noise (a large r, a low estimate:
         * measured on the furnace sphere, --bias-correction, n = 3, the
         * mean radiance 0.88 instead of 1) */
        const reps_value *v = ready_value(r, m, i, s);
        float p[3];
        kd_point(&r->own, i, p);
        vec3 d = vec_make((double)p[0] - q[0], (double)p[1] - q[1], (double)p[2] - q[2]);
        vec3 nr = vec_make(v->normal[0], v->normal[1], v->normal[2]);
        if (est_surface_height(d, n, nr) <= r->rep_gate_tau * sqrt((double)v->radius2))
            return v;
    }
    return NULL;
}

vec3 reps_lookup(const reps_set *r, const photons_map *m, vec3 x, vec3 n, const est_gather *g,
                 est_scratch *s, int *found)
{
    float max_r2 = (float)g->max_r2;
    float q[3], d2;
    photons_map_point(m, x, q);
    lookup_ctx c = {r, n};
    const reps_value *v = NULL;
    s->rep_lookups++;
    if (r->rep_gate != CONFIG_REP_GATE_NONE) {
        assert(r->rep_tree == CONFIG_REP_TREE_SEPARATE); /* config_check */
        v = gate_accept(r, m, q, n, max_r2, s);
        if (!v) {
            uint32_t k;
            vec3 e = est_irradiance(m, x, n, g, s, &k);
            *found = REPS_FALLBACK | (k > 0 ? REPS_FOUND : 0);
            return e;
        }
    } else if (r->rep_tree == CONFIG_REP_TREE_SEPARATE) {
        /* the paper's: the nearest representative whose normal agrees */
        uint32_t i = KD_NONE;
        if (s->last_rep == KD_NONE && r->first_r2 > 0.0f && r->first_r2 < max_r2)
            i = kd_nearest_if_counted(&r->own, q, r->first_r2, pred_separate, &c, KD_NONE, &d2, &s->rep_work);
        if (i == KD_NONE)
            i = kd_nearest_if_counted(&r->own, q, max_r2, pred_separate, &c, s->last_rep, &d2, &s->rep_work);
        if (i != KD_NONE)
            v = ready_value(r, m, i, s);
        s->last_rep = i;
    } else {
        uint32_t i = kd_nearest_if_counted(&m->tree, q, max_r2, pred_shared, &c, s->last_rep, &d2, &s->rep_work);
        if (i != KD_NONE)
            v = ready_value(r, m, r->rep_of[i], s);
        s->last_rep = i;
    }
    *found = v != NULL ? REPS_FOUND : 0;
    if (!v)
        return vec_make(0, 0, 0);
    return vec_mul(vec_make(v->irradiance[0], v->irradiance[1], v->irradiance[2]), est_world_factor(m));
}

uint64_t reps_evaluated(const reps_set *r)
{
    if (!r->state)
        return r->value ? r->count : 0;
    uint64_t n = 0;
    for (uint32_t i = 0; i < r->count; i++)
        n += atomic_load_explicit(&r->state[i], memory_order_acquire) == REPS_READY;
    return n;
}

pm_status reps_write_csv(const reps_set *r, const photons_map *m, FILE *f)
{
    vec3 wf = est_world_factor(m);
    fputs("x,y,z,nx,ny,nz,e_r,e_g,e_b\n", f);
    for (uint32_t i = 0; i < r->count; i++) {
        /* where representative i sits in the map frame: its own tree's leaf
         * i (separate layout) or site i (shared) */
        float q[3];
        if (r->rep_tree == CONFIG_REP_TREE_SEPARATE) {
            q[0] = r->own.x[i];
            q[1] = r->own.y[i];
            q[2] = r->own.z[i];
        } else {
            memcpy(q, r->site[i].pos, sizeof q);
        }
        const reps_value *e = &r->value[i];
        fprintf(f, "%.9g,%.9g,%.9g,%.6f,%.6f,%.6f,%.9g,%.9g,%.9g\n", m->centre.x + m->scale * q[0],
                m->centre.y + m->scale * q[1], m->centre.z + m->scale * q[2], e->normal[0], e->normal[1],
                e->normal[2], e->irradiance[0] * wf.x, e->irradiance[1] * wf.y, e->irradiance[2] * wf.z);
    }
    return ferror(f) ? PM_ERR_IO : PM_OK;
}

size_t reps_bytes(const reps_set *r, const photons_map *m)
{
    size_t b = (size_t)r->count * sizeof(reps_value);
    if (r->state)
        b += (size_t)r->count * sizeof(atomic_uchar);
    if (r->site_of)
        b += (size_t)r->count * sizeof(uint32_t);
    if (r->rep_tree == CONFIG_REP_TREE_SEPARATE)
        b += kd_bytes(&r->own);
    else
        b += (size_t)m->count * sizeof(uint32_t);
    return b;
}

void reps_free(reps_set *r)
{
    free_values(r);
    mem_free(r->site);
    memset(r, 0, sizeof *r);
}

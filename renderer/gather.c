/* gather: final gathering's rays, their strata and the estimates where
 * they land (gather.h). */
#include "gather.h"

#include <assert.h>
#include <math.h>

#include "kdtree.h"
#include "material.h"

void gather_strata(uint32_t n, uint32_t *strata_u, uint32_t *strata_v)
{
    if (n == 0) {
        *strata_u = *strata_v = 0;
        return;
    }
    uint32_t root = (uint32_t)floor(sqrt((double)n));
    while ((uint64_t)root * root > n)
        root--;
    while ((uint64_t)(root + 1) * (root + 1) <= n)
        root++;
    uint32_t u = root;
    while (n % u != 0)
        u--;
    if ((uint64_t)n / u <= 4ull * u) {
        *strata_u = u;
        *strata_v = n / u;
    } else {
        *strata_u = root;
        *strata_v = n / root;
    }
}

gather_params gather_params_make(const scene *sc, const config_render *cfg, const photons_map *global,
                                 const reps_set *reps, const photons_map *caustic, double max_radius)
{
    gather_params g;
    g.sc = sc;
    g.global = global;
    g.reps = cfg->method == CONFIG_METHOD_PRECOMPUTED ? reps : NULL;
    g.caustic = caustic;
    g.global_gather = est_gather_make(global, cfg->nn, max_radius, cfg->bias_correction);
    g.caustic_gather = caustic ? est_gather_make(caustic, cfg->nn, max_radius, cfg->bias_correction) : g.global_gather;
    g.rays = cfg->gather;
    gather_strata(cfg->gather, &g.strata_u, &g.strata_v);
    g.depth = cfg->eye_depth;
    return g;
}

rng_stream gather_stream(uint64_t seed, uint64_t sample)
{
    return rng_make(seed, GATHER_STREAM_BASE + sample);
}

vec3 gather_direction(const gather_params *g, uint32_t i, double xi1, double xi2, vec3 n, vec3 t, vec3 b)
{
    double u1 = xi1, u2 = xi2;
    if (i < g->strata_u * g->strata_v) {
        u1 = ((double)(i % g->strata_u) + xi1) / (double)g->strata_u;
        u2 = ((double)(i / g->strata_u) + xi2) / (double)g->strata_v;
    }
    /* cosine-weighted: a uniform point of the unit disc (radius sqrt(u1))
     * lifted onto the hemisphere, pdf cos(theta) / pi */
    double r = sqrt(u1), phi = 2.0 * VEC_PI * u2;
    double x = r * cos(phi), y = r * sin(phi), z = sqrt(vec_max2(0.0, 1.0 - u1));
    return vec_norm(vec_add(vec_add(vec_scale(t, x), vec_scale(b, y)), vec_scale(n, z)));
}

vec3 gather_estimate(const gather_params *g, vec3 y, vec3 n, est_scratch *s, gather_counts *c)
{
    c->lookups++;
    if (g->reps) {
        int found;
        /* no starting candidate: the previous lookup's representative (another
         * gather ray's, landing elsewhere) is the answer at y for 0.2% of the
         * lookups on cornell (N = 32), and trying it costs more nodes and
         * points than it prunes (renderer/README.md, "Final gathering") */
        s->last_rep = KD_NONE;
        vec3 e = reps_lookup(g->reps, g->global, y, n, &g->global_gather, s, &found);
        c->empty += !(found & REPS_FOUND);
        c->fallbacks += (found & REPS_FALLBACK) != 0;
        return e;
    }
    uint32_t found;
    vec3 e = est_irradiance(g->global, y, n, &g->global_gather, s, &found);
    c->empty += found == 0;
    return e;
}

/* The radiance arriving along r from its first diffuse hit, through mirror
 * and glass (weight: the path's throughput so far, for the eye pass's
 * cut-off); depth counts the specular bounces. At glass one branch is
 * followed, reflection with probability F (Fresnel) and refraction with
 * 1 - F, drawn from rs: the branch's radiance is then an unbiased estimate
 * of the Fresnel-weighted sum, and a gather path stays one path
 * (renderer/README.md, "Final gathering"). */
static vec3 radiance(const gather_params *g, shape_ray r, uint32_t depth, double weight, rng_stream *rs,
                     est_scratch *s, gather_counts *c)
{
    scene_hit h;
    if (!scene_intersect_counted(g->sc, &r, INFINITY, &h, &c->shape_tests)) {
        c->missed++;
        return vec_make(0, 0, 0);
    }
    const material *m = &g->sc->materials[g->sc->shapes[h.shape].material];
    if (m->kind == MATERIAL_LAMBERT)
        return vec_mul(vec_scale(m->color, 1.0 / VEC_PI), gather_estimate(g, h.p, h.n, s, c));
    if (depth >= g->depth) {
        c->depth_hits++;
        return vec_make(0, 0, 0);
    }
    if (m->kind == MATERIAL_MIRROR) {
        double w = weight * vec_maxc(m->color);
        if (w < CONFIG_EYE_MIN_THROUGHPUT)
            return vec_make(0, 0, 0);
        c->specular++;
        return vec_mul(m->color,
                       radiance(g, scene_spawn(&h, material_reflect(r.dir, h.n), 1), depth + 1, w, rs, s, c));
    }
    vec3 refr;
    int can_refract;
    double fr = material_glass_split(r.dir, h.n, h.front, m->ior, &refr, &can_refract);
    double xi = rng_next_double(rs);
    c->specular++;
    if (!can_refract || xi < fr)
        return radiance(g, scene_spawn(&h, material_reflect(r.dir, h.n), 1), depth + 1, weight, rs, s, c);
    return radiance(g, scene_spawn(&h, refr, 0), depth + 1, weight, rs, s, c);
}

vec3 gather_indirect(const gather_params *g, const scene_hit *x, rng_stream *rs, est_scratch *s, gather_counts *c)
{
    if (g->rays == 0)
        return vec_make(0, 0, 0);
    vec3 t, b;
    vec_basis(x->n, &t, &b);
    vec3 sum = vec_make(0, 0, 0);
    for (uint32_t i = 0; i < g->rays; i++) {
        double xi1 = rng_next_double(rs), xi2 = rng_next_double(rs);
        vec3 d = gather_direction(g, i, xi1, xi2, x->n, t, b);
        sum = vec_add(sum, radiance(g, scene_spawn(x, d, 1), 0, 1.0, rs, s, c));
    }
    c->rays += g->rays;
    /* E = integral of L cos over the hemisphere; with pdf cos / pi each
     * ray's estimate is pi L */
    return vec_scale(sum, VEC_PI / (double)g->rays);
}

vec3 gather_caustic(const gather_params *g, const scene_hit *x, est_scratch *s, gather_counts *c)
{
    if (!g->caustic)
        return vec_make(0, 0, 0);
    uint32_t found;
    c->caustic_lookups++;
    return est_irradiance(g->caustic, x->p, x->n, &g->caustic_gather, s, &found);
}

void gather_counts_add(gather_counts *a, const gather_counts *b)
{
    a->rays += b->rays;
    a->specular += b->specular;
    a->lookups += b->lookups;
    a->empty += b->empty;
    a->fallbacks += b->fallbacks;
    a->missed += b->missed;
    a->depth_hits += b->depth_hits;
    a->caustic_lookups += b->caustic_lookups;
    a->shape_tests += b->shape_tests;
}

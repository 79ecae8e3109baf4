/* reps: the representatives of the precomputed method (eq. 2 of the
 * paper): the rule that chooses them, the leave-out mask, their sites, both
 * lookup layouts (their own kd-tree or the photon tree by flag), the
 * precompute (eager or lazy), the lookup (nearest agreeing, or the plane
 * gate) and their CSV form. renderer/README.md has the design. */
#ifndef PM_REPS_H
#define PM_REPS_H

#include <stdatomic.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "config.h"
#include "estimate.h"
#include "kdtree.h"
#include "photons.h"
#include "progress.h"
#include "status.h"
#include "vec.h"
#include "work.h"

/* The representatives' settings, named as their options (reps_params_of). */
typedef struct {
    uint32_t rep_every;       /* every K-th stored photon (trace order); 0 (and rep_count 0): none */
    uint64_t rep_count;       /* the fixed-count rule instead, when > 0: stored photon floor(j * stored /
                                 rep_count) for j = 0 .. rep_count-1 (every stored photon when fewer) */
    config_rep_tree rep_tree; /* the lookup's layout */
    int bias_correction;      /* 1: the photon tree holds only the photons that are not representatives */
    config_rep_eval rep_eval; /* eager (0) or on first use */
    config_rep_gate rep_gate; /* none (0): the nearest agreeing; plane: the gate (and its gather); plane-lookup */
    double rep_gate_tau;      /* the plane gate's tolerance, in kNN radii */
    double normal_cos;        /* a representative's normal must agree with x's above this cosine */
} reps_params;

/* How many of the nearest representatives the plane gate tries before it
 * falls back to the conventional estimate. */
#define REPS_GATE_CANDIDATES 4u
/* A lookup without a starting candidate (final gathering's) first searches
 * within reps_set.first_r2 and searches again within the cap only when that
 * finds nothing: the nearest agreeing representative within the cap is the
 * same either way, and the small radius prunes most of the tree. first_r2
 * is REPS_FIRST_SCALE times the REPS_FIRST_QUANTILE quantile of the squared
 * distance from REPS_FIRST_SAMPLES representatives (evenly spaced in the
 * tree's order) to their nearest other agreeing one. */
#define REPS_FIRST_SAMPLES 1024u
#define REPS_FIRST_QUANTILE 0.9
#define REPS_FIRST_SCALE 2.5f

/* The representatives' settings of cfg: none for the conventional method.
 * Never fails. */
reps_params reps_params_of(const config_render *cfg);

/* Refuses a --rep-count that takes every one of `stored` photons under
 * --bias-correction (none left to gather from). Returns PM_OK, or
 * PM_ERR_INPUT with the reason in err. */
pm_status reps_check_stored(const config_render *cfg, uint64_t stored, char *err, size_t errlen);

/* Flags the representatives of list l by p's rule (PHOTONS_FLAG_REP).
 * Returns how many it flagged (0 for the conventional method). Never
 * fails. */
uint64_t reps_choose(const reps_params *p, photons_list *l);
/* The flags photons_build_map keeps out of the tree: PHOTONS_FLAG_REP
 * with p->bias_correction, else 0. */
uint8_t reps_leave_out_mask(const reps_params *p);

/* A representative's site: its position in the map frame, its surface
 * normal, and where it sits in the photon tree (KD_NONE when the map leaves
 * it out). */
typedef struct {
    float pos[3];
    int8_t normal[3];
    uint8_t pad;
    uint32_t tree_index;
} reps_site;

/* A representative's precomputed value. */
typedef struct {
    float irradiance[3]; /* relative to photons_map.unit / scale^2 */
    float normal[3];     /* unit */
    float radius2;       /* the squared radius its estimate divided by (map frame) */
} reps_value;

/* The representatives: their sites, values and lookup layout. */
typedef struct {
    config_rep_tree rep_tree;
    uint32_t count;
    reps_site *site;    /* the map's representatives in the photon tree, in its leaf order, then those
                           left out, in trace order */
    kd_tree own;        /* separate: the representatives' own tree */
    reps_value *value;  /* separate: in that tree's leaf order; shared: by site (see rep_of) */
    uint32_t *rep_of;   /* shared: photon tree index -> site index or KD_NONE */
    config_rep_eval rep_eval;
    config_rep_gate rep_gate;
    double rep_gate_tau;
    double normal_cos;
    est_gather gather;  /* the precompute's (reps_evaluate's g) */
    /* lazy: per value, REPS_PENDING, REPS_CLAIMED (a thread computes it) or
     * REPS_READY (published with release order); NULL when eager */
    atomic_uchar *state;
    uint32_t *site_of;  /* lazy, separate layout: value index -> site index */
    float first_r2;     /* separate layout: a lookup's first radius squared (REPS_FIRST_SCALE), map frame;
                           0: none (the cap at once) */
    work_counts work;   /* what reps_evaluate did: the representatives' tree, its queries and evaluations */
} reps_set;

enum { REPS_PENDING = 0, REPS_CLAIMED = 1, REPS_READY = 2 };

/* The sites of the representatives into out: the flagged photons of m's
 * tree, then those left out into `left` (NULL: none). Returns PM_OK, or
 * PM_ERR_NOMEM (out is then empty). */
pm_status reps_collect(const reps_params *p, const photons_map *m, const photons_list *left, reps_set *out);
/* Bytes the sites hold. */
size_t reps_sites_bytes(const reps_set *r);

/* Builds r's lookup and computes every representative's irradiance from
 * its g->nn nearest photons of m on `threads` threads (lazy: their normals
 * only; m and g must outlive the lookups). Returns PM_OK, or PM_ERR_NOMEM
 * (r's lookup and values are then freed, its sites kept). */
pm_status reps_evaluate(reps_set *r, const photons_map *m, const est_gather *g, unsigned threads, progress *prog);

/* What reps_lookup's *found holds: bits. */
#define REPS_FOUND 1    /* an estimate from photons: a representative's, or the fallback's */
#define REPS_FALLBACK 2 /* the plane gate accepted none: the conventional estimate at x */

/* Irradiance (W per unit^2) at world point x of normal n: the nearest
 * representative within the radius cap whose normal agrees above
 * r->normal_cos (ties: the first in tree order), or with the plane gate the
 * first of the REPS_GATE_CANDIDATES nearest that passes it, else the
 * conventional estimate with g (REPS_FALLBACK). Lazy: computes what it
 * reads once, thread-safely. Returns 0 with *found = 0 when nothing
 * qualifies. */
vec3 reps_lookup(const reps_set *r, const photons_map *m, vec3 x, vec3 n, const est_gather *g,
                 est_scratch *s, int *found);

/* How many representatives have their irradiance computed: all (eager),
 * or those the lookups have read so far (lazy). */
uint64_t reps_evaluated(const reps_set *r);

/* Writes the representatives as CSV to f (renderer/README.md has the
 * columns). Returns PM_OK, or PM_ERR_IO on a write error. */
pm_status reps_write_csv(const reps_set *r, const photons_map *m, FILE *f);
/* Bytes the values and the lookup layout hold (not the sites). */
size_t reps_bytes(const reps_set *r, const photons_map *m);
/* Frees the representatives; a zeroed struct is fine. */
void reps_free(reps_set *r);

#endif

/* reps: the representatives of the precomputed method (eq. 2 of the paper,
 * after Christensen 2000), everything about them in one place:
 *  - the rule that chooses them among the stored photons (every K-th in
 *    trace order, or a fixed count spread evenly), and its checks;
 *  - the leave-out mask: the corrected estimate keeps them out of the photon
 *    tree, so that their irradiance comes from the other photons;
 *  - their sites (position in the map frame, normal, place in the tree);
 *  - both layouts of the lookup: their own kd-tree (separate) or the photon
 *    tree, found by flag (shared);
 *  - the precompute (equation 1 at every representative, estimate.h), all
 *    before the eye pass (eager, the paper's) or each representative the
 *    first time a lookup selects it (lazy: the same bits, computed once);
 *  - the lookup: the nearest representative whose normal agrees (the
 *    paper's), or the plane gate: of the REPS_GATE_CANDIDATES nearest, the
 *    first whose normal agrees, which lies within tau of its kNN radius r
 *    from x's tangent plane (within the radius cap, not r, of x: a test
 *    against r selects by the estimate's noise), else the conventional
 *    estimate at x (a fallback); with `plane` the precompute counts only
 *    the photons within tau r of the representative's tangent plane,
 *    with `plane-lookup` all (the paper's gather); heights are
 *    est_surface_height's, which sees no curvature on a sphere;
 *  - their CSV form (--dump-reps). */
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

/* Which photons are representatives and where they live, as the pipeline
 * needs it (reps_params_of derives it from a config_render). */
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

/* The rule and layout of cfg: none for the conventional method; the
 * representatives are left out of the photon tree for the corrected
 * precomputed estimate (--bias-correction), which gathers at them from the
 * other photons only. Never fails. */
reps_params reps_params_of(const config_render *cfg);

/* The check that needs the stored count (known after the photon pass): a
 * fixed count that takes every stored photon leaves the corrected estimate
 * none to gather from. Returns PM_OK, or PM_ERR_INPUT with the reason in
 * err. */
pm_status reps_check_stored(const config_render *cfg, uint64_t stored, char *err, size_t errlen);

/* Flags the representatives of list l by p's rule (PHOTONS_FLAG_REP).
 * Never fails. */
void reps_choose(const reps_params *p, photons_list *l);
/* The flags of the photons that photons_build_map must keep out of the
 * tree: PHOTONS_FLAG_REP when p->leave_out, else 0. */
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
    work_counts work;   /* what reps_evaluate did: the representatives' tree, its queries and evaluations */
} reps_set;

enum { REPS_PENDING = 0, REPS_CLAIMED = 1, REPS_READY = 2 };

/* The sites of the representatives into out (no values yet, p's layout):
 * the flagged photons of m's tree, then those photons_build_map left out
 * into `left` (NULL: none). Returns PM_OK, or PM_ERR_NOMEM when memory
 * runs out (out is then empty). */
pm_status reps_collect(const reps_params *p, const photons_map *m, const photons_list *left, reps_set *out);
/* Bytes the sites hold. */
size_t reps_sites_bytes(const reps_set *r);

/* Builds r's lookup layout and computes the irradiance at every
 * representative from its g->nn nearest photons of m (equation 1,
 * est_irradiance_at; with the plane gate est_irradiance_plane_at), on
 * `threads` threads, deterministically; lazy: only their normals, the
 * irradiance then on first use by reps_lookup (m and g must outlive r's
 * lookups). The shared
 * layout needs the representatives in the photon tree (asserted). Returns
 * PM_OK, or PM_ERR_NOMEM when memory runs out (r's lookup and values are
 * then freed, its sites kept). */
pm_status reps_evaluate(reps_set *r, const photons_map *m, const est_gather *g, unsigned threads, progress *prog);

/* What reps_lookup's *found holds: bits. */
#define REPS_FOUND 1    /* an estimate from photons: a representative's, or the fallback's */
#define REPS_FALLBACK 2 /* the plane gate accepted none: the conventional estimate at x */

/* Irradiance (W per unit^2) of the nearest representative within the
 * gather's radius cap of world point x whose normal has cosine >
 * r->normal_cos with n (of equally near ones, the first in tree order, so the answer does
 * not depend on s, whose last answer only starts the search); with the
 * plane gate, of the REPS_GATE_CANDIDATES nearest (by distance, then tree
 * order) the first that passes it, else the conventional estimate at x with
 * g (REPS_FALLBACK). Lazy: computes the irradiance of the representatives
 * it reads that no thread has yet (with s's buffers), thread-safely, once.
 * Returns 0 and sets *found = 0 when none qualifies (ungated) or the
 * fallback found no photon. */
vec3 reps_lookup(const reps_set *r, const photons_map *m, vec3 x, vec3 n, const est_gather *g,
                 est_scratch *s, int *found);

/* How many representatives have their irradiance computed: all (eager),
 * or those the lookups have read so far (lazy). */
uint64_t reps_evaluated(const reps_set *r);

/* Writes the representatives as CSV to f: the header
 * "x,y,z,nx,ny,nz,e_r,e_g,e_b", then one line per representative: its
 * position in scene units, its unit normal and its precomputed irradiance
 * in W per scene unit^2 (what reps_lookup returns for it). Returns PM_OK,
 * or PM_ERR_IO on a write error. */
pm_status reps_write_csv(const reps_set *r, const photons_map *m, FILE *f);
/* Bytes the values and the lookup layout hold (not the sites). */
size_t reps_bytes(const reps_set *r, const photons_map *m);
/* Frees the representatives; a zeroed struct is fine. */
void reps_free(reps_set *r);

#endif

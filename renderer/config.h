/* config: every render setting, its default and the checks of which
 * settings go together. */
#ifndef PM_CONFIG_H
#define PM_CONFIG_H

#include <stdint.h>

#include "scene.h"

typedef enum { CONFIG_METHOD_CONVENTIONAL = 0, CONFIG_METHOD_PRECOMPUTED = 1 } config_method;
typedef enum { CONFIG_DIRECT_PHOTONS = 0, CONFIG_DIRECT_SHADOW_RAYS = 1 } config_direct;
/* --rep-tree, --rep-eval, --rep-gate (renderer/README.md) */
typedef enum { CONFIG_REP_TREE_SEPARATE = 0, CONFIG_REP_TREE_SHARED = 1 } config_rep_tree;
typedef enum { CONFIG_REP_EVAL_EAGER = 0, CONFIG_REP_EVAL_LAZY = 1 } config_rep_eval;
typedef enum { CONFIG_REP_GATE_NONE = 0, CONFIG_REP_GATE_PLANE = 1, CONFIG_REP_GATE_PLANE_LOOKUP = 2 } config_rep_gate;

/* Every setting of one render. */
typedef struct {
    config_method method;     /* radiance estimate: eq. 1 or eq. 2 of the paper */
    config_direct direct;     /* direct light from the photon map or by shadow rays */
    uint64_t photons;         /* P_e: photons emitted from the light */
    uint32_t nn;              /* n: nearest photons per estimate / per precompute */
    uint32_t width, height;   /* output size in pixels */
    uint32_t subpixels;       /* S: SxS subpixel grid per pixel, box filtered */
    uint32_t threads;         /* 0 = all online cores */
    uint64_t seed;            /* names every random stream */
    uint32_t rep_every;       /* precomputed: every K-th stored photon is a representative */
    uint64_t rep_count;       /* precomputed: this many representatives, spread evenly over the stored
                                 photons (all when fewer are stored); 0: the rep_every rule */
    double normal_cos;        /* precomputed: representative's normal must agree above this cosine */
    double max_radius;        /* search radius cap in scene units; <= 0: derived from the photon map */
    double max_radius_frac;   /* the derived cap: this fraction of the photons' bounding-box diagonal */
    uint32_t photon_depth;    /* maximum bounces of a photon path */
    uint32_t eye_depth;       /* maximum specular bounces of an eye path */
    config_rep_tree rep_tree; /* precomputed: the representatives in their own kd-tree (faster, see README)
                                 or found in the photon tree by flag */
    int allow_nonfinite;      /* 1: a pixel out of the float range is reported but does not fail the run */
    int bias_correction;      /* 1: the unbiased estimate (README): photons strictly inside r; for the
                                 precomputed method, from the photons that are not representatives */
    scene_accel accel;        /* ray casting: a BVH from SCENE_BVH_MIN_SHAPES shapes on, always, or never
                                 (the image does not depend on it) */
    const char *dump_reps;    /* precomputed: write the representatives (position, normal, precomputed
                                 irradiance) to this CSV file; NULL: none */
    /* precomputed, beyond the paper (reps.h): */
    config_rep_eval rep_eval; /* when the representatives' irradiance is computed */
    config_rep_gate rep_gate; /* which representative a lookup accepts */
    double rep_gate_tau;      /* plane gate: the largest distance from the tangent plane, in kNN radii */
    uint32_t repeats;         /* times the timed pipeline runs, same seed, same bits (repeat.h);
                                 CONFIG_REPEATS_AUTO: adaptive */
    uint32_t gather;          /* final gathering: gather rays per eye hit (gather.h); 0: the map seen
                                 directly (the paper) */
} config_render;

#define CONFIG_DEFAULT_PHOTONS 100000u
#define CONFIG_DEFAULT_NN 50u
#define CONFIG_DEFAULT_WIDTH 1024u
#define CONFIG_DEFAULT_HEIGHT 768u
#define CONFIG_DEFAULT_SUBPIXELS 2u
#define CONFIG_DEFAULT_SEED 1u
#define CONFIG_DEFAULT_REP_EVERY 4u
#define CONFIG_DEFAULT_REP_COUNT 0u /* 0: the rep_every rule */
#define CONFIG_MAX_REP_COUNT 4294967295ull /* the map holds at most 2^32-1 photons */
#define CONFIG_DEFAULT_NORMAL_COS 0.9
#define CONFIG_DEFAULT_MAX_RADIUS_FRAC 0.05
/* The same as text, for the usage line (keep the two equal). */
#define CONFIG_DEFAULT_MAX_RADIUS_FRAC_TEXT "0.05"
#define CONFIG_DEFAULT_PHOTON_DEPTH 64u
#define CONFIG_DEFAULT_EYE_DEPTH 16u
/* The plane gate's default tolerance (--rep-gate-tau) and its range. */
#define CONFIG_DEFAULT_REP_GATE_TAU 0.1
#define CONFIG_MIN_REP_GATE_TAU 1e-3
#define CONFIG_MAX_REP_GATE_TAU 1.0
/* --repeats: 1 is a single render; auto (CONFIG_REPEATS_AUTO) repeats at
 * least CONFIG_REPEATS_AUTO_MIN times, then until the repeats' totals add
 * up to CONFIG_REPEATS_AUTO_BUDGET_S seconds, at most
 * CONFIG_REPEATS_AUTO_MAX times; an explicit count is at most
 * CONFIG_MAX_REPEATS. */
#define CONFIG_DEFAULT_REPEATS 1u
#define CONFIG_REPEATS_AUTO 0u
#define CONFIG_REPEATS_AUTO_MIN 3u
#define CONFIG_REPEATS_AUTO_MAX 10u
#define CONFIG_REPEATS_AUTO_BUDGET_S 2.0
#define CONFIG_MAX_REPEATS 100u
/* With more than one repeat, freed buffers of up to this many bytes are
 * kept for the next repeat (mem_keep): a fresh page's first touch would
 * otherwise be timed each time, and on some machines it costs more, and
 * varies more, than the work that fills it (renderer/README.md). */
#define CONFIG_REPEAT_KEEP_BYTES ((size_t)1 << 30)
/* The same as text, for the usage line (keep them equal to the above). */
#define CONFIG_REPEATS_AUTO_TEXT "at least 3 times, then until the repeats' totals add up to 2 s, at most 10 times"
#define CONFIG_DEFAULT_REPEATS_TEXT "1; auto or an integer in [1, 100]"
/* --gather: 0 is the paper's direct visualisation; at most this many
 * gather rays per first diffuse eye hit. */
#define CONFIG_DEFAULT_GATHER 0u
#define CONFIG_MAX_GATHER 65536u
/* Eye paths through glass split into reflected and refracted branches; a
 * branch whose throughput falls below this is dropped (bias < this). */
#define CONFIG_EYE_MIN_THROUGHPUT 1e-4
/* The PNG preview's scale (--exposure). */
#define CONFIG_DEFAULT_EXPOSURE 1.0

/* Warnings on stderr (main.c), for renders that run but are likely not
 * what was meant: more than this share of the emitted photons left the
 * scene (the project's scenes are closed rooms and lose none), or more eye
 * paths than this share of the camera's samples were cut at the eye-depth
 * limit (a camera among mirrors: those paths are black). */
#define CONFIG_WARN_ESCAPED_SHARE 0.01
#define CONFIG_WARN_DEPTH_LIMIT_SHARE 0.1

/* Limits that the command line enforces (user errors beyond them exit 2). */
#define CONFIG_MAX_PHOTONS 2000000000ull
#define CONFIG_MIN_NN 2u
#define CONFIG_MAX_NN 100000u
#define CONFIG_MAX_SIDE 16384u
#define CONFIG_MAX_PIXELS (64ull * 1024 * 1024)
#define CONFIG_MAX_SUBPIXELS 16u
#define CONFIG_MAX_THREADS 256u
#define CONFIG_MAX_DEPTH 1000u
/* A render whose photon map is expected to need more than this share of
 * physical memory is refused up front (render_check_memory). */
#define CONFIG_MEMORY_HEADROOM 0.8

/* The defaults above as a struct; never fails. */
config_render config_defaults(void);
/* Returns NULL when the settings of c go together, else why they do not
 * (a user error: degenerate estimates are refused, not computed). */
const char *config_check(const config_render *c);
/* Each enum's spellings, in the enum's order and NULL-terminated: the
 * option tables' choices, the usage text and the stats use these alone. */
extern const char *const config_method_names[];
extern const char *const config_direct_names[];
extern const char *const config_rep_tree_names[];
extern const char *const config_rep_eval_names[];
extern const char *const config_rep_gate_names[];
extern const char *const config_accel_names[];
/* The spelling of one value ("precomputed"); never fails. */
const char *config_method_name(config_method m);
const char *config_direct_name(config_direct d);
const char *config_rep_tree_name(config_rep_tree t);
const char *config_rep_eval_name(config_rep_eval e);
const char *config_rep_gate_name(config_rep_gate g);
const char *config_accel_name(scene_accel a);

#endif

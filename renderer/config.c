/* config: the default render configuration and the names of its enums. */
#include "config.h"

#include <assert.h>
#include <stddef.h>


config_render config_defaults(void)
{
    config_render c;
    c.method = CONFIG_METHOD_CONVENTIONAL;
    c.direct = CONFIG_DIRECT_PHOTONS;
    c.photons = CONFIG_DEFAULT_PHOTONS;
    c.nn = CONFIG_DEFAULT_NN;
    c.width = CONFIG_DEFAULT_WIDTH;
    c.height = CONFIG_DEFAULT_HEIGHT;
    c.subpixels = CONFIG_DEFAULT_SUBPIXELS;
    c.threads = 0;
    c.seed = CONFIG_DEFAULT_SEED;
    c.rep_every = CONFIG_DEFAULT_REP_EVERY;
    c.rep_count = CONFIG_DEFAULT_REP_COUNT;
    c.normal_cos = CONFIG_DEFAULT_NORMAL_COS;
    c.max_radius = 0.0;
    c.max_radius_frac = CONFIG_DEFAULT_MAX_RADIUS_FRAC;
    c.photon_depth = CONFIG_DEFAULT_PHOTON_DEPTH;
    c.eye_depth = CONFIG_DEFAULT_EYE_DEPTH;
    c.rep_tree = CONFIG_REP_TREE_SEPARATE;
    c.allow_nonfinite = 0;
    c.bias_correction = 0;
    c.accel = SCENE_ACCEL_AUTO;
    c.dump_reps = NULL;
    c.rep_eval = CONFIG_REP_EVAL_EAGER;
    c.rep_gate = CONFIG_REP_GATE_NONE;
    c.rep_gate_tau = CONFIG_DEFAULT_REP_GATE_TAU;
    c.repeats = CONFIG_DEFAULT_REPEATS;
    c.gather = CONFIG_DEFAULT_GATHER;
    return c;
}

const char *config_check(const config_render *c)
{
    if (c->nn < CONFIG_MIN_NN)
        return "--nn 1: the estimate has no finite mean (1/r^2 of the nearest photon diverges); use --nn 2 or more";
    if (c->dump_reps && c->method != CONFIG_METHOD_PRECOMPUTED)
        return "--dump-reps writes the representatives of the precomputed method: use it with --method precomputed";
    if (c->gather > 0 && c->direct == CONFIG_DIRECT_PHOTONS)
        return "--gather takes direct light at the eye hit from shadow rays and the rest from the photon maps; "
               "--direct photons would count it twice: leave --direct out, or give --direct shadow-rays";
    /* the variants beyond the paper */
    if (c->rep_eval != CONFIG_REP_EVAL_EAGER && c->method != CONFIG_METHOD_PRECOMPUTED)
        return "--rep-eval lazy evaluates the representatives of the precomputed method on first use; the "
               "conventional method has none: use it with --method precomputed";
    if (c->rep_gate != CONFIG_REP_GATE_NONE && c->method != CONFIG_METHOD_PRECOMPUTED)
        return "--rep-gate plane (and plane-lookup) chooses among the representatives of the precomputed method; the conventional "
               "method has none: use it with --method precomputed";
    if (c->rep_gate != CONFIG_REP_GATE_NONE && c->rep_tree == CONFIG_REP_TREE_SHARED)
        return "--rep-gate plane (and plane-lookup) tries the nearest representatives in their own kd-tree; --rep-tree shared has "
               "none: use --rep-tree separate";
    if (c->rep_eval == CONFIG_REP_EVAL_LAZY && c->dump_reps)
        return "--dump-reps writes every representative's precomputed irradiance; --rep-eval lazy computes only "
               "those the eye pass selects: use --rep-eval eager";
    if (c->method != CONFIG_METHOD_PRECOMPUTED)
        return NULL;
    if (!c->bias_correction && c->nn < 3)
        return "--method precomputed with --nn 2: a representative is its own nearest photon, so r is the "
               "distance to one other photon and the estimate has no finite mean (it follows n/(n-2)); use --nn 3 "
               "or more, or --bias-correction";
    if (c->bias_correction && c->rep_every < 2)
        return "--bias-correction with --method precomputed estimates at representatives from the photons that "
               "are not representatives; --rep-every 1 leaves none: use --rep-every 2 or more";
    if (c->bias_correction && c->rep_tree == CONFIG_REP_TREE_SHARED)
        return "--bias-correction with --method precomputed keeps the representatives out of the photon tree; "
               "--rep-tree shared finds them there: use --rep-tree separate";
    return NULL;
}

const char *const config_method_names[] = {"conventional", "precomputed", NULL};
const char *const config_direct_names[] = {"photons", "shadow-rays", NULL};
const char *const config_rep_tree_names[] = {"separate", "shared", NULL};
const char *const config_rep_eval_names[] = {"eager", "lazy", NULL};
const char *const config_rep_gate_names[] = {"none", "plane", "plane-lookup", NULL};
const char *const config_accel_names[] = {"auto", "bvh", "linear", NULL};

const char *config_method_name(config_method m)
{
    assert(m >= CONFIG_METHOD_CONVENTIONAL && m <= CONFIG_METHOD_PRECOMPUTED);
    return config_method_names[m];
}

const char *config_direct_name(config_direct d)
{
    assert(d >= CONFIG_DIRECT_PHOTONS && d <= CONFIG_DIRECT_SHADOW_RAYS);
    return config_direct_names[d];
}

const char *config_rep_tree_name(config_rep_tree t)
{
    assert(t >= CONFIG_REP_TREE_SEPARATE && t <= CONFIG_REP_TREE_SHARED);
    return config_rep_tree_names[t];
}

const char *config_rep_eval_name(config_rep_eval e)
{
    assert(e >= CONFIG_REP_EVAL_EAGER && e <= CONFIG_REP_EVAL_LAZY);
    return config_rep_eval_names[e];
}

const char *config_rep_gate_name(config_rep_gate g)
{
    assert(g >= CONFIG_REP_GATE_NONE && g <= CONFIG_REP_GATE_PLANE_LOOKUP);
    return config_rep_gate_names[g];
}

const char *config_accel_name(scene_accel a)
{
    assert(a >= SCENE_ACCEL_AUTO && a <= SCENE_ACCEL_LINEAR);
    return config_accel_names[a];
}

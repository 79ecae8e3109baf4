/* config: the default render configuration and the names of its enums. */
#include "config.h"

#include <stddef.h>

#include "reps.h"

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
    return c;
}

const char *config_check(const config_render *c)
{
    if (c->nn < CONFIG_MIN_NN)
        return "--nn 1: the estimate has no finite mean (1/r^2 of the nearest photon diverges); use --nn 2 or more";
    return reps_check(c);
}

const char *config_method_name(config_method m)
{
    return m == CONFIG_METHOD_PRECOMPUTED ? "precomputed" : "conventional";
}

const char *config_direct_name(config_direct d)
{
    return d == CONFIG_DIRECT_SHADOW_RAYS ? "shadow-rays" : "photons";
}

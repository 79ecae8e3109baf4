/* config: the default render configuration and the names of its enums. */
#include "config.h"

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
    c.normal_cos = CONFIG_DEFAULT_NORMAL_COS;
    c.max_radius = 0.0;
    c.max_radius_frac = CONFIG_DEFAULT_MAX_RADIUS_FRAC;
    c.photon_depth = CONFIG_DEFAULT_PHOTON_DEPTH;
    c.eye_depth = CONFIG_DEFAULT_EYE_DEPTH;
    c.reps_shared = 0;
    c.allow_nonfinite = 0;
    return c;
}

const char *config_method_name(config_method m)
{
    return m == CONFIG_METHOD_PRECOMPUTED ? "precomputed" : "conventional";
}

const char *config_direct_name(config_direct d)
{
    return d == CONFIG_DIRECT_SHADOW_RAYS ? "shadow-rays" : "photons";
}

/* test_config: the defaults are the documented constants, and config_check
 * accepts the defaults and every method, and refuses each
 * combination that has no finite or meaningful estimate (the negative
 * controls). */
#include <string.h>

#include "check.h"
#include "config.h"
#include "reps.h"
#include "tests.h"

void test_config_defaults(void)
{
    config_render c = config_defaults();
    CHECK(c.method == CONFIG_METHOD_CONVENTIONAL && c.direct == CONFIG_DIRECT_PHOTONS);
    CHECK(c.photons == CONFIG_DEFAULT_PHOTONS && c.nn == CONFIG_DEFAULT_NN);
    CHECK(c.width == CONFIG_DEFAULT_WIDTH && c.height == CONFIG_DEFAULT_HEIGHT);
    CHECK(c.subpixels == CONFIG_DEFAULT_SUBPIXELS && c.seed == CONFIG_DEFAULT_SEED && c.threads == 0);
    CHECK(c.rep_every == CONFIG_DEFAULT_REP_EVERY && c.rep_count == CONFIG_DEFAULT_REP_COUNT);
    CHECK(c.rep_tree == CONFIG_REP_TREE_SEPARATE && c.accel == SCENE_ACCEL_AUTO);
    CHECK(c.normal_cos == CONFIG_DEFAULT_NORMAL_COS && c.max_radius == 0.0);
    CHECK(c.max_radius_frac == CONFIG_DEFAULT_MAX_RADIUS_FRAC && !c.bias_correction && !c.dump_reps);
    CHECK(!strcmp(config_method_name(CONFIG_METHOD_PRECOMPUTED), "precomputed"));
    CHECK(!strcmp(config_direct_name(CONFIG_DIRECT_SHADOW_RAYS), "shadow-rays"));
}

void test_config_check(void)
{
    config_render c = config_defaults();
    CHECK(config_check(&c) == NULL);
    c.method = CONFIG_METHOD_PRECOMPUTED;
    CHECK(config_check(&c) == NULL);
    c.bias_correction = 1;
    CHECK(config_check(&c) == NULL);
    c.rep_tree = CONFIG_REP_TREE_SHARED; /* negative control: shared and left out */
    CHECK(config_check(&c) != NULL && strstr(config_check(&c), "--rep-tree shared"));
    c.rep_tree = CONFIG_REP_TREE_SEPARATE;
    c.rep_every = 1; /* left out of the tree, every photon a representative */
    CHECK(config_check(&c) != NULL && strstr(config_check(&c), "--rep-every 1"));
    c = config_defaults();
    c.nn = 1;
    CHECK(config_check(&c) != NULL && strstr(config_check(&c), "--nn 1"));
    c = config_defaults();
    c.method = CONFIG_METHOD_PRECOMPUTED;
    c.nn = 2;
    CHECK(config_check(&c) != NULL && strstr(config_check(&c), "--nn 2"));
    c.bias_correction = 1; /* n = 2 is fine when the representative is not among its own photons */
    CHECK(config_check(&c) == NULL);
    c = config_defaults();
    c.dump_reps = "x.csv"; /* the conventional method has no representatives */
    CHECK(config_check(&c) != NULL && strstr(config_check(&c), "--dump-reps"));
    c = config_defaults();
    c.rep_count = 10;
    CHECK(config_check(&c) == NULL);

    /* the check that needs the stored count */
    char err[512];
    c = config_defaults();
    c.method = CONFIG_METHOD_PRECOMPUTED;
    c.bias_correction = 1;
    c.rep_count = 100;
    CHECK(reps_check_stored(&c, 101, err, sizeof err) == PM_OK);
    CHECK(reps_check_stored(&c, 100, err, sizeof err) == PM_ERR_INPUT && strstr(err, "--rep-count 100"));
    c.bias_correction = 0;
    CHECK(reps_check_stored(&c, 100, err, sizeof err) == PM_OK);
}

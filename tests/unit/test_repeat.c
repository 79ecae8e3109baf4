/* test_repeat: the repeats (repeat.h): the same bits and counts every
 * repeat, the minima, the parser and the auto rule. */
#include <math.h>
#include <string.h>

#include "check.h"
#include "helpers.h"
#include "render.h"
#include "repeat.h"
#include "tests.h"
#include "work.h"

void test_repeat_same_bits(void)
{
    scene *sc = NULL;
    char err[512];
    CHECK_MSG(scene_load("scenes/cornell.scene", &sc, err, sizeof err) == PM_OK, "%s", err);
    if (!sc)
        return;
    config_render cfg = config_defaults();
    cfg.photons = 10000;
    cfg.width = 48;
    cfg.height = 36;
    cfg.method = CONFIG_METHOD_PRECOMPUTED;
    render_result once, thrice;
    CHECK(render_run(sc, &cfg, 2, 0, &once, err, sizeof err) == PM_OK);
    cfg.repeats = 3;
    CHECK(repeat_render(sc, &cfg, 2, 0, &thrice, err, sizeof err) == PM_OK);
    /* the last of 3 repeats: the first render's bits and counts */
    size_t n = (size_t)cfg.width * cfg.height * 3;
    CHECK(memcmp(once.img.rgb, thrice.img.rgb, n * sizeof(float)) == 0);
    CHECK(work_equal(&once.st.work, &thrice.st.work));
    const stats_run *st = &thrice.st;
    CHECK(st->repeats.n == 3);
    /* the times: each phase's minimum, the total the smallest total */
    double lo = INFINITY, lo_trace = INFINITY;
    for (uint32_t i = 0; i < st->repeats.n; i++) {
        lo = fmin(lo, st->repeats.t[i][STATS_TOTAL]);
        lo_trace = fmin(lo_trace, st->repeats.t[i][STATS_TRACE]);
        CHECK(st->repeats.t[i][STATS_TOTAL] >= st->repeats.t[i][STATS_RENDER]);
    }
    CHECK(st->total == lo && st->trace == lo_trace);
    render_result_free(&once);
    render_result_free(&thrice);
    scene_free(sc);
}

void test_repeat_rule(void)
{
    char err[256];
    uint32_t r = 7;
    CHECK(repeat_parse("auto", &r, err, sizeof err) == PM_OK && r == CONFIG_REPEATS_AUTO);
    CHECK(repeat_parse("1", &r, err, sizeof err) == PM_OK && r == 1);
    CHECK(repeat_parse("100", &r, err, sizeof err) == PM_OK && r == 100);
    const char *bad[] = {"0", "101", "-1", "3x", "", " 3", "Auto", "99999999999999999999999"};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++)
        CHECK_MSG(repeat_parse(bad[i], &r, err, sizeof err) == PM_ERR_INPUT, "'%s'", bad[i]);
    /* a count: exactly that many */
    CHECK(!repeat_done(3, 2, 100.0) && repeat_done(3, 3, 0.0));
    /* auto: at least 3, then until the budget, at most 10 */
    CHECK(!repeat_done(CONFIG_REPEATS_AUTO, 2, 100.0));
    CHECK(!repeat_done(CONFIG_REPEATS_AUTO, 3, 0.5 * CONFIG_REPEATS_AUTO_BUDGET_S));
    CHECK(repeat_done(CONFIG_REPEATS_AUTO, 3, CONFIG_REPEATS_AUTO_BUDGET_S));
    CHECK(!repeat_done(CONFIG_REPEATS_AUTO, 9, 0.0) && repeat_done(CONFIG_REPEATS_AUTO, 10, 0.0));
}

/* test_stats: the run's JSON names every setting that changes the image,
 * keeps the keys readers use, escapes any path so the file parses, writes
 * a non-finite mean as null, and reports a failed write as PM_ERR_IO. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "check.h"
#include "stats.h"
#include "tests.h"

/* stats_write_json's text into buf. */
static pm_status json_of(const config_render *cfg, const stats_run *st, const char *scene, const char *refused,
                         char *buf, size_t cap)
{
    buf[0] = '\0';
    FILE *f = tmpfile();
    if (!f)
        return PM_ERR_IO;
    pm_status rc = stats_write_json(f, scene, cfg, 2, st, refused);
    rewind(f);
    size_t n = fread(buf, 1, cap - 1, f);
    buf[n] = '\0';
    fclose(f);
    return rc;
}

void test_stats_json_keys(void)
{
    static char buf[8192];
    config_render cfg = config_defaults();
    cfg.method = CONFIG_METHOD_PRECOMPUTED;
    cfg.rep_tree = CONFIG_REP_TREE_SHARED;
    cfg.photon_depth = 7;
    cfg.eye_depth = 9;
    cfg.bias_correction = 1;
    stats_run st;
    memset(&st, 0, sizeof st);
    CHECK(json_of(&cfg, &st, "a.scene", NULL, buf, sizeof buf) == PM_OK);
    const char *want[] = {"\"status\": \"ok\"", "\"method\": \"precomputed\"", "\"estimate\": \"corrected\"",
                          "\"rep_tree\": \"shared\"", "\"photon_depth\": 7", "\"eye_depth\": 9",
                          "\"rep_eval\": \"eager\"", "\"rep_gate\": \"none\"", "\"accel\": \"auto\"",
                          "\"direct\": \"photons\"", "\"normal_cos\": 0.9", "\"samples_per_pixel\": 4",
                          "\"photons_emitted\": 0", "\"threads\": 2", "\"time_s\": {"};
    for (size_t i = 0; i < sizeof want / sizeof want[0]; i++)
        CHECK_MSG(strstr(buf, want[i]) != NULL, "no %s in the JSON", want[i]);
    CHECK(strstr(buf, "\"reason\"") == NULL);
    /* negative control: the paper's estimate is not called corrected */
    cfg.bias_correction = 0;
    CHECK(json_of(&cfg, &st, "a.scene", NULL, buf, sizeof buf) == PM_OK);
    CHECK(strstr(buf, "\"estimate\": \"paper\"") && !strstr(buf, "corrected"));
}

void test_stats_json_escapes(void)
{
    static char buf[8192];
    config_render cfg = config_defaults();
    stats_run st;
    memset(&st, 0, sizeof st);
    st.mean_radiance[1] = NAN;
    CHECK(json_of(&cfg, &st, "q\"b\\\x01\xff.scene", "too \"bright\"", buf, sizeof buf) == PM_OK);
    CHECK(strstr(buf, "\"scene\": \"q\\\"b\\\\\\u0001\\ufffd.scene\"") != NULL);
    CHECK(strstr(buf, "\"status\": \"refused\"") && strstr(buf, "\"reason\": \"too \\\"bright\\\"\""));
    CHECK(strstr(buf, "\"mean_radiance\": [0, null, 0]") != NULL);
    FILE *full = fopen("/dev/full", "w");
    if (!full) {
        CHECK_SKIP("no /dev/full");
        return;
    }
    setvbuf(full, NULL, _IONBF, 0);
    CHECK(stats_write_json(full, "a.scene", &cfg, 1, &st, NULL) == PM_ERR_IO);
    fclose(full);
}

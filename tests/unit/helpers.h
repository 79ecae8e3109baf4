/* helpers: small shared pieces of the unit tests (scenes from text). */
#ifndef PM_TEST_HELPERS_H
#define PM_TEST_HELPERS_H

#include "config.h"
#include "image.h"
#include "scene.h"
#include "stats.h"

/* Parses scene text or aborts the test run with the parser's message. */
scene *helper_scene(const char *text);
/* render_run without progress; prints render_run's message when it fails.
 * Returns render_run's result (RENDER_OK = 0). */
int helper_render(const scene *sc, const config_render *cfg, unsigned threads, image *out, stats_run *st);

#endif

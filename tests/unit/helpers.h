/* helpers: small shared pieces of the unit tests (scenes from text). */
#ifndef PM_TEST_HELPERS_H
#define PM_TEST_HELPERS_H

#include "scene.h"

/* Parses scene text or aborts the test run with the parser's message. */
scene *helper_scene(const char *text);

#endif

/* repeat: the timed pipeline run several times with the same seed, for
 * reproducible times (renderer/README.md). */
#ifndef PM_REPEAT_H
#define PM_REPEAT_H

#include <stddef.h>

#include "config.h"
#include "render.h"
#include "scene.h"
#include "status.h"

/* Parses --repeats' value: "auto" (CONFIG_REPEATS_AUTO) or a count in [1,
 * CONFIG_MAX_REPEATS] into *out. Returns PM_OK, or PM_ERR_INPUT with the
 * reason in err. */
pm_status repeat_parse(const char *text, uint32_t *out, char *err, size_t errlen);

/* 1 when a render that has done n repeats whose totals add up to `spent`
 * seconds is done under `repeats` (a count, or CONFIG_REPEATS_AUTO), else 0. */
int repeat_done(uint32_t repeats, uint32_t n, double spent);

/* render_run cfg->repeats times (repeat_done decides for auto) into *out:
 * the last repeat's image and counts, every repeat's times in
 * out->st.repeats, and in out->st's times each phase's minimum and the
 * smallest total. Returns PM_ERR_NOMEM or PM_ERR_INPUT as render_run
 * does, with the reason in err (out is then empty). */
pm_status repeat_render(const scene *sc, const config_render *cfg, unsigned threads, int show_progress,
                        render_result *out, char *err, size_t errlen);

#endif

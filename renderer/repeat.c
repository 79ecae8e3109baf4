/* repeat: the repeat loop and its times. */
#include "repeat.h"

#include "mem.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>

/* The process's minor page faults so far (first touches of fresh pages;
 * 0 where getrusage fails). */
static uint64_t minor_faults(void)
{
    struct rusage u;
    return getrusage(RUSAGE_SELF, &u) == 0 ? (uint64_t)u.ru_minflt : 0;
}

/* every freed mapping a repeat may keep has a slot, so that only the first
 * repeat pays for fresh pages (a full cache unmaps) */
_Static_assert(CONFIG_REPEAT_KEEP_BYTES <= (size_t)MEM_CACHE_SLOTS * MEM_MAP_MIN,
               "mem's cache has fewer slots than CONFIG_REPEAT_KEEP_BYTES can fill");

pm_status repeat_parse(const char *text, uint32_t *out, char *err, size_t errlen)
{
    if (!strcmp(text, "auto")) {
        *out = CONFIG_REPEATS_AUTO;
        return PM_OK;
    }
    char *end;
    errno = 0;
    unsigned long long v = (text[0] >= '0' && text[0] <= '9') ? strtoull(text, &end, 10) : 0;
    if (text[0] < '0' || text[0] > '9' || *end != '\0' || errno || v < 1 || v > CONFIG_MAX_REPEATS) {
        snprintf(err, errlen, "--repeats '%s': expected auto or a count from 1 to %u", text, CONFIG_MAX_REPEATS);
        return PM_ERR_INPUT;
    }
    *out = (uint32_t)v;
    return PM_OK;
}

int repeat_done(uint32_t repeats, uint32_t n, double spent)
{
    if (repeats != CONFIG_REPEATS_AUTO)
        return n >= repeats;
    if (n < CONFIG_REPEATS_AUTO_MIN)
        return 0;
    return n >= CONFIG_REPEATS_AUTO_MAX || spent >= CONFIG_REPEATS_AUTO_BUDGET_S;
}

pm_status repeat_render(const scene *sc, const config_render *cfg, unsigned threads, int show_progress,
                        render_result *out, char *err, size_t errlen)
{
    stats_repeats times;
    memset(&times, 0, sizeof times);
    memset(out, 0, sizeof *out);
    double spent = 0.0;
    if (cfg->repeats != 1)
        mem_keep(CONFIG_REPEAT_KEEP_BYTES);
    while (!repeat_done(cfg->repeats, times.n, spent) && times.n < CONFIG_MAX_REPEATS) {
        /* the repeat before: memory does not grow, and its mappings serve
         * this one (mem_keep), so that only the first repeat pays for
         * fresh pages */
        render_result_free(out);
        uint64_t faults = minor_faults();
        pm_status rc = render_run(sc, cfg, threads, show_progress, out, err, errlen);
        if (rc != PM_OK)
            return rc;
        times.faults[times.n] = minor_faults() - faults;
        const stats_run *st = &out->st;
        double *t = times.t[times.n++];
        t[STATS_TRACE] = st->trace;
        t[STATS_BUILD] = st->build;
        t[STATS_PRECOMPUTE] = st->precompute;
        t[STATS_RENDER] = st->render;
        t[STATS_TOTAL] = st->total;
        spent += st->total;
    }
    mem_keep(0);
    mem_trim();
    double best[STATS_PHASES];
    for (int p = 0; p < STATS_PHASES; p++) {
        best[p] = times.t[0][p];
        for (uint32_t i = 1; i < times.n; i++)
            best[p] = times.t[i][p] < best[p] ? times.t[i][p] : best[p];
    }
    stats_run *st = &out->st;
    st->trace = best[STATS_TRACE];
    st->build = best[STATS_BUILD];
    st->precompute = best[STATS_PRECOMPUTE];
    st->render = best[STATS_RENDER];
    st->total = best[STATS_TOTAL];
    st->repeats = times;
    return PM_OK;
}

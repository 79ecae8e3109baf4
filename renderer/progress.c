/* progress: "label [#####.....]  42%  ETA 12s" redrawn in place with \r. */
#include "progress.h"

#include <stdio.h>

#include "clock.h"

#define PROGRESS_PERIOD_NS 200000000LL

static void progress_draw(progress *p, int final)
{
    uint64_t done = atomic_load(&p->done);
    double frac = p->total ? (double)done / (double)p->total : 1.0;
    if (frac > 1.0)
        frac = 1.0;
    double elapsed = (double)(clock_now_ns() - p->start_ns) * 1e-9;
    char bar[31];
    int fill = (int)(frac * 30.0);
    for (int i = 0; i < 30; i++)
        bar[i] = i < fill ? '#' : '.';
    bar[30] = '\0';
    if (final)
        fprintf(stderr, "\r%-10s [%s] 100%%  %.1fs       \n", p->label, bar, elapsed);
    else if (frac > 0.0)
        fprintf(stderr, "\r%-10s [%s] %3d%%  ETA %.0fs   ", p->label, bar, (int)(frac * 100.0),
                elapsed / frac - elapsed);
    else
        fprintf(stderr, "\r%-10s [%s]   0%%", p->label, bar);
    fflush(stderr);
}

void progress_begin(progress *p, const char *label, uint64_t total, int enabled)
{
    p->label = label;
    p->total = total;
    atomic_init(&p->done, 0);
    p->start_ns = clock_now_ns();
    atomic_init(&p->next_draw_ns, p->start_ns);
    atomic_flag_clear(&p->drawing);
    p->enabled = enabled;
}

void progress_add(progress *p, uint64_t n)
{
    if (!p)
        return;
    atomic_fetch_add_explicit(&p->done, n, memory_order_relaxed);
    if (!p->enabled)
        return;
    int64_t now = clock_now_ns();
    if (now < atomic_load_explicit(&p->next_draw_ns, memory_order_relaxed))
        return;
    if (atomic_flag_test_and_set(&p->drawing))
        return;
    atomic_store(&p->next_draw_ns, now + PROGRESS_PERIOD_NS);
    progress_draw(p, 0);
    atomic_flag_clear(&p->drawing);
}

void progress_end(progress *p)
{
    if (p && p->enabled)
        progress_draw(p, 1);
}

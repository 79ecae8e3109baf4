/* progress: a progress bar with ETA on stderr, drawn only when stderr is a
 * terminal. Safe to advance from many threads at once. */
#ifndef PM_PROGRESS_H
#define PM_PROGRESS_H

#include <stdatomic.h>
#include <stdint.h>

/* One phase's progress bar. */
typedef struct {
    const char *label;
    uint64_t total;
    _Atomic uint64_t done;
    _Atomic int64_t next_draw_ns; /* monotonic time of the next redraw */
    atomic_flag drawing;
    int64_t start_ns;
    int enabled;
} progress;

/* Starts a phase of `total` units; draws nothing unless enabled. */
void progress_begin(progress *p, const char *label, uint64_t total, int enabled);
/* Adds n finished units; redraws at most a few times a second. */
void progress_add(progress *p, uint64_t n);
/* Draws the final state and ends the line. */
void progress_end(progress *p);

#endif

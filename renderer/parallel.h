/* parallel: a parallel-for over numbered work items on POSIX threads. Items
 * are claimed from a shared atomic counter; what an item computes must depend
 * only on its number, so results are identical for any thread count. */
#ifndef PM_PARALLEL_H
#define PM_PARALLEL_H

#include <stdint.h>

/* Work for one item; `thread` is the worker's number in [0, threads). */
typedef void (*parallel_fn)(uint64_t item, unsigned thread, void *ctx);

/* Runs fn for every item in [0, nitems) on `threads` workers (the calling
 * thread is one of them). Never fails: when a thread cannot be started,
 * the threads that did (at least the caller) run every item. */
void parallel_for(unsigned threads, uint64_t nitems, parallel_fn fn, void *ctx);
/* Online CPU cores (at least 1). */
unsigned parallel_cores(void);

#endif

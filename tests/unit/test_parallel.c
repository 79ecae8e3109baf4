/* test_parallel: parallel_for runs every item exactly once, on worker
 * numbers below the thread count, for any thread and item count (none,
 * fewer items than threads, many); parallel_cores is at least 1. */
#include <stdatomic.h>
#include <stdlib.h>

#include "check.h"
#include "parallel.h"
#include "tests.h"

typedef struct {
    _Atomic unsigned *runs;
    unsigned threads;
    _Atomic unsigned bad_thread;
} par_ctx;

static void count_item(uint64_t item, unsigned thread, void *arg)
{
    par_ctx *c = arg;
    atomic_fetch_add(&c->runs[item], 1u);
    if (thread >= c->threads)
        atomic_fetch_add(&c->bad_thread, 1u);
}

void test_parallel_every_item_once(void)
{
    const unsigned threads[] = {0, 1, 2, 3, 8};
    const uint64_t items[] = {0, 1, 2, 5, 1000, 12345};
    for (size_t t = 0; t < sizeof threads / sizeof threads[0]; t++) {
        for (size_t k = 0; k < sizeof items / sizeof items[0]; k++) {
            uint64_t n = items[k];
            par_ctx c;
            c.runs = calloc(n + 1, sizeof *c.runs);
            c.threads = threads[t] ? threads[t] : 1;
            atomic_init(&c.bad_thread, 0u);
            parallel_for(threads[t], n, count_item, &c);
            uint64_t wrong = 0;
            for (uint64_t i = 0; i < n; i++)
                wrong += atomic_load(&c.runs[i]) != 1;
            CHECK_MSG(wrong == 0, "%u threads, %llu items: %llu items not run exactly once", threads[t],
                      (unsigned long long)n, (unsigned long long)wrong);
            CHECK(atomic_load(&c.runs[n]) == 0); /* none beyond the range */
            CHECK(atomic_load(&c.bad_thread) == 0);
            free(c.runs);
        }
    }
    CHECK(parallel_cores() >= 1);
}

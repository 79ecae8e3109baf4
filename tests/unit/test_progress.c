/* test_progress: a disabled bar counts what it is given, from many threads
 * at once, and draws nothing; a NULL bar is a no-op. */
#include "check.h"
#include "parallel.h"
#include "progress.h"
#include "tests.h"

static void add_three(uint64_t item, unsigned thread, void *arg)
{
    (void)item;
    (void)thread;
    progress_add(arg, 3);
}

void test_progress_counts(void)
{
    progress p;
    progress_begin(&p, "test", 3000, 0);
    CHECK(atomic_load(&p.done) == 0 && p.total == 3000 && !p.enabled);
    parallel_for(4, 1000, add_three, &p);
    CHECK(atomic_load(&p.done) == 3000);
    progress_add(&p, 5);
    CHECK(atomic_load(&p.done) == 3005);
    progress_end(&p);
    progress_add(NULL, 1);
    progress_end(NULL);
}

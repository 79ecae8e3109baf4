/* parallel: pthread workers pulling item numbers from an atomic counter. */
#include "parallel.h"

#include <pthread.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <unistd.h>

typedef struct {
    parallel_fn fn;
    void *ctx;
    uint64_t nitems;
    _Atomic uint64_t next;
} parallel_job;

typedef struct {
    parallel_job *job;
    unsigned thread;
} parallel_worker;

static void *parallel_run(void *arg)
{
    parallel_worker *w = arg;
    parallel_job *job = w->job;
    for (;;) {
        uint64_t i = atomic_fetch_add_explicit(&job->next, 1, memory_order_relaxed);
        if (i >= job->nitems)
            break;
        job->fn(i, w->thread, job->ctx);
    }
    return NULL;
}

void parallel_for(unsigned threads, uint64_t nitems, parallel_fn fn, void *ctx)
{
    parallel_job job;
    job.fn = fn;
    job.ctx = ctx;
    job.nitems = nitems;
    atomic_init(&job.next, 0);
    if (threads < 1)
        threads = 1;
    if (threads > nitems)
        threads = nitems > 0 ? (unsigned)nitems : 1;
    pthread_t *tid = threads > 1 ? malloc(sizeof(pthread_t) * threads) : NULL;
    parallel_worker *w = malloc(sizeof(parallel_worker) * threads);
    if (!w || (threads > 1 && !tid)) {
        free(tid);
        free(w);
        parallel_worker self = {&job, 0};
        parallel_run(&self);
        return;
    }
    unsigned started = 1;
    for (unsigned t = 1; t < threads; t++) {
        w[t].job = &job;
        w[t].thread = t;
        if (pthread_create(&tid[t], NULL, parallel_run, &w[t]) != 0)
            break;
        started++;
    }
    w[0].job = &job;
    w[0].thread = 0;
    parallel_run(&w[0]);
    for (unsigned t = 1; t < started; t++)
        pthread_join(tid[t], NULL);
    free(tid);
    free(w);
}

unsigned parallel_cores(void)
{
    long n = sysconf(_SC_NPROCESSORS_ONLN);
    return n > 0 ? (unsigned)n : 1u;
}

/* check: the unit-test harness. A test is a function; CHECK* record a
 * failure with file:line and the values involved but let the test go on;
 * CHECK_SKIP marks a test that cannot run here. The runner (main.c) prints
 * "N passed, N failed, N skipped" and exits non-zero on any failure. */
#ifndef PM_CHECK_H
#define PM_CHECK_H

#include <math.h>
#include <stdio.h>

typedef struct {
    int failures;        /* checks failed in the current test */
    const char *skipped; /* why the current test could not run here; NULL: it ran */
} check_state;

/* The runner's state for the test that is running. */
check_state *check_current(void);

/* Marks the current test as skipped, for the reason `why` (a string
 * literal), when what it tests cannot run on this machine (AVX2 on a CPU
 * without it): the runner counts it as skipped, never as passed (a check
 * that failed before still fails it). The test returns after it. */
#define CHECK_SKIP(why) (check_current()->skipped = (why))

#define CHECK(cond)                                                                                  \
    do {                                                                                             \
        if (!(cond)) {                                                                               \
            fprintf(stderr, "  %s:%d: check failed: %s\n", __FILE__, __LINE__, #cond);               \
            check_current()->failures++;                                                             \
        }                                                                                            \
    } while (0)

#define CHECK_MSG(cond, ...)                                                                         \
    do {                                                                                             \
        if (!(cond)) {                                                                               \
            fprintf(stderr, "  %s:%d: check failed: %s: ", __FILE__, __LINE__, #cond);              \
            fprintf(stderr, __VA_ARGS__);                                                            \
            fputc('\n', stderr);                                                                     \
            check_current()->failures++;                                                             \
        }                                                                                            \
    } while (0)

/* |a - b| <= tol */
#define CHECK_NEAR(a, b, tol)                                                                        \
    do {                                                                                             \
        double check_a_ = (double)(a), check_b_ = (double)(b), check_t_ = (double)(tol);             \
        if (!(fabs(check_a_ - check_b_) <= check_t_)) {                                              \
            fprintf(stderr, "  %s:%d: check failed: %s = %.9g, %s = %.9g, tolerance %.3g\n", __FILE__, \
                    __LINE__, #a, check_a_, #b, check_b_, check_t_);                                 \
            check_current()->failures++;                                                             \
        }                                                                                            \
    } while (0)

/* |a/b - 1| <= rel */
#define CHECK_REL(a, b, rel)                                                                         \
    do {                                                                                             \
        double check_a_ = (double)(a), check_b_ = (double)(b), check_t_ = (double)(rel);             \
        if (!(fabs(check_a_ - check_b_) <= check_t_ * fabs(check_b_))) {                             \
            fprintf(stderr, "  %s:%d: check failed: %s = %.9g vs %s = %.9g, relative tolerance %.3g\n", \
                    __FILE__, __LINE__, #a, check_a_, #b, check_b_, check_t_);                       \
            check_current()->failures++;                                                             \
        }                                                                                            \
    } while (0)

#endif

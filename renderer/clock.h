/* clock: the monotonic clock that times the phases of a render. */
#ifndef PM_CLOCK_H
#define PM_CLOCK_H

#include <stdint.h>

/* Monotonic time in nanoseconds; never fails. */
int64_t clock_now_ns(void);

#endif

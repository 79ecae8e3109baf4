/* test_clock: the monotonic clock never goes back and measures a sleep of
 * 2 ms as at least 2 ms. */
#include <time.h>

#include "check.h"
#include "clock.h"
#include "tests.h"

void test_clock_monotonic(void)
{
    int64_t prev = clock_now_ns();
    int back = 0;
    for (int i = 0; i < 10000; i++) {
        int64_t now = clock_now_ns();
        back += now < prev;
        prev = now;
    }
    CHECK(back == 0);
    int64_t t0 = clock_now_ns();
    struct timespec ts = {0, 2000000};
    nanosleep(&ts, NULL);
    int64_t dt = clock_now_ns() - t0;
    CHECK_MSG(dt >= 2000000 && dt < 2000000000, "a 2 ms sleep measured %lld ns", (long long)dt);
}

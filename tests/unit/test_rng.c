/* test_rng: the counter-based random streams (independent, reproducible). */
#include <math.h>

#include "check.h"
#include "rng.h"
#include "tests.h"

void test_rng_streams(void)
{
    rng_stream a = rng_make(42, 7), b = rng_make(42, 7), c = rng_make(42, 8), d = rng_make(43, 7);
    int same = 1, diff_c = 0, diff_d = 0;
    double mean = 0.0;
    for (int i = 0; i < 1000; i++) {
        uint64_t x = rng_next_u64(&a);
        same &= x == rng_next_u64(&b);
        diff_c += x != rng_next_u64(&c);
        diff_d += x != rng_next_u64(&d);
    }
    CHECK(same && diff_c == 1000 && diff_d == 1000);
    rng_stream e = rng_make(1, 1);
    for (int i = 0; i < 100000; i++) {
        double u = rng_next_double(&e);
        CHECK(u >= 0.0 && u < 1.0);
        mean += u;
    }
    CHECK_NEAR(mean / 100000, 0.5, 0.005);
}

/* test_numfmt: numfmt_put_exact writes every double so that strtod reads
 * back the same bits, in 15 digits when they suffice, and -0 as 0; %.15g
 * alone does not round-trip (the negative control). */
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "numfmt.h"
#include "rng.h"
#include "tests.h"

/* numfmt_put_exact(x) as a string, into buf. */
static const char *put(double x, char *buf, size_t cap)
{
    FILE *f = tmpfile();
    if (!f)
        return "";
    numfmt_put_exact(f, x);
    rewind(f);
    size_t n = fread(buf, 1, cap - 1, f);
    buf[n] = '\0';
    fclose(f);
    return buf;
}

void test_numfmt_round_trip(void)
{
    char buf[64];
    const double fixed[] = {0.0, 1.0, -1.0, 0.1, 1.0 / 3.0, 2.0 / 3.0, 1e-300, 1e300, DBL_MAX, DBL_MIN,
                            DBL_MIN / 1024.0, DBL_EPSILON, 0.5 + DBL_EPSILON, 123456789.123456789};
    int bad = 0;
    for (size_t i = 0; i < sizeof fixed / sizeof fixed[0]; i++)
        bad += strtod(put(fixed[i], buf, sizeof buf), NULL) != fixed[i];
    rng_stream rs = rng_make(7, 0);
    for (int i = 0; i < 20000; i++) {
        uint64_t bits = rng_next_u64(&rs);
        double x;
        memcpy(&x, &bits, sizeof x);
        if (!isfinite(x))
            continue;
        double y = strtod(put(x, buf, sizeof buf), NULL);
        bad += memcmp(&x, &y, sizeof x) != 0 && !(x == 0.0 && y == 0.0);
    }
    CHECK_MSG(bad == 0, "%d doubles did not read back", bad);
    CHECK(!strcmp(put(0.1, buf, sizeof buf), "0.1"));
    CHECK(!strcmp(put(-0.0, buf, sizeof buf), "0"));
    /* negative control: 15 digits lose 1/3's last bits */
    char short_form[64];
    snprintf(short_form, sizeof short_form, "%.15g", 1.0 / 3.0);
    CHECK(strtod(short_form, NULL) != 1.0 / 3.0);
}

/* numfmt.c: the exporters' exact number format (numfmt.h). */
#include "numfmt.h"

#include <assert.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

void numfmt_put_exact(FILE *f, double x)
{
    assert(isfinite(x));
    char buf[40];
    snprintf(buf, sizeof buf, "%.15g", x);
    if (strtod(buf, NULL) != x)
        snprintf(buf, sizeof buf, "%.17g", x);
    if (!strcmp(buf, "-0"))
        strcpy(buf, "0");
    fputs(buf, f);
}

/* numfmt.h: how the exporters (povray.c, pbrt.c) print a double so that it
 * reads back exactly: the one number format of every scene file they write. */
#ifndef PM_NUMFMT_H
#define PM_NUMFMT_H

#include <stdio.h>

/* Writes x (finite: asserted) as the shortest of %.15g / %.17g that strtod
 * reads back to the same double, with -0 written as 0. Errors of f are left
 * in its error flag for the caller's fflush/ferror. */
void numfmt_put_exact(FILE *f, double x);

#endif

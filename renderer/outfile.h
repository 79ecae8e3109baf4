/* outfile: result files that appear whole or not at all. Data goes to a
 * temporary name in the same directory and is renamed over the final path
 * only when complete, so a failed or killed run never leaves a half-written
 * result and an existing file is only replaced by a complete one. */
#ifndef PM_OUTFILE_H
#define PM_OUTFILE_H

#include <stdio.h>

#define OUTFILE_PATH_MAX 4096

typedef struct {
    char path[OUTFILE_PATH_MAX]; /* final name */
    char tmp[OUTFILE_PATH_MAX];  /* temporary name beside it */
    FILE *f;                     /* open on tmp when a stream was asked for */
} outfile;

/* Prepares writing `path`: creates the temporary file (so an unwritable
 * directory fails now, before any work) and, if `stream`, keeps it open as
 * o->f. Returns 0, or -1 with "path: reason" in err. */
int outfile_begin(outfile *o, const char *path, int stream, char *err, size_t errlen);
/* Flushes, syncs and closes the stream (if any) and renames tmp over path.
 * Returns 0, or -1 with "path: reason" in err (the temporary is removed). */
int outfile_commit(outfile *o, char *err, size_t errlen);
/* Closes and removes the temporary; the final path is untouched. */
void outfile_abort(outfile *o);

#endif

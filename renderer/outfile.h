/* outfile: result files that appear whole or not at all, written to a
 * temporary beside the path and renamed over it when complete
 * (renderer/README.md). */
#ifndef PM_OUTFILE_H
#define PM_OUTFILE_H

#include <stdio.h>

#include "status.h"

#define OUTFILE_PATH_MAX 4096

/* One result file being written. */
typedef struct {
    char path[OUTFILE_PATH_MAX]; /* final name */
    char tmp[OUTFILE_PATH_MAX];  /* temporary name beside it */
    FILE *f;                     /* open on tmp when a stream was asked for */
    int slot;                    /* where the signal handler finds tmp (OUTFILE_NO_SLOT: nowhere) */
} outfile;

#define OUTFILE_NO_SLOT (-1)

/* Prepares writing `path`: creates the temporary file (so an unwritable
 * directory fails now, before any work) and, if `stream`, keeps it open as
 * o->f. Returns PM_OK, or PM_ERR_IO with "path: reason" in err. */
pm_status outfile_begin(outfile *o, const char *path, int stream, char *err, size_t errlen);
/* Flushes, syncs and closes the stream (if any) and renames tmp over path.
 * Returns PM_OK, or PM_ERR_IO with "path: reason" in err (the temporary is
 * removed). */
pm_status outfile_commit(outfile *o, char *err, size_t errlen);
/* Closes and removes the temporary; the final path is untouched. Never
 * fails. */
void outfile_abort(outfile *o);
/* 1 when paths a and b name the same file (the same string, the same
 * existing file, or the same name in the same resolved directory), else 0. */
int outfile_same_target(const char *a, const char *b);

#endif

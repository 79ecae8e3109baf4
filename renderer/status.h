/* status: the renderer's one result code, its messages and exit codes.
 * Functions that can fail return a pm_status and write the details into
 * the caller's err buffer; invariants are asserts. */
#ifndef PM_STATUS_H
#define PM_STATUS_H

typedef enum {
    PM_OK = 0,    /* done; go on */
    PM_DONE,      /* nothing more to do, not an error (the usage text was printed for --help) */
    PM_ERR_INPUT, /* a user input error: a bad option or scene file, settings that do not go together,
                     a scene the renderer cannot render faithfully (exit 2) */
    PM_ERR_NOMEM, /* memory ran out (exit 1) */
    PM_ERR_IO     /* a file could not be read or written (exit 1) */
} pm_status;

/* A short English message for s ("out of memory"); never NULL. */
const char *pm_status_message(pm_status s);
/* The process exit code for s: 0 for PM_OK and PM_DONE, 2 for a user input
 * error, 1 for a runtime failure (memory, I/O). */
int pm_status_exit(pm_status s);

#endif

/* outfile: temporary-then-rename writes with errors that name the path,
 * and the removal of temporaries when the process is interrupted. */
#define _XOPEN_SOURCE 700 /* realpath */
#include "outfile.h"

#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* ---- temporaries still open, for the signal handler ----
 * The one piece of mutable global state in the renderer: a handler of
 * SIGINT, SIGTERM and SIGHUP can only reach what is global. Slots are
 * written by the main thread (outputs are written there) and read by the
 * handler, which only calls async-signal-safe functions (unlink, sigaction,
 * raise). A slot's path is complete before its flag is set. */
#define OUTFILE_SLOTS 8
static char outfile_pending[OUTFILE_SLOTS][OUTFILE_PATH_MAX];
static volatile sig_atomic_t outfile_used[OUTFILE_SLOTS];
static volatile sig_atomic_t outfile_handlers_set;

static void outfile_on_signal(int sig)
{
    for (int i = 0; i < OUTFILE_SLOTS; i++)
        if (outfile_used[i])
            unlink(outfile_pending[i]);
    struct sigaction dfl;
    memset(&dfl, 0, sizeof dfl);
    dfl.sa_handler = SIG_DFL;
    sigemptyset(&dfl.sa_mask);
    sigaction(sig, &dfl, NULL);
    raise(sig); /* die of the signal, as without the handler */
}

static void outfile_install_handlers(void)
{
    if (outfile_handlers_set)
        return;
    outfile_handlers_set = 1;
    const int sigs[3] = {SIGINT, SIGTERM, SIGHUP};
    for (int i = 0; i < 3; i++) {
        struct sigaction old, sa;
        /* a signal the caller ignores (nohup, a background job) stays ignored */
        if (sigaction(sigs[i], NULL, &old) == 0 && old.sa_handler == SIG_IGN)
            continue;
        memset(&sa, 0, sizeof sa);
        sa.sa_handler = outfile_on_signal;
        sigemptyset(&sa.sa_mask);
        sigaction(sigs[i], &sa, NULL);
    }
}

/* Remembers tmp for the handler; returns its slot, or OUTFILE_NO_SLOT when
 * all are used (the file is still written, only not removed on a signal). */
static int outfile_track(const char *tmp)
{
    outfile_install_handlers();
    for (int i = 0; i < OUTFILE_SLOTS; i++) {
        if (!outfile_used[i]) {
            memcpy(outfile_pending[i], tmp, strlen(tmp) + 1);
            outfile_used[i] = 1;
            return i;
        }
    }
    return OUTFILE_NO_SLOT;
}

static void outfile_untrack(outfile *o)
{
    if (o->slot != OUTFILE_NO_SLOT)
        outfile_used[o->slot] = 0;
    o->slot = OUTFILE_NO_SLOT;
}

pm_status outfile_begin(outfile *o, const char *path, int stream, char *err, size_t errlen)
{
    memset(o, 0, sizeof *o);
    o->slot = OUTFILE_NO_SLOT;
    size_t n = strlen(path);
    if (n == 0 || n + 32 >= OUTFILE_PATH_MAX) {
        snprintf(err, errlen, "%s: bad output path", path);
        return PM_ERR_IO;
    }
    /* Renaming over a device, FIFO or directory would replace it: `-o
     * /dev/full` run as root would turn /dev/full into a regular file
     * (tests/hostile.test.sh). Only regular files or new names are outputs. */
    struct stat st;
    if (stat(path, &st) == 0 && !S_ISREG(st.st_mode)) {
        snprintf(err, errlen, "%s: not a regular file; outputs are written beside it and renamed over it", path);
        return PM_ERR_IO;
    }
    memcpy(o->path, path, n + 1);
    snprintf(o->tmp, sizeof o->tmp, "%s.tmp.%ld", path, (long)getpid());
    o->slot = outfile_track(o->tmp);
    int fd = open(o->tmp, O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd < 0) {
        snprintf(err, errlen, "%s: cannot write: %s", path, strerror(errno));
        outfile_untrack(o);
        o->tmp[0] = '\0';
        return PM_ERR_IO;
    }
    if (stream) {
        o->f = fdopen(fd, "wb");
        if (!o->f) {
            snprintf(err, errlen, "%s: %s", path, strerror(errno));
            close(fd);
            unlink(o->tmp);
            outfile_untrack(o);
            o->tmp[0] = '\0';
            return PM_ERR_IO;
        }
    } else {
        close(fd);
    }
    return PM_OK;
}

pm_status outfile_commit(outfile *o, char *err, size_t errlen)
{
    pm_status rc = PM_OK;
    if (o->f) {
        if (fflush(o->f) != 0 || ferror(o->f) || fsync(fileno(o->f)) != 0) {
            snprintf(err, errlen, "%s: write failed: %s", o->path, strerror(errno));
            rc = PM_ERR_IO;
        }
        if (fclose(o->f) != 0 && rc == PM_OK) {
            snprintf(err, errlen, "%s: write failed: %s", o->path, strerror(errno));
            rc = PM_ERR_IO;
        }
        o->f = NULL;
    }
    if (rc == PM_OK && rename(o->tmp, o->path) != 0) {
        snprintf(err, errlen, "%s: cannot rename into place: %s", o->path, strerror(errno));
        rc = PM_ERR_IO;
    }
    if (rc != PM_OK)
        unlink(o->tmp);
    outfile_untrack(o);
    o->tmp[0] = '\0';
    return rc;
}

void outfile_abort(outfile *o)
{
    if (o->f) {
        fclose(o->f);
        o->f = NULL;
    }
    if (o->tmp[0])
        unlink(o->tmp);
    outfile_untrack(o);
    o->tmp[0] = '\0';
}

/* The canonical name of path (which need not exist): its directory resolved
 * by realpath, then its last component. Returns PM_OK, or PM_ERR_IO when
 * the directory cannot be resolved or the name does not fit. */
static pm_status canonical_name(const char *path, char *out, size_t cap)
{
    char dir[OUTFILE_PATH_MAX], real[PATH_MAX];
    const char *slash = strrchr(path, '/');
    const char *base = slash ? slash + 1 : path;
    size_t dlen = slash ? (size_t)(slash - path) : 0;
    if (dlen + 1 > sizeof dir)
        return PM_ERR_IO;
    if (slash && dlen == 0)
        strcpy(dir, "/");
    else if (slash) {
        memcpy(dir, path, dlen);
        dir[dlen] = '\0';
    } else
        strcpy(dir, ".");
    if (!realpath(dir, real))
        return PM_ERR_IO;
    int n = snprintf(out, cap, "%s/%s", real, base);
    return n < 0 || (size_t)n >= cap ? PM_ERR_IO : PM_OK;
}

int outfile_same_target(const char *a, const char *b)
{
    if (!strcmp(a, b))
        return 1;
    struct stat sa, sb;
    if (stat(a, &sa) == 0 && stat(b, &sb) == 0)
        return sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
    char ca[OUTFILE_PATH_MAX + PATH_MAX], cb[OUTFILE_PATH_MAX + PATH_MAX];
    return canonical_name(a, ca, sizeof ca) == PM_OK && canonical_name(b, cb, sizeof cb) == PM_OK && !strcmp(ca, cb);
}

/* outfile: temporary-then-rename writes with errors that name the path. */
#include "outfile.h"

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

int outfile_begin(outfile *o, const char *path, int stream, char *err, size_t errlen)
{
    memset(o, 0, sizeof *o);
    size_t n = strlen(path);
    if (n == 0 || n + 32 >= OUTFILE_PATH_MAX) {
        snprintf(err, errlen, "%s: bad output path", path);
        return -1;
    }
    /* Renaming over a device, FIFO or directory would replace it: `-o
     * /dev/full` run as root turned /dev/full into a regular file (found by
     * tests/hostile.test.sh). Only regular files or new names are outputs. */
    struct stat st;
    if (stat(path, &st) == 0 && !S_ISREG(st.st_mode)) {
        snprintf(err, errlen, "%s: not a regular file; outputs are written beside it and renamed over it", path);
        return -1;
    }
    memcpy(o->path, path, n + 1);
    snprintf(o->tmp, sizeof o->tmp, "%s.tmp.%ld", path, (long)getpid());
    int fd = open(o->tmp, O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd < 0) {
        snprintf(err, errlen, "%s: cannot write: %s", path, strerror(errno));
        o->tmp[0] = '\0';
        return -1;
    }
    if (stream) {
        o->f = fdopen(fd, "wb");
        if (!o->f) {
            snprintf(err, errlen, "%s: %s", path, strerror(errno));
            close(fd);
            unlink(o->tmp);
            o->tmp[0] = '\0';
            return -1;
        }
    } else {
        close(fd);
    }
    return 0;
}

int outfile_commit(outfile *o, char *err, size_t errlen)
{
    int rc = 0;
    if (o->f) {
        if (fflush(o->f) != 0 || ferror(o->f) || fsync(fileno(o->f)) != 0) {
            snprintf(err, errlen, "%s: write failed: %s", o->path, strerror(errno));
            rc = -1;
        }
        if (fclose(o->f) != 0 && rc == 0) {
            snprintf(err, errlen, "%s: write failed: %s", o->path, strerror(errno));
            rc = -1;
        }
        o->f = NULL;
    }
    if (rc == 0 && rename(o->tmp, o->path) != 0) {
        snprintf(err, errlen, "%s: cannot rename into place: %s", o->path, strerror(errno));
        rc = -1;
    }
    if (rc != 0)
        unlink(o->tmp);
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
    o->tmp[0] = '\0';
}

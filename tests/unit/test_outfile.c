/* test_outfile: a result file appears whole or not at all: committed data
 * replaces an existing file, an aborted or failed write leaves that file
 * untouched and no temporary behind (the negative controls), and two names of
 * one file are recognised. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "check.h"
#include "outfile.h"
#include "tests.h"

/* The whole content of path into buf (at most cap-1 bytes); -1 if absent. */
static long read_all(const char *path, char *buf, size_t cap)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return -1;
    size_t n = fread(buf, 1, cap - 1, f);
    buf[n] = '\0';
    fclose(f);
    return (long)n;
}

/* Entries of dir other than . and .. */
static int entries(const char *dir)
{
    char cmd[600];
    snprintf(cmd, sizeof cmd, "ls -A '%s' | wc -l", dir);
    FILE *p = popen(cmd, "r");
    int n = -1;
    if (p) {
        if (fscanf(p, "%d", &n) != 1)
            n = -1;
        pclose(p);
    }
    return n;
}

void test_outfile_whole_or_nothing(void)
{
    char dir[] = "/tmp/pm-outfile-XXXXXX";
    CHECK(mkdtemp(dir) != NULL);
    char path[512], buf[256], err[512];
    snprintf(path, sizeof path, "%s/result.txt", dir);
    outfile o;

    CHECK(outfile_begin(&o, path, 1, err, sizeof err) == PM_OK);
    fputs("first", o.f);
    CHECK(read_all(path, buf, sizeof buf) == -1); /* nothing at the final name before the commit */
    CHECK(outfile_commit(&o, err, sizeof err) == PM_OK);
    CHECK(read_all(path, buf, sizeof buf) == 5 && !strcmp(buf, "first"));

    /* negative control: an aborted write leaves the existing file and no temporary */
    CHECK(outfile_begin(&o, path, 1, err, sizeof err) == PM_OK);
    fputs("second, half written", o.f);
    outfile_abort(&o);
    CHECK(read_all(path, buf, sizeof buf) == 5 && !strcmp(buf, "first"));
    CHECK(entries(dir) == 1);

    /* a commit replaces it */
    CHECK(outfile_begin(&o, path, 1, err, sizeof err) == PM_OK);
    fputs("third", o.f);
    CHECK(outfile_commit(&o, err, sizeof err) == PM_OK);
    CHECK(read_all(path, buf, sizeof buf) == 5 && !strcmp(buf, "third"));
    CHECK(entries(dir) == 1);

    /* negative control: an unwritable place fails up front, naming the path */
    char bad[600];
    snprintf(bad, sizeof bad, "%s/no-such-dir/x.txt", dir);
    CHECK(outfile_begin(&o, bad, 1, err, sizeof err) == PM_ERR_IO && strstr(err, "no-such-dir"));

    /* two names of one file */
    char other[600];
    snprintf(other, sizeof other, "%s/./result.txt", dir);
    CHECK(outfile_same_target(path, path) == 1);
    CHECK(outfile_same_target(path, other) == 1);
    snprintf(other, sizeof other, "%s/other.txt", dir);
    CHECK(outfile_same_target(path, other) == 0);

    unlink(path);
    CHECK(rmdir(dir) == 0);
}

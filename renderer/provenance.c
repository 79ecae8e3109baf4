/* provenance: the build's constants and the machine's state. */
#include "provenance.h"

#include <stdio.h>
#include <string.h>

#ifndef PM_COMMIT
#define PM_COMMIT "unknown"
#endif
#ifndef PM_TREE
#define PM_TREE "unknown"
#endif
#ifndef PM_FLAGS
#define PM_FLAGS "unknown"
#endif

#define PROVENANCE_STR2(x) #x
#define PROVENANCE_STR(x) PROVENANCE_STR2(x)
#if defined(__clang__)
#define PROVENANCE_COMPILER                                                                                   \
    "clang " PROVENANCE_STR(__clang_major__) "." PROVENANCE_STR(__clang_minor__) "." PROVENANCE_STR(          \
        __clang_patchlevel__)
#elif defined(__GNUC__)
#define PROVENANCE_COMPILER                                                                                   \
    "gcc " PROVENANCE_STR(__GNUC__) "." PROVENANCE_STR(__GNUC_MINOR__) "." PROVENANCE_STR(__GNUC_PATCHLEVEL__)
#else
#define PROVENANCE_COMPILER "unknown"
#endif

/* The first "model name" of /proc/cpuinfo into out, or "unknown". */
static void cpu_model(char *out, size_t len)
{
    snprintf(out, len, "unknown");
    FILE *f = fopen("/proc/cpuinfo", "r");
    if (!f)
        return;
    char line[512];
    while (fgets(line, sizeof line, f)) {
        if (strncmp(line, "model name", 10) != 0)
            continue;
        const char *v = strchr(line, ':');
        if (!v)
            continue;
        v++;
        while (*v == ' ' || *v == '\t')
            v++;
        size_t n = strcspn(v, "\n");
        snprintf(out, len, "%.*s", (int)n, v);
        break;
    }
    fclose(f);
}

/* The load averages from /proc/loadavg, or -1 each. */
static void load_average(double out[3])
{
    out[0] = out[1] = out[2] = -1.0;
    FILE *f = fopen("/proc/loadavg", "r");
    if (!f)
        return;
    double a, b, c;
    if (fscanf(f, "%lf %lf %lf", &a, &b, &c) == 3) {
        out[0] = a;
        out[1] = b;
        out[2] = c;
    }
    fclose(f);
}

void provenance_collect(provenance_info *p)
{
    memset(p, 0, sizeof *p);
    p->commit = PM_COMMIT;
    p->tree = PM_TREE;
    p->compiler = PROVENANCE_COMPILER;
    p->flags = PM_FLAGS;
    cpu_model(p->cpu, sizeof p->cpu);
    load_average(p->loadavg);
}

/* provenance: the build (PM_COMMIT, PM_TREE, PM_FLAGS), compiler, CPU and
 * load average that a stats file records. */
#ifndef PM_PROVENANCE_H
#define PM_PROVENANCE_H

/* What a stats file records about the binary and the machine. */
typedef struct {
    const char *commit;   /* the short hash, or "unknown" */
    const char *tree;     /* "clean", "dirty" (uncommitted changes to tracked files) or "unknown" */
    const char *compiler; /* "gcc 12.2.0", "clang 14.0.6", ... */
    const char *flags;    /* the optimisation and debug flags, or "unknown" */
    char cpu[128];        /* /proc/cpuinfo's first "model name", or "unknown" */
    double loadavg[3];    /* the 1, 5 and 15 minute load averages; negative when unknown */
} provenance_info;

/* Fills p for a render that starts now. Never fails: what cannot be read
 * is "unknown" (or negative). */
void provenance_collect(provenance_info *p);

#endif

/* work: the counters' sums, comparison and JSON form. */
#include "work.h"

void work_add(work_counts *a, const work_counts *b)
{
#define WORK_ADD(name) a->name += b->name;
    WORK_FIELDS(WORK_ADD)
#undef WORK_ADD
}

static int counts_equal(const work_counts *a, const work_counts *b)
{
    int eq = 1;
#define WORK_EQ(name) eq &= a->name == b->name;
    WORK_FIELDS(WORK_EQ)
#undef WORK_EQ
    return eq;
}

int work_equal(const work_phases *a, const work_phases *b)
{
    return counts_equal(&a->trace, &b->trace) && counts_equal(&a->build, &b->build) &&
           counts_equal(&a->precompute, &b->precompute) && counts_equal(&a->render, &b->render);
}

static void write_counts(FILE *f, const char *phase, const work_counts *w, int last)
{
    fprintf(f, "    \"%s\": {", phase);
    const char *sep = "";
#define WORK_JSON(name)                                                                                      \
    fprintf(f, "%s\"" #name "\": %llu", sep, (unsigned long long)w->name);                                 \
    sep = ", ";
    WORK_FIELDS(WORK_JSON)
#undef WORK_JSON
    fprintf(f, "}%s\n", last ? "" : ",");
}

pm_status work_write_json(FILE *f, const work_phases *w)
{
    fputs("{\n", f);
    write_counts(f, "trace", &w->trace, 0);
    write_counts(f, "build", &w->build, 0);
    write_counts(f, "precompute", &w->precompute, 0);
    write_counts(f, "render", &w->render, 1);
    fputs("  }", f);
    return ferror(f) ? PM_ERR_IO : PM_OK;
}

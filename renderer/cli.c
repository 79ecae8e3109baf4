/* cli: one table-driven parser for every subcommand's options, their range
 * errors and their usage text. */
#include "cli.h"

#include <assert.h>
#include <errno.h>
#include <inttypes.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

pm_status cli_error(const cli_command *cmd, const char *fmt, ...)
{
    va_list ap;
    fprintf(stderr, "photonmap: ");
    va_start(ap, fmt);
    vfprintf(stderr, fmt, ap);
    va_end(ap);
    fprintf(stderr, "\n(run 'photonmap %s --help' for usage)\n", cmd->name);
    return PM_ERR_INPUT;
}

/* "a, b or c" (bar = 0) or "a|b|c" (bar = 1) for a NULL-terminated list,
 * into buf. */
static const char *choice_list(const char *const *choices, int bar, char *buf, size_t cap)
{
    buf[0] = '\0';
    size_t n = 0;
    while (choices[n])
        n++;
    for (size_t i = 0; i < n; i++) {
        const char *sep = i == 0 ? "" : bar ? "|" : (i + 1 == n ? " or " : ", ");
        strncat(buf, sep, cap - strlen(buf) - 1);
        strncat(buf, choices[i], cap - strlen(buf) - 1);
    }
    return buf;
}

/* Parses v as option o's value into args. Returns PM_OK, or PM_ERR_INPUT
 * after printing why. */
static pm_status parse_value(const cli_command *cmd, const cli_option *o, const char *v, void *args)
{
    char *dst = (char *)args + o->offset;
    char buf[256];
    switch (o->kind) {
    case CLI_U32:
    case CLI_U64: {
        const char *p = v[0] == '+' ? v + 1 : v;
        char *end = NULL;
        unsigned long long x = 0;
        errno = 0;
        if (*p >= '0' && *p <= '9')
            x = strtoull(p, &end, 10);
        if (!(*p >= '0' && *p <= '9') || *end != '\0' || errno == ERANGE || x < o->ulo || x > o->uhi)
            return cli_error(cmd, "%s: expected an integer in [%" PRIu64 ", %" PRIu64 "], got '%s'", o->name, o->ulo,
                             o->uhi, v);
        if (o->kind == CLI_U32) {
            uint32_t u = (uint32_t)x;
            memcpy(dst, &u, sizeof u);
        } else {
            uint64_t u = (uint64_t)x;
            memcpy(dst, &u, sizeof u);
        }
        return PM_OK;
    }
    case CLI_REAL: {
        char *end = NULL;
        errno = 0;
        double x = strtod(v, &end);
        /* decimal only: strtod also reads hex floats, "inf" and "nan" */
        int decimal = strpbrk(v, "xXnN") == NULL;
        if (end == v || *end != '\0' || !decimal || !isfinite(x) || x < o->rlo || x > o->rhi)
            return cli_error(cmd, "%s: expected a number in [%g, %g], got '%s'", o->name, o->rlo, o->rhi, v);
        memcpy(dst, &x, sizeof x);
        return PM_OK;
    }
    case CLI_CHOICE:
        for (int i = 0; o->choices[i]; i++) {
            if (!strcmp(v, o->choices[i])) {
                memcpy(dst, &i, sizeof i);
                return PM_OK;
            }
        }
        return cli_error(cmd, "%s: expected %s, got '%s'", o->name, choice_list(o->choices, 0, buf, sizeof buf), v);
    case CLI_STRING:
        if (v[0] == '\0')
            return cli_error(cmd, "%s: expected a non-empty value", o->name);
        memcpy(dst, &v, sizeof v);
        return PM_OK;
    case CLI_FLAG:
        break;
    }
    assert(!"parse_value: a flag has no value");
    return PM_ERR_INPUT;
}

pm_status cli_parse(const cli_command *cmd, int argc, char **argv, int first, void *args)
{
    const char *positional = NULL;
    for (int i = first; i < argc; i++) {
        const char *a = argv[i];
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            cli_usage(stdout, cmd, args); /* args holds the defaults here */
            return PM_DONE;
        }
    }
    for (int i = first; i < argc; i++) {
        const char *a = argv[i];
        if (a[0] != '-' || !strcmp(a, "-")) {
            if (positional)
                return cli_error(cmd, "unexpected argument '%s' (%s already given: '%s')", a, cmd->positional,
                                 positional);
            positional = a;
            continue;
        }
        const cli_option *o = NULL;
        for (size_t k = 0; k < cmd->noptions; k++)
            if (!strcmp(a, cmd->options[k].name))
                o = &cmd->options[k];
        if (!o)
            return cli_error(cmd, "unknown option '%s'", a);
        if (o->kind == CLI_FLAG) {
            memcpy((char *)args + o->offset, &o->flag_value, sizeof(int));
            continue;
        }
        if (i + 1 >= argc)
            return cli_error(cmd, "%s needs a value", a);
        pm_status rc = parse_value(cmd, o, argv[++i], args);
        if (rc != PM_OK)
            return rc;
    }
    if (!positional)
        return cli_error(cmd, "%s needs a %s", cmd->name, cmd->positional_what);
    memcpy((char *)args + cmd->positional_offset, &positional, sizeof positional);
    return PM_OK;
}

/* The value of o in `defaults` as text, into buf. */
static const char *default_value(const cli_option *o, const void *defaults, char *buf, size_t cap)
{
    if (o->default_text)
        return o->default_text;
    if (!defaults)
        return NULL;
    const char *src = (const char *)defaults + o->offset;
    switch (o->kind) {
    case CLI_U32: {
        uint32_t u;
        memcpy(&u, src, sizeof u);
        snprintf(buf, cap, "%" PRIu32, u);
        return buf;
    }
    case CLI_U64: {
        uint64_t u;
        memcpy(&u, src, sizeof u);
        snprintf(buf, cap, "%" PRIu64, u);
        return buf;
    }
    case CLI_REAL: {
        double x;
        memcpy(&x, src, sizeof x);
        snprintf(buf, cap, "%g", x);
        return buf;
    }
    case CLI_CHOICE: {
        int i;
        memcpy(&i, src, sizeof i);
        return o->choices[i];
    }
    case CLI_STRING: {
        const char *s;
        memcpy(&s, src, sizeof s);
        return s ? s : "none";
    }
    case CLI_FLAG: {
        int f;
        memcpy(&f, src, sizeof f);
        return f == o->flag_value ? "on" : "off";
    }
    }
    return NULL;
}

void cli_usage(FILE *f, const cli_command *cmd, const void *defaults)
{
    char buf[256], def[64], range[128];
    fprintf(f, "usage: photonmap %s %s [options]\n  %s\n\noptions:\n", cmd->name, cmd->positional, cmd->summary);
    for (size_t k = 0; k < cmd->noptions; k++) {
        const cli_option *o = &cmd->options[k];
        const char *meta = o->metavar ? o->metavar : "";
        if (o->kind == CLI_CHOICE)
            meta = choice_list(o->choices, 1, buf, sizeof buf);
        range[0] = '\0';
        if (o->kind == CLI_U32 || o->kind == CLI_U64)
            snprintf(range, sizeof range, "; an integer in [%" PRIu64 ", %" PRIu64 "]", o->ulo, o->uhi);
        else if (o->kind == CLI_REAL)
            snprintf(range, sizeof range, "; a number in [%g, %g]", o->rlo, o->rhi);
        const char *d = default_value(o, defaults, def, sizeof def);
        fprintf(f, "  %s%s%s\n      %s (default: %s%s)\n", o->name, meta[0] ? " " : "", meta, o->help,
                d ? d : "none", range);
    }
    fprintf(f, "  --help\n      this text\n");
}

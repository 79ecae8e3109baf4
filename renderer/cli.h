/* cli: the command line's option tables and the one parser they drive.
 * Each subcommand describes its options in a table (name, kind, range,
 * where the value goes in the subcommand's argument struct, help); the same
 * table parses argv, reports range errors and prints the usage text with
 * every default and range. Results are pm_status codes (status.h). */
#ifndef PM_CLI_H
#define PM_CLI_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "status.h"

typedef enum {
    CLI_FLAG,   /* no value: stores flag_value in an int */
    CLI_U32,    /* decimal integer in [ulo, uhi] into a uint32_t */
    CLI_U64,    /* decimal integer in [ulo, uhi] into a uint64_t */
    CLI_REAL,   /* finite decimal number in [rlo, rhi] into a double */
    CLI_CHOICE, /* one of choices[] into an int-sized enum (its index) */
    CLI_STRING  /* any non-empty string into a const char * */
} cli_kind;

typedef struct {
    const char *name;           /* "--photons" */
    cli_kind kind;
    const char *metavar;        /* "N" in the usage text (NULL for flags and choices) */
    size_t offset;              /* offsetof(args struct, field) */
    uint64_t ulo, uhi;          /* CLI_U32, CLI_U64 */
    double rlo, rhi;            /* CLI_REAL */
    const char *const *choices; /* CLI_CHOICE: NULL-terminated */
    int flag_value;             /* CLI_FLAG */
    const char *help;
    const char *default_text;   /* shown instead of the default's value when not NULL */
} cli_option;

typedef struct {
    const char *name;            /* "render" */
    const char *summary;         /* one line */
    const char *positional;      /* "SCENE": the one required argument */
    const char *positional_what; /* "scene file": what it names, for messages */
    size_t positional_offset;    /* offsetof(args struct, the const char * it goes to) */
    const cli_option *options;
    size_t noptions;
} cli_command;

/* Parses argv[first..argc) into *args, which holds the defaults on entry.
 * Returns PM_OK when the command should run; PM_DONE after printing the
 * usage on stdout for --help/-h; PM_ERR_INPUT after printing
 * "photonmap: <what is wrong>" on stderr (unknown option, missing or
 * malformed value, value out of range, missing or second positional). */
pm_status cli_parse(const cli_command *cmd, int argc, char **argv, int first, void *args);
/* Prints cmd's usage with every option's range and default (read from
 * `defaults`, an args struct holding the defaults) to f. */
void cli_usage(FILE *f, const cli_command *cmd, const void *defaults);
/* Prints "photonmap: <message>" and the hint to run --help on stderr;
 * returns PM_ERR_INPUT. */
pm_status cli_error(const cli_command *cmd, const char *fmt, ...);

#endif

/* cli: the option table of each subcommand (render, export-pov,
 * export-pbrt, info) and the one parser they drive. A table row names an option,
 * its kind and range, the field of the subcommand's argument struct it
 * fills, and its help line; the same table parses argv, reports range
 * errors and prints the usage text with every default and range. */
#ifndef PM_CLI_H
#define PM_CLI_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "config.h"
#include "pbrt.h"
#include "povray.h"
#include "status.h"

/* The kinds of option value, and where each is stored. */
typedef enum {
    CLI_FLAG,   /* no value: stores flag_value in an int */
    CLI_U32,    /* decimal integer in [ulo, uhi] into a uint32_t */
    CLI_U64,    /* decimal integer in [ulo, uhi] into a uint64_t */
    CLI_REAL,   /* finite decimal number in [rlo, rhi] into a double */
    CLI_CHOICE, /* one of choices[] into an int-sized enum (its index) */
    CLI_STRING  /* any non-empty string into a const char * */
} cli_kind;

/* One row of an option table. */
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

/* A subcommand: its positional argument and its option table. */
typedef struct {
    const char *name;            /* "render" */
    const char *summary;         /* one line */
    const char *positional;      /* "SCENE": the one required argument */
    const char *positional_what; /* "scene file": what it names, for messages */
    size_t positional_offset;    /* offsetof(args struct, the const char * it goes to) */
    const cli_option *options;
    size_t noptions;
} cli_command;

/* The most options a command may have. */
#define CLI_MAX_OPTIONS 64

/* Which of a command's options the command line gave, by table row. */
typedef struct {
    unsigned char given[CLI_MAX_OPTIONS];
} cli_given;

/* Parses argv[first..argc) into *args, which holds the defaults on entry,
 * and records in *given (NULL: nowhere) which options appeared. Returns
 * PM_OK when the command should run; PM_DONE after printing the usage on
 * stdout for --help/-h; PM_ERR_INPUT after printing "photonmap: <what is
 * wrong>" on stderr (unknown option, missing or malformed value, value out
 * of range, missing or second positional). */
pm_status cli_parse(const cli_command *cmd, int argc, char **argv, int first, void *args, cli_given *given);
/* 1 when option `name` of cmd was given, else 0; name must be in the table. */
int cli_was_given(const cli_command *cmd, const cli_given *given, const char *name);
/* Prints cmd's usage with every option's range and default (read from
 * `defaults`, an args struct holding the defaults) to f. */
void cli_usage(FILE *f, const cli_command *cmd, const void *defaults);
/* Prints "photonmap: <message>" and the hint to run --help on stderr;
 * returns PM_ERR_INPUT. */
pm_status cli_error(const cli_command *cmd, const char *fmt, ...);

/* `photonmap render`'s arguments. */
typedef struct {
    config_render cfg;
    const char *scene;
    const char *exr, *png, *stats;
    double exposure;
    int quiet;
    int no_output; /* --no-output: a render for its times only, no file */
    const char *repeats; /* --repeats: "auto" or a count (repeat_parse); NULL: the default */
    cli_given given;
} cli_render_args;

/* `photonmap export-pov`'s arguments. */
typedef struct {
    povray_options pov;
    const char *scene, *out;
} cli_pov_args;

/* `photonmap export-pbrt`'s arguments. */
typedef struct {
    pbrt_options pbrt;
    const char *scene, *out;
} cli_pbrt_args;

/* `photonmap info`'s arguments. */
typedef struct {
    const char *scene;
    int json;              /* --json: the one output format, required */
    uint32_t width, height; /* the image size of the camera basis */
} cli_info_args;

/* The subcommands' tables. */
extern const cli_command cli_render;
extern const cli_command cli_export_pov;
extern const cli_command cli_export_pbrt;
extern const cli_command cli_info;

/* Each subcommand's arguments holding the defaults; never fail. */
cli_render_args cli_render_defaults(void);
cli_pov_args cli_pov_defaults(void);
cli_pbrt_args cli_pbrt_defaults(void);
cli_info_args cli_info_defaults(void);

/* Settles the settings whose default depends on others: with --gather and
 * no --direct, direct light comes by shadow rays. Never fails. */
void cli_render_resolve(cli_render_args *a);
/* Refuses render arguments that do not go together: options given together
 * that exclude each other, config_check's refusals, an image too large.
 * Returns PM_OK, or PM_ERR_INPUT after printing why (cli_error). */
pm_status cli_render_check(const cli_render_args *a);

#endif

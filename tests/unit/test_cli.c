/* test_cli: the table-driven option parser on a small table of every kind:
 * values land in their fields, ranges and malformed values are refused
 * (the negative controls: each refused argv must leave PM_ERR_INPUT), and
 * the usage text shows every default and range. */
#include <fcntl.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "check.h"
#include "cli.h"
#include "tests.h"

typedef struct {
    const char *pos;
    uint32_t u32;
    uint64_t u64;
    double real;
    int choice;
    int flag;
    const char *str;
} cli_test_args;

static const char *const colours[] = {"red", "green", "blue", NULL};

#define TO(field) offsetof(cli_test_args, field)
static const cli_option test_options[] = {
    {.name = "--u32", .kind = CLI_U32, .metavar = "N", .offset = TO(u32), .ulo = 2, .uhi = 10, .help = "a u32"},
    {.name = "--u64", .kind = CLI_U64, .metavar = "N", .offset = TO(u64), .uhi = UINT64_MAX, .help = "a u64"},
    {.name = "--real", .kind = CLI_REAL, .metavar = "X", .offset = TO(real), .rlo = -1.0, .rhi = 1.0, .help = "a real"},
    {.name = "--colour", .kind = CLI_CHOICE, .offset = TO(choice), .choices = colours, .help = "a choice"},
    {.name = "--flag", .kind = CLI_FLAG, .offset = TO(flag), .flag_value = 1, .help = "a flag"},
    {.name = "--str", .kind = CLI_STRING, .metavar = "S", .offset = TO(str), .help = "a string",
     .default_text = "nothing"},
};
#undef TO

static const cli_command test_command = {
    .name = "try",
    .summary = "a test command",
    .positional = "THING",
    .positional_what = "thing",
    .positional_offset = offsetof(cli_test_args, pos),
    .options = test_options,
    .noptions = sizeof test_options / sizeof test_options[0]};

static cli_test_args defaults(void)
{
    cli_test_args a;
    memset(&a, 0, sizeof a);
    a.u32 = 5;
    a.real = 0.5;
    a.choice = 1;
    return a;
}

/* cli_parse of the NULL-terminated words after "photonmap try". */
static pm_status parse(cli_test_args *a, const char *const *words)
{
    char *argv[16];
    int argc = 0;
    argv[argc++] = (char *)"photonmap";
    argv[argc++] = (char *)"try";
    while (*words && argc < 15)
        argv[argc++] = (char *)*words++;
    argv[argc] = NULL;
    *a = defaults();
    return cli_parse(&test_command, argc, argv, 2, a, NULL);
}

void test_cli_parses_every_kind(void)
{
    cli_test_args a;
    const char *ok[] = {"x.scene", "--u32", "10", "--u64", "+18446744073709551615", "--real", "-0.25",
                        "--colour", "blue", "--flag", "--str", "hello", NULL};
    CHECK(parse(&a, ok) == PM_OK);
    CHECK(a.pos && !strcmp(a.pos, "x.scene"));
    CHECK(a.u32 == 10 && a.u64 == UINT64_MAX && a.real == -0.25 && a.choice == 2 && a.flag == 1);
    CHECK(a.str && !strcmp(a.str, "hello"));
    /* untouched options keep their defaults */
    const char *only_pos[] = {"y", NULL};
    CHECK(parse(&a, only_pos) == PM_OK && a.u32 == 5 && a.real == 0.5 && a.choice == 1 && a.flag == 0 && !a.str);

    /* negative controls: each of these must be refused as a user error */
    const char *bad[][4] = {
        {"x", "--u32", "1", NULL},      /* below the range */
        {"x", "--u32", "11", NULL},     /* above it */
        {"x", "--u32", "3x", NULL},     /* trailing garbage */
        {"x", "--u32", "-3", NULL},     /* a sign */
        {"x", "--u64", "18446744073709551616", NULL}, /* overflow */
        {"x", "--real", "1.5", NULL},   /* out of range */
        {"x", "--real", "nan", NULL},   /* not a decimal number */
        {"x", "--real", "0x1p-2", NULL},/* hex float */
        {"x", "--colour", "pink", NULL},/* not a choice */
        {"x", "--str", "", NULL},       /* empty string */
        {"x", "--nope", NULL, NULL},    /* unknown option */
        {"x", "--u32", NULL, NULL},     /* missing value */
        {"x", "y", NULL, NULL},         /* a second positional */
        {"--flag", NULL, NULL, NULL},   /* no positional */
    };
    enum { NBAD = sizeof bad / sizeof bad[0] };
    pm_status rc[NBAD];
    /* the parser explains each refusal on stderr: not in the test log */
    fflush(stderr);
    int saved = dup(STDERR_FILENO), null = open("/dev/null", O_WRONLY);
    if (saved >= 0 && null >= 0)
        dup2(null, STDERR_FILENO);
    for (size_t i = 0; i < NBAD; i++)
        rc[i] = parse(&a, bad[i]);
    fflush(stderr);
    if (saved >= 0 && null >= 0)
        dup2(saved, STDERR_FILENO);
    if (saved >= 0)
        close(saved);
    if (null >= 0)
        close(null);
    for (size_t i = 0; i < NBAD; i++) {
        CHECK_MSG(rc[i] == PM_ERR_INPUT, "case %zu (%s %s) gave %d", i, bad[i][1] ? bad[i][1] : "", bad[i][2] ? bad[i][2] : "",
                  (int)rc[i]);
    }
}

void test_cli_usage_lists_defaults_and_ranges(void)
{
    cli_test_args d = defaults();
    FILE *f = tmpfile();
    CHECK(f != NULL);
    if (!f)
        return;
    cli_usage(f, &test_command, &d);
    char buf[4096];
    rewind(f);
    size_t n = fread(buf, 1, sizeof buf - 1, f);
    buf[n] = '\0';
    fclose(f);
    CHECK(strstr(buf, "usage: photonmap try THING [options]") != NULL);
    CHECK(strstr(buf, "--u32 N\n      a u32 (default: 5; an integer in [2, 10])") != NULL);
    CHECK(strstr(buf, "--real X\n      a real (default: 0.5; a number in [-1, 1])") != NULL);
    CHECK(strstr(buf, "--colour red|green|blue\n      a choice (default: green)") != NULL);
    CHECK(strstr(buf, "--flag\n      a flag (default: off)") != NULL);
    CHECK(strstr(buf, "a string (default: nothing)") != NULL);
    /* negative control: a default the table does not hold is not shown */
    CHECK(strstr(buf, "default: 6;") == NULL);
}

/* render's arguments: which options were given, not their values, decide
 * the refusals of options that exclude each other. */
void test_cli_render_given(void)
{
    char *ok[] = {"photonmap", "render", "s.scene", "--rep-count", "10", "--rep-every", "4", NULL};
    cli_render_args a = cli_render_defaults();
    CHECK(cli_parse(&cli_render, 7, ok, 2, &a, &a.given) == PM_OK);
    CHECK(cli_was_given(&cli_render, &a.given, "--rep-count") && cli_was_given(&cli_render, &a.given, "--rep-every"));
    CHECK(!cli_was_given(&cli_render, &a.given, "--nn"));
    /* --rep-every 4 is the default: given all the same, so refused */
    CHECK(a.cfg.rep_every == CONFIG_DEFAULT_REP_EVERY && cli_render_check(&a) == PM_ERR_INPUT);
    char *one[] = {"photonmap", "render", "s.scene", "--rep-count", "10", "--method", "precomputed", NULL};
    a = cli_render_defaults();
    CHECK(cli_parse(&cli_render, 7, one, 2, &a, &a.given) == PM_OK && cli_render_check(&a) == PM_OK);
    char *tau[] = {"photonmap", "render", "s.scene", "--rep-gate-tau", "0.1", NULL};
    a = cli_render_defaults();
    CHECK(cli_parse(&cli_render, 5, tau, 2, &a, &a.given) == PM_OK && cli_render_check(&a) == PM_ERR_INPUT);
}

/* main: runs every unit test of tests.list.h (or those named on the
 * command line), prints each result and "N passed, N failed, N skipped";
 * exit 1 on failure. */
#include <stdio.h>
#include <string.h>

#include "check.h"
#include "tests.h"

static check_state current;

check_state *check_current(void)
{
    return &current;
}

typedef struct {
    const char *name;
    void (*fn)(void);
} test_entry;

static const test_entry all_tests[] = {
#define X(name) {#name, test_##name},
#include "tests.list.h"
#undef X
};

int main(int argc, char **argv)
{
    int passed = 0, failed = 0, skipped = 0;
    for (size_t i = 0; i < sizeof all_tests / sizeof all_tests[0]; i++) {
        if (argc > 1) {
            int wanted = 0;
            for (int a = 1; a < argc; a++)
                wanted |= strcmp(argv[a], all_tests[i].name) == 0;
            if (!wanted)
                continue;
        }
        current.failures = 0;
        current.skipped = NULL;
        all_tests[i].fn();
        if (current.failures > 0) {
            failed++;
            printf("FAIL %s (%d checks)\n", all_tests[i].name, current.failures);
        } else if (current.skipped) {
            skipped++;
            printf("skip %s (%s)\n", all_tests[i].name, current.skipped);
        } else {
            passed++;
            printf("ok   %s\n", all_tests[i].name);
        }
        fflush(stdout);
    }
    printf("%d passed, %d failed, %d skipped\n", passed, failed, skipped);
    return failed ? 1 : 0;
}

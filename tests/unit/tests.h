/* tests: the unit tests. Each is a function `void test_NAME(void)`, its
 * definition starting a line of tests/unit/test_MODULE.c, the file of the
 * module it tests; the build collects them into tests.list.h (one X(NAME)
 * per test, Makefile), so adding a test touches its own file only. */
#ifndef PM_TESTS_H
#define PM_TESTS_H

#define X(name) void test_##name(void);
#include "tests.list.h"
#undef X

#endif

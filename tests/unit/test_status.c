/* test_status: every result code has a message and the documented exit
 * code (0 done, 2 user input error, 1 runtime failure). */
#include <string.h>

#include "check.h"
#include "status.h"
#include "tests.h"

void test_status_codes(void)
{
    CHECK(PM_OK == 0);
    CHECK(pm_status_exit(PM_OK) == 0 && pm_status_exit(PM_DONE) == 0);
    CHECK(pm_status_exit(PM_ERR_INPUT) == 2);
    CHECK(pm_status_exit(PM_ERR_NOMEM) == 1 && pm_status_exit(PM_ERR_IO) == 1);
    CHECK(!strcmp(pm_status_message(PM_ERR_NOMEM), "out of memory"));
    const pm_status all[] = {PM_OK, PM_DONE, PM_ERR_INPUT, PM_ERR_NOMEM, PM_ERR_IO};
    for (size_t i = 0; i < sizeof all / sizeof all[0]; i++) {
        const char *m = pm_status_message(all[i]);
        CHECK(m && m[0]);
        for (size_t j = 0; j < i; j++) /* negative control: no two codes share a message */
            CHECK(strcmp(m, pm_status_message(all[j])) != 0);
    }
}

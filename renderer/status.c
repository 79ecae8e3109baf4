/* status: result codes to messages and exit codes (status.h). */
#include "status.h"

const char *pm_status_message(pm_status s)
{
    switch (s) {
    case PM_OK:
        return "ok";
    case PM_DONE:
        return "done";
    case PM_ERR_INPUT:
        return "input error";
    case PM_ERR_NOMEM:
        return "out of memory";
    case PM_ERR_IO:
        return "input/output error";
    }
    return "unknown status";
}

int pm_status_exit(pm_status s)
{
    switch (s) {
    case PM_OK:
    case PM_DONE:
        return 0;
    case PM_ERR_INPUT:
        return 2;
    case PM_ERR_NOMEM:
    case PM_ERR_IO:
        return 1;
    }
    return 1;
}

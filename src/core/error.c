#include "core/error.h"

#include <stdarg.h>
#include <stdio.h>

static _Thread_local char last_error[512];
static _Thread_local neuv_status last_status;

neuv_status error_set(neuv_status code, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(last_error, sizeof last_error, fmt, ap);
    va_end(ap);
    last_status = code;
    return code;
}

neuv_status error_nomem(const char *what)
{
    return error_set(NEUV_ERR_NOMEM, "out of memory allocating %s", what);
}

neuv_status error_cancelled(void)
{
    return error_set(NEUV_ERR_CANCELLED, "cancelled: the progress callback returned 0");
}

neuv_status error_last(void) { return last_status != NEUV_OK ? last_status : NEUV_ERR_INTERNAL; }

void error_clear(void) { last_error[0] = '\0'; last_status = NEUV_OK; }

const char *neuv_last_error(void) { return last_error; }

const char *neuv_status_name(neuv_status status)
{
    switch (status) {
    case NEUV_OK: return "ok";
    case NEUV_ERR_INTERNAL: return "internal error";
    case NEUV_ERR_INPUT: return "bad input";
    case NEUV_ERR_IO: return "input/output error";
    case NEUV_ERR_NOMEM: return "out of memory";
    case NEUV_ERR_CANCELLED: return "cancelled";
    }
    return "unknown status";
}

int neuv_exit_code(neuv_status status)
{
    switch (status) {
    case NEUV_OK: return 0;
    case NEUV_ERR_INPUT:
    case NEUV_ERR_IO:
    case NEUV_ERR_NOMEM:
    case NEUV_ERR_CANCELLED: return 2;
    default: return 1;
    }
}

const char *neuv_version(void) { return NEUV_VERSION; }

/* Error reporting: a status code plus a per-thread one-line message. */
#ifndef NEUV_CORE_ERROR_H
#define NEUV_CORE_ERROR_H

#include "neuv/neuv.h"

/* Records a formatted message for neuv_last_error() and returns `code`,
 * so failures read `return error_set(NEUV_ERR_INPUT, "face %d ...", f);`. */
neuv_status error_set(neuv_status code, const char *fmt, ...)
    __attribute__((format(printf, 2, 3)));
/* Shorthand for an allocation failure of `what`. */
neuv_status error_nomem(const char *what);
/* NEUV_ERR_CANCELLED with its message, for a stage that stops because the
 * progress callback asked it to (core/log.h log_cancelled). */
neuv_status error_cancelled(void);
/* The status of the last error_set on this thread (NEUV_ERR_INTERNAL when
 * none), for a caller of a function that reports failure by returning NULL
 * or -1 after error_set: `if (!p) return error_last();`. */
neuv_status error_last(void);
void error_clear(void);

#endif

/* Logging, progress and cancellation through the callbacks of the public
 * call in progress on this thread.
 *
 * A public entry point that runs long (an unwrap, a training) opens a scope
 * with the caller's neuv_callbacks for its duration; log_message and
 * log_progress inside it reach those callbacks, and a progress callback that
 * returns 0 marks the scope cancelled, which the stages poll with
 * log_cancelled() to stop with NEUV_ERR_CANCELLED. Scopes nest (an inner
 * scope replaces the outer one until it closes) and belong to one thread:
 * two unwraps on two threads report to their own callbacks. Messages from
 * OpenMP worker threads are not forwarded (none is sent from them). */
#ifndef NEUV_CORE_LOG_H
#define NEUV_CORE_LOG_H

#include "neuv/neuv.h"

typedef struct log_scope {
    neuv_callbacks callbacks;
    int cancelled;
    struct log_scope *outer;
} log_scope;

/* Opens `scope` on this thread with a copy of cb (NULL: silent, never
 * cancelled). Every log_scope_open is paired with log_scope_close. */
void log_scope_open(log_scope *scope, const neuv_callbacks *cb);
void log_scope_close(log_scope *scope);

void log_message(neuv_log_level level, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
/* Reports progress of `stage`; detail may be NULL. Cheap when no callback is
 * set. Returns 1 when the callback asked to cancel (now or earlier in this
 * scope), 0 otherwise. */
int log_progress(const char *stage, double fraction, const char *detail_fmt, ...)
    __attribute__((format(printf, 3, 4)));
/* 1 when the progress callback of this thread's scope has asked to cancel. */
int log_cancelled(void);

#endif

#include "core/log.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

/* The scope of the public call in progress on this thread (NULL: none, so
 * messages go nowhere). Thread-local by design: it is the dynamic extent of
 * one call, not a setting shared between calls. */
static _Thread_local log_scope *current;

void log_scope_open(log_scope *scope, const neuv_callbacks *cb)
{
    memset(scope, 0, sizeof *scope);
    if (cb) scope->callbacks = *cb;
    scope->outer = current;
    current = scope;
}

void log_scope_close(log_scope *scope)
{
    if (current == scope) current = scope->outer;
}

void log_message(neuv_log_level level, const char *fmt, ...)
{
    if (!current || !current->callbacks.log) return;
    char buf[1024];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(buf, sizeof buf, fmt, ap);
    va_end(ap);
    current->callbacks.log(current->callbacks.user, level, buf);
}

int log_progress(const char *stage, double fraction, const char *detail_fmt, ...)
{
    if (!current) return 0;
    if (current->cancelled || !current->callbacks.progress) return current->cancelled;
    char buf[256];
    buf[0] = '\0';
    if (detail_fmt) {
        va_list ap;
        va_start(ap, detail_fmt);
        vsnprintf(buf, sizeof buf, detail_fmt, ap);
        va_end(ap);
    }
    if (!current->callbacks.progress(current->callbacks.user, stage, fraction, detail_fmt ? buf : NULL))
        current->cancelled = 1;
    return current->cancelled;
}

int log_cancelled(void) { return current && current->cancelled; }

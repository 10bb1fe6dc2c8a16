#include "core/log.h"

#include <stdarg.h>
#include <stdio.h>

static neuv_log_fn log_fn;
static neuv_progress_fn progress_fn;
static void *callback_user;

void neuv_set_callbacks(neuv_log_fn log, neuv_progress_fn progress, void *user)
{
    log_fn = log;
    progress_fn = progress;
    callback_user = user;
}

void log_message(neuv_log_level level, const char *fmt, ...)
{
    if (!log_fn) return;
    char buf[1024];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(buf, sizeof buf, fmt, ap);
    va_end(ap);
    log_fn(callback_user, level, buf);
}

void log_progress(const char *stage, double fraction, const char *detail_fmt, ...)
{
    if (!progress_fn) return;
    char buf[256];
    buf[0] = '\0';
    if (detail_fmt) {
        va_list ap;
        va_start(ap, detail_fmt);
        vsnprintf(buf, sizeof buf, detail_fmt, ap);
        va_end(ap);
    }
    progress_fn(callback_user, stage, fraction, detail_fmt ? buf : NULL);
}

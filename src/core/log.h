/* Logging and progress through the callbacks the application installed. */
#ifndef NEUV_CORE_LOG_H
#define NEUV_CORE_LOG_H

#include "neuv/neuv.h"

void log_message(neuv_log_level level, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
/* Reports progress of `stage`; detail may be NULL. Cheap when no callback is set. */
void log_progress(const char *stage, double fraction, const char *detail_fmt, ...)
    __attribute__((format(printf, 3, 4)));

#endif

#ifndef NEUV_CORE_TIMER_H
#define NEUV_CORE_TIMER_H
/* Monotonic wall-clock seconds. */
double now_seconds(void);
#endif

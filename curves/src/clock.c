/* The one monotonic clock (clock_internal.h). Monotonic, not the wall clock: a step of the
 * system time must not turn a measured duration negative. */
#define _POSIX_C_SOURCE 200809L
#include "clock_internal.h"

#include <time.h>

double cj_clock_seconds(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

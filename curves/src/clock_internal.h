/* Private, shared by every layer (as error_internal.h): the one monotonic clock the library's
 * stage timings, the solvers' statistics and the viewer's frame clock read. */
#ifndef CASTELJAU_CLOCK_INTERNAL_H
#define CASTELJAU_CLOCK_INTERNAL_H

/* Seconds of CLOCK_MONOTONIC (an arbitrary origin; differences only). */
double cj_clock_seconds(void);

#endif

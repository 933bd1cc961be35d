/* Private: the single funnel every failure passes through (set a breakpoint on cj_fail). */
#ifndef CASTELJAU_ERROR_INTERNAL_H
#define CASTELJAU_ERROR_INTERNAL_H

#include "casteljau/status.h"
#include <stddef.h>

#if defined(__GNUC__)
#define CJ_PRINTF(a, b) __attribute__((format(printf, a, b)))
#else
#define CJ_PRINTF(a, b)
#endif

#ifdef __cplusplus
extern "C" {
#endif

/* Records a formatted message for cj_last_error() and returns `status` unchanged, so that
 * callers write `return cj_fail(CJ_ERR_EMPTY, "no control points");`. */
cj_status cj_fail(cj_status status, const char *fmt, ...) CJ_PRINTF(2, 3);

/* Validates `count` values: all finite, else CJ_ERR_NONFINITE naming `what` and the index. */
cj_status cj_check_finite(const double *values, size_t count, const char *what);

/* Validates point data (count points of dimension dim): finite, else CJ_ERR_NONFINITE naming
 * the point and coordinate. */
cj_status cj_check_points(const double *pts, size_t count, int dim, const char *what);

#ifdef __cplusplus
}
#endif
#endif

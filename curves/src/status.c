#include "error_internal.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>

/* Thread-local like errno: a message per thread, no shared mutable state between threads. */
static _Thread_local char last_message[512];

static const char *const status_names[CJ_STATUS_COUNT_] = {
    [CJ_OK] = "ok",
    [CJ_ERR_NONFINITE] = "NaN or infinite value",
    [CJ_ERR_EMPTY] = "empty input",
    [CJ_ERR_DIMENSION] = "bad or mismatched dimension",
    [CJ_ERR_DEGREE] = "degree above the method's limit",
    [CJ_ERR_RANGE] = "parameter out of range",
    [CJ_ERR_ARGUMENT] = "invalid argument",
    [CJ_ERR_DEGENERATE] = "degenerate geometry",
    [CJ_ERR_SINGULAR] = "singular or inconsistent system",
    [CJ_ERR_CAP] = "internal cap reached",
    [CJ_ERR_BUFFER] = "buffer too small",
    [CJ_ERR_NOMEM] = "out of memory",
    [CJ_ERR_IO] = "input/output error",
    [CJ_ERR_PARSE] = "malformed input",
    [CJ_ERR_UNSUPPORTED] = "not supported",
    [CJ_ERR_CANCELLED] = "cancelled",
};

const char *cj_status_str(cj_status status) {
    if ((unsigned)status >= CJ_STATUS_COUNT_) return "unknown status";
    return status_names[status];
}

const char *cj_last_error(void) {
    return last_message;
}

cj_status cj_fail(cj_status status, const char *fmt, ...) {
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(last_message, sizeof last_message, fmt, ap);
    va_end(ap);
    return status;
}

cj_status cj_check_finite(const double *values, size_t count, const char *what) {
    for (size_t i = 0; i < count; ++i)
        if (!isfinite(values[i]))
            return cj_fail(CJ_ERR_NONFINITE, "%s %zu is %s", what, i,
                           isnan(values[i]) ? "NaN" : "infinite");
    return CJ_OK;
}

cj_status cj_check_points(const double *pts, size_t count, int dim, const char *what) {
    for (size_t i = 0; i < count; ++i)
        for (int k = 0; k < dim; ++k) {
            double v = pts[i * (size_t)dim + (size_t)k];
            if (!isfinite(v))
                return cj_fail(CJ_ERR_NONFINITE, "%s %zu, coordinate %d is %s", what, i, k,
                               isnan(v) ? "NaN" : "infinite");
        }
    return CJ_OK;
}

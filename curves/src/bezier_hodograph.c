#include "bezier_internal.h"

#include <assert.h>
#include <math.h>
#include <string.h>

cj_status cj_bezier_hodograph(const cj_bezier *c, int k, double *out) {
    assert(out != NULL);
    cj_status st = cj_bezier_check(c, CJ_BEZIER_MAX_DEGREE);
    if (st) return st;
    if (k < 0) return cj_fail(CJ_ERR_ARGUMENT, "derivative order %d is negative", k);
    const int n = c->degree, d = c->dim;
    if (k > n) {
        memset(out, 0, sizeof(double) * (size_t)d);
        return CJ_OK;
    }
    double w[CJ_BEZIER_WORK];
    memcpy(w, c->pts, sizeof(double) * (size_t)(n + 1) * (size_t)d);
    /* Differences one order at a time, scaling by the degree of that order, so that each
     * level is itself the hodograph of the previous one (no large factorial formed at once). */
    for (int q = 0; q < k; ++q) {
        const double m = (double)(n - q);
        for (int i = 0; i < (n - q) * d; ++i) w[i] = m * (w[i + d] - w[i]);
    }
    /* The factor n!/(n-k)! can push the points past the double range for high orders of
     * high-degree curves: report it rather than hand back infinities (out stays untouched). */
    const size_t count = (size_t)(n - k + 1) * (size_t)d;
    for (size_t i = 0; i < count; ++i)
        if (!isfinite(w[i]))
            return cj_fail(CJ_ERR_RANGE,
                           "hodograph of order %d: control point %zu overflows the double range", k,
                           i / (size_t)d);
    memcpy(out, w, sizeof(double) * count);
    return CJ_OK;
}

/* Pieces of a curve (subcurve), degree elevation and reversal. */
#include "bezier_internal.h"

#include <assert.h>
#include <string.h>

cj_status cj_bezier_subcurve(const cj_bezier *c, double a, double b, double *out) {
    assert(out != NULL);
    cj_status st = cj_bezier_check(c, CJ_BEZIER_MAX_DEGREE);
    if (st) return st;
    if ((st = cj_check_param(a, "subcurve start a"))) return st;
    if ((st = cj_check_param(b, "subcurve end b"))) return st;
    if (a < 0.0 || a > 1.0)
        return cj_fail(CJ_ERR_RANGE, "subcurve start a = %.17g is outside [0,1]", a);
    if (b < 0.0 || b > 1.0)
        return cj_fail(CJ_ERR_RANGE, "subcurve end b = %.17g is outside [0,1]", b);
    if (a == b)
        return cj_fail(CJ_ERR_ARGUMENT, "subcurve interval [a,b] is empty (a = b = %.17g)", a);
    const int n = c->degree, d = c->dim;
    const size_t count = (size_t)(n + 1) * (size_t)d;
    const int reversed = a > b;
    const double lo = reversed ? b : a, hi = reversed ? a : b;
    /* c on [0,hi] first, then its right part from lo/hi: both steps are convex combinations,
     * and the ratio lo/hi lies in [0,1). */
    double left[CJ_BEZIER_WORK], piece[CJ_BEZIER_WORK];
    if (hi == 1.0)
        memcpy(left, c->pts, sizeof(double) * count);
    else
        (void)cj_bezier_split(c, hi, left, NULL);
    if (lo == 0.0) {
        memcpy(piece, left, sizeof(double) * count);
    } else {
        cj_bezier lc = cj_bezier_view(n, d, left);
        (void)cj_bezier_split(&lc, lo / hi, NULL, piece);
    }
    if (reversed) {
        for (int i = 0; i <= n; ++i)
            memcpy(out + (size_t)i * d, piece + (size_t)(n - i) * d, sizeof(double) * (size_t)d);
    } else {
        memcpy(out, piece, sizeof(double) * count);
    }
    return CJ_OK;
}

cj_status cj_bezier_elevate(const cj_bezier *c, int r, double *out) {
    assert(out != NULL);
    cj_status st = cj_bezier_check(c, CJ_BEZIER_MAX_DEGREE);
    if (st) return st;
    if (r < 0) return cj_fail(CJ_ERR_ARGUMENT, "elevation step count r = %d is negative", r);
    if (r > CJ_BEZIER_MAX_DEGREE - c->degree)
        return cj_fail(CJ_ERR_DEGREE, "elevating degree %d by %d exceeds the limit of %d",
                       c->degree, r, CJ_BEZIER_MAX_DEGREE);
    const int d = c->dim;
    int n = c->degree;
    double w[CJ_BEZIER_WORK];
    memcpy(w, c->pts, sizeof(double) * (size_t)(n + 1) * (size_t)d);
    /* One step at a time: b'_i = (i/(n+1)) b_{i-1} + (1 - i/(n+1)) b_i, i = 0..n+1, a convex
     * combination (no large binomials). Running i downwards lets the update happen in place. */
    for (int step = 0; step < r; ++step, ++n) {
        const double inv = 1.0 / (double)(n + 1);
        memcpy(w + (size_t)(n + 1) * d, w + (size_t)n * d, sizeof(double) * (size_t)d);
        for (int i = n; i >= 1; --i) {
            const double alpha = (double)i * inv, beta = (double)(n + 1 - i) * inv;
            for (int k = 0; k < d; ++k)
                w[(size_t)i * d + k] =
                    alpha * w[(size_t)(i - 1) * d + k] + beta * w[(size_t)i * d + k];
        }
    }
    memcpy(out, w, sizeof(double) * (size_t)(n + 1) * (size_t)d);
    return CJ_OK;
}

cj_status cj_bezier_reverse(const cj_bezier *c, double *out) {
    assert(out != NULL);
    cj_status st = cj_bezier_check(c, CJ_BEZIER_MAX_DEGREE);
    if (st) return st;
    const int n = c->degree, d = c->dim;
    if (out != c->pts) memcpy(out, c->pts, sizeof(double) * (size_t)(n + 1) * (size_t)d);
    for (int i = 0, j = n; i < j; ++i, --j)
        for (int k = 0; k < d; ++k) {
            double tmp = out[(size_t)i * d + k];
            out[(size_t)i * d + k] = out[(size_t)j * d + k];
            out[(size_t)j * d + k] = tmp;
        }
    return CJ_OK;
}

/* The de Casteljau triangle: evaluation, derivatives and subdivision. */
#include "bezier_internal.h"
#include "eval_internal.h"

#include <assert.h>
#include <string.h>

/* Runs the triangle in place on w[(m+1)*d] down to one point: w[0..d-1] = value at t. */
static void decasteljau_collapse(double *w, int m, int d, double t) {
    const double s = 1.0 - t;
    for (int r = m; r > 0; --r)
        for (int i = 0; i < r * d; ++i) w[i] = s * w[i] + t * w[i + d];
}

/* The triangle with the dimension a compile-time constant at each call site below (so the
 * inner loops unroll), reading the control points directly for the first level instead of
 * copying them. Three roundings per level and path (fl(1-t), the product, the sum): the
 * classical bound |res - c(t)| <= gamma(3n) Σ|b_i| B_i^n(t) for t in [0,1]. */
CJ_ALWAYS_INLINE void dc_run(const double *restrict p, int n, int d, double t,
                             double *restrict out) {
    if (n == 0) {
        for (int k = 0; k < d; ++k) out[k] = p[k];
        return;
    }
    double w[CJ_BEZIER_WORK];
    const double s = 1.0 - t;
    for (int i = 0; i < n * d; ++i) w[i] = s * p[i] + t * p[i + d];
    for (int r = n - 1; r > 0; --r)
        for (int i = 0; i < r * d; ++i) w[i] = s * w[i] + t * w[i + d];
    for (int k = 0; k < d; ++k) out[k] = w[k];
}

/* Cubics (the common case) get their own instances with the degree a constant too: the loops
 * unroll completely and the triangle stays in registers. Same arithmetic, same bits. */
#define CJ_DC_DIM(d)                                                                               \
    do {                                                                                           \
        if (c->degree == 3)                                                                        \
            dc_run(c->pts, 3, d, t, out);                                                          \
        else                                                                                       \
            dc_run(c->pts, c->degree, d, t, out);                                                  \
    } while (0)

void cj_decasteljau_kernel(const cj_bezier *c, double t, double *out) {
    switch (c->dim) {
    case 1:
        CJ_DC_DIM(1);
        break;
    case 2:
        CJ_DC_DIM(2);
        break;
    case 3:
        CJ_DC_DIM(3);
        break;
    case 4:
        CJ_DC_DIM(4);
        break;
    default:
        dc_run(c->pts, c->degree, c->dim, t, out);
        break;
    }
}

cj_status cj_bezier_eval_decasteljau(const cj_bezier *c, double t, double *out) {
    assert(out != NULL);
    cj_status st = cj_bezier_check(c, CJ_BEZIER_MAX_DEGREE);
    if (st) return st;
    if ((st = cj_check_param(t, "parameter t"))) return st;
    double v[CJ_MAX_DIM];
    cj_decasteljau_kernel(c, t, v);
    if ((st = cj_check_value(v, c->dim, t))) return st;
    cj_copy_point(out, v, c->dim);
    return CJ_OK;
}

cj_status cj_bezier_eval_derivs(const cj_bezier *c, double t, int kmax, double *out) {
    assert(out != NULL);
    cj_status st = cj_bezier_check(c, CJ_BEZIER_MAX_DEGREE);
    if (st) return st;
    if ((st = cj_check_param(t, "parameter t"))) return st;
    if (kmax < 0) return cj_fail(CJ_ERR_ARGUMENT, "derivative order %d is negative", kmax);
    const int n = c->degree, d = c->dim;
    const int kk = kmax < n ? kmax : n;
    /* c^(j)(t) = n!/(n-j)! Δ^j b_0^(n-j)(t), where b^(r) is level r of the triangle. Running
     * n-kk levels once leaves kk+1 points; since de Casteljau steps and forward differences
     * are both shift-invariant linear maps they commute, so each order j takes j differences
     * of those points and then the remaining kk-j steps. */
    double w[CJ_BEZIER_WORK];
    memcpy(w, c->pts, sizeof(double) * (size_t)(n + 1) * (size_t)d);
    const double s = 1.0 - t;
    for (int r = n; r > kk; --r)
        for (int i = 0; i < r * d; ++i) w[i] = s * w[i] + t * w[i + d];
    /* Each difference level is scaled by its degree as it is formed (as in the hodograph), not
     * by n!/(n-j)! at the end: that factor overflows for high orders even when the derivative
     * does not, and inf * 0 would be a NaN. Results go to a local buffer first so that an
     * overflow (far extrapolation) leaves out untouched. */
    double res[CJ_BEZIER_WORK];
    for (int j = 0; j <= kk; ++j) {
        double tmp[CJ_BEZIER_WORK];
        const int m = kk; /* points 0..m */
        memcpy(tmp, w, sizeof(double) * (size_t)(m + 1) * (size_t)d);
        for (int q = 0; q < j; ++q) { /* j scaled differences: m-q points remain */
            const double f = (double)(n - q);
            for (int i = 0; i < (m - q) * d; ++i) tmp[i] = f * (tmp[i + d] - tmp[i]);
        }
        decasteljau_collapse(tmp, m - j, d, t);
        for (int k = 0; k < d; ++k) res[j * d + k] = tmp[k];
        if ((st = cj_check_value(res + j * d, d, t)))
            return cj_fail(CJ_ERR_RANGE,
                           "derivative of order %d at t = %.17g overflows the double range", j, t);
    }
    memcpy(out, res, sizeof(double) * (size_t)(kk + 1) * (size_t)d);
    for (int j = kk + 1; j <= kmax; ++j)
        for (int k = 0; k < d; ++k) out[j * d + k] = 0.0;
    return CJ_OK;
}

cj_status cj_bezier_split(const cj_bezier *c, double t, double *left, double *right) {
    cj_status st = cj_bezier_check(c, CJ_BEZIER_MAX_DEGREE);
    if (st) return st;
    if ((st = cj_check_param(t, "split parameter t"))) return st;
    if (t < 0.0 || t > 1.0)
        return cj_fail(CJ_ERR_RANGE, "split parameter t = %.17g is outside [0,1]", t);
    const int n = c->degree, d = c->dim;
    double w[CJ_BEZIER_WORK];
    memcpy(w, c->pts, sizeof(double) * (size_t)(n + 1) * (size_t)d);
    const double s = 1.0 - t;
    /* Left points are the first entry of each level, right points the last. */
    for (int r = n;; --r) {
        if (left) memcpy(left + (size_t)(n - r) * d, w, sizeof(double) * (size_t)d);
        if (right) memcpy(right + (size_t)r * d, w + (size_t)r * d, sizeof(double) * (size_t)d);
        if (r == 0) break;
        for (int i = 0; i < r * d; ++i) w[i] = s * w[i] + t * w[i + d];
    }
    return CJ_OK;
}

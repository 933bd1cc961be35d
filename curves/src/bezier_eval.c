/* Evaluation by the Bernstein sum and the Horner-like (Volk–Schumaker) scheme, the method
 * dispatcher, batch evaluation, condition numbers and a-priori error bounds. */
#include "binomial_internal.h"
#include "bezier_internal.h"
#include "eft_internal.h"

#include <assert.h>
#include <math.h>
#include <string.h>

/* Unchecked kernels: the curve and t have been validated by the caller. */

static void bernstein_kernel(const cj_bezier *c, double t, double *out) {
    const int n = c->degree, d = c->dim;
    const double *binom = cj_binomial_row(n);
    const double s = 1.0 - t;
    double spow[CJ_BEZIER_BINOMIAL_MAX_DEGREE + 1]; /* spow[j] = s^j */
    spow[0] = 1.0;
    for (int j = 1; j <= n; ++j) spow[j] = spow[j - 1] * s;
    double acc[CJ_MAX_DIM] = {0};
    double tpow = 1.0;
    for (int i = 0; i <= n; ++i) {
        const double basis = binom[i] * tpow * spow[n - i];
        const double *b = c->pts + (size_t)i * (size_t)d;
        for (int k = 0; k < d; ++k) acc[k] += basis * b[k];
        tpow *= t;
    }
    memcpy(out, acc, sizeof(double) * (size_t)d);
}

/* Volk–Schumaker: c(t) = s^n Σ C(n,i) b_i q^i with q = t/s for t <= 1/2, and the mirrored
 * form t^n Σ C(n,i) b_{n-i} q^i with q = s/t above, so that |q| <= 1 on [0,1] and Horner's
 * rule runs in O(n d) with one division, always by a number >= 1/2 (never zero, even when
 * extrapolating). fma keeps each Horner step to one rounding. */
static void horner_kernel(const cj_bezier *c, double t, double *out) {
    const int n = c->degree, d = c->dim;
    const double *binom = cj_binomial_row(n);
    const double s = 1.0 - t;
    const int mirrored = t > 0.5;
    const double base = mirrored ? t : s;
    const double q = mirrored ? s / t : t / s;
    double acc[CJ_MAX_DIM];
    const double *bn = c->pts + (size_t)(mirrored ? 0 : n) * (size_t)d;
    for (int k = 0; k < d; ++k) acc[k] = bn[k]; /* C(n,n) = 1 */
    for (int i = n - 1; i >= 0; --i) {
        const double *b = c->pts + (size_t)(mirrored ? n - i : i) * (size_t)d;
        for (int k = 0; k < d; ++k) acc[k] = fma(acc[k], q, binom[i] * b[k]);
    }
    double scale = 1.0, p = base; /* base^n by repeated squaring */
    for (int e = n; e; e >>= 1, p *= p)
        if (e & 1) scale *= p;
    for (int k = 0; k < d; ++k) out[k] = acc[k] * scale;
}

static void decasteljau_kernel(const cj_bezier *c, double t, double *out) {
    const int n = c->degree, d = c->dim;
    double w[CJ_BEZIER_WORK];
    memcpy(w, c->pts, sizeof(double) * (size_t)(n + 1) * (size_t)d);
    const double s = 1.0 - t;
    for (int r = n; r > 0; --r)
        for (int i = 0; i < r * d; ++i) w[i] = s * w[i] + t * w[i + d];
    memcpy(out, w, sizeof(double) * (size_t)d);
}

static int method_limit(cj_eval_method m) {
    return (m == CJ_EVAL_BERNSTEIN || m == CJ_EVAL_HORNER) ? CJ_BEZIER_BINOMIAL_MAX_DEGREE
                                                           : CJ_BEZIER_MAX_DEGREE;
}

static cj_status check_method(cj_eval_method m) {
    if ((unsigned)m > CJ_EVAL_COMPENSATED)
        return cj_fail(CJ_ERR_ARGUMENT, "unknown evaluation method %d", (int)m);
    return CJ_OK;
}

static void eval_kernel(const cj_bezier *c, cj_eval_method m, double t, double *out) {
    switch (m) {
    case CJ_EVAL_BERNSTEIN:
        bernstein_kernel(c, t, out);
        break;
    case CJ_EVAL_HORNER:
        horner_kernel(c, t, out);
        break;
    case CJ_EVAL_COMPENSATED:
        cj_compensated_kernel(c, t, out, NULL);
        break;
    case CJ_EVAL_DECASTELJAU:
    default:
        decasteljau_kernel(c, t, out);
        break;
    }
}

static cj_status check_eval(const cj_bezier *c, cj_eval_method m, double t) {
    cj_status st = check_method(m);
    if (st) return st;
    if ((st = cj_bezier_check(c, method_limit(m)))) return st;
    return cj_check_param(t, "parameter t");
}

cj_status cj_bezier_eval(const cj_bezier *c, cj_eval_method method, double t, double *out) {
    assert(out != NULL);
    cj_status st = check_eval(c, method, t);
    if (st) return st;
    eval_kernel(c, method, t, out);
    return CJ_OK;
}

cj_status cj_bezier_eval_bernstein(const cj_bezier *c, double t, double *out) {
    return cj_bezier_eval(c, CJ_EVAL_BERNSTEIN, t, out);
}

cj_status cj_bezier_eval_horner(const cj_bezier *c, double t, double *out) {
    return cj_bezier_eval(c, CJ_EVAL_HORNER, t, out);
}

cj_status cj_bezier_eval_batch(const cj_bezier *c, cj_eval_method method, const double *ts,
                               size_t nt, double *out) {
    assert(ts != NULL || nt == 0);
    assert(out != NULL || nt == 0);
    cj_status st = check_method(method);
    if (st) return st;
    if ((st = cj_bezier_check(c, method_limit(method)))) return st;
    if ((st = cj_check_finite(ts, nt, "parameter"))) return st;
    const size_t d = (size_t)c->dim;
    for (size_t j = 0; j < nt; ++j) eval_kernel(c, method, ts[j], out + j * d);
    return CJ_OK;
}

/* Σ|b_i,k| B_i^n(|t|) per coordinate, by de Casteljau on absolute values with |1-t| and |t|:
 * the magnitude every first-order error analysis of these methods is proportional to. The
 * result carries a relative error of at most gamma(2n), absorbed by the slack in callers. */
static void abs_sum(const cj_bezier *c, double t, double *out) {
    const int n = c->degree, d = c->dim;
    double w[CJ_BEZIER_WORK];
    for (int i = 0; i < (n + 1) * d; ++i) w[i] = fabs(c->pts[i]);
    const double s = fabs(1.0 - t), a = fabs(t);
    for (int r = n; r > 0; --r)
        for (int i = 0; i < r * d; ++i) w[i] = s * w[i] + a * w[i + d];
    memcpy(out, w, sizeof(double) * (size_t)d);
}

cj_status cj_bezier_cond(const cj_bezier *c, double t, double *cond) {
    assert(cond != NULL);
    cj_status st = check_eval(c, CJ_EVAL_COMPENSATED, t);
    if (st) return st;
    double num[CJ_MAX_DIM], val[CJ_MAX_DIM];
    abs_sum(c, t, num);
    cj_compensated_kernel(c, t, val, NULL);
    for (int k = 0; k < c->dim; ++k)
        cond[k] = val[k] == 0.0 ? (num[k] == 0.0 ? 1.0 : INFINITY) : num[k] / fabs(val[k]);
    return CJ_OK;
}

cj_status cj_bezier_error_bound(const cj_bezier *c, cj_eval_method method, double t,
                                double *bound) {
    assert(bound != NULL);
    cj_status st = check_eval(c, method, t);
    if (st) return st;
    const int n = c->degree, d = c->dim;
    double mag[CJ_MAX_DIM];
    abs_sum(c, t, mag);
    /* The magnitude itself is computed in floating point: inflate by (1 + gamma(2n+2)). */
    const double slack = 1.0 + cj_gamma(2 * n + 2);
    if (method == CJ_EVAL_COMPENSATED) {
        double val[CJ_MAX_DIM];
        cj_compensated_kernel(c, t, val, NULL);
        const double g = cj_gamma(3 * n);
        for (int k = 0; k < d; ++k)
            bound[k] = (CJ_UNIT_ROUNDOFF * fabs(val[k]) + 2.0 * g * g * mag[k] * slack) * slack;
    } else {
        /* Bernstein and Horner carry larger constants than de Casteljau's 3n: the basis is
         * formed from up to n products and the binomial, and Horner adds a division and the
         * power s^n; gamma(4n+2) covers both. */
        const int k_ops = method == CJ_EVAL_DECASTELJAU ? 3 * n : 4 * n + 2;
        const double g = cj_gamma(k_ops);
        for (int k = 0; k < d; ++k) bound[k] = g * mag[k] * slack;
    }
    return CJ_OK;
}

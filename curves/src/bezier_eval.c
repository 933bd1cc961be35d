/* Evaluation by the Bernstein sum and the Horner-like (Volk–Schumaker) scheme, the method
 * dispatcher, batch evaluation, condition numbers and a-priori error bounds. */
#include "binomial_internal.h"
#include "bezier_internal.h"
#include "eval_internal.h"

#include <assert.h>
#include <math.h>

/* Unchecked kernels: the curve and t have been validated by the caller. Each is written once
 * with the dimension as a parameter and instantiated for d = 1..4 by the dispatchers below, so
 * the per-coordinate loops unroll. */

/* Σ C(n,i) t^i s^(n-i) b_i with the powers formed by repeated products. Rounding count for the
 * term i (s = fl(1-t) counts (n-i) times): at most 2n for the basis value, 1 for the product
 * with b_i and n for the running sum, so |res - c(t)| <= gamma(3n+1) Σ|b_i| B_i^n(|t|). */
CJ_ALWAYS_INLINE void bernstein_run(const double *restrict p, int n, int d, double t,
                                    double *restrict out) {
    const double *binom = cj_binomial_row(n);
    const double s = 1.0 - t;
    double spow[CJ_BEZIER_BINOMIAL_MAX_DEGREE + 1]; /* spow[j] = s^j */
    spow[0] = 1.0;
    for (int j = 1; j <= n; ++j) spow[j] = spow[j - 1] * s;
    double acc[CJ_MAX_DIM];
    for (int k = 0; k < d; ++k) acc[k] = 0.0;
    double tpow = 1.0;
    for (int i = 0; i <= n; ++i) {
        const double basis = binom[i] * tpow * spow[n - i];
        for (int k = 0; k < d; ++k) acc[k] += basis * p[i * d + k];
        tpow *= t;
    }
    for (int k = 0; k < d; ++k) out[k] = acc[k];
}

/* Volk–Schumaker: c(t) = s^n Σ_j c_j q^j with q = t/s and c_j = C(n,j) b_j for t <= 1/2, and
 * the mirrored form t^n Σ_j c_j q^j with q = s/t and c_j = C(n,j) b_(n-j) above, so that
 * |q| <= 1 on [0,1] and the polynomial in q costs O(n d) with one division, always by a number
 * >= 1/2 (never zero, even when extrapolating). The polynomial in q is split into its even and
 * odd parts, E(q^2) + q O(q^2), two independent Horner chains in q^2 (half the latency of one
 * chain: each step waits for the previous fma), joined by one fma; fma keeps each step to one
 * rounding.
 *
 * Rounding count for the term c_j q^j, j = 2m or 2m+1: s = fl(1-t) and the division enter q^j
 * j times each, q^2 m times, c_j once (not at all when C(n,j) = 1), the chain m+1 times, the
 * join once, base^n by repeated squaring n-1 times and the final product once. For t <= 1/2
 * the fl(1-t) in q^j and in s^n combine to n-j+j = n: at most 3n+2 in all. Mirrored, fl(1-t)
 * is exact for t in [1/2, 2] (Sterbenz) and enters j times otherwise: at most 3j + n + 2 <=
 * 4n+2 (j = n has c_n = b_0 exactly). Hence |res - c(t)| <= gamma(4n+2) Σ|b_i| B_i^n(|t|). */
CJ_ALWAYS_INLINE void horner_run(const double *restrict p, int n, int d, double t,
                                 double *restrict out) {
    const double *binom = cj_binomial_row(n);
    const double s = 1.0 - t;
    const int mirrored = t > 0.5;
    const double base = mirrored ? t : s;
    const double q = mirrored ? s / t : t / s;
    const double q2 = q * q;
    /* Coefficient j reads point pj + j*step. */
    const double *pj = mirrored ? p + (size_t)n * (size_t)d : p;
    const int step = mirrored ? -d : d;
    const int je = n - (n & 1), jo = n - 1 + (n & 1); /* highest even and odd powers */
    double ev[CJ_MAX_DIM], od[CJ_MAX_DIM];
    for (int k = 0; k < d; ++k) ev[k] = binom[je] * pj[je * step + k];
    for (int a = je - 2; a >= 0; a -= 2)
        for (int k = 0; k < d; ++k) ev[k] = fma(ev[k], q2, binom[a] * pj[a * step + k]);
    if (jo > 0) {
        for (int k = 0; k < d; ++k) od[k] = binom[jo] * pj[jo * step + k];
        for (int b = jo - 2; b > 0; b -= 2)
            for (int k = 0; k < d; ++k) od[k] = fma(od[k], q2, binom[b] * pj[b * step + k]);
    } else {
        for (int k = 0; k < d; ++k) od[k] = 0.0;
    }
    double scale = 1.0, pw = base; /* base^n by repeated squaring */
    for (int e = n; e; e >>= 1, pw *= pw)
        if (e & 1) scale *= pw;
    for (int k = 0; k < d; ++k) out[k] = fma(od[k], q, ev[k]) * scale;
}

#define CJ_DISPATCH_DIM(run, c, t, out)                                                            \
    do {                                                                                           \
        switch ((c)->dim) {                                                                        \
        case 1:                                                                                    \
            run((c)->pts, (c)->degree, 1, t, out);                                                 \
            break;                                                                                 \
        case 2:                                                                                    \
            run((c)->pts, (c)->degree, 2, t, out);                                                 \
            break;                                                                                 \
        case 3:                                                                                    \
            run((c)->pts, (c)->degree, 3, t, out);                                                 \
            break;                                                                                 \
        case 4:                                                                                    \
            run((c)->pts, (c)->degree, 4, t, out);                                                 \
            break;                                                                                 \
        default:                                                                                   \
            run((c)->pts, (c)->degree, (c)->dim, t, out);                                          \
            break;                                                                                 \
        }                                                                                          \
    } while (0)

static void bernstein_kernel(const cj_bezier *c, double t, double *out) {
    CJ_DISPATCH_DIM(bernstein_run, c, t, out);
}

/* Degree 3 (the cubics of paths and drawing), division-free: Horner in t with coefficients
 * carrying the powers of s = 1 - t,
 *     c(t) = ((b_3 t + 3 s b_2) t + 3 s^2 b_1) t + s^3 b_0,
 * three fma in a chain per coordinate, the coefficients formed beside it. Rounding count for the
 * term i: fl(1-t) enters s^(3-i) 3-i times, forming the power 2-i times, the factor 3 and the
 * product with b_i once each, and the chain i+1 times: at most 2n+2 = 8 <= 4n+2, so the
 * Horner bound gamma(4n+2) M of cj_bezier_error_bound holds (also off [0,1], with |t|, |1-t|). */
CJ_ALWAYS_INLINE void horner3_run(const double *restrict p, int d, double t, double *restrict out) {
    const double s = 1.0 - t, s2 = s * s, s3 = s2 * s, s1x3 = 3.0 * s, s2x3 = 3.0 * s2;
    for (int k = 0; k < d; ++k) {
        double r = fma(p[3 * d + k], t, s1x3 * p[2 * d + k]);
        r = fma(r, t, s2x3 * p[d + k]);
        out[k] = fma(r, t, s3 * p[k]);
    }
}

static void horner_kernel(const cj_bezier *c, double t, double *out) {
    if (c->degree == 3) {
        switch (c->dim) {
        case 2:
            horner3_run(c->pts, 2, t, out);
            return;
        case 3:
            horner3_run(c->pts, 3, t, out);
            return;
        default:
            horner3_run(c->pts, c->dim, t, out);
            return;
        }
    }
    CJ_DISPATCH_DIM(horner_run, c, t, out);
}

static int method_limit(cj_eval_method m) {
    return (m == CJ_EVAL_BERNSTEIN || m == CJ_EVAL_HORNER) ? CJ_BEZIER_BINOMIAL_MAX_DEGREE
                                                           : CJ_BEZIER_MAX_DEGREE;
}

static const char *method_name(cj_eval_method m) {
    switch (m) {
    case CJ_EVAL_BERNSTEIN:
        return "Bernstein";
    case CJ_EVAL_HORNER:
        return "Horner";
    case CJ_EVAL_COMPENSATED:
        return "compensated de Casteljau";
    case CJ_EVAL_DECASTELJAU:
    default:
        return "de Casteljau";
    }
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
        cj_decasteljau_kernel(c, t, out);
        break;
    }
}

static cj_status check_curve(const cj_bezier *c, cj_eval_method m) {
    cj_status st = check_method(m);
    if (st) return st;
    const int limit = method_limit(m);
    assert(c != NULL);
    if (c->degree > limit)
        return cj_fail(CJ_ERR_DEGREE, "degree %d exceeds the %s method's limit of %d", c->degree,
                       method_name(m), limit);
    return cj_bezier_check(c, limit);
}

static cj_status check_eval(const cj_bezier *c, cj_eval_method m, double t) {
    cj_status st = check_curve(c, m);
    if (st) return st;
    return cj_check_param(t, "parameter t");
}

/* The whole validation of an evaluation as one inline predicate for the common case of good
 * input; only when it fails does check_eval run again to name what is wrong. */
static inline int eval_inputs_ok(const cj_bezier *c, cj_eval_method m, double t) {
    assert(c != NULL && c->pts != NULL);
    return (unsigned)m <= CJ_EVAL_COMPENSATED && c->degree >= 0 && c->degree <= method_limit(m) &&
           c->dim >= 1 && c->dim <= CJ_MAX_DIM && t - t == 0.0 &&
           cj_all_finite(c->pts, (size_t)(c->degree + 1) * (size_t)c->dim);
}

cj_status cj_bezier_eval(const cj_bezier *c, cj_eval_method method, double t, double *out) {
    assert(out != NULL && c != NULL && c->pts != NULL);
    cj_status st;
    if (method == CJ_EVAL_HORNER && c->degree == 3 && c->dim == 2 && t - t == 0.0 &&
        cj_all_finite(c->pts, 8)) { /* planar cubics, validated inline */
        double v[2];
        horner3_run(c->pts, 2, t, v);
        if (!cj_all_finite(v, 2) && (st = cj_check_value(v, 2, t))) return st;
        out[0] = v[0], out[1] = v[1];
        return CJ_OK;
    }
    if (!eval_inputs_ok(c, method, t) && (st = check_eval(c, method, t))) return st;
    double v[CJ_MAX_DIM];
    eval_kernel(c, method, t, v);
    if (!cj_all_finite(v, (size_t)c->dim) && (st = cj_check_value(v, c->dim, t))) return st;
    cj_copy_point(out, v, c->dim);
    return CJ_OK;
}

void cj_bezier_eval_unchecked(const cj_bezier *c, cj_eval_method method, double t, double *out) {
    /* The contract (bezier.h) is the caller's; debug builds check it. */
    assert(out != NULL && eval_inputs_ok(c, method, t));
    if (method == CJ_EVAL_HORNER && c->degree == 3 && c->dim == 2) { /* planar cubics */
        horner3_run(c->pts, 2, t, out);
        return;
    }
    eval_kernel(c, method, t, out);
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
    cj_status st = check_curve(c, method);
    if (st) return st;
    if ((st = cj_check_finite(ts, nt, "parameter"))) return st;
    const size_t d = (size_t)c->dim;
    /* The same kernels as the single-point calls: results are bit-identical. */
    switch (method) {
    case CJ_EVAL_BERNSTEIN:
        for (size_t j = 0; j < nt; ++j) bernstein_kernel(c, ts[j], out + j * d);
        break;
    case CJ_EVAL_HORNER:
        for (size_t j = 0; j < nt; ++j) horner_kernel(c, ts[j], out + j * d);
        break;
    case CJ_EVAL_COMPENSATED:
        for (size_t j = 0; j < nt; ++j) cj_compensated_kernel(c, ts[j], out + j * d, NULL);
        break;
    case CJ_EVAL_DECASTELJAU:
    default:
        for (size_t j = 0; j < nt; ++j) cj_decasteljau_kernel(c, ts[j], out + j * d);
        break;
    }
    /* Overflow (far extrapolation) is reported; the results before it are valid. */
    if (!cj_all_finite(out, nt * d))
        for (size_t j = 0; j < nt; ++j)
            if ((st = cj_check_value(out + j * d, c->dim, ts[j]))) return st;
    return CJ_OK;
}

/* Σ|b_i,k| B_i^n(|t|) per coordinate (B with |1-t| and |t|), by de Casteljau on absolute values:
 * the magnitude every first-order error analysis of these methods is proportional to. Every
 * term is non-negative and goes through at most 3n roundings (fl(1-t) n-i times, one product
 * and one sum per level), so the exact magnitude is at most (1 + gamma(3n)) times the result. */
static void abs_sum(const cj_bezier *c, double t, double *out) {
    const int n = c->degree, d = c->dim;
    double w[CJ_BEZIER_WORK];
    for (int i = 0; i < (n + 1) * d; ++i) w[i] = fabs(c->pts[i]);
    const double s = fabs(1.0 - t), a = fabs(t);
    for (int r = n; r > 0; --r)
        for (int i = 0; i < r * d; ++i) w[i] = s * w[i] + a * w[i + d];
    for (int k = 0; k < d; ++k) out[k] = w[k];
}

cj_status cj_bezier_cond(const cj_bezier *c, double t, double *cond) {
    assert(cond != NULL);
    cj_status st = check_eval(c, CJ_EVAL_COMPENSATED, t);
    if (st) return st;
    double num[CJ_MAX_DIM], val[CJ_MAX_DIM];
    abs_sum(c, t, num);
    cj_compensated_kernel(c, t, val, NULL);
    if ((st = cj_check_value(val, c->dim, t))) return st;
    for (int k = 0; k < c->dim; ++k) cond[k] = val[k] == 0.0 ? INFINITY : num[k] / fabs(val[k]);
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
    /* The magnitude is low by at most a factor 1 + gamma(3n); the few products forming the
     * bound below cost 4 more roundings, all covered by inflating with 1 + gamma(3n+8). */
    const double slack = 1.0 + cj_gamma(3 * n + 8);
    if (method == CJ_EVAL_COMPENSATED) {
        /* u|c(t)| is taken at the computed value; |c(t)| <= |val| + (the error), whose
         * u-multiple is second order and absorbed by the same slack. */
        double val[CJ_MAX_DIM];
        cj_compensated_kernel(c, t, val, NULL);
        if ((st = cj_check_value(val, c->dim, t))) return st;
        const double g = cj_gamma(3 * n);
        const double uf = cj_underflow_allowance(n, t, 8.0);
        for (int k = 0; k < d; ++k)
            bound[k] = (CJ_UNIT_ROUNDOFF * fabs(val[k]) + 2.0 * g * g * mag[k]) * slack + uf;
    } else if (method == CJ_EVAL_DECASTELJAU) {
        /* Underflow: 2 products per entry and level may each lose eta/2; 2 more for abs_sum. */
        const double g = cj_gamma(3 * n);
        const double uf = cj_underflow_allowance(n, t, 4.0);
        for (int k = 0; k < d; ++k) bound[k] = g * mag[k] * slack + uf;
    } else {
        /* gamma(4n+2) covers both (see the kernels). Underflow: an eta lost in a power of t or
         * q is later multiplied by at most C(n,i)|b_i| A^n, hence the binomial-weighted sum. */
        const double g = cj_gamma(4 * n + 2);
        const double uf = cj_underflow_allowance(n, t, 8.0);
        const double *binom = cj_binomial_row(n);
        for (int k = 0; k < d; ++k) {
            double wsum = 1.0;
            for (int i = 0; i <= n; ++i) wsum += binom[i] * fabs(c->pts[i * d + k]);
            bound[k] = g * mag[k] * slack + uf * wsum * (1.0 + 0x1p-40);
        }
    }
    /* Control points near the top of the double range overflow M_k (or the binomial sum): a
     * bound of inf says nothing, so say that instead. */
    for (int k = 0; k < d; ++k)
        if (!isfinite(bound[k]))
            return cj_fail(CJ_ERR_RANGE,
                           "error bound at t = %.17g, coordinate %d, overflows the double range "
                           "(control points too large)",
                           t, k);
    return CJ_OK;
}

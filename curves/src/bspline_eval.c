/* B-spline and NURBS evaluation: de Boor, derivatives by divided differences of the span's
 * points, and the a-priori error bound. See casteljau/bspline.h. */
#include "bspline_internal.h"
#include "error_internal.h"

#include <assert.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

void cj_bspline_eval_unchecked(const cj_bspline *c, double t, double *out) {
    assert(t >= c->knots[c->degree] && t <= c->knots[c->npts]);
    const int p = c->degree, d = c->dim, hd = cj_bsp_hdim(c);
    const int s = cj_bsp_span(c, t);
    double loc[CJ_BSP_LOCAL];
    cj_bsp_local(c, s, loc);
    cj_bsp_deboor(c->knots, p, s, hd, loc, t, NULL);
    const double *v = loc + p * hd;
    if (c->weights)
        for (int k = 0; k < d; ++k) out[k] = v[k] / v[d];
    else
        for (int k = 0; k < d; ++k) out[k] = v[k];
}

cj_status cj_bspline_eval(const cj_bspline *c, double t, double *out) {
    assert(out != NULL);
    cj_status st = cj_bspline_check(c);
    if (st) return st;
    if ((st = cj_bsp_check_param(c, t, "parameter t"))) return st;
    cj_bspline_eval_unchecked(c, t, out);
    return CJ_OK;
}

cj_status cj_bspline_eval_batch(const cj_bspline *c, const double *ts, size_t nt, double *out) {
    assert((ts != NULL && out != NULL) || nt == 0);
    cj_status st = cj_bspline_check(c);
    if (st) return st;
    for (size_t j = 0; j < nt; ++j) {
        char what[48];
        if (!isfinite(ts[j]) || ts[j] < c->knots[c->degree] || ts[j] > c->knots[c->npts]) {
            snprintf(what, sizeof what, "parameter %zu", j);
            return cj_bsp_check_param(c, ts[j], what);
        }
    }
    for (size_t j = 0; j < nt; ++j) cj_bspline_eval_unchecked(c, ts[j], out + j * (size_t)c->dim);
    return CJ_OK;
}

/* Homogeneous derivatives 0..kmax of span s at t into h[(kmax+1)*hd]. Returns the first order
 * that overflowed, or -1. */
int cj_bsp_homogeneous_derivs(const cj_bspline *c, int s, double t, int kmax, double *h) {
    const int p = c->degree, hd = cj_bsp_hdim(c);
    double diff[CJ_BSP_LOCAL], work[CJ_BSP_LOCAL];
    cj_bsp_local(c, s, diff);
    for (int j = 0; j <= kmax; ++j) {
        double *dst = h + j * hd;
        if (j > p) {
            memset(dst, 0, sizeof(double) * (size_t)hd);
            continue;
        }
        if (j > 0) {
            /* diff[jj] for jj = j..p holds the order-j points of indices s-p+jj. */
            const double f = (double)(p - j + 1);
            for (int jj = p; jj >= j; --jj) {
                const int i = s - p + jj;
                /* one division per point, shared by its coordinates: still four roundings per
                 * level (the knot difference, the quotient, the point difference, the product),
                 * as the bound in bspline.h counts */
                const double g = f / (c->knots[i + p + 1 - j] - c->knots[i]);
                for (int k = 0; k < hd; ++k)
                    diff[jj * hd + k] = g * (diff[jj * hd + k] - diff[(jj - 1) * hd + k]);
            }
        }
        const int q = p - j;
        memcpy(work, diff + j * hd, sizeof(double) * (size_t)((q + 1) * hd));
        cj_bsp_deboor(c->knots, q, s, hd, work, t, NULL);
        for (int k = 0; k < hd; ++k) {
            dst[k] = work[q * hd + k];
            if (!isfinite(dst[k])) return j;
        }
    }
    return -1;
}

/* Derivatives 0..kmax into out; returns the first order that overflowed, or -1. */
static int derivs(const cj_bspline *c, double t, int kmax, double *out) {
    const int d = c->dim, hd = cj_bsp_hdim(c);
    const int s = cj_bsp_span(c, t);
    double h[(CJ_BSPLINE_MAX_DERIV + 1) * CJ_BSP_MAX_HDIM];
    int bad = cj_bsp_homogeneous_derivs(c, s, t, kmax, h);
    if (!c->weights) {
        memcpy(out, h, sizeof(double) * (size_t)((kmax + 1) * d));
        return bad;
    }
    /* Quotient rule, binomials by Pascal's rule row by row. */
    double binom[CJ_BSPLINE_MAX_DERIV + 1];
    const double w0 = h[d];
    binom[0] = 1.0;
    for (int j = 0; j <= kmax; ++j) {
        if (j > 0) {
            binom[j] = 1.0;
            for (int i = j - 1; i > 0; --i) binom[i] += binom[i - 1];
        }
        for (int k = 0; k < d; ++k) {
            double v = h[j * hd + k];
            for (int i = 1; i <= j; ++i) v -= binom[i] * h[i * hd + d] * out[(j - i) * d + k];
            v /= w0;
            if (!isfinite(v) && bad < 0) bad = j;
            out[j * d + k] = v;
        }
    }
    return bad;
}

void cj_bspline_eval_derivs_unchecked(const cj_bspline *c, double t, int kmax, double *out) {
    assert(t >= c->knots[c->degree] && t <= c->knots[c->npts]);
    assert(kmax >= 0 && kmax <= CJ_BSPLINE_MAX_DERIV);
    (void)derivs(c, t, kmax, out);
}

cj_status cj_bspline_eval_derivs(const cj_bspline *c, double t, int kmax, double *out) {
    assert(out != NULL);
    cj_status st = cj_bspline_check(c);
    if (st) return st;
    if ((st = cj_bsp_check_param(c, t, "parameter t"))) return st;
    if (kmax < 0 || kmax > CJ_BSPLINE_MAX_DERIV)
        return cj_fail(CJ_ERR_ARGUMENT, "derivative order %d is outside 0..%d", kmax,
                       CJ_BSPLINE_MAX_DERIV);
    double res[(CJ_BSPLINE_MAX_DERIV + 1) * CJ_MAX_DIM];
    const int bad = derivs(c, t, kmax, res);
    if (bad >= 0)
        return cj_fail(CJ_ERR_RANGE, "derivative of order %d at t = %.17g overflows", bad, t);
    memcpy(out, res, sizeof(double) * (size_t)((kmax + 1) * c->dim));
    return CJ_OK;
}

cj_status cj_bspline_error_bound(const cj_bspline *c, double t, double *bound) {
    assert(bound != NULL);
    cj_status st = cj_bspline_check(c);
    if (st) return st;
    if ((st = cj_bsp_check_param(c, t, "parameter t"))) return st;
    const int p = c->degree, d = c->dim, hd = cj_bsp_hdim(c);
    const int s = cj_bsp_span(c, t);
    double val[CJ_BSP_LOCAL], mag[CJ_BSP_LOCAL];
    double dmax[CJ_BSP_MAX_HDIM] = {0};
    cj_bsp_local(c, s, val);
    for (int i = 0; i < (p + 1) * hd; ++i) {
        mag[i] = fabs(val[i]);
        if (mag[i] > dmax[i % hd]) dmax[i % hd] = mag[i];
    }
    cj_bsp_deboor(c->knots, p, s, hd, val, t, NULL);
    cj_bsp_deboor(c->knots, p, s, hd, mag, t, NULL);
    const double eta = 0x1p-1074;
    /* A NURBS's homogeneous points w_i d_i carry one rounding more. */
    const double g = cj_gamma(5 * p + (c->weights != NULL)), inflate = 1.0 + cj_gamma(5 * p + 8);
    double e[CJ_BSP_MAX_HDIM];
    for (int k = 0; k < hd; ++k) {
        const double m = mag[p * hd + k] * inflate;
        e[k] = (g * m + 4.0 * (p + 1) * eta * (1.0 + dmax[k])) * (1.0 + 4 * CJ_UNIT_ROUNDOFF);
        if (!isfinite(e[k]))
            return cj_fail(CJ_ERR_RANGE, "error bound of coordinate %d at t = %.17g overflows", k,
                           t);
    }
    if (!c->weights) {
        memcpy(bound, e, sizeof(double) * (size_t)d);
        return CJ_OK;
    }
    const double u = CJ_UNIT_ROUNDOFF, w = val[p * hd + d], ew = e[d];
    if (!(w > 2.0 * ew))
        return cj_fail(CJ_ERR_RANGE, "weight sum %g at t = %.17g is within its error bound %g", w,
                       t, ew);
    /* |A/w - Â/ŵ| <= (E_A + |c| E_w)/ŵ and |c| <= (q + E_A/ŵ)/(1 - E_w/ŵ), q = |Â/ŵ|. */
    for (int k = 0; k < d; ++k) {
        const double q = fabs(val[p * hd + k] / w) * (1.0 + 2 * u);
        const double cmax = (q + e[k] / w) / (1.0 - ew / w) * (1.0 + 4 * u);
        const double b = u * q + (e[k] + cmax * ew) / w + eta; /* eta: a subnormal quotient */
        bound[k] = b * (1.0 + 8 * u);
    }
    return CJ_OK;
}

cj_status cj_bspline_derivs_error_bound(const cj_bspline *c, double t, int kmax, double *bound) {
    assert(bound != NULL);
    cj_status st = cj_bspline_check(c);
    if (st) return st;
    if ((st = cj_bsp_check_param(c, t, "parameter t"))) return st;
    if (kmax < 0 || kmax > CJ_BSPLINE_MAX_DERIV)
        return cj_fail(CJ_ERR_ARGUMENT, "derivative order %d is outside 0..%d", kmax,
                       CJ_BSPLINE_MAX_DERIV);
    if (c->weights) return cj_bsp_nurbs_derivs_bound(c, t, kmax, bound);
    const int p = c->degree, d = c->dim, s = cj_bsp_span(c, t);
    double m[CJ_BSP_LOCAL], work[CJ_BSP_LOCAL];
    cj_bsp_local(c, s, m);
    for (int i = 0; i < (p + 1) * d; ++i) m[i] = fabs(m[i]);
    const double eta = 0x1p-1074, u = CJ_UNIT_ROUNDOFF, inflate = 1.0 + cj_gamma(5 * p + 8);
    double out[(CJ_BSPLINE_MAX_DERIV + 1) * CJ_MAX_DIM];
    for (int j = 0; j <= kmax; ++j) {
        if (j > p) {
            for (int k = 0; k < d; ++k) out[j * d + k] = 0.0;
            continue;
        }
        if (j > 0) {
            const double f = (double)(p - j + 1);
            for (int jj = p; jj >= j; --jj) {
                const int i = s - p + jj;
                const double den = c->knots[i + p + 1 - j] - c->knots[i];
                for (int k = 0; k < d; ++k)
                    m[jj * d + k] = f * (m[jj * d + k] + m[(jj - 1) * d + k]) / den;
            }
        }
        const int q = p - j;
        double mmax[CJ_MAX_DIM] = {0};
        for (int jj = j; jj <= p; ++jj)
            for (int k = 0; k < d; ++k) mmax[k] = fmax(mmax[k], m[jj * d + k]);
        memcpy(work, m + j * d, sizeof(double) * (size_t)((q + 1) * d));
        cj_bsp_deboor(c->knots, q, s, d, work, t, NULL);
        const double g = cj_gamma(5 * p - j);
        for (int k = 0; k < d; ++k) {
            const double b =
                (g * work[q * d + k] * inflate + 8.0 * (p + 1) * eta * (1.0 + mmax[k] * inflate)) *
                (1.0 + 4 * u);
            if (!isfinite(b))
                return cj_fail(CJ_ERR_RANGE,
                               "error bound of derivative %d, coordinate %d at t = %.17g overflows",
                               j, k, t);
            out[j * d + k] = b;
        }
    }
    memcpy(bound, out, sizeof(double) * (size_t)((kmax + 1) * d));
    return CJ_OK;
}

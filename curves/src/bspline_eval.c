/* B-spline and NURBS evaluation: de Boor, derivatives by divided differences of the span's
 * points, and the a-priori error bound of the value and the pieces of the derivatives' bound
 * (bspline_derivs_bound.c puts them together). See casteljau/bspline.h. */
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

void cj_bsp_pyramid(const double *knots, int p, int s, int hd, double *loc, double t, int jtop,
                    int sums, double *out) {
    double tmp[CJ_BSP_LOCAL], binom[CJ_BSPLINE_MAX_DEGREE + 1];
    /* C(p, j) by Pascal's rule (exact below 2^53, else off by at most gamma(p)) */
    binom[0] = 1.0;
    for (int r = 1; r <= p; ++r) {
        binom[r] = 1.0;
        for (int i = r - 1; i > 0; --i) binom[i] += binom[i - 1];
    }
    for (int r = 0;; ++r) {
        const int j = p - r;
        if (j <= jtop) {
            /* loc[r..p]: the de Boor points of the degree-j spline x -> B(t^(p-j), x^j) on
             * points s-j..s; its j-th derivative, times C(p, j), is c^(j)(t) */
            memcpy(tmp, loc + r * hd, sizeof(double) * (size_t)((j + 1) * hd));
            for (int l = 1; l <= j; ++l)
                for (int m = j; m >= l; --m) {
                    const int i = s - j + m;
                    const double g = (double)(j - l + 1) / (knots[i + j + 1 - l] - knots[i]);
                    double *dst = tmp + m * hd;
                    const double *prev = dst - hd;
                    if (sums)
                        for (int k = 0; k < hd; ++k)
                            dst[k] = g * (dst[k] + prev[k]) + (sums == 2 ? 0x1p-1072 : 0.0);
                    else
                        for (int k = 0; k < hd; ++k) dst[k] = g * (dst[k] - prev[k]);
                }
            for (int k = 0; k < hd; ++k) out[j * hd + k] = binom[j] * tmp[j * hd + k];
        }
        if (r == p) break;
        /* level r+1 of de Boor, as cj_bsp_deboor runs it */
        const int R = r + 1;
        for (int jj = p; jj >= R; --jj) {
            const int i = s - p + jj;
            const double lo = knots[i], hi = knots[i + p + 1 - R];
            const double den = hi - lo;
            const double a = (t - lo) / den, b = (hi - t) / den;
            double *dst = loc + jj * hd;
            const double *prev = dst - hd;
            for (int k = 0; k < hd; ++k) dst[k] = b * prev[k] + a * dst[k];
        }
    }
}

/* Homogeneous derivatives 0..kmax of span s at t into h[(kmax+1)*hd], from one de Boor
 * pyramid (cj_bsp_pyramid). Returns the first order that overflowed, or -1. */
int cj_bsp_homogeneous_derivs(const cj_bspline *c, int s, double t, int kmax, double *h) {
    const int p = c->degree, hd = cj_bsp_hdim(c), jtop = kmax < p ? kmax : p;
    double loc[CJ_BSP_LOCAL];
    cj_bsp_local(c, s, loc);
    cj_bsp_pyramid(c->knots, p, s, hd, loc, t, jtop, 0, h);
    for (int j = jtop + 1; j <= kmax; ++j) memset(h + j * hd, 0, sizeof(double) * (size_t)hd);
    for (int j = 0; j <= jtop; ++j)
        for (int k = 0; k < hd; ++k)
            if (!isfinite(h[j * hd + k])) return j;
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

cj_status cj_bsp_check_derivs(const cj_bspline *c, double t, int kmax) {
    cj_status st = cj_bspline_check(c);
    if (st) return st;
    if ((st = cj_bsp_check_param(c, t, "parameter t"))) return st;
    if (kmax < 0 || kmax > CJ_BSPLINE_MAX_DERIV)
        return cj_fail(CJ_ERR_ARGUMENT, "derivative order %d is outside 0..%d", kmax,
                       CJ_BSPLINE_MAX_DERIV);
    return CJ_OK;
}

cj_status cj_bspline_eval_derivs(const cj_bspline *c, double t, int kmax, double *out) {
    assert(out != NULL);
    cj_status st = cj_bsp_check_derivs(c, t, kmax);
    if (st) return st;
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

void cj_bsp_pyramid_bound(const cj_bspline *c, int s, double t, int kmax, int extra, double *out) {
    double loc[CJ_BSP_LOCAL];
    cj_bsp_local(c, s, loc);
    cj_bsp_local_pyramid_bound(c->knots, c->degree, s, cj_bsp_hdim(c), c->dim, loc, t, kmax, extra,
                               out);
}

void cj_bsp_local_pyramid_bound(const double *knots, int p, int s, int hd, int dim,
                                const double *loc, double t, int kmax, int extra, double *out) {
    const int jtop = kmax < p ? kmax : p;
    const double eta = 0x1p-1074, u = CJ_UNIT_ROUNDOFF, inflate = 1.0 + cj_gamma(6 * p + 8);
    double mag[CJ_BSP_LOCAL], slack[CJ_BSP_LOCAL], M[(CJ_BSPLINE_MAX_DERIV + 1) * CJ_BSP_MAX_HDIM],
        S[(CJ_BSPLINE_MAX_DERIV + 1) * CJ_BSP_MAX_HDIM];
    double D = 0.0;
    for (int i = 0; i < (p + 1) * hd; ++i) {
        mag[i] = fabs(loc[i]);
        D = fmax(D, mag[i]);
    }
    /* absolute (subnormal) slack: de Boor's levels at most 8 (p+1) eta (1 + D) in all (as in
     * cj_bspline_error_bound), and 4 eta per operation of differences (sums = 2 adds it), carried
     * by the same recurrences */
    for (int i = 0; i < (p + 1) * hd; ++i) slack[i] = 8.0 * (p + 1) * eta * (1.0 + D);
    cj_bsp_pyramid(knots, p, s, hd, mag, t, jtop, 1, M);
    cj_bsp_pyramid(knots, p, s, hd, slack, t, jtop, 2, S);
    for (int j = 0; j <= kmax; ++j)
        for (int k = 0; k < hd; ++k) {
            if (j > jtop) {
                out[j * hd + k] = 0.0; /* exact zeros above the degree */
                continue;
            }
            const double g = cj_gamma(6 * p - j + 2 + (k < dim ? extra : 0));
            out[j * hd + k] =
                (g * M[j * hd + k] * inflate + S[j * hd + k] * inflate + eta) * (1.0 + 4 * u);
        }
}

/* Partial derivatives of tensor-product B-spline / NURBS surfaces with their proven bound: the
 * curve pyramid of bspline_eval.c run in u on the q+1 rows of the v-span, then in v on each
 * order's row values, then (NURBS) the two-variable quotient rule. See casteljau/bspline_surface.h.
 */
#include "bspline_internal.h"
#include "casteljau/bspline_surface.h"
#include "error_internal.h"

#include <assert.h>
#include <math.h>
#include <string.h>

enum { LOCAL = (CJ_PATCH_MAX_DEGREE + 1) * 4, ORDERS = CJ_BSPLINE_SURFACE_MAX_DERIV + 1 };

/* The (p+1) homogeneous points of row jrow from column i0 on into loc. */
static void row_points(const cj_bspline_surface *s, int i0, int jrow, double *loc) {
    const int p = s->deg_u, hd = s->weights ? 4 : 3;
    for (int ii = 0; ii <= p; ++ii) {
        const size_t k = (size_t)jrow * (size_t)s->npts_u + (size_t)(i0 + ii);
        const double *d = s->pts + 3 * k;
        const double w = s->weights ? s->weights[k] : 1.0;
        for (int c = 0; c < 3; ++c) loc[ii * hd + c] = s->weights ? w * d[c] : d[c];
        if (s->weights) loc[ii * hd + 3] = w;
    }
}

static cj_status check_args(const cj_bspline_surface *s, double u, double v, int ku, int kv) {
    cj_status st = cj_bspline_surface_check(s);
    if (st) return st;
    const cj_bspline cu = cj_bspline_view(s->deg_u, 1, s->npts_u, NULL, NULL, s->knots_u);
    const cj_bspline cv = cj_bspline_view(s->deg_v, 1, s->npts_v, NULL, NULL, s->knots_v);
    if ((st = cj_bsp_check_param(&cu, u, "parameter u"))) return st;
    if ((st = cj_bsp_check_param(&cv, v, "parameter v"))) return st;
    if (ku < 0 || kv < 0 || ku > CJ_BSPLINE_SURFACE_MAX_DERIV || kv > CJ_BSPLINE_SURFACE_MAX_DERIV)
        return cj_fail(CJ_ERR_ARGUMENT, "derivative orders (%d, %d) are outside 0..%d", ku, kv,
                       CJ_BSPLINE_SURFACE_MAX_DERIV);
    return CJ_OK;
}

/* Homogeneous partials H[(k*(kv+1) + l)*hd + c] of the span pair at (u, v) and, if E is not
 * NULL, their bounds E (same layout): the v pass's own bound on the computed row values plus
 * the u pass's bounds carried through the v derivative on magnitudes (|Σ δ_j N_j^(l)| is at
 * most the sums-pyramid of |δ_j|). Orders above a degree are exact zeros. */
static void homogeneous(const cj_bspline_surface *s, double u, double v, int ku, int kv, double *H,
                        double *E) {
    const int p = s->deg_u, q = s->deg_v, hd = s->weights ? 4 : 3;
    const cj_bspline cu = cj_bspline_view(p, 1, s->npts_u, NULL, NULL, s->knots_u);
    const cj_bspline cv = cj_bspline_view(q, 1, s->npts_v, NULL, NULL, s->knots_v);
    const int su = cj_bsp_span(&cu, u), sv = cj_bsp_span(&cv, v);
    const int jku = ku < p ? ku : p, jkv = kv < q ? kv : q, nl = kv + 1;
    /* rows[k][jj]: order-k u-derivative of row sv-q+jj; erow likewise its bound */
    double rows[ORDERS][LOCAL], erow[ORDERS][LOCAL], loc[LOCAL], tmp[ORDERS * 4];
    for (int jj = 0; jj <= q; ++jj) {
        row_points(s, su - p, sv - q + jj, loc);
        if (E) {
            cj_bsp_local_pyramid_bound(s->knots_u, p, su, hd, 3, loc, u, jku, s->weights != NULL,
                                       tmp);
            for (int k = 0; k <= jku; ++k)
                memcpy(erow[k] + jj * hd, tmp + k * hd, sizeof(double) * (size_t)hd);
        }
        cj_bsp_pyramid(s->knots_u, p, su, hd, loc, u, jku, 0, tmp);
        for (int k = 0; k <= jku; ++k)
            memcpy(rows[k] + jj * hd, tmp + k * hd, sizeof(double) * (size_t)hd);
    }
    memset(H, 0, sizeof(double) * (size_t)((ku + 1) * nl * hd));
    if (E) memset(E, 0, sizeof(double) * (size_t)((ku + 1) * nl * hd));
    const double inflate = 1.0 + cj_gamma(6 * q + 8), uu = CJ_UNIT_ROUNDOFF;
    for (int k = 0; k <= jku; ++k) {
        double own[ORDERS * 4], carried[ORDERS * 4];
        if (E) {
            cj_bsp_local_pyramid_bound(s->knots_v, q, sv, hd, 3, rows[k], v, jkv, 0, own);
            cj_bsp_pyramid(s->knots_v, q, sv, hd, erow[k], v, jkv, 1, carried);
        }
        cj_bsp_pyramid(s->knots_v, q, sv, hd, rows[k], v, jkv, 0, tmp);
        for (int l = 0; l <= jkv; ++l)
            for (int c = 0; c < hd; ++c) {
                H[(k * nl + l) * hd + c] = tmp[l * hd + c];
                if (E)
                    E[(k * nl + l) * hd + c] =
                        (own[l * hd + c] + carried[l * hd + c] * inflate) * (1.0 + 2 * uu);
            }
    }
}

/* C(n, i) for n, i <= CJ_BSPLINE_SURFACE_MAX_DERIV (exact). */
static double binom(int n, int i) {
    double b = 1.0;
    for (int j = 1; j <= i; ++j) b = b * (n - i + j) / j;
    return b;
}

/* NURBS partials from the homogeneous ones by the two-variable quotient rule
 * S^(k,l) W = A^(k,l) − Σ_{(a,b) != (0,0)} C(k,a) C(l,b) W^(a,b) S^(k−a,l−b), in order of k then l
 * (every S on the right is already known). */
static void quotient(const double *H, int ku, int kv, double *out) {
    const int nl = kv + 1;
    const double w0 = H[3];
    for (int k = 0; k <= ku; ++k)
        for (int l = 0; l <= kv; ++l)
            for (int c = 0; c < 3; ++c) {
                double x = H[(k * nl + l) * 4 + c];
                for (int a = 0; a <= k; ++a)
                    for (int b = 0; b <= l; ++b) {
                        if (a == 0 && b == 0) continue;
                        x -= binom(k, a) * binom(l, b) * H[(a * nl + b) * 4 + 3] *
                             out[((k - a) * nl + (l - b)) * 3 + c];
                    }
                out[(k * nl + l) * 3 + c] = x / w0;
            }
}

cj_status cj_bspline_surface_eval_derivs(const cj_bspline_surface *s, double u, double v, int ku,
                                         int kv, double *out) {
    assert(out != NULL);
    cj_status st = check_args(s, u, v, ku, kv);
    if (st) return st;
    double H[ORDERS * ORDERS * 4];
    homogeneous(s, u, v, ku, kv, H, NULL);
    const int n = (ku + 1) * (kv + 1);
    if (s->weights)
        quotient(H, ku, kv, out);
    else
        memcpy(out, H, sizeof(double) * (size_t)(3 * n));
    for (int i = 0; i < 3 * n; ++i)
        if (!isfinite(out[i]))
            return cj_fail(CJ_ERR_RANGE,
                           "partial derivative (%d, %d) at (%.17g, %.17g) is beyond the double "
                           "range",
                           i / 3 / (kv + 1), i / 3 % (kv + 1), u, v);
    return CJ_OK;
}

cj_status cj_bspline_surface_derivs_error_bound(const cj_bspline_surface *s, double u, double v,
                                                int ku, int kv, double *bound) {
    assert(bound != NULL);
    cj_status st = check_args(s, u, v, ku, kv);
    if (st) return st;
    double H[ORDERS * ORDERS * 4], E[ORDERS * ORDERS * 4];
    homogeneous(s, u, v, ku, kv, H, E);
    const int nl = kv + 1, n = (ku + 1) * nl;
    if (!s->weights) {
        memcpy(bound, E, sizeof(double) * (size_t)(3 * n));
    } else {
        /* e_kl (Ŵ − E_W00) <= E_A,kl + Σ C C (E_W,ab |Ŝ_{k−a,l−b}| + (|Ŵ_ab| + E_W,ab) e_{k−a,l−b})
         *                   + gamma(2m+3) T_kl + |Ŝ_kl| (E_W00 + u (1 + 2u) Ŵ),
         * m the number of terms, T_kl = |Â_kl| + Σ C C |Ŵ_ab| |Ŝ_{k−a,l−b}|: the curve's
         * derivation (bspline.h) with the sum over (a, b) in place of i. */
        double S[ORDERS * ORDERS * 3];
        quotient(H, ku, kv, S);
        const double w0 = H[3], ew0 = E[3], uu = CJ_UNIT_ROUNDOFF;
        if (!(w0 > 2.0 * ew0))
            return cj_fail(CJ_ERR_RANGE,
                           "weight sum %g at (%.17g, %.17g) is within its error bound %g", w0, u, v,
                           ew0);
        for (int k = 0; k <= ku; ++k)
            for (int l = 0; l <= kv; ++l) {
                const int m = (k + 1) * (l + 1) - 1;
                for (int c = 0; c < 3; ++c) {
                    const double sk = fabs(S[(k * nl + l) * 3 + c]);
                    double rhs = E[(k * nl + l) * 4 + c], t = fabs(H[(k * nl + l) * 4 + c]);
                    for (int a = 0; a <= k; ++a)
                        for (int b = 0; b <= l; ++b) {
                            if (a == 0 && b == 0) continue;
                            const double cc = binom(k, a) * binom(l, b);
                            const int o = ((k - a) * nl + (l - b)) * 3 + c;
                            const double wab = fabs(H[(a * nl + b) * 4 + 3]);
                            const double ewab = E[(a * nl + b) * 4 + 3];
                            rhs += cc * (ewab * fabs(S[o]) + (wab + ewab) * bound[o]);
                            t += cc * wab * fabs(S[o]);
                        }
                    rhs += cj_gamma(2 * m + 3) * t + sk * (ew0 + uu * (1 + 2 * uu) * w0);
                    bound[(k * nl + l) * 3 + c] = rhs / (w0 - ew0) * (1.0 + cj_gamma(4 * m + 12));
                }
            }
    }
    for (int i = 0; i < 3 * n; ++i)
        if (!isfinite(bound[i]))
            return cj_fail(CJ_ERR_RANGE,
                           "error bound of partial derivative (%d, %d) at (%.17g, %.17g) "
                           "overflows",
                           i / 3 / nl, i / 3 % nl, u, v);
    return CJ_OK;
}

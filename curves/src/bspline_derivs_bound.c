/* The a-priori rounding bound of a B-spline's derivatives, cj_bspline_derivs_error_bound: the
 * pyramid bound of bspline_eval.c for a polynomial curve, and for a NURBS (a curve with weights)
 * the homogeneous bound carried through the quotient rule (derivation in casteljau/bspline.h). */
#include "bspline_internal.h"
#include "error_internal.h"

#include <assert.h>
#include <math.h>
#include <string.h>

/* A NURBS: c is validated, t in the domain, 0 <= kmax <= CJ_BSPLINE_MAX_DERIV. */
static cj_status nurbs_derivs_bound(const cj_bspline *c, double t, int kmax, double *bound) {
    const int d = c->dim, hd = d + 1, s = cj_bsp_span(c, t);
    const double u = CJ_UNIT_ROUNDOFF;
    enum { NJ = CJ_BSPLINE_MAX_DERIV + 1 };
    /* 1. Homogeneous bounds E[j][k] (k = d: the weight), as for a polynomial B-spline of the
     * points (w_i d_i, w_i), one rounding more for the products w_i d_i. */
    double Ef[NJ * CJ_BSP_MAX_HDIM], E[NJ][CJ_BSP_MAX_HDIM];
    cj_bsp_pyramid_bound(c, s, t, kmax, 1, Ef);
    for (int j = 0; j <= kmax; ++j)
        for (int k = 0; k < hd; ++k) E[j][k] = Ef[j * hd + k];
    /* 2. The computed homogeneous derivatives and the computed derivatives the caller gets. */
    double h[NJ * CJ_BSP_MAX_HDIM], out[NJ * CJ_MAX_DIM];
    (void)cj_bsp_homogeneous_derivs(c, s, t, kmax, h);
    cj_bspline_eval_derivs_unchecked(c, t, kmax, out);
    const double w = h[d], ew = E[0][d];
    if (!(w > 2.0 * ew) || !isfinite(w))
        return cj_fail(CJ_ERR_RANGE, "weight sum %g at t = %.17g is within its error bound %g", w,
                       t, ew);
    /* 3. The quotient rule c^(j) w = A^(j) - Σ_{i=1..j} C(j,i) w^(i) c^(j-i), computed as
     * v = Â^(j) - Σ C ŵ^(i) ĉ^(j-i) (two products and a subtraction per term: off by at most
     * gamma(j+2) S_j, S_j = |Â^(j)| + Σ C |ŵ^(i)| |ĉ^(j-i)|), ĉ^(j) = v / ŵ (|ĉ ŵ - v| <=
     * u (1+2u) |ĉ| ŵ). Subtracting the exact relation, with ŵ^(i) ĉ - w^(i) c =
     * (ŵ^(i) - w^(i)) ĉ + w^(i) (ĉ - c), |w^(i)| <= |ŵ^(i)| + E_w,i and |c^(j)| <= |ĉ^(j)| + e_j:
     *   e_j (ŵ - E_w,0) <= E_A,j + Σ C (E_w,i |ĉ^(j-i)| + (|ŵ^(i)| + E_w,i) e_{j-i})
     *                      + gamma(j+2) S_j + |ĉ^(j)| (E_w,0 + u (1+2u) ŵ).
     * Every term is non-negative and takes at most 4j + 8 roundings to compute: the result is
     * inflated by 1 + gamma(4j + 12), plus 2^-1060 for products that fell into subnormals. */
    double e[NJ * CJ_MAX_DIM], binom[NJ];
    binom[0] = 1.0;
    for (int j = 0; j <= kmax; ++j) {
        if (j > 0) {
            binom[j] = 1.0;
            for (int i = j - 1; i > 0; --i) binom[i] += binom[i - 1];
        }
        for (int k = 0; k < d; ++k) {
            double S = fabs(h[j * hd + k]), num = E[j][k];
            for (int i = 1; i <= j; ++i) {
                const double wi = fabs(h[i * hd + d]), ci = fabs(out[(j - i) * d + k]);
                S += binom[i] * wi * ci;
                num += binom[i] * (E[i][d] * ci + (wi + E[i][d]) * e[(j - i) * d + k]);
            }
            num += cj_gamma(2 * j + 3) * S + fabs(out[j * d + k]) * (ew + u * (1 + 2 * u) * w);
            const double b = (num / (w - ew) + 0x1p-1060) * (1.0 + cj_gamma(4 * j + 12));
            if (!isfinite(b))
                return cj_fail(CJ_ERR_RANGE,
                               "error bound of derivative %d, coordinate %d at t = %.17g overflows",
                               j, k, t);
            e[j * d + k] = b;
        }
    }
    memcpy(bound, e, sizeof(double) * (size_t)((kmax + 1) * d));
    return CJ_OK;
}

cj_status cj_bspline_derivs_error_bound(const cj_bspline *c, double t, int kmax, double *bound) {
    assert(bound != NULL);
    cj_status st = cj_bsp_check_derivs(c, t, kmax);
    if (st) return st;
    if (c->weights) return nurbs_derivs_bound(c, t, kmax, bound);
    const int d = c->dim, s = cj_bsp_span(c, t);
    double out[(CJ_BSPLINE_MAX_DERIV + 1) * CJ_MAX_DIM];
    cj_bsp_pyramid_bound(c, s, t, kmax, 0, out);
    for (int j = 0; j <= kmax; ++j)
        for (int k = 0; k < d; ++k)
            if (!isfinite(out[j * d + k]))
                return cj_fail(CJ_ERR_RANGE,
                               "error bound of derivative %d, coordinate %d at t = %.17g overflows",
                               j, k, t);
    memcpy(bound, out, sizeof(double) * (size_t)((kmax + 1) * d));
    return CJ_OK;
}

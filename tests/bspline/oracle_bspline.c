#include "oracle_bspline.h"

#include <assert.h>
#include <math.h>
#include <stdlib.h>

#define PREC CJ_ORACLE_BSP_PREC

/* Basis functions N_{i,q}(t) for i = 0..n1-1 by the full Cox–de Boor triangle (0/0 = 0). */
static void basis(const double *u, int n1, int q, const mpfr_t t, int span, mpfr_t *N) {
    const int nk = n1 + q + 1;
    mpfr_t *B = malloc(sizeof(mpfr_t) * (size_t)nk);
    mpfr_t a, b, den;
    mpfr_inits2(PREC, a, b, den, (mpfr_ptr)0);
    for (int i = 0; i < nk - 1; ++i) {
        mpfr_init2(B[i], PREC);
        mpfr_set_ui(B[i], i == span ? 1 : 0, MPFR_RNDN);
    }
    for (int k = 1; k <= q; ++k)
        for (int i = 0; i + k + 1 < nk; ++i) {
            /* N_{i,k} = (t - u_i)/(u_{i+k} - u_i) N_{i,k-1} + (u_{i+k+1} - t)/(u_{i+k+1} - u_{i+1})
             * N_{i+1,k-1}; in place: B[i] uses the old B[i] and B[i+1]. */
            mpfr_set_ui(a, 0, MPFR_RNDN);
            if (u[i + k] != u[i]) {
                mpfr_set_d(den, u[i + k], MPFR_RNDN);
                mpfr_sub_d(den, den, u[i], MPFR_RNDN);
                mpfr_sub_d(a, t, u[i], MPFR_RNDN);
                mpfr_div(a, a, den, MPFR_RNDN);
                mpfr_mul(a, a, B[i], MPFR_RNDN);
            }
            mpfr_set_ui(b, 0, MPFR_RNDN);
            if (u[i + k + 1] != u[i + 1]) {
                mpfr_set_d(den, u[i + k + 1], MPFR_RNDN);
                mpfr_sub_d(den, den, u[i + 1], MPFR_RNDN);
                mpfr_d_sub(b, u[i + k + 1], t, MPFR_RNDN);
                mpfr_div(b, b, den, MPFR_RNDN);
                mpfr_mul(b, b, B[i + 1], MPFR_RNDN);
            }
            mpfr_add(B[i], a, b, MPFR_RNDN);
        }
    for (int i = 0; i < n1; ++i) mpfr_set(N[i], B[i], MPFR_RNDN);
    for (int i = 0; i < nk - 1; ++i) mpfr_clear(B[i]);
    mpfr_clears(a, b, den, (mpfr_ptr)0);
    free(B);
}

static int find_span(const cj_obsp *c, const mpfr_t t) {
    int s = -1;
    for (int i = c->p; i < c->n1; ++i)
        if (c->knots[i] < c->knots[i + 1] && mpfr_cmp_d(t, c->knots[i]) >= 0) s = i;
    assert(s >= 0);
    return s;
}

/* Homogeneous coordinate j (0..dim-1 numerator, dim = weight) of point i. */
static void hcoord(const cj_obsp *c, int i, int j, mpfr_t out) {
    if (j == c->dim) {
        mpfr_set_d(out, c->w ? c->w[i] : 1.0, MPFR_RNDN);
        return;
    }
    mpfr_set_d(out, c->pts[(size_t)i * (size_t)c->dim + (size_t)j], MPFR_RNDN);
    if (c->w) mpfr_mul_d(out, out, c->w[i], MPFR_RNDN);
}

/* Derivatives 0..kmax of homogeneous coordinate j: val[o], and Σ|d^(o)|N in mag[o]. */
static void hderivs(const cj_obsp *c, int j, const mpfr_t t, int kmax, mpfr_t *val, mpfr_t *mag) {
    const int p = c->p, n1 = c->n1, span = find_span(c, t);
    mpfr_t *d = malloc(sizeof(mpfr_t) * (size_t)n1), *N = malloc(sizeof(mpfr_t) * (size_t)n1);
    mpfr_t *dm = malloc(sizeof(mpfr_t) * (size_t)n1); /* the same differences of |d| as sums */
    mpfr_t den, tmp;
    mpfr_inits2(PREC, den, tmp, (mpfr_ptr)0);
    for (int i = 0; i < n1; ++i) {
        mpfr_inits2(PREC, d[i], N[i], dm[i], (mpfr_ptr)0);
        hcoord(c, i, j, d[i]);
        mpfr_abs(dm[i], d[i], MPFR_RNDN);
    }
    for (int o = 0; o <= kmax; ++o) {
        mpfr_set_ui(val[o], 0, MPFR_RNDN);
        if (mag) mpfr_set_ui(mag[o], 0, MPFR_RNDN);
        if (o > p) continue;
        if (o > 0)
            for (int i = n1 - 1; i >= o; --i) {
                const double hi = c->knots[i + p + 1 - o], lo = c->knots[i];
                if (hi == lo) {
                    mpfr_set_ui(d[i], 0, MPFR_RNDN);
                    mpfr_set_ui(dm[i], 0, MPFR_RNDN);
                    continue;
                }
                mpfr_set_d(den, hi, MPFR_RNDN);
                mpfr_sub_d(den, den, lo, MPFR_RNDN);
                mpfr_add(dm[i], dm[i], dm[i - 1], MPFR_RNDN);
                mpfr_mul_ui(dm[i], dm[i], (unsigned long)(p - o + 1), MPFR_RNDN);
                mpfr_div(dm[i], dm[i], den, MPFR_RNDN);
                mpfr_sub(d[i], d[i], d[i - 1], MPFR_RNDN);
                mpfr_mul_ui(d[i], d[i], (unsigned long)(p - o + 1), MPFR_RNDN);
                mpfr_div(d[i], d[i], den, MPFR_RNDN);
            }
        basis(c->knots, n1, p - o, t, span, N);
        for (int i = o; i < n1; ++i) {
            mpfr_mul(tmp, d[i], N[i], MPFR_RNDN);
            mpfr_add(val[o], val[o], tmp, MPFR_RNDN);
            if (mag) {
                mpfr_mul(tmp, dm[i], N[i], MPFR_RNDN);
                mpfr_add(mag[o], mag[o], tmp, MPFR_RNDN);
            }
        }
    }
    for (int i = 0; i < n1; ++i) mpfr_clears(d[i], N[i], dm[i], (mpfr_ptr)0);
    free(dm);
    mpfr_clears(den, tmp, (mpfr_ptr)0);
    free(d);
    free(N);
}

void cj_obsp_eval(const cj_obsp *c, int k, const mpfr_t t, int kmax, mpfr_t *val, mpfr_t *mag) {
    for (int o = 0; o <= kmax; ++o) {
        mpfr_set_prec(val[o], PREC);
        if (mag) mpfr_set_prec(mag[o], PREC);
    }
    if (!c->w) {
        hderivs(c, k, t, kmax, val, mag);
        return;
    }
    mpfr_t *A = malloc(sizeof(mpfr_t) * (size_t)(kmax + 1));
    mpfr_t *W = malloc(sizeof(mpfr_t) * (size_t)(kmax + 1));
    mpfr_t *MA = malloc(sizeof(mpfr_t) * (size_t)(kmax + 1));
    for (int o = 0; o <= kmax; ++o) mpfr_inits2(PREC, A[o], W[o], MA[o], (mpfr_ptr)0);
    hderivs(c, k, t, kmax, A, MA);
    hderivs(c, c->dim, t, kmax, W, NULL);
    mpfr_t tmp, bin;
    mpfr_inits2(PREC, tmp, bin, (mpfr_ptr)0);
    for (int o = 0; o <= kmax; ++o) {
        mpfr_set(val[o], A[o], MPFR_RNDN);
        mpfr_set_ui(bin, 1, MPFR_RNDN);
        for (int i = 1; i <= o; ++i) {
            mpfr_mul_ui(bin, bin, (unsigned long)(o - i + 1), MPFR_RNDN); /* C(o,i), exact */
            mpfr_div_ui(bin, bin, (unsigned long)i, MPFR_RNDN);
            mpfr_mul(tmp, bin, W[i], MPFR_RNDN);
            mpfr_mul(tmp, tmp, val[o - i], MPFR_RNDN);
            mpfr_sub(val[o], val[o], tmp, MPFR_RNDN);
        }
        mpfr_div(val[o], val[o], W[0], MPFR_RNDN);
        if (mag) mpfr_div(mag[o], MA[o], W[0], MPFR_RNDN);
    }
    mpfr_clears(tmp, bin, (mpfr_ptr)0);
    for (int o = 0; o <= kmax; ++o) mpfr_clears(A[o], W[o], MA[o], (mpfr_ptr)0);
    free(A);
    free(W);
    free(MA);
}

double cj_obsp_abs_error(const cj_obsp *c, int k, double t, double computed, double *magnitude) {
    mpfr_t tt, v, m, e;
    mpfr_inits2(PREC, tt, v, m, e, (mpfr_ptr)0);
    mpfr_set_d(tt, t, MPFR_RNDN);
    cj_obsp_eval(c, k, tt, 0, &v, &m);
    mpfr_sub_d(e, v, computed, MPFR_RNDN);
    mpfr_abs(e, e, MPFR_RNDN);
    const double r = mpfr_get_d(e, MPFR_RNDU);
    if (magnitude) *magnitude = mpfr_get_d(m, MPFR_RNDU);
    mpfr_clears(tt, v, m, e, (mpfr_ptr)0);
    return r;
}

void cj_obsp_basis(const double *knots, int n1, int p, const mpfr_t t, mpfr_t *N) {
    const cj_obsp c = {p, 1, n1, NULL, NULL, knots};
    for (int i = 0; i < n1; ++i) mpfr_set_prec(N[i], PREC);
    basis(knots, n1, p, t, find_span(&c, t), N);
}

#include "oracle_mpfr.h"

#include <assert.h>
#include <math.h>
#include <stdlib.h>

/* de Casteljau in MPFR at precision prec; absolute != 0 runs it on |b|, |1-t|, |t|. Returns 1
 * if every operation was exact. */
static int run(const double *pts, int n, int d, int k, double t, int absolute, mpfr_prec_t prec,
               mpfr_t out) {
    mpfr_t *w = malloc(sizeof(mpfr_t) * (size_t)(n + 1));
    assert(w != NULL);
    mpfr_t s, tt;
    int inexact = 0;
    mpfr_init2(s, prec);
    mpfr_init2(tt, 64);
    mpfr_set_d(tt, t, MPFR_RNDN); /* exact: 53 bits */
    inexact |= mpfr_ui_sub(s, 1, tt, MPFR_RNDN);
    if (absolute) {
        mpfr_abs(s, s, MPFR_RNDN);
        mpfr_abs(tt, tt, MPFR_RNDN);
    }
    for (int i = 0; i <= n; ++i) {
        mpfr_init2(w[i], prec);
        double b = pts[(size_t)i * (size_t)d + (size_t)k];
        mpfr_set_d(w[i], absolute ? fabs(b) : b, MPFR_RNDN);
    }
    for (int r = n; r > 0; --r)
        for (int i = 0; i < r; ++i) inexact |= mpfr_fmma(w[i], s, w[i], tt, w[i + 1], MPFR_RNDN);
    mpfr_set_prec(out, prec);
    mpfr_set(out, w[0], MPFR_RNDN);
    for (int i = 0; i <= n; ++i) mpfr_clear(w[i]);
    mpfr_clear(s);
    mpfr_clear(tt);
    free(w);
    return !inexact;
}

double cj_oracle_bezier(const double *pts, int degree, int dim, int k, double t,
                        mpfr_prec_t max_prec, mpfr_t value, mpfr_t magnitude) {
    assert(pts && degree >= 0 && dim >= 1 && k >= 0 && k < dim && isfinite(t));
    if (max_prec < 256) max_prec = 256;
    mpfr_prec_t prec = 64 * (mpfr_prec_t)(degree + 2);
    if (prec < 256) prec = 256;
    if (prec > max_prec) prec = max_prec;
    for (;;) {
        int exact = run(pts, degree, dim, k, t, 0, prec, value);
        if (magnitude) exact &= run(pts, degree, dim, k, t, 1, prec, magnitude);
        if (exact) return 0.0;
        if (prec >= max_prec) break;
        prec = prec * 2 > max_prec ? max_prec : prec * 2;
    }
    /* Each fmma rounds once, 1-t once: relative to the magnitude the error is at most
     * gamma(2n+1) in precision prec; 3n 2^(1-prec) is a generous upper bound of it. */
    return ldexp(3.0 * (degree + 1), 1 - (int)prec);
}

double cj_oracle_abs_error(double computed, const mpfr_t exact) {
    mpfr_t e;
    mpfr_init2(e, mpfr_get_prec(exact) + 1100);
    mpfr_sub_d(e, exact, computed, MPFR_RNDN); /* exact at this precision for normal ranges */
    mpfr_abs(e, e, MPFR_RNDN);
    double r = mpfr_get_d(e, MPFR_RNDU);
    mpfr_clear(e);
    return r;
}

double cj_oracle_rel_error(double computed, const mpfr_t exact) {
    if (mpfr_zero_p(exact)) return computed == 0.0 ? 0.0 : INFINITY;
    mpfr_t e;
    mpfr_init2(e, mpfr_get_prec(exact) + 1100);
    mpfr_sub_d(e, exact, computed, MPFR_RNDN);
    mpfr_abs(e, e, MPFR_RNDN);
    mpfr_t a;
    mpfr_init2(a, mpfr_get_prec(exact));
    mpfr_abs(a, exact, MPFR_RNDN);
    mpfr_div(e, e, a, MPFR_RNDU);
    mpfr_clear(a);
    double r = mpfr_get_d(e, MPFR_RNDU);
    mpfr_clear(e);
    return r;
}

double cj_oracle_up(const mpfr_t x) {
    return mpfr_get_d(x, MPFR_RNDU);
}

#include "eval_check.h"
#include "oracle_mpfr.h"

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>

static const char *const method_names[CJ_N_METHODS] = {"decasteljau", "bernstein", "horner",
                                                       "compensated"};
#define ETA 0x1p-1074
#define U   0x1p-53

static double gam(int k) {
    return (double)k * U / (1.0 - (double)k * U) * (1.0 + 0x1p-50); /* rounded up generously */
}

/* The documented underflow allowance: ops (n+1) eta on [0,1]; none for a constant, which is
 * returned without arithmetic. */
static double uflow(int n, double ops) {
    return n ? ops * (n + 1) * ETA : 0.0;
}

static void fail_check(const char *label, int m, double t, int k, const char *what, double err,
                       double bound) {
    fail_msg("%s: method %s, t = %a (%.17g), coordinate %d: error %.3e exceeds %s %.3e", label,
             method_names[m], t, t, k, err, what, bound);
}

double cj_check_eval_point(const char *label, const cj_bezier *c, double t, mpfr_prec_t max_prec,
                           cj_eval_stats *st, double *values) {
    const int n = c->degree, d = c->dim;
    double out[CJ_N_METHODS][CJ_MAX_DIM], lib[CJ_N_METHODS][CJ_MAX_DIM], apost[CJ_MAX_DIM];
    int have[CJ_N_METHODS] = {0};
    for (int m = 0; m < CJ_N_METHODS; ++m) {
        if ((m == CJ_EVAL_BERNSTEIN || m == CJ_EVAL_HORNER) && n > CJ_BEZIER_BINOMIAL_MAX_DEGREE)
            continue;
        have[m] = 1;
        assert_int_equal(cj_bezier_eval(c, (cj_eval_method)m, t, out[m]), CJ_OK);
        assert_int_equal(cj_bezier_error_bound(c, (cj_eval_method)m, t, lib[m]), CJ_OK);
        if (values)
            for (int k = 0; k < d; ++k) values[m * d + k] = out[m][k];
    }
    double comp2[CJ_MAX_DIM];
    assert_int_equal(cj_bezier_eval_compensated(c, t, comp2, apost), CJ_OK);
    double cond0 = 0.0;
    mpfr_t val, mag;
    mpfr_inits2(256, val, mag, (mpfr_ptr)0);
    for (int k = 0; k < d; ++k) {
        const double rho = cj_oracle_bezier(c->pts, n, d, k, t, max_prec, val, mag);
        const double M = cj_oracle_up(mag) * (1.0 + rho);
        const double slack = rho * M; /* the oracle's own uncertainty */
        const double absval = fabs(mpfr_get_d(val, MPFR_RNDA)) + slack;
        const double cond = mpfr_zero_p(val) ? INFINITY : M / fabs(mpfr_get_d(val, MPFR_RNDZ));
        if (k == 0) cond0 = cond;
        if (cond > st->max_cond) st->max_cond = cond;
        double wsum = 1.0, binom = 1.0;
        for (int i = 0; i <= n && n <= CJ_BEZIER_BINOMIAL_MAX_DEGREE; ++i) {
            wsum += binom * fabs(c->pts[i * d + k]);
            binom = binom * (double)(n - i) / (double)(i + 1);
        }
        for (int m = 0; m < CJ_N_METHODS; ++m) {
            if (!have[m]) continue;
            const double err = cj_oracle_abs_error(out[m][k], val);
            const double errlo = err - slack > 0 ? err - slack : 0.0;
            double pub;
            if (m == CJ_EVAL_DECASTELJAU)
                pub = gam(3 * n) * M + uflow(n, 4.0);
            else if (m == CJ_EVAL_COMPENSATED)
                pub = (U * absval + 2.0 * gam(3 * n) * gam(3 * n) * M) * (1.0 + 0x1p-50) +
                      uflow(n, 8.0);
            else
                pub = gam(4 * n + 2) * M + uflow(n, 8.0) * wsum * (1.0 + 0x1p-40);
            if (errlo > pub) fail_check(label, m, t, k, "the published bound", errlo, pub);
            if (errlo > lib[m][k])
                fail_check(label, m, t, k, "cj_bezier_error_bound", errlo, lib[m][k]);
            /* The library's bound uses computed magnitudes: it must not fall below the
             * published one (allowing the oracle's uncertainty and 2^-40 for the rounding of
             * this comparison). */
            if (lib[m][k] < pub * (1.0 - 0x1p-40) - 4.0 * slack)
                fail_msg("%s: method %s, t = %a, coordinate %d: cj_bezier_error_bound %.6e is "
                         "below the published bound %.6e",
                         label, method_names[m], t, k, lib[m][k], pub);
            if (pub > 0 && errlo / pub > st->worst_published[m])
                st->worst_published[m] = errlo / pub;
            if (lib[m][k] > 0 && errlo / lib[m][k] > st->worst_library[m])
                st->worst_library[m] = errlo / lib[m][k];
            if (m == CJ_EVAL_COMPENSATED) {
                if (comp2[k] != out[m][k] && !(comp2[k] != comp2[k]))
                    fail_msg("%s: t = %a: compensated value with and without bound differ (%a, "
                             "%a)",
                             label, t, comp2[k], out[m][k]);
                if (errlo > apost[k])
                    fail_check(label, m, t, k, "the a-posteriori bound", errlo, apost[k]);
                if (apost[k] > 2.0 * pub)
                    fail_msg("%s: t = %a, coordinate %d: a-posteriori bound %.3e is not "
                             "informative (published a-priori bound %.3e)",
                             label, t, k, apost[k], pub);
                if (apost[k] > 0 && errlo / apost[k] > st->worst_aposteriori)
                    st->worst_aposteriori = errlo / apost[k];
            }
        }
        st->points++;
    }
    mpfr_clears(val, mag, (mpfr_ptr)0);
    return cond0;
}

void cj_eval_stats_print(const char *label, const cj_eval_stats *s) {
    printf("%s: %ld coordinates; worst error/bound published [dc %.2g bern %.2g horner %.2g "
           "comp %.2g], library [%.2g %.2g %.2g %.2g], a-posteriori %.2g; max cond %.2g\n",
           label, s->points, s->worst_published[0], s->worst_published[1], s->worst_published[2],
           s->worst_published[3], s->worst_library[0], s->worst_library[1], s->worst_library[2],
           s->worst_library[3], s->worst_aposteriori, s->max_cond);
}

/* Checks one evaluation point of a Bézier curve, every method, against the exact MPFR oracle
 * and the published error bounds (curves/include/casteljau/bezier.h). Shared by the stability
 * and degree test programs. A violation fails the current cmocka test with a message naming
 * the case label, the method, t, the coordinate, the error and the bound. */
#ifndef CJ_TEST_EVAL_CHECK_H
#define CJ_TEST_EVAL_CHECK_H

#include "casteljau/bezier.h"
#include <mpfr.h>

#define CJ_N_METHODS 4

/* Worst ratios error / bound seen so far, per method (for the summary a test prints). */
typedef struct cj_eval_stats {
    long points;                          /* coordinates checked */
    double worst_published[CJ_N_METHODS]; /* max error / published bound */
    double worst_library[CJ_N_METHODS];   /* max error / cj_bezier_error_bound */
    double worst_aposteriori;             /* max error / a-posteriori bound (compensated) */
    double max_cond;                      /* largest exact condition number met */
} cj_eval_stats;

/* Per coordinate of c at t, exact value and magnitude M = Σ|b_i|B_i(|t|) by the oracle
 * (precision up to max_prec bits), then for each method allowed at this degree:
 *   error <= published bound, where published is (eta = 2^-1074; the eta terms are the
 *   documented underflow allowance, absent for n = 0)
 *     de Casteljau:        gamma(3n) M + 4(n+1) eta
 *     Bernstein, Horner:   gamma(4n+2) M + 8(n+1) eta (1 + Σ C(n,i)|b_i|)
 *     compensated:         u|c(t)| + 2 gamma(3n)^2 M + 8(n+1) eta
 *   error <= cj_bezier_error_bound(...) and that bound >= the published one;
 * and for the compensated method also error <= the a-posteriori bound <= 2 x published.
 * t must lie in [0,1] (the published bounds are stated there). Returns the exact relative
 * condition number of coordinate 0 (M / |c_0(t)|, +inf at a zero). If values is not NULL,
 * values[m*dim + k] receives the result of method m. */
double cj_check_eval_point(const char *label, const cj_bezier *c, double t, mpfr_prec_t max_prec,
                           cj_eval_stats *stats, double *values);

/* Prints one summary line for the stats. */
void cj_eval_stats_print(const char *label, const cj_eval_stats *stats);

#endif

/* A high-precision oracle for B-spline and NURBS curves with double data, independent of the
 * library: the Cox–de Boor recurrence of the basis functions in MPFR at CJ_ORACLE_BSP_PREC bits
 * (knot differences of doubles are then exact; each division rounds by at most 2^-PREC
 * relatively, so the value is within ~4(p+1)^2 2^-PREC of its magnitude, far below any double
 * error), derivatives by the divided differences of the control points, computed in MPFR too.
 */
#ifndef CJ_TEST_ORACLE_BSPLINE_H
#define CJ_TEST_ORACLE_BSPLINE_H

#include <mpfr.h>

#define CJ_ORACLE_BSP_PREC 2300

typedef struct cj_obsp {
    int p, dim, n1;
    const double *pts, *w, *knots; /* w may be NULL */
} cj_obsp;

/* Derivatives 0..kmax of coordinate k of the curve at the parameter t (an mpfr value in the
 * domain; the span is the one containing t, the last non-empty one at the right end):
 * val[j] = c_k^(j)(t) and mag[j] (may be NULL) = Σ m^(j)_i N_{i,p-j}(t), where m^(j) are the
 * divided differences taken on magnitudes, m^(0) = |d_i,k|, m^(j)_i = (p-j+1)(m^(j-1)_i +
 * m^(j-1)_{i-1}) / (t_{i+p+1-j} - t_i): what rounding errors of the differences scale with
 * (polynomial), or
 * for a NURBS the magnitude of the homogeneous numerator Σ |w_i d_i,k| N_{i,p}(t) / w(t)
 * (mag[0] only). val and mag: kmax+1 mpfr_t each, initialised by the caller. */
void cj_obsp_eval(const cj_obsp *c, int k, const mpfr_t t, int kmax, mpfr_t *val, mpfr_t *mag);

/* Same at a double parameter, first coordinate value as a double-rounded error helper:
 * |computed - c_k(t)| rounded up, and the magnitude rounded up (may be NULL). */
double cj_obsp_abs_error(const cj_obsp *c, int k, double t, double computed, double *magnitude);

/* The n1 basis functions N_{i,p}(t) of the knot vector (t in its domain) into N[n1] (initialised
 * mpfr_t; precision reset to CJ_ORACLE_BSP_PREC). */
void cj_obsp_basis(const double *knots, int n1, int p, const mpfr_t t, mpfr_t *N);

#endif

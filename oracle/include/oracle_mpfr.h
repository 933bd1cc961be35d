/* An exact (or rigorously enclosed) oracle for Bézier curves with double control points, built
 * on MPFR. Independent of the library: it runs its own de Casteljau triangle in MPFR, where
 * every operation reports whether it rounded (the ternary value). In exact mode the precision
 * is doubled until no operation rounds, so the value is the exact real value of the polynomial
 * with those double coefficients at that double parameter. */
#ifndef CJ_TEST_ORACLE_MPFR_H
#define CJ_TEST_ORACLE_MPFR_H

#include <mpfr.h>

/* Coordinate k of the curve (degree n, dimension d, point-major pts) at t:
 *   value     <- Σ b_{i,k} C(n,i) t^i (1-t)^(n-i)
 *   magnitude <- Σ |b_{i,k}| C(n,i) |t|^i |1-t|^(n-i)   (may be NULL)
 * Both outputs must be initialised mpfr_t; their precision is reset. The working precision
 * starts at max(256, 64 (n+2)) bits (capped at max_prec) and doubles while some operation was
 * inexact, up to max_prec (>= 256). Returns a relative radius rho >= 0: with M the exact
 * magnitude, |value - exact value| <= rho M and |magnitude - M| <= rho M. rho is 0.0 when every
 * operation was exact, else 3(n+1) 2^(1-prec), above the de Casteljau error bound at that
 * precision. */
double cj_oracle_bezier(const double *pts, int degree, int dim, int k, double t,
                        mpfr_prec_t max_prec, mpfr_t value, mpfr_t magnitude);

/* |computed - exact| rounded up to a double. */
double cj_oracle_abs_error(double computed, const mpfr_t exact);

/* |computed - exact| / |exact| rounded up; 0 when both are zero, +INFINITY when only the exact
 * value is zero. */
double cj_oracle_rel_error(double computed, const mpfr_t exact);

/* A double rounded up (towards +infinity) from an MPFR value. */
double cj_oracle_up(const mpfr_t x);

#endif

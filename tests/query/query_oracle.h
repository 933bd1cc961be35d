/* Test oracles for the certified queries, independent of the library's code:
 *   - MPFR evaluation of plane Bézier and rational curves (point and first derivative, by the
 *     de Casteljau triangle of the homogeneous points at 256 bits);
 *   - MPFR Newton on a(s) - b(t) = 0 from a starting point, giving the root to ~70 digits;
 *   - polyline crossings of two curves in long double (a different method: sampled, not
 *     subdivided, and no hulls), with the sampling error bound h^2/8 max|c''|. */
#ifndef CJ_TEST_QUERY_ORACLE_H
#define CJ_TEST_QUERY_ORACLE_H

#include <mpfr.h>

typedef struct qo_curve {
    int n;
    const double *pts;
    const double *w; /* NULL: polynomial */
} qo_curve;

/* Point p[2] and derivative d[2] (may be NULL) of c at t, at precision of the outputs. */
void qo_eval(const qo_curve *c, const mpfr_t t, mpfr_t p[2], mpfr_t d[2]);

/* Newton for a(s) = b(t) from (s0, t0) at 256 bits. Writes the root and returns |F| at it as a
 * double (about 1e-70 for a simple root; large if Newton did not converge). */
double qo_newton(const qo_curve *a, const qo_curve *b, double s0, double t0, mpfr_t s, mpfr_t t);

/* Exact (256-bit) distance from q to c(t). */
double qo_distance(const qo_curve *c, double t, const double q[2]);

/* Crossings of the polylines through N+1 samples of each curve (long double): writes up to cap
 * parameter pairs (s, t) into st[2*i], returns the count. *errbound receives the largest
 * distance from a curve to its polyline (h^2/8 max|c''|). */
int qo_polyline_crossings(const qo_curve *a, const qo_curve *b, int N, double *st, int cap,
                          double *errbound);

/* Self-crossings of the polyline of a: pairs of non-neighbouring segments, s < t. */
int qo_polyline_self_crossings(const qo_curve *a, int N, double *st, int cap, double *errbound);

#endif

/* casteljau: B-spline curves fitted to data — global interpolation through points and
 * least-squares approximation to a tolerance.
 *
 * Data: N points Q_0..Q_{N-1} of dimension dim (point-major, Q_k = pts[k*dim ..]). Each gets a
 * parameter ū_k in [0, 1], ū_0 = 0, ū_{N-1} = 1, spaced by
 *     uniform:      ū_{k+1} − ū_k ∝ 1
 *     chord length: ū_{k+1} − ū_k ∝ |Q_{k+1} − Q_k|
 *     centripetal:  ū_{k+1} − ū_k ∝ |Q_{k+1} − Q_k|^(1/2)
 * (chord length and centripetal refuse two equal consecutive points: CJ_ERR_DEGENERATE naming
 * them). The result is a clamped polynomial B-spline over [0, 1] (cj_bspline, ready for every
 * function of bspline.h); derivatives are with respect to that parameter.
 *
 * Knots. Interpolation averages the parameters (de Boor's choice, which makes every row of the
 * collocation matrix non-zero on its diagonal, so the system is never singular by the
 * Schoenberg–Whitney condition): with the list ext = ū, where an end with a prescribed derivative
 * repeats its parameter once, interior knot j = 1..M-p-1 is the mean of ext_j..ext_{j+p-1}
 * (M control points). Approximation with M control points places interior knot j = 1..M-p-1 at
 * (1−α) ū_{i−1} + α ū_i with i = floor(j N/(M−p)), α = j N/(M−p) − i, so every knot span holds
 * at least one parameter and the normal equations are positive definite.
 *
 * Systems are solved by LAPACK in band storage (dgbsv for the collocation matrix, bandwidth p;
 * dpbsv for the normal equations): O(N p^2) work. The functions allocate their work space
 * (CJ_ERR_NOMEM).
 */
#ifndef CASTELJAU_BSPLINE_FIT_H
#define CASTELJAU_BSPLINE_FIT_H

#include "casteljau/bspline.h"
#include "casteljau/status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum cj_fit_param {
    CJ_FIT_UNIFORM = 0,
    CJ_FIT_CHORD,      /* chord length */
    CJ_FIT_CENTRIPETAL /* square root of the chord length */
} cj_fit_param;

/* The parameters ū_k of the data points into ts[npts] (npts >= 2). Statuses: CJ_ERR_EMPTY
 * (npts < 2), CJ_ERR_DIMENSION, CJ_ERR_NONFINITE (a point, named), CJ_ERR_DEGENERATE (equal
 * consecutive points for chord/centripetal), CJ_ERR_ARGUMENT (unknown kind). */
cj_status cj_fit_params(const double *pts, int npts, int dim, cj_fit_param kind, double *ts);

/* Global interpolation of degree p (1..CJ_BSPLINE_MAX_DEGREE) through npts points: c(ū_k) =
 * Q_k exactly up to the solver's rounding, and, when d_start / d_end (dim doubles each, or NULL)
 * are given, c'(0) = d_start, c'(1) = d_end. M = npts + (d_start != NULL) + (d_end != NULL)
 * control points into out_pts[M*dim], M + p + 1 knots into out_knots; *npts_out = M.
 * npts must be >= p + 1 − (number of end derivatives) and >= 2 (CJ_ERR_EMPTY otherwise); end
 * derivatives need p >= 2 (CJ_ERR_DEGREE).
 * *residual (may be NULL) receives max_k |c(ū_k) − Q_k| measured by cj_bspline_eval.
 * CJ_ERR_SINGULAR if LAPACK reports a singular system (cannot happen with distinct parameters;
 * reported rather than assumed). */
cj_status cj_bspline_interpolate(const double *pts, int npts, int dim, int degree,
                                 cj_fit_param kind, const double *d_start, const double *d_end,
                                 double *out_pts, double *out_knots, int *npts_out,
                                 double *residual);

/* Least-squares approximation to a tolerance: the clamped B-spline of degree p with the fewest
 * control points M (p+1 <= M <= min(max_pts, npts)) whose largest deviation at the data
 * parameters, max_k |c(ū_k) − Q_k| (Euclidean, measured by cj_bspline_eval), is <= tol. End
 * points are interpolated exactly (d_0 = Q_0, d_{M-1} = Q_{N-1}); the inner points minimise
 * Σ_k |c(ū_k) − Q_k|^2. M is searched by growing it by half until the tolerance is met, then by
 * bisection between the last failure and that success (deviation is not monotone in M in
 * general, so M is the smallest found by this search, not a proven minimum).
 * out_pts must hold min(max_pts, npts)*dim doubles, out_knots min(max_pts, npts) + p + 1;
 * *npts_out receives M, *max_dev the deviation reached. If no M up to the cap meets tol, the
 * best (largest-M) curve is written and CJ_ERR_CAP is returned. tol >= 0 (CJ_ERR_ARGUMENT);
 * max_pts >= p+1. */
cj_status cj_bspline_approximate(const double *pts, int npts, int dim, int degree,
                                 cj_fit_param kind, double tol, int max_pts, double *out_pts,
                                 double *out_knots, int *npts_out, double *max_dev);

/* The least-squares fit with exactly M control points (same rules as above, no search):
 * out_pts[M*dim], out_knots[M+p+1], *max_dev (may be NULL) the deviation at the data. */
cj_status cj_bspline_lsq(const double *pts, int npts, int dim, int degree, cj_fit_param kind, int m,
                         double *out_pts, double *out_knots, double *max_dev);

#ifdef __cplusplus
}
#endif
#endif

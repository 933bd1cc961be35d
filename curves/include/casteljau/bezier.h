/* casteljau: polynomial Bézier curves of any degree and dimension.
 *
 * A curve of degree n in dimension d has n+1 control points b_0..b_n stored point-major in one
 * array of (n+1)*d doubles: coordinate k of point i is pts[i*d + k]. It is
 *
 *     c(t) = Σ_{i=0..n} b_i B_i^n(t),   B_i^n(t) = C(n,i) t^i (1-t)^(n-i).
 *
 * cj_bezier is a non-owning view; the caller owns `pts` and every output buffer. No function in
 * this header allocates: work space lives on the stack, bounded by CJ_BEZIER_MAX_DEGREE and
 * CJ_MAX_DIM.
 *
 * Parameters: evaluation accepts any finite t (outside [0,1] it is polynomial extrapolation,
 * with error growing like the size of the basis there); operations that produce pieces of the
 * curve (split, subcurve) require parameters in [0,1] and return CJ_ERR_RANGE otherwise.
 *
 * Every function validates its input (degree, dimension, finite coordinates and parameters)
 * and returns a status; on failure cj_last_error() names the offending input and outputs are
 * untouched.
 */
#ifndef CASTELJAU_BEZIER_H
#define CASTELJAU_BEZIER_H

#include "casteljau/status.h"
#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Largest dimension of a control point. */
#define CJ_MAX_DIM 8
/* Largest degree for de Casteljau, compensated de Casteljau, derivatives and subdivision. */
#define CJ_BEZIER_MAX_DEGREE 255
/* Largest degree for the methods that use binomial coefficients (Bernstein sum, Horner-like):
 * C(n,i) is exact in double for every i only while n <= 56 (C(57,28) > 2^53). */
#define CJ_BEZIER_BINOMIAL_MAX_DEGREE 56

typedef struct cj_bezier {
    int degree;        /* n >= 0; there are n+1 control points */
    int dim;           /* 1..CJ_MAX_DIM */
    const double *pts; /* (degree+1)*dim coordinates, point-major */
} cj_bezier;

typedef enum cj_eval_method {
    CJ_EVAL_DECASTELJAU = 0, /* the triangle of convex combinations: stable, O(n^2 d) */
    CJ_EVAL_BERNSTEIN,       /* direct sum Σ b_i B_i^n(t), basis by powers and binomials */
    CJ_EVAL_HORNER,          /* Volk–Schumaker: Horner in t/(1-t) (or (1-t)/t), O(n d); at
                              * degree 3, Horner in t with s-power coefficients (no division) */
    CJ_EVAL_COMPENSATED      /* de Casteljau with error-free transformations (Graillat et al.) */
} cj_eval_method;

/* Builds a view. Convenience only: no validation happens until the view is used. */
static inline cj_bezier cj_bezier_view(int degree, int dim, const double *pts) {
    cj_bezier c;
    c.degree = degree;
    c.dim = dim;
    c.pts = pts;
    return c;
}

/* Validates a curve: degree in [0, max_degree], dim in [1, CJ_MAX_DIM], finite coordinates.
 * Returns CJ_ERR_DEGREE / CJ_ERR_DIMENSION / CJ_ERR_NONFINITE with a message naming the point. */
cj_status cj_bezier_check(const cj_bezier *c, int max_degree);

/* Unit round-off u = 2^-53 and gamma(k) = k u / (1 - k u), used by the published bounds. */
#define CJ_UNIT_ROUNDOFF 0x1p-53
double cj_gamma(int k);

/* ---- evaluation ---------------------------------------------------------------------- */

/* c(t) by the chosen method into out[0..dim-1]. Degree limit: CJ_BEZIER_MAX_DEGREE for
 * de Casteljau and compensated, CJ_BEZIER_BINOMIAL_MAX_DEGREE for Bernstein and Horner.
 * A value that overflows (far extrapolation of a high degree) is CJ_ERR_RANGE naming t, with
 * out untouched: a NaN or infinity is never returned. */
cj_status cj_bezier_eval(const cj_bezier *c, cj_eval_method method, double t, double *out);

/* Unchecked evaluation, for callers that validate a curve once and evaluate it many times
 * (a validated curve costs nothing more to evaluate: cj_bezier_eval spends 5-10 ns per call on
 * validation, as much as Horner's work at degree 8).
 * CONTRACT, the caller's to keep (nothing is checked in release builds; debug builds assert it):
 *   - cj_bezier_check(c, limit) returned CJ_OK for this curve, with limit the method's degree
 *     limit (CJ_BEZIER_MAX_DEGREE, or CJ_BEZIER_BINOMIAL_MAX_DEGREE for Bernstein and Horner),
 *     and neither the view nor its control points have changed since;
 *   - method is one of the four cj_eval_method values and t is finite;
 *   - out has room for c->dim doubles and does not overlap the control points.
 * Then out receives exactly what cj_bezier_eval would write (same kernels, bit-identical, the
 * same error bounds), with no status and no error state touched. The one difference: a value
 * that overflows (far extrapolation, t well outside [0,1]) is written as it comes out, possibly
 * infinite or NaN, where cj_bezier_eval returns CJ_ERR_RANGE; for t in [0,1] and coordinates
 * below 2^(1000-n) in magnitude this cannot happen. Breaking the contract is undefined behaviour.
 * CJ_EVAL_HORNER at degree 3 is a division-free unrolled kernel, ((b_3 t + 3 s b_2) t +
 * 3 s^2 b_1) t + s^3 b_0 with s = 1 - t, within the same gamma(4n+2) bound (bench_eval: per-call
 * cost against de Casteljau). */
void cj_bezier_eval_unchecked(const cj_bezier *c, cj_eval_method method, double t, double *out);

/* Individual methods, same contract as cj_bezier_eval. */
cj_status cj_bezier_eval_decasteljau(const cj_bezier *c, double t, double *out);
cj_status cj_bezier_eval_bernstein(const cj_bezier *c, double t, double *out);
cj_status cj_bezier_eval_horner(const cj_bezier *c, double t, double *out);

/* Compensated de Casteljau: out[k] is c_k(t) computed as if in twice the working precision,
 * then rounded. If `bound` is not NULL, bound[k] receives a computable a-posteriori bound on
 * |out[k] - c_k(t)| that holds for t in [0,1] (outside [0,1] it is still computed, and holds
 * with 1-t and t replaced by their absolute values in the running-error analysis). */
cj_status cj_bezier_eval_compensated(const cj_bezier *c, double t, double *out, double *bound);

/* A-priori absolute error bound of a method at t, per coordinate. With M_k = Σ|b_i,k| B_i^n(|t|)
 * (the numerator of the condition number), eta = 2^-1074 and A = |1-t| + |t| (A = 1 on [0,1]):
 *   de Casteljau:      gamma(3n) M_k                       + 4 (n+1) eta A^n
 *   Bernstein, Horner: gamma(4n+2) M_k                     + 8 (n+1) eta A^n (1 + Σ C(n,i)|b_i,k|)
 *   compensated:       u |c_k(t)| + 2 gamma(3n)^2 M_k      + 8 (n+1) eta A^n
 * The eta terms cover roundings that underflow into subnormals (where the relative model fails);
 * they vanish for n = 0 and are negligible unless the values themselves are tiny. |c_k(t)| is
 * taken at the compensated value, M_k is computed and inflated by 1 + gamma(3n+8) so the
 * computed bound is an upper bound of the exact one. Checked against an MPFR oracle in
 * tests/test_bezier_stability.c. A bound that overflows the double range (control points near
 * it) is CJ_ERR_RANGE naming t and the coordinate; bound is then partly written. */
cj_status cj_bezier_error_bound(const cj_bezier *c, cj_eval_method method, double t, double *bound);

/* Condition number of each coordinate at t: cond_k = Σ|b_i,k| B_i^n(t) / |c_k(t)|.
 * A coordinate whose value is exactly zero gets +INFINITY (the relative error is undefined). */
cj_status cj_bezier_cond(const cj_bezier *c, double t, double *cond);

/* Evaluates at nt parameters: out[j*dim + k] = c_k(ts[j]), bit-identical to the single-point
 * calls. Validates the curve once, then runs without allocation. All parameters are validated
 * before anything is written; a value that overflows is CJ_ERR_RANGE naming its parameter, and
 * the results before that parameter are valid. */
cj_status cj_bezier_eval_batch(const cj_bezier *c, cj_eval_method method, const double *ts,
                               size_t nt, double *out);

/* ---- derivatives --------------------------------------------------------------------- */

/* The k-th hodograph: the derivative c^(k) as a Bézier curve of degree n-k, whose control
 * points n!/(n-k)! Δ^k b_i are written to out[(n-k+1)*dim]. For k > n the derivative is the
 * zero curve of degree 0 (one zero point is written). k < 0 is CJ_ERR_ARGUMENT; control points
 * beyond the double range (high orders of high degrees) are CJ_ERR_RANGE, out untouched. */
cj_status cj_bezier_hodograph(const cj_bezier *c, int k, double *out);

/* Point and derivatives 0..kmax together in one pass of the de Casteljau triangle:
 * out[j*dim + k] = coordinate k of c^(j)(t), j = 0..kmax. Orders above n are zero.
 * A derivative beyond the double range is CJ_ERR_RANGE, out untouched. */
cj_status cj_bezier_eval_derivs(const cj_bezier *c, double t, int kmax, double *out);

/* ---- subdivision and degree ---------------------------------------------------------- */

/* Splits at t in [0,1]: left = c on [0,t], right = c on [t,1], each n+1 points reparametrised
 * to [0,1]. Either output may be NULL. left[n] and right[0] are bit-identical. */
cj_status cj_bezier_split(const cj_bezier *c, double t, double *left, double *right);

/* The piece on [a,b] (0 <= a < b <= 1, or a > b for a reversed piece) as n+1 points: out(u) =
 * c(a + (b-a) u). Computed by two de Casteljau splits (at max(a,b), then at min/max), so the
 * points carry the split's rounding. a == b is CJ_ERR_ARGUMENT (empty piece); a or b outside
 * [0,1] is CJ_ERR_RANGE. */
cj_status cj_bezier_subcurve(const cj_bezier *c, double a, double b, double *out);

/* Exact degree elevation by r >= 0 steps: out holds (n+r+1)*dim coordinates of the same curve.
 * One degree at a time, b'_i = i/(m+1) b_{i-1} + (1 - i/(m+1)) b_i (convex combinations, no
 * large binomials). Fails with CJ_ERR_DEGREE if n+r exceeds CJ_BEZIER_MAX_DEGREE, with
 * CJ_ERR_ARGUMENT if r < 0. */
cj_status cj_bezier_elevate(const cj_bezier *c, int r, double *out);

/* Reversal: out is the same curve traversed backwards, c'(t) = c(1-t). out may equal pts. */
cj_status cj_bezier_reverse(const cj_bezier *c, double *out);

/* ---- geometry ------------------------------------------------------------------------ */

/* Tight axis-aligned bounding box of c([0,1]): endpoints plus the interior zeros of each
 * coordinate's derivative (found by Bernstein-form root isolation: sign-variation test,
 * midpoint subdivision to depth 48, safeguarded Newton/bisection on isolated simple zeros).
 * lo, hi: dim doubles. The box is the hull of computed curve points, so it is tight up to the
 * evaluation error (cj_bezier_error_bound) at the extremal parameters. Any degree up to
 * CJ_BEZIER_MAX_DEGREE; about 100 KiB of stack. */
cj_status cj_bezier_bbox(const cj_bezier *c, double *lo, double *hi);

/* 2D convex hull of the control polygon (dim must be 2, else CJ_ERR_DIMENSION): indices of the
 * hull vertices in counter-clockwise order starting from the lowest-then-leftmost point,
 * collinear points dropped. idx must hold degree+1 entries; *count receives the number of hull
 * vertices. Andrew's monotone chain with an exact orientation predicate (filtered, then
 * error-free expansion), so near-collinear input never yields a non-convex hull.
 * Degenerate input is not an error: coincident points are reported once (the lowest index);
 * if all points coincide, *count = 1; if all are collinear, *count = 2 (the two extremes, the
 * lowest-then-leftmost first). */
cj_status cj_bezier_hull2d(const cj_bezier *c, int *idx, int *count);

/* Arc length of c on [a,b] (any a <= b in [0,1]) by adaptive Gauss–Legendre quadrature of |c'|,
 * to absolute tolerance tol > 0. *length gets the value, *error_estimate (may be NULL) the
 * error estimate reached. If the recursion cap is hit before tol is met, the best value and
 * its estimate are still written and CJ_ERR_CAP is returned.
 * Method: globally adaptive Gauss–Kronrod 7/15 (worst interval bisected first), at most 2000
 * intervals (initially 2 + n/8 uniform pieces), no allocation. The estimate is Σ|K15 - G7| plus
 * a rounding floor gamma(3n + 2d + 17) * length, so a tol below what double precision can
 * deliver ends in CJ_ERR_CAP rather than a false claim; on an interval whose nodes are too
 * sparse to exclude a hidden dip of the speed (h max|c''| > 4 min node speed) the estimate is
 * replaced by the rigorous bound h (max node speed + 0.052 h max|c''|), so near-cusps are
 * refined instead of being missed. a > b or a, b outside [0,1]: CJ_ERR_RANGE; tol <= 0:
 * CJ_ERR_ARGUMENT; NaN: CJ_ERR_NONFINITE. */
cj_status cj_bezier_arclength(const cj_bezier *c, double a, double b, double tol, double *length,
                              double *error_estimate);

/* Unit tangent at t. Where c'(t) vanishes (a cusp, repeated control points), the direction is
 * the first non-vanishing derivative c^(j)(t), j >= 2, which is the limit of c'(s)/|c'(s)| as s
 * approaches t from above; *order (may be NULL) receives the j used. A curve whose every
 * derivative vanishes at t (a single point) is CJ_ERR_DEGENERATE.
 * "Vanishing" is relative to the curve's scale: with S = max |b_i,k| and D_j(t) =
 * c^(j)(t) (n-j)!/n! = Σ Δ^j b_i B_i^{n-j}(t), the derivative counts as zero when
 * max_k |D_j,k(t)| <= 8 n u 2^j S (u = 2^-53), a small multiple of the rounding noise of D_j.
 * The rule is invariant under uniform scaling of the control points. The same test decides
 * "non-vanishing" in cj_bezier_normal and cj_bezier_curvature. */
cj_status cj_bezier_tangent(const cj_bezier *c, double t, double *tangent, int *order);

/* Unit normal at t. In 2D: the tangent turned +90 degrees (left normal). In 3D: the principal
 * normal, component of the next non-vanishing derivative orthogonal to the tangent; a straight
 * piece with no such component is CJ_ERR_DEGENERATE. Other dimensions: CJ_ERR_DIMENSION. */
cj_status cj_bezier_normal(const cj_bezier *c, double t, double *normal);

/* Curvature at t: signed in 2D ((x'y'' - y'x'')/|c'|^3, positive turning left), |c' x c''|/|c'|^3
 * in 3D (non-negative). At a zero-speed point the limit along the first non-vanishing
 * derivatives is used where it exists; otherwise CJ_ERR_DEGENERATE.
 * Precisely: with c^(j) the first non-vanishing derivative and c^(m) the first one with a
 * non-vanishing component across c^(j), the limit as s -> t+ is
 * |c^(j) x c^(m)| (m-j) ((j-1)!)^2 / ((m-1)! |c^(j)|^3) if m = 2j (j = 1, m = 2 is the formula
 * above), 0 if m > 2j or no such m exists (straight, inflection), and unbounded if m < 2j (an
 * ordinary cusp): CJ_ERR_DEGENERATE. A single point is CJ_ERR_DEGENERATE; dims other than 2, 3
 * are CJ_ERR_DIMENSION. */
cj_status cj_bezier_curvature(const cj_bezier *c, double t, double *kappa);

#ifdef __cplusplus
}
#endif
#endif

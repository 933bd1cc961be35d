/* casteljau: polynomial interpolation with value and derivative constraints (Hermite–Birkhoff),
 * returned in Bézier form (and power form on request) with a condition estimate.
 *
 * Given m constraints c^(r_j)(t_j) = v_j (r_j = 0: a value, 1: a first derivative, ...), each
 * v_j a point of dimension d, the interpolant is the unique polynomial curve c of degree
 * n = m − 1 that satisfies them all, if one exists. It is returned as a Bézier curve over a
 * parameter interval [a, b] chosen by the caller (typically [min t_j, max t_j]): the control
 * points b_0..b_n satisfy c(t) = Σ b_i B_i^n((t − a)/(b − a)).
 *
 * Method: the m×m system in the Bernstein basis on [a, b] (row j: the r_j-th derivative of each
 * B_i^n at t_j, scaled by (b − a)^(−r_j)) is equilibrated and solved by LU with partial
 * pivoting and iterative refinement (LAPACK dgesvx); no inverse is formed. The condition
 * estimate is 1/rcond, rcond being LAPACK's reciprocal 1-norm condition estimate of the
 * equilibrated matrix.
 *
 * Clashes are refused with CJ_ERR_SINGULAR and a message naming the constraints:
 *   - two constraints of the same order at the same t (equal or different values),
 *   - a derivative order above the degree n = m − 1 (that derivative is identically zero),
 *   - any other set that does not determine the polynomial (e.g. only derivatives, no value):
 *     found by QR with column pivoting of the transposed matrix (dgeqp3), which names a
 *     constraint that depends linearly on the others.
 * A condition estimate above 1/(64 u) ≈ 5.6e14 counts as singular; the message then says
 * whether a constraint is numerically dependent on the others or the set is merely too
 * ill-conditioned for double precision (equispaced parameters at degree 40, say).
 */
#ifndef CASTELJAU_INTERP_H
#define CASTELJAU_INTERP_H

#include "casteljau/status.h"
#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Largest interpolation degree (m <= CJ_INTERP_MAX_DEGREE + 1 constraints). */
#define CJ_INTERP_MAX_DEGREE 64

typedef struct cj_interp_constraint {
    double t;            /* parameter, finite */
    int order;           /* 0 = value, 1 = first derivative, ... (>= 0) */
    const double *value; /* dim doubles: the prescribed value or derivative d^r c/dt^r */
} cj_interp_constraint;

/* Solves the constraint set cons[m] in dimension dim (1..CJ_MAX_DIM) on [a, b] (a < b, finite).
 *   bez:   (m)*dim doubles, the Bézier control points over [a, b] (point-major)
 *   power: NULL, or m*dim doubles: power-form coefficients in the ORIGINAL parameter t,
 *          c(t) = Σ_k power[k*dim..] t^k (computed from the Bézier form by Taylor expansion at
 *          t = 0; ill-conditioned when 0 is far from [a, b] — the Bézier form is the reliable one)
 *   cond:  NULL, or the condition estimate (>= 1).
 * Status: CJ_ERR_EMPTY (m = 0), CJ_ERR_DEGREE (m > CJ_INTERP_MAX_DEGREE + 1), CJ_ERR_DIMENSION,
 * CJ_ERR_NONFINITE (a parameter or value, named), CJ_ERR_ARGUMENT (negative order, a >= b),
 * CJ_ERR_RANGE (b - a overflows the double range), CJ_ERR_SINGULAR (clash, named),
 * CJ_ERR_NOMEM. Outputs are untouched on failure. */
cj_status cj_interp_solve(const cj_interp_constraint *cons, size_t m, int dim, double a, double b,
                          double *bez, double *power, double *cond);

/* Convenience: value interpolation of npts points pts[npts*dim] at parameters ts[npts]
 * (degree npts − 1) over [a, b]; same outputs and statuses as cj_interp_solve. */
cj_status cj_interp_points(const double *ts, const double *pts, size_t npts, int dim, double a,
                           double b, double *bez, double *power, double *cond);

/* n+1 equispaced parameters a + (b − a) k/n, k = 0..n, into out[n+1] (n >= 1; the ends are
 * exactly a and b). CJ_ERR_ARGUMENT if n < 1 or a >= b; CJ_ERR_NONFINITE for a bad bound. */
cj_status cj_interp_equispaced(int n, double a, double b, double *out);

/* n+1 Chebyshev parameters (roots of T_{n+1}), ascending, mapped to [a, b]:
 *     a + (b − a)(1 − cos((2k+1)π / (2n+2)))/2,   k = 0..n.
 * They cluster near the ends and keep the Lebesgue constant O(log n). Same statuses. */
cj_status cj_interp_chebyshev(int n, double a, double b, double *out);

#ifdef __cplusplus
}
#endif
#endif

/* casteljau: the certified nearest point of a plane Bézier or rational Bézier curve.
 *
 * cj_nearest_curve finds the global minimum of |c(t) - q| over t in [0,1] with a proof, not by a
 * local Newton iteration. Polynomial curves up to degree 12 first go through the roots of
 * g = (c - q) . c': its Bernstein coefficients (with a bound of their rounding) are halved until
 * Descartes' rule isolates every local minimum, each bracketed by proven signs of g, so the
 * minimum is at an end or in one of those brackets (docs/queries.md). Whatever that cannot prove
 * (a double root of g, say) goes to the general method, branch and bound: the parameter interval is
 * split into pieces (exact halving, with the rounding of every control point tracked), and a piece
 * is discarded only when a PROVEN lower bound of its distance to q (the gap between q and the
 * projection of the piece's enclosed control points on the direction from q to the piece, in
 * outward-rounded interval arithmetic) is at least the best distance found so far minus tol. Upper
 * bounds come from enclosed evaluations at piece midpoints polished by Newton steps on g = 0.
 * The result carries both bounds: lower <= min_t |c(t) - q| <= distance, distance - lower <= tol,
 * and distance is an upper bound of |c(t) - q| at the reported t (the rounding of c(t) is
 * enclosed). pieces counts the work: pieces of g isolated, or pieces of the curve examined. Ties
 * (several points at the same distance) are broken by the search order; t is one of them.
 *
 * tol: finite, > 0 and at least 2^-40 times the scale (max |coordinate| of the control points
 * and of q), else CJ_ERR_ARGUMENT naming tol. The curve is validated as in intersect.h
 * (CJ_ERR_DEGREE, CJ_ERR_NONFINITE, CJ_ERR_ARGUMENT for weights, CJ_ERR_DEGENERATE for a curve
 * that is a single point); a NaN or infinite q is CJ_ERR_NONFINITE. No allocation.
 */
#ifndef CASTELJAU_NEAREST_H
#define CASTELJAU_NEAREST_H

#include "casteljau/intersect.h"
#include "casteljau/status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct cj_nearest {
    double t;        /* parameter of the nearest point found */
    double point[2]; /* c(t) (rounded) */
    double distance; /* proven upper bound of |c(t) - q|, so of the minimum distance */
    double lower;    /* proven lower bound of min over [0,1] of |c(s) - q| */
    long pieces;     /* pieces examined (the work done) */
} cj_nearest;

cj_status cj_nearest_curve(const cj_bezier2 *c, const double q[2], double tol, cj_nearest *out);

#ifdef __cplusplus
}
#endif
#endif

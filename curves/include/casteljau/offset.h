/* casteljau: offset curves with a proven deviation, and degree reduction with an error bound.
 *
 * OFFSET. The offset of a plane curve c (cj_bezier2: polynomial or rational) at signed distance
 * d is o(t) = c(t) + d N(t), N the unit left normal (c' turned +90 degrees, normalised):
 * positive d offsets to the left of the direction of travel. cj_offset_curve approximates o by
 * cubic Bézier pieces, each the Hermite cubic of o on a parameter interval [a, b] (end points
 * o(a), o(b), end derivatives (b - a) o'(a), (b - a) o'(b)), and PROVES each piece: with
 * e(u) = q(u) - o(a + (b - a) u), the second-order Taylor bound |e(m)| + |e'(m)| r +
 * |e''(U)| r^2 / 2 (m the midpoint and r the half-width of U; in outward-rounded interval
 * arithmetic over the exact control points, with c, c', c'', c''' enclosed) is <= tol on every
 * sub-interval U of a cover of [0,1]. A parametric distance bounds the
 * Hausdorff distance, so every point of the pieces lies within *deviation <= tol of the true
 * offset and every point of the offset within *deviation of the pieces. Intervals that fail
 * are halved (adaptive, at most 2^20 pieces deep).
 *
 * Cusps and loops. Where 1 - d κ(t) = 0 (κ signed, positive turning left; the offset distance
 * equals the radius of curvature on the concave side) the offset has a cusp: o' vanishes there, but
 * o stays smooth in t, so the Hermite pieces follow it and the proof holds through it; *cusps
 * counts the sign changes of 1 - d κ between consecutive piece ends (each is at least one cusp
 * inside that piece). Past such cusps the offset runs backwards and forms loops (the "swallowtails"
 * of a tight bend): they are returned as part of the raw offset, not trimmed. cj_intersect_curves
 * on pairs of pieces finds their crossings, which is what a trim needs. A curve whose derivative
 * vanishes (a cusp of c itself, where N is undefined) is CJ_ERR_DEGENERATE naming the parameter.
 *
 * Parameters: d finite (CJ_ERR_NONFINITE); tol finite, > 0 and >= 2^-40 (scale + |d|)
 * (CJ_ERR_ARGUMENT naming tol); pts receives 8 doubles (4 points) per piece, cap_pieces the
 * room in pieces; breaks (may be NULL) receives cap_pieces + 1 parameters: piece k approximates
 * o on [breaks[k], breaks[k+1]] (CJ_ERR_BUFFER with *npieces the count needed, when it is too
 * small; a NULL pts with cap_pieces 0 just counts). Consecutive pieces share bit-identical end
 * points. The curve is validated as in intersect.h. Work space on the stack; no allocation.
 */
#ifndef CASTELJAU_OFFSET_H
#define CASTELJAU_OFFSET_H

#include "casteljau/bezier.h"
#include "casteljau/intersect.h"
#include "casteljau/status.h"

#ifdef __cplusplus
extern "C" {
#endif

cj_status cj_offset_curve(const cj_bezier2 *c, double d, double tol, double *pts, double *breaks,
                          int cap_pieces, int *npieces, double *deviation, int *cusps);

/* Degree reduction: the curve r of degree m < n (any dimension) closest to c in the least-squares
 * sense on the control points of r elevated to degree n, with the end points kept (r(0) = c(0),
 * r(1) = c(1), so reduced pieces still join). out receives (m+1)*dim coordinates; m must be in
 * 1..n-1 (CJ_ERR_DEGREE otherwise; m >= n is no reduction). *bound receives a PROVEN bound of
 * max over t of |c(t) - r(t)| (Euclidean): the largest distance between the control points of c
 * and of r elevated to degree n (both curves are then convex combinations of those points with
 * the same weights B_i^n(t)), plus the rounding of the elevation and of that comparison,
 * 4 (n + 2) u times the largest coordinate. Degree up to CJ_QUERY_MAX_DEGREE. */
cj_status cj_bezier_reduce(const cj_bezier *c, int m, double *out, double *bound);

#ifdef __cplusplus
}
#endif
#endif

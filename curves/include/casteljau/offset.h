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
 * on pairs of pieces finds their crossings, which is what a trim needs.
 *
 * Cusps of c itself (c' = 0 inside (0,1), N flips there; polynomial curves): found as the local
 * minima of |c'| where it is below 2^-24 n times the control points' extent, when the plain run
 * cannot prove a piece near one. The pieces then cover [0, t - δ] and [t + δ, 1], with δ such
 * that c stays within tol/4 of c(t) on [t - δ, t + δ], and between them the offset is COMPLETED by
 * the arc of radius |d| about c(t) from o(t - δ) to o(t + δ), turning the way the curve turns
 * there (the sign of its curvature on both sides: the outer offset goes round the tip, the inner
 * one through the inside of the cusp, where a trim removes it). The arc is proven cubic pieces
 * (within tol of the circle); *deviation bounds the distance to that completed offset; breaks
 * give the arc's pieces equal shares of [t - δ, t + δ]. A rational curve whose derivative
 * vanishes, or a cusp at an end (c'(0) = 0), is CJ_ERR_DEGENERATE naming the parameter.
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

/* Trims the raw offset of c at distance d (the np cubic pieces of cj_offset_curve, 8 doubles
 * each, with its proven `deviation`): the pieces are cut at their crossings with each other
 * and their own self-intersections (cj_intersect_curves, cj_intersect_self; the joints of
 * consecutive pieces are not crossings), and each span between consecutive cuts is dropped
 * when the certified distance from its middle point to c (cj_nearest_curve) is below
 * |d| - 2 (deviation + tol): there the raw offset ran past the evolute (the swallowtail between
 * two cusps of a tight bend) or over another part of the curve (an arc offset inwards past its
 * radius disappears whole). The kept spans come back as cubic pieces in out (8 doubles each, cap
 * pieces); newline (may be NULL, cap ints) is 1 where a piece does not continue the previous
 * one: after a removed loop the two sides meet at its crossing and the piece continues,
 * sharing the previous piece's end point bit for bit. *dropped (may be NULL) counts the dropped
 * spans. Every kept point lies within `deviation` of the true offset, which is at distance |d|
 * of c there within deviation + tol.
 * LIMITS. Validity is decided once per span, at its middle: it changes only at crossings of the
 * offset, except near the ends of an open curve, where the offset may pass inside the circle
 * of radius |d| about an end point without crossing itself (no end caps are built).
 * Errors: CJ_ERR_EMPTY (np < 1), CJ_ERR_NONFINITE (a piece's coordinate or d), CJ_ERR_ARGUMENT
 * (deviation < 0; tol not finite, <= 0 or below 2^-36 times the pieces' scale), CJ_ERR_BUFFER
 * (*nout pieces needed), CJ_ERR_NOMEM (the cut list), and those of the intersection and nearest
 * queries (CJ_ERR_CAP). */
cj_status cj_offset_trim(const cj_bezier2 *c, double d, double tol, const double *pieces, int np,
                         double deviation, double *out, int *newline, int cap, int *nout,
                         int *dropped);

/* The OUTLINE of the stroke of c with half-width w > 0 (the boundary of the region swept by a
 * disc of radius w along c, before removing its overlaps): closed loops of cubic pieces.
 * Open curve (c(0) != c(1)): ONE loop: the offset at +w from t = 0 to 1, the end cap at c(1),
 * the offset at -w from t = 1 back to 0, the start cap at c(0). Caps (tangent T at the end,
 * pointing out of the curve):
 *   CJ_OFFSET_CAP_BUTT    the segment between the two offset ends;
 *   CJ_OFFSET_CAP_ROUND   the half circle of radius w about the end point, through end + w T
 *                         (cubic arcs, proven as in the cusp completion above);
 *   CJ_OFFSET_CAP_SQUARE  the three segments out to end + w T and back (the half square).
 * Closed curve (c(0) == c(1) bit for bit): TWO loops, the offsets at +w and -w (the second
 * reversed), each closed at the seam: snapped when the two ends of the offset meet (a smooth
 * closure, the gap added to the deviation), else by a round join about c(0) on the convex side
 * of the corner and through c(0) (two segments, inside the stroke) on the concave side.
 * Cusps of c are completed as in cj_offset_curve. Consecutive pieces of a loop share their end
 * points bit for bit and every loop closes bit for bit; newline (may be NULL, cap ints) is 1 at
 * the first piece of each loop. *deviation: the largest proven bound of the offsets and the
 * arcs; *cusps the total of both offsets. Errors as cj_offset_curve (w <= 0: CJ_ERR_ARGUMENT;
 * cap_pieces too small: CJ_ERR_BUFFER with *npieces the count needed; an unknown cap:
 * CJ_ERR_ARGUMENT). No allocation. */
typedef enum cj_offset_cap {
    CJ_OFFSET_CAP_BUTT = 0,
    CJ_OFFSET_CAP_ROUND = 1,
    CJ_OFFSET_CAP_SQUARE = 2
} cj_offset_cap;

cj_status cj_offset_outline(const cj_bezier2 *c, double w, double tol, cj_offset_cap cap,
                            double *pts, int *newline, int cap_pieces, int *npieces,
                            double *deviation, int *cusps);

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

/* casteljau: certified intersections of plane Bézier and rational Bézier curves.
 *
 * A plane curve is a view cj_bezier2: degree n, n+1 control points (x, y) point-major, and
 * optionally n+1 weights (NULL: a polynomial curve, all weights 1). Rational curves need finite
 * weights > 0, so the curve lies in the hull of its control points. B-spline and NURBS curves
 * are queried through their Bézier pieces (one call per pair of pieces).
 *
 * WHAT IS GUARANTEED. Every intersection comes back with parameter intervals [s_lo, s_hi] on
 * the first curve and [t_lo, t_hi] on the second that are proven to contain it, with a kind:
 *
 *   CJ_ISECT_CROSSING  a simple (transversal) intersection, proven to exist and to be the only
 *                      one in a box around the reported intervals (Krawczyk's interval Newton
 *                      test on F(s,t) = a(s) - b(t), in outward-rounded interval arithmetic,
 *                      over control points whose products w_i x_i are enclosed too). The
 *                      intervals are then shrunk by the same operator, typically to a few ulps.
 *   CJ_ISECT_CONTACT   a region the method cannot resolve at the tolerance: the pieces of both
 *                      curves there are smaller than tol, come within tol of each other, and no
 *                      simple intersection could be certified; or a flat stretch (a triple or
 *                      higher root, a near-coincidence) where both pieces are proven within
 *                      `deviation` <= tol of each other everywhere and a search of 256 boxes
 *                      inside it did not settle it. Tangencies (touching, double roots),
 *                      near-tangencies whose crossings lie closer than the rounding can
 *                      separate, high-order roots and intersections at cusps land here. It may
 *                      hold 0, 1 or more true intersections, but every intersection in it lies
 *                      within the reported intervals, and the curves there are within
 *                      `deviation` <= 2 sqrt(2) tol of each other. Touching leaves are merged,
 *                      so one contact is reported once; a crossing inside a contact is
 *                      reported by the contact only.
 *   CJ_ISECT_OVERLAP   coincident pieces (polynomial curves): a(s) for s in [s_lo, s_hi] and
 *                      b(t) for t in [t_lo, t_hi] are the same curve up to a linear change of
 *                      parameter, with control points of the two pieces (elevated to one
 *                      degree) within `deviation` <= tol of each other, so every point of one
 *                      piece lies within `deviation` of the other.
 *
 * Never missed: the search only discards a region of the parameter square when it has proven
 * that it holds no intersection (separating axes of the control point hulls with rounding
 * margins, or Krawczyk's operator mapping the region off itself), so every intersection lies in
 * one of the reported results. Never duplicated: two crossings are the same root exactly when
 * one's enclosure lies in the other's uniqueness box, and those are merged; contact leaves in a
 * crossing's uniqueness box are dropped; contacts and crossings inside an overlap are absorbed
 * by it.
 *
 * LIMITS. A crossing within its enclosure width (a few ulps of the parameter) of a curve's end
 * is reported with its intervals clipped to [0,1] and `at_end` set: it may in truth lie just
 * outside, by at most that width (a joint of two curves whose end points are bitwise equal is
 * found exactly, at_end set). Overlaps of rational curves, and of polynomial curves related by a
 * non-linear change of parameter (a straight cubic over a line segment with other speeds), are
 * not recognised as overlaps: they come back as contacts, or, when long, as CJ_ERR_CAP once the
 * work cap is hit. Crossings of the shared piece with itself inside an overlap's parameter box
 * (a loop of the common curve) are absorbed by the overlap. The work is capped at
 * CJ_ISECT_MAX_BOXES parameter boxes (CJ_ERR_CAP: the results found are written, `*count` is valid,
 * but the list may be incomplete).
 *
 * TOLERANCE. tol is a distance in the curves' units: the size below which pieces are not split
 * further. It must be finite, > 0, and at least 2^-40 times the largest control point
 * coordinate of the curves (what double precision resolves at their scale, with room for the
 * rounding of subdivision): else CJ_ERR_ARGUMENT naming tol and the scale. Crossings are
 * refined far below tol; tol only limits how close two separate intersections can be and
 * still be told apart.
 *
 * Work space: one allocation of about 250 KiB per call for the tables of roots and contact
 * leaves (CJ_ERR_NOMEM if it fails), and the stack (about 3 KiB per recursion level, at most
 * 104 levels).
 */
#ifndef CASTELJAU_INTERSECT_H
#define CASTELJAU_INTERSECT_H

#include "casteljau/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Largest degree of the curves the queries accept. */
#define CJ_QUERY_MAX_DEGREE 48
/* Cap on the parameter boxes one intersection call examines. */
#define CJ_ISECT_MAX_BOXES 2000000L

typedef struct cj_bezier2 {
    int degree;            /* 0..CJ_QUERY_MAX_DEGREE */
    const double *pts;     /* (degree+1)*2 coordinates: x0 y0 x1 y1 ... */
    const double *weights; /* degree+1 weights > 0, or NULL for a polynomial curve */
} cj_bezier2;

static inline cj_bezier2 cj_bezier2_view(int degree, const double *pts, const double *weights) {
    cj_bezier2 c;
    c.degree = degree;
    c.pts = pts;
    c.weights = weights;
    return c;
}

typedef enum cj_isect_kind {
    CJ_ISECT_CROSSING = 0, /* simple intersection, existence and uniqueness proven */
    CJ_ISECT_CONTACT,      /* tangency or unresolved cluster within tol (see above) */
    CJ_ISECT_OVERLAP       /* coincident pieces over the parameter ranges */
} cj_isect_kind;

typedef struct cj_isect {
    cj_isect_kind kind;
    double s, t;       /* best estimate of the parameters (inside the intervals) */
    double s_lo, s_hi; /* proven enclosure on the first curve */
    double t_lo, t_hi; /* proven enclosure on the second curve (or the line parameter) */
    double point[2];   /* a(s), the estimate of the intersection point */
    double deviation;  /* OVERLAP: max control point distance; CONTACT: distance bound; else 0 */
    int at_end;        /* 1 if the enclosure touches an end of a curve (see LIMITS) */
} cj_isect;

/* Short name of a kind: "crossing", "contact", "overlap". */
const char *cj_isect_kind_name(cj_isect_kind kind);

/* Intersections of curves a and b, sorted by s (then t). out holds cap results; *count
 * receives the number found (when it exceeds cap, the first cap are written and CJ_ERR_BUFFER
 * is returned with *count the total). Errors: CJ_ERR_DEGREE (degree outside
 * 0..CJ_QUERY_MAX_DEGREE), CJ_ERR_NONFINITE (a NaN or infinite coordinate or weight, naming
 * the curve and point), CJ_ERR_ARGUMENT (a weight <= 0; tol out of range), CJ_ERR_DEGENERATE
 * (a curve whose control points all coincide: a point, not a curve), CJ_ERR_CAP (see LIMITS). */
cj_status cj_intersect_curves(const cj_bezier2 *a, const cj_bezier2 *b, double tol, cj_isect *out,
                              int cap, int *count);

/* Intersections of curve a with the straight line through p in direction d (d != 0), with the
 * same guarantees; t is the line parameter λ of p + λ d. The line is enclosed exactly (as
 * intervals) over the span that covers the curve's control points. */
cj_status cj_intersect_line(const cj_bezier2 *a, const double p[2], const double d[2], double tol,
                            cj_isect *out, int cap, int *count);

/* Self-intersections of a: pairs s < t with a(s) = a(t), same kinds and guarantees. Pieces whose
 * derivative directions (for a rational curve, the vectors whose positive combinations give
 * the derivative) lie in an open half-plane are proven free of self-intersections; a piece
 * smaller than tol where that fails (a cusp, a loop smaller than tol) is reported as a CONTACT
 * with s and t intervals both covering it. */
cj_status cj_intersect_self(const cj_bezier2 *a, double tol, cj_isect *out, int cap, int *count);

#ifdef __cplusplus
}
#endif
#endif

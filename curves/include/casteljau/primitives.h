/* casteljau: plane primitives of seed chapter 2 — lines, segments and rays, circles and
 * ellipses (parametric and implicit), regular n-gons and polygons.
 *
 * Forms:
 *   parametric line   p(s) = p + s d   (d ≠ 0); a segment is s in [0,1], a ray s >= 0
 *   implicit line     a x + b y + c = 0   ((a,b) ≠ 0; normal (a,b))
 *   circle            p(θ) = c + r (cos θ, sin θ);        f = |x − c|² − r²
 *   ellipse           p(θ) = c + R(rot) (rx cos θ, ry sin θ);  f = (u/rx)² + (v/ry)² − 1,
 *                     (u, v) = R(−rot)(x − c)
 * The tangent of a parametric form is its derivative; the normal of an implicit form is its
 * gradient. For the built-in shapes the two agree: the derivative is perpendicular to the
 * gradient at the same point (tested), and the left normal of the derivative (turned +90°)
 * points inward for counter-clockwise θ, i.e. against the gradient.
 *
 * All functions are pure and allocate nothing. Degenerate input (zero direction, coincident
 * points, r <= 0, n < 3) returns CJ_ERR_DEGENERATE; non-finite input CJ_ERR_NONFINITE.
 */
#ifndef CASTELJAU_PRIMITIVES_H
#define CASTELJAU_PRIMITIVES_H

#include "casteljau/status.h"
#include "casteljau/vec.h"
#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct cj_line2 { /* parametric: p + s d */
    cj_vec2 p, d;
} cj_line2;

typedef struct cj_iline2 { /* implicit: a x + b y + c = 0 */
    double a, b, c;
} cj_iline2;

typedef struct cj_circle {
    cj_vec2 center;
    double r;
} cj_circle;

typedef struct cj_ellipse {
    cj_vec2 center;
    double rx, ry; /* semi-axes along the rotated x and y axes */
    double rot;    /* rotation in radians, counter-clockwise */
} cj_ellipse;

/* Which part of a parametric line counts in an intersection. */
typedef enum cj_line_extent {
    CJ_EXTENT_LINE = 0, /* all s */
    CJ_EXTENT_RAY,      /* s >= 0 */
    CJ_EXTENT_SEGMENT   /* 0 <= s <= 1 */
} cj_line_extent;

typedef enum cj_intersection {
    CJ_ISECT_NONE = 0,  /* parallel and distinct, or the hit is outside the extent */
    CJ_ISECT_POINT,     /* one point */
    CJ_ISECT_COINCIDENT /* the parametric line lies on the implicit one (every s hits) */
} cj_intersection;

/* ---- lines -------------------------------------------------------------------------- */

/* The parametric line through p and q: p + s (q − p), so s in [0,1] is the segment.
 * CJ_ERR_DEGENERATE if p == q. */
cj_status cj_line2_from_points(cj_vec2 p, cj_vec2 q, cj_line2 *out);
/* Point p + s d (no validation). */
cj_vec2 cj_line2_point(const cj_line2 *l, double s);
/* Implicit form of a parametric line, normalised so that (a, b) is the unit left normal of d
 * (then a x + b y + c is the signed distance, positive on the left). */
cj_status cj_line2_to_implicit(const cj_line2 *l, cj_iline2 *out);
/* Parametric form of an implicit line: p = the point closest to the origin, d = (b, −a)
 * (so that the left normal of d is (a, b)/|(a, b)|, consistent with cj_line2_to_implicit). */
cj_status cj_iline2_to_param(const cj_iline2 *m, cj_line2 *out);
/* Signed value a x + b y + c divided by |(a, b)|: the signed distance of q from the line. */
cj_status cj_iline2_distance(const cj_iline2 *m, cj_vec2 q, double *dist);

/* Intersects the parametric line l (restricted to `extent`) with the implicit line m:
 * substituting gives (a d_x + b d_y) s = −(a p_x + b p_y + c). The lines are parallel when
 * |a d_x + b d_y| <= 8u·|(a,b)|·|d| (u = 2^-53); then they are coincident when the distance
 * of p from m is <= 8u·(|a p_x| + |b p_y| + |c|)/|(a,b)|, else there is no intersection.
 * *kind gets the case; for CJ_ISECT_POINT, *s (may be NULL) the parameter and *point (may be
 * NULL) the point. A hit outside the extent is CJ_ISECT_NONE with *s still written. */
cj_status cj_line2_intersect_implicit(const cj_line2 *l, cj_line_extent extent, const cj_iline2 *m,
                                      cj_intersection *kind, double *s, cj_vec2 *point);

/* Perpendicular bisector of the segment pq: the parametric line through the midpoint with
 * direction perp(q − p) (q − p turned +90°); if implicit is not NULL it also gets the implicit
 * form (q − p)·x − (|q|² − |p|²)/2 = 0. CJ_ERR_DEGENERATE if p == q. */
cj_status cj_perpendicular_bisector(cj_vec2 p, cj_vec2 q, cj_line2 *out, cj_iline2 *implicit);

/* ---- circles and ellipses ------------------------------------------------------------ */

/* Validates (finite, r > 0 / rx, ry > 0). */
cj_status cj_circle_check(const cj_circle *c);
cj_status cj_ellipse_check(const cj_ellipse *e);

/* Parametric point and derivative dp/dθ at θ (either output may be NULL). */
cj_status cj_circle_eval(const cj_circle *c, double theta, cj_vec2 *point, cj_vec2 *deriv);
cj_status cj_ellipse_eval(const cj_ellipse *e, double theta, cj_vec2 *point, cj_vec2 *deriv);
/* Implicit value f(q) and gradient ∇f(q) (either output may be NULL). */
cj_status cj_circle_implicit(const cj_circle *c, cj_vec2 q, double *f, cj_vec2 *grad);
cj_status cj_ellipse_implicit(const cj_ellipse *e, cj_vec2 q, double *f, cj_vec2 *grad);
/* Unit tangent (from the derivative) and unit outward normal (from the gradient) at θ. */
cj_status cj_ellipse_frame(const cj_ellipse *e, double theta, cj_vec2 *tangent, cj_vec2 *normal);

/* ---- polygons ------------------------------------------------------------------------ */

/* Regular n-gon (n >= 3) inscribed in the circle (center, radius): vertex k at angle
 * phase + 2πk/n, counter-clockwise, into out[n]. */
cj_status cj_regular_ngon(cj_vec2 center, double radius, int n, double phase, cj_vec2 *out);

/* Signed area by the shoelace formula (positive for counter-clockwise), n >= 3. */
cj_status cj_polygon_area(const cj_vec2 *v, size_t n, double *area);

/* Simple: no two non-adjacent edges touch and adjacent edges meet only at their shared vertex
 * (a zero-length edge or a fold back along the previous edge makes a polygon non-simple).
 * O(n²) exact-sign segment tests (orientation by a floating-point filter with an exact
 * fallback). *simple gets 1 or 0. CJ_ERR_EMPTY for n < 3. */
cj_status cj_polygon_is_simple(const cj_vec2 *v, size_t n, int *simple);

/* Convex: simple, and every vertex turns the same way (collinear vertices allowed, but not a
 * polygon whose vertices are all collinear). *convex gets 1 or 0; *orientation (may be NULL)
 * +1 for counter-clockwise, −1 clockwise, 0 if not convex. */
cj_status cj_polygon_is_convex(const cj_vec2 *v, size_t n, int *convex, int *orientation);

/* Point in polygon by the crossing rule (even–odd); points on the boundary count as inside.
 * *inside gets 1 or 0. */
cj_status cj_polygon_contains(const cj_vec2 *v, size_t n, cj_vec2 q, int *inside);

#ifdef __cplusplus
}
#endif
#endif

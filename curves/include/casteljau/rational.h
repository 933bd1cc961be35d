/* casteljau: rational Bézier curves (control points with weights), exact conic arcs.
 *
 * A rational curve of degree n in dimension d has control points b_0..b_n (point-major, exactly
 * as cj_bezier: pts[i*d + k]) and weights w_0..w_n:
 *
 *     c(t) = Σ w_i b_i B_i^n(t) / Σ w_i B_i^n(t),   t in [0,1].
 *
 * It is the central projection of the polynomial curve with homogeneous control points
 * (w_i b_i, w_i) in dimension d+1. Weights must be finite and strictly positive (then the
 * denominator is positive on [0,1] and the curve lies in the convex hull of its control points);
 * a zero or negative weight is CJ_ERR_ARGUMENT naming the weight. Equal weights give the
 * polynomial curve with the same control points.
 *
 * Conic arcs are exact: a circular arc of opening angle φ < π is the quadratic with end points
 * on the circle, middle point at the intersection of the end tangents, and weights
 * 1, cos(φ/2), 1; an ellipse arc is the affine image of a circle arc (same weights).
 *
 * cj_rbezier is a non-owning view; the caller owns pts, weights and every output buffer. No
 * function here allocates; work space is bounded by CJ_BEZIER_MAX_DEGREE and CJ_MAX_DIM - 1
 * (the homogeneous coordinate takes one slot, so dim <= CJ_MAX_DIM - 1 = 7).
 */
#ifndef CASTELJAU_RATIONAL_H
#define CASTELJAU_RATIONAL_H

#include "casteljau/bezier.h"
#include "casteljau/status.h"
#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct cj_rbezier {
    int degree;            /* n >= 0; n+1 control points and weights */
    int dim;               /* 1..CJ_MAX_DIM-1 */
    const double *pts;     /* (degree+1)*dim coordinates, point-major */
    const double *weights; /* degree+1 weights, finite and > 0 */
} cj_rbezier;

/* Largest dimension of a rational curve (one coordinate is used for the weight). */
#define CJ_RBEZIER_MAX_DIM (CJ_MAX_DIM - 1)

static inline cj_rbezier cj_rbezier_view(int degree, int dim, const double *pts,
                                         const double *weights) {
    cj_rbezier c;
    c.degree = degree;
    c.dim = dim;
    c.pts = pts;
    c.weights = weights;
    return c;
}

/* Validates: degree in [0, CJ_BEZIER_MAX_DEGREE] (CJ_ERR_EMPTY if negative, CJ_ERR_DEGREE if
 * too high), dim in [1, CJ_RBEZIER_MAX_DIM] (CJ_ERR_DIMENSION), finite coordinates and weights
 * (CJ_ERR_NONFINITE), weights > 0 (CJ_ERR_ARGUMENT). */
cj_status cj_rbezier_check(const cj_rbezier *c);

/* c(t) into out[dim], by de Casteljau on the homogeneous points. Any finite t is accepted,
 * but outside [0,1] the denominator may vanish: CJ_ERR_DEGENERATE then. */
cj_status cj_rbezier_eval(const cj_rbezier *c, double t, double *out);

/* Point and derivatives 0..kmax at t: out[j*dim + k] = coordinate k of c^(j)(t). Computed from
 * the homogeneous derivatives A^(j) (numerator) and w^(j) (denominator) by the quotient rule
 *     c^(j) = ( A^(j) − Σ_{i=1..j} C(j,i) w^(i) c^(j−i) ) / w.
 * kmax must be in [0, 64] (CJ_ERR_ARGUMENT otherwise). */
cj_status cj_rbezier_eval_derivs(const cj_rbezier *c, double t, int kmax, double *out);

/* Splits at t in [0,1] (CJ_ERR_RANGE otherwise) into two rational curves of the same degree:
 * left = c on [0,t], right = c on [t,1], each reparametrised to [0,1]. Each output pair
 * (points (n+1)*dim, weights n+1) may be NULL together. The shared end point is bit-identical
 * in both halves. Weights of the halves are not renormalised. */
cj_status cj_rbezier_split(const cj_rbezier *c, double t, double *left_pts, double *left_w,
                           double *right_pts, double *right_w);

/* Homogeneous form: out[i*(dim+1) + k] = w_i b_i,k for k < dim and out[i*(dim+1) + dim] = w_i,
 * a polynomial cj_bezier of dimension dim+1 ((n+1)*(dim+1) doubles). */
cj_status cj_rbezier_homogeneous(const cj_rbezier *c, double *out);

/* Reparametrises to standard form w_0 = w_n = 1 (same curve, same parameter direction, by the
 * Möbius reparametrisation that preserves [0,1]); weights_out receives n+1 weights. For n = 0
 * the weight becomes 1. Control points are unchanged. */
cj_status cj_rbezier_normalize_weights(const cj_rbezier *c, double *weights_out);

/* ---- exact conic arcs ------------------------------------------------------------------- */

/* Number of quadratic pieces cj_rbezier_ellipse_arcs uses for the arc from angle a0 to a1:
 * ceil(|a1 − a0| / (π/2)), at least 1. Returns 0 if the angles are not finite or the sweep
 * exceeds 2π by more than rounding. */
int cj_rbezier_arc_pieces(double a0, double a1);

/* One quadratic rational Bézier for the ellipse arc
 *     p(θ) = c + R(rot) (rx cos θ, ry sin θ),   θ from a0 to a1 (a1 < a0 runs clockwise),
 * where R(rot) rotates by rot radians; |a1 − a0| must be < π (CJ_ERR_RANGE otherwise); a zero
 * sweep is CJ_ERR_DEGENERATE. rx, ry > 0 (CJ_ERR_DEGENERATE otherwise).
 * pts receives 3 points (6 doubles), weights 3 weights: 1, cos((a1−a0)/2), 1. The rational
 * curve passes through p(a0), p((a0+a1)/2) (at t = 1/2) and p(a1), and every point of it lies
 * exactly on the ellipse (up to rounding). A circle is rx = ry = r. */
cj_status cj_rbezier_ellipse_arc(double cx, double cy, double rx, double ry, double rot, double a0,
                                 double a1, double pts[6], double weights[3]);

/* The ellipse arc from a0 to a1 (|a1 − a0| <= 2π; 2π is the full ellipse) as
 * cj_rbezier_arc_pieces(a0, a1) quadratic pieces of equal sweep, each as in
 * cj_rbezier_ellipse_arc: pts receives 6 doubles and weights 3 doubles per piece. cap_pieces is
 * the capacity of the buffers in pieces (CJ_ERR_BUFFER if too small); *npieces receives the
 * count. Consecutive pieces share bit-identical end points; for a full ellipse the last end
 * point is bit-identical to the first. */
cj_status cj_rbezier_ellipse_arcs(double cx, double cy, double rx, double ry, double rot, double a0,
                                  double a1, double *pts, double *weights, int cap_pieces,
                                  int *npieces);

#ifdef __cplusplus
}
#endif
#endif

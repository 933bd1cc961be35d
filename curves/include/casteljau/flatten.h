/* casteljau: flattening Bézier curves (polynomial and rational, any degree) to polylines.
 *
 * A flattening of c: [0,1] -> R^d at tolerance tol is a polyline p_0..p_m (m segments) with
 * p_0 = c(0), p_m = c(1), every vertex a point of the curve, and
 *
 *     Hausdorff distance(curve, polyline) <= tol,
 *
 * guaranteed by a PROVEN bound computed for every segment (not by sampling). The bound each
 * call reaches is reported in cj_flatten_stats.bound (always <= tol on success).
 *
 * Bounds used (b_i control points of the piece, S the chord segment b_0 b_n, n the degree):
 *  - Wang (uniform method, polynomial): with M = max_i |b_i - 2 b_{i+1} + b_{i+2}|, m equal
 *    parameter steps give |c(t) - chord(t)| <= n(n-1) M / (8 m^2), so
 *        m = ceil( sqrt( n(n-1) M / (8 tol) ) ).
 *    Rational: the same on the homogeneous curve (w_i (b_i - o), w_i), o the centre of the
 *    control points' bounding box, R = max |b_i - o|, w_min = min w_i:
 *        |c - chord| <= n(n-1) (M_wb + R M_w) / (8 m^2 w_min).
 *  - Piece flatness (subdivision and near-optimal methods, also used to verify): the
 *    component e(t) of c(t) - b_0 perpendicular to S (or the distance to S when some control
 *    point projects outside S) is bounded two ways and the smaller is taken:
 *      (a) convexity: dist(c(t), S) <= g * max_i dist(b_i, S), where g = sup_t of the weight
 *          share of the inner control points (1 - 2^(1-n) for polynomials; for rational
 *          curves wI (1-s) / (wE s + wI (1-s)), s = 2^(1-n), wI the largest inner weight,
 *          wE the smaller end weight);
 *      (b) factoring: e(t) = t(1-t) q(t) / W(t), q of degree n-2 with Bernstein coefficients
 *          q_j = w_{j+1} e_{j+1} n(n-1) / ((j+1)(n-1-j)), so |e| <= max_j |q_j| / (4 min w),
 *          which is exact for parabolas, symmetric cubic arcs and (in standard form, up to
 *          the min-weight factor) circular arcs;
 *      (c) polynomials only: (b) applied to the full parametric error c(t) - chord(t), which
 *          needs no projection condition, and n(n-1)/8 max|Δ² b_i|.
 *    Rational pieces are first put in standard form w_0 = w_n (Möbius reparametrisation,
 *    same curve) so that wE, wI and min w are as favourable as possible.
 *      (d) refinement, for degrees 2-16, used by the flatteners when (a)-(c) do not certify
 *          a piece or lie near the target and exceed the distance of c(1/2) from S by more
 *          than 2% (else it cannot gain more), always by cj_flatten_piece_bound: the piece is
 *          halved twice (de Casteljau) into 4 parts; each part lies in the convex hull of its
 *          control points and dist(., S) is convex, so on part j
 *              dist(c(t), S) <= dE_j + (1 - σ_j) max(0, dI_j - dE_j),
 *          dE_j the larger distance from S of the part's end points (points of the curve),
 *          dI_j the largest of its inner control points, σ_j the smallest weight share of the
 *          end points (as g above, with the part's own weights). It converges to the true
 *          deviation as the parts shrink and is exact when the farthest point is a part's end
 *          point with the curve parallel to S there (e.g. symmetric loops and cusps); it
 *          removes most of the slack of (a)-(c) near cusps and tight loops.
 *    Each bound is a bound on sup_t dist(c(t), S). Since the curve is continuous from one end
 *    of S to the other, its orthogonal projection onto the line of S covers all of S, and a
 *    curve point projecting into S lies at its distance to S from that projection: every
 *    point of S is also that close to the curve, so the bound holds in both directions (curve
 *    to polyline and polyline to curve). A small rounding allowance (a multiple of
 *    n u max|coordinate|) is added to every reported bound.
 *
 * Methods (the point is to show the trade):
 *  - CJ_FLATTEN_UNIFORM: m equal parameter steps from Wang's formula; one pass, no search,
 *    over-refines where the curve is straight.
 *  - CJ_FLATTEN_SUBDIVIDE: recursive (dyadic) de Casteljau subdivision until each piece's
 *    flatness bound is <= tol. Piece counts are powers-of-two-ish.
 *  - CJ_FLATTEN_NEAR_OPTIMAL: each segment is grown greedily from the previous end point until
 *    its proven flatness bound lies in [0.95 tol, tol] (log-log secant on the bound inside a
 *    bracket; first guess: the previous step, corrected for its unused error and extrapolated
 *    by the trend of the last two steps; ~1.2-2.5 bound evaluations per segment), so every
 *    produced segment is verified by construction and carries nearly the whole allowed error.
 *    Since a short arc deviates from its chord by κ l^2 / 8, equalising the error per segment
 *    is the spacing by the curvature integral ∫ sqrt(|κ|/(8 tol)) ds (Levien's criterion);
 *    measured counts are 1.01-1.08x that continuous optimum (near-cusp cubic included;
 *    bench_flatten), its ceiling on a circular arc.
 *    Planar polynomial quadratics and cubics (the curves of fonts, paths and maps) take a fast
 *    form with the same guarantee: all break points are placed up front at equal steps of a
 *    closed-form estimate of ∫ sqrt(|κ|) ds (each cubic modelled by a few parabolas, whose
 *    integral has a closed form), aiming at 0.9 tol per segment; each segment is then
 *    certified: its control points follow from the point and derivative at its two ends, and
 *    its deviation is bounded by the maximum of the signed distance from the chord,
 *    t(1-t)(A(1-t) + B t)/|v| (max(|A|,|B|)/(4|v|) first, compared in squares; the exact
 *    maximum in closed form where that does not certify), whenever every control point projects
 *    into the chord segment; otherwise that maximum with the overshoot past the chord's ends,
 *    sqrt(E^2 + O^2), and where that does not certify the piece, (a)-(d). The few segments the
 *    bound rejects are shortened until certified. Counts are 1.05-1.09x the continuous optimum
 *    on random cubics (bench_flatten, peer table, beside kurbo and cairo).
 *
 * Degenerate curves (all control points equal, collinear points out of order, cusps, loops,
 * inflections) are handled: an all-equal curve flattens to one segment (two equal points).
 *
 * No function here allocates. Work space is on the stack, bounded by CJ_BEZIER_MAX_DEGREE
 * and CJ_MAX_DIM (rational: CJ_RBEZIER_MAX_DIM). Results go either into a caller buffer
 * (count-then-fill) or through a callback.
 *
 * Statuses common to all functions:
 *   CJ_ERR_NONFINITE  tol is NaN/Inf, or a coordinate/weight is NaN/Inf
 *   CJ_ERR_RANGE      tol <= 0, or tol is below what double rounding of these coordinates can
 *                     guarantee (4x the rounding allowance, ~1e-13 of the largest coordinate
 *                     for cubics), or a bound exceeds the double range (deviations ~1e308;
 *                     coordinates are scaled by powers of two internally, so 1e-300..1e307
 *                     work)
 *   CJ_ERR_EMPTY      degree < 0 (no control points); a sequence with no pieces
 *   CJ_ERR_DEGREE     degree > CJ_BEZIER_MAX_DEGREE (degree 0, one point, is accepted as a
 *                     single zero-length segment)
 *   CJ_ERR_DIMENSION  dim outside [1, CJ_MAX_DIM] (rational: [1, CJ_RBEZIER_MAX_DIM]), or
 *                     pieces of a sequence with different dims
 *   CJ_ERR_ARGUMENT   a weight <= 0, an unknown method
 *   CJ_ERR_CAP        more than opts->max_segments segments would be needed (the default cap
 *                     is CJ_FLATTEN_DEFAULT_CAP). *npoints is not meaningful then; the
 *                     callback variants may already have emitted a prefix (documented there).
 *   CJ_ERR_BUFFER     the caller buffer is too small (*npoints receives the count needed)
 */
#ifndef CASTELJAU_FLATTEN_H
#define CASTELJAU_FLATTEN_H

#include "casteljau/bezier.h"
#include "casteljau/rational.h"
#include "casteljau/status.h"
#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Default cap on the number of segments of one call (all pieces of a sequence together). */
#define CJ_FLATTEN_DEFAULT_CAP ((size_t)1 << 22)

typedef enum cj_flatten_method {
    CJ_FLATTEN_UNIFORM = 0,  /* Wang's formula, equal parameter steps */
    CJ_FLATTEN_SUBDIVIDE,    /* recursive de Casteljau halving with a proven flatness test */
    CJ_FLATTEN_NEAR_OPTIMAL, /* curvature-spaced, each segment verified by the proven bound */
    CJ_FLATTEN_METHOD_COUNT_
} cj_flatten_method;

typedef struct cj_flatten_opts {
    cj_flatten_method method;
    double tol;          /* > 0, finite: max distance curve <-> polyline */
    size_t max_segments; /* cap on segments; 0 = CJ_FLATTEN_DEFAULT_CAP */
} cj_flatten_opts;

/* Options with the given method and tolerance and the default cap. */
static inline cj_flatten_opts cj_flatten_defaults(cj_flatten_method method, double tol) {
    cj_flatten_opts o;
    o.method = method;
    o.tol = tol;
    o.max_segments = 0;
    return o;
}

typedef struct cj_flatten_stats {
    size_t segments; /* number of segments produced (points - 1 for one curve) */
    double bound;    /* proven upper bound on the Hausdorff distance curve <-> polyline */
} cj_flatten_stats;

/* Receives each polyline vertex in order: pt[dim] coordinates (valid only during the call),
 * the index of the piece it belongs to (0 for single curves) and its parameter t in [0,1] on
 * that piece. The first vertex of a curve is emitted with t = 0, the last with t = 1. */
typedef void (*cj_flatten_sink)(void *user, const double *pt, int dim, size_t piece, double t);

/* One piece of a sequence: a polynomial Bézier curve (weights == NULL) or a rational one
 * (weights: degree+1 positive weights for the control points of `curve`). */
typedef struct cj_flatten_piece {
    cj_bezier curve;
    const double *weights;
} cj_flatten_piece;

/* ---- polynomial curves ------------------------------------------------------------------ */

/* Count-then-fill. out: room for cap_points points of c->dim doubles each (point-major), or
 * NULL to only count. *npoints receives the number of points (segments + 1) whether or not
 * they fit; if out != NULL and they do not fit: CJ_ERR_BUFFER (the buffer's contents are then
 * unspecified). stats may be NULL. The same input always gives the same points, so counting
 * with out == NULL and then filling a buffer of *npoints points works. */
cj_status cj_flatten_bezier(const cj_bezier *c, const cj_flatten_opts *opts, double *out,
                            size_t cap_points, size_t *npoints, cj_flatten_stats *stats);

/* Callback form: emits the vertices through sink as they are found (no buffer at all). On
 * CJ_ERR_CAP the uniform method has emitted nothing (its count is known first); the other
 * methods may have emitted a prefix of the polyline, which the caller must discard. */
cj_status cj_flatten_bezier_cb(const cj_bezier *c, const cj_flatten_opts *opts,
                               cj_flatten_sink sink, void *user, cj_flatten_stats *stats);

/* ---- rational curves -------------------------------------------------------------------- */

/* As cj_flatten_bezier for a rational curve (see rational.h); weights must be > 0. */
cj_status cj_flatten_rbezier(const cj_rbezier *c, const cj_flatten_opts *opts, double *out,
                             size_t cap_points, size_t *npoints, cj_flatten_stats *stats);

cj_status cj_flatten_rbezier_cb(const cj_rbezier *c, const cj_flatten_opts *opts,
                                cj_flatten_sink sink, void *user, cj_flatten_stats *stats);

/* ---- sequences (splines, interpolants, conic arcs) -------------------------------------- */

/* Flattens pieces[0..count-1] (all of one dim) into ONE polyline. Where piece i+1 starts
 * exactly (bit for bit) at the end of piece i, that shared point appears once; otherwise both
 * are kept and the polyline jumps between them with a straight segment (which is counted and
 * is not part of any curve). The tolerance applies to every piece; stats->bound is the
 * largest per-piece bound and stats->segments the total. Count-then-fill as above. */
cj_status cj_flatten_sequence(const cj_flatten_piece *pieces, size_t count,
                              const cj_flatten_opts *opts, double *out, size_t cap_points,
                              size_t *npoints, cj_flatten_stats *stats);

cj_status cj_flatten_sequence_cb(const cj_flatten_piece *pieces, size_t count,
                                 const cj_flatten_opts *opts, cj_flatten_sink sink, void *user,
                                 cj_flatten_stats *stats);

/* ---- bounds (exposed for tests and callers that split curves themselves) ---------------- */

/* The proven flatness bound described above for one piece: an upper bound on the Hausdorff
 * distance between the curve and its chord b_0 b_n. weights may be NULL (polynomial).
 * Validates like the flatteners. */
cj_status cj_flatten_piece_bound(const cj_bezier *c, const double *weights, double *bound);

/* Wang's segment count for tolerance tol (uniform method), without flattening. */
cj_status cj_flatten_wang_count(const cj_bezier *c, const double *weights, double tol,
                                size_t *segments);

#ifdef __cplusplus
}
#endif
#endif

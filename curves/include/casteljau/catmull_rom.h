/* casteljau: interpolating cubic splines through points — Catmull-Rom (uniform, centripetal,
 * chordal), Kochanek–Bartels, and cubic Hermite segments — all returned as cubic Béziers.
 *
 * A spline through points p_0..p_{N-1} (dimension d, point-major: pts[j*d + k]) with tangents
 * τ_j is returned as an array of cubic Bézier segments. Segment j runs from p_j to p_{j+1} and
 * has the four control points (seed, chapter 14)
 *
 *     p_j,   p_j + Δ_j τ_j⁺/3,   p_{j+1} − Δ_j τ_{j+1}⁻/3,   p_{j+1}
 *
 * where Δ_j is the knot spacing of the segment (1 for uniform splines) and τ⁺/τ⁻ are the
 * outgoing/incoming tangents at a point (equal except for Kochanek–Bartels with continuity ≠ 0).
 * Segments are stored back to back, 4*d doubles each: coordinate k of control point i of
 * segment s is segs[(s*4 + i)*d + k], so cj_bezier_view(3, d, segs + s*4*d) views segment s.
 *
 * Tangents of the seed's Catmull-Rom spline with tension κ (seed eq. 126; κ = 0.5 is the
 * classic spline):
 *     interior   τ_j = κ (p_{j+1} − p_{j−1})
 *     ends       τ_0 = κ (p_1 − p_0),   τ_{N−1} = κ (p_{N−1} − p_{N−2})
 * Centripetal (α = 1/2) and chordal (α = 1) splines use knots t_{j+1} = t_j + |p_{j+1} − p_j|^α,
 * Δ_j = t_{j+1} − t_j, and 2κ times the Barry–Goldman tangent (the derivative of the non-uniform
 * Catmull-Rom pyramid at t_j):
 *     τ_j = 2κ [ (p_j − p_{j−1})/Δ_{j−1} − (p_{j+1} − p_{j−1})/(Δ_{j−1} + Δ_j) + (p_{j+1} −
 * p_j)/Δ_j ] with ends τ_0 = κ (p_1 − p_0)/Δ_0 and τ_{N−1} = κ (p_{N−1} − p_{N−2})/Δ_{N−2}. At α =
 * 0 these reduce exactly to the uniform formulas, and κ = 0.5 gives the textbook
 * centripetal/chordal curves (no cusps or self-intersections within a segment for α = 1/2).
 * Kochanek–Bartels (uniform knots) with tension T, continuity C and bias B:
 *     τ_j⁺ = (1−T)(1+B)(1+C)/2 (p_j − p_{j−1}) + (1−T)(1−B)(1−C)/2 (p_{j+1} − p_j)   (outgoing)
 *     τ_j⁻ = (1−T)(1+B)(1−C)/2 (p_j − p_{j−1}) + (1−T)(1−B)(1+C)/2 (p_{j+1} − p_j)   (incoming)
 * with ends as the seed's formula for κ = (1−T)/2. T = C = B = 0 is the uniform spline, κ = 0.5.
 *
 * Closed (periodic) splines treat the points cyclically (p_{−1} = p_{N−1}, p_N = p_0) and have
 * N segments, the last one from p_{N−1} back to p_0; open splines have N−1 segments.
 *
 * Continuity: every spline except Kochanek–Bartels with C ≠ 0 is C¹ in its own knot parameter
 * (uniform: the segment parameter; non-uniform: the derivative of segment j at its end divided
 * by Δ_j equals that of segment j+1 at its start divided by Δ_{j+1}).
 *
 * Degenerate input: fewer than 2 points (3 for a closed spline) is CJ_ERR_EMPTY. Repeated
 * consecutive points give a defined curve for the uniform kinds (the tangent formulas need no
 * division) but CJ_ERR_DEGENERATE for centripetal and chordal, whose knot spacing would be zero;
 * the message names the two points. Non-finite coordinates or options are CJ_ERR_NONFINITE.
 * Results that overflow the double range (points whose distance, or tangents scaled by a huge
 * tension, continuity or bias, exceed it) are CJ_ERR_RANGE naming the segment; segments before
 * it may have been written.
 * No function here allocates.
 */
#ifndef CASTELJAU_CATMULL_ROM_H
#define CASTELJAU_CATMULL_ROM_H

#include "casteljau/status.h"
#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef enum cj_spline_kind {
    CJ_SPLINE_CATMULL_ROM = 0, /* uniform knots, tension κ (seed) */
    CJ_SPLINE_CENTRIPETAL,     /* knots spaced by |Δp|^0.5 */
    CJ_SPLINE_CHORDAL,         /* knots spaced by |Δp| */
    CJ_SPLINE_KOCHANEK_BARTELS /* uniform knots, tension/continuity/bias */
} cj_spline_kind;

typedef struct cj_spline_options {
    cj_spline_kind kind;
    double tension;    /* κ for the Catmull-Rom kinds (any finite value; 0.5 classic);
                          T for Kochanek–Bartels (0 = Catmull-Rom) */
    double continuity; /* C, Kochanek–Bartels only */
    double bias;       /* B, Kochanek–Bartels only */
    int closed;        /* nonzero: periodic spline through the points taken cyclically */
} cj_spline_options;

/* The defaults: uniform Catmull-Rom, κ = 0.5, open, C = B = 0. */
cj_spline_options cj_spline_defaults(void);

/* Number of cubic segments a spline through npts points has: npts-1 open, npts closed
 * (0 when npts is too small to make a spline). */
size_t cj_spline_segment_count(size_t npts, int closed);

/* Builds the spline through pts[npts*dim] (dim 1..CJ_MAX_DIM). opts may be NULL for the
 * defaults. segs receives cj_spline_segment_count(npts, closed) segments of 4*dim doubles; it
 * must hold cap_segs segments, else CJ_ERR_BUFFER (nothing written). *nsegs (may be NULL)
 * receives the segment count. If knots is not NULL it receives the npts (+1 when closed)
 * knot values t_j used (t_0 = 0), so that callers can map global to segment parameters. */
cj_status cj_catmull_rom(const double *pts, size_t npts, int dim, const cj_spline_options *opts,
                         double *segs, size_t cap_segs, size_t *nsegs, double *knots);

/* The tangents alone (formulas above). out_tan and in_tan (either may be NULL) receive npts*dim
 * doubles: the outgoing tangent τ_j⁺ and the incoming tangent τ_j⁻ at each point, as derivatives
 * with respect to the knot parameter (multiply by Δ_j for the segment parameter). For an open
 * spline the incoming tangent at p_0 and the outgoing one at p_{N−1} equal the end tangents. */
cj_status cj_catmull_rom_tangents(const double *pts, size_t npts, int dim,
                                  const cj_spline_options *opts, double *out_tan, double *in_tan);

/* One cubic Hermite segment: the cubic with c(0) = p0, c'(0) = v0, c(1) = p1, c'(1) = v1
 * (derivatives with respect to the segment parameter in [0,1]) as 4*dim Bézier control points
 * p0, p0 + v0/3, p1 − v1/3, p1. Non-finite input is CJ_ERR_NONFINITE. */
cj_status cj_hermite_segment(const double *p0, const double *v0, const double *p1, const double *v1,
                             int dim, double *out);

/* A cubic Hermite spline through pts[npts*dim] with tangents tans[npts*dim] (derivatives with
 * respect to the global parameter) at increasing knots[npts] (NULL: knots 0,1,2,...).
 * Segment j gets p_j, p_j + Δ_j τ_j/3, p_{j+1} − Δ_j τ_{j+1}/3, p_{j+1}; npts-1 segments into
 * segs (cap_segs segments available, else CJ_ERR_BUFFER). Knots that do not strictly increase
 * are CJ_ERR_ARGUMENT naming the pair; fewer than 2 points is CJ_ERR_EMPTY. */
cj_status cj_hermite_spline(const double *pts, const double *tans, const double *knots, size_t npts,
                            int dim, double *segs, size_t cap_segs, size_t *nsegs);

#ifdef __cplusplus
}
#endif
#endif

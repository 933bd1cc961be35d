/* casteljau: implicit plane curves f(x,y) = 0 — built-ins, gradients and normals, and
 * contouring to polylines at a tolerance.
 *
 * An implicit curve is a function f with an optional gradient. Built-ins (line, circle,
 * ellipse, bivariate polynomial) keep their data in a caller-owned cj_implicit_shape; the
 * cj_implicit returned by their constructors points into it, so the shape must outlive it.
 * A user function may leave grad NULL: the gradient is then taken by central differences with
 * step h = 2^-17·max(1, |x|) (resp. |y|), relative error about 1e-10 for smooth f.
 *
 * Contouring (cj_implicit_contour):
 *   1. Grid pass: f is sampled on the (nx+1)×(ny+1) corners of a regular grid over the box
 *      [x0,x1]×[y0,y1]; a corner is "inside" when f < 0 (f == 0 counts as outside). Each cell
 *      edge with a sign change holds one crossing. Marching squares links the crossings of
 *      each cell; an ambiguous (saddle) cell — diagonal corners inside, the others outside —
 *      is resolved by the sign of f at the cell centre: the inside corners are joined when the
 *      centre is inside, separated otherwise. The same rule is applied to every cell, and
 *      crossings live on edges shared by both neighbouring cells, so the linking is consistent.
 *   2. Refinement: every crossing is moved along its edge by safeguarded regula falsi
 *      (Illinois) until |f|/|∇f| <= tol/4 or the bracket is narrower than tol/8.
 *   3. Chords: between consecutive crossings, the chord midpoint is projected onto the curve by
 *      Newton steps along ∇f; if it moved more than tol/2, the projected point is inserted and
 *      both halves are checked again (depth cap 24 per grid chord). With vertices within tol/4
 *      and chord sagitta below tol/2 (to first order), the polyline stays within tol of the
 *      curve.
 *   4. Linking: crossings are chained into polylines. A chain that returns to its start is a
 *      closed loop and is emitted with closed = 1 and its last point bit-identical to its first;
 *      a chain ending on the box boundary is open.
 * Each polyline is emitted with the largest |f|/|∇f| over its vertices (a first-order estimate
 * of the distance from each vertex to the curve). Features smaller than a grid cell (a loop
 * entirely inside one cell, two crossings on one edge) can be missed: choose nx, ny to resolve
 * them. Singular points (∇f = 0 on the curve) are reported through a large residual.
 *
 * Bounded work: the tolerance must be one that doubles can resolve at the box's scale,
 * tol >= CJ_CONTOUR_MIN_REL_TOL · max(|x0|, |y0|, |x1|, |y1|, x1 − x0, y1 − y0) (a finer one is
 * CJ_ERR_RANGE before any work), and one call emits at most CJ_CONTOUR_MAX_POINTS vertices in
 * all (more is CJ_ERR_CAP: contouring stops, what was emitted stays emitted).
 *
 * Contouring allocates its work space (O(nx·ny) doubles, plus the longest polyline) with
 * malloc and frees it before it returns; all other functions here allocate nothing.
 */
#ifndef CASTELJAU_IMPLICIT_H
#define CASTELJAU_IMPLICIT_H

#include "casteljau/alloc.h"
#include "casteljau/status.h"
#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* f(x, y); must be deterministic. A non-finite value makes the operation fail with
 * CJ_ERR_NONFINITE naming the point. */
typedef double (*cj_implicit_curve_fn)(const void *user, double x, double y);
/* ∇f(x, y) into g[0] = ∂f/∂x, g[1] = ∂f/∂y. */
typedef void (*cj_implicit_curve_grad_fn)(const void *user, double x, double y, double g[2]);

typedef struct cj_implicit {
    cj_implicit_curve_fn f;         /* required */
    cj_implicit_curve_grad_fn grad; /* optional: NULL = central differences */
    const void *user;               /* passed to f and grad */
} cj_implicit;

/* Storage for a built-in curve. Fields are private to the library. */
typedef struct cj_implicit_shape {
    int kind;
    int degree;
    double c[8];
    const double *coef;
} cj_implicit_shape;

/* Number of coefficients of a bivariate polynomial of total degree n: (n+1)(n+2)/2. */
size_t cj_implicit_poly_ncoef(int degree);

/* Line a x + b y + c = 0; (a, b) = (0, 0) is CJ_ERR_DEGENERATE. */
cj_status cj_implicit_line(double a, double b, double c, cj_implicit_shape *shape,
                           cj_implicit *out);
/* Circle (x − cx)² + (y − cy)² − r² = 0; r <= 0 is CJ_ERR_DEGENERATE. Inside: f < 0. */
cj_status cj_implicit_circle(double cx, double cy, double r, cj_implicit_shape *shape,
                             cj_implicit *out);
/* Ellipse (u/rx)² + (v/ry)² − 1 = 0 with (u, v) = R(−rot)(x − cx, y − cy); rx, ry > 0. */
cj_status cj_implicit_ellipse(double cx, double cy, double rx, double ry, double rot,
                              cj_implicit_shape *shape, cj_implicit *out);
/* Bivariate polynomial Σ coef[k] x^i y^j of total degree <= degree (0..32), coefficients in
 * graded order: for s = 0..degree, the terms x^s, x^(s−1) y, ..., y^s. So coef = {1, x, y,
 * x², xy, y², x³, ...}: cj_implicit_poly_ncoef(degree) values, which are copied by reference
 * (coef must outlive the shape). Evaluated by Horner in y inside Horner in x; the gradient is
 * exact (differentiated coefficients). */
cj_status cj_implicit_poly(int degree, const double *coef, cj_implicit_shape *shape,
                           cj_implicit *out);

/* f and ∇f at (x, y); either output may be NULL. CJ_ERR_NONFINITE if the point or a result is
 * not finite. */
cj_status cj_implicit_curve_eval(const cj_implicit *f, double x, double y, double *value,
                                 double g[2]);

/* Unit normal ∇f/|∇f| at (x, y) (pointing towards increasing f: outwards for the built-in
 * circle and ellipse). CJ_ERR_DEGENERATE where ∇f = 0. */
cj_status cj_implicit_curve_normal(const cj_implicit *f, double x, double y, double n[2]);

/* Moves (x, y) onto the curve by Newton steps along the gradient,
 * p ← p − f(p) ∇f(p)/|∇f(p)|², until |f|/|∇f| <= tol (at most 50 steps: CJ_ERR_CAP, with the
 * last point written). xy is updated in place; *residual (may be NULL) gets |f|/|∇f|. */
cj_status cj_implicit_curve_project(const cj_implicit *f, double xy[2], double tol,
                                    double *residual);

/* Receives one polyline: npts points xy[2*npts]; closed = 1 for a loop (last point == first);
 * max_residual = max over its vertices of |f|/|∇f|. The points are valid only during the call.
 * Return CJ_OK to continue; any other status stops contouring and is returned by it. */
typedef cj_status (*cj_polyline_fn)(void *user, const double *xy, size_t npts, int closed,
                                    double max_residual);

/* 2^-40 ≈ 9.1e-13: 4096 units in the last place of the box's largest coordinate. */
#define CJ_CONTOUR_MIN_REL_TOL 0x1p-40
/* 2^24 vertices per call (16.8 million; 256 MiB as points). */
#define CJ_CONTOUR_MAX_POINTS ((size_t)1 << 24)

typedef struct cj_contour_options {
    int nx, ny;                /* grid cells in x and y, 1..4096 each (0: 64) */
    double tol;                /* > 0: target |f|/|∇f| of vertices and chord-to-curve distance */
    const cj_allocator *alloc; /* work space (grid, polyline buffer); NULL: malloc/free */
} cj_contour_options;

typedef struct cj_contour_stats {
    size_t polylines;    /* polylines emitted */
    size_t closed;       /* of which closed loops */
    size_t points;       /* total vertices emitted */
    double max_residual; /* largest |f|/|∇f| over all vertices (0 if none) */
} cj_contour_stats;

/* Contours f = 0 inside box = {x0, y0, x1, y1} (x0 < x1, y0 < y1, else CJ_ERR_DEGENERATE),
 * emitting polylines through emit(user, ...) (algorithm above). stats may be NULL.
 * Status: CJ_ERR_NONFINITE (box, tol, or f not finite somewhere: the message names the point),
 * CJ_ERR_ARGUMENT (tol <= 0, grid size out of range), CJ_ERR_RANGE (a box whose sides overflow
 * the double range, or tol below CJ_CONTOUR_MIN_REL_TOL times the box's scale: the message
 * gives the smallest tolerance accepted), CJ_ERR_NOMEM, CJ_ERR_CAP when some vertex could not
 * be brought within tol (everything is still emitted, the residuals tell where) or more than
 * CJ_CONTOUR_MAX_POINTS vertices were needed (contouring stopped there), or whatever emit
 * returned. */
cj_status cj_implicit_contour(const cj_implicit *f, const double box[4],
                              const cj_contour_options *opts, cj_polyline_fn emit, void *user,
                              cj_contour_stats *stats);

#ifdef __cplusplus
}
#endif
#endif

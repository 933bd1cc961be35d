/* casteljau: motion along a path at a controlled speed — arc-length reparameterisation of a
 * chain of cubic Bézier segments (a Catmull-Rom path from casteljau/catmull_rom.h, a keyframe
 * channel's segments, or any G0 chain) with ease-in / ease-out profiles.
 *
 * The path c is the chain of segments c_0 .. c_{M−1} (each a cubic in u ∈ [0,1], dimension
 * 1..CJ_MAX_DIM, laid out 4·dim doubles per segment as catmull_rom.h does). Its arc length
 * from the start to (segment j, parameter u) is
 *
 *     S(j, u) = Σ_{i<j} L_i + ∫_0^u |c_j'(w)| dw.
 *
 * cj_path_create() tabulates S at CJ_PATH_TABLE pieces per segment with the library's adaptive
 * Gauss–Kronrod arc length (cj_bezier_arclength, casteljau/bezier.h). cj_path_at_length(s)
 * inverts S: the table brackets the answer, then safeguarded Newton on
 * f(u) = ∫_{u_a}^u |c'| − r with f'(u) = |c'(u)| (bisection whenever the Newton step leaves the
 * bracket or the speed vanishes) stops when |f| <= the piece tolerance. The achieved accuracy:
 *
 *     |S(j, u) − s| <= rel_tol · L      (L the path length, rel_tol given to create)
 *
 * up to the arc-length routine's own certified error (its estimates are summed and the sum is
 * kept below rel_tol·L/2 when the table is built; CJ_ERR_CAP otherwise). rel_tol down to
 * ~1e-13 is attainable in double precision; the tests check 1e-10 against closed-form lengths.
 *
 * EASE PROFILES map the time fraction x ∈ [0,1] to the length fraction σ(x) ∈ [0,1]:
 *   LINEAR      σ = x (constant speed)
 *   SMOOTHSTEP  σ = 3x² − 2x³ (speed 6x(1−x): starts and stops at rest)
 *   SINE        σ = (1 − cos πx)/2
 *   TRAPEZOID   constant acceleration for a fraction a ∈ (0, ½] of the time, cruise, constant
 *               deceleration for the last fraction a: with v = 1/(1−a),
 *               σ = v x²/(2a) (x < a), v (x − a/2) (a <= x <= 1−a), 1 − v (1−x)²/(2a) (x > 1−a).
 * x outside [0,1] is clamped.
 *
 * OWNERSHIP: the path copies the segments (one allocation through the optional allocator);
 * lookups allocate nothing and may run concurrently.
 *
 * Errors: M = 0: CJ_ERR_EMPTY; dim outside 1..CJ_MAX_DIM: CJ_ERR_DIMENSION; non-finite control
 * points: CJ_ERR_NONFINITE (naming the segment); rel_tol not in [1e-14, 0.1]: CJ_ERR_RANGE; a path
 * of zero length: CJ_ERR_DEGENERATE; s or x NaN: CJ_ERR_NONFINITE (s outside [0, L] is clamped).
 */
#ifndef CASTELJAU_MOTION_H
#define CASTELJAU_MOTION_H

#include "casteljau/alloc.h"
#include "casteljau/status.h"
#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Table pieces per segment. */
#define CJ_PATH_TABLE 16

typedef enum cj_ease {
    CJ_EASE_LINEAR = 0,
    CJ_EASE_SMOOTHSTEP,
    CJ_EASE_SINE,
    CJ_EASE_TRAPEZOID /* parameter: the acceleration fraction a ∈ (0, 1/2] */
} cj_ease;

typedef struct cj_path cj_path;

cj_status cj_path_create(const double *segs, size_t nsegs, int dim, double rel_tol,
                         const cj_allocator *alloc, cj_path **out);
void cj_path_destroy(cj_path *path);

/* The total length L. */
double cj_path_length(const cj_path *path);
/* The dimension of its points. */
int cj_path_dim(const cj_path *path);

/* The point at arc length s from the start (clamped to [0, L]): point[dim] (may be NULL), unit
 * tangent[dim] (may be NULL; the zero vector where the speed vanishes), and the segment and
 * parameter (either may be NULL). */
cj_status cj_path_at_length(const cj_path *path, double s, double *point, double *tangent,
                            size_t *segment, double *u);

/* σ(x) of a profile (header above); a TRAPEZOID parameter outside (0, 1/2] is CJ_ERR_RANGE. */
cj_status cj_ease_eval(cj_ease ease, double param, double x, double *sigma);

/* The point at time fraction x: cj_path_at_length(σ(x) · L). */
cj_status cj_path_motion(const cj_path *path, cj_ease ease, double param, double x, double *point,
                         double *tangent);

#ifdef __cplusplus
}
#endif
#endif

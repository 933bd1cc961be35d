/* Private: the working form of a curve being flattened and its proven bounds. */
#ifndef CASTELJAU_FLATTEN_INTERNAL_H
#define CASTELJAU_FLATTEN_INTERNAL_H

#include "casteljau/flatten.h"
#include "error_internal.h"

#include <string.h>

/* Homogeneous work space: (n+1) points of up to CJ_MAX_DIM (+1 weight) coordinates. */
#define CJ_FL_WORK ((CJ_BEZIER_MAX_DEGREE + 1) * (CJ_MAX_DIM + 1))

/* A validated curve in homogeneous form: hom[i*D + k] = w_i b_i,k (k < d), hom[i*D + d] = w_i
 * for rational curves (D = d+1); hom = b for polynomial ones (D = d). Coordinates and weights
 * are stored scaled by powers of two (see escale); cj_fl_point and the bounds undo it. */
typedef struct cj_fl_curve {
    int n, d, D;
    int rational;
    double slack;      /* rounding allowance added to every bound */
    int escale;        /* coordinates are stored times 2^-escale (exact scaling) */
    double s2;         /* 2^(1-n), the smallest end-weight share of a polynomial piece */
    const double *pts; /* the caller's Euclidean control points (exact end points) */
    double hom[CJ_FL_WORK];
} cj_fl_curve;

/* Validates (tolerance excluded) and fills fc. weights may be NULL. */
cj_status cj_fl_init(cj_fl_curve *fc, const cj_bezier *c, const double *weights);

/* Homogeneous control points of the piece on [a,b] (0 <= a < b <= 1) into sub[(n+1)*D]. */
void cj_fl_subcurve(const cj_fl_curve *fc, double a, double b, double *sub);

/* Splits homogeneous points src at t = 1/2 into left and right (neither may alias src). */
void cj_fl_split_half(const double *src, int n, int D, double *left, double *right);

/* Proven Hausdorff bound between the piece with homogeneous control points sub and its chord
 * (without the rounding slack). */
double cj_fl_piece_bound(const cj_fl_curve *fc, const double *sub);

/* Halvings of the refinement (d) (2^levels parts) and the largest degree it is used for (its
 * cost grows as n^2, its stack as levels * degree). */
#define CJ_FL_REFINE_LEVELS     2
#define CJ_FL_REFINE_MAX_DEGREE 16
/* The flatteners refine only where the cheap bound exceeds the distance of c(1/2) by more than
 * this factor (min_gain below). */
#define CJ_FL_REFINE_GAIN 1.02

/* cj_fl_piece_bound, and where it lies in (refine_above, refine_below] (it does not certify the
 * piece or lies near the target, but not so far above that refining is pointless) and exceeds
 * min_gain times the distance of c(1/2) from the chord (below that, refining cannot gain much:
 * the true deviation is at least that distance), the smaller of it and the refinement (d): the
 * piece halved CJ_FL_REFINE_LEVELS times, whose parts' control points' distances to the chord
 * segment bound the curve's. The refinement stops as soon as it exceeds stop (the result is
 * then > stop but may be below the full value). Same units and guarantee as
 * cj_fl_piece_bound. */
double cj_fl_piece_bound_refined(const cj_fl_curve *fc, const double *sub, double refine_above,
                                 double refine_below, double min_gain, double stop);

/* End point (i = 0 or n) of the curve, exactly the caller's control point, into out[d]. */
void cj_fl_end(const cj_fl_curve *fc, int i, double *out);

/* Euclidean point i of homogeneous control points h into out[d]. */
void cj_fl_point(const cj_fl_curve *fc, const double *h, int i, double *out);

/* Point of the curve at t (de Casteljau on the homogeneous points) into out[d]. */
void cj_fl_eval(const cj_fl_curve *fc, double t, double *out);

/* Wang's bound coefficient K: m equal steps give a bound of K / m^2 (plus slack). */
double cj_fl_wang_coefficient(const cj_fl_curve *fc);

/* Where points go: a caller buffer (out may be NULL to count) or a sink. */
typedef struct cj_fl_emitter {
    int d;
    double *out;
    size_t cap_points;
    cj_flatten_sink sink;
    void *user;
    size_t count;      /* points emitted so far in this call */
    size_t max_points; /* max_segments + 1 */
    size_t piece;
    int skip_equal; /* the next point is the start of a sequence piece */
    double last[CJ_MAX_DIM];
} cj_fl_emitter;

/* Returns 1 when the cap forbids this point. */
static inline int cj_fl_emit(cj_fl_emitter *e, const double *pt, double t) {
    if (e->skip_equal) {
        e->skip_equal = 0;
        if (e->count > 0 && memcmp(e->last, pt, sizeof(double) * (size_t)e->d) == 0) return 0;
    }
    if (e->count >= e->max_points) return 1;
    if (e->out && e->count < e->cap_points)
        memcpy(e->out + e->count * (size_t)e->d, pt, sizeof(double) * (size_t)e->d);
    if (e->sink) e->sink(e->user, pt, e->d, e->piece, t);
    memcpy(e->last, pt, sizeof(double) * (size_t)e->d);
    e->count++;
    return 0;
}

static inline cj_status cj_fl_cap_fail(const cj_fl_emitter *e, const char *method) {
    return cj_fail(CJ_ERR_CAP, "flattening (%s) needs more than max_segments = %zu segments",
                   method, e->max_points - 1);
}

/* The near-optimal method for planar polynomial quadratics and cubics (flatten_fast.c): the
 * same contract as the general one, at a fraction of its cost. cj_fl_fast_applies says whether
 * it takes the curve. */
int cj_fl_fast_applies(const cj_fl_curve *fc);
cj_status cj_fl_run_fast(const cj_fl_curve *fc, double tol_eff, cj_fl_emitter *em, double *bound);

#endif

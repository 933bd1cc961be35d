/* casteljau: tensor-product Bézier patches of any degree (m, n) in 3D, rational optional.
 *
 * A patch of degree (m, n) has (m+1)(n+1) control points b_ij (i = 0..m along u, j = 0..n
 * along v) and, if rational, one weight w_ij > 0 each. The control net is stored ROW BY ROW
 * WITH u FASTEST: point b_ij is pts[3*(j*(m+1) + i) + k], weight w_ij is weights[j*(m+1) + i]
 * (the layout of `casteljau tessellate --patch` and of the .bpt files). The patch is
 *
 *     S(u,v) = Σ_i Σ_j b_ij B_i^m(u) B_j^n(v)                        (polynomial), or
 *     S(u,v) = Σ w_ij b_ij B_i^m(u) B_j^n(v) / Σ w_ij B_i^m(u) B_j^n(v)   (rational),
 *
 * for (u,v) in [0,1]^2. Rational patches are handled in homogeneous form (w b, w) and
 * projected at the end. Orientation: the normal is S_u x S_v / |S_u x S_v|; a triangle whose
 * (u,v) corners run counter-clockwise is counter-clockwise seen from the side the normal
 * points to.
 *
 * cj_patch is a non-owning view: the caller owns pts, weights and every output buffer. No
 * function here allocates; work space lives on the stack, bounded by CJ_PATCH_MAX_DEGREE.
 *
 * Status codes common to every function (on failure cj_last_error() names the input):
 *   CJ_ERR_EMPTY      a negative degree;
 *   CJ_ERR_DEGREE     a degree above CJ_PATCH_MAX_DEGREE;
 *   CJ_ERR_NONFINITE  a NaN/Inf control coordinate, weight or parameter (named by i, j);
 *   CJ_ERR_ARGUMENT   a weight <= 0 (named), an unknown method/side, a negative order;
 *   CJ_ERR_RANGE      a parameter outside [0,1] where a piece of the patch is asked for
 *                     (evaluation itself accepts any finite (u,v): extrapolation).
 */
#ifndef CASTELJAU_PATCH_H
#define CASTELJAU_PATCH_H

#include "casteljau/bezier.h"
#include "casteljau/status.h"
#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Largest degree in each direction (the stack work space is (m+1)(n+1) homogeneous points). */
#define CJ_PATCH_MAX_DEGREE 32
/* Largest derivative order per direction accepted by cj_patch_eval_derivs. */
#define CJ_PATCH_MAX_DERIV 8

typedef struct cj_patch {
    int deg_u;             /* m >= 0 */
    int deg_v;             /* n >= 0 */
    const double *pts;     /* 3*(m+1)*(n+1) coordinates, point j*(m+1)+i is b_ij */
    const double *weights; /* NULL (polynomial) or (m+1)*(n+1) weights > 0, same order */
} cj_patch;

static inline cj_patch cj_patch_view(int deg_u, int deg_v, const double *pts,
                                     const double *weights) {
    cj_patch p;
    p.deg_u = deg_u;
    p.deg_v = deg_v;
    p.pts = pts;
    p.weights = weights;
    return p;
}

/* Number of control points (m+1)(n+1) (no validation). */
static inline size_t cj_patch_point_count(const cj_patch *p) {
    return (size_t)(p->deg_u + 1) * (size_t)(p->deg_v + 1);
}

/* Validates degrees, finite coordinates and positive finite weights. */
cj_status cj_patch_check(const cj_patch *p);

/* ---- evaluation ---------------------------------------------------------------------- */

/* S(u,v) into out[3]. method:
 *   CJ_EVAL_DECASTELJAU  de Casteljau on each row (in u), then on the column of results
 *                        (in v). Error <= gamma(3(m+n)) Σ|b_ij| B_i^m(u) B_j^n(v) per
 *                        coordinate (u,v in [0,1], polynomial).
 *   CJ_EVAL_COMPENSATED  a tensor compensated scheme: each row runs the compensated
 *                        (error-free transformation) de Casteljau WITHOUT rounding its
 *                        correction away; the row values and their corrections then seed the
 *                        value and error triangles of the compensated column pass, so the
 *                        result is as accurate as the tensor de Casteljau run in twice the
 *                        working precision and rounded once: per coordinate, for (u,v) in
 *                        [0,1]^2, |error| <= u|S| + O(gamma(3(m+n))^2) Σ|b_ij| B_i^m B_j^n
 *                        (checked against MPFR in tests/test_patch.c; for rational patches
 *                        the homogeneous coordinates get this accuracy and the final division
 *                        adds one rounding).
 * Other methods: CJ_ERR_ARGUMENT. */
cj_status cj_patch_eval(const cj_patch *p, cj_eval_method method, double u, double v,
                        double out[3]);

/* Partial derivatives D^{a,b} S = ∂^{a+b} S / ∂u^a ∂v^b for 0 <= a <= ku, 0 <= b <= kv
 * (each <= CJ_PATCH_MAX_DERIV) into out[3*(a*(kv+1) + b) + k]. Polynomial patches: the
 * hodographs of the rows (m!/(m-a)! Δ_u^a) then of the column, evaluated by de Casteljau;
 * orders above the degree are exactly zero. Rational patches: the homogeneous derivatives by
 * the same scheme, then Leibniz's rule
 *   D^{a,b}S = (D^{a,b}P - Σ_{(c,d) != (0,0)} C(a,c) C(b,d) D^{c,d}w D^{a-c,b-d}S) / w. */
cj_status cj_patch_eval_derivs(const cj_patch *p, double u, double v, int ku, int kv, double *out);

/* One partial derivative D^{a,b} S at (u,v) into out[3]. */
cj_status cj_patch_deriv(const cj_patch *p, int a, int b, double u, double v, double out[3]);

/* Unit normal at (u,v) into n[3].
 * RULE. Let N(u,v) = S_u x S_v. If |N| is not negligible (|N| > 64 u |S_u||S_v|), n = N/|N|.
 * Otherwise (a collapsed edge such as the teapot's lid top and bottom centre, a degenerate
 * corner, a fold) n is the limit of N/|N| along the ray from (u,v) towards the patch centre
 * (1/2,1/2) (direction +u at the centre itself): with d = (h,k) that direction, the Taylor
 * coefficients of N(u+th, v+tk) = Σ_r c_r t^r are
 *     c_r = Σ_{s=0..r} a_s x b_{r-s},  a_s = Σ_{i+j=s} h^i k^j/(i! j!) D^{i+1,j}S,
 *                                       b_s = Σ_{i+j=s} h^i k^j/(i! j!) D^{i,j+1}S,
 * and n = c_r/|c_r| for the first r (up to 4) whose c_r is not negligible (relative to
 * Σ|a_s||b_{r-s}|). On a collapsed edge v = 0 (S_u = 0 there) this is (S_uv x S_v)/|.|, at
 * u = 0 (S_v = 0) it is (S_u x S_uv)/|.|, and so on: the next non-vanishing derivatives. The
 * result is continuous with the normals of nearby interior points. *order (may be NULL)
 * receives r (0 for the regular case). CJ_ERR_DEGENERATE if every c_r vanishes (a patch
 * collapsed to a curve or a point). */
cj_status cj_patch_normal(const cj_patch *p, double u, double v, double n[3], int *order);

/* ---- subdivision, degree, geometry --------------------------------------------------- */

/* Splits at u = t (t in [0,1]) into left (u in [0,t]) and right (u in [t,1]) patches of the
 * same degree, each reparametrised to [0,1]. Outputs have the input's layout: *_pts holds
 * 3(m+1)(n+1) doubles, *_w (m+1)(n+1) weights and must be non-NULL exactly when the patch is
 * rational. Either half may be NULL (both its pts and w). The column u = t is bit-identical
 * in both halves. */
cj_status cj_patch_split_u(const cj_patch *p, double t, double *left_pts, double *left_w,
                           double *right_pts, double *right_w);
/* Same in v. */
cj_status cj_patch_split_v(const cj_patch *p, double t, double *left_pts, double *left_w,
                           double *right_pts, double *right_w);

/* The piece over [u0,u1] x [v0,v1] (0 <= u0 < u1 <= 1, same for v) reparametrised to [0,1]^2,
 * written to out_pts (and out_w when rational). */
cj_status cj_patch_subpatch(const cj_patch *p, double u0, double u1, double v0, double v1,
                            double *out_pts, double *out_w);

/* Exact degree elevation by ru >= 0 in u and rv >= 0 in v: out holds the (m+ru+1)(n+rv+1)
 * points (and weights) of the same surface, same layout. CJ_ERR_DEGREE past the limit. */
cj_status cj_patch_elevate(const cj_patch *p, int ru, int rv, double *out_pts, double *out_w);

/* Axis-aligned box of the control net (Euclidean points): contains the patch by the convex
 * hull property (weights > 0). It is not tight in general. */
cj_status cj_patch_bbox(const cj_patch *p, double lo[3], double hi[3]);

/* Size of a patch for relative tolerances: the diagonal of cj_patch_bbox. */
cj_status cj_patch_size(const cj_patch *p, double *size);

/* ---- curves on the patch (wireframes, control nets) ---------------------------------- */

/* The iso-parameter curve v -> S(u, v) at fixed u: a Bézier curve of degree n whose n+1
 * control points go to out_pts[3(n+1)] (weights to out_w[n+1] when rational; a polynomial
 * patch gives a polynomial curve usable as cj_bezier_view(n, 3, out_pts)). */
cj_status cj_patch_iso_u(const cj_patch *p, double u, double *out_pts, double *out_w);
/* The curve u -> S(u, v) at fixed v: degree m, m+1 points (and weights). */
cj_status cj_patch_iso_v(const cj_patch *p, double v, double *out_pts, double *out_w);

/* The four boundary curves, copied exactly from the control net. Each runs in the direction
 * of increasing parameter (not around the patch):
 *   CJ_PATCH_EDGE_V0: v = 0, u from 0 to 1 (degree m)    CJ_PATCH_EDGE_U1: u = 1, v 0→1 (n)
 *   CJ_PATCH_EDGE_V1: v = 1, u from 0 to 1 (degree m)    CJ_PATCH_EDGE_U0: u = 0, v 0→1 (n) */
typedef enum cj_patch_edge {
    CJ_PATCH_EDGE_V0 = 0,
    CJ_PATCH_EDGE_U1 = 1,
    CJ_PATCH_EDGE_V1 = 2,
    CJ_PATCH_EDGE_U0 = 3
} cj_patch_edge;

/* Control points of a boundary curve; *degree (may be NULL) receives its degree. */
cj_status cj_patch_boundary(const cj_patch *p, cj_patch_edge edge, double *out_pts, double *out_w,
                            int *degree);

#ifdef __cplusplus
}
#endif
#endif

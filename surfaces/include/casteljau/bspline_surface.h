/* casteljau: tensor-product B-spline and NURBS surfaces in 3D, converted to Bézier patches so
 * that tessellation, rendering and ray tracing (which take cj_patch) work on them.
 *
 * A surface of degrees (p, q) with nu × nv control points d_ij (i = 0..nu-1 along u, j along v),
 * optional weights w_ij > 0 and knot vectors U (nu + p + 1 knots) and V (nv + q + 1) is
 *
 *     S(u,v) = Σ_i Σ_j w_ij d_ij N_{i,p}(u) N_{j,q}(v) / Σ_i Σ_j w_ij N_{i,p}(u) N_{j,q}(v)
 *
 * (all w_ij = 1: the polynomial surface) on the domain [u_p, u_nu] × [v_q, v_nv]. The control net
 * is stored as cj_patch stores it, ROW BY ROW WITH u FASTEST: d_ij is pts[3*(j*nu + i) + k] and
 * w_ij is weights[j*nu + i]. Each knot vector follows the rules of casteljau/bspline.h (clamped,
 * unclamped or periodic-by-wrapping; multiplicities <= degree + 1; a non-empty domain).
 *
 * Validation (every function): degrees in [0, CJ_PATCH_MAX_DEGREE] (CJ_ERR_DEGREE; the patches
 * must fit cj_patch), nu >= p+1 and nv >= q+1 (CJ_ERR_EMPTY), knots as for curves with messages
 * naming "u knot i" / "v knot j" (CJ_ERR_ARGUMENT, CJ_ERR_NONFINITE, CJ_ERR_DEGENERATE), finite
 * points named by (i, j) (CJ_ERR_NONFINITE), weights finite and > 0 named by (i, j)
 * (CJ_ERR_NONFINITE, CJ_ERR_ARGUMENT). cj_bspline_surface is a non-owning view.
 */
#ifndef CASTELJAU_BSPLINE_SURFACE_H
#define CASTELJAU_BSPLINE_SURFACE_H

#include "casteljau/bspline_fit.h"
#include "casteljau/patch.h"
#include "casteljau/status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct cj_bspline_surface {
    int deg_u, deg_v;      /* p, q */
    int npts_u, npts_v;    /* nu >= p+1, nv >= q+1 */
    const double *pts;     /* 3*nu*nv coordinates, point (i, j) at j*nu + i */
    const double *weights; /* NULL (polynomial) or nu*nv weights > 0, same order */
    const double *knots_u; /* nu + p + 1 */
    const double *knots_v; /* nv + q + 1 */
} cj_bspline_surface;

cj_status cj_bspline_surface_check(const cj_bspline_surface *s);

/* S(u,v) into out[3]: de Boor in u on the q+1 rows of the v-span, then in v on the results
 * (homogeneous for a NURBS, one division at the end). (u,v) outside the domain: CJ_ERR_RANGE;
 * NaN: CJ_ERR_NONFINITE. Allocates nothing. */
cj_status cj_bspline_surface_eval(const cj_bspline_surface *s, double u, double v, double *out);

/* A-priori absolute error bound of cj_bspline_surface_eval at (u,v), per coordinate (bound[3]),
 * in the style of cj_bspline_error_bound: the u pass leaves every row value equal to the exact
 * de Boor sum of its points times (1 + θ_ij), |θ| <= gamma(5p), and the v pass multiplies each
 * row's term by (1 + φ_j), |φ| <= gamma(5q), so with M_k = Σ_i Σ_j |d_ij,k| N_i(u) N_j(v),
 *     |Ŝ_k − S_k| <= gamma(5(p+q)) M_k + 4 (p+q+2) eta (1 + max |d_ij,k|)      (polynomial);
 * a NURBS bounds the homogeneous numerator and weight the same way (gamma(5(p+q)+1), for the
 * rounding of w d) and propagates them through the division exactly as cj_bspline_error_bound.
 * Checked against the tensor MPFR oracle in tests/bspline/test_bspline_surface.c. */
cj_status cj_bspline_surface_error_bound(const cj_bspline_surface *s, double u, double v,
                                         double *bound);

/* Largest derivative order per direction of cj_bspline_surface_eval_derivs. */
#define CJ_BSPLINE_SURFACE_MAX_DERIV 16

/* Partial derivatives S_{u^k v^l}(u, v) for k = 0..ku, l = 0..kv (each in
 * [0, CJ_BSPLINE_SURFACE_MAX_DERIV], else CJ_ERR_ARGUMENT) into out[3 * ((k (kv+1) + l)) + c]
 * ((0, 0): the point). Method: the curve derivative pyramid of cj_bspline_eval_derivs on the q+1
 * rows of the v-span in u (homogeneous points), then on each order's q+1 row values in v;
 * a NURBS then takes the two-variable quotient rule
 *     S^(k,l) W = A^(k,l) − Σ_{(a,b) != (0,0), a<=k, b<=l} C(k,a) C(l,b) W^(a,b) S^(k−a,l−b).
 * Order (0, 0) is bit-identical to cj_bspline_surface_eval (the same de Boor levels). Orders
 * above a degree are zero for a polynomial surface. At a knot the value is the one from
 * the right (from the left at the domain's right end), as for curves. (u, v) outside the
 * domain: CJ_ERR_RANGE; NaN: CJ_ERR_NONFINITE; a derivative beyond the double range:
 * CJ_ERR_RANGE naming the order. Allocates nothing. */
cj_status cj_bspline_surface_eval_derivs(const cj_bspline_surface *s, double u, double v, int ku,
                                         int kv, double *out);

/* A-priori absolute error bound of cj_bspline_surface_eval_derivs, same layout (bound[3 * (k
 * (kv+1) + l) + c]), built from the curve bound of cj_bspline_derivs_error_bound:
 *   - u pass: row jj's computed order-k value R̂_jj^(k) is within δ_jj <= the curve bound of the
 *     row (gamma(6p − k + 2 (+1 NURBS)) times the magnitude pyramid, plus the subnormal slack);
 *   - v pass: the computed order-l value is within the curve bound of the spline whose points
 *     are the R̂^(k) (gamma(6q − l + 2) on their magnitudes) of that spline's exact derivative,
 *     which differs from the true one by Σ δ_jj N_jj^(l)(v), at most the magnitude pyramid run on
 *     the δ (sums instead of differences), inflated by 1 + gamma(6q + 8);
 *   - NURBS: the curve's quotient-rule recurrence with the sum over (a, b), order by order,
 *     e_kl (Ŵ − E_W) <= E_A,kl + Σ C(k,a) C(l,b) (E_W,ab |Ŝ_{k−a,l−b}| + (|Ŵ_ab| + E_W,ab)
 *     e_{k−a,l−b}) + gamma(2m+3) T_kl + |Ŝ_kl| (E_W + u (1+2u) Ŵ)   (m = (k+1)(l+1) − 1 terms,
 *     T_kl the sum of the magnitudes of the terms), inflated by 1 + gamma(4m + 12); requires
 *     Ŵ > 2 E_W (else CJ_ERR_RANGE).
 * Checked against the tensor MPFR oracle (basis derivatives in 2300-bit arithmetic) in
 * tests/bspline/test_bspline_surface_ops.c. Errors as cj_bspline_surface_eval_derivs. */
cj_status cj_bspline_surface_derivs_error_bound(const cj_bspline_surface *s, double u, double v,
                                                int ku, int kv, double *bound);

/* Number of Bézier patches: non-empty u spans times non-empty v spans. */
cj_status cj_bspline_surface_patch_count(const cj_bspline_surface *s, int *count);

/* The surface as Bézier patches of degree (p, q), rational for a NURBS: every breakpoint of each
 * direction raised to multiplicity p (q) by Boehm insertion on whole rows (columns), then the
 * (p+1)(q+1) points of every span pair. Patch a along u, b along v is number b*nspans_u + a; its
 * points (cj_patch layout) at pts + 3*(p+1)*(q+1)*k, weights at weights + (p+1)*(q+1)*k
 * (weights must be given exactly for a NURBS, else CJ_ERR_ARGUMENT), so
 *     cj_patch_view(p, q, pts + 3*(p+1)*(q+1)*k, weights ? weights + (p+1)*(q+1)*k : NULL)
 * is patch k, covering [ub[a], ub[a+1]] × [vb[b], vb[b+1]] of the surface's parameters
 * (ub, vb: the breaks, nspans_u + 1 and nspans_v + 1 values, either may be NULL). Neighbouring
 * patches share their boundary control points bit for bit where the surface is continuous
 * (they are the same refined control points), so watertight tessellation holds across them.
 * cap: capacity in patches (CJ_ERR_BUFFER if too small); *count (may be NULL) the count.
 * Allocates its work space (CJ_ERR_NOMEM). */
cj_status cj_bspline_surface_to_patches(const cj_bspline_surface *s, double *pts, double *weights,
                                        double *ub, double *vb, int cap, int *count);

/* Inserts the knot x r times in direction dir (0: u, 1: v) by Boehm's algorithm on every row
 * (column) at once: the same surface with nu + r (or nv + r) points in that direction. Outputs:
 * out_pts (3 per point, same layout with the new count), out_w (NURBS; else NULL), out_knots
 * (the refined direction's knot vector; the other one is unchanged). Multiplicity after
 * insertion above the degree: CJ_ERR_ARGUMENT naming x; x outside the domain: CJ_ERR_RANGE. */
cj_status cj_bspline_surface_insert_knot(const cj_bspline_surface *s, int dir, double x, int r,
                                         double *out_pts, double *out_w, double *out_knots);

/* Removes up to r copies of the interior knot x of direction dir (0: u, 1: v) while the surface
 * moves by at most tol >= 0: one copy at a time, every row (column) at once, as
 * cj_bspline_remove_knot does for a curve, on the wide curve whose points are whole rows of
 * homogeneous points; a copy goes only if every row (column) can lose it within what is left
 * of tol. Each removal's rigorous bound comes from re-inserting x and comparing the nets
 * (e = largest Euclidean distance between corresponding homogeneous points, convex hull):
 *     polynomial: e;   NURBS: e (1 + P) / w_min
 * (P = max |d'_ij| of the new net, w_min the smallest weight before the removal), from
 * A/W − A'/W' = (A − A')/W − (A'/W')(W − W')/W with |A − A'|, |W − W'| <= e. *removed gets the
 * count (0..r), *error (may be NULL) the sum of the bounds: |S − S'| <= *error everywhere on the
 * domain, plus the rounding of the re-refinement (about gamma(5p) of the coordinates). Outputs:
 * out_pts, out_w (NURBS; else NULL) and out_knots (the changed direction's knot vector) as large
 * as the input's; nothing removed: the input bit for bit. x not inside the domain: CJ_ERR_RANGE;
 * not a knot: CJ_ERR_ARGUMENT; tol NaN: CJ_ERR_NONFINITE, negative: CJ_ERR_ARGUMENT. Allocates
 * its work space (CJ_ERR_NOMEM). */
cj_status cj_bspline_surface_remove_knot(const cj_bspline_surface *s, int dir, double x, int r,
                                         double tol, double *out_pts, double *out_w,
                                         double *out_knots, int *removed, double *error);

/* Number of points along dir after elevating that degree by r: the rule of
 * cj_bspline_elevate_count, (p + r + 1) + Σ_interior (m_j + r). Degree 0: CJ_ERR_DEGREE;
 * p + r above CJ_PATCH_MAX_DEGREE: CJ_ERR_DEGREE; an interior knot of multiplicity p + 1 (a
 * jump): CJ_ERR_ARGUMENT; r < 0: CJ_ERR_ARGUMENT. */
cj_status cj_bspline_surface_elevate_count(const cj_bspline_surface *s, int dir, int r,
                                           int *npts_out);

/* Degree elevation by r in direction dir (0: u, 1: v), the same surface: the wide curve of whole
 * rows (columns) of homogeneous points split into Bézier pieces, every row of every piece elevated
 * by cj_bezier_elevate, joined, and the p − m extra copies of every interior knot removed again
 * (exact in exact arithmetic). *error (may be NULL) receives the sum of the removal bounds of
 * cj_bspline_surface_remove_knot (a few rounding units of the coordinates, times (1 + P)/w_min for
 * a NURBS; the rounding of the Bézier split and the elevation, a few hundred units of the
 * coordinates, comes on top). An unclamped direction comes out clamped over the same domain.
 * Outputs: out_pts[3 * npts_out * other], out_w (NURBS; else NULL) likewise, out_knots[npts_out + p
 * + r + 1] with npts_out from cj_bspline_surface_elevate_count (errors as there). Allocates its
 * work space (CJ_ERR_NOMEM). */
cj_status cj_bspline_surface_elevate(const cj_bspline_surface *s, int dir, int r, double *out_pts,
                                     double *out_w, double *out_knots, double *error);

/* Interpolation through a grid of nu × nv points Q_ij (same layout as pts) with degrees (p, q):
 * parameters per direction are the average over the rows (columns) of cj_fit_params of each
 * row (column); knots by averaging as in bspline_fit.h; every row is interpolated in u, then
 * every column of the result in v (one banded solve per direction, all rows as right-hand
 * sides). S(ū_i, v̄_j) = Q_ij up to rounding. Outputs: out_pts[3*nu*nv], knots_u[nu + p + 1],
 * knots_v[nv + q + 1]; ubar[nu], vbar[nv] (may be NULL) the parameters used. */
cj_status cj_bspline_surface_interpolate(const double *grid, int nu, int nv, int deg_u, int deg_v,
                                         cj_fit_param kind, double *out_pts, double *knots_u,
                                         double *knots_v, double *ubar, double *vbar);

#ifdef __cplusplus
}
#endif
#endif

/* casteljau: B-spline and NURBS curves of any degree and dimension, and their Bézier pieces.
 *
 * A B-spline of degree p with n+1 control points d_0..d_n (dimension dim, point-major exactly as
 * cj_bezier: pts[i*dim + k]) and the non-decreasing knot vector t_0..t_{n+p+1} is
 *
 *     c(t) = Σ_{i=0..n} d_i N_{i,p}(t),        t in the domain [t_p, t_{n+1}],
 *
 * with N_{i,p} the normalised B-spline basis (Cox–de Boor recurrence). With weights w_i > 0 it is
 * a NURBS (rational B-spline): c(t) = Σ w_i d_i N_{i,p}(t) / Σ w_i N_{i,p}(t), the central
 * projection of the polynomial B-spline with homogeneous points (w_i d_i, w_i) in dim+1.
 *
 * Knot vectors. Only the domain [t_p, t_{n+1}] is evaluated (outside it fewer than p+1 basis
 * functions sum to one; a parameter there is CJ_ERR_RANGE). The three usual kinds are one
 * representation:
 *   - clamped: p+1 equal knots at each end; the curve starts at d_0 and ends at d_n;
 *   - unclamped: any other non-decreasing knots (e.g. uniform 0,1,2,...);
 *   - periodic: a closed curve of m "cyclic" control points, stored unclamped with uniform knot
 *     spacing and the first p points repeated at the end (n+1 = m+p); then c and its first p-1
 *     derivatives agree at both ends of the domain. cj_bspline_periodic builds this form.
 * cj_bspline_uniform_knots writes the clamped and unclamped uniform vectors.
 *
 * Validation (cj_bspline_check, done by every function): degree in [0, CJ_BSPLINE_MAX_DEGREE]
 * (CJ_ERR_DEGREE), dim in [1, CJ_MAX_DIM] (polynomial) or [1, CJ_MAX_DIM-1] (NURBS)
 * (CJ_ERR_DIMENSION), at least p+1 control points (CJ_ERR_EMPTY, "3 control points are too few
 * for degree 3"), finite knots, points and weights (CJ_ERR_NONFINITE naming the knot, point or
 * weight), knots non-decreasing (CJ_ERR_ARGUMENT naming the pair), no knot value repeated more
 * than p+1 times (CJ_ERR_ARGUMENT naming the knot), a non-empty domain t_p < t_{n+1}
 * (CJ_ERR_DEGENERATE), weights > 0 (CJ_ERR_ARGUMENT naming the weight).
 *
 * cj_bspline is a non-owning view; the caller owns every array. Evaluation, derivatives, the
 * error bound and the Bézier split allocate nothing (work space on the stack, bounded by
 * CJ_BSPLINE_MAX_DEGREE and CJ_MAX_DIM). Functions that produce a curve whose size depends on
 * the data follow count-then-fill: they name the output size, which the caller provides.
 */
#ifndef CASTELJAU_BSPLINE_H
#define CASTELJAU_BSPLINE_H

#include "casteljau/bezier.h"
#include "casteljau/catmull_rom.h"
#include "casteljau/status.h"
#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Largest degree of a B-spline (work space of every call is O(degree * dim) on the stack). */
#define CJ_BSPLINE_MAX_DEGREE 64
/* Largest derivative order cj_bspline_eval_derivs returns (orders above the degree are zero). */
#define CJ_BSPLINE_MAX_DERIV 64

typedef struct cj_bspline {
    int degree;            /* p >= 0 */
    int dim;               /* 1..CJ_MAX_DIM (NURBS: 1..CJ_MAX_DIM-1) */
    int npts;              /* n+1 >= p+1 control points */
    const double *pts;     /* npts*dim coordinates, point-major */
    const double *weights; /* NULL: polynomial B-spline; else npts weights > 0 (NURBS) */
    const double *knots;   /* npts + degree + 1 knots, non-decreasing */
} cj_bspline;

static inline cj_bspline cj_bspline_view(int degree, int dim, int npts, const double *pts,
                                         const double *weights, const double *knots) {
    cj_bspline c;
    c.degree = degree;
    c.dim = dim;
    c.npts = npts;
    c.pts = pts;
    c.weights = weights;
    c.knots = knots;
    return c;
}

/* Number of knots of a curve: npts + degree + 1. */
static inline int cj_bspline_knot_count(const cj_bspline *c) {
    return c->npts + c->degree + 1;
}

/* Validates the curve (rules in the header comment). */
cj_status cj_bspline_check(const cj_bspline *c);

/* The parameter domain [t_p, t_{n+1}]. */
cj_status cj_bspline_domain(const cj_bspline *c, double *t0, double *t1);

/* ---- knot vectors --------------------------------------------------------------------- */

/* Uniform knot vectors for npts points of degree p over [a, b] (a < b), npts+p+1 knots:
 *   clamped != 0: p+1 copies of a, npts-p-1 equispaced interior knots, p+1 copies of b;
 *   clamped == 0: npts+p+1 equispaced knots with the domain [t_p, t_npts] = [a, b].
 * CJ_ERR_EMPTY if npts < p+1, CJ_ERR_ARGUMENT if a >= b, CJ_ERR_NONFINITE for a bad bound. */
cj_status cj_bspline_uniform_knots(int npts, int degree, double a, double b, int clamped,
                                   double *knots);

/* A closed (periodic) B-spline through the cyclic control polygon cyc[m*dim] (and cyclic
 * weights cyc_w[m], or NULL) of degree p (1 <= p, m >= p+1 distinct-index points): writes the
 * m+p control points (the m points followed by the first p again) to pts, the weights likewise
 * (if cyc_w), and m+2p+1 uniform knots with domain [0, m] (knot i is i - p) to knots. The
 * curve is C^{p-1} everywhere including at the seam c(0) = c(m). */
cj_status cj_bspline_periodic(const double *cyc, const double *cyc_w, int m, int dim, int degree,
                              double *pts, double *weights, double *knots);

/* Index s of the knot span containing t: t_s <= t < t_{s+1}, p <= s <= n, with the right end
 * t = t_{n+1} assigned to the last non-empty span. t outside the domain is CJ_ERR_RANGE. */
cj_status cj_bspline_find_span(const cj_bspline *c, double t, int *span);

/* ---- evaluation ----------------------------------------------------------------------- */

/* c(t) into out[dim] by de Boor's algorithm on the p+1 control points of the span (on the
 * homogeneous points for a NURBS, then one division). t must be in the domain (CJ_ERR_RANGE).
 * The convex combinations use α = (t − t_i)/(t_{i+p+1−r} − t_i) and 1 − α computed as
 * (t_{i+p+1−r} − t)/(t_{i+p+1−r} − t_i), so both are exact up to three roundings. */
cj_status cj_bspline_eval(const cj_bspline *c, double t, double *out);

/* cj_bspline_eval validates the whole curve on every call (O(npts) work: knots, points,
 * weights), which dominates for long curves. For many evaluations of one curve:
 *   - cj_bspline_eval_batch validates once, then evaluates ts[nt] (each in the domain, checked
 *     before anything is written) into out[nt*dim], bit-identical to cj_bspline_eval;
 *   - cj_bspline_eval_unchecked evaluates with no checks at all. CONTRACT (the caller's):
 *     cj_bspline_check returned CJ_OK for this curve and nothing changed since, t is in the
 *     domain [t_p, t_{n+1}] (not NaN), out holds dim doubles. Same result as cj_bspline_eval;
 *     breaking the contract is undefined behaviour (debug builds assert the parameter). */
cj_status cj_bspline_eval_batch(const cj_bspline *c, const double *ts, size_t nt, double *out);
void cj_bspline_eval_unchecked(const cj_bspline *c, double t, double *out);

/* Point and derivatives 0..kmax with respect to t: out[j*dim + k] = coordinate k of c^(j)(t),
 * j = 0..kmax (kmax in [0, CJ_BSPLINE_MAX_DERIV], else CJ_ERR_ARGUMENT); orders above p are
 * zero for a polynomial B-spline. Method: one de Boor pyramid at t, read off at level p−j: the
 * j+1 points left there are the de Boor points of the degree-j spline x ↦ B(t^(p−j), x^j) (B
 * the blossom), so c^(j)(t) = C(p,j) times its j-th derivative, j levels of differences
 *     d_i ← (j−l+1) (d_i − d_{i−1}) / (t_{i+j+1−l} − t_i),   l = 1..j
 * (the point, order 0, is bit-identical to cj_bspline_eval's); a NURBS combines the homogeneous
 * derivatives by the quotient rule
 * c^(j) = (A^(j) − Σ_{i=1..j} C(j,i) w^(i) c^(j−i)) / w. At a knot of multiplicity that makes a
 * derivative discontinuous the value is the one from the right (from the left at the domain's
 * right end). A derivative beyond the double range is CJ_ERR_RANGE naming the order. */
cj_status cj_bspline_eval_derivs(const cj_bspline *c, double t, int kmax, double *out);

/* cj_bspline_eval_derivs without any check, under the contract of cj_bspline_eval_unchecked
 * (validated curve, t in the domain) plus 0 <= kmax <= CJ_BSPLINE_MAX_DERIV. Same results; a
 * derivative beyond the double range comes out as it is (infinite or NaN) instead of an error. */
void cj_bspline_eval_derivs_unchecked(const cj_bspline *c, double t, int kmax, double *out);

/* A-priori absolute error bound of cj_bspline_eval at t, per coordinate, for the exact value of
 * the B-spline with the given (double) knots, points and t.
 * Polynomial B-spline: with M_k = Σ |d_i,k| N_{i,p}(t) and D_k = max |d_i,k| over the span's
 * p+1 points, u = 2^-53, eta = 2^-1074:
 *     |ĉ_k − c_k| <= gamma(5p) M_k + 4 (p+1) eta (1 + D_k).
 * Derivation: each of the p levels of de Boor forms d' = β d_{i−1} + α d_i with α, β ≥ 0 (t is
 * in the span), each of α, β computed with 3 roundings (two subtractions of doubles, one
 * division), the two products and the sum add 3 more: every term of level r carries a factor
 * (1+θ) with |θ| <= gamma(5) per level (the product of α's and β's rounding with the product's),
 * so the computed value is the exact de Boor sum of d_i N_i (1+θ_i), |θ_i| <= gamma(5p), as for
 * de Casteljau's gamma(3n). Underflow: a coefficient or a product that falls into subnormals is
 * off by at most eta absolutely instead of relatively: per level at most 2 eta (products) plus
 * 2 eta D_k (coefficients), carried by convex combinations: the second term, doubled for the
 * (1+gamma) growth.
 * NURBS: with the homogeneous bounds E_k (coordinate k of A = Σ w_i d_i N_i) and E_w (of
 * w = Σ w_i N_i; gamma(5p+1) there, for the rounding of w_i d_i), ŵ the computed weight sum and q_k
 * = |Â_k/ŵ|: |ĉ_k − c_k| <= u q_k + (E_k + C_k E_w) / ŵ,   C_k = (q_k + E_k/ŵ) / (1 − E_w/ŵ) >=
 * |c_k|, from Â/ŵ − A/w = ((Â − A) w − A (ŵ − w)) / (w ŵ) (requires ŵ > 2 E_w, else CJ_ERR_RANGE).
 * M_k is computed by de Boor on |d_i,k| and inflated by 1 + gamma(5p+8) so the computed bound
 * is an upper bound. Checked against an MPFR oracle (Cox–de Boor basis functions in 1024-bit
 * arithmetic) in tests/test_bspline_eval.c on random, repeated-knot, tiny-span, high-degree,
 * huge- and tiny-coordinate curves. bound: dim doubles. */
cj_status cj_bspline_error_bound(const cj_bspline *c, double t, double *bound);

/* A-priori absolute error bound of cj_bspline_eval_derivs at t: bound[j*dim + k] for order
 * j = 0..kmax, coordinate k.
 * Polynomial B-spline. With M_j,k the same pyramid run on magnitudes (|d_i,k| in, de Boor's
 * convex combinations, sums instead of differences, times C(p,j)) and S_j,k the same recurrences
 * run on the subnormal slack 8 (p+1) eta (1 + max|d|) with 4 eta added at every sum:
 *     |ĉ^(j)_k − c^(j)_k| <= gamma(6p − j + 2) M_j,k + S_j,k (+ eta)   (j <= p), 0 above p.
 * Derivation: de Boor's p−j levels round five times each (as for the value: the computed
 * points are the exact blossom of points off by gamma(5(p−j)) relatively); a level of
 * differences rounds four times (the knot difference, the quotient (j−l+1)/den, the point
 * difference, the product), so j levels add gamma(4j) of the magnitudes; C(p,j) by Pascal's rule
 * is off by at most gamma(p) and the product by it rounds once; (1+gamma(a)) gamma(b) + gamma(a)
 * <= gamma(a+b). M and S are computed by the same recurrences and inflated by 1 + gamma(6p+8).
 * NURBS. The homogeneous derivatives A^(j) (of Σ w_i d_i N_i) and w^(j) (of Σ w_i N_i) are
 * bounded as above on the points (w_i d_i, w_i): E_A,j,k with gamma(6p − j + 3) (the products
 * w_i d_i round once: the exact derivative of the spline of those roundings is at most u M_j)
 * and E_w,j with gamma(6p − j + 2). The derivatives come from the quotient rule
 * c^(j) w = A^(j) − Σ_{i=1..j} C(j,i) w^(i) c^(j−i), computed as v = Â^(j) − Σ C ŵ^(i) ĉ^(j−i)
 * (off by at most gamma(j+2) S_j, S_j = |Â^(j)| + Σ C |ŵ^(i)| |ĉ^(j−i)|; gamma(2j+3) is used)
 * and ĉ^(j) = v/ŵ (|ĉ ŵ − v| <= u(1+2u)|ĉ| ŵ). Subtracting the exact relation, with
 * ŵ^(i)ĉ − w^(i)c = (ŵ^(i) − w^(i))ĉ + w^(i)(ĉ − c), |w^(i)| <= |ŵ^(i)| + E_w,i and
 * |c^(j)| <= |ĉ^(j)| + e_j, the errors e_j = |ĉ^(j)_k − c^(j)_k| satisfy, order by order,
 *     e_j (ŵ − E_w,0) <= E_A,j + Σ_{i=1..j} C(j,i) (E_w,i |ĉ^(j−i)| + (|ŵ^(i)| + E_w,i) e_{j−i})
 *                        + gamma(2j+3) S_j + |ĉ^(j)| (E_w,0 + u(1+2u) ŵ),
 * evaluated on the computed values (each term non-negative, the result inflated by
 * 1 + gamma(4j+12) for its own roundings). Requires ŵ > 2 E_w,0 (else CJ_ERR_RANGE, as for the
 * value). Checked against the MPFR oracle in tests/bspline/test_bspline_eval.c (polynomial and
 * NURBS, orders 0..p+2). */
cj_status cj_bspline_derivs_error_bound(const cj_bspline *c, double t, int kmax, double *bound);

/* ---- knots: insertion, refinement, removal ------------------------------------------- */

/* Inserts the knot value x (in the domain) r >= 0 times by Boehm's algorithm, one at a time:
 * the result has npts + r points (out_pts[(npts+r)*dim], out_w[npts+r] for a NURBS, else NULL)
 * and npts + r + p + 1 knots (out_knots), and is the same curve. The multiplicity of x after
 * insertion must not exceed p (CJ_ERR_ARGUMENT naming x). A NURBS is refined in homogeneous
 * coordinates. Outputs must not overlap the input. */
cj_status cj_bspline_insert_knot(const cj_bspline *c, double x, int r, double *out_pts,
                                 double *out_w, double *out_knots);

/* Knot refinement: inserts the nx values xs[] (non-decreasing, each in the domain, final
 * multiplicities <= p) by repeated Boehm insertion, the same curve with npts + nx points.
 * Outputs as cj_bspline_insert_knot. */
cj_status cj_bspline_refine(const cj_bspline *c, const double *xs, int nx, double *out_pts,
                            double *out_w, double *out_knots);

/* Removes up to r copies of the interior knot x (t_p < x < t_{n+1}, present in the vector)
 * while the curve moves by at most tol >= 0. One copy at a time: the p − s + 1 equations of
 * Boehm's insertion (s the multiplicity) are solved for the p − s unknown points from both ends
 * towards the middle; the candidate is then re-refined by inserting x again and compared with
 * the original points, which gives a rigorous bound of the deviation (convex hull property):
 *     polynomial: max_i |d_i − d'_i|   (Euclidean),
 *     NURBS:      (max_i |A_i − A'_i| + P max_i |w_i − w'_i|) / min_i w_i
 *                 (A_i = w_i d_i, P = max_i |d'_i|; from A/w − A'/w' = (A−A')/w − c'(w−w')/w).
 * Removals stop before the first one that would bring the sum of these bounds above tol.
 * *removed receives the number of copies removed (0..r), *error (may be NULL) the bound reached
 * (the sum over the removed copies; rounding of the re-refinement, ~ gamma(5p) times the
 * points, comes on top). Outputs: npts − *removed points and their knots, written into buffers
 * as large as the input's (out_w NULL for a polynomial B-spline). */
cj_status cj_bspline_remove_knot(const cj_bspline *c, double x, int r, double tol, double *out_pts,
                                 double *out_w, double *out_knots, int *removed, double *error);

/* ---- degree elevation ----------------------------------------------------------------- */

/* Number of control points of the curve elevated by r degrees: the result is clamped over the
 * same domain, every distinct interior knot of multiplicity m gets multiplicity m + r (the
 * same continuity), so npts_out = (p + r + 1) + Σ_interior (m_j + r). */
cj_status cj_bspline_elevate_count(const cj_bspline *c, int r, int *npts_out);

/* Degree elevation by r >= 0 (p + r <= CJ_BSPLINE_MAX_DEGREE): split into Bézier pieces,
 * elevate each exactly (cj_bezier_elevate), join them and remove the p − m_j extra copies of
 * every interior knot again (exactly removable in exact arithmetic; *error, may be NULL,
 * receives the bound of the removals: a few rounding units of the coordinates per removal,
 * times wmax/wmin for a NURBS curve, whose removals divide homogeneous differences by the
 * smallest weight). An unclamped
 * input comes out clamped over the same domain (the same curve there). Degree 0 is
 * CJ_ERR_DEGREE and a jump (interior multiplicity p+1) CJ_ERR_ARGUMENT. Outputs sized by
 * cj_bspline_elevate_count: out_pts[npts_out*dim], out_w[npts_out] (NURBS), out_knots
 * [npts_out + p + r + 1]. Allocates its work space (CJ_ERR_NOMEM). */
cj_status cj_bspline_elevate(const cj_bspline *c, int r, double *out_pts, double *out_w,
                             double *out_knots, double *error);

/* ---- Bézier pieces -------------------------------------------------------------------- */

/* Number of Bézier pieces: the non-empty knot spans inside the domain. */
cj_status cj_bspline_bezier_count(const cj_bspline *c, int *npieces);

/* Splits the curve into its polynomial (or rational) Bézier pieces, one per non-empty span,
 * in order. Piece j covers [breaks[j], breaks[j+1]] of the B-spline parameter and is
 *     cj_bezier_view(p, dim, pts + j*(p+1)*dim)                     (polynomial), or
 *     cj_rbezier_view(p, dim, pts + j*(p+1)*dim, w + j*(p+1))       (NURBS; w must be given),
 * with c(t) = piece_j((t − breaks[j]) / (breaks[j+1] − breaks[j])). Bézier point i of the span
 * [a, b] is the blossom c[a^(p−i), b^i], computed by de Boor with level arguments (convex
 * combinations, same rounding model as cj_bspline_eval). Where the curve is continuous (the
 * joint's knot has multiplicity <= p) the end point of piece j and the start point of piece j+1
 * are bit-identical (the second is copied from the first), so polylines and meshes built per
 * piece join without gaps; at a knot of multiplicity p+1 the pieces keep their own end points.
 * cap_pieces: capacity of the buffers in pieces (CJ_ERR_BUFFER if too small, nothing written);
 * breaks (may be NULL): npieces+1 values; *npieces (may be NULL) receives the count. w must be
 * non-NULL exactly for a NURBS (CJ_ERR_ARGUMENT otherwise). */
cj_status cj_bspline_to_bezier(const cj_bspline *c, double *pts, double *w, double *breaks,
                               int cap_pieces, int *npieces);

/* The B-spline made of npieces Bézier pieces of degree p (pts: npieces*(p+1)*dim, point-major
 * piece after piece; w: npieces*(p+1) weights or NULL) joined at breaks[npieces+1] (strictly
 * increasing). Exact where the pieces meet exactly: the end point of piece j must equal the
 * start point of piece j+1 (and for a NURBS, the end weight equal the start weight) within
 * join_tol >= 0 (max coordinate difference; 0 asks for equality), else CJ_ERR_ARGUMENT naming
 * the joint. The result is clamped with interior knots of multiplicity p: npts_out =
 * npieces*p + 1 points (the joint takes piece j+1's start point), npts_out + p + 1 knots.
 * Knots where the pieces join more smoothly can then be removed by cj_bspline_remove_knot. */
cj_status cj_bspline_from_bezier(const double *pts, const double *w, const double *breaks,
                                 int npieces, int degree, int dim, double join_tol, double *out_pts,
                                 double *out_w, double *out_knots);

/* The cubic spline of catmull_rom.h (any kind, open or closed) through pts[npts*dim] as a cubic
 * B-spline: the Hermite pieces joined at the spline's knots (its own parameter, so the
 * non-uniform kinds stay C^1), one copy of each interior knot removed where the pieces join C^1
 * (all of them, except for Kochanek–Bartels with continuity != 0). *npts_out receives the count
 * of points written; buffers must hold 3*nsegs+1 points and 3*nsegs+5 knots
 * (nsegs = cj_spline_segment_count(npts, closed)); *error (may be NULL) the removal bound. */
cj_status cj_bspline_from_spline(const double *pts, size_t npts, int dim,
                                 const cj_spline_options *opts, double *out_pts, double *out_knots,
                                 int *npts_out, double *error);

#ifdef __cplusplus
}
#endif
#endif

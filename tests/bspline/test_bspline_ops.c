/* B-spline operations that must not move the curve, measured with the MPFR oracle (exact curves
 * of the double data before and after): Boehm insertion and refinement, knot removal (its
 * reported bound is an upper bound of the true deviation; removable knots go, others stay),
 * degree elevation, Bézier pieces (each reproduces its span), pieces back to a B-spline,
 * Catmull-Rom and the other cubic splines as B-splines, periodic curves, and refused input. */
#include "bsp_test.h"
#include "oracle_bspline.h"
#include "oracle_mpfr.h"

#include "casteljau/bspline.h"
#include "casteljau/catmull_rom.h"
#include "casteljau/rational.h"
#include "casteljau/status.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static cj_obsp oracle_of(const cj_bspline *c) {
    cj_obsp o = {c->degree, c->dim, c->npts, c->pts, c->weights, c->knots};
    return o;
}

/* max_k |a_k(t) - b_k(t)| between the exact curves at the (exact, mpfr) parameter t. */
static double gap_at(const cj_bspline *a, const cj_bspline *b, const mpfr_t t) {
    const cj_obsp oa = oracle_of(a), ob = oracle_of(b);
    mpfr_t va, vb;
    mpfr_inits2(64, va, vb, (mpfr_ptr)0);
    double g = 0.0;
    for (int k = 0; k < a->dim; ++k) {
        cj_obsp_eval(&oa, k, t, 0, &va, NULL);
        cj_obsp_eval(&ob, k, t, 0, &vb, NULL);
        mpfr_sub(va, va, vb, MPFR_RNDN);
        mpfr_abs(va, va, MPFR_RNDN);
        g = fmax(g, mpfr_get_d(va, MPFR_RNDU));
    }
    mpfr_clears(va, vb, (mpfr_ptr)0);
    return g;
}

/* Largest gap over the knots of both, the domain ends and n random parameters. */
static double gap(cj_rng *r, const cj_bspline *a, const cj_bspline *b, int n) {
    const double t0 = a->knots[a->degree], t1 = a->knots[a->npts];
    mpfr_t t;
    mpfr_init2(t, 64);
    double g = 0.0;
    for (int j = 0; j < n + 2; ++j) {
        double x = j == 0 ? t0 : (j == 1 ? t1 : t0 + (t1 - t0) * cj_rng_unit(r));
        if (x > t1) x = t1;
        mpfr_set_d(t, x, MPFR_RNDN);
        g = fmax(g, gap_at(a, b, t));
    }
    mpfr_clear(t);
    return g;
}

static double max_abs(const double *v, int n) {
    double m = 0.0;
    for (int i = 0; i < n; ++i) m = fmax(m, fabs(v[i]));
    return m;
}

/* The scale a perturbation of the homogeneous points is multiplied by (1 for polynomials). */
static double weight_ratio(const cj_bspline *c) {
    if (!c->weights) return 1.0;
    double lo = INFINITY, hi = 0.0;
    for (int i = 0; i < c->npts; ++i) {
        lo = fmin(lo, c->weights[i]);
        hi = fmax(hi, c->weights[i]);
    }
    return 2.0 * hi / lo + 1.0;
}

static int multiplicity(const double *u, int n, double x) {
    int m = 0;
    for (int i = 0; i < n; ++i) m += u[i] == x;
    return m;
}

static double out_pts[BSP_MAXN * 4 * 8], out_w[BSP_MAXN * 4], out_knots[BSP_MAXN * 4 + 70];
static double pts2[BSP_MAXN * 4 * 8], w2[BSP_MAXN * 4], knots2[BSP_MAXN * 4 + 70];

static void test_insert_refine(cj_rng *r) {
    static bsp_case c;
    double worst = 0.0;
    int cases = 0;
    for (int rep = 0; rep < 60; ++rep) {
        const int p = cj_rng_int(r, 1, 7), n1 = p + 1 + cj_rng_int(r, 0, 10);
        bsp_generate(r, &c, p, n1, cj_rng_int(r, 1, 3), rep % 2, rep % BSP_KNOTS_KINDS,
                     rep % 4 == 3 ? BSP_COORDS_MIXED : BSP_COORDS_UNIT);
        const cj_bspline v = bsp_view(&c);
        /* A refinement: a few random parameters plus an existing knot, sorted. */
        double xs[12];
        int nx = 0;
        const double a = c.knots[p], b = c.knots[n1];
        for (int j = 0; j < 6; ++j) xs[nx++] = a + (b - a) * cj_rng_unit(r);
        xs[nx++] = c.knots[cj_rng_int(r, p, n1)];
        for (int i = 1; i < nx; ++i)
            for (int j = i; j > 0 && xs[j] < xs[j - 1]; --j) {
                const double t = xs[j];
                xs[j] = xs[j - 1];
                xs[j - 1] = t;
            }
        cj_status st = cj_bspline_refine(&v, xs, nx, out_pts, c.rational ? out_w : NULL, out_knots);
        if (st == CJ_ERR_ARGUMENT) { /* the existing knot was already at multiplicity p */
            BSP_CHECK(strstr(cj_last_error(), "multiplicity") != NULL, "%s: %s", c.what,
                      cj_last_error());
            continue;
        }
        BSP_CHECK(st == CJ_OK, "%s: refine: %s", c.what, cj_last_error());
        if (st) continue;
        const cj_bspline f =
            cj_bspline_view(p, c.dim, n1 + nx, out_pts, c.rational ? out_w : NULL, out_knots);
        BSP_CHECK(cj_bspline_check(&f) == CJ_OK, "%s: refined curve invalid: %s", c.what,
                  cj_last_error());
        const double tol =
            nx * cj_gamma(8) * max_abs(c.pts, n1 * c.dim) * weight_ratio(&v) + 0x1p-1000;
        const double g = gap(r, &v, &f, 6);
        BSP_CHECK(g <= tol, "%s: refinement by %d knots moved the curve by %.3g > %.3g", c.what, nx,
                  g, tol);
        worst = fmax(worst, g / tol);
        /* Single insertion up to multiplicity p. */
        const double x = a + (b - a) * 0.375;
        st = cj_bspline_insert_knot(&v, x, p, out_pts, c.rational ? out_w : NULL, out_knots);
        if (st == CJ_OK) {
            int mult = 0;
            for (int i = 0; i < n1 + 2 * p + 1; ++i) mult += out_knots[i] == x;
            BSP_CHECK(mult >= p, "%s: knot %.17g inserted p times has multiplicity %d", c.what, x,
                      mult);
            const cj_bspline f2 =
                cj_bspline_view(p, c.dim, n1 + p, out_pts, c.rational ? out_w : NULL, out_knots);
            const double g2 = gap(r, &v, &f2, 4);
            const double tol2 =
                p * cj_gamma(8) * max_abs(c.pts, n1 * c.dim) * weight_ratio(&v) + 0x1p-1000;
            BSP_CHECK(g2 <= tol2, "%s: p-fold insertion moved the curve by %.3g", c.what, g2);
            worst = fmax(worst, g2 / tol2);
        }
        ++cases;
    }
    printf("insertion/refinement: %d random curves (half NURBS) refined by 7 knots and by one knot "
           "p times; the exact curves differ by at most (insertions) gamma(8) max|d| (2 wmax/wmin "
           "+ 1); largest gap/tolerance %.3g\n",
           cases, worst);
}

static void test_removal(cj_rng *r) {
    static bsp_case c;
    int exact = 0, bounded = 0;
    double worst = 0.0;
    for (int rep = 0; rep < 50; ++rep) {
        const int p = cj_rng_int(r, 1, 6), n1 = p + 2 + cj_rng_int(r, 0, 8);
        bsp_generate(r, &c, p, n1, cj_rng_int(r, 1, 3), rep % 2, BSP_KNOTS_RANDOM, BSP_COORDS_UNIT);
        const cj_bspline v = bsp_view(&c);
        double *wo = c.rational ? out_w : NULL, *w2o = c.rational ? w2 : NULL;
        /* (a) insert a new knot p-1 times, then remove it again: all copies go, the bound is
         * rounding-sized and the curve is the original one. */
        const double a = c.knots[p], b = c.knots[n1];
        double x = a + (b - a) * (0.3 + 0.4 * cj_rng_unit(r));
        if (multiplicity(c.knots, n1 + p + 1, x)) continue;
        const int ins = p > 1 ? p - 1 : 1;
        cj_status st = cj_bspline_insert_knot(&v, x, ins, out_pts, wo, out_knots);
        BSP_CHECK(st == CJ_OK, "%s: insert: %s", c.what, cj_last_error());
        if (st) continue;
        const cj_bspline f = cj_bspline_view(p, c.dim, n1 + ins, out_pts, wo, out_knots);
        int removed = -1;
        double err = -1.0;
        st = cj_bspline_remove_knot(&f, x, ins, 1e-9, pts2, w2o, knots2, &removed, &err);
        BSP_CHECK(st == CJ_OK && removed == ins && err <= 1e-9,
                  "%s: removing %d inserted copies: status %d removed %d bound %.3g", c.what, ins,
                  st, removed, err);
        const cj_bspline back = cj_bspline_view(p, c.dim, n1 + ins - removed, pts2, w2o, knots2);
        const double g = gap(r, &v, &back, 6);
        const double tol = 2 * ins * cj_gamma(8) * weight_ratio(&v) + err;
        BSP_CHECK(g <= tol, "%s: insert+remove moved the curve by %.3g > %.3g", c.what, g, tol);
        ++exact;
        /* (b) an original interior knot of a random curve is (generically) not removable: tol 0
         * keeps it, tol = infinity removes it and the reported bound covers the true change. */
        int idx = -1;
        for (int i = p + 1; i < n1; ++i)
            if (c.knots[i] > a && c.knots[i] < b) idx = i;
        if (idx < 0) continue;
        x = c.knots[idx];
        st = cj_bspline_remove_knot(&v, x, 1, 0.0, pts2, w2o, knots2, &removed, &err);
        BSP_CHECK(st == CJ_OK && removed == 0 && err == 0.0, "%s: tol 0 removed %d copies of %.17g",
                  c.what, removed, x);
        BSP_CHECK(memcmp(pts2, c.pts, sizeof(double) * (size_t)(n1 * c.dim)) == 0,
                  "%s: nothing removed but the points changed", c.what);
        st = cj_bspline_remove_knot(&v, x, 1, INFINITY, pts2, w2o, knots2, &removed, &err);
        /* A NURBS candidate may need a weight <= 0: then nothing is removed, at any tolerance. */
        BSP_CHECK(st == CJ_OK && (removed == 1 || c.rational), "%s: tol inf removed %d", c.what,
                  removed);
        if (st || removed != 1) continue;
        const cj_bspline less = cj_bspline_view(p, c.dim, n1 - 1, pts2, w2o, knots2);
        const double gl = gap(r, &v, &less, 12);
        /* rounding of the re-refinement that measured the bound comes on top of it */
        const double slack =
            4 * cj_gamma(8) * (max_abs(c.pts, n1 * c.dim) + err) * weight_ratio(&v);
        BSP_CHECK(gl <= err + slack, "%s: removal moved the curve by %.6g, bound said %.6g", c.what,
                  gl, err);
        if (err > 0) worst = fmax(worst, gl / err);
        ++bounded;
    }
    printf("removal: %d curves got back after inserting a knot p-1 times and removing it (bound "
           "<= 1e-9, curve unchanged); %d non-removable knots kept at tol 0 and removed at tol "
           "inf with the true deviation (oracle, 14 parameters) at most the reported bound: "
           "largest deviation/bound %.3g\n",
           exact, bounded, worst);
}

/* Piece j of the split at local parameter s (a dyadic double) against the B-spline at
 * a + (b-a) s, both exact (MPFR). */
static void test_bezier_pieces(cj_rng *r) {
    static bsp_case c;
    static double bp[BSP_MAXN * 70 * 8], bw[BSP_MAXN * 70], br[BSP_MAXN + 1];
    double worst = 0.0;
    int pieces = 0, joints = 0;
    for (int rep = 0; rep < 60; ++rep) {
        const int p = cj_rng_int(r, 0, 8), n1 = p + 1 + cj_rng_int(r, 0, 10);
        bsp_generate(r, &c, p, n1, cj_rng_int(r, 1, 3), rep % 2, rep % BSP_KNOTS_KINDS,
                     rep % 4 == 1 ? BSP_COORDS_HUGE : BSP_COORDS_UNIT);
        const cj_bspline v = bsp_view(&c);
        int np = -1, np2 = -1;
        BSP_CHECK(cj_bspline_bezier_count(&v, &np) == CJ_OK, "%s: count", c.what);
        cj_status st = cj_bspline_to_bezier(&v, bp, c.rational ? bw : NULL, br, np, &np2);
        BSP_CHECK(st == CJ_OK && np2 == np, "%s: split: %s", c.what, cj_last_error());
        if (st) continue;
        if (np > 1) {
            st = cj_bspline_to_bezier(&v, bp, c.rational ? bw : NULL, br, np - 1, &np2);
            BSP_CHECK(st == CJ_ERR_BUFFER, "%s: a buffer one piece short gave %d", c.what, st);
        }
        const cj_obsp o = oracle_of(&v);
        const int e = c.dim + c.rational;
        double hom[70 * 8];
        mpfr_t t, vb, vw, mb, vs, diff;
        mpfr_inits2(CJ_ORACLE_BSP_PREC, t, vb, vw, mb, vs, diff, (mpfr_ptr)0);
        for (int j = 0; j < np; ++j) {
            const double *P = bp + (size_t)j * (size_t)((p + 1) * c.dim);
            const double *W = bw + (size_t)j * (size_t)(p + 1);
            for (int i = 0; i <= p; ++i) {
                for (int k = 0; k < c.dim; ++k)
                    hom[i * e + k] = c.rational ? P[i * c.dim + k] * W[i] : P[i * c.dim + k];
                if (c.rational) hom[i * e + c.dim] = W[i];
            }
            if (j + 1 < np && p > 0 && multiplicity(c.knots, n1 + p + 1, br[j + 1]) <= p) {
                const double *Q = P + (p + 1) * c.dim;
                BSP_CHECK(memcmp(P + p * c.dim, Q, sizeof(double) * (size_t)c.dim) == 0,
                          "%s: pieces %d and %d do not share their end point bit for bit", c.what,
                          j, j + 1);
                ++joints;
            }
            for (int q = 0; q <= 8; ++q) {
                const double s = q / 8.0;
                /* At a jump the oracle takes the right-hand value, the piece the left one. */
                if (q == 8 && j + 1 < np && multiplicity(c.knots, n1 + p + 1, br[j + 1]) > p)
                    continue;
                mpfr_set_d(t, br[j + 1], MPFR_RNDN);
                mpfr_sub_d(t, t, br[j], MPFR_RNDN);
                mpfr_mul_d(t, t, s, MPFR_RNDN);
                mpfr_add_d(t, t, br[j], MPFR_RNDN);
                double mag_w = 1.0;
                if (c.rational) cj_oracle_bezier(hom, p, e, c.dim, s, 4096, vw, NULL);
                if (c.rational) mag_w = mpfr_get_d(vw, MPFR_RNDD);
                for (int k = 0; k < c.dim; ++k) {
                    cj_oracle_bezier(hom, p, e, k, s, 4096, vb, mb);
                    if (c.rational) mpfr_div(vb, vb, vw, MPFR_RNDN);
                    cj_obsp_eval(&o, k, t, 0, &vs, NULL);
                    mpfr_sub(diff, vb, vs, MPFR_RNDN);
                    mpfr_abs(diff, diff, MPFR_RNDN);
                    const double g = mpfr_get_d(diff, MPFR_RNDU);
                    /* The blossom's rounding (gamma(5p) of the magnitudes) and for a NURBS the
                     * dehomogenised points (one rounding each) re-multiplied by the weights. */
                    const double tol =
                        4 * cj_gamma(5 * p + 4) *
                            (mpfr_get_d(mb, MPFR_RNDU) / mag_w + max_abs(c.pts, n1 * c.dim)) *
                            weight_ratio(&v) +
                        0x1p-1000;
                    BSP_CHECK(g <= tol, "%s: piece %d at s=%g coordinate %d off by %.3g > %.3g",
                              c.what, j, s, k, g, tol);
                    worst = fmax(worst, g / tol);
                }
            }
            ++pieces;
        }
        mpfr_clears(t, vb, vw, mb, vs, diff, (mpfr_ptr)0);
        /* Back to a B-spline (continuous curves only: a jump has no shared joint point). */
        int jump = 0;
        for (int i = p + 1; i < n1; ++i)
            jump |= p > 0 && multiplicity(c.knots, n1 + p + 1, c.knots[i]) > p &&
                    c.knots[i] > c.knots[p] && c.knots[i] < c.knots[n1];
        if (p == 0 || jump) continue;
        st = cj_bspline_from_bezier(bp, c.rational ? bw : NULL, br, np, p, c.dim, 0.0, pts2,
                                    c.rational ? w2 : NULL, knots2);
        BSP_CHECK(st == CJ_OK, "%s: from_bezier: %s", c.what, cj_last_error());
        if (st) continue;
        const cj_bspline back =
            cj_bspline_view(p, c.dim, np * p + 1, pts2, c.rational ? w2 : NULL, knots2);
        BSP_CHECK(cj_bspline_check(&back) == CJ_OK, "%s: joined curve invalid", c.what);
        const double g = gap(r, &v, &back, 8);
        const double tol =
            4 * cj_gamma(5 * p + 4) * max_abs(c.pts, n1 * c.dim) * weight_ratio(&v) * (p + 1) +
            0x1p-1000;
        BSP_CHECK(g <= tol, "%s: pieces joined back differ by %.3g > %.3g", c.what, g, tol);
    }
    printf("Bézier pieces: %d pieces of 60 curves (degree 0..8, half NURBS, huge coordinates) "
           "reproduce their spans at 9 parameters each within 4 gamma(5p+4) of the magnitudes "
           "(exact oracles on both sides); largest gap/tolerance %.3g; %d continuous joints "
           "bit-identical; pieces joined back are the same curve\n",
           pieces, worst, joints);
}

static void test_elevate(cj_rng *r) {
    static bsp_case c;
    int cases = 0;
    double worst_err = 0.0;
    for (int rep = 0; rep < 40; ++rep) {
        const int p = cj_rng_int(r, 1, 5), n1 = p + 1 + cj_rng_int(r, 0, 8);
        bsp_generate(r, &c, p, n1, cj_rng_int(r, 1, 3), rep % 2,
                     rep % 2 ? BSP_KNOTS_RANDOM : BSP_KNOTS_UNIFORM, BSP_COORDS_UNIT);
        const cj_bspline v = bsp_view(&c);
        int jump = 0;
        for (int i = p + 1; i < n1; ++i)
            jump |= multiplicity(c.knots, n1 + p + 1, c.knots[i]) > p && c.knots[i] > c.knots[p] &&
                    c.knots[i] < c.knots[n1];
        const int rr = cj_rng_int(r, 1, 3);
        int nout = 0;
        BSP_CHECK(cj_bspline_elevate_count(&v, rr, &nout) == CJ_OK, "%s: count", c.what);
        double err = -1;
        cj_status st = cj_bspline_elevate(&v, rr, pts2, c.rational ? w2 : NULL, knots2, &err);
        if (jump) {
            BSP_CHECK(st == CJ_ERR_ARGUMENT, "%s: elevating a jump gave %d", c.what, st);
            continue;
        }
        BSP_CHECK(st == CJ_OK, "%s: elevate by %d: %s", c.what, rr, cj_last_error());
        if (st) continue;
        const cj_bspline e =
            cj_bspline_view(p + rr, c.dim, nout, pts2, c.rational ? w2 : NULL, knots2);
        BSP_CHECK(cj_bspline_check(&e) == CJ_OK, "%s: elevated curve invalid: %s", c.what,
                  cj_last_error());
        const double g = gap(r, &v, &e, 8);
        const double tol =
            err + 16 * cj_gamma(5 * (p + rr)) * max_abs(c.pts, n1 * c.dim) * weight_ratio(&v) +
            0x1p-1000;
        BSP_CHECK(g <= tol, "%s: elevation by %d moved the curve by %.3g > %.3g (bound %.3g)",
                  c.what, rr, g, tol, err);
        /* the header's claim: rounding units of the coordinates times the weight ratio (the
         * removals divide homogeneous differences by the smallest weight), per removal */
        const double rounding_scale =
            cj_gamma(5 * (p + rr)) * max_abs(c.pts, n1 * c.dim) * weight_ratio(&v);
        BSP_CHECK(err <= 64.0 * n1 * rounding_scale + 0x1p-1000,
                  "%s: elevation removal bound %.3g is %.3g rounding units (x weight ratio)",
                  c.what, err, err / rounding_scale);
        worst_err = fmax(worst_err, err);
        ++cases;
    }
    printf("elevation: %d curves raised by 1..3 degrees stay the same curve (oracle, 10 "
           "parameters each) with the knot multiplicities raised by the same amount; largest "
           "removal bound %.3g\n",
           cases, worst_err);
}

static void test_splines(cj_rng *r) {
    double pts[40 * 3], segs[41 * 4 * 3], knots[42];
    int checked = 0;
    for (int kind = 0; kind < 5; ++kind)
        for (int closed = 0; closed < 2; ++closed) {
            const int n = 9, dim = 3;
            for (int i = 0; i < n * dim; ++i) pts[i] = cj_rng_range(r, -1, 1);
            cj_spline_options o = cj_spline_defaults();
            o.kind = kind == 4 ? CJ_SPLINE_KOCHANEK_BARTELS : (cj_spline_kind)kind;
            if (kind == 3) o.tension = 0.2, o.bias = 0.3;
            if (kind == 4) o.continuity = 0.5;
            o.closed = closed;
            size_t ns = 0;
            cj_status st = cj_catmull_rom(pts, n, dim, &o, segs, 41, &ns, knots);
            BSP_CHECK(st == CJ_OK, "spline kind %d: %s", kind, cj_last_error());
            int nb = 0;
            double err = -1;
            st = cj_bspline_from_spline(pts, n, dim, &o, pts2, knots2, &nb, &err);
            BSP_CHECK(st == CJ_OK, "from_spline kind %d: %s", kind, cj_last_error());
            if (st) continue;
            const int want = kind == 4 ? 3 * (int)ns + 1 : 2 * (int)ns + 2;
            BSP_CHECK(nb == want, "kind %d closed %d: %d B-spline points, expected %d", kind,
                      closed, nb, want);
            const cj_bspline b = cj_bspline_view(3, dim, nb, pts2, NULL, knots2);
            for (size_t s = 0; s < ns; ++s)
                for (int q = 0; q <= 4; ++q) {
                    const double u = q / 4.0;
                    const double t = knots[s] + (knots[s + 1] - knots[s]) * u;
                    double vb[3], vs[3];
                    cj_bezier seg = cj_bezier_view(3, dim, segs + s * 4 * dim);
                    cj_bezier_eval(&seg, CJ_EVAL_DECASTELJAU, u, vs);
                    st = cj_bspline_eval(&b, t, vb);
                    for (int k = 0; k < dim; ++k)
                        BSP_CHECK(st == CJ_OK && fabs(vb[k] - vs[k]) <= 1e-13,
                                  "kind %d closed %d segment %zu u=%g: %.17g vs %.17g", kind,
                                  closed, s, u, vb[k], vs[k]);
                    ++checked;
                }
        }
    printf("splines: uniform, centripetal, chordal, Kochanek-Bartels (C = 0 and C = 0.5), open and "
           "closed, as cubic B-splines: %d points agree with the Bézier segments within 1e-13; C1 "
           "kinds drop one copy of every interior knot (2 nsegs + 2 points), the kinked one keeps "
           "them (3 nsegs + 1)\n",
           checked);
}

static void test_periodic(cj_rng *r) {
    double cyc[12 * 2], w[12], P[20 * 2], W[20], K[30];
    int checked = 0;
    for (int p = 1; p <= 5; ++p)
        for (int rational = 0; rational < 2; ++rational) {
            const int m = 8;
            for (int i = 0; i < m * 2; ++i) cyc[i] = cj_rng_range(r, -1, 1);
            for (int i = 0; i < m; ++i) w[i] = cj_rng_range(r, 0.5, 2);
            cj_status st =
                cj_bspline_periodic(cyc, rational ? w : NULL, m, 2, p, P, rational ? W : NULL, K);
            BSP_CHECK(st == CJ_OK, "periodic p=%d: %s", p, cj_last_error());
            const cj_bspline c = cj_bspline_view(p, 2, m + p, P, rational ? W : NULL, K);
            double t0, t1, d0[12 * 2], d1[12 * 2];
            cj_bspline_domain(&c, &t0, &t1);
            BSP_CHECK(t0 == 0.0 && t1 == m, "periodic domain [%g, %g]", t0, t1);
            cj_bspline_eval_derivs(&c, t0, p - 1, d0);
            cj_bspline_eval_derivs(&c, t1, p - 1, d1);
            for (int j = 0; j < p * 2; ++j)
                BSP_CHECK(fabs(d0[j] - d1[j]) <= 1e-12 * (1 + fabs(d0[j])),
                          "periodic p=%d %s: derivative %d differs at the seam: %.17g vs %.17g", p,
                          rational ? "NURBS" : "poly", j / 2, d0[j], d1[j]);
            checked += p;
        }
    double U[20];
    BSP_CHECK(cj_bspline_uniform_knots(7, 3, 0.0, 2.0, 0, U) == CJ_OK && U[3] == 0.0 && U[7] == 2.0,
              "unclamped uniform knots: domain [%g, %g]", U[3], U[7]);
    BSP_CHECK(cj_bspline_uniform_knots(7, 3, 0.0, 2.0, 1, U) == CJ_OK && U[0] == 0.0 &&
                  U[3] == 0.0 && U[10] == 2.0 && U[4] == 0.5,
              "clamped uniform knots");
    printf("periodic: closed curves of degree 1..5 (polynomial and NURBS) match in value and %d "
           "derivatives of orders < p at the seam; uniform clamped/unclamped knot vectors have "
           "the asked domain\n",
           checked);
}

static void test_refusals(void) {
    double pts[] = {0, 0, 1, 1, 2, 0, 3, 1, 4, 0};
    double knots[] = {0, 0, 0, 1, 2, 3, 3, 3};
    const cj_bspline c = cj_bspline_view(2, 2, 5, pts, NULL, knots);
    cj_status st = cj_bspline_insert_knot(&c, 1.0, 2, out_pts, NULL, out_knots);
    BSP_CHECK(st == CJ_ERR_ARGUMENT && strstr(cj_last_error(), "multiplicity"),
              "insertion above the degree: %d %s", st, cj_last_error());
    st = cj_bspline_insert_knot(&c, 4.0, 1, out_pts, NULL, out_knots);
    BSP_CHECK(st == CJ_ERR_RANGE, "insertion outside the domain: %d", st);
    double w[5] = {1, 1, 1, 1, 1};
    st = cj_bspline_insert_knot(&c, 1.5, 1, out_pts, w, out_knots);
    BSP_CHECK(st == CJ_ERR_ARGUMENT && strstr(cj_last_error(), "weights"),
              "weights for a polynomial curve: %d", st);
    int removed;
    st = cj_bspline_remove_knot(&c, 1.5, 1, 1.0, out_pts, NULL, out_knots, &removed, NULL);
    BSP_CHECK(st == CJ_ERR_ARGUMENT && strstr(cj_last_error(), "1.5"), "removing a missing knot");
    st = cj_bspline_remove_knot(&c, 0.0, 1, 1.0, out_pts, NULL, out_knots, &removed, NULL);
    BSP_CHECK(st == CJ_ERR_RANGE, "removing an end knot: %d", st);
    st = cj_bspline_remove_knot(&c, 1.0, 1, -1.0, out_pts, NULL, out_knots, &removed, NULL);
    BSP_CHECK(st == CJ_ERR_ARGUMENT, "negative tolerance: %d", st);
    double bez[] = {0, 0, 1, 1, 2, 0, 2.5, 0, 3, 1, 4, 0};
    double br[] = {0, 1, 2};
    st = cj_bspline_from_bezier(bez, NULL, br, 2, 2, 2, 0.0, out_pts, NULL, out_knots);
    BSP_CHECK(st == CJ_ERR_ARGUMENT && strstr(cj_last_error(), "pieces 0 and 1"),
              "pieces that do not meet: %d %s", st, cj_last_error());
    st = cj_bspline_from_bezier(bez, NULL, br, 2, 2, 2, 0.5, out_pts, NULL, out_knots);
    BSP_CHECK(st == CJ_OK, "pieces within the join tolerance: %s", cj_last_error());
    br[1] = 0.0;
    st = cj_bspline_from_bezier(bez, NULL, br, 2, 2, 2, 0.5, out_pts, NULL, out_knots);
    BSP_CHECK(st == CJ_ERR_ARGUMENT && strstr(cj_last_error(), "breaks 0 and 1"),
              "breaks that do not increase: %s", cj_last_error());
    double sp[] = {0, 0, 1, 1, 1, 1, 2, 0};
    cj_spline_options o = cj_spline_defaults();
    o.kind = CJ_SPLINE_CENTRIPETAL;
    int nb;
    st = cj_bspline_from_spline(sp, 4, 2, &o, out_pts, out_knots, &nb, NULL);
    BSP_CHECK(st == CJ_ERR_DEGENERATE, "centripetal spline with repeated points: %d", st);
    printf("refusals: insertion above the degree or outside the domain, weights for a polynomial, "
           "removing a missing or end knot, negative tolerance, pieces that do not meet, breaks "
           "that do not increase, repeated points in a centripetal spline\n");
}

int main(void) {
    const uint64_t seed = cj_test_seed("test_bspline_ops", 22);
    cj_rng r;
    cj_rng_init(&r, seed);
    test_insert_refine(&r);
    test_removal(&r);
    test_bezier_pieces(&r);
    test_elevate(&r);
    test_splines(&r);
    test_periodic(&r);
    test_refusals();
    mpfr_free_cache();
    if (bsp_failures) {
        printf("%d failure(s)\n", bsp_failures);
        return 1;
    }
    printf("test_bspline_ops: all checks passed\n");
    return 0;
}

/* B-spline and NURBS evaluation against the MPFR oracle (Cox–de Boor basis functions at 2300
 * bits): the de Boor value is always within cj_bspline_error_bound of the exact value, on random
 * and adversarial curves (repeated knots, tiny spans, high degree, huge, tiny and mixed
 * coordinates); derivatives of every order within a stated multiple of their magnitude; and
 * every kind of bad input refused with a message naming it. */
#include "bsp_test.h"
#include "oracle_bspline.h"

#include "casteljau/bspline.h"
#include "casteljau/status.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

static const double U = 0x1p-53;

static cj_obsp oracle_of(const bsp_case *c) {
    cj_obsp o = {c->p, c->dim, c->n1, c->pts, c->rational ? c->w : NULL, c->knots};
    return o;
}

/* Value and bound against the oracle at many parameters; returns the largest error/bound. */
static double check_value(cj_rng *r, const bsp_case *c, int nparams, long *checked) {
    const cj_bspline v = bsp_view(c);
    const cj_obsp o = oracle_of(c);
    double worst = 0.0;
    for (int j = 0; j < nparams; ++j) {
        const double t = bsp_param(r, c);
        double val[8], bound[8];
        cj_status st = cj_bspline_eval(&v, t, val);
        BSP_CHECK(st == CJ_OK, "%s: eval at %.17g: %s", c->what, t, cj_last_error());
        if (st) return INFINITY;
        st = cj_bspline_error_bound(&v, t, bound);
        BSP_CHECK(st == CJ_OK, "%s: bound at %.17g: %s", c->what, t, cj_last_error());
        if (st) return INFINITY;
        for (int k = 0; k < c->dim; ++k) {
            double mag;
            const double err = cj_obsp_abs_error(&o, k, t, val[k], &mag);
            /* The oracle's own radius, ~4(p+1)^2 2^-2300 of the magnitude, is below any double. */
            BSP_CHECK(err <= bound[k], "%s: t=%.17g coordinate %d error %.3g above bound %.3g",
                      c->what, t, k, err, bound[k]);
            if (bound[k] > 0x1p-1000 && err / bound[k] > worst) worst = err / bound[k];
            ++*checked;
        }
    }
    return worst;
}

static void test_values(cj_rng *r) {
    long checked = 0;
    double worst = 0.0;
    static bsp_case c;
    for (int rep = 0; rep < 160; ++rep) {
        const int p = rep % 4 == 3 ? cj_rng_int(r, 12, CJ_BSPLINE_MAX_DEGREE) : cj_rng_int(r, 0, 7);
        const int n1 = p + 1 + cj_rng_int(r, 0, p > 12 ? 6 : 20);
        const int dim = cj_rng_int(r, 1, 4);
        bsp_generate(r, &c, p, n1, dim, rep % 3 == 1, rep % BSP_KNOTS_KINDS,
                     (rep / BSP_KNOTS_KINDS) % BSP_COORDS_KINDS);
        const double wr = check_value(r, &c, p > 12 ? 3 : 8, &checked);
        if (wr > worst) worst = wr;
    }
    printf("values: %ld coordinates on 160 curves (degree 0..%d, repeated/tiny/uniform knots, "
           "huge/tiny/mixed coordinates, 1/3 NURBS) within cj_bspline_error_bound; largest "
           "error/bound %.3g (bounds above 2^-1000)\n",
           checked, CJ_BSPLINE_MAX_DEGREE, worst);
}

/* An ill-conditioned case: the value cancels (points alternate in sign), so the bound must
 * come from the magnitude, not the value. */
static void test_cancellation(void) {
    bsp_case c;
    memset(&c, 0, sizeof c);
    c.p = 5;
    c.n1 = 12;
    c.dim = 1;
    for (int i = 0; i < c.n1; ++i) c.pts[i] = (i % 2 ? -1.0 : 1.0) * (1.0 + i * 0x1p-30);
    for (int i = 0; i < c.n1 + c.p + 1; ++i) c.knots[i] = i * 0.1;
    snprintf(c.what, sizeof c.what, "alternating points");
    cj_rng r;
    cj_rng_init(&r, 7);
    long checked = 0;
    const double worst = check_value(&r, &c, 40, &checked);
    printf("cancellation: %ld values of an alternating-sign spline within the bound (largest "
           "error/bound %.3g)\n",
           checked, worst);
}

static void test_derivs(cj_rng *r) {
    static bsp_case c;
    long checked = 0, nurbs_checked = 0;
    double nurbs_loose = 0.0;
    double worst = 0.0;
    for (int rep = 0; rep < 120; ++rep) {
        const int p = cj_rng_int(r, 0, 9), n1 = p + 1 + cj_rng_int(r, 0, 12);
        const int rational = rep % 3 == 2;
        bsp_generate(r, &c, p, n1, cj_rng_int(r, 1, 3), rational,
                     rep % BSP_KNOTS_KINDS == 2 ? 0 : rep % BSP_KNOTS_KINDS, BSP_COORDS_UNIT);
        const cj_bspline v = bsp_view(&c);
        const cj_obsp o = oracle_of(&c);
        const int kmax = p + 2;
        for (int j = 0; j < 4; ++j) {
            const double t = bsp_param(r, &c);
            double out[(CJ_BSPLINE_MAX_DERIV + 1) * 8], bnd[(CJ_BSPLINE_MAX_DERIV + 1) * 8];
            cj_status st = cj_bspline_eval_derivs(&v, t, kmax, out);
            BSP_CHECK(st == CJ_OK, "%s: derivs at %.17g: %s", c.what, t, cj_last_error());
            if (st) continue;
            st = cj_bspline_derivs_error_bound(&v, t, kmax, bnd);
            BSP_CHECK(st == CJ_OK, "%s: derivative bound: %s", c.what, cj_last_error());
            mpfr_t val[16], mag[16], tt, e;
            mpfr_inits2(64, tt, e, (mpfr_ptr)0);
            mpfr_set_prec(tt, 64);
            mpfr_set_d(tt, t, MPFR_RNDN);
            for (int q = 0; q <= kmax; ++q) mpfr_inits2(64, val[q], mag[q], (mpfr_ptr)0);
            for (int k = 0; k < c.dim; ++k) {
                cj_obsp_eval(&o, k, tt, kmax, val, rational ? NULL : mag);
                for (int q = 0; q <= kmax; ++q) {
                    mpfr_set_prec(e, CJ_ORACLE_BSP_PREC);
                    mpfr_sub_d(e, val[q], out[q * c.dim + k], MPFR_RNDN);
                    mpfr_abs(e, e, MPFR_RNDN);
                    const double err = mpfr_get_d(e, MPFR_RNDU);
                    /* Polynomial: every difference rounds relatively to the magnitudes it
                     * combines, so the error is a rounding multiple of Σ m^(q) N; NURBS: the
                     * quotient rule mixes orders, measured relative to the size of the value and
                     * of the lower orders. */
                    /* Polynomial: the published bound (cj_bspline_derivs_error_bound), checked
                     * also against the oracle's own magnitude Σ m^(q) N; NURBS: the quotient rule
                     * mixes orders, measured relative to the value and the lower orders. */
                    double tol;
                    if (!rational) {
                        tol = bnd[q * c.dim + k];
                        const double m = mpfr_get_d(mag[q], MPFR_RNDU);
                        BSP_CHECK(q > p || tol >= cj_gamma(5 * p - q) * m,
                                  "%s: order %d bound %.3g below gamma(5p-q) M = %.3g", c.what, q,
                                  tol, cj_gamma(5 * p - q) * m);
                    } else {
                        /* the NURBS bound, and how far it is from the error (reported) */
                        tol = bnd[q * c.dim + k];
                        double scale = 0.0;
                        for (int i = 0; i <= q; ++i)
                            scale = fmax(scale, fabs(mpfr_get_d(val[i], MPFR_RNDN)));
                        if (scale > 0 && tol / (U * scale) > nurbs_loose)
                            nurbs_loose = tol / (U * scale);
                        ++nurbs_checked;
                    }
                    BSP_CHECK(err <= tol, "%s: t=%.17g order %d coordinate %d error %.3g > %.3g",
                              c.what, t, q, k, err, tol);
                    if (tol > 0 && err / tol > worst) worst = err / tol;
                    ++checked;
                }
            }
            for (int q = 0; q <= kmax; ++q) mpfr_clears(val[q], mag[q], (mpfr_ptr)0);
            mpfr_clears(tt, e, (mpfr_ptr)0);
        }
    }
    printf("derivatives: %ld values of orders 0..p+2 (above p they are zero) on 120 curves agree "
           "with the oracle within cj_bspline_derivs_error_bound: polynomial (gamma(5p-q) "
           "Σ m^(q) N, m^(q) the differences of magnitudes) and NURBS (%ld values, the quotient "
           "rule's recurrence; its bound is at most %.3g u max|c^(0..q)|); largest "
           "error/bound %.3g\n",
           checked, nurbs_checked, nurbs_loose, worst);
}

/* The batch and unchecked entry points give exactly what the checked calls give. */
static void test_unchecked(cj_rng *r) {
    static bsp_case c;
    int n = 0;
    for (int rep = 0; rep < 40; ++rep) {
        const int p = cj_rng_int(r, 0, 8);
        bsp_generate(r, &c, p, p + 1 + cj_rng_int(r, 0, 12), cj_rng_int(r, 1, 4), rep % 2,
                     rep % BSP_KNOTS_KINDS, BSP_COORDS_UNIT);
        const cj_bspline v = bsp_view(&c);
        double ts[16], batch[16 * 8];
        for (int j = 0; j < 16; ++j) ts[j] = bsp_param(r, &c);
        BSP_CHECK(cj_bspline_eval_batch(&v, ts, 16, batch) == CJ_OK, "%s: batch: %s", c.what,
                  cj_last_error());
        for (int j = 0; j < 16; ++j) {
            double a[8], b[8], da[(CJ_BSPLINE_MAX_DERIV + 1) * 8],
                db[(CJ_BSPLINE_MAX_DERIV + 1) * 8];
            cj_bspline_eval(&v, ts[j], a);
            cj_bspline_eval_unchecked(&v, ts[j], b);
            cj_bspline_eval_derivs(&v, ts[j], p + 1, da);
            cj_bspline_eval_derivs_unchecked(&v, ts[j], p + 1, db);
            BSP_CHECK(!memcmp(a, b, sizeof(double) * (size_t)c.dim) &&
                          !memcmp(a, batch + j * c.dim, sizeof(double) * (size_t)c.dim) &&
                          !memcmp(da, db, sizeof(double) * (size_t)((p + 2) * c.dim)),
                      "%s: t=%.17g: unchecked or batch results differ from the checked ones",
                      c.what, ts[j]);
            ++n;
        }
    }
    const cj_bspline v = bsp_view(&c);
    double t_bad[2] = {c.knots[c.p], 1e300};
    double out[16];
    BSP_CHECK(cj_bspline_eval_batch(&v, t_bad, 2, out) == CJ_ERR_RANGE &&
                  strstr(cj_last_error(), "parameter 1"),
              "batch with a parameter outside the domain: %s", cj_last_error());
    printf("unchecked: %d evaluations: cj_bspline_eval_batch, _unchecked and "
           "_derivs_unchecked are bit-identical to the checked calls; a bad batch parameter is "
           "named\n",
           n);
}

static void expect(cj_status got, cj_status want, const char *needle, const char *what) {
    BSP_CHECK(got == want, "%s: status %d, expected %d (%s)", what, got, want, cj_last_error());
    if (got != CJ_OK && needle)
        BSP_CHECK(strstr(cj_last_error(), needle) != NULL, "%s: message \"%s\" lacks \"%s\"", what,
                  cj_last_error(), needle);
}

static void test_bad_input(void) {
    double pts[] = {0, 0, 1, 1, 2, 0, 3, 1, 4, 0};
    double w[] = {1, 1, 1, 1, 1};
    double knots[] = {0, 0, 0, 1, 2, 3, 3, 3};
    double out[8];
    cj_bspline c = cj_bspline_view(2, 2, 5, pts, NULL, knots);
    expect(cj_bspline_check(&c), CJ_OK, NULL, "valid curve");
    knots[4] = 0.5;
    expect(cj_bspline_check(&c), CJ_ERR_ARGUMENT, "knot 4", "decreasing knots");
    knots[4] = 2;
    double k2[] = {0, 0, 0, 1, 1, 1, 1, 3};
    c.knots = k2;
    expect(cj_bspline_check(&c), CJ_ERR_ARGUMENT, "multiplicity 4", "multiplicity degree + 2");
    c.knots = knots;
    c.weights = w;
    w[2] = 0.0;
    expect(cj_bspline_check(&c), CJ_ERR_ARGUMENT, "weight 2", "zero weight");
    w[2] = -1.0;
    expect(cj_bspline_check(&c), CJ_ERR_ARGUMENT, "weight 2", "negative weight");
    w[2] = NAN;
    expect(cj_bspline_check(&c), CJ_ERR_NONFINITE, "weight 2", "NaN weight");
    w[2] = 1.0;
    pts[7] = NAN;
    expect(cj_bspline_eval(&c, 1.0, out), CJ_ERR_NONFINITE, "control point 3", "NaN point");
    pts[7] = 1.0;
    knots[5] = INFINITY;
    expect(cj_bspline_check(&c), CJ_ERR_NONFINITE, "knot 5", "infinite knot");
    knots[5] = 3.0;
    c.npts = 2;
    expect(cj_bspline_check(&c), CJ_ERR_EMPTY, "too few", "too few points");
    c.npts = 5;
    expect(cj_bspline_eval(&c, 3.5, out), CJ_ERR_RANGE, "outside the domain", "t beyond domain");
    expect(cj_bspline_eval(&c, NAN, out), CJ_ERR_NONFINITE, "parameter", "NaN parameter");
    expect(cj_bspline_eval_derivs(&c, 1.0, -1, out), CJ_ERR_ARGUMENT, "order", "negative order");
    c.degree = CJ_BSPLINE_MAX_DEGREE + 1;
    expect(cj_bspline_check(&c), CJ_ERR_DEGREE, "degree", "degree above the limit");
    c.degree = 2;
    c.dim = CJ_MAX_DIM;
    expect(cj_bspline_check(&c), CJ_ERR_DIMENSION, "NURBS dimension", "NURBS dimension 8");
    c.dim = 2;
    double flat[] = {0, 0, 0, 0, 0, 0, 0, 0};
    c.knots = flat;
    expect(cj_bspline_check(&c), CJ_ERR_ARGUMENT, "multiplicity", "all knots equal");
    double flat2[] = {0, 0, 0, 1, 1, 1, 5, 5};
    c.npts = 3;
    c.knots = flat2;
    expect(cj_bspline_check(&c), CJ_OK, NULL, "clamped Bézier-like");
    double flat3[] = {0, 1, 1, 1, 1, 2};
    c.knots = flat3;
    c.degree = 2;
    c.npts = 3;
    expect(cj_bspline_check(&c), CJ_ERR_ARGUMENT, "multiplicity", "empty domain by repeats");
    printf("bad input: decreasing knots, multiplicity above p+1, weights 0/-1/NaN, NaN point, "
           "infinite knot, too few points, t outside the domain, NaN t, negative order, degree "
           "and dimension limits refused with messages naming the input\n");
}

int main(void) {
    const uint64_t seed = cj_test_seed("test_bspline_eval", 20261126);
    cj_rng r;
    cj_rng_init(&r, seed);
    test_values(&r);
    test_cancellation();
    test_derivs(&r);
    test_unchecked(&r);
    test_bad_input();
    mpfr_free_cache();
    if (bsp_failures) {
        printf("%d failure(s)\n", bsp_failures);
        return 1;
    }
    printf("test_bspline_eval: all checks passed\n");
    return 0;
}

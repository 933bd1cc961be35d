/* Rational Bézier curves: evaluation and derivatives against an MPFR oracle (direct Bernstein
 * sums and the quotient rule at 256 bits), exact circle/ellipse arcs, subdivision, weights. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "casteljau/bezier.h"
#include "casteljau/rational.h"
#include "rng.h"

#include <math.h>
#include <mpfr.h>
#include <stdio.h>
#include <string.h>

#define PREC 256
#define PI   3.14159265358979323846

/* MPFR oracle: value, first and second derivative of coordinate k at t, by Bernstein sums of
 * the numerator N = Σ w_i b_i B_i and denominator W = Σ w_i B_i and their hodographs. */
static void bern_sum(const mpfr_t *c, int n, mpfr_t t, mpfr_t out) {
    mpfr_t s, term, omt, binom;
    mpfr_inits2(PREC, s, term, omt, binom, (mpfr_ptr)0);
    mpfr_set_ui(s, 0, MPFR_RNDN);
    mpfr_ui_sub(omt, 1, t, MPFR_RNDN);
    mpfr_set_ui(binom, 1, MPFR_RNDN);
    for (int i = 0; i <= n; ++i) {
        mpfr_pow_ui(term, t, (unsigned long)i, MPFR_RNDN);
        mpfr_mul(term, term, binom, MPFR_RNDN);
        mpfr_t p;
        mpfr_init2(p, PREC);
        mpfr_pow_ui(p, omt, (unsigned long)(n - i), MPFR_RNDN);
        mpfr_mul(term, term, p, MPFR_RNDN);
        mpfr_clear(p);
        mpfr_mul(term, term, c[i], MPFR_RNDN);
        mpfr_add(s, s, term, MPFR_RNDN);
        mpfr_mul_ui(binom, binom, (unsigned long)(n - i), MPFR_RNDN);
        mpfr_div_ui(binom, binom, (unsigned long)(i + 1), MPFR_RNDN);
    }
    mpfr_set(out, s, MPFR_RNDN);
    mpfr_clears(s, term, omt, binom, (mpfr_ptr)0);
}

/* Derivatives 0..2 of Σ c_i B_i^n at t (hodographs by differences, exact in MPFR). */
static void bern_derivs(const mpfr_t *c, int n, mpfr_t t, mpfr_t d[3]) {
    mpfr_t h[64];
    for (int i = 0; i <= n; ++i) {
        mpfr_init2(h[i], PREC);
        mpfr_set(h[i], c[i], MPFR_RNDN);
    }
    int m = n;
    for (int order = 0; order < 3; ++order) {
        if (m < 0)
            mpfr_set_ui(d[order], 0, MPFR_RNDN);
        else
            bern_sum((const mpfr_t *)h, m, t, d[order]);
        if (m >= 1)
            for (int i = 0; i < m; ++i) {
                mpfr_sub(h[i], h[i + 1], h[i], MPFR_RNDN);
                mpfr_mul_ui(h[i], h[i], (unsigned long)m, MPFR_RNDN);
            }
        --m;
    }
    for (int i = 0; i <= n; ++i) mpfr_clear(h[i]);
}

/* out[0..2] = c, c', c'' of coordinate k (rounded to double). */
static void oracle(const cj_rbezier *c, int k, double tt, double out[3]) {
    const int n = c->degree;
    mpfr_t num[64], den[64], t, N[3], W[3], c0, c1, c2, tmp;
    for (int i = 0; i <= n; ++i) {
        mpfr_inits2(PREC, num[i], den[i], (mpfr_ptr)0);
        mpfr_set_d(den[i], c->weights[i], MPFR_RNDN);
        mpfr_set_d(num[i], c->pts[i * c->dim + k], MPFR_RNDN);
        mpfr_mul(num[i], num[i], den[i], MPFR_RNDN);
    }
    mpfr_inits2(PREC, t, N[0], N[1], N[2], W[0], W[1], W[2], c0, c1, c2, tmp, (mpfr_ptr)0);
    mpfr_set_d(t, tt, MPFR_RNDN);
    bern_derivs((const mpfr_t *)num, n, t, N);
    bern_derivs((const mpfr_t *)den, n, t, W);
    mpfr_div(c0, N[0], W[0], MPFR_RNDN); /* c = N/W */
    mpfr_mul(tmp, W[1], c0, MPFR_RNDN);  /* c' = (N' - W'c)/W */
    mpfr_sub(c1, N[1], tmp, MPFR_RNDN);
    mpfr_div(c1, c1, W[0], MPFR_RNDN);
    mpfr_mul(tmp, W[1], c1, MPFR_RNDN); /* c'' = (N'' - 2W'c' - W''c)/W */
    mpfr_mul_ui(tmp, tmp, 2, MPFR_RNDN);
    mpfr_sub(c2, N[2], tmp, MPFR_RNDN);
    mpfr_mul(tmp, W[2], c0, MPFR_RNDN);
    mpfr_sub(c2, c2, tmp, MPFR_RNDN);
    mpfr_div(c2, c2, W[0], MPFR_RNDN);
    out[0] = mpfr_get_d(c0, MPFR_RNDN);
    out[1] = mpfr_get_d(c1, MPFR_RNDN);
    out[2] = mpfr_get_d(c2, MPFR_RNDN);
    for (int i = 0; i <= n; ++i) mpfr_clears(num[i], den[i], (mpfr_ptr)0);
    mpfr_clears(t, N[0], N[1], N[2], W[0], W[1], W[2], c0, c1, c2, tmp, (mpfr_ptr)0);
}

static void random_curve(cj_rng *r, int n, int dim, double *pts, double *w) {
    for (int i = 0; i <= n; ++i) {
        for (int k = 0; k < dim; ++k) pts[i * dim + k] = cj_rng_range(r, -10, 10);
        w[i] = exp(cj_rng_range(r, log(0.2), log(5.0)));
    }
}

static void test_eval_derivs_vs_mpfr(void **state) {
    (void)state;
    cj_rng rng;
    cj_rng_init(&rng, cj_test_seed("test_rational/mpfr", 3201));
    double worst[3] = {0, 0, 0};
    for (int cas = 0; cas < 300; ++cas) {
        const int n = cj_rng_int(&rng, 1, 12), dim = cj_rng_int(&rng, 1, 3);
        double pts[13 * 3], w[13];
        random_curve(&rng, n, dim, pts, w);
        cj_rbezier c = cj_rbezier_view(n, dim, pts, w);
        for (int q = 0; q < 8; ++q) {
            const double t = q == 0 ? 0.0 : q == 1 ? 1.0 : cj_rng_unit(&rng);
            double d[3 * 3], p[3];
            assert_int_equal(cj_rbezier_eval_derivs(&c, t, 2, d), CJ_OK);
            assert_int_equal(cj_rbezier_eval(&c, t, p), CJ_OK);
            for (int k = 0; k < dim; ++k) {
                double o[3];
                oracle(&c, k, t, o);
                /* scale: control-point size times n^order times the weight ratio^(order+1) */
                double wr = 1;
                for (int i = 0; i <= n; ++i)
                    for (int j = 0; j <= n; ++j) wr = fmax(wr, w[i] / w[j]);
                for (int j = 0; j < 3; ++j) {
                    const double sc = 10.0 * pow(n * wr, j) * wr;
                    const double e = fabs(d[j * dim + k] - o[j]) / sc;
                    worst[j] = fmax(worst[j], e);
                    if (e > 1e-13)
                        fail_msg("case %d n=%d t=%.17g order %d coord %d: %.17g vs oracle %.17g",
                                 cas, n, t, j, k, d[j * dim + k], o[j]);
                }
                assert_true(fabs(p[k] - o[0]) <= 1e-13 * 10 * wr);
            }
        }
    }
    printf("rational eval/derivatives vs MPFR (256-bit Bernstein sums + quotient rule), 300 "
           "curves deg 1..12: worst scaled error c %.1e, c' %.1e, c'' %.1e\n",
           worst[0], worst[1], worst[2]);
}

static void test_circle_arcs_exact(void **state) {
    (void)state;
    cj_rng rng;
    cj_rng_init(&rng, cj_test_seed("test_rational/circle", 3202));
    double worst = 0;
    for (int cas = 0; cas < 200; ++cas) {
        const double cx = cj_rng_range(&rng, -5, 5), cy = cj_rng_range(&rng, -5, 5);
        const double r = cj_rng_range(&rng, 0.1, 10);
        const double a0 = cj_rng_range(&rng, -7, 7), sweep = cj_rng_range(&rng, -3.1, 3.1);
        if (fabs(sweep) < 1e-3) continue;
        double pts[6], w[3];
        assert_int_equal(cj_rbezier_ellipse_arc(cx, cy, r, r, 0.0, a0, a0 + sweep, pts, w), CJ_OK);
        cj_rbezier c = cj_rbezier_view(2, 2, pts, w);
        for (int q = 0; q <= 1000; ++q) {
            double p[2];
            assert_int_equal(cj_rbezier_eval(&c, q / 1000.0, p), CJ_OK);
            const double e = fabs(hypot(p[0] - cx, p[1] - cy) - r) / (r + fabs(cx) + fabs(cy));
            worst = fmax(worst, e);
            if (e > 1e-14) fail_msg("case %d q %d: distance error %g", cas, q, e);
        }
        double mid[2]; /* t = 1/2 is the angle midpoint */
        cj_rbezier_eval(&c, 0.5, mid);
        const double am = a0 + sweep / 2;
        assert_true(fabs(mid[0] - (cx + r * cos(am))) <= 1e-13 * (r + 10));
        assert_true(fabs(mid[1] - (cy + r * sin(am))) <= 1e-13 * (r + 10));
    }
    printf("circle arcs (sweep < pi): 200 arcs x 1001 points on the circle, worst relative "
           "radius error %.2e\n",
           worst);
}

static void test_full_ellipse(void **state) {
    (void)state;
    const double cx = 1.5, cy = -2, rx = 3, ry = 0.75, rot = 0.6;
    double pts[4 * 6], w[4 * 3];
    int np = 0;
    assert_int_equal(
        cj_rbezier_ellipse_arcs(cx, cy, rx, ry, rot, 0.3, 0.3 + 2 * PI, pts, w, 4, &np), CJ_OK);
    assert_int_equal(np, 4);
    double worst = 0;
    for (int k = 0; k < np; ++k) {
        cj_rbezier c = cj_rbezier_view(2, 2, pts + 6 * k, w + 3 * k);
        const double *nx = pts + 6 * ((k + 1) % np);
        assert_memory_equal(pts + 6 * k + 4, nx, 2 * sizeof(double)); /* shared end points */
        for (int q = 0; q <= 500; ++q) {
            double p[2];
            cj_rbezier_eval(&c, q / 500.0, p);
            const double dx = p[0] - cx, dy = p[1] - cy;
            const double u = cos(rot) * dx + sin(rot) * dy, v = -sin(rot) * dx + cos(rot) * dy;
            const double f = (u / rx) * (u / rx) + (v / ry) * (v / ry) - 1;
            worst = fmax(worst, fabs(f));
            assert_true(fabs(f) < 1e-14);
        }
        /* C1 at the joint: equal sweeps and standard weights give equal derivatives */
        double d0[4], d1[4];
        cj_rbezier c1 = cj_rbezier_view(2, 2, nx, w + 3 * ((k + 1) % np));
        cj_rbezier_eval_derivs(&c, 1.0, 1, d0);
        cj_rbezier_eval_derivs(&c1, 0.0, 1, d1);
        assert_true(fabs(d0[2] - d1[2]) < 1e-13 && fabs(d0[3] - d1[3]) < 1e-13);
    }
    assert_int_equal(cj_rbezier_arc_pieces(0, 2 * PI), 4);
    assert_int_equal(cj_rbezier_arc_pieces(0, PI / 2), 1);
    assert_int_equal(cj_rbezier_arc_pieces(0, -3), 2);
    assert_int_equal(cj_rbezier_arc_pieces(0, 7), 0);
    assert_int_equal(cj_rbezier_ellipse_arcs(cx, cy, rx, ry, rot, 0, 2 * PI, pts, w, 3, &np),
                     CJ_ERR_BUFFER);
    printf("full rotated ellipse as 4 rational quadratics: closed bit-exactly, C1 joints, max "
           "|implicit| %.2e\n",
           worst);
}

static void test_split_and_weights(void **state) {
    (void)state;
    cj_rng rng;
    cj_rng_init(&rng, cj_test_seed("test_rational/split", 3203));
    for (int cas = 0; cas < 200; ++cas) {
        const int n = cj_rng_int(&rng, 1, 9), dim = cj_rng_int(&rng, 1, 3);
        double pts[10 * 3], w[10], lp[30], lw[10], rp[30], rw[10];
        random_curve(&rng, n, dim, pts, w);
        cj_rbezier c = cj_rbezier_view(n, dim, pts, w);
        const double t = cj_rng_unit(&rng);
        assert_int_equal(cj_rbezier_split(&c, t, lp, lw, rp, rw), CJ_OK);
        assert_memory_equal(lp + n * dim, rp, sizeof(double) * (size_t)dim);
        cj_rbezier L = cj_rbezier_view(n, dim, lp, lw), R = cj_rbezier_view(n, dim, rp, rw);
        for (int q = 0; q <= 10; ++q) {
            const double s = q / 10.0;
            double a[3], b[3], x[3], y[3];
            cj_rbezier_eval(&L, s, a);
            cj_rbezier_eval(&c, t * s, x);
            cj_rbezier_eval(&R, s, b);
            cj_rbezier_eval(&c, t + (1 - t) * s, y);
            for (int k = 0; k < dim; ++k) {
                if (fabs(a[k] - x[k]) > 1e-13 * 10 || fabs(b[k] - y[k]) > 1e-13 * 10)
                    fail_msg("case %d n=%d t=%g s=%g", cas, n, t, s);
            }
        }
        /* normalised weights: end weights exactly 1, same curve */
        double nw[10];
        assert_int_equal(cj_rbezier_normalize_weights(&c, nw), CJ_OK);
        assert_true(nw[0] == 1.0 && nw[n] == 1.0);
        /* Scaling w_i by rho^i is the reparametrisation t/(1-t) = rho u/(1-u): the
         * normalised curve at u is the original at t = rho u / ((1 - u) + rho u). */
        const double rho = pow(w[0] / w[n], 1.0 / n);
        cj_rbezier Nc = cj_rbezier_view(n, dim, pts, nw);
        for (int q = 1; q < 10; ++q) {
            const double u = q / 10.0;
            const double s = rho * u / ((1 - u) + rho * u);
            double a[3], b[3];
            cj_rbezier_eval(&Nc, u, a);
            cj_rbezier_eval(&c, s, b);
            for (int k = 0; k < dim; ++k)
                if (fabs(a[k] - b[k]) > 1e-12 * 10) fail_msg("normalize case %d u=%g", cas, u);
        }
    }
    /* equal weights: the polynomial curve */
    const double p[] = {0, 0, 1, 3, 4, -1, 5, 2}, ones[] = {2, 2, 2, 2};
    cj_rbezier c = cj_rbezier_view(3, 2, p, ones);
    cj_bezier b = cj_bezier_view(3, 2, p);
    double x[2], y[2];
    cj_rbezier_eval(&c, 0.3, x);
    cj_bezier_eval_decasteljau(&b, 0.3, y);
    assert_true(fabs(x[0] - y[0]) < 1e-15 * 8 && fabs(x[1] - y[1]) < 1e-15 * 8);
    printf("rational split (200 random, halves trace the curve, shared point bit-identical) and "
           "weight normalisation\n");
}

static void test_errors(void **state) {
    (void)state;
    double p[] = {0, 0, 1, 1, 2, 0}, w[] = {1, 0, 1}, out[6], ow[3];
    cj_rbezier c = cj_rbezier_view(2, 2, p, w);
    assert_int_equal(cj_rbezier_eval(&c, 0.5, out), CJ_ERR_ARGUMENT);
    assert_non_null(strstr(cj_last_error(), "weight 1"));
    w[1] = NAN;
    assert_int_equal(cj_rbezier_eval(&c, 0.5, out), CJ_ERR_NONFINITE);
    w[1] = 1;
    c.dim = CJ_MAX_DIM;
    assert_int_equal(cj_rbezier_eval(&c, 0.5, out), CJ_ERR_DIMENSION);
    c.dim = 2;
    assert_int_equal(cj_rbezier_split(&c, 1.5, out, ow, NULL, NULL), CJ_ERR_RANGE);
    assert_int_equal(cj_rbezier_eval(&c, NAN, out), CJ_ERR_NONFINITE);
    assert_int_equal(cj_rbezier_eval_derivs(&c, 0.5, -1, out), CJ_ERR_ARGUMENT);
    assert_int_equal(cj_rbezier_ellipse_arc(0, 0, 1, 1, 0, 0, PI, p, ow), CJ_ERR_RANGE);
    assert_int_equal(cj_rbezier_ellipse_arc(0, 0, 1, 1, 0, 1, 1, p, ow), CJ_ERR_DEGENERATE);
    assert_int_equal(cj_rbezier_ellipse_arc(0, 0, 0, 1, 0, 0, 1, p, ow), CJ_ERR_DEGENERATE);
    int np;
    assert_int_equal(cj_rbezier_ellipse_arcs(0, 0, 1, 1, 0, 0, 3 * PI, p, ow, 9, &np),
                     CJ_ERR_RANGE);
    printf("rational errors: zero/NaN weight, dimension, range, arc sweep, radii\n");
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_eval_derivs_vs_mpfr),
        cmocka_unit_test(test_circle_arcs_exact),
        cmocka_unit_test(test_full_ellipse),
        cmocka_unit_test(test_split_and_weights),
        cmocka_unit_test(test_errors),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

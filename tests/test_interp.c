/* Polynomial (Hermite–Birkhoff) interpolation: reconstruction of known polynomials from value
 * and derivative constraints, power form, clash diagnostics, and the Runge phenomenon in
 * numbers (equispaced vs Chebyshev, checked against an independent barycentric formula). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "casteljau/bezier.h"
#include "casteljau/interp.h"
#include "rng.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

static double runge(double x) {
    return 1.0 / (1.0 + 25.0 * x * x);
}

/* Lagrange interpolant at x by the barycentric formula in long double (independent of the
 * Bernstein solve): w_j = 1/Π_{k≠j}(x_j − x_k). */
static double barycentric(const double *xs, const double *fs, int m, double x) {
    long double num = 0, den = 0;
    for (int j = 0; j < m; ++j) {
        if (x == xs[j]) return fs[j];
        long double w = 1;
        for (int k = 0; k < m; ++k)
            if (k != j) w /= ((long double)xs[j] - xs[k]);
        long double c = w / ((long double)x - xs[j]);
        num += c * fs[j];
        den += c;
    }
    return (double)(num / den);
}

static void runge_case(int chebyshev, double *max_err, double *end_err, double *mid_err,
                       double *cond) {
    const int n = 20;
    double xs[21], fs[21], bez[21];
    if (chebyshev)
        assert_int_equal(cj_interp_chebyshev(n, -1, 1, xs), CJ_OK);
    else
        assert_int_equal(cj_interp_equispaced(n, -1, 1, xs), CJ_OK);
    for (int j = 0; j <= n; ++j) fs[j] = runge(xs[j]);
    assert_int_equal(cj_interp_points(xs, fs, 21, 1, -1, 1, bez, NULL, cond), CJ_OK);
    cj_bezier c = cj_bezier_view(n, 1, bez);
    *max_err = *end_err = *mid_err = 0;
    double scale = 1, agree = 0;
    for (int q = 0; q <= 4000; ++q) {
        const double x = -1 + 2.0 * q / 4000, u = (x + 1) / 2;
        double p;
        assert_int_equal(cj_bezier_eval_decasteljau(&c, u, &p), CJ_OK);
        scale = fmax(scale, fabs(p));
        const double bary = barycentric(xs, fs, 21, x);
        if (fabs(p - bary) > fmax(1e-13, 256 * 0x1p-53 * *cond) * fmax(1.0, fabs(bary)))
            fail_msg("%s: Bezier interpolant %.17g vs barycentric %.17g at x = %g (cond %g)",
                     chebyshev ? "Chebyshev" : "equispaced", p, bary, x, *cond);
        agree = fmax(agree, fabs(p - bary) / fmax(1.0, fabs(bary)));
        const double e = fabs(p - runge(x));
        *max_err = fmax(*max_err, e);
        if (fabs(x) >= 0.9) *end_err = fmax(*end_err, e);
        if (fabs(x) <= 0.5) *mid_err = fmax(*mid_err, e);
    }
    printf("  %s: Bezier-form interpolant vs long-double barycentric formula: max difference "
           "%.2e\n",
           chebyshev ? "Chebyshev" : "equispaced", agree);
}

static void test_runge(void **state) {
    (void)state;
    double em, ee, emid, ce, cm, ce2, cmid, conde, condc;
    runge_case(0, &em, &ee, &emid, &conde);
    runge_case(1, &cm, &ce2, &cmid, &condc);
    printf("Runge f(x) = 1/(1+25x^2), degree 20 on [-1,1], 4001 samples:\n");
    printf("  equispaced: max |p-f| = %.4g (|x|>=0.9: %.4g, |x|<=0.5: %.3g), cond %.3g\n", em, ee,
           emid, conde);
    printf("  Chebyshev : max |p-f| = %.4g (|x|>=0.9: %.4g, |x|<=0.5: %.3g), cond %.3g\n", cm, ce2,
           cmid, condc);
    (void)ce;
    assert_true(em > 10.0);       /* the oscillation near the ends */
    assert_true(ee > 100 * emid); /* ... lives near the ends */
    assert_true(cm < 0.05);       /* Chebyshev parameters: no oscillation */
    assert_true(em > 500 * cm);
}

/* Random truth P (Bézier on [a,b]); Hermite-type constraints (orders 0..k-1 at each of several
 * distinct parameters), values from P; the solve must give P back. */
static void test_reconstruction(void **state) {
    (void)state;
    cj_rng rng;
    cj_rng_init(&rng, cj_test_seed("test_interp/reconstruct", 3301));
    double worst = 0, worst_power = 0;
    for (int cas = 0; cas < 300; ++cas) {
        const int n = cj_rng_int(&rng, 0, 12), dim = cj_rng_int(&rng, 1, 3), m = n + 1;
        const int unit = cas % 3 == 0;
        const double a = unit ? 0.0 : cj_rng_range(&rng, -3, 1);
        const double b = unit ? 1.0 : a + cj_rng_range(&rng, 0.5, 4);
        double P[13 * 3], vals[13 * 3], bez[13 * 3], power[13 * 3], cond;
        for (int i = 0; i < m * dim; ++i) P[i] = cj_rng_range(&rng, -5, 5);
        cj_bezier truth = cj_bezier_view(n, dim, P);
        cj_interp_constraint cons[13];
        int j = 0;
        while (j < m) {
            const double t = cj_rng_range(&rng, a, b);
            const int k = cj_rng_int(&rng, 1, m - j < 3 ? m - j : 3);
            double d[4 * 3];
            assert_int_equal(cj_bezier_eval_derivs(&truth, (t - a) / (b - a), k - 1, d), CJ_OK);
            for (int r = 0; r < k; ++r, ++j) {
                cons[j].t = t;
                cons[j].order = r;
                for (int q = 0; q < dim; ++q) vals[j * dim + q] = d[r * dim + q] / pow(b - a, r);
                cons[j].value = vals + j * dim;
            }
        }
        cj_status st = cj_interp_solve(cons, (size_t)m, dim, a, b, bez, power, &cond);
        if (st == CJ_ERR_SINGULAR) continue; /* nearly coincident random parameters */
        assert_int_equal(st, CJ_OK);
        assert_true(cond >= 1.0);
        for (int i = 0; i < m * dim; ++i) {
            const double e = fabs(bez[i] - P[i]) / 5.0;
            worst = fmax(worst, e / cond);
            if (e > 64 * 0x1p-53 * cond * (n + 1))
                fail_msg("case %d n=%d: control %d: %.17g vs truth %.17g (cond %.3g)", cas, n, i,
                         bez[i], P[i], cond);
        }
        if (unit) { /* power form in t from the binomial formula, computed here */
            for (int k = 0; k <= n; ++k)
                for (int q = 0; q < dim; ++q) {
                    double s = 0, ck = 1; /* C(k,i) */
                    for (int i = 0; i <= k; ++i) {
                        s += (((k - i) & 1) ? -ck : ck) * P[i * dim + q];
                        ck = ck * (k - i) / (i + 1);
                    }
                    double cnk = 1;
                    for (int i = 0; i < k; ++i) cnk = cnk * (n - i) / (i + 1);
                    const double e = fabs(power[k * dim + q] - cnk * s) / (5.0 * pow(2, n));
                    worst_power = fmax(worst_power, e / cond);
                    if (e > 1e-13 * cond * (n + 1))
                        fail_msg("case %d: power coefficient %d: %.17g vs %.17g", cas, k,
                                 power[k * dim + q], cnk * s);
                }
        }
    }
    printf("Hermite interpolation recovers 300 random polynomials (deg 0..12): worst "
           "error/cond %.2e (power form %.2e)\n",
           worst, worst_power);
}

static void expect_clash(cj_interp_constraint *c, size_t m, const char *needle) {
    double bez[16], cond;
    assert_int_equal(cj_interp_solve(c, m, 1, 0, 1, bez, NULL, &cond), CJ_ERR_SINGULAR);
    if (!strstr(cj_last_error(), needle))
        fail_msg("message '%s' does not contain '%s'", cj_last_error(), needle);
    printf("  refused: %s\n", cj_last_error());
}

static void test_clashes(void **state) {
    (void)state;
    const double v0 = 0, v1 = 1, v2 = 2;
    printf("clashing constraint sets:\n");
    cj_interp_constraint a[3] = {{0.5, 0, &v0}, {0.0, 0, &v1}, {0.5, 0, &v1}};
    expect_clash(a, 3, "constraints 0 and 2 both fix the value at t = 0.5 to different points");
    cj_interp_constraint b[3] = {{0.0, 0, &v0}, {0.3, 1, &v2}, {0.3, 1, &v2}};
    expect_clash(b, 3,
                 "constraints 1 and 2 both fix derivative 1 at t = 0.29999999999999999 (repeated)");
    cj_interp_constraint c[2] = {{0.0, 0, &v0}, {0.2, 2, &v1}};
    expect_clash(c, 2, "constraint 1: derivative order 2 exceeds the degree 1");
    cj_interp_constraint d[2] = {{0.0, 1, &v0}, {1.0, 1, &v1}}; /* no value at all */
    expect_clash(d, 2, "depends linearly on the others");
    /* Birkhoff: p(-1), p(1), p'(0) do not determine a quadratic */
    cj_interp_constraint e[3] = {{-1.0, 0, &v0}, {1.0, 0, &v1}, {0.0, 1, &v2}};
    double bez[3];
    assert_int_equal(cj_interp_solve(e, 3, 1, -1, 1, bez, NULL, NULL), CJ_ERR_SINGULAR);
    assert_non_null(strstr(cj_last_error(), "depends linearly on the others"));
    printf("  refused: %s\n", cj_last_error());
    /* ... while p(-1), p(1), p'(0.5) do */
    e[2].t = 0.5;
    assert_int_equal(cj_interp_solve(e, 3, 1, -1, 1, bez, NULL, NULL), CJ_OK);
}

static void test_inputs_and_helpers(void **state) {
    (void)state;
    const double v = 1, nan = NAN;
    double bez[70], xs[21];
    cj_interp_constraint c[1] = {{0.5, 0, &v}};
    assert_int_equal(cj_interp_solve(c, 0, 1, 0, 1, bez, NULL, NULL), CJ_ERR_EMPTY);
    assert_int_equal(cj_interp_solve(c, 1, 1, 1, 1, bez, NULL, NULL), CJ_ERR_ARGUMENT);
    assert_int_equal(cj_interp_solve(c, 1, 0, 0, 1, bez, NULL, NULL), CJ_ERR_DIMENSION);
    cj_interp_constraint bad[1] = {{NAN, 0, &v}};
    assert_int_equal(cj_interp_solve(bad, 1, 1, 0, 1, bez, NULL, NULL), CJ_ERR_NONFINITE);
    cj_interp_constraint badv[1] = {{0.5, 0, &nan}};
    assert_int_equal(cj_interp_solve(badv, 1, 1, 0, 1, bez, NULL, NULL), CJ_ERR_NONFINITE);
    assert_non_null(strstr(cj_last_error(), "constraint 0"));
    cj_interp_constraint neg[1] = {{0.5, -1, &v}};
    assert_int_equal(cj_interp_solve(neg, 1, 1, 0, 1, bez, NULL, NULL), CJ_ERR_ARGUMENT);
    double ts[70], ps[70];
    for (int i = 0; i < 70; ++i) ts[i] = ps[i] = i;
    assert_int_equal(cj_interp_points(ts, ps, 66, 1, 0, 65, bez, NULL, NULL), CJ_ERR_DEGREE);
    /* degree 0: a constant */
    assert_int_equal(cj_interp_solve(c, 1, 1, 0, 1, bez, NULL, NULL), CJ_OK);
    assert_true(bez[0] == 1.0);
    /* parameter helpers */
    assert_int_equal(cj_interp_equispaced(20, -1, 1, xs), CJ_OK);
    assert_true(xs[0] == -1 && xs[20] == 1 && fabs(xs[10]) < 1e-16);
    assert_int_equal(cj_interp_chebyshev(20, -1, 1, xs), CJ_OK);
    for (int k = 0; k <= 20; ++k) {
        const double expect = -cos((2.0 * k + 1) * 3.14159265358979323846 / 42.0);
        assert_true(fabs(xs[k] - expect) < 1e-15);
        if (k) assert_true(xs[k] > xs[k - 1]);
    }
    assert_int_equal(cj_interp_chebyshev(0, -1, 1, xs), CJ_ERR_ARGUMENT);
    assert_int_equal(cj_interp_equispaced(3, 1, -1, xs), CJ_ERR_ARGUMENT);
    assert_int_equal(cj_interp_equispaced(3, 0, INFINITY, xs), CJ_ERR_NONFINITE);
    printf("interpolation input errors and parameter helpers (equispaced ends exact, Chebyshev "
           "roots ascending)\n");
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_runge),
        cmocka_unit_test(test_reconstruction),
        cmocka_unit_test(test_clashes),
        cmocka_unit_test(test_inputs_and_helpers),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

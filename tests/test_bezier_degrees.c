/* Degrees, dimensions and the evaluation API's edges: every degree 0..100 (and samples up to
 * CJ_BEZIER_MAX_DEGREE = 255) in dimensions 1..4 checked against the exact MPFR oracle and the
 * published bounds for each method allowed at that degree; the binomial limit 56 of Bernstein
 * and Horner; batch evaluation bit-identical to single evaluation; bad input statuses, the
 * messages naming the bad input, and outputs left untouched on failure. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "casteljau/bezier.h"
#include "eval_check.h"
#include "rng.h"

#include <float.h>
#include <gmp.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

static uint64_t seed;
static double pts[(CJ_BEZIER_MAX_DEGREE + 2) * CJ_MAX_DIM];

static void fill(cj_rng *r, int n, int d) {
    for (int i = 0; i < (n + 1) * d; ++i) pts[i] = cj_rng_range(r, -1.0, 1.0);
}

static void expect_fail(cj_status got, cj_status want, const char *needle, const char *what);

static void test_every_degree_against_oracle(void **state) {
    (void)state;
    cj_rng r;
    cj_rng_init(&r, seed);
    cj_eval_stats st = {0};
    static const int beyond[] = {128, 200, 254, 255};
    int curves = 0;
    for (int idx = 0; idx <= 100 + 4; ++idx) {
        const int n = idx <= 100 ? idx : beyond[idx - 101];
        const int d = 1 + idx % 4;
        fill(&r, n, d);
        const cj_bezier c = cj_bezier_view(n, d, pts);
        const double ts[3] = {cj_rng_unit(&r), cj_rng_unit(&r), (idx % 2) ? 0.0 : 1.0};
        for (int j = 0; j < (n > 100 ? 1 : 3); ++j) {
            char label[96];
            snprintf(label, sizeof label, "degree %d, dim %d (seed %llu)", n, d,
                     (unsigned long long)seed);
            cj_check_eval_point(label, &c, ts[j], 512, &st, NULL);
        }
        ++curves;
    }
    printf("%d curves of degree 0..100, 128, 200, 254, 255 in dims 1..4 (Bernstein and Horner "
           "up to 56)\n",
           curves);
    cj_eval_stats_print("every degree", &st);
}

static void test_degree_limits(void **state) {
    (void)state;
    cj_rng r;
    cj_rng_init(&r, seed ^ 1);
    double out[CJ_MAX_DIM], out2[CJ_MAX_DIM], ts[2] = {0.25, 0.75};
    for (int d = 1; d <= 4; ++d) {
        fill(&r, CJ_BEZIER_MAX_DEGREE + 1, d);
        /* 56 works for every method, 57 only for de Casteljau and compensated. */
        cj_bezier c56 = cj_bezier_view(CJ_BEZIER_BINOMIAL_MAX_DEGREE, d, pts);
        cj_bezier c57 = cj_bezier_view(CJ_BEZIER_BINOMIAL_MAX_DEGREE + 1, d, pts);
        for (int m = 0; m < CJ_N_METHODS; ++m) {
            assert_int_equal(cj_bezier_eval(&c56, (cj_eval_method)m, 0.3, out), CJ_OK);
            const int binomial = m == CJ_EVAL_BERNSTEIN || m == CJ_EVAL_HORNER;
            out2[0] = 12345.0;
            const cj_status st = cj_bezier_eval(&c57, (cj_eval_method)m, 0.3, out2);
            if (binomial) {
                assert_int_equal(st, CJ_ERR_DEGREE);
                assert_true(out2[0] == 12345.0);
                assert_non_null(strstr(cj_last_error(), "57"));
                assert_non_null(strstr(cj_last_error(), "56"));
                assert_int_equal(cj_bezier_error_bound(&c57, (cj_eval_method)m, 0.3, out2),
                                 CJ_ERR_DEGREE);
                assert_int_equal(cj_bezier_eval_batch(&c57, (cj_eval_method)m, ts, 2, out2),
                                 CJ_ERR_DEGREE);
            } else {
                assert_int_equal(st, CJ_OK);
            }
        }
        assert_int_equal(cj_bezier_eval_bernstein(&c57, 0.3, out), CJ_ERR_DEGREE);
        assert_int_equal(cj_bezier_eval_horner(&c57, 0.3, out), CJ_ERR_DEGREE);
        /* 255 works for de Casteljau, compensated, bounds, cond, derivatives; 256 does not. */
        cj_bezier c255 = cj_bezier_view(CJ_BEZIER_MAX_DEGREE, d, pts);
        cj_bezier c256 = cj_bezier_view(CJ_BEZIER_MAX_DEGREE + 1, d, pts);
        double bnd[CJ_MAX_DIM], derivs[3 * CJ_MAX_DIM];
        assert_int_equal(cj_bezier_eval_decasteljau(&c255, 0.6, out), CJ_OK);
        assert_int_equal(cj_bezier_eval_compensated(&c255, 0.6, out, bnd), CJ_OK);
        assert_int_equal(cj_bezier_cond(&c255, 0.6, out), CJ_OK);
        assert_int_equal(cj_bezier_eval_derivs(&c255, 0.6, 2, derivs), CJ_OK);
        for (int m = 0; m < CJ_N_METHODS; ++m) {
            assert_int_equal(cj_bezier_eval(&c256, (cj_eval_method)m, 0.6, out), CJ_ERR_DEGREE);
            assert_int_equal(cj_bezier_error_bound(&c256, (cj_eval_method)m, 0.6, out),
                             CJ_ERR_DEGREE);
        }
        assert_int_equal(cj_bezier_eval_compensated(&c256, 0.6, out, bnd), CJ_ERR_DEGREE);
        assert_non_null(strstr(cj_last_error(), "256"));
        assert_int_equal(cj_bezier_cond(&c256, 0.6, out), CJ_ERR_DEGREE);
    }
    /* Derivatives of every order of a degree-255 constant curve are exactly zero: the factor
     * 255!/(255-j)! overflows for large j, and must not turn 0 into a NaN (t = 1/4 keeps the
     * triangle exact). */
    static double konst[(CJ_BEZIER_MAX_DEGREE + 1) * 2], dv[(CJ_BEZIER_MAX_DEGREE + 3) * 2];
    for (int i = 0; i <= CJ_BEZIER_MAX_DEGREE; ++i) konst[2 * i] = 3.0, konst[2 * i + 1] = -1.5;
    const cj_bezier ck = cj_bezier_view(CJ_BEZIER_MAX_DEGREE, 2, konst);
    assert_int_equal(cj_bezier_eval_derivs(&ck, 0.25, CJ_BEZIER_MAX_DEGREE + 2, dv), CJ_OK);
    assert_true(dv[0] == 3.0 && dv[1] == -1.5);
    for (int j = 1; j <= CJ_BEZIER_MAX_DEGREE + 2; ++j)
        if (dv[2 * j] != 0.0 || dv[2 * j + 1] != 0.0)
            fail_msg("derivative %d of a constant degree-255 curve is (%g, %g)", j, dv[2 * j],
                     dv[2 * j + 1]);
    /* A hodograph whose points exceed the double range is reported, not returned as inf. */
    for (int i = 0; i <= CJ_BEZIER_MAX_DEGREE; ++i) konst[i] = (i % 2) ? 1e300 : -1e300;
    const cj_bezier big = cj_bezier_view(CJ_BEZIER_MAX_DEGREE, 1, konst);
    dv[0] = 7.0;
    expect_fail(cj_bezier_hodograph(&big, 5, dv), CJ_ERR_RANGE, "overflows", "hodograph overflow");
    assert_true(dv[0] == 7.0);
    printf("degree limits: 56 for Bernstein/Horner, 255 for de Casteljau/compensated, dims 1..4\n");
}

static void test_batch_equals_single(void **state) {
    (void)state;
    cj_rng r;
    cj_rng_init(&r, seed ^ 2);
    const double ts[] = {0.0,
                         1.0,
                         0.5,
                         nextafter(0.5, 1.0),
                         nextafter(0.5, 0.0),
                         nextafter(0.0, 1.0),
                         DBL_MIN,
                         nextafter(1.0, 0.0),
                         -0.5,
                         1.5,
                         -3.0,
                         0.1,
                         0.3,
                         0.7,
                         0.9,
                         1e-300,
                         0.123456789};
    const size_t nt = sizeof ts / sizeof ts[0];
    static const int degrees[] = {0, 1, 2, 3, 7, 8, 20, 56, 100, 255};
    static double batch[sizeof ts / sizeof ts[0] * CJ_MAX_DIM];
    int combos = 0;
    for (size_t di = 0; di < sizeof degrees / sizeof degrees[0]; ++di)
        for (int d = 1; d <= CJ_MAX_DIM; d = d < 4 ? d + 1 : CJ_MAX_DIM + (d == CJ_MAX_DIM)) {
            const int n = degrees[di];
            fill(&r, n, d);
            const cj_bezier c = cj_bezier_view(n, d, pts);
            for (int m = 0; m < CJ_N_METHODS; ++m) {
                if ((m == CJ_EVAL_BERNSTEIN || m == CJ_EVAL_HORNER) &&
                    n > CJ_BEZIER_BINOMIAL_MAX_DEGREE)
                    continue;
                assert_int_equal(cj_bezier_eval_batch(&c, (cj_eval_method)m, ts, nt, batch), CJ_OK);
                for (size_t j = 0; j < nt; ++j) {
                    double one[CJ_MAX_DIM];
                    assert_int_equal(cj_bezier_eval(&c, (cj_eval_method)m, ts[j], one), CJ_OK);
                    if (memcmp(one, batch + j * (size_t)d, sizeof(double) * (size_t)d) != 0)
                        fail_msg("method %d, degree %d, dim %d, t = %a: batch %a differs from "
                                 "single %a",
                                 m, n, d, ts[j], batch[j * (size_t)d], one[0]);
                    /* The named entry points are the same computation. */
                    double named[CJ_MAX_DIM];
                    cj_status st =
                        m == CJ_EVAL_DECASTELJAU ? cj_bezier_eval_decasteljau(&c, ts[j], named)
                        : m == CJ_EVAL_BERNSTEIN ? cj_bezier_eval_bernstein(&c, ts[j], named)
                        : m == CJ_EVAL_HORNER    ? cj_bezier_eval_horner(&c, ts[j], named)
                                              : cj_bezier_eval_compensated(&c, ts[j], named, NULL);
                    assert_int_equal(st, CJ_OK);
                    assert_memory_equal(named, one, sizeof(double) * (size_t)d);
                }
                ++combos;
            }
            if (d == CJ_MAX_DIM) break;
        }
    double untouched = 42.0;
    const cj_bezier c0 = cj_bezier_view(2, 1, pts);
    assert_int_equal(cj_bezier_eval_batch(&c0, CJ_EVAL_HORNER, ts, 0, &untouched), CJ_OK);
    assert_true(untouched == 42.0);
    printf("batch == single bit for bit: %d method/degree/dim combinations x %zu parameters "
           "(incl. extrapolation, subnormal t, both sides of 1/2)\n",
           combos, nt);
}

/* The binomial table behind Bernstein and Horner, checked through the public API: with the
 * unit coefficient vector e_i and t = 1/2 every power is exact, so the Bernstein sum must be
 * exactly C(n,i) 2^-n, compared with GMP's exact binomial for every n <= 56. */
static void test_binomials_exact(void **state) {
    (void)state;
    static double e[CJ_BEZIER_BINOMIAL_MAX_DEGREE + 1];
    mpz_t bin;
    mpz_init(bin);
    int checked = 0;
    for (int n = 0; n <= CJ_BEZIER_BINOMIAL_MAX_DEGREE; ++n)
        for (int i = 0; i <= n; ++i) {
            memset(e, 0, sizeof e);
            e[i] = 1.0;
            const cj_bezier c = cj_bezier_view(n, 1, e);
            double v;
            assert_int_equal(cj_bezier_eval_bernstein(&c, 0.5, &v), CJ_OK);
            mpz_bin_uiui(bin, (unsigned long)n, (unsigned long)i);
            const double want = ldexp(mpz_get_d(bin), -n); /* exact: C(n,i) < 2^53 */
            if (v != want)
                fail_msg("C(%d,%d): table gives %.17g 2^%d, exact %.17g", n, i, ldexp(v, n), -n,
                         mpz_get_d(bin));
            ++checked;
        }
    mpz_clear(bin);
    printf("binomial table: %d entries C(n,i), n <= 56, exact\n", checked);
}

static void expect_fail(cj_status got, cj_status want, const char *needle, const char *what) {
    if (got != want)
        fail_msg("%s: status %d (%s), expected %d (%s)", what, (int)got, cj_status_str(got),
                 (int)want, cj_status_str(want));
    if (needle && !strstr(cj_last_error(), needle))
        fail_msg("%s: message '%s' does not mention '%s'", what, cj_last_error(), needle);
}

static void test_bad_input(void **state) {
    (void)state;
    double p[] = {0, 0, 1, 2, 2, 0, 3, 1};
    double out[2] = {7, 7}, bnd[2] = {7, 7}, batch[8];
    const cj_eval_method all[] = {CJ_EVAL_DECASTELJAU, CJ_EVAL_BERNSTEIN, CJ_EVAL_HORNER,
                                  CJ_EVAL_COMPENSATED};
    for (int m = 0; m < 4; ++m) {
        cj_bezier c = cj_bezier_view(3, 2, p);
        p[7] = NAN;
        expect_fail(cj_bezier_eval(&c, all[m], 0.5, out), CJ_ERR_NONFINITE,
                    "control point 3, coordinate 1 is NaN", "NaN coordinate");
        p[7] = -INFINITY;
        expect_fail(cj_bezier_error_bound(&c, all[m], 0.5, out), CJ_ERR_NONFINITE,
                    "control point 3, coordinate 1 is infinite", "infinite coordinate");
        p[7] = 1;
        expect_fail(cj_bezier_eval(&c, all[m], NAN, out), CJ_ERR_NONFINITE, "parameter t is NaN",
                    "NaN t");
        expect_fail(cj_bezier_eval(&c, all[m], INFINITY, out), CJ_ERR_NONFINITE,
                    "parameter t is infinite", "infinite t");
        const double ts[] = {0.1, 0.2, 0.3, 0.4, 0.5, INFINITY};
        for (int i = 0; i < 8; ++i) batch[i] = 7;
        expect_fail(cj_bezier_eval_batch(&c, all[m], ts, 6, batch), CJ_ERR_NONFINITE,
                    "parameter 5 is infinite", "batch with a bad parameter");
        for (int i = 0; i < 8; ++i) assert_true(batch[i] == 7); /* nothing written */
        c.dim = 0;
        expect_fail(cj_bezier_eval(&c, all[m], 0.5, out), CJ_ERR_DIMENSION, "dimension 0",
                    "dimension 0");
        c.dim = CJ_MAX_DIM + 1;
        expect_fail(cj_bezier_eval(&c, all[m], 0.5, out), CJ_ERR_DIMENSION, "dimension 9",
                    "dimension 9");
        c = cj_bezier_view(-1, 2, p);
        expect_fail(cj_bezier_eval(&c, all[m], 0.5, out), CJ_ERR_EMPTY, "no control points",
                    "degree -1");
        expect_fail(cj_bezier_eval_batch(&c, all[m], ts, 2, batch), CJ_ERR_EMPTY, NULL,
                    "batch degree -1");
    }
    cj_bezier c = cj_bezier_view(3, 2, p);
    expect_fail(cj_bezier_eval(&c, (cj_eval_method)7, 0.5, out), CJ_ERR_ARGUMENT,
                "unknown evaluation method 7", "unknown method");
    expect_fail(cj_bezier_error_bound(&c, (cj_eval_method)-1, 0.5, out), CJ_ERR_ARGUMENT,
                "unknown evaluation method", "negative method");
    expect_fail(cj_bezier_eval_batch(&c, (cj_eval_method)4, p, 1, out), CJ_ERR_ARGUMENT,
                "unknown evaluation method 4", "unknown method in batch");
    expect_fail(cj_bezier_eval_compensated(&c, NAN, out, bnd), CJ_ERR_NONFINITE, "parameter t",
                "compensated NaN t");
    expect_fail(cj_bezier_cond(&c, -INFINITY, out), CJ_ERR_NONFINITE, "parameter t",
                "cond infinite t");
    assert_true(out[0] == 7 && out[1] == 7 && bnd[0] == 7 && bnd[1] == 7);
    /* Far extrapolation overflows: reported, never a silent NaN or infinity. */
    for (int m = 0; m < 4; ++m) {
        expect_fail(cj_bezier_eval(&c, all[m], 1e200, out), CJ_ERR_RANGE, "overflows",
                    "overflowing extrapolation");
        const double far[] = {0.5, -1e300};
        expect_fail(cj_bezier_eval_batch(&c, all[m], far, 2, batch), CJ_ERR_RANGE, "overflows",
                    "overflowing extrapolation in batch");
    }
    expect_fail(cj_bezier_eval_compensated(&c, 1e200, out, bnd), CJ_ERR_RANGE, "overflows",
                "compensated overflow");
    expect_fail(cj_bezier_eval_decasteljau(&c, -1e200, out), CJ_ERR_RANGE, "overflows",
                "de Casteljau overflow");
    expect_fail(cj_bezier_cond(&c, 1e200, out), CJ_ERR_RANGE, "overflows", "cond overflow");
    double dv[3 * 2] = {7, 7, 7, 7, 7, 7};
    expect_fail(cj_bezier_eval_derivs(&c, 1e200, 2, dv), CJ_ERR_RANGE, "overflows",
                "derivatives overflow");
    for (int i = 0; i < 6; ++i) assert_true(dv[i] == 7);
    assert_true(out[0] == 7 && out[1] == 7 && bnd[0] == 7 && bnd[1] == 7);
    printf("bad input: NaN/inf coordinates and parameters, dimension 0/9, degree -1, unknown "
           "method, overflowing extrapolation; statuses, messages, untouched outputs\n");
}

int main(void) {
    seed = cj_test_seed("test_bezier_degrees", 4242);
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_every_degree_against_oracle),
        cmocka_unit_test(test_degree_limits),
        cmocka_unit_test(test_binomials_exact),
        cmocka_unit_test(test_batch_equals_single),
        cmocka_unit_test(test_bad_input),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

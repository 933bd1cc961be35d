/* Unit tests of the Bézier core: known values, derivatives, subdivision, bad input. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "casteljau/bezier.h"

#include <math.h>
#include <string.h>

/* The quadratic (0,0) (1,2) (2,0): c(t) = (2t, 4t(1-t)). */
static const double quad[] = {0, 0, 1, 2, 2, 0};

static void test_known_values_all_methods(void **state) {
    (void)state;
    cj_bezier c = cj_bezier_view(2, 2, quad);
    const cj_eval_method methods[] = {CJ_EVAL_DECASTELJAU, CJ_EVAL_BERNSTEIN, CJ_EVAL_HORNER,
                                      CJ_EVAL_COMPENSATED};
    const double ts[] = {0.0, 0.25, 0.5, 0.75, 1.0, -1.0, 2.0};
    for (size_t m = 0; m < 4; ++m)
        for (size_t j = 0; j < sizeof ts / sizeof ts[0]; ++j) {
            double p[2];
            double t = ts[j];
            assert_int_equal(cj_bezier_eval(&c, methods[m], t, p), CJ_OK);
            assert_true(fabs(p[0] - 2 * t) <= 1e-15 * (1 + fabs(t)));
            assert_true(fabs(p[1] - 4 * t * (1 - t)) <= 1e-14 * (1 + t * t));
        }
}

static void test_degree_zero_and_one(void **state) {
    (void)state;
    const double pt[] = {3, -4, 5};
    cj_bezier c0 = cj_bezier_view(0, 3, pt);
    double p[3];
    assert_int_equal(cj_bezier_eval_decasteljau(&c0, 0.3, p), CJ_OK);
    assert_memory_equal(p, pt, sizeof pt);
    double h[3];
    assert_int_equal(cj_bezier_hodograph(&c0, 1, h), CJ_OK);
    assert_true(h[0] == 0 && h[1] == 0 && h[2] == 0);
}

static void test_derivs_match_hodograph(void **state) {
    (void)state;
    const double cubic[] = {0, 0, 1, 3, 4, -1, 5, 2};
    cj_bezier c = cj_bezier_view(3, 2, cubic);
    double d[5 * 2];
    assert_int_equal(cj_bezier_eval_derivs(&c, 0.3, 4, d), CJ_OK);
    double h1[3 * 2], h2[2 * 2];
    assert_int_equal(cj_bezier_hodograph(&c, 1, h1), CJ_OK);
    assert_int_equal(cj_bezier_hodograph(&c, 2, h2), CJ_OK);
    cj_bezier c1 = cj_bezier_view(2, 2, h1), c2 = cj_bezier_view(1, 2, h2);
    double v1[2], v2[2];
    cj_bezier_eval_decasteljau(&c1, 0.3, v1);
    cj_bezier_eval_decasteljau(&c2, 0.3, v2);
    for (int k = 0; k < 2; ++k) {
        assert_true(fabs(d[2 + k] - v1[k]) < 1e-13);
        assert_true(fabs(d[4 + k] - v2[k]) < 1e-13);
        assert_true(d[8 + k] == 0.0); /* fourth derivative of a cubic */
    }
    /* Third derivative of a cubic is 6 Δ^3 b_0. */
    assert_true(fabs(d[6] - 6 * (5 - 3 * 4 + 3 * 1 - 0)) < 1e-12);
}

static void test_split_halves_reproduce(void **state) {
    (void)state;
    const double cubic[] = {0, 0, 1, 3, 4, -1, 5, 2};
    cj_bezier c = cj_bezier_view(3, 2, cubic);
    double l[8], r[8];
    assert_int_equal(cj_bezier_split(&c, 0.4, l, r), CJ_OK);
    assert_memory_equal(l + 6, r, 2 * sizeof(double));
    cj_bezier cl = cj_bezier_view(3, 2, l), cr = cj_bezier_view(3, 2, r);
    for (int j = 0; j <= 10; ++j) {
        double u = j / 10.0, a[2], b[2];
        cj_bezier_eval_decasteljau(&cl, u, a);
        cj_bezier_eval_decasteljau(&c, 0.4 * u, b);
        assert_true(fabs(a[0] - b[0]) < 1e-14 && fabs(a[1] - b[1]) < 1e-14);
        cj_bezier_eval_decasteljau(&cr, u, a);
        cj_bezier_eval_decasteljau(&c, 0.4 + 0.6 * u, b);
        assert_true(fabs(a[0] - b[0]) < 1e-14 && fabs(a[1] - b[1]) < 1e-14);
    }
}

static void test_bad_input_is_reported(void **state) {
    (void)state;
    double bad[] = {0, 0, NAN, 1, 2, 0};
    cj_bezier c = cj_bezier_view(2, 2, bad);
    double p[2] = {7, 7};
    assert_int_equal(cj_bezier_eval_decasteljau(&c, 0.5, p), CJ_ERR_NONFINITE);
    assert_true(p[0] == 7 && p[1] == 7); /* outputs untouched */
    assert_non_null(strstr(cj_last_error(), "control point 1, coordinate 0 is NaN"));
    cj_bezier good = cj_bezier_view(2, 2, quad);
    assert_int_equal(cj_bezier_eval_decasteljau(&good, INFINITY, p), CJ_ERR_NONFINITE);
    assert_int_equal(cj_bezier_split(&good, 1.5, p, NULL), CJ_ERR_RANGE);
    cj_bezier empty = cj_bezier_view(-1, 2, quad);
    assert_int_equal(cj_bezier_eval_decasteljau(&empty, 0.5, p), CJ_ERR_EMPTY);
    cj_bezier wide = cj_bezier_view(2, CJ_MAX_DIM + 1, quad);
    assert_int_equal(cj_bezier_eval_decasteljau(&wide, 0.5, p), CJ_ERR_DIMENSION);
    static double big[(CJ_BEZIER_BINOMIAL_MAX_DEGREE + 2) * 1];
    cj_bezier high = cj_bezier_view(CJ_BEZIER_BINOMIAL_MAX_DEGREE + 1, 1, big);
    assert_int_equal(cj_bezier_eval(&high, CJ_EVAL_HORNER, 0.5, p), CJ_ERR_DEGREE);
    assert_int_equal(cj_bezier_eval(&high, CJ_EVAL_DECASTELJAU, 0.5, p), CJ_OK);
    assert_string_equal(cj_status_str(CJ_ERR_NONFINITE), "NaN or infinite value");
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_known_values_all_methods),
        cmocka_unit_test(test_degree_zero_and_one),
        cmocka_unit_test(test_derivs_match_hodograph),
        cmocka_unit_test(test_split_halves_reproduce),
        cmocka_unit_test(test_bad_input_is_reported),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

/* Numerical stability of Bézier evaluation against an exact oracle (MPFR, see
 * oracle/include/oracle_mpfr.h): every method's error must stay within its published bound, the
 * library's computed bounds must hold and not undercut the published ones, and the compensated
 * method's a-posteriori bound must hold and stay informative. Cases: the classic hard
 * polynomial (s-1)(s-3/4)^7 ever closer to its 7-fold root, random curves of degree 20, 40 and
 * 80 (well and ill conditioned), parameters a few ulps from 0 and 1 (subnormal products
 * included), and coordinates offset by 1e8. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "casteljau/bezier.h"
#include "eval_check.h"
#include "oracle_mpfr.h"
#include "rng.h"

#include <float.h>
#include <gmp.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

static uint64_t seed;

/* Bernstein coefficients of (s-1)(s-3/4)^7 computed with GMP rationals from the monomial
 * coefficients a_k: b_i = Σ_{k<=i} C(i,k)/C(n,k) a_k. Rounded to double when not exact (the
 * case is then that rounded polynomial, which the oracle evaluates exactly); returns the number
 * of coefficients that needed rounding. */
static int hard_case_coefficients(double b[9]) {
    mpq_t a[9], acc, term, q;
    mpq_init(acc);
    mpq_init(term);
    mpq_init(q);
    for (int k = 0; k <= 8; ++k) mpq_init(a[k]);
    /* a = (s-3/4)^7 (s-1): start from 1, multiply by (s - r) eight times. */
    mpq_set_ui(a[0], 1, 1);
    for (int f = 0; f < 8; ++f) {
        mpq_set_ui(q, f < 7 ? 3 : 1, f < 7 ? 4 : 1); /* root r */
        for (int k = f + 1; k >= 0; --k) {           /* a_k <- a_{k-1} - r a_k */
            mpq_mul(term, q, a[k]);
            if (k > 0)
                mpq_sub(a[k], a[k - 1], term);
            else
                mpq_neg(a[k], term);
        }
    }
    int rounded = 0;
    mpz_t ci, cn;
    mpz_inits(ci, cn, NULL);
    for (int i = 0; i <= 8; ++i) {
        mpq_set_ui(acc, 0, 1);
        for (int k = 0; k <= i; ++k) {
            mpz_bin_uiui(ci, (unsigned long)i, (unsigned long)k);
            mpz_bin_uiui(cn, 8, (unsigned long)k);
            mpq_set_num(q, ci);
            mpq_set_den(q, cn);
            mpq_canonicalize(q);
            mpq_mul(term, q, a[k]);
            mpq_add(acc, acc, term);
        }
        b[i] = mpq_get_d(acc); /* truncates; exactness is checked next */
        mpq_set_d(term, b[i]);
        if (!mpq_equal(term, acc)) {
            mpfr_t x;
            mpfr_init2(x, 53);
            mpfr_set_q(x, acc, MPFR_RNDN);
            b[i] = mpfr_get_d(x, MPFR_RNDN);
            mpfr_clear(x);
            ++rounded;
        }
    }
    mpz_clears(ci, cn, NULL);
    for (int k = 0; k <= 8; ++k) mpq_clear(a[k]);
    mpq_clear(acc);
    mpq_clear(term);
    mpq_clear(q);
    return rounded;
}

static void test_hard_case(void **state) {
    (void)state;
    double b[9];
    const int rounded = hard_case_coefficients(b);
    const cj_bezier c = cj_bezier_view(8, 1, b);
    cj_eval_stats st = {0};
    const double u = CJ_UNIT_ROUNDOFF, g = cj_gamma(24);
    printf("hard case p(s) = (s-1)(s-3/4)^7, degree 8, Bernstein coefficients exact in double: "
           "%s\n",
           rounded ? "no (rounded)" : "yes");
    printf("  %-8s %9s | %9s %9s | %9s %9s %9s | %9s %9s\n", "s-3/4", "cond", "decast.", "g(3n)c",
           "compens.", "u+2g^2c", "a-post.", "bernst.", "horner");
    double worst_comp_well = 0.0; /* compensated relative error while cond <= 1e15 */
    double max_cond = 0.0, dc_at_max = 0.0;
    for (int side = 0; side < 2; ++side)
        for (int j = 2; j <= 20; ++j) {
            const double delta = pow(10.0, -0.5 * j);
            const double s = side ? 0.75 - delta : 0.75 + delta;
            double v[CJ_N_METHODS];
            char label[64];
            snprintf(label, sizeof label, "hard case, s = 3/4 %c 1e-%.1f", side ? '-' : '+',
                     0.5 * j);
            const double cond = cj_check_eval_point(label, &c, s, 1 << 16, &st, v);
            mpfr_t val;
            mpfr_init2(val, 256);
            assert_true(cj_oracle_bezier(b, 8, 1, 0, s, 1 << 16, val, NULL) == 0.0);
            double rel[CJ_N_METHODS];
            for (int m = 0; m < CJ_N_METHODS; ++m) rel[m] = cj_oracle_rel_error(v[m], val);
            double ab, apost, vc;
            assert_int_equal(cj_bezier_eval_compensated(&c, s, &vc, &ab), CJ_OK);
            const double absval = fabs(mpfr_get_d(val, MPFR_RNDN));
            mpfr_clear(val);
            if (cond <= 1e15 && rel[3] > worst_comp_well) worst_comp_well = rel[3];
            if (cond > max_cond) {
                max_cond = cond;
                dc_at_max = rel[0];
            }
            apost = ab / absval;
            if (!side)
                printf("  %-8.1e %9.2e | %9.2e %9.2e | %9.2e %9.2e %9.2e | %9.2e %9.2e\n", delta,
                       cond, rel[0], g * cond, rel[3], u + 2 * g * g * cond, apost, rel[1], rel[2]);
        }
    /* The case must really be hard, or it shows nothing. */
    assert_true(max_cond > 1e30);
    printf("  compensated relative error while cond <= 1e15: max %.2e (= %.2f u); "
           "de Casteljau at cond %.1e: %.1e\n",
           worst_comp_well, worst_comp_well / u, max_cond, dc_at_max);
    cj_eval_stats_print("  hard case bounds", &st);
}

/* Random curves of high degree, coordinates of random sign and magnitude 2^-8..2^8, at random
 * parameters; plus the ill-conditioned family b_i = (-1)^i (1 + small), whose value near t = 1/2
 * is about (1-2t)^n + small. */
static void random_degree(int n, int curves, int params, mpfr_prec_t prec) {
    cj_rng r;
    cj_rng_init(&r, seed + (uint64_t)n);
    cj_eval_stats st = {0};
    double pts[(80 + 1) * 3];
    for (int cv = 0; cv < curves; ++cv) {
        const int d = 1 + cv % 3;
        const int alternating = cv % 2;
        /* Curve 1 mod 4 is exactly (1-2t)^n (up to the sign of each coordinate's term), curve
         * 3 mod 4 perturbs its coefficients by 2^-40 relative. */
        const double wobble = cv % 4 == 1 ? 0.0 : 0x1p-40;
        for (int i = 0; i <= n; ++i)
            for (int k = 0; k < d; ++k) {
                double x;
                if (alternating)
                    x = ((i % 2) ? -1.0 : 1.0) * (1.0 + cj_rng_range(&r, -wobble, wobble));
                else
                    x = ldexp(cj_rng_range(&r, -1.0, 1.0), cj_rng_int(&r, -8, 8));
                pts[i * d + k] = x;
            }
        const cj_bezier c = cj_bezier_view(n, d, pts);
        for (int j = 0; j < params; ++j) {
            double t = cj_rng_unit(&r);
            if (alternating && j % 2)
                t = 0.5 + ldexp(cj_rng_range(&r, -1, 1), -cj_rng_int(&r, 2, 12));
            char label[96];
            snprintf(label, sizeof label, "random degree %d, dim %d, curve %d (seed %llu)", n, d,
                     cv, (unsigned long long)seed);
            cj_check_eval_point(label, &c, t, prec, &st, NULL);
        }
    }
    char label[64];
    snprintf(label, sizeof label, "random degree %d", n);
    cj_eval_stats_print(label, &st);
}

static void test_random_degree_20(void **state) {
    (void)state;
    random_degree(20, 12, 8, 1 << 14);
}

static void test_random_degree_40(void **state) {
    (void)state;
    random_degree(40, 8, 6, 8192);
}

static void test_random_degree_80(void **state) {
    (void)state;
    random_degree(80, 6, 4, 4096);
}

/* Parameters within a few ulps of 0 and 1, including subnormal t, where products underflow and
 * only the documented absolute allowance keeps the bounds true. */
static void test_parameters_near_ends(void **state) {
    (void)state;
    const double ts[] = {0.0,
                         nextafter(0.0, 1.0),
                         2 * nextafter(0.0, 1.0),
                         3 * nextafter(0.0, 1.0),
                         DBL_MIN,
                         nextafter(DBL_MIN, 1.0),
                         0x1p-53,
                         0x1p-52,
                         3 * 0x1p-53,
                         nextafter(1.0, 0.0),
                         nextafter(nextafter(1.0, 0.0), 0.0),
                         1.0 - 3 * 0x1p-53,
                         1.0 - 0x1p-30,
                         1.0};
    cj_rng r;
    cj_rng_init(&r, seed ^ 0x5eed);
    cj_eval_stats st = {0};
    for (int variant = 0; variant < 4; ++variant) {
        const int n = variant < 2 ? 5 : 12, d = 2;
        double pts[13 * 2];
        for (int i = 0; i < (n + 1) * d; ++i) pts[i] = cj_rng_range(&r, -1.0, 1.0);
        if (variant % 2) { /* zero end points: the value near the ends is itself tiny */
            pts[0] = pts[1] = 0.0;
            pts[n * d] = pts[n * d + 1] = 0.0;
        }
        const cj_bezier c = cj_bezier_view(n, d, pts);
        for (size_t j = 0; j < sizeof ts / sizeof ts[0]; ++j) {
            char label[96];
            snprintf(label, sizeof label, "near the ends, degree %d variant %d (seed %llu)", n,
                     variant, (unsigned long long)seed);
            cj_check_eval_point(label, &c, ts[j], 1 << 15, &st, NULL);
        }
    }
    cj_eval_stats_print("parameters near 0 and 1", &st);
}

/* Coordinates offset by 1e8: the relative bounds hold with respect to the large magnitude. */
static void test_far_from_origin(void **state) {
    (void)state;
    cj_rng r;
    cj_rng_init(&r, seed ^ 0xfa7);
    cj_eval_stats st = {0};
    static const int degrees[] = {3, 8, 20};
    for (size_t di = 0; di < 3; ++di)
        for (int d = 2; d <= 3; ++d) {
            const int n = degrees[di];
            double pts[21 * 3];
            for (int i = 0; i < (n + 1) * d; ++i)
                pts[i] = (i % d == 0 ? 1e8 : -1e8) + cj_rng_range(&r, -1.0, 1.0);
            const cj_bezier c = cj_bezier_view(n, d, pts);
            for (int j = 0; j < 10; ++j) {
                char label[96];
                snprintf(label, sizeof label, "offset 1e8, degree %d dim %d (seed %llu)", n, d,
                         (unsigned long long)seed);
                cj_check_eval_point(label, &c, cj_rng_unit(&r), 1 << 14, &st, NULL);
            }
        }
    cj_eval_stats_print("coordinates offset by 1e8", &st);
}

/* Extrapolation (t outside [0,1]): the published bounds are stated on [0,1], but the library's
 * bounds use |1-t| and |t| and must hold everywhere; checked for every method against the
 * exact value. */
static void test_extrapolation(void **state) {
    (void)state;
    cj_rng r;
    cj_rng_init(&r, seed ^ 0xe7);
    static const int degrees[] = {1, 3, 8, 20, 56};
    static const double ts[] = {-1.0, -0.25, -1e-3, 1.001, 1.25, 2.0, 2.5, 5.0};
    mpfr_t val;
    mpfr_init2(val, 256);
    double worst[CJ_N_METHODS + 1] = {0};
    int checked = 0;
    for (size_t di = 0; di < sizeof degrees / sizeof degrees[0]; ++di)
        for (int cv = 0; cv < 3; ++cv) {
            const int n = degrees[di], d = 1 + cv;
            double pts[57 * 3];
            for (int i = 0; i < (n + 1) * d; ++i) pts[i] = cj_rng_range(&r, -1.0, 1.0);
            const cj_bezier c = cj_bezier_view(n, d, pts);
            for (size_t j = 0; j < sizeof ts / sizeof ts[0]; ++j) {
                double v[CJ_N_METHODS][CJ_MAX_DIM], b[CJ_N_METHODS][CJ_MAX_DIM], vc[CJ_MAX_DIM],
                    ap[CJ_MAX_DIM];
                for (int m = 0; m < CJ_N_METHODS; ++m) {
                    assert_int_equal(cj_bezier_eval(&c, (cj_eval_method)m, ts[j], v[m]), CJ_OK);
                    assert_int_equal(cj_bezier_error_bound(&c, (cj_eval_method)m, ts[j], b[m]),
                                     CJ_OK);
                }
                assert_int_equal(cj_bezier_eval_compensated(&c, ts[j], vc, ap), CJ_OK);
                for (int k = 0; k < d; ++k) {
                    assert_true(cj_oracle_bezier(pts, n, d, k, ts[j], 1 << 15, val, NULL) == 0.0);
                    for (int m = 0; m <= CJ_N_METHODS; ++m) {
                        const double got = m < CJ_N_METHODS ? v[m][k] : vc[k];
                        const double bound = m < CJ_N_METHODS ? b[m][k] : ap[k];
                        const double err = cj_oracle_abs_error(got, val);
                        if (!(err <= bound))
                            fail_msg("extrapolation, degree %d dim %d, t = %g, method %d%s, "
                                     "coordinate %d: error %.3e > bound %.3e (seed %llu)",
                                     n, d, ts[j], m < CJ_N_METHODS ? m : 3,
                                     m < CJ_N_METHODS ? "" : " (a-posteriori)", k, err, bound,
                                     (unsigned long long)seed);
                        if (bound > 0 && err / bound > worst[m]) worst[m] = err / bound;
                    }
                    ++checked;
                }
            }
        }
    mpfr_clear(val);
    printf("extrapolation t in [-1,5] \\ [0,1]: %d coordinates, degrees 1..56; worst error/bound "
           "dc %.2g bern %.2g horner %.2g comp %.2g a-posteriori %.2g\n",
           checked, worst[0], worst[1], worst[2], worst[3], worst[4]);
}

/* cj_bezier_cond against the exact condition number. */
static void test_condition_number(void **state) {
    (void)state;
    double b[9];
    hard_case_coefficients(b);
    const cj_bezier c = cj_bezier_view(8, 1, b);
    mpfr_t val, mag;
    mpfr_inits2(256, val, mag, (mpfr_ptr)0);
    int checked = 0;
    for (int j = 2; j <= 20; ++j) {
        const double s = 0.75 + pow(10.0, -0.5 * j);
        assert_true(cj_oracle_bezier(b, 8, 1, 0, s, 1 << 16, val, mag) == 0.0);
        mpfr_div(mag, mag, val, MPFR_RNDN);
        const double cond = fabs(mpfr_get_d(mag, MPFR_RNDN));
        double lc;
        assert_int_equal(cj_bezier_cond(&c, s, &lc), CJ_OK);
        /* lc = computed magnitude / |compensated value|: relative error at most
         * gamma(3n) + (u + 2 gamma(3n)^2 cond) / (1 - that), so check while that is small. */
        const double g = cj_gamma(24), rel = CJ_UNIT_ROUNDOFF + 2 * g * g * cond;
        if (rel > 0.25) continue;
        const double tol = g + 2 * rel / (1 - rel);
        if (fabs(lc / cond - 1.0) > tol)
            fail_msg("cond at s = %a: library %.6e, exact %.6e (tolerance %.2e)", s, lc, cond, tol);
        ++checked;
    }
    mpfr_clears(val, mag, (mpfr_ptr)0);
    const double zero[] = {1.0, -1.0, 1.0}; /* (1-2t)^2 vanishes at t = 1/2 */
    const cj_bezier z = cj_bezier_view(2, 1, zero);
    double lc;
    assert_int_equal(cj_bezier_cond(&z, 0.5, &lc), CJ_OK);
    assert_true(isinf(lc) && lc > 0);
    printf("cj_bezier_cond: %d points match the exact condition number; a zero gives +inf\n",
           checked);
}

int main(void) {
    seed = cj_test_seed("test_bezier_stability", 20261121);
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_hard_case),
        cmocka_unit_test(test_random_degree_20),
        cmocka_unit_test(test_random_degree_40),
        cmocka_unit_test(test_random_degree_80),
        cmocka_unit_test(test_parameters_near_ends),
        cmocka_unit_test(test_far_from_origin),
        cmocka_unit_test(test_extrapolation),
        cmocka_unit_test(test_condition_number),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

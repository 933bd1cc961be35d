/* cj_bezier_eval_unchecked: bit-identical to cj_bezier_eval (and to the batch form) for every
 * method, degree 0-12 and dimension 1-8 on seeded random curves; the degree-3 Horner kernel
 * (division-free, its own code path) within the published gamma(4n+2) bound against the exact
 * MPFR oracle on random cubics of mixed magnitude and near their roots, where the condition
 * number is large. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "casteljau/bezier.h"
#include "eval_check.h"
#include "rng.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

static const cj_eval_method methods[4] = {CJ_EVAL_DECASTELJAU, CJ_EVAL_BERNSTEIN, CJ_EVAL_HORNER,
                                          CJ_EVAL_COMPENSATED};

static void test_unchecked_bit_identical(void **state) {
    (void)state;
    const uint64_t seed = cj_test_seed("test_eval_unchecked", 2613);
    cj_rng r;
    cj_rng_init(&r, seed);
    double pts[13 * CJ_MAX_DIM], ts[16], batch[16 * CJ_MAX_DIM];
    long compared = 0;
    for (int c = 0; c < 2000; ++c) {
        const int n = c % 13, d = 1 + (c / 13) % CJ_MAX_DIM;
        for (int i = 0; i < (n + 1) * d; ++i)
            pts[i] = cj_rng_range(&r, -1, 1) * ldexp(1.0, cj_rng_int(&r, -20, 20));
        for (int j = 0; j < 16; ++j) ts[j] = cj_rng_range(&r, -0.5, 1.5);
        const cj_bezier cv = cj_bezier_view(n, d, pts);
        for (int m = 0; m < 4; ++m) {
            assert_int_equal(cj_bezier_eval_batch(&cv, methods[m], ts, 16, batch), CJ_OK);
            for (int j = 0; j < 16; ++j) {
                double a[CJ_MAX_DIM], b[CJ_MAX_DIM];
                assert_int_equal(cj_bezier_eval(&cv, methods[m], ts[j], a), CJ_OK);
                cj_bezier_eval_unchecked(&cv, methods[m], ts[j], b);
                if (memcmp(a, b, sizeof(double) * (size_t)d) != 0 ||
                    memcmp(a, batch + j * d, sizeof(double) * (size_t)d) != 0)
                    fail_msg("method %d degree %d dim %d t %.17g: checked, unchecked and batch "
                             "differ (seed %llu case %d)",
                             m, n, d, ts[j], (unsigned long long)seed, c);
                compared += d;
            }
        }
    }
    printf("unchecked == checked == batch, bit for bit: %ld coordinates (4 methods, degrees "
           "0-12, dims 1-8, t in [-0.5, 1.5])\n",
           compared);
}

static void test_horner3_bound(void **state) {
    (void)state;
    const uint64_t seed = cj_test_seed("test_eval_horner3", 3313);
    cj_rng r;
    cj_rng_init(&r, seed);
    cj_eval_stats st;
    memset(&st, 0, sizeof st);
    char label[128];
    double pts[4 * 3];
    for (int c = 0; c < 400; ++c) {
        const int d = 2 + c % 2;
        for (int i = 0; i < 4 * d; ++i)
            pts[i] = cj_rng_range(&r, -1, 1) * ldexp(1.0, cj_rng_int(&r, -8, 8));
        /* Near a root of coordinate 0: shift it so that c_0(t0) is ~0 at a random t0. */
        const double t0 = cj_rng_range(&r, 0.01, 0.99);
        const cj_bezier cv = cj_bezier_view(3, d, pts);
        double v[CJ_MAX_DIM];
        cj_bezier_eval(&cv, CJ_EVAL_DECASTELJAU, t0, v);
        if (c % 4 != 0)
            for (int i = 0; i < 4; ++i) pts[i * d] -= v[0];
        for (int j = 0; j < 8; ++j) {
            const double t =
                j < 4 ? cj_rng_unit(&r) : t0 + ldexp(cj_rng_range(&r, -1, 1), -10 * (j - 3));
            if (!(t >= 0.0 && t <= 1.0)) continue;
            snprintf(label, sizeof label, "cubic dim %d case %d (seed %llu)", d, c,
                     (unsigned long long)seed);
            cj_check_eval_point(label, &cv, t, 1 << 12, &st, NULL);
        }
    }
    cj_eval_stats_print("degree-3 cubics near roots, all methods incl. the division-free Horner",
                        &st);
    assert_true(st.points > 0);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_unchecked_bit_identical),
        cmocka_unit_test(test_horner3_bound),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

/* Motion at controlled speed: the arc-length inverse checked against closed-form lengths
 * (straight paths with uneven parameterisation, chains of parabolas) to 1e-10 of the path
 * length, for every ease profile. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "casteljau/motion.h"
#include "rng.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#define NSEG 6

/* Exact arc length of the quadratic c(u) = b0 B0 + b1 B1 + b2 B2 (2D) from 0 to u:
 * c'(u) = A + B u with A = 2(b1 − b0), B = 2(b2 − 2b1 + b0); |c'|² = a u² + b u + c. */
static long double parabola_len(const double *b, long double u) {
    const long double Ax = 2.0L * (b[2] - b[0]), Ay = 2.0L * (b[3] - b[1]);
    const long double Bx = 2.0L * (b[4] - 2.0L * b[2] + b[0]),
                      By = 2.0L * (b[5] - 2.0L * b[3] + b[1]);
    const long double a = Bx * Bx + By * By, bb = 2 * (Ax * Bx + Ay * By), c = Ax * Ax + Ay * Ay;
    const long double sa = sqrtl(a);
    long double F[2];
    const long double us[2] = {0.0L, u};
    for (int i = 0; i < 2; ++i) {
        const long double x = us[i], q = sqrtl(a * x * x + bb * x + c);
        F[i] = (2 * a * x + bb) * q / (4 * a) +
               (4 * a * c - bb * bb) / (8 * a * sa) * logl(2 * sa * q + 2 * a * x + bb);
    }
    return F[1] - F[0];
}

typedef struct {
    double quad[NSEG][6];
    double segs[NSEG * 4 * 2];
    long double seglen[NSEG];
} chain;

static void make_chain(cj_rng *r, chain *ch) {
    double p[2] = {0, 0};
    for (int j = 0; j < NSEG; ++j) {
        double *q = ch->quad[j];
        q[0] = p[0];
        q[1] = p[1];
        q[2] = p[0] + cj_rng_range(r, 0.5, 3);
        q[3] = p[1] + cj_rng_range(r, -3, 3);
        q[4] = q[2] + cj_rng_range(r, 0.5, 3);
        q[5] = q[3] + cj_rng_range(r, -3, 3);
        p[0] = q[4];
        p[1] = q[5];
        /* exact degree elevation to a cubic */
        double *s = ch->segs + j * 8;
        for (int k = 0; k < 2; ++k) {
            s[0 + k] = q[k];
            s[2 + k] = (q[k] + 2 * q[2 + k]) / 3;
            s[4 + k] = (2 * q[2 + k] + q[4 + k]) / 3;
            s[6 + k] = q[4 + k];
        }
        ch->seglen[j] = parabola_len(q, 1.0L);
    }
}

static long double exact_S(const chain *ch, size_t seg, double u) {
    long double s = 0;
    for (size_t j = 0; j < seg; ++j) s += ch->seglen[j];
    return s + parabola_len(ch->quad[seg], u);
}

static void test_parabola_chain(void **state) {
    (void)state;
    cj_rng r;
    cj_rng_init(&r, cj_test_seed("test_anim_path/parabolas", 1621));
    double worst = 0, worst_len = 0;
    int queries = 0;
    const cj_ease eases[4] = {CJ_EASE_LINEAR, CJ_EASE_SMOOTHSTEP, CJ_EASE_SINE, CJ_EASE_TRAPEZOID};
    for (int cas = 0; cas < 40; ++cas) {
        chain ch;
        make_chain(&r, &ch);
        cj_path *p = NULL;
        assert_int_equal(cj_path_create(ch.segs, NSEG, 2, 1e-10, NULL, &p), CJ_OK);
        long double L = 0;
        for (int j = 0; j < NSEG; ++j) L += ch.seglen[j];
        worst_len = fmax(worst_len, (double)(fabsl(cj_path_length(p) - L) / L));
        for (int q = 0; q <= 100; ++q) {
            const cj_ease e = eases[q % 4];
            const double x = q / 100.0, param = 0.3;
            double sigma, pt[2], u;
            size_t seg;
            assert_int_equal(cj_ease_eval(e, param, x, &sigma), CJ_OK);
            assert_int_equal(cj_path_motion(p, e, param, x, pt, NULL), CJ_OK);
            const double want = sigma * cj_path_length(p);
            assert_int_equal(cj_path_at_length(p, want, NULL, NULL, &seg, &u), CJ_OK);
            const double err = (double)(fabsl(exact_S(&ch, seg, u) - (long double)sigma * L) / L);
            worst = fmax(worst, err);
            if (err > 1e-10)
                fail_msg("case %d ease %d x=%g: |s - s_wanted| = %.3g of the length", cas, (int)e,
                         x, err);
            ++queries;
        }
        cj_path_destroy(p);
    }
    printf("chains of %d parabolas (cubic form), closed-form lengths: %d queries over 4 ease "
           "profiles, worst |s(t) - s_wanted(t)| = %.3g of L (bound 1e-10); length error %.3g\n",
           NSEG, queries, worst, worst_len);
}

/* A straight path with a very uneven parameterisation: the constant-speed motion must still be
 * uniform along the line. Exact S(u) = |d| g(u). */
static void test_uneven_line(void **state) {
    (void)state;
    const double d[3] = {3, -4, 12}; /* |d| = 13 */
    const double g[4] = {0, 0.01, 0.98, 1};
    double segs[4 * 3];
    for (int i = 0; i < 4; ++i)
        for (int k = 0; k < 3; ++k) segs[i * 3 + k] = 1 + g[i] * d[k];
    cj_path *p = NULL;
    assert_int_equal(cj_path_create(segs, 1, 3, 1e-12, NULL, &p), CJ_OK);
    double worst = 0;
    for (int q = 0; q <= 1000; ++q) {
        double pt[3], tan[3];
        assert_int_equal(cj_path_at_length(p, 13.0 * q / 1000, pt, tan, NULL, NULL), CJ_OK);
        /* distance from the start along d */
        const double along = ((pt[0] - 1) * 3 + (pt[1] - 1) * -4 + (pt[2] - 1) * 12) / 13;
        worst = fmax(worst, fabs(along - 13.0 * q / 1000) / 13);
        if (q > 0 && q < 1000) assert_true(fabs(tan[0] * 13 - 3) < 1e-12);
    }
    printf("straight path with control values 0, 0.01, 0.98, 1: 1001 positions uniform in "
           "arc length to %.3g of L (path tolerance 1e-12)\n",
           worst);
    assert_true(worst <= 1e-12);
    cj_path_destroy(p);
}

static void test_ease_profiles(void **state) {
    (void)state;
    const cj_ease eases[4] = {CJ_EASE_LINEAR, CJ_EASE_SMOOTHSTEP, CJ_EASE_SINE, CJ_EASE_TRAPEZOID};
    for (int e = 0; e < 4; ++e) {
        double s0, s1, prev = -1;
        assert_int_equal(cj_ease_eval(eases[e], 0.25, 0, &s0), CJ_OK);
        assert_int_equal(cj_ease_eval(eases[e], 0.25, 1, &s1), CJ_OK);
        assert_true(s0 == 0 && fabs(s1 - 1) < 1e-15);
        for (int q = 0; q <= 400; ++q) {
            double s;
            assert_int_equal(cj_ease_eval(eases[e], 0.25, q / 400.0, &s), CJ_OK);
            assert_true(s >= prev);
            prev = s;
        }
        if (e > 0) { /* ease-in/out: starts and ends at rest (speed -> 0) */
            double a, b;
            assert_int_equal(cj_ease_eval(eases[e], 0.25, 1e-4, &a), CJ_OK);
            assert_int_equal(cj_ease_eval(eases[e], 0.25, 1 - 1e-4, &b), CJ_OK);
            assert_true(a / 1e-4 < 1e-2 && (1 - b) / 1e-4 < 1e-2);
        }
    }
    /* the trapezoid's phases join continuously in position and speed */
    const double a = 0.3, h = 1e-7;
    double l, m, rr;
    for (int side = 0; side < 2; ++side) {
        const double x = side ? 1 - a : a;
        assert_int_equal(cj_ease_eval(CJ_EASE_TRAPEZOID, a, x - h, &l), CJ_OK);
        assert_int_equal(cj_ease_eval(CJ_EASE_TRAPEZOID, a, x, &m), CJ_OK);
        assert_int_equal(cj_ease_eval(CJ_EASE_TRAPEZOID, a, x + h, &rr), CJ_OK);
        assert_true(fabs((m - l) / h - (rr - m) / h) < 1e-6);
        assert_true(fabs((rr - m) / h - 1 / (1 - a)) < 1e-6);
    }
    double s;
    assert_int_equal(cj_ease_eval(CJ_EASE_TRAPEZOID, 0.6, 0.5, &s), CJ_ERR_RANGE);
    printf("ease profiles: 0 -> 0, 1 -> 1, monotone, at rest at both ends; trapezoid C1 at its "
           "phase joins with cruise speed 1/(1-a)\n");
}

static void test_path_errors(void **state) {
    (void)state;
    double segs[8] = {0, 0, 1, 1, 2, 2, 3, 3};
    cj_path *p = NULL;
    segs[3] = NAN;
    assert_int_equal(cj_path_create(segs, 1, 2, 1e-10, NULL, &p), CJ_ERR_NONFINITE);
    assert_non_null(strstr(cj_last_error(), "segment 0, control point 1"));
    segs[3] = 1;
    assert_int_equal(cj_path_create(segs, 1, 2, 0.0, NULL, &p), CJ_ERR_RANGE);
    const double pt[8] = {1, 1, 1, 1, 1, 1, 1, 1};
    assert_int_equal(cj_path_create(pt, 1, 2, 1e-10, NULL, &p), CJ_ERR_DEGENERATE);
    assert_int_equal(cj_path_create(segs, 0, 2, 1e-10, NULL, &p), CJ_ERR_EMPTY);
    assert_null(p);
    assert_int_equal(cj_path_create(segs, 1, 2, 1e-10, NULL, &p), CJ_OK);
    double out[2];
    assert_int_equal(cj_path_at_length(p, NAN, out, NULL, NULL, NULL), CJ_ERR_NONFINITE);
    assert_int_equal(cj_path_at_length(p, 1e9, out, NULL, NULL, NULL), CJ_OK); /* clamped */
    assert_true(out[0] == 3 && out[1] == 3);
    cj_path_destroy(p);
    printf(
        "paths refuse NaN control points (named), a zero length, a bad tolerance, no segments\n");
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_parabola_chain),
        cmocka_unit_test(test_uneven_line),
        cmocka_unit_test(test_ease_profiles),
        cmocka_unit_test(test_path_errors),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

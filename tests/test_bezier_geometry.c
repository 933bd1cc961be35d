/* Unit tests of the Bézier geometry: subcurve, elevation, reversal, bounding box, control
 * polygon hull, arc length, tangent/normal/curvature, with degenerate cases and bad input.
 * Expected values come from closed forms worked out by hand (see each test), and the hull is
 * checked against an exact MPFR orientation oracle. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "casteljau/bezier.h"
#include "rng.h"

#include <math.h>
#include <mpfr.h>
#include <stdio.h>
#include <string.h>

#define CHECK_CLOSE(a, b, tol)                                                                     \
    do {                                                                                           \
        double a_ = (a), b_ = (b), t_ = (tol);                                                     \
        if (!(fabs(a_ - b_) <= t_))                                                                \
            fail_msg("%s = %.17g, expected %s = %.17g (tol %.3g)", #a, a_, #b, b_, t_);            \
    } while (0)

static void eval(const cj_bezier *c, double t, double *out) {
    assert_int_equal(cj_bezier_eval_decasteljau(c, t, out), CJ_OK);
}

/* ---- subcurve / elevate / reverse -------------------------------------------------------- */

static const double cubic2[] = {0, 0, 1, 3, 4, -1, 5, 2};

static void test_subcurve(void **state) {
    (void)state;
    cj_bezier c = cj_bezier_view(3, 2, cubic2);
    double piece[8], rev[8];
    const double a = 0.25, b = 0.75; /* dyadic: a + (b-a)u is exact below */
    assert_int_equal(cj_bezier_subcurve(&c, a, b, piece), CJ_OK);
    assert_int_equal(cj_bezier_subcurve(&c, b, a, rev), CJ_OK);
    cj_bezier cp = cj_bezier_view(3, 2, piece), cr = cj_bezier_view(3, 2, rev);
    for (int j = 0; j <= 16; ++j) {
        const double u = j / 16.0;
        double p[2], q[2], r[2];
        eval(&cp, u, p);
        eval(&c, a + (b - a) * u, q);
        eval(&cr, u, r);
        double q2[2];
        eval(&c, b + (a - b) * u, q2);
        for (int k = 0; k < 2; ++k) {
            CHECK_CLOSE(p[k], q[k], 1e-14);
            CHECK_CLOSE(r[k], q2[k], 1e-14);
        }
    }
    /* Full interval is the curve itself; [0, b] is the left split. */
    double full[8], left[8], split[8];
    assert_int_equal(cj_bezier_subcurve(&c, 0.0, 1.0, full), CJ_OK);
    assert_memory_equal(full, cubic2, sizeof full);
    assert_int_equal(cj_bezier_subcurve(&c, 0.0, 0.5, left), CJ_OK);
    assert_int_equal(cj_bezier_split(&c, 0.5, split, NULL), CJ_OK);
    assert_memory_equal(left, split, sizeof left);
    /* Bad input: out untouched. */
    double guard[8];
    memcpy(guard, cubic2, sizeof guard);
    assert_int_equal(cj_bezier_subcurve(&c, 0.3, 0.3, guard), CJ_ERR_ARGUMENT);
    assert_int_equal(cj_bezier_subcurve(&c, -0.1, 0.3, guard), CJ_ERR_RANGE);
    assert_int_equal(cj_bezier_subcurve(&c, 0.1, 1.5, guard), CJ_ERR_RANGE);
    assert_int_equal(cj_bezier_subcurve(&c, NAN, 0.3, guard), CJ_ERR_NONFINITE);
    assert_non_null(strstr(cj_last_error(), "start a"));
    assert_memory_equal(guard, cubic2, sizeof guard);
}

static void test_elevate(void **state) {
    (void)state;
    /* Quadratic -> cubic by the textbook formula: b0, (b0 + 2 b1)/3, (2 b1 + b2)/3, b2. */
    const double q[] = {0, 0, 3, 6, 6, 0};
    cj_bezier c = cj_bezier_view(2, 2, q);
    double e1[8];
    assert_int_equal(cj_bezier_elevate(&c, 1, e1), CJ_OK);
    const double want[] = {0, 0, 2, 4, 4, 4, 6, 0};
    for (int i = 0; i < 8; ++i) CHECK_CLOSE(e1[i], want[i], 1e-15);
    /* r = 0 copies; r = 5 keeps the curve. */
    double e0[6];
    assert_int_equal(cj_bezier_elevate(&c, 0, e0), CJ_OK);
    assert_memory_equal(e0, q, sizeof q);
    double e5[16];
    assert_int_equal(cj_bezier_elevate(&c, 5, e5), CJ_OK);
    cj_bezier c5 = cj_bezier_view(7, 2, e5);
    for (int j = 0; j <= 20; ++j) {
        double a[2], b[2];
        eval(&c, j / 20.0, a);
        eval(&c5, j / 20.0, b);
        CHECK_CLOSE(a[0], b[0], 1e-14);
        CHECK_CLOSE(a[1], b[1], 1e-14);
    }
    /* Degree 0 elevated: all copies of the point. */
    const double pt[] = {7, -1};
    cj_bezier c0 = cj_bezier_view(0, 2, pt);
    double ep[6];
    assert_int_equal(cj_bezier_elevate(&c0, 2, ep), CJ_OK);
    for (int i = 0; i < 3; ++i) assert_true(ep[2 * i] == 7 && ep[2 * i + 1] == -1);
    assert_int_equal(cj_bezier_elevate(&c, -1, e1), CJ_ERR_ARGUMENT);
    assert_int_equal(cj_bezier_elevate(&c, CJ_BEZIER_MAX_DEGREE - 1, e1), CJ_ERR_DEGREE);
    assert_non_null(strstr(cj_last_error(), "exceeds"));
}

static void test_reverse(void **state) {
    (void)state;
    cj_bezier c = cj_bezier_view(3, 2, cubic2);
    double r[8];
    assert_int_equal(cj_bezier_reverse(&c, r), CJ_OK);
    const double want[] = {5, 2, 4, -1, 1, 3, 0, 0};
    assert_memory_equal(r, want, sizeof r);
    /* In place, twice: back to the original. */
    double w[8];
    memcpy(w, cubic2, sizeof w);
    cj_bezier cw = cj_bezier_view(3, 2, w);
    assert_int_equal(cj_bezier_reverse(&cw, w), CJ_OK);
    assert_memory_equal(w, want, sizeof w);
    assert_int_equal(cj_bezier_reverse(&cw, w), CJ_OK);
    assert_memory_equal(w, cubic2, sizeof w);
    const double bad[] = {0, 0, INFINITY, 1};
    cj_bezier cb = cj_bezier_view(1, 2, bad);
    assert_int_equal(cj_bezier_reverse(&cb, r), CJ_ERR_NONFINITE);
}

/* ---- bbox -------------------------------------------------------------------------------- */

static void test_bbox_closed_forms(void **state) {
    (void)state;
    /* Quadratic (0,0) (1,2) (2,0): y = 4t(1-t), max 1 at t = 1/2; x = 2t. */
    const double quad[] = {0, 0, 1, 2, 2, 0};
    cj_bezier c = cj_bezier_view(2, 2, quad);
    double lo[2], hi[2];
    assert_int_equal(cj_bezier_bbox(&c, lo, hi), CJ_OK);
    CHECK_CLOSE(lo[0], 0, 0);
    CHECK_CLOSE(hi[0], 2, 0);
    CHECK_CLOSE(lo[1], 0, 0);
    CHECK_CLOSE(hi[1], 1, 1e-15);
    /* x-coordinates (0, 3, -3, 0): x = 9 t (1-t)(1-2t), extremes at t = (3 -+ sqrt3)/6 with
     * values +-sqrt(3)/2. The control polygon box [-3, 3] is far from tight. */
    const double s[] = {0, 0, 3, 1, -3, 1, 0, 0};
    cj_bezier cs = cj_bezier_view(3, 2, s);
    assert_int_equal(cj_bezier_bbox(&cs, lo, hi), CJ_OK);
    CHECK_CLOSE(hi[0], sqrt(3.0) / 2, 4e-16);
    CHECK_CLOSE(lo[0], -sqrt(3.0) / 2, 4e-16);
    CHECK_CLOSE(hi[1], 0.75, 2e-16); /* y = 3t(1-t): max 3/4 */
    CHECK_CLOSE(lo[1], 0, 0);
    /* Degree 0 and a straight line with repeated control points. */
    const double pt[] = {1, 2, 3};
    cj_bezier c0 = cj_bezier_view(0, 3, pt);
    double l3[3], h3[3];
    assert_int_equal(cj_bezier_bbox(&c0, l3, h3), CJ_OK);
    for (int k = 0; k < 3; ++k) assert_true(l3[k] == pt[k] && h3[k] == pt[k]);
    const double line[] = {0, 0, 0, 0, 1, 1, 1, 1, 1, 1};
    cj_bezier cl = cj_bezier_view(4, 2, line);
    assert_int_equal(cj_bezier_bbox(&cl, lo, hi), CJ_OK);
    assert_true(lo[0] == 0 && lo[1] == 0 && hi[0] == 1 && hi[1] == 1);
    /* A constant coordinate: derivative identically zero. */
    const double flat[] = {0, 5, 1, 5, 2, 5, 3, 5};
    cj_bezier cf = cj_bezier_view(3, 2, flat);
    assert_int_equal(cj_bezier_bbox(&cf, lo, hi), CJ_OK);
    assert_true(lo[1] == 5 && hi[1] == 5);
    const double bad[] = {0, 0, NAN, 1, 2, 2};
    cj_bezier cb = cj_bezier_view(2, 2, bad);
    assert_int_equal(cj_bezier_bbox(&cb, lo, hi), CJ_ERR_NONFINITE);
    assert_non_null(strstr(cj_last_error(), "control point 1"));
}

/* A double root of the derivative (x = (2t-1)^3 style plateau) and a root exactly at a split
 * point: the isolator must neither miss extrema nor invent any. Degree 30 wiggle checked
 * against dense sampling refined by golden section. */
static void test_bbox_hard_cases(void **state) {
    (void)state;
    /* x(t) = (2t-1)^3: monotone, derivative has a double root at 1/2. Bernstein coefficients
     * of (2t-1)^3 are -1, 1/3, -1/3, 1. */
    const double plateau[] = {-1, 1.0 / 3, -1.0 / 3, 1};
    cj_bezier cp = cj_bezier_view(3, 1, plateau);
    double lo, hi;
    assert_int_equal(cj_bezier_bbox(&cp, &lo, &hi), CJ_OK);
    CHECK_CLOSE(lo, -1, 0);
    CHECK_CLOSE(hi, 1, 0);
    /* x = -(t-1/2)^4/4 + 9/128 (t-1/2)^2: global minimum 0 at t = 1/2, exactly where the
     * isolator splits (its derivative's Bernstein coefficients (7,-19,19,-7)/512 have three sign
     * changes), and maximum 81/16384 at t = 1/8 and 7/8. Bernstein coefficients by hand from
     * the power form. */
    const double split_root[] = {1.0 / 512, 1.0 / 64, -11.0 / 512, 1.0 / 64, 1.0 / 512};
    cj_bezier cr = cj_bezier_view(4, 1, split_root);
    assert_int_equal(cj_bezier_bbox(&cr, &lo, &hi), CJ_OK);
    CHECK_CLOSE(lo, 0.0, 1e-18);
    CHECK_CLOSE(hi, 81.0 / 16384, 1e-17);
    /* Degree 30 in 1D: sum of cosines sampled into control points (any data will do). */
    double w[31];
    for (int i = 0; i <= 30; ++i) w[i] = cos(1.7 * i) + 0.3 * sin(5.1 * i);
    cj_bezier cw = cj_bezier_view(30, 1, w);
    assert_int_equal(cj_bezier_bbox(&cw, &lo, &hi), CJ_OK);
    double smax = -INFINITY, smin = INFINITY;
    const int ns = 20000;
    for (int j = 0; j <= ns; ++j) {
        double v;
        eval(&cw, (double)j / ns, &v);
        smax = fmax(smax, v);
        smin = fmin(smin, v);
    }
    assert_true(lo <= smin + 1e-15 && hi >= smax - 1e-15);
    /* Dense sampling misses the true extreme by at most O(h^2 |x''|): h = 5e-5, |x''| < 1e4. */
    assert_true(smin - lo < 1e-4 && hi - smax < 1e-4);
    printf("bbox degree 30: [%.17g, %.17g], dense sampling [%.17g, %.17g]\n", lo, hi, smin, smax);
}

/* ---- hull -------------------------------------------------------------------------------- */

/* Exact orientation sign of (a-o) x (b-o) with MPFR (300 bits: exact for these inputs). */
static int mp_orient(const double *o, const double *a, const double *b) {
    mpfr_t ax, ay, bx, by, l, r;
    mpfr_inits2(300, ax, ay, bx, by, l, r, (mpfr_ptr)0);
    mpfr_set_d(ax, a[0], MPFR_RNDN);
    mpfr_sub_d(ax, ax, o[0], MPFR_RNDN);
    mpfr_set_d(ay, a[1], MPFR_RNDN);
    mpfr_sub_d(ay, ay, o[1], MPFR_RNDN);
    mpfr_set_d(bx, b[0], MPFR_RNDN);
    mpfr_sub_d(bx, bx, o[0], MPFR_RNDN);
    mpfr_set_d(by, b[1], MPFR_RNDN);
    mpfr_sub_d(by, by, o[1], MPFR_RNDN);
    mpfr_mul(l, ax, by, MPFR_RNDN);
    mpfr_mul(r, ay, bx, MPFR_RNDN);
    mpfr_sub(l, l, r, MPFR_RNDN);
    int s = mpfr_sgn(l);
    mpfr_clears(ax, ay, bx, by, l, r, (mpfr_ptr)0);
    return s;
}

/* Checks a hull against the exact oracle: strictly convex ccw, every point inside or on. */
static void check_hull_exact(const double *p, int np, const int *idx, int count) {
    assert_true(count >= 1 && count <= np);
    /* Start: lowest, then leftmost. */
    for (int i = 0; i < np; ++i) {
        const double *s = p + 2 * idx[0];
        assert_true(p[2 * i + 1] > s[1] || (p[2 * i + 1] == s[1] && p[2 * i] >= s[0]));
    }
    if (count >= 3) {
        for (int i = 0; i < count; ++i) {
            const double *a = p + 2 * idx[i], *b = p + 2 * idx[(i + 1) % count],
                         *cc = p + 2 * idx[(i + 2) % count];
            assert_int_equal(mp_orient(a, b, cc), 1);
            for (int j = 0; j < np; ++j) assert_true(mp_orient(a, b, p + 2 * j) >= 0);
        }
    } else if (count == 2) {
        for (int j = 0; j < np; ++j)
            assert_int_equal(mp_orient(p + 2 * idx[0], p + 2 * idx[1], p + 2 * j), 0);
    }
}

static void test_hull_known(void **state) {
    (void)state;
    /* Square (0,0) (4,0) (4,4) (0,4) with interior points and points on edges. */
    const double p[] = {2, 2, 0, 0, 4, 0, 2, 0, 4, 4, 0, 4, 1, 1, 4, 2};
    cj_bezier c = cj_bezier_view(7, 2, p);
    int idx[8], count = -1;
    assert_int_equal(cj_bezier_hull2d(&c, idx, &count), CJ_OK);
    assert_int_equal(count, 4);
    const int want[] = {1, 2, 4, 5};
    assert_memory_equal(idx, want, sizeof want);
    /* All equal: one vertex, the lowest index. */
    const double same[] = {3, 3, 3, 3, 3, 3};
    cj_bezier cs = cj_bezier_view(2, 2, same);
    assert_int_equal(cj_bezier_hull2d(&cs, idx, &count), CJ_OK);
    assert_int_equal(count, 1);
    assert_int_equal(idx[0], 0);
    /* All collinear (with a repeat): the two extremes, lowest first. */
    const double col[] = {1, 1, 3, 3, 0, 0, 2, 2, 3, 3};
    cj_bezier cc = cj_bezier_view(4, 2, col);
    assert_int_equal(cj_bezier_hull2d(&cc, idx, &count), CJ_OK);
    assert_int_equal(count, 2);
    assert_int_equal(idx[0], 2);
    assert_int_equal(idx[1], 1);
    /* Horizontal collinear: lowest-then-leftmost first. */
    const double hor[] = {5, 1, -2, 1, 0, 1};
    cj_bezier ch = cj_bezier_view(2, 2, hor);
    assert_int_equal(cj_bezier_hull2d(&ch, idx, &count), CJ_OK);
    assert_int_equal(count, 2);
    assert_true(idx[0] == 1 && idx[1] == 0);
    /* Degree 0. */
    cj_bezier c0 = cj_bezier_view(0, 2, p);
    assert_int_equal(cj_bezier_hull2d(&c0, idx, &count), CJ_OK);
    assert_int_equal(count, 1);
    /* Bad input. */
    cj_bezier c3 = cj_bezier_view(1, 3, p);
    assert_int_equal(cj_bezier_hull2d(&c3, idx, &count), CJ_ERR_DIMENSION);
    const double bad[] = {0, 0, NAN, 0};
    cj_bezier cb = cj_bezier_view(1, 2, bad);
    assert_int_equal(cj_bezier_hull2d(&cb, idx, &count), CJ_ERR_NONFINITE);
}

/* Nearly collinear points (a line y = 0.3 x + 0.1 rounded to doubles, plus perturbations of a
 * few ulps) defeat a naive floating-point orientation test; the hull must still be exactly
 * convex and contain every point, checked with MPFR. */
static void test_hull_near_degenerate(void **state) {
    (void)state;
    cj_rng rng;
    const uint64_t seed = cj_test_seed("hull near-degenerate", 20261121);
    cj_rng_init(&rng, seed);
    const int cases = 300;
    for (int cs = 0; cs < cases; ++cs) {
        const int np = cj_rng_int(&rng, 3, 40);
        double p[2 * 40];
        for (int i = 0; i < np; ++i) {
            const double x = cj_rng_range(&rng, -1, 1) * (cs % 2 ? 1e6 : 1.0);
            double y = 0.3 * x + 0.1;
            const int wiggle = cj_rng_int(&rng, -2, 2);
            y = wiggle ? y + wiggle * 2.3e-16 * fabs(y) : y;
            p[2 * i] = x;
            p[2 * i + 1] = y;
        }
        cj_bezier c = cj_bezier_view(np - 1, 2, p);
        int idx[40], count;
        assert_int_equal(cj_bezier_hull2d(&c, idx, &count), CJ_OK);
        check_hull_exact(p, np, idx, count);
    }
    printf("hull: %d near-collinear point sets exactly convex and containing (MPFR)\n", cases);
}

/* ---- arc length -------------------------------------------------------------------------- */

static void test_arclength(void **state) {
    (void)state;
    /* Parabola (0,0) (1,2) (2,0): speed sqrt(4 + (4-8t)^2), length
     * (sqrt(20) + ln((4 + sqrt(20))/2)) / 2. */
    const double quad[] = {0, 0, 1, 2, 2, 0};
    cj_bezier c = cj_bezier_view(2, 2, quad);
    const double exact = 0.5 * (sqrt(20.0) + log((4.0 + sqrt(20.0)) / 2.0));
    double len, err;
    assert_int_equal(cj_bezier_arclength(&c, 0, 1, 1e-12, &len, &err), CJ_OK);
    CHECK_CLOSE(len, exact, 1e-12);
    assert_true(err <= 1e-12);
    /* Line with uneven control points (not arc-length parametrised) in 3D. */
    const double line[] = {0, 0, 0, 0.1, 0.2, 0.2, 2, 4, 4, 3, 6, 6};
    cj_bezier cl = cj_bezier_view(3, 3, line);
    assert_int_equal(cj_bezier_arclength(&cl, 0, 1, 1e-10, &len, NULL), CJ_OK);
    CHECK_CLOSE(len, 9.0, 1e-10);
    /* Turn-around with zero speed at t = 1/2: x = 2t(1-t) goes 0 -> 1/2 -> 0, length 1. */
    const double back[] = {0, 0, 1, 0, 0, 0};
    cj_bezier cb = cj_bezier_view(2, 2, back);
    assert_int_equal(cj_bezier_arclength(&cb, 0, 1, 1e-12, &len, &err), CJ_OK);
    CHECK_CLOSE(len, 1.0, 1e-12);
    assert_int_equal(cj_bezier_arclength(&cb, 0.25, 0.5, 1e-12, &len, &err), CJ_OK);
    CHECK_CLOSE(len, 0.125, 1e-12);
    /* Empty interval and a single point. */
    assert_int_equal(cj_bezier_arclength(&c, 0.3, 0.3, 1e-9, &len, &err), CJ_OK);
    assert_true(len == 0 && err == 0);
    cj_bezier c0 = cj_bezier_view(0, 2, quad);
    assert_int_equal(cj_bezier_arclength(&c0, 0, 1, 1e-9, &len, &err), CJ_OK);
    assert_true(len == 0);
    /* Cap: an unreachable tolerance still writes the value and its estimate. */
    len = -1;
    err = -1;
    assert_int_equal(cj_bezier_arclength(&c, 0, 1, 1e-300, &len, &err), CJ_ERR_CAP);
    CHECK_CLOSE(len, exact, 1e-12);
    assert_true(err >= 0 && err < 1e-10);
    /* Bad input. */
    assert_int_equal(cj_bezier_arclength(&c, 0.6, 0.4, 1e-9, &len, &err), CJ_ERR_RANGE);
    assert_int_equal(cj_bezier_arclength(&c, 0, 1.1, 1e-9, &len, &err), CJ_ERR_RANGE);
    assert_int_equal(cj_bezier_arclength(&c, 0, 1, 0.0, &len, &err), CJ_ERR_ARGUMENT);
    assert_int_equal(cj_bezier_arclength(&c, 0, 1, NAN, &len, &err), CJ_ERR_NONFINITE);
    assert_non_null(strstr(cj_last_error(), "tolerance"));
}

/* ---- tangent, normal, curvature ---------------------------------------------------------- */

static void test_frame_regular(void **state) {
    (void)state;
    /* Parabola at t = 1/2: c' = (2, 0), c'' = (0, -8): tangent (1,0), left normal (0,1),
     * signed curvature (x'y'' - y'x'')/|c'|^3 = -16/8 = -2. */
    const double quad[] = {0, 0, 1, 2, 2, 0};
    cj_bezier c = cj_bezier_view(2, 2, quad);
    double tg[2], nm[2], k;
    int order = 0;
    assert_int_equal(cj_bezier_tangent(&c, 0.5, tg, &order), CJ_OK);
    assert_int_equal(order, 1);
    CHECK_CLOSE(tg[0], 1, 1e-15);
    CHECK_CLOSE(tg[1], 0, 1e-15);
    assert_int_equal(cj_bezier_normal(&c, 0.5, nm), CJ_OK);
    CHECK_CLOSE(nm[0], 0, 1e-15);
    CHECK_CLOSE(nm[1], 1, 1e-15);
    assert_int_equal(cj_bezier_curvature(&c, 0.5, &k), CJ_OK);
    CHECK_CLOSE(k, -2, 1e-14);
    /* 3D cubic at t = 0.3 against the textbook formulas from the derivatives. */
    const double sp[] = {0, 0, 0, 1, 0, 1, 1, 1, 2, 0, 2, 3};
    cj_bezier c3 = cj_bezier_view(3, 3, sp);
    double dv[9];
    assert_int_equal(cj_bezier_eval_derivs(&c3, 0.3, 2, dv), CJ_OK);
    const double *d1 = dv + 3, *d2 = dv + 6;
    const double cr[3] = {d1[1] * d2[2] - d1[2] * d2[1], d1[2] * d2[0] - d1[0] * d2[2],
                          d1[0] * d2[1] - d1[1] * d2[0]};
    const double s1 = sqrt(d1[0] * d1[0] + d1[1] * d1[1] + d1[2] * d1[2]);
    const double kref = sqrt(cr[0] * cr[0] + cr[1] * cr[1] + cr[2] * cr[2]) / (s1 * s1 * s1);
    assert_int_equal(cj_bezier_curvature(&c3, 0.3, &k), CJ_OK);
    CHECK_CLOSE(k, kref, 1e-13 * kref);
    double t3[3], n3[3];
    assert_int_equal(cj_bezier_tangent(&c3, 0.3, t3, NULL), CJ_OK);
    assert_int_equal(cj_bezier_normal(&c3, 0.3, n3), CJ_OK);
    /* Principal normal: unit, orthogonal to T, in the plane of c', c'' and towards c''. */
    double dot_tn = 0, dot_nn = 0, dot_n2 = 0, dot_ncr = 0;
    for (int i = 0; i < 3; ++i) {
        dot_tn += t3[i] * n3[i];
        dot_nn += n3[i] * n3[i];
        dot_n2 += n3[i] * d2[i];
        dot_ncr += n3[i] * cr[i];
        CHECK_CLOSE(t3[i], d1[i] / s1, 1e-15);
    }
    CHECK_CLOSE(dot_tn, 0, 1e-15);
    CHECK_CLOSE(dot_nn, 1, 1e-15);
    CHECK_CLOSE(dot_ncr, 0, 1e-13);
    assert_true(dot_n2 > 0);
}

/* c(t) = q(t^2) for a quadratic q(s) = A + B s + C s^2: zero speed at t = 0 but the same
 * geometry as q at s = 0, so tangent = B/|B| (order 2) and curvature = (B x 2C)/|B|^3.
 * Power-to-Bernstein (degree 4): b0 = b1 = A, b2 = A + B/6, b3 = A + B/2, b4 = A + B + C. */
static void test_frame_zero_speed(void **state) {
    (void)state;
    const double A[2] = {1, 2}, B[2] = {3, 1}, C[2] = {-1, 2};
    double p[10];
    for (int k = 0; k < 2; ++k) {
        p[0 + k] = A[k];
        p[2 + k] = A[k];
        p[4 + k] = A[k] + B[k] / 6;
        p[6 + k] = A[k] + B[k] / 2;
        p[8 + k] = A[k] + B[k] + C[k];
    }
    cj_bezier c = cj_bezier_view(4, 2, p);
    double tg[2], k;
    int order;
    assert_int_equal(cj_bezier_tangent(&c, 0.0, tg, &order), CJ_OK);
    assert_int_equal(order, 2);
    const double nb = hypot(B[0], B[1]);
    CHECK_CLOSE(tg[0], B[0] / nb, 1e-15);
    CHECK_CLOSE(tg[1], B[1] / nb, 1e-15);
    assert_int_equal(cj_bezier_curvature(&c, 0.0, &k), CJ_OK);
    const double kq = (B[0] * 2 * C[1] - B[1] * 2 * C[0]) / (nb * nb * nb);
    CHECK_CLOSE(k, kq, 1e-13 * fabs(kq));
    /* The tangent at the zero-speed point is the limit from above. */
    double dv[4];
    assert_int_equal(cj_bezier_eval_derivs(&c, 1e-7, 1, dv), CJ_OK);
    const double s = hypot(dv[2], dv[3]);
    CHECK_CLOSE(tg[0], dv[2] / s, 1e-6);
    CHECK_CLOSE(tg[1], dv[3] / s, 1e-6);
    /* Same answer at extreme scales: the vanishing test is relative to the curve's size. */
    for (int e = -1; e <= 1; e += 2) {
        double ps[10];
        for (int i = 0; i < 10; ++i) ps[i] = ldexp(p[i], e * 600);
        cj_bezier cs = cj_bezier_view(4, 2, ps);
        double ts[2];
        assert_int_equal(cj_bezier_tangent(&cs, 0.0, ts, &order), CJ_OK);
        assert_int_equal(order, 2);
        CHECK_CLOSE(ts[0], tg[0], 1e-15);
        double ks;
        assert_int_equal(cj_bezier_curvature(&cs, 0.0, &ks), CJ_OK);
        CHECK_CLOSE(ldexp(ks, e * 600), k, 1e-13 * fabs(k));
    }
    /* An ordinary cusp: cubic with b0 = b1 and a transverse third difference; the curvature
     * is unbounded there, the tangent is still defined. */
    const double cusp[] = {0, 0, 0, 0, 1, 0, 1, 1};
    cj_bezier cc = cj_bezier_view(3, 2, cusp);
    assert_int_equal(cj_bezier_tangent(&cc, 0.0, tg, &order), CJ_OK);
    assert_int_equal(order, 2);
    CHECK_CLOSE(tg[0], 1, 1e-15);
    assert_int_equal(cj_bezier_curvature(&cc, 0.0, &k), CJ_ERR_DEGENERATE);
    assert_non_null(strstr(cj_last_error(), "cusp"));
    /* The cusp of the symmetric cubic (0,0) (1,1) (0,1) (1,0) at t = 1/2: c'(1/2) = 0. */
    const double sym[] = {0, 0, 1, 1, 0, 1, 1, 0};
    cj_bezier cy = cj_bezier_view(3, 2, sym);
    assert_int_equal(cj_bezier_tangent(&cy, 0.5, tg, &order), CJ_OK);
    assert_int_equal(order, 2);
}

static void test_frame_degenerate(void **state) {
    (void)state;
    /* Single point (repeated): everything degenerate. */
    const double pt[] = {1, 2, 3, 1, 2, 3, 1, 2, 3};
    cj_bezier c = cj_bezier_view(2, 3, pt);
    double v[3], k;
    assert_int_equal(cj_bezier_tangent(&c, 0.4, v, NULL), CJ_ERR_DEGENERATE);
    assert_int_equal(cj_bezier_normal(&c, 0.4, v), CJ_ERR_DEGENERATE);
    assert_int_equal(cj_bezier_curvature(&c, 0.4, &k), CJ_ERR_DEGENERATE);
    cj_bezier c0 = cj_bezier_view(0, 3, pt);
    assert_int_equal(cj_bezier_tangent(&c0, 0.4, v, NULL), CJ_ERR_DEGENERATE);
    /* Straight 3D line: no principal normal, curvature 0; 2D line: left normal exists. */
    const double line3[] = {0, 0, 0, 1, 1, 1, 3, 3, 3};
    cj_bezier cl = cj_bezier_view(2, 3, line3);
    assert_int_equal(cj_bezier_normal(&cl, 0.2, v), CJ_ERR_DEGENERATE);
    assert_int_equal(cj_bezier_curvature(&cl, 0.2, &k), CJ_OK);
    assert_true(k == 0.0);
    const double line2[] = {0, 0, 1, 2, 2, 4};
    cj_bezier c2 = cj_bezier_view(2, 2, line2);
    assert_int_equal(cj_bezier_normal(&c2, 0.2, v), CJ_OK);
    CHECK_CLOSE(v[0], -2 / sqrt(5.0), 1e-15);
    CHECK_CLOSE(v[1], 1 / sqrt(5.0), 1e-15);
    /* Inflection of (0,0) (1,1) (2,-1) (3,0) at t = 1/2: curvature 0 up to rounding. */
    const double infl[] = {0, 0, 1, 1, 2, -1, 3, 0};
    cj_bezier ci = cj_bezier_view(3, 2, infl);
    assert_int_equal(cj_bezier_curvature(&ci, 0.5, &k), CJ_OK);
    CHECK_CLOSE(k, 0, 1e-15);
    /* Bad input. */
    const double p4[] = {0, 0, 0, 0, 1, 1, 1, 1};
    cj_bezier c4 = cj_bezier_view(1, 4, p4);
    double v4[4];
    assert_int_equal(cj_bezier_tangent(&c4, 0.5, v4, NULL), CJ_OK);
    assert_int_equal(cj_bezier_normal(&c4, 0.5, v4), CJ_ERR_DIMENSION);
    assert_int_equal(cj_bezier_curvature(&c4, 0.5, &k), CJ_ERR_DIMENSION);
    assert_int_equal(cj_bezier_tangent(&c2, NAN, v, NULL), CJ_ERR_NONFINITE);
    cj_bezier ce = cj_bezier_view(-1, 2, line2);
    assert_int_equal(cj_bezier_tangent(&ce, 0.5, v, NULL), CJ_ERR_EMPTY);
}

/* The largest degree the API accepts: bbox, hull, arc length, frames and elevation still work
 * (fixed stack work space) and agree with independent checks. */
static void test_max_degree(void **state) {
    (void)state;
    enum { N = CJ_BEZIER_MAX_DEGREE };
    static double p[(N + 1) * 2];
    cj_rng rng;
    cj_rng_init(&rng, cj_test_seed("max degree", 255));
    for (int i = 0; i < (N + 1) * 2; ++i) p[i] = cj_rng_range(&rng, -1, 1);
    cj_bezier c = cj_bezier_view(N, 2, p);
    /* bbox vs 8001 samples: contains them, and sampling gets within O(h^2) of each face. The
     * same samples give inscribed polylines with 4000 and 8000 segments for the length. */
    double lo[2], hi[2];
    assert_int_equal(cj_bezier_bbox(&c, lo, hi), CJ_OK);
    double slo[2] = {INFINITY, INFINITY}, shi[2] = {-INFINITY, -INFINITY};
    double poly = 0, poly_half = 0, prev[2], prev2[2];
    const int ns = 8000;
    for (int j = 0; j <= ns; ++j) {
        double v[2];
        eval(&c, (double)j / ns, v);
        for (int k = 0; k < 2; ++k) {
            slo[k] = fmin(slo[k], v[k]);
            shi[k] = fmax(shi[k], v[k]);
        }
        if (j) poly += hypot(v[0] - prev[0], v[1] - prev[1]);
        if (j && j % 2 == 0) poly_half += hypot(v[0] - prev2[0], v[1] - prev2[1]);
        prev[0] = v[0];
        prev[1] = v[1];
        if (j % 2 == 0) {
            prev2[0] = v[0];
            prev2[1] = v[1];
        }
    }
    for (int k = 0; k < 2; ++k) {
        assert_true(lo[k] <= slo[k] + 1e-13 && hi[k] >= shi[k] - 1e-13);
        assert_true(slo[k] - lo[k] < 1e-5 && hi[k] - shi[k] < 1e-5);
    }
    /* Hull of 256 points, exact check. */
    int idx[N + 1], count;
    assert_int_equal(cj_bezier_hull2d(&c, idx, &count), CJ_OK);
    check_hull_exact(p, N + 1, idx, count);
    /* Arc length: at least the inscribed polyline, at most the control polygon, and equal to
     * the Richardson limit of the polylines (their error falls like h^2) up to a fraction of
     * the last correction. */
    double len, err, ctrl = 0;
    for (int i = 0; i < N; ++i) ctrl += hypot(p[2 * i + 2] - p[2 * i], p[2 * i + 3] - p[2 * i + 1]);
    const cj_status st = cj_bezier_arclength(&c, 0, 1, 1e-9, &len, &err);
    assert_int_equal(st, CJ_OK);
    assert_true(len >= poly - 1e-9 && len <= ctrl);
    const double rich = poly + (poly - poly_half) / 3;
    if (!(fabs(len - rich) <= 0.05 * (poly - poly_half) + 1e-9))
        fail_msg("length %.15g, polylines %.15g %.15g, Richardson %.15g", len, poly_half, poly,
                 rich);
    /* Frames and elevation to the limit. */
    double tg[2], k;
    assert_int_equal(cj_bezier_tangent(&c, 0.37, tg, NULL), CJ_OK);
    assert_int_equal(cj_bezier_curvature(&c, 0.37, &k), CJ_OK);
    cj_bezier c200 = cj_bezier_view(200, 2, p);
    static double el[(N + 1) * 2];
    assert_int_equal(cj_bezier_elevate(&c200, N - 200, el), CJ_OK);
    assert_int_equal(cj_bezier_elevate(&c200, N - 199, el), CJ_ERR_DEGREE);
    printf("degree %d: bbox [%.6f,%.6f]x[%.6f,%.6f], hull %d vertices, length %.12f (polyline "
           "Richardson %.12f, estimate %.2g)\n",
           N, lo[0], hi[0], lo[1], hi[1], count, len, rich, err);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_subcurve),
        cmocka_unit_test(test_elevate),
        cmocka_unit_test(test_reverse),
        cmocka_unit_test(test_bbox_closed_forms),
        cmocka_unit_test(test_bbox_hard_cases),
        cmocka_unit_test(test_hull_known),
        cmocka_unit_test(test_hull_near_degenerate),
        cmocka_unit_test(test_arclength),
        cmocka_unit_test(test_frame_regular),
        cmocka_unit_test(test_frame_zero_speed),
        cmocka_unit_test(test_frame_degenerate),
        cmocka_unit_test(test_max_degree),
    };
    printf("bezier geometry: subcurve/elevate/reverse, bbox closed forms, hull vs MPFR, arc "
           "length closed forms, frames incl. cusps and zero speed\n");
    return cmocka_run_group_tests(tests, NULL, NULL);
}

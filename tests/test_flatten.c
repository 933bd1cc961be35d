/* Flattening: the proven bound holds against dense sampling of the exact curve (an independent
 * long-double evaluator), on random curves of degrees 2-10 (polynomial and rational, 2D and
 * 3D) and on hard shapes; the quarter circle needs 12 segments; caps and errors are reported.
 * The oracle lives in flatten_oracle.c, the fast planar path's test in flatten_fast_path.c. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "casteljau/flatten.h"
#include "flatten_internal.h" /* the cheap and refined piece bounds, compared directly */
#include "flatten_test.h"
#include "rng.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *mname(int m) {
    return m == CJ_FLATTEN_UNIFORM     ? "uniform"
           : m == CJ_FLATTEN_SUBDIVIDE ? "subdivide"
                                       : "near-opt";
}

/* Flattens with every method and checks the contract; returns the near-optimal count. */
static size_t check_curve(int n, int d, const double *pts, const double *w, double tol,
                          const char *what, int per) {
    size_t nopt = 0;
    double scale = 0;
    for (int i = 0; i < (n + 1) * d; ++i) scale = fmax(scale, fabs(pts[i]));
    for (int m = 0; m < CJ_FLATTEN_METHOD_COUNT_; ++m) {
        cj_flatten_opts o = cj_flatten_defaults((cj_flatten_method)m, tol);
        poly p = {.d = d};
        cj_flatten_stats st;
        cj_bezier c = cj_bezier_view(n, d, pts);
        cj_rbezier rc = cj_rbezier_view(n, d, pts, w);
        cj_status s = w ? cj_flatten_rbezier_cb(&rc, &o, sink, &p, &st)
                        : cj_flatten_bezier_cb(&c, &o, sink, &p, &st);
        if (s != CJ_OK)
            fail_msg("%s (%s, tol %g): status %d: %s", what, mname(m), tol, s, cj_last_error());
        double verr;
        const double dev = measure(n, d, pts, w, &p, per, &verr);
        if (!(st.bound <= tol) || !(dev <= st.bound * (1 + 1e-9) + 1e-12 * scale) ||
            st.segments + 1 != p.n || p.ts[0] != 0.0 || p.ts[p.n - 1] != 1.0 ||
            verr > 1e-11 * scale)
            fail_msg("%s (%s, tol %g): segments %zu points %zu bound %g measured %g vertex err %g",
                     what, mname(m), tol, st.segments, p.n, st.bound, dev, verr);
        /* Endpoints exact, parameters increasing. */
        for (int k = 0; k < d; ++k) {
            assert_true(p.pts[k] == pts[k]);
            assert_true(p.pts[(p.n - 1) * d + k] == pts[n * d + k]);
        }
        for (size_t j = 0; j + 1 < p.n; ++j) assert_true(p.ts[j] < p.ts[j + 1]);
        /* Count-then-fill agrees with the callback, bit for bit. */
        size_t np = 0;
        s = w ? cj_flatten_rbezier(&rc, &o, NULL, 0, &np, NULL)
              : cj_flatten_bezier(&c, &o, NULL, 0, &np, NULL);
        assert_int_equal(s, CJ_OK);
        assert_int_equal(np, p.n);
        double *buf = malloc(sizeof(double) * np * (size_t)d);
        assert_non_null(buf);
        s = w ? cj_flatten_rbezier(&rc, &o, buf, np, &np, NULL)
              : cj_flatten_bezier(&c, &o, buf, np, &np, NULL);
        assert_int_equal(s, CJ_OK);
        assert_memory_equal(buf, p.pts, sizeof(double) * np * (size_t)d);
        free(buf);
        if (m == CJ_FLATTEN_NEAR_OPTIMAL) nopt = st.segments;
        poly_free(&p);
    }
    return nopt;
}

/* ---- tests -------------------------------------------------------------------------------- */

static void test_quarter_circle(void **state) {
    (void)state;
    const double pts[] = {100, 0, 100, 100, 0, 100};
    const double w[] = {1, sqrt(0.5), 1};
    const size_t nopt = check_curve(2, 2, pts, w, 0.25, "quarter circle r=100", 64);
    /* Continuous optimum (π/2) r sqrt(1/(8 r tol)) = 11.1, so 12 is the least whole count. */
    assert_int_equal(nopt, 12);
    /* Dense check with the exact circle: every vertex at radius 100, max sagitta <= 0.25. */
    cj_rbezier rc = cj_rbezier_view(2, 2, pts, w);
    cj_flatten_opts o = cj_flatten_defaults(CJ_FLATTEN_NEAR_OPTIMAL, 0.25);
    double buf[64 * 2];
    size_t np;
    cj_flatten_stats st;
    assert_int_equal(cj_flatten_rbezier(&rc, &o, buf, 64, &np, &st), CJ_OK);
    double worst = 0;
    for (size_t j = 0; j + 1 < np; ++j) {
        assert_true(fabs(hypot(buf[2 * j], buf[2 * j + 1]) - 100) < 1e-10);
        /* sagitta of the chord on a circle: r - distance of the chord from the centre */
        const double mx = 0.5 * (buf[2 * j] + buf[2 * j + 2]),
                     my = 0.5 * (buf[2 * j + 1] + buf[2 * j + 3]);
        worst = fmax(worst, 100 - hypot(mx, my));
    }
    assert_true(worst <= 0.25);
    printf("quarter circle r=100 tol 0.25: near-optimal %zu segments, exact sagitta max %.4f, "
           "proven bound %.4f\n",
           np - 1, worst, st.bound);
}

static void random_curve(cj_rng *r, int n, int d, double box, double *pts) {
    for (int i = 0; i <= n; ++i)
        for (int k = 0; k < d; ++k) pts[i * d + k] = cj_rng_range(r, -box, box);
}

static void test_random_polynomial(void **state) {
    (void)state;
    const uint64_t seed = cj_test_seed("test_flatten_random", 20261121);
    cj_rng r;
    cj_rng_init(&r, seed);
    double pts[11 * 3];
    char what[128];
    int count = 0;
    for (int c = 0; c < 1000; ++c) {
        const int n = 2 + c % 9, d = 2 + (c / 9) % 2;
        random_curve(&r, n, d, 100, pts);
        const double tol = pow(10.0, cj_rng_range(&r, -2, 1));
        snprintf(what, sizeof what, "seed %llu case %d (degree %d dim %d)",
                 (unsigned long long)seed, c, n, d);
        check_curve(n, d, pts, NULL, tol, what, 12);
        ++count;
    }
    printf("random polynomial: %d curves (degrees 2-10, 2D/3D, tol 0.01-10), 3 methods each: "
           "bound <= tol and sampled deviation <= bound\n",
           count);
}

static void test_random_rational(void **state) {
    (void)state;
    const uint64_t seed = cj_test_seed("test_flatten_rational", 4242);
    cj_rng r;
    cj_rng_init(&r, seed);
    double pts[11 * 3], w[11];
    char what[128];
    int count = 0;
    for (int c = 0; c < 300; ++c) {
        const int n = 2 + c % 7, d = 2 + (c / 7) % 2;
        random_curve(&r, n, d, 100, pts);
        for (int i = 0; i <= n; ++i) w[i] = exp(cj_rng_range(&r, -1.5, 1.5));
        const double tol = pow(10.0, cj_rng_range(&r, -2, 1));
        snprintf(what, sizeof what, "seed %llu rational case %d (degree %d dim %d)",
                 (unsigned long long)seed, c, n, d);
        check_curve(n, d, pts, w, tol, what, 12);
        ++count;
    }
    printf("random rational: %d curves (degrees 2-8, weights e^[-1.5,1.5]), bound holds\n", count);
}

static void test_hard_shapes(void **state) {
    (void)state;
    static const struct {
        const char *name;
        int n;
        double p[11 * 2];
    } shapes[] = {
        {"cusp", 3, {0, 0, 100, 100, 0, 100, 100, 0}},
        {"near-cusp", 3, {0, 0, 100, 100, 0, 100, 100.5, 0}},
        {"loop", 3, {0, 0, 150, 100, -50, 100, 100, 0}},
        {"inflection", 3, {0, 0, 100, 100, 200, -100, 300, 0}},
        {"all equal", 3, {7, 7, 7, 7, 7, 7, 7, 7}},
        {"collinear out of order", 3, {0, 0, 300, 0, -100, 0, 200, 0}},
        {"collinear deg 6 shuffled", 6, {0, 0, 5, 5, -3, -3, 9, 9, 1, 1, -7, -7, 2, 2}},
        {"closed (ends equal)", 3, {0, 0, 100, 100, -100, 100, 0, 0}},
        {"degree 10 zigzag", 10, {0,   0,  10,   100, 20,  -100, 30,   100, 40,  -100, 50,
                                  100, 60, -100, 70,  100, 80,   -100, 90,  100, 100,  0}},
        {"straight line", 2, {0, 0, 1, 1, 2, 2}},
    };
    const double tols[] = {1e-6, 1e-3, 0.25, 1, 1e3, 1e9};
    int count = 0;
    for (size_t s = 0; s < sizeof shapes / sizeof shapes[0]; ++s)
        for (size_t j = 0; j < sizeof tols / sizeof tols[0]; ++j) {
            char what[96];
            snprintf(what, sizeof what, "%s", shapes[s].name);
            const size_t n = check_curve(shapes[s].n, 2, shapes[s].p, NULL, tols[j], what, 48);
            if (tols[j] >= 1e9) assert_int_equal(n, 1);
            ++count;
        }
    /* Degree 40 (too big for the subdivision stack: takes the stack-free dyadic walk). */
    {
        cj_rng r;
        cj_rng_init(&r, 99);
        double p40[41 * 2];
        random_curve(&r, 40, 2, 100, p40);
        check_curve(40, 2, p40, NULL, 0.5, "degree 40", 16);
        check_curve(40, 2, p40, NULL, 0.01, "degree 40", 8);
    }
    /* A 3D cusp-and-twist curve, and degree 0. */
    const double p3[] = {0, 0, 0, 100, 100, 50, 0, 100, -50, 100, 0, 0};
    for (size_t j = 0; j < 4; ++j) check_curve(3, 3, p3, NULL, tols[j], "3D cusp", 48);
    const double p0[] = {1, 2};
    cj_bezier c0 = cj_bezier_view(0, 2, p0);
    cj_flatten_opts o = cj_flatten_defaults(CJ_FLATTEN_SUBDIVIDE, 0.1);
    double buf[4];
    size_t np;
    assert_int_equal(cj_flatten_bezier(&c0, &o, buf, 2, &np, NULL), CJ_OK);
    assert_int_equal(np, 2);
    assert_true(buf[2] == 1 && buf[3] == 2);
    printf("hard shapes: %d shape/tolerance pairs (cusp, loop, inflection, equal, collinear "
           "unordered, tol 1e-6..1e9) plus degree 40, 3D cusp and degree 0\n",
           count);
}

static void test_caps(void **state) {
    (void)state;
    const double pts[] = {0, 0, 100, 100, 0, 100, 100, 0};
    cj_bezier c = cj_bezier_view(3, 2, pts);
    for (int m = 0; m < CJ_FLATTEN_METHOD_COUNT_; ++m) {
        cj_flatten_opts o = cj_flatten_defaults((cj_flatten_method)m, 0.01);
        size_t np;
        cj_flatten_stats st;
        assert_int_equal(cj_flatten_bezier(&c, &o, NULL, 0, &np, &st), CJ_OK);
        o.max_segments = st.segments; /* exactly enough */
        assert_int_equal(cj_flatten_bezier(&c, &o, NULL, 0, &np, NULL), CJ_OK);
        o.max_segments = st.segments - 1; /* one short: reported, not silently applied */
        assert_int_equal(cj_flatten_bezier(&c, &o, NULL, 0, &np, NULL), CJ_ERR_CAP);
        assert_true(strstr(cj_last_error(), "max_segments") != NULL);
    }
    /* Tiny tolerance: the default cap (2^22 segments) is hit, or the rounding floor. */
    cj_flatten_opts o = cj_flatten_defaults(CJ_FLATTEN_UNIFORM, 1e-11);
    size_t np;
    assert_int_equal(cj_flatten_bezier(&c, &o, NULL, 0, &np, NULL), CJ_ERR_CAP);
    o.tol = 1e-14;
    assert_int_equal(cj_flatten_bezier(&c, &o, NULL, 0, &np, NULL), CJ_ERR_RANGE);
    /* Buffer too small: count reported. */
    o = cj_flatten_defaults(CJ_FLATTEN_NEAR_OPTIMAL, 1);
    double buf[2 * 4];
    assert_int_equal(cj_flatten_bezier(&c, &o, buf, 4, &np, NULL), CJ_ERR_BUFFER);
    assert_true(np > 4);
    printf("caps: exact cap passes, one less is CJ_ERR_CAP for all 3 methods; tiny tol -> CAP / "
           "RANGE; small buffer -> CJ_ERR_BUFFER with the count\n");
}

static void test_errors(void **state) {
    (void)state;
    double pts[] = {0, 0, 1, 1, 2, 0};
    double w[] = {1, 1, 1};
    cj_bezier c = cj_bezier_view(2, 2, pts);
    size_t np;
    cj_flatten_opts o = cj_flatten_defaults(CJ_FLATTEN_SUBDIVIDE, NAN);
    assert_int_equal(cj_flatten_bezier(&c, &o, NULL, 0, &np, NULL), CJ_ERR_NONFINITE);
    o.tol = INFINITY;
    assert_int_equal(cj_flatten_bezier(&c, &o, NULL, 0, &np, NULL), CJ_ERR_NONFINITE);
    o.tol = 0;
    assert_int_equal(cj_flatten_bezier(&c, &o, NULL, 0, &np, NULL), CJ_ERR_RANGE);
    o.tol = -1;
    assert_int_equal(cj_flatten_bezier(&c, &o, NULL, 0, &np, NULL), CJ_ERR_RANGE);
    o.tol = 0.1;
    o.method = (cj_flatten_method)7;
    assert_int_equal(cj_flatten_bezier(&c, &o, NULL, 0, &np, NULL), CJ_ERR_ARGUMENT);
    o.method = CJ_FLATTEN_NEAR_OPTIMAL;
    pts[3] = NAN;
    assert_int_equal(cj_flatten_bezier(&c, &o, NULL, 0, &np, NULL), CJ_ERR_NONFINITE);
    pts[3] = 1;
    cj_bezier bad = cj_bezier_view(2, 0, pts);
    assert_int_equal(cj_flatten_bezier(&bad, &o, NULL, 0, &np, NULL), CJ_ERR_DIMENSION);
    bad = cj_bezier_view(CJ_BEZIER_MAX_DEGREE + 1, 2, pts);
    assert_int_equal(cj_flatten_bezier(&bad, &o, NULL, 0, &np, NULL), CJ_ERR_DEGREE);
    cj_rbezier rc = cj_rbezier_view(2, 2, pts, w);
    w[1] = 0;
    assert_int_equal(cj_flatten_rbezier(&rc, &o, NULL, 0, &np, NULL), CJ_ERR_ARGUMENT);
    w[1] = -2;
    assert_int_equal(cj_flatten_rbezier(&rc, &o, NULL, 0, &np, NULL), CJ_ERR_ARGUMENT);
    w[1] = NAN;
    assert_int_equal(cj_flatten_rbezier(&rc, &o, NULL, 0, &np, NULL), CJ_ERR_NONFINITE);
    w[1] = 1;
    /* Bounds at the edges of the double range (squares would overflow or underflow without
     * the library's power-of-two scaling); the long-double oracle has the range to check. */
    {
        double big[] = {0, 0, 1e300, 1e300, -1e300, 0, 5e299, -1e300};
        check_curve(3, 2, big, NULL, 1e298, "coordinates ~1e300", 16);
        double tiny[] = {0, 0, 1e-300, 1e-300, -1e-300, 0, 5e-301, -1e-300};
        check_curve(3, 2, tiny, NULL, 1e-302, "coordinates ~1e-300", 16);
        const double wt[] = {1e-200, 1e-199, 3e-200, 1e-200};
        check_curve(3, 2, big, wt, 1e298, "weights ~1e-200", 16);
        /* the largest doubles: fine while the deviation is a double, refused beyond */
        double huge[] = {0, 0, 1.7e308, 1.7e308, -1.7e308, 0};
        check_curve(2, 2, huge, NULL, 1e307, "coordinates ~1.7e308", 16);
        double over[] = {-1.7e308, 0, 1.7e308, 1.7e308, 1.7e308, -1.7e308, -1.7e308, 1.7e308};
        cj_bezier cb = cj_bezier_view(3, 2, over);
        o.tol = 1e307;
        for (int m = 0; m < CJ_FLATTEN_METHOD_COUNT_; ++m) {
            o.method = (cj_flatten_method)m;
            assert_int_equal(cj_flatten_bezier(&cb, &o, NULL, 0, &np, NULL), CJ_ERR_RANGE);
        }
        o.method = CJ_FLATTEN_NEAR_OPTIMAL;
        o.tol = 0.1;
    }
    /* sequences */
    o.tol = 0.1;
    assert_int_equal(cj_flatten_sequence(NULL, 0, &o, NULL, 0, &np, NULL), CJ_ERR_EMPTY);
    double p3[] = {0, 0, 0, 1, 1, 1};
    cj_flatten_piece seq[2] = {{cj_bezier_view(2, 2, pts), NULL}, {cj_bezier_view(1, 3, p3), NULL}};
    assert_int_equal(cj_flatten_sequence(seq, 2, &o, NULL, 0, &np, NULL), CJ_ERR_DIMENSION);
    printf("errors: NaN/Inf/<=0 tol, bad method, NaN point, dim, degree, weights <=0/NaN, "
           "coordinates ~1e300 and ~1e-300 flattened correctly, overflowing bound refused, "
           "empty and mixed-dim sequences\n");
}

static void test_sequence(void **state) {
    (void)state;
    /* A cubic, a rational quarter circle joined at its end, and a detached line. */
    const double a[] = {0, 0, 50, 100, 100, 100, 200, 0};
    const double b[] = {200, 0, 200, -100, 100, -100};
    const double wb[] = {1, sqrt(0.5), 1};
    const double c[] = {0, 0, 10, 10};
    cj_flatten_piece seq[3] = {{cj_bezier_view(3, 2, a), NULL},
                               {cj_bezier_view(2, 2, b), wb},
                               {cj_bezier_view(1, 2, c), NULL}};
    cj_flatten_opts o = cj_flatten_defaults(CJ_FLATTEN_NEAR_OPTIMAL, 0.25);
    poly p = {.d = 2};
    cj_flatten_stats st;
    assert_int_equal(cj_flatten_sequence_cb(seq, 3, &o, sink, &p, &st), CJ_OK);
    size_t sa, sb;
    cj_flatten_stats s1;
    cj_bezier ca = cj_bezier_view(3, 2, a);
    cj_rbezier cbr = cj_rbezier_view(2, 2, b, wb);
    assert_int_equal(cj_flatten_bezier(&ca, &o, NULL, 0, &sa, &s1), CJ_OK);
    assert_int_equal(cj_flatten_rbezier(&cbr, &o, NULL, 0, &sb, &s1), CJ_OK);
    /* shared point once: (sa) + (sb - 1); then the detached line adds 2 points */
    assert_int_equal(p.n, sa + sb - 1 + 2);
    assert_int_equal(st.segments, p.n - 1);
    assert_true(p.piece[sa - 1] == 0 && p.piece[sa] == 1 && p.piece[p.n - 1] == 2);
    assert_true(st.bound <= 0.25);
    double buf[256 * 2];
    size_t np;
    assert_int_equal(cj_flatten_sequence(seq, 3, &o, buf, 256, &np, NULL), CJ_OK);
    assert_int_equal(np, p.n);
    assert_memory_equal(buf, p.pts, sizeof(double) * 2 * np);
    poly_free(&p);
    printf("sequence: joined pieces share their end point once (%zu points), detached piece "
           "kept, buffer == callback\n",
           np);
}

/* Largest distance from the curve to its chord segment b_0 b_n: 4000 samples, then a golden-
 * section search around the best one (long-double oracle). A lower estimate of the true sup
 * that is accurate to ~1e-15 relative where the maximum is a smooth peak. */
static double sampled_chord_deviation(int n, int d, const double *pts, const double *w) {
    const int N = 4000;
    long double best = -1, tb = 0;
    for (int s = 0; s <= N; ++s) {
        long double c[CJ_MAX_DIM];
        oracle_eval(n, d, pts, w, (long double)s / N, c);
        const long double dd = dist_point_segment(c, pts, pts + n * d, d);
        if (dd > best) best = dd, tb = (long double)s / N;
    }
    long double lo = fmaxl(0, tb - 1.0L / N), hi = fminl(1, tb + 1.0L / N);
    const long double g = 0.6180339887498948482L;
    for (int it = 0; it < 80; ++it) {
        const long double m1 = hi - g * (hi - lo), m2 = lo + g * (hi - lo);
        long double c1[CJ_MAX_DIM], c2[CJ_MAX_DIM];
        oracle_eval(n, d, pts, w, m1, c1);
        oracle_eval(n, d, pts, w, m2, c2);
        const long double d1 = dist_point_segment(c1, pts, pts + n * d, d),
                          d2 = dist_point_segment(c2, pts, pts + n * d, d);
        if (d1 > best) best = d1;
        if (d2 > best) best = d2;
        if (d1 < d2)
            lo = m1;
        else
            hi = m2;
    }
    return (double)best;
}

/* The refined piece bound (d) against the sampled deviation on random pieces: never below it,
 * never above the cheap bound, and exact (to 1e-9) on symmetric loops and cusps, where the
 * cheap bounds (a)-(c) are all loose and the maximum sits on a part's end point: there a bound
 * 1% too small fails this test. */
static void test_refined_bound(void **state) {
    (void)state;
    const uint64_t seed = cj_test_seed("test_flatten_refined_bound", 777);
    cj_rng r;
    cj_rng_init(&r, seed);
    double pts[8 * 3], w[8];
    int cases = 0, active = 0, sym = 0;
    double ratio_sum = 0, cheap_ratio_sum = 0, sym_worst = 1;
    for (int c = 0; c < 1600; ++c) {
        const int kind = c % 4;
        int n = 3, d = 2;
        const double *wp = NULL;
        if (kind == 0) { /* random polynomial, degree 2-7, 2D/3D */
            n = 2 + (c / 4) % 6, d = 2 + (c / 24) % 2;
            random_curve(&r, n, d, 100, pts);
        } else if (kind == 1) { /* random rational */
            n = 2 + (c / 4) % 5, d = 2 + (c / 20) % 2;
            random_curve(&r, n, d, 100, pts);
            for (int i = 0; i <= n; ++i) w[i] = exp(cj_rng_range(&r, -1.5, 1.5));
            wp = w;
        } else { /* cubic loops and near-cusps; kind 3 symmetric about the chord's bisector */
            const double s = cj_rng_range(&r, -30, 80), h = cj_rng_range(&r, 20, 150);
            double q[8] = {0, 0, 100 + s, h, -s, h, 100, 0};
            if (kind == 2)
                for (int i = 2; i < 6; ++i) q[i] += cj_rng_range(&r, -25, 25);
            const double ang = cj_rng_range(&r, 0, 6.283185307179586),
                         sc = cj_rng_range(&r, 0.01, 50);
            const double ox = cj_rng_range(&r, -500, 500), oy = cj_rng_range(&r, -500, 500);
            for (int i = 0; i < 4; ++i) {
                pts[2 * i] = ox + sc * (cos(ang) * q[2 * i] - sin(ang) * q[2 * i + 1]);
                pts[2 * i + 1] = oy + sc * (sin(ang) * q[2 * i] + cos(ang) * q[2 * i + 1]);
            }
        }
        cj_bezier cb = cj_bezier_view(n, d, pts);
        cj_fl_curve fc;
        assert_int_equal(cj_fl_init(&fc, &cb, wp), CJ_OK);
        const double cheap = cj_fl_piece_bound(&fc, fc.hom);
        const double refined = cj_fl_piece_bound_refined(&fc, fc.hom, 0.0, INFINITY, 0.0, INFINITY);
        const double dev = sampled_chord_deviation(n, d, pts, wp);
        double pub = 0;
        assert_int_equal(cj_flatten_piece_bound(&cb, wp, &pub), CJ_OK);
        if (!(dev <= refined + fc.slack) || !(refined <= cheap) || pub != refined + fc.slack)
            fail_msg("seed %llu case %d (kind %d degree %d dim %d): sampled %.17g refined %.17g "
                     "(+slack %.3g) cheap %.17g public %.17g",
                     (unsigned long long)seed, c, kind, n, d, dev, refined, fc.slack, cheap, pub);
        ++cases;
        if (refined < 0.97 * cheap) {
            ++active;
            ratio_sum += dev / refined;
            cheap_ratio_sum += dev / cheap;
        }
        if (kind == 3 && refined < cheap) { /* (else cheap is exact already) */
            ++sym;
            if (dev / refined < sym_worst) sym_worst = dev / refined;
            if (!(dev >= refined * (1 - 1e-9)))
                fail_msg("seed %llu case %d: symmetric loop/cusp: refined bound %.17g not exact "
                         "(sampled %.17g, cheap %.17g)",
                         (unsigned long long)seed, c, refined, dev, cheap);
        }
    }
    assert_true(active > cases / 4); /* the refinement matters on many of these pieces */
    assert_true(sym > 200);
    printf(
        "refined bound: %d pieces (random poly/rational deg 2-7, loops, near-cusps): sampled "
        "deviation <= bound always; on the %d where refining helps, deviation/bound %.3f on "
        "average (cheap bound: %.3f); %d refined symmetric loops/cusps exact (worst ratio %.12f)\n",
        cases, active, ratio_sum / active, cheap_ratio_sum / active, sym, sym_worst);
}

static void test_bounds_direct(void **state) {
    (void)state;
    /* Parabola (0,0) (50,100) (100,0): farthest from its chord at t = 1/2, distance 50. */
    const double par[] = {0, 0, 50, 100, 100, 0};
    cj_bezier c = cj_bezier_view(2, 2, par);
    double b;
    assert_int_equal(cj_flatten_piece_bound(&c, NULL, &b), CJ_OK);
    assert_true(b >= 50 && b <= 50 + 1e-9);
    /* Circular arc of 90 degrees, r = 100: sagitta r (1 - cos 45°) = 29.29; the bound may
     * exceed it only by the min-weight factor (1 + w)/(2w) with w = cos 45°. */
    const double arc[] = {100, 0, 100, 100, 0, 100}, w[] = {1, sqrt(0.5), 1};
    const double sag = 100 * (1 - sqrt(0.5));
    assert_int_equal(cj_flatten_piece_bound(&c, NULL, &b), CJ_OK);
    cj_bezier ca = cj_bezier_view(2, 2, arc);
    assert_int_equal(cj_flatten_piece_bound(&ca, w, &b), CJ_OK);
    assert_true(b >= sag && b <= sag * (1 + sqrt(0.5)) / (2 * sqrt(0.5)) + 1e-9);
    /* Wang's count against the formula computed here: cubic with max|Δ²b| = |(-300, 0)|. */
    const double cub[] = {0, 0, 100, 100, 0, 100, 100, 0};
    cj_bezier cc = cj_bezier_view(3, 2, cub);
    size_t m;
    assert_int_equal(cj_flatten_wang_count(&cc, NULL, 0.5, &m), CJ_OK);
    /* Δ² b_0 = (0,0)-2(100,100)+(0,100) = (-200,-100); Δ² b_1 = (100,100)-2(0,100)+(100,0) =
     * (200,-100): M = sqrt(50000); m = ceil(sqrt(6 M / (8 * 0.5))) */
    assert_int_equal(m, (size_t)ceil(sqrt(6 * sqrt(50000.0) / 4)));
    printf("bounds: parabola bound = exact 50, 90° arc bound within the min-weight factor of "
           "the sagitta %.3f (%.3f), Wang count %zu as computed by hand\n",
           sag, b, m);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_quarter_circle),
        cmocka_unit_test(test_hard_shapes),
        cmocka_unit_test(test_random_polynomial),
        cmocka_unit_test(test_random_rational),
        cmocka_unit_test(test_caps),
        cmocka_unit_test(test_errors),
        cmocka_unit_test(test_sequence),
        cmocka_unit_test(test_bounds_direct),
        cmocka_unit_test(test_refined_bound),
        cmocka_unit_test(test_fast_path_hard),
        cmocka_unit_test(test_fast_path_few),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

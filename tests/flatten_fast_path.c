/* test_flatten's fast planar path (degrees 2 and 3) where its estimate is worst: near-cusps,
 * control points past the chord, coordinates 1e-200..1e200; a refined sampled deviation
 * against the proven bound. Part of the test_flatten program (see flatten_test.h). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "casteljau/flatten.h"
#include "flatten_test.h"
#include "rng.h"

#include <math.h>
#include <stdio.h>

/* Largest distance of the curve from the polyline segment of its own parameter interval:
 * `per` samples per segment, then the largest sample refined by golden-section search on its
 * two neighbouring sample intervals (the distance is smooth there). */
static double measure_refined(int n, const double *pts, const poly *p, int per) {
    long double worst = 0;
    for (size_t j = 0; j + 1 < p->n; ++j) {
        const long double t0 = p->ts[j], t1 = p->ts[j + 1];
        const double *a = p->pts + 2 * j, *b = p->pts + 2 * j + 2;
        long double best = -1, tb = t0;
        for (int s = 0; s <= per; ++s) {
            long double c[2];
            const long double t = t0 + (t1 - t0) * s / per;
            oracle_eval(n, 2, pts, NULL, t, c);
            const long double dd = dist_point_segment(c, a, b, 2);
            if (dd > best) best = dd, tb = t;
        }
        long double lo = fmaxl(t0, tb - (t1 - t0) / per), hi = fminl(t1, tb + (t1 - t0) / per);
        for (int it = 0; it < 40; ++it) {
            const long double m1 = lo + (hi - lo) * 0.381966L, m2 = hi - (hi - lo) * 0.381966L;
            long double c1[2], c2[2];
            oracle_eval(n, 2, pts, NULL, m1, c1);
            oracle_eval(n, 2, pts, NULL, m2, c2);
            const long double d1 = dist_point_segment(c1, a, b, 2),
                              d2 = dist_point_segment(c2, a, b, 2);
            if (d1 > best) best = d1;
            if (d2 > best) best = d2;
            if (d1 < d2)
                lo = m1;
            else
                hi = m2;
        }
        if (best > worst) worst = best;
    }
    return (double)worst;
}

/* Near-optimal flattening of a planar quadratic or cubic: bound <= tol, refined sampled
 * deviation <= bound (up to rounding of these coordinates), exact end points, increasing
 * parameters, vertices on the curve. Returns the deviation / bound ratio. */
static double check_fast_stats(int n, const double *pts, double tol, const char *what,
                               cj_flatten_stats *stats_out) {
    double scale = 0;
    for (int i = 0; i < (n + 1) * 2; ++i) scale = fmax(scale, fabs(pts[i]));
    cj_flatten_opts o = cj_flatten_defaults(CJ_FLATTEN_NEAR_OPTIMAL, tol);
    poly p = {.d = 2};
    cj_flatten_stats st;
    cj_bezier c = cj_bezier_view(n, 2, pts);
    cj_status s = cj_flatten_bezier_cb(&c, &o, sink, &p, &st);
    if (s != CJ_OK) fail_msg("%s (tol %g): status %d: %s", what, tol, s, cj_last_error());
    double verr;
    (void)measure(n, 2, pts, NULL, &p, 2, &verr);
    const double dev = measure_refined(n, pts, &p, 32);
    if (!(st.bound <= tol) || !(dev <= st.bound * (1 + 1e-9) + 1e-12 * scale) ||
        st.segments + 1 != p.n || verr > 1e-11 * scale)
        fail_msg("%s (tol %g): segments %zu bound %g measured %g vertex err %g", what, tol,
                 st.segments, st.bound, dev, verr);
    assert_true(p.pts[0] == pts[0] && p.pts[1] == pts[1]);
    assert_true(p.pts[2 * (p.n - 1)] == pts[2 * n] && p.pts[2 * (p.n - 1) + 1] == pts[2 * n + 1]);
    for (size_t j = 0; j + 1 < p.n; ++j) assert_true(p.ts[j] < p.ts[j + 1]);
    poly_free(&p);
    *stats_out = st;
    return st.bound > 0 ? dev / st.bound : 1.0;
}

static double check_fast(int n, const double *pts, double tol, const char *what) {
    cj_flatten_stats st;
    return check_fast_stats(n, pts, tol, what, &st);
}

void test_fast_path_hard(void **state) {
    (void)state;
    const uint64_t seed = cj_test_seed("test_flatten_fast", 1313);
    cj_rng r;
    cj_rng_init(&r, seed);
    char what[160];
    int count = 0;
    double worst_ratio = 0;
    const double tols[] = {1e-3, 0.01, 0.25, 1, 10};
    /* Near-cusps: affine images of the cusp (0,0) (1,1) (0,1) (1,0) with the last point moved
     * by 10^-1 .. 10^-9 of the size, and quadratics whose control point runs far past the
     * chord (the curve turns back on itself). */
    for (int c = 0; c < 80; ++c) {
        double m[4], pts[8];
        for (int k = 0; k < 4; ++k) m[k] = cj_rng_range(&r, -300, 300);
        const double base[8] = {0, 0, 1, 1, 0, 1, 1, 0};
        const double ox = cj_rng_range(&r, -500, 500), oy = cj_rng_range(&r, -500, 500);
        for (int i = 0; i < 4; ++i) {
            pts[2 * i] = ox + m[0] * base[2 * i] + m[1] * base[2 * i + 1];
            pts[2 * i + 1] = oy + m[2] * base[2 * i] + m[3] * base[2 * i + 1];
        }
        const double eps = pow(10.0, -cj_rng_range(&r, 1, 9)) * 300;
        pts[6] += cj_rng_range(&r, -eps, eps);
        pts[7] += cj_rng_range(&r, -eps, eps);
        const double tol = tols[c % 5];
        snprintf(what, sizeof what, "seed %llu near-cusp cubic %d (eps %.2g)",
                 (unsigned long long)seed, c, eps);
        worst_ratio = fmax(worst_ratio, check_fast(3, pts, tol, what));
        ++count;
    }
    for (int c = 0; c < 80; ++c) {
        /* Control points beyond the chord: the inner points project outside [b_0, b_n]. */
        double pts[8];
        const double L = cj_rng_range(&r, 10, 500), past = cj_rng_range(&r, 0.1, 3) * L;
        const double h1 = cj_rng_range(&r, -1, 1) * L, h2 = cj_rng_range(&r, -1, 1) * L;
        const double q[8] = {0, 0, L + past, h1, -past, h2, L, 0};
        const double ang = cj_rng_range(&r, 0, 6.283185307179586);
        for (int i = 0; i < 4; ++i) {
            pts[2 * i] = q[2 * i] * cos(ang) - q[2 * i + 1] * sin(ang) + 100;
            pts[2 * i + 1] = q[2 * i] * sin(ang) + q[2 * i + 1] * cos(ang) - 50;
        }
        const int n = c % 2 ? 3 : 2;
        if (n == 2) pts[2] = pts[2] + 0.0, pts[4] = pts[6], pts[5] = pts[7];
        const double tol = tols[c % 5];
        snprintf(what, sizeof what, "seed %llu past-the-chord degree %d case %d",
                 (unsigned long long)seed, n, c);
        worst_ratio = fmax(worst_ratio, check_fast(n, pts, tol, what));
        ++count;
    }
    /* Tiny and huge coordinates: random quadratics and cubics scaled by 2^-660 (~1e-199),
     * 1e-200, 1e200 and 2^660, with the tolerance scaled alike. */
    const double scales[4] = {0x1p-660, 1e-200, 1e200, 0x1p660};
    for (int c = 0; c < 120; ++c) {
        double pts[8];
        const int n = 2 + c % 2;
        const double sc = scales[(c / 2) % 4];
        for (int i = 0; i < (n + 1) * 2; ++i) pts[i] = cj_rng_range(&r, -500, 500) * sc;
        const double tol = tols[c % 5] * sc;
        snprintf(what, sizeof what, "seed %llu scaled %g degree %d case %d",
                 (unsigned long long)seed, sc, n, c);
        worst_ratio = fmax(worst_ratio, check_fast(n, pts, tol, what));
        ++count;
    }
    printf("fast path (planar degree 2/3): %d near-cusps, control points past the chord, "
           "coordinates 1e-200..1e200: bound <= tol and refined sampled deviation <= bound "
           "(largest deviation/bound %.6f)\n",
           count, worst_ratio);
}

/* Few segments per curve (2 to about 30): the measured second placement of the fast path
 * (flatten_fast_small.c) with its repairs, on random quadratics and cubics, near-cusps and
 * S-curves (an inflection inside), the tolerance 10^-1 .. 10^-3 of the curve's size. */
void test_fast_path_few(void **state) {
    (void)state;
    const uint64_t seed = cj_test_seed("test_flatten_fast_few", 2026);
    cj_rng r;
    cj_rng_init(&r, seed);
    char what[160];
    int count = 0;
    double worst_ratio = 0;
    size_t segments = 0;
    for (int c = 0; c < 240; ++c) {
        double pts[8];
        const int kind = c % 4, n = kind == 1 ? 2 : 3;
        const double size = cj_rng_range(&r, 1, 1000);
        if (kind <= 1) { /* random cubic or quadratic */
            for (int i = 0; i < (n + 1) * 2; ++i) pts[i] = cj_rng_range(&r, 0, size);
        } else if (kind == 2) { /* near-cusp: the cusp's end point moved by 10^-1 .. 10^-6 */
            const double base[8] = {0, 0, 1, 1, 0, 1, 1, 0};
            for (int i = 0; i < 8; ++i) pts[i] = base[i] * size;
            const double eps = pow(10.0, -cj_rng_range(&r, 1, 6)) * size;
            pts[6] += cj_rng_range(&r, -eps, eps);
            pts[7] += cj_rng_range(&r, -eps, eps);
        } else { /* S-curve: inner points on opposite sides of the chord */
            const double h1 = cj_rng_range(&r, 0.1, 1) * size, h2 = cj_rng_range(&r, 0.1, 1) * size;
            const double q[8] = {
                0,    0, cj_rng_range(&r, 0, 0.6) * size, h1, cj_rng_range(&r, 0.4, 1) * size, -h2,
                size, 0};
            for (int i = 0; i < 8; ++i) pts[i] = q[i];
        }
        const double tol = size * pow(10.0, -cj_rng_range(&r, 1, 3));
        snprintf(what, sizeof what, "seed %llu few-segments kind %d case %d (tol %.3g)",
                 (unsigned long long)seed, kind, c, tol);
        cj_flatten_stats st;
        worst_ratio = fmax(worst_ratio, check_fast_stats(n, pts, tol, what, &st));
        segments += st.segments;
        ++count;
    }
    printf("fast path, few segments: %d curves (random, near-cusps, S-curves), %zu segments: "
           "bound <= tol and refined sampled deviation <= bound (largest deviation/bound "
           "%.6f)\n",
           count, segments, worst_ratio);
}

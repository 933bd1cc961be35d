/* test_flatten_count: the planar fast path of CJ_FLATTEN_NEAR_OPTIMAL (segments placed up front
 * by the parabola model of ∫ sqrt|κ| ds, each certified, the rejected ones shortened) on seeded
 * random quadratics and cubics in a 1000 x 1000 box at tol 0.01, 0.25 and 1:
 *  - every call succeeds with stats.bound <= tol, parameters strictly increasing from 0 to 1,
 *    the end points exactly the curve's;
 *  - the bound is a bound: the distance of dense curve samples (long double, independent of the
 *    library) from their own segment never exceeds stats.bound;
 *  - the count stays near the continuous optimum Σ ∫ sqrt(|κ|/(8 tol)) ds (adaptive Simpson in
 *    long double on the exact derivatives): at most COUNT_LIMIT times Σ max(1, ceil(optimum))
 *    per set (the whole-number optimum each curve can reach at best). */
#include "casteljau/flatten.h"
#include "rng.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define NCURVES     300
#define SAMPLES     32
#define COUNT_LIMIT 1.08

typedef struct pl {
    size_t n, cap;
    double *pts, *ts;
} pl;

static void collect(void *user, const double *pt, int dim, size_t piece, double t) {
    (void)dim;
    (void)piece;
    pl *p = user;
    if (p->n == p->cap) {
        p->cap = p->cap ? 2 * p->cap : 256;
        p->pts = realloc(p->pts, sizeof(double) * 2 * p->cap);
        p->ts = realloc(p->ts, sizeof(double) * p->cap);
        if (!p->pts || !p->ts) abort();
    }
    p->pts[2 * p->n] = pt[0];
    p->pts[2 * p->n + 1] = pt[1];
    p->ts[p->n++] = t;
}

/* Point, first and second derivative at t (long double de Casteljau on the differences). */
static void eval3(int n, const double *b, long double t, long double *c, long double *d1,
                  long double *d2) {
    long double w[8];
    for (int i = 0; i < 2 * (n + 1); ++i) w[i] = b[i];
    for (int k = 0; k < 2; ++k) d2[k] = 0;
    for (int r = n; r > 0; --r) {
        if (r == 2)
            for (int k = 0; k < 2; ++k)
                d2[k] = (long double)n * (n - 1) * (w[k] - 2 * w[2 + k] + w[4 + k]);
        if (r == 1)
            for (int k = 0; k < 2; ++k) d1[k] = (long double)n * (w[2 + k] - w[k]);
        for (int i = 0; i < 2 * r; ++i) w[i] = (1 - t) * w[i] + t * w[i + 2];
    }
    c[0] = w[0], c[1] = w[1];
}

/* sqrt|κ| |c'| = sqrt|c' x c''| / sqrt|c'| */
static long double integrand(int n, const double *b, long double t) {
    long double c[2], d1[2], d2[2];
    eval3(n, b, t, c, d1, d2);
    const long double cr = fabsl(d1[0] * d2[1] - d1[1] * d2[0]);
    const long double sp = sqrtl(d1[0] * d1[0] + d1[1] * d1[1]);
    return sp > 0 ? sqrtl(cr) / sqrtl(sp) : 0;
}

static long double simpson(int n, const double *b, long double a, long double c, long double fa,
                           long double fm, long double fc, long double whole, int depth) {
    const long double m = 0.5L * (a + c), lm = 0.5L * (a + m), rm = 0.5L * (m + c);
    const long double flm = integrand(n, b, lm), frm = integrand(n, b, rm);
    const long double left = (m - a) / 6 * (fa + 4 * flm + fm);
    const long double right = (c - m) / 6 * (fm + 4 * frm + fc);
    if (depth > 30 || fabsl(left + right - whole) < 1e-9L * (1 + fabsl(whole)))
        return left + right + (left + right - whole) / 15;
    return simpson(n, b, a, m, fa, flm, fm, left, depth + 1) +
           simpson(n, b, m, c, fm, frm, fc, right, depth + 1);
}

static double sqrt_kappa_integral(int n, const double *b) {
    long double total = 0;
    for (int i = 0; i < 32; ++i) {
        const long double a = i / 32.0L, c = (i + 1) / 32.0L, m = 0.5L * (a + c);
        const long double fa = integrand(n, b, a), fm = integrand(n, b, m), fc = integrand(n, b, c);
        total += simpson(n, b, a, c, fa, fm, fc, (c - a) / 6 * (fa + 4 * fm + fc), 0);
    }
    return (double)total;
}

/* Largest distance of curve samples from their own segment (a lower estimate of the true
 * deviation, so it must not exceed a proven bound). */
static double sampled_deviation(int n, const double *b, const pl *p) {
    long double worst = 0;
    for (size_t j = 0; j + 1 < p->n; ++j) {
        const double *s0 = p->pts + 2 * j, *s1 = s0 + 2;
        const long double vx = (long double)s1[0] - s0[0], vy = (long double)s1[1] - s0[1];
        const long double v2 = vx * vx + vy * vy;
        for (int k = 1; k < SAMPLES; ++k) {
            long double c[2], d1[2], d2[2];
            const long double t = p->ts[j] + (p->ts[j + 1] - (long double)p->ts[j]) * k / SAMPLES;
            eval3(n, b, t, c, d1, d2);
            long double u = v2 > 0 ? ((c[0] - s0[0]) * vx + (c[1] - s0[1]) * vy) / v2 : 0;
            u = u < 0 ? 0 : (u > 1 ? 1 : u);
            const long double dx = c[0] - (s0[0] + u * vx), dy = c[1] - (s0[1] + u * vy);
            const long double d = sqrtl(dx * dx + dy * dy);
            if (d > worst) worst = d;
        }
    }
    return (double)worst;
}

int main(void) {
    const uint64_t seed = cj_test_seed("test_flatten_count", 20261126);
    static double ctrl[NCURVES][8], I[NCURVES];
    const double tols[3] = {0.01, 0.25, 1.0};
    pl p = {0};
    int fails = 0;
    for (int n = 2; n <= 3; ++n) {
        cj_rng rng;
        cj_rng_init(&rng, seed + (uint64_t)n);
        for (int i = 0; i < NCURVES; ++i) {
            for (int k = 0; k < 2 * (n + 1); ++k) ctrl[i][k] = cj_rng_range(&rng, 0.0, 1000.0);
            I[i] = sqrt_kappa_integral(n, ctrl[i]);
        }
        for (int ti = 0; ti < 3; ++ti) {
            const double tol = tols[ti];
            double opt = 0, opt_ceil = 0, worst_ratio = 0;
            size_t segs = 0;
            for (int i = 0; i < NCURVES; ++i) {
                const double o = I[i] / sqrt(8 * tol);
                opt += o;
                opt_ceil += o > 1 ? ceil(o) : 1;
                cj_bezier c = cj_bezier_view(n, 2, ctrl[i]);
                cj_flatten_opts opts = cj_flatten_defaults(CJ_FLATTEN_NEAR_OPTIMAL, tol);
                cj_flatten_stats st;
                p.n = 0;
                if (cj_flatten_bezier_cb(&c, &opts, collect, &p, &st)) {
                    printf("FAIL degree %d tol %g curve %d: %s\n", n, tol, i, cj_last_error());
                    ++fails;
                    continue;
                }
                segs += st.segments;
                int ok = st.bound <= tol && p.n == st.segments + 1 && p.ts[0] == 0.0 &&
                         p.ts[p.n - 1] == 1.0 && p.pts[0] == ctrl[i][0] && p.pts[1] == ctrl[i][1] &&
                         p.pts[2 * p.n - 2] == ctrl[i][2 * n] &&
                         p.pts[2 * p.n - 1] == ctrl[i][2 * n + 1];
                for (size_t j = 0; j + 1 < p.n; ++j) ok = ok && p.ts[j] < p.ts[j + 1];
                const double dev = sampled_deviation(n, ctrl[i], &p);
                if (dev / st.bound > worst_ratio) worst_ratio = dev / st.bound;
                if (!ok || dev > st.bound) {
                    printf("FAIL degree %d tol %g curve %d (seed %llu): bound %.17g, sampled "
                           "deviation %.17g, %zu points\n",
                           n, tol, i, (unsigned long long)seed, st.bound, dev, p.n);
                    ++fails;
                }
            }
            const double ratio = (double)segs / opt_ceil;
            printf("degree %d tol %-4g: %d curves, %zu segments, %.3f x the optimum, %.3f x the "
                   "whole-number optimum (limit %.2f); sampled deviation <= %.4f x the bound\n",
                   n, tol, NCURVES, segs, segs / opt, ratio, COUNT_LIMIT, worst_ratio);
            if (!(ratio <= COUNT_LIMIT)) {
                printf("FAIL degree %d tol %g: %.3f x the whole-number optimum\n", n, tol, ratio);
                ++fails;
            }
        }
    }
    free(p.pts);
    free(p.ts);
    printf("test_flatten_count: %s\n", fails ? "FAILED" : "ok");
    return fails ? 1 : 0;
}

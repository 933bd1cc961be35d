/* Trimmed offsets (cj_offset_trim, casteljau/offset.h) on closed forms:
 *  - a quarter circle (rational, radius 1) offset inwards by 0.5 keeps everything, on the circle
 *    of radius 0.5; offset inwards past its radius (1.5) disappears whole; outwards by 0.5 keeps
 *    everything, on radius 1.5;
 *  - the parabola y = x^2 on [-1,1] offset by 0.8 towards its concave side (radius of curvature
 *    0.5 at the vertex): the swallowtail is dropped, the kept pieces form ONE connected curve
 *    whose sides meet at the exact crossing (0, 0.89), and every kept point lies at distance
 *    0.8 from the parabola within the proven margins (long-double dense oracle); the raw offset
 *    had points far nearer (the loop);
 *  - an S-shaped cubic offset by a small distance: nothing dropped, same pieces;
 *  - bad input refused naming it. */
#include "casteljau/offset.h"
#include "check.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define CAP 4096
static double raw[8 * CAP], trimmed[8 * CAP];
static int newline[CAP];

/* Distance from x to the curve, by 40001 long-double samples refined by ternary search around
 * the best (an independent oracle; the curves here are convex near their nearest points). */
static double oracle_dist(const cj_bezier2 *c, const double x[2]) {
    int n = c->degree, N = 40000;
    long double best = 1e300L, bt = 0;
    for (int pass = 0; pass < 2; ++pass) {
        long double lo = pass ? fmaxl(0, bt - 1.0L / N) : 0,
                    hi = pass ? fminl(1, bt + 1.0L / N) : 1;
        int M = pass ? 2000 : N;
        for (int s = 0; s <= M; ++s) {
            long double t = lo + (hi - lo) * s / M, w[64][3];
            for (int i = 0; i <= n; ++i) {
                long double wt = c->weights ? c->weights[i] : 1.0L;
                w[i][0] = wt * c->pts[2 * i], w[i][1] = wt * c->pts[2 * i + 1], w[i][2] = wt;
            }
            for (int r = n; r > 0; --r)
                for (int i = 0; i < r; ++i)
                    for (int k = 0; k < 3; ++k) w[i][k] = (1 - t) * w[i][k] + t * w[i + 1][k];
            long double dx = w[0][0] / w[0][2] - x[0], dy = w[0][1] / w[0][2] - x[1];
            long double dd = sqrtl(dx * dx + dy * dy);
            if (dd < best) best = dd, bt = t;
        }
    }
    return (double)best;
}

static void eval_cubic(const double *p, double t, double out[2]) {
    double s = 1 - t;
    for (int k = 0; k < 2; ++k)
        out[k] = s * s * s * p[k] + 3 * s * s * t * p[2 + k] + 3 * s * t * t * p[4 + k] +
                 t * t * t * p[6 + k];
}

typedef struct trim_out {
    int nraw, nout, dropped, lines;
    double dev;
} trim_out;

static cj_status run(const cj_bezier2 *c, double d, double tol, trim_out *r) {
    int cusps = 0;
    cj_status st = cj_offset_curve(c, d, tol, raw, NULL, CAP, &r->nraw, &r->dev, &cusps);
    if (st != CJ_OK) return st;
    st = cj_offset_trim(c, d, tol, raw, r->nraw, r->dev, trimmed, newline, CAP, &r->nout,
                        &r->dropped);
    r->lines = 0;
    for (int i = 0; i < r->nout; ++i) r->lines += newline[i];
    return st;
}

static void check_circle(void) {
    const double pts[6] = {1, 0, 1, 1, 0, 1}, w[3] = {1, sqrt(0.5), 1};
    cj_bezier2 c = cj_bezier2_view(2, pts, w);
    const double ds[3] = {0.5, 1.5, -0.5}, radius[3] = {0.5, -1, 1.5};
    for (int k = 0; k < 3; ++k) {
        trim_out r;
        cj_status st = run(&c, ds[k], 1e-6, &r);
        CHECK(st == CJ_OK, "arc d = %g: status %d", ds[k], (int)st);
        if (radius[k] < 0) {
            CHECK(r.nout == 0 && r.dropped >= 1, "arc d = %g: %d pieces kept (must vanish)", ds[k],
                  r.nout);
            printf("quarter circle offset inwards by %g (past its radius): %d raw pieces, all "
                   "dropped\n",
                   ds[k], r.nraw);
            continue;
        }
        double worst = 0;
        for (int i = 0; i < r.nout; ++i)
            for (int s = 0; s <= 16; ++s) {
                double x[2];
                eval_cubic(trimmed + 8 * i, s / 16.0, x);
                worst = fmax(worst, fabs(hypot(x[0], x[1]) - radius[k]));
            }
        CHECK(r.nout == r.nraw && r.dropped == 0 && r.lines == 1 && worst <= r.dev + 1e-15,
              "arc d = %g: %d of %d kept, %d dropped, %d lines, %g off the circle (dev %g)", ds[k],
              r.nout, r.nraw, r.dropped, r.lines, worst, r.dev);
        printf("quarter circle offset by %g: all %d pieces kept, on the circle of radius %g within "
               "%.2g (deviation %.2g)\n",
               ds[k], r.nout, radius[k], worst, r.dev);
    }
}

static void check_parabola(void) {
    const double pts[6] = {-1, 1, 0, -1, 1, 1};
    cj_bezier2 c = cj_bezier2_view(2, pts, NULL);
    double d = 0.8, tol = 1e-6;
    trim_out r;
    cj_status st = run(&c, d, tol, &r);
    CHECK(st == CJ_OK, "parabola: status %d", (int)st);
    if (st != CJ_OK) return;
    double raw_min = INFINITY;
    for (int i = 0; i < r.nraw; ++i) {
        double x[2];
        eval_cubic(raw + 8 * i, 0.5, x);
        raw_min = fmin(raw_min, oracle_dist(&c, x));
    }
    double lo = INFINITY, hi = 0, join = INFINITY;
    for (int i = 0; i < r.nout; ++i) {
        for (int s = 0; s <= 8; ++s) {
            double x[2];
            eval_cubic(trimmed + 8 * i, s / 8.0, x);
            double dist = oracle_dist(&c, x);
            lo = fmin(lo, dist);
            hi = fmax(hi, dist);
        }
        if (i > 0 && !newline[i]) {
            double gap =
                hypot(trimmed[8 * i] - trimmed[8 * i - 2], trimmed[8 * i + 1] - trimmed[8 * i - 1]);
            CHECK(gap == 0.0, "parabola: piece %d starts %g from the previous end", i, gap);
        }
        join = fmin(join, hypot(trimmed[8 * i], trimmed[8 * i + 1] - 0.89));
    }
    double margin = 2 * (r.dev + tol) + 1e-7;
    CHECK(r.dropped >= 1 && r.lines == 1 && r.nout > 0, "parabola: %d dropped, %d lines, %d pieces",
          r.dropped, r.lines, r.nout);
    CHECK(lo >= d - margin && hi <= d + r.dev + 1e-7,
          "parabola: kept points at distances %.12g .. %.12g from the curve (d = %g)", lo, hi, d);
    CHECK(join <= 2 * r.dev, "parabola: no kept piece starts at the crossing (0, 0.89): %g", join);
    CHECK(raw_min < d - 0.1, "parabola: the raw offset had no loop (min distance %g)", raw_min);
    printf("parabola y = x^2 offset by 0.8 (radius 0.5 at the vertex): raw %d pieces with points "
           "down to %.3f from the curve; trimmed: %d pieces in one connected curve, %d span(s) "
           "dropped, kept points at %.9f .. %.9f, joined at the exact crossing (0, 0.89) within "
           "%.2g\n",
           r.nraw, raw_min, r.nout, r.dropped, lo, hi, join);
}

static void check_s_curve(void) {
    const double pts[8] = {0, 0, 1, 1, 2, -1, 3, 0};
    cj_bezier2 c = cj_bezier2_view(3, pts, NULL);
    trim_out r;
    cj_status st = run(&c, 0.05, 1e-6, &r);
    CHECK(st == CJ_OK && r.nout == r.nraw && r.dropped == 0 && r.lines == 1,
          "S curve: status %d, %d of %d kept, %d lines", (int)st, r.nout, r.nraw, r.lines);
    int same = st == CJ_OK && memcmp(raw, trimmed, sizeof(double) * 8 * (size_t)r.nout) == 0;
    CHECK(same, "S curve: the kept pieces differ from the raw ones");
    printf("S-shaped cubic offset by 0.05: nothing to trim, the %d pieces come back unchanged\n",
           r.nout);
}

static void check_bad_input(void) {
    const double pts[6] = {-1, 1, 0, -1, 1, 1};
    cj_bezier2 c = cj_bezier2_view(2, pts, NULL);
    double p[8] = {0, 0, 1, 1, 2, 1, 3, 0}, out[8];
    int n, dropped;
    CHECK(cj_offset_trim(&c, 0.1, 1e-6, p, 0, 0, out, NULL, 1, &n, &dropped) == CJ_ERR_EMPTY,
          "no pieces");
    CHECK(cj_offset_trim(&c, 0.1, 0.0, p, 1, 0, out, NULL, 1, &n, &dropped) == CJ_ERR_ARGUMENT,
          "tol 0");
    CHECK(strstr(cj_last_error(), "tol") != NULL, "message %s", cj_last_error());
    CHECK(cj_offset_trim(&c, NAN, 1e-6, p, 1, 0, out, NULL, 1, &n, &dropped) == CJ_ERR_NONFINITE,
          "NaN d");
    CHECK(cj_offset_trim(&c, 0.1, 1e-6, p, 1, -1, out, NULL, 1, &n, &dropped) == CJ_ERR_ARGUMENT,
          "negative deviation");
    p[3] = NAN;
    CHECK(cj_offset_trim(&c, 0.1, 1e-6, p, 1, 0, out, NULL, 1, &n, &dropped) == CJ_ERR_NONFINITE,
          "NaN piece");
    CHECK(strstr(cj_last_error(), "piece 0") != NULL, "message %s", cj_last_error());
    p[3] = 1;
    CHECK(cj_offset_trim(&c, 0.1, 1e-6, p, 1, 0, out, NULL, 0, &n, &dropped) == CJ_ERR_BUFFER &&
              n == 1,
          "buffer too small: n = %d", n);
    printf("bad input: no pieces, tol 0, NaN d, negative deviation, NaN piece, small buffer: "
           "refused\n");
}

int main(void) {
    check_circle();
    check_parabola();
    check_s_curve();
    check_bad_input();
    return cj_check_exit();
}

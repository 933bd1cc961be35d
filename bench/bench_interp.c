/* bench_interp: figures for issue 3's constructions.
 *
 * 1. Runge table: interpolation of 1/(1+25x^2) on [-1,1] at equispaced and Chebyshev
 *    parameters, degrees 5..40: max error on 4001 samples and the condition estimate.
 * 2. Cost: Catmull-Rom (uniform, centripetal) ns per segment on 10^4 planar points; polynomial
 *    interpolation µs per solve by degree; rational de Casteljau ns per evaluation.
 * 3. Contouring a unit circle in [-2,2]^2 on a 64x64 grid at tol 1e-2..1e-10: vertices, exact
 *    max distance of vertices and chord points to the circle, ms per contour.
 * Times are medians of 15 runs. */
#define _POSIX_C_SOURCE 199309L
#include "casteljau/bezier.h"
#include "casteljau/catmull_rom.h"
#include "casteljau/implicit.h"
#include "casteljau/interp.h"
#include "casteljau/rational.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include "bench_clock.h"

#define RUNS 15
static volatile double sink;

static void runge_table(void) {
    printf("Runge: 1/(1+25x^2) on [-1,1], max |p - f| on 4001 samples (condition estimate)\n");
    printf("  degree   equispaced            Chebyshev\n");
    const int degs[] = {5, 10, 15, 20, 25, 30, 40};
    for (size_t d = 0; d < sizeof degs / sizeof degs[0]; ++d) {
        const int n = degs[d];
        printf("  %6d", n);
        for (int cheb = 0; cheb < 2; ++cheb) {
            double xs[41], fs[41], bez[41], cond;
            if (cheb)
                cj_interp_chebyshev(n, -1, 1, xs);
            else
                cj_interp_equispaced(n, -1, 1, xs);
            for (int j = 0; j <= n; ++j) fs[j] = 1.0 / (1.0 + 25.0 * xs[j] * xs[j]);
            if (cj_interp_points(xs, fs, (size_t)n + 1, 1, -1, 1, bez, NULL, &cond)) {
                printf("   %-20s", cj_status_str(CJ_ERR_SINGULAR));
                continue;
            }
            cj_bezier c = cj_bezier_view(n, 1, bez);
            double err = 0;
            for (int q = 0; q <= 4000; ++q) {
                const double x = -1 + 2.0 * q / 4000;
                double p;
                cj_bezier_eval_decasteljau(&c, (x + 1) / 2, &p);
                err = fmax(err, fabs(p - 1.0 / (1.0 + 25.0 * x * x)));
            }
            printf("   %9.3g (%8.2g)", err, cond);
        }
        printf("\n");
    }
}

static void costs(void) {
    enum { N = 10000 };
    static double pts[2 * N], segs[8 * N];
    for (int i = 0; i < N; ++i) {
        pts[2 * i] = i + 0.3 * sin(i * 1.7);
        pts[2 * i + 1] = cos(i * 0.37) * 3;
    }
    const cj_spline_kind kinds[2] = {CJ_SPLINE_CATMULL_ROM, CJ_SPLINE_CENTRIPETAL};
    const char *names[2] = {"uniform", "centripetal"};
    for (int k = 0; k < 2; ++k) {
        cj_spline_options o = cj_spline_defaults();
        o.kind = kinds[k];
        double t[RUNS];
        for (int r = 0; r < RUNS; ++r) {
            const double t0 = (1e9 * cj_bench_wall());
            cj_catmull_rom(pts, N, 2, &o, segs, N, NULL, NULL);
            t[r] = ((1e9 * cj_bench_wall()) - t0) / (N - 1);
            sink = segs[5];
        }
        printf("Catmull-Rom %-12s %7.1f ns per segment (10^4 planar points)\n", names[k],
               cj_bench_median(t, (size_t)(RUNS)));
    }
    printf("polynomial interpolation (Chebyshev parameters, planar values), us per solve:\n");
    const int degs[] = {3, 5, 10, 20, 40, 64};
    for (size_t d = 0; d < sizeof degs / sizeof degs[0]; ++d) {
        const int n = degs[d];
        double xs[65], vals[130], bez[130], t[RUNS];
        cj_interp_chebyshev(n, 0, 1, xs);
        for (int j = 0; j <= n; ++j) {
            vals[2 * j] = sin(3 * xs[j]);
            vals[2 * j + 1] = xs[j] * xs[j];
        }
        for (int r = 0; r < RUNS; ++r) {
            const int reps = 20;
            const double t0 = (1e9 * cj_bench_wall());
            for (int q = 0; q < reps; ++q)
                cj_interp_points(xs, vals, (size_t)n + 1, 2, 0, 1, bez, NULL, NULL);
            t[r] = ((1e9 * cj_bench_wall()) - t0) / reps / 1e3;
            sink = bez[1];
        }
        printf("  degree %2d: %8.2f us\n", n, cj_bench_median(t, (size_t)(RUNS)));
    }
    const int rdeg[] = {2, 5, 10};
    for (size_t d = 0; d < 3; ++d) {
        const int n = rdeg[d];
        double p[22], w[11], out[2], t[RUNS];
        for (int i = 0; i <= n; ++i) {
            p[2 * i] = i;
            p[2 * i + 1] = (i % 2) * 2.0;
            w[i] = 1 + 0.5 * (i % 3);
        }
        cj_rbezier c = cj_rbezier_view(n, 2, p, w);
        for (int r = 0; r < RUNS; ++r) {
            const int reps = 20000;
            const double t0 = (1e9 * cj_bench_wall());
            for (int q = 0; q < reps; ++q) {
                cj_rbezier_eval(&c, (q + 0.5) / reps, out);
                sink = out[0];
            }
            t[r] = ((1e9 * cj_bench_wall()) - t0) / reps;
        }
        printf("rational de Casteljau, degree %2d: %6.1f ns per point\n", n,
               cj_bench_median(t, (size_t)(RUNS)));
    }
}

typedef struct dist_acc {
    double worst;
    size_t points;
} dist_acc;

static cj_status measure(void *user, const double *xy, size_t n, int closed, double res) {
    (void)closed;
    (void)res;
    dist_acc *a = user;
    a->points += n;
    for (size_t i = 0; i < n; ++i) {
        a->worst = fmax(a->worst, fabs(hypot(xy[2 * i], xy[2 * i + 1]) - 1));
        if (i + 1 < n)
            for (int q = 1; q < 4; ++q) {
                const double s = q / 4.0;
                const double x = (1 - s) * xy[2 * i] + s * xy[2 * i + 2];
                const double y = (1 - s) * xy[2 * i + 1] + s * xy[2 * i + 3];
                a->worst = fmax(a->worst, fabs(hypot(x, y) - 1));
            }
    }
    return CJ_OK;
}

static cj_status count_only(void *user, const double *xy, size_t n, int closed, double res) {
    (void)xy;
    (void)closed;
    (void)res;
    *(size_t *)user += n;
    return CJ_OK;
}

static void contour_table(void) {
    cj_implicit_shape sh;
    cj_implicit f;
    cj_implicit_circle(0, 0, 1, &sh, &f);
    const double box[4] = {-2, -2, 2, 2};
    printf("contour of the unit circle, box [-2,2]^2, grid 64x64:\n");
    printf("  tol       vertices   max distance (vertices+chords)   ms\n");
    for (int e = 2; e <= 10; e += 2) {
        const double tol = pow(10, -e);
        cj_contour_options o = {64, 64, tol, NULL};
        dist_acc acc = {0, 0};
        cj_implicit_contour(&f, box, &o, measure, &acc, NULL);
        double t[RUNS];
        for (int r = 0; r < RUNS; ++r) {
            size_t cnt = 0;
            const double t0 = (1e9 * cj_bench_wall());
            cj_implicit_contour(&f, box, &o, count_only, &cnt, NULL);
            t[r] = ((1e9 * cj_bench_wall()) - t0) / 1e6;
        }
        printf("  %-8.0e %9zu   %.3g (%.2f tol)   %27.3f\n", tol, acc.points, acc.worst,
               acc.worst / tol, cj_bench_median(t, (size_t)(RUNS)));
    }
}

int main(void) {
    runge_table();
    costs();
    contour_table();
    return 0;
}

/* bench_viewer_query: what the 2D editor's queries cost per call on the document of
 * docs/viewer_bspline.png (a cubic B-spline of 5 spans, a quadratic NURBS of 3 spans, a
 * rational quadratic): the certified snap of a cursor position (cj_vdoc_snap, run on every
 * cursor motion while P is on), the intersection marks of the whole document
 * (cj_vdoc_intersections, run with every picture while T is on) and a knot insertion.
 * Thread CPU time, median of the repetitions. */
#include "bench_clock.h"
#include "casteljau/viewer_model.h"

#include <stdio.h>
#include <string.h>

static const double bs_pts[] = {0.4, 0.6, 0.9, 3.0, 1.7, 0.5, 2.5, 3.3,
                                3.3, 0.8, 4.1, 3.1, 4.9, 0.7, 5.6, 2.6};
static const double bs_knots[] = {0, 0, 0, 0, 0.2, 0.4, 0.6, 0.8, 1, 1, 1, 1};
static const double nu_pts[] = {0.3, 3.6, 2.0, 1.2, 3.4, 3.7, 4.6, 1.4, 5.7, 3.5};
static const double nu_w[] = {1, 3, 1, 0.5, 1};
static const double nu_knots[] = {0, 0, 0, 0.3, 0.6, 1, 1, 1};
static const double rb_pts[] = {0.2, 1.9, 3.0, 0.3, 5.8, 2.0};
static const double rb_w[] = {1, 1, 1};

int main(int argc, char **argv) {
    const int reps = argc > 1 ? atoi(argv[1]) : 2000;
    cj_vdoc *d = NULL;
    if (cj_vdoc_create(&d)) return 1;
    cj_vcurve c = cj_vcurve_init(CJ_VCURVE_BSPLINE, 8, bs_pts, NULL);
    c.degree = 3;
    c.knot_vector = (double *)bs_knots;
    cj_vcurve n = cj_vcurve_init(CJ_VCURVE_BSPLINE, 5, nu_pts, nu_w);
    n.degree = 2;
    n.knot_vector = (double *)nu_knots;
    cj_vcurve r = cj_vcurve_init(CJ_VCURVE_RATIONAL, 3, rb_pts, rb_w);
    if (cj_vdoc_add_curve(d, &c) || cj_vdoc_add_curve(d, &n) || cj_vdoc_add_curve(d, &r)) {
        fprintf(stderr, "bench_viewer_query: %s\n", cj_last_error());
        return 1;
    }
    double *t = malloc(sizeof(double) * (size_t)reps);
    if (!t || reps < 1) return 1;
    /* 1e-3 px at the picture's 120 px per unit, as the viewer asks */
    const double tol = 1e-3 / 120.0;
    long pieces = 0;
    for (int i = 0; i < reps; ++i) {
        const double q[2] = {6.0 * ((i * 7919) % reps) / reps, 4.0 * ((i * 104729) % reps) / reps};
        cj_vsnap s;
        const double t0 = cj_bench_thread_cpu();
        if (cj_vdoc_snap(d, q, -1, tol, &s)) return 1;
        t[i] = cj_bench_thread_cpu() - t0;
        pieces += s.pieces;
    }
    printf("snap (P, every cursor motion): 3 curves, 9 Bezier pieces, tol 1e-3 px: median "
           "%.1f us per query over %d cursor positions, %.0f pieces examined per query\n",
           1e6 * cj_bench_median(t, (size_t)reps), reps, (double)pieces / reps);
    const int ir = reps / 20 > 5 ? reps / 20 : 5;
    size_t marks = 0;
    for (int i = 0; i < ir; ++i) {
        cj_vmark *m = NULL;
        size_t k = 0;
        const double t0 = cj_bench_thread_cpu();
        if (cj_vdoc_intersections(d, tol, &m, &k, NULL)) return 1;
        t[i] = cj_bench_thread_cpu() - t0;
        free(m);
        marks = k;
    }
    printf("intersections (T, every picture): %zu marks from 23 piece pairs: median %.2f ms per "
           "document (%d repetitions)\n",
           marks, 1e3 * cj_bench_median(t, (size_t)ir), ir);
    for (int i = 0; i < ir; ++i) {
        const double t0 = cj_bench_thread_cpu();
        if (cj_vdoc_insert_knot(d, 0, 0.5) || cj_vdoc_undo(d)) return 1;
        t[i] = cj_bench_thread_cpu() - t0;
    }
    printf("knot insertion + undo (I): median %.2f us\n", 1e6 * cj_bench_median(t, (size_t)ir));
    free(t);
    cj_vdoc_destroy(d);
    return 0;
}

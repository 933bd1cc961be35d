/* Example: evaluate a cubic Bézier curve with a proven error bound, then flatten it into a
 * polyline within a tolerance. Build against the installed library with
 *     cc curve_flatten.c $(pkg-config --cflags --libs casteljau) -o curve_flatten
 * (or, in CMake, target_link_libraries(... casteljau::curves)).
 * Output: the point at t = 1/2 and its bound, then the polyline as "x y" lines. */
#include <casteljau/bezier.h>
#include <casteljau/flatten.h>
#include <casteljau/status.h>
#include <stdio.h>
#include <stdlib.h>

/* Every casteljau call returns a status; the message names the input that was wrong. */
static void check(cj_status st, const char *what) {
    if (st != CJ_OK) {
        fprintf(stderr, "%s: %s (%s)\n", what, cj_last_error(), cj_status_str(st));
        exit(1);
    }
}

int main(void) {
    /* Four control points in 2-D, point-major: x0 y0 x1 y1 ... */
    const double pts[] = {0.0, 0.0, 1.0, 2.0, 3.0, 2.0, 4.0, 0.0};
    cj_bezier curve = cj_bezier_view(3, 2, pts);

    /* Compensated de Casteljau: the value as if computed in twice the precision, and a bound
     * on its distance from the exact value, per coordinate. */
    double mid[2], bound[2];
    check(cj_bezier_eval_compensated(&curve, 0.5, mid, bound), "evaluate");
    printf("c(0.5) = (%.17g, %.17g), error at most (%.3g, %.3g)\n", mid[0], mid[1], bound[0],
           bound[1]);

    /* Count, then fill: the first call sizes the buffer, the second writes the points. */
    cj_flatten_opts opts = cj_flatten_defaults(CJ_FLATTEN_NEAR_OPTIMAL, 1e-3);
    size_t npoints = 0;
    check(cj_flatten_bezier(&curve, &opts, NULL, 0, &npoints, NULL), "count");
    double *poly = malloc(npoints * 2 * sizeof *poly);
    if (!poly) return 1;
    cj_flatten_stats stats;
    check(cj_flatten_bezier(&curve, &opts, poly, npoints, &npoints, &stats), "flatten");
    printf("flattened into %zu segments, distance to the curve at most %.3g (asked 1e-3)\n",
           stats.segments, stats.bound);
    for (size_t i = 0; i < npoints; i++) printf("%.6f %.6f\n", poly[2 * i], poly[2 * i + 1]);
    free(poly);
    return 0;
}

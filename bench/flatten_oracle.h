/* bench_flatten's distance oracle: the largest distance from a planar polynomial Bézier curve
 * (degree <= 3) to a polyline, enclosed in [lo, hi] by branch and bound (see
 * flatten_oracle.c). */
#ifndef CJ_BENCH_FLATTEN_ORACLE_H
#define CJ_BENCH_FLATTEN_ORACLE_H

#include <stddef.h>

typedef struct cj_oracle_dev {
    double lo; /* a distance the curve attains (a point of the curve this far from the polyline) */
    double hi; /* no point of the curve is farther than this */
} cj_oracle_dev;

/* max over t in [0,1] of dist(c(t), polyline) for the curve of degree n (2 or 3) with control
 * points p[2(n+1)], the polyline pts[2 np] (np >= 2), enclosed to within rel_gap * scale
 * (hi - lo <= rel_gap * scale unless the subdivision depth runs out, which only widens hi). */
cj_oracle_dev cj_oracle_curve_polyline(int n, const double *p, const double *pts, size_t np,
                                       double rel_gap, double scale);

#endif

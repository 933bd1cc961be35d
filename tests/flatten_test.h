/* Shared by the source files of test_flatten: the long-double oracle (independent of the
 * library), the polyline collected from the flattening callback, and the measured deviation;
 * flatten_oracle.c holds them, flatten_fast_path.c the fast planar path's test. */
#ifndef CJ_TEST_FLATTEN_H
#define CJ_TEST_FLATTEN_H

#include <stddef.h>

/* Point of the (rational, when w is not NULL) Bézier curve of degree n in dimension d at t:
 * de Casteljau in long double on homogeneous points. */
void oracle_eval(int n, int d, const double *pts, const double *w, long double t, long double *out);
/* Distance from p to the segment [a, b] in dimension d, in long double. */
long double dist_point_segment(const long double *p, const double *a, const double *b, int d);

/* Collects vertices and parameters from the callback. */
typedef struct poly {
    int d;
    size_t n, cap;
    double *pts, *ts;
    size_t *piece;
} poly;

/* Flattening callback (cj_flatten_*_cb) appending to the poly in user. */
void sink(void *user, const double *pt, int dim, size_t piece, double t);
void poly_free(poly *p);
/* Largest distance from dense samples of the curve (per segment, `per` samples plus the
 * segment's own parameters) to that segment of the polyline. Distance to the own segment is
 * at least the distance to the whole polyline, so this is a stricter check. Also checks the
 * vertices lie on the curve. */
double measure(int n, int d, const double *pts, const double *w, const poly *p, int per,
               double *vertex_err);

/* flatten_fast_path.c */
void test_fast_path_hard(void **state);
void test_fast_path_few(void **state);

#endif

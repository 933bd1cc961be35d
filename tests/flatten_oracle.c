/* The oracle and polyline helpers of test_flatten (see flatten_test.h). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "casteljau/flatten.h"
#include "flatten_test.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* ---- oracle: long-double de Casteljau on homogeneous points, independent of the library --- */

void oracle_eval(int n, int d, const double *pts, const double *w, long double t,
                 long double *out) {
    long double h[64 * (CJ_MAX_DIM + 1)]; /* the tests use degrees < 64 */
    assert_true(n < 64);
    const int D = d + 1;
    for (int i = 0; i <= n; ++i) {
        const long double wi = w ? (long double)w[i] : 1.0L;
        for (int k = 0; k < d; ++k) h[i * D + k] = wi * (long double)pts[i * d + k];
        h[i * D + d] = wi;
    }
    for (int r = n; r > 0; --r)
        for (int i = 0; i < r * D; ++i) h[i] = (1.0L - t) * h[i] + t * h[i + D];
    for (int k = 0; k < d; ++k) out[k] = h[k] / h[d];
}

long double dist_point_segment(const long double *p, const double *a, const double *b, int d) {
    long double ab2 = 0, ap_ab = 0;
    for (int k = 0; k < d; ++k) {
        const long double ab = (long double)b[k] - a[k];
        ab2 += ab * ab;
        ap_ab += (p[k] - a[k]) * ab;
    }
    long double s = ab2 > 0 ? ap_ab / ab2 : 0;
    if (s < 0) s = 0;
    if (s > 1) s = 1;
    long double dd = 0;
    for (int k = 0; k < d; ++k) {
        const long double q = p[k] - (a[k] + s * ((long double)b[k] - a[k]));
        dd += q * q;
    }
    return sqrtl(dd);
}

void sink(void *user, const double *pt, int dim, size_t piece, double t) {
    poly *p = user;
    assert_int_equal(dim, p->d);
    if (p->n == p->cap) {
        p->cap = p->cap ? 2 * p->cap : 64;
        p->pts = realloc(p->pts, sizeof(double) * p->cap * (size_t)p->d);
        p->ts = realloc(p->ts, sizeof(double) * p->cap);
        p->piece = realloc(p->piece, sizeof(size_t) * p->cap);
        assert_non_null(p->pts);
        assert_non_null(p->ts);
        assert_non_null(p->piece);
    }
    memcpy(p->pts + p->n * (size_t)p->d, pt, sizeof(double) * (size_t)dim);
    p->ts[p->n] = t;
    p->piece[p->n] = piece;
    p->n++;
}

void poly_free(poly *p) {
    free(p->pts);
    free(p->ts);
    free(p->piece);
    memset(p, 0, sizeof *p);
}

/* Largest distance from dense samples of the curve (per segment, `per` samples plus the
 * segment's own parameters) to that segment of the polyline. Distance to the own segment is
 * at least the distance to the whole polyline, so this is a stricter check. Also checks the
 * vertices lie on the curve. */
double measure(int n, int d, const double *pts, const double *w, const poly *p, int per,
               double *vertex_err) {
    long double worst = 0, verr = 0;
    /* keep the cost bounded on very fine flattenings */
    if (p->n > 1 && (size_t)per * (p->n - 1) > 400000) per = (int)(400000 / (p->n - 1));
    if (per < 2) per = 2;
    for (size_t j = 0; j < p->n; ++j) {
        long double c[CJ_MAX_DIM], e = 0;
        oracle_eval(n, d, pts, w, p->ts[j], c);
        for (int k = 0; k < d; ++k) e += (c[k] - p->pts[j * d + k]) * (c[k] - p->pts[j * d + k]);
        if (sqrtl(e) > verr) verr = sqrtl(e);
    }
    for (size_t j = 0; j + 1 < p->n; ++j) {
        const long double t0 = p->ts[j], t1 = p->ts[j + 1];
        for (int s = 0; s <= per; ++s) {
            long double c[CJ_MAX_DIM];
            oracle_eval(n, d, pts, w, t0 + (t1 - t0) * s / per, c);
            const long double dd = dist_point_segment(c, p->pts + j * d, p->pts + (j + 1) * d, d);
            if (dd > worst) worst = dd;
        }
    }
    if (vertex_err) *vertex_err = (double)verr;
    return (double)worst;
}

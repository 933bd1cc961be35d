/* B-spline validation, knot vectors, spans. See casteljau/bspline.h. */
#include "bspline_internal.h"
#include "error_internal.h"

#include <assert.h>
#include <math.h>

cj_status cj_bsp_check_knots(const double *knots, int npts, int p, const char *name) {
    const int nk = npts + p + 1;
    cj_status st = cj_check_finite(knots, (size_t)nk, name);
    if (st) return st;
    int run = 1;
    for (int i = 1; i < nk; ++i) {
        if (knots[i] < knots[i - 1])
            return cj_fail(CJ_ERR_ARGUMENT,
                           "%s %d (%.17g) is below %s %d (%.17g): knots must not decrease", name, i,
                           knots[i], name, i - 1, knots[i - 1]);
        run = knots[i] == knots[i - 1] ? run + 1 : 1;
        if (run > p + 1)
            return cj_fail(CJ_ERR_ARGUMENT,
                           "%s %d (%.17g) has multiplicity %d, above degree + 1 = %d", name, i,
                           knots[i], run, p + 1);
    }
    if (!(knots[p] < knots[npts]))
        return cj_fail(CJ_ERR_DEGENERATE, "empty domain: %s %d equals %s %d (%.17g)", name, p, name,
                       npts, knots[p]);
    return CJ_OK;
}

cj_status cj_bspline_check(const cj_bspline *c) {
    assert(c != NULL);
    const int p = c->degree;
    if (p < 0) return cj_fail(CJ_ERR_DEGREE, "B-spline degree %d is negative", p);
    if (p > CJ_BSPLINE_MAX_DEGREE)
        return cj_fail(CJ_ERR_DEGREE, "B-spline degree %d exceeds the limit of %d", p,
                       CJ_BSPLINE_MAX_DEGREE);
    const int maxdim = c->weights ? CJ_MAX_DIM - 1 : CJ_MAX_DIM;
    if (c->dim < 1 || c->dim > maxdim)
        return cj_fail(CJ_ERR_DIMENSION, "%s dimension %d is outside 1..%d",
                       c->weights ? "NURBS" : "B-spline", c->dim, maxdim);
    if (c->npts < p + 1)
        return cj_fail(CJ_ERR_EMPTY, "%d control points are too few for degree %d (need %d)",
                       c->npts, p, p + 1);
    assert(c->pts != NULL && c->knots != NULL);
    cj_status st = cj_bsp_check_knots(c->knots, c->npts, p, "knot");
    if (st) return st;
    if ((st = cj_check_points(c->pts, (size_t)c->npts, c->dim, "control point"))) return st;
    if (c->weights) {
        if ((st = cj_check_finite(c->weights, (size_t)c->npts, "weight"))) return st;
        for (int i = 0; i < c->npts; ++i)
            if (!(c->weights[i] > 0.0))
                return cj_fail(CJ_ERR_ARGUMENT, "weight %d is %.17g; weights must be positive", i,
                               c->weights[i]);
    }
    return CJ_OK;
}

cj_status cj_bspline_domain(const cj_bspline *c, double *t0, double *t1) {
    assert(t0 != NULL && t1 != NULL);
    cj_status st = cj_bspline_check(c);
    if (st) return st;
    *t0 = c->knots[c->degree];
    *t1 = c->knots[c->npts];
    return CJ_OK;
}

cj_status cj_bspline_uniform_knots(int npts, int degree, double a, double b, int clamped,
                                   double *knots) {
    assert(knots != NULL);
    if (degree < 0 || degree > CJ_BSPLINE_MAX_DEGREE)
        return cj_fail(CJ_ERR_DEGREE, "degree %d is outside 0..%d", degree, CJ_BSPLINE_MAX_DEGREE);
    if (npts < degree + 1)
        return cj_fail(CJ_ERR_EMPTY, "%d control points are too few for degree %d", npts, degree);
    if (!isfinite(a) || !isfinite(b))
        return cj_fail(CJ_ERR_NONFINITE, "knot range [%g, %g] is not finite", a, b);
    if (!(a < b)) return cj_fail(CJ_ERR_ARGUMENT, "knot range [%.17g, %.17g] is empty", a, b);
    const int p = degree, nk = npts + p + 1;
    if (clamped) {
        const int spans = npts - p;
        for (int i = 0; i <= p; ++i) {
            knots[i] = a;
            knots[nk - 1 - i] = b;
        }
        for (int j = 1; j < spans; ++j) knots[p + j] = a + (b - a) * ((double)j / spans);
    } else {
        const int spans = npts - p;
        const double h = (b - a) / spans;
        for (int i = 0; i < nk; ++i) knots[i] = a + h * (i - p);
        knots[p] = a;
        knots[npts] = b;
    }
    return CJ_OK;
}

cj_status cj_bspline_periodic(const double *cyc, const double *cyc_w, int m, int dim, int degree,
                              double *pts, double *weights, double *knots) {
    assert(cyc != NULL && pts != NULL && knots != NULL);
    if (degree < 1 || degree > CJ_BSPLINE_MAX_DEGREE)
        return cj_fail(CJ_ERR_DEGREE, "periodic degree %d is outside 1..%d", degree,
                       CJ_BSPLINE_MAX_DEGREE);
    const int maxdim = cyc_w ? CJ_MAX_DIM - 1 : CJ_MAX_DIM;
    if (dim < 1 || dim > maxdim)
        return cj_fail(CJ_ERR_DIMENSION, "dimension %d is outside 1..%d", dim, maxdim);
    if (m < degree + 1)
        return cj_fail(CJ_ERR_EMPTY, "%d cyclic points are too few for a closed curve of degree %d",
                       m, degree);
    cj_status st = cj_check_points(cyc, (size_t)m, dim, "cyclic point");
    if (st) return st;
    if (cyc_w) {
        assert(weights != NULL);
        if ((st = cj_check_finite(cyc_w, (size_t)m, "weight"))) return st;
        for (int i = 0; i < m; ++i)
            if (!(cyc_w[i] > 0.0))
                return cj_fail(CJ_ERR_ARGUMENT, "weight %d is %.17g; weights must be positive", i,
                               cyc_w[i]);
    }
    const int n1 = m + degree;
    for (int i = 0; i < n1; ++i) {
        for (int k = 0; k < dim; ++k) pts[i * dim + k] = cyc[(i % m) * dim + k];
        if (cyc_w) weights[i] = cyc_w[i % m];
    }
    for (int i = 0; i < n1 + degree + 1; ++i) knots[i] = (double)(i - degree);
    return CJ_OK;
}

int cj_bsp_multiplicity(const double *knots, int nknots, double x) {
    int m = 0;
    for (int i = 0; i < nknots; ++i) m += knots[i] == x;
    return m;
}

int cj_bsp_span(const cj_bspline *c, double t) {
    const double *u = c->knots;
    const int p = c->degree, n = c->npts - 1;
    /* Largest s in [p, n] with u[s] <= t (u[p] <= t holds), by a branch-free halving: a
     * data-dependent branch per step costs more than the step on random parameters. */
    int lo = p, len = n - p + 1;
    while (len > 1) {
        const int half = len / 2;
        lo = u[lo + half] <= t ? lo + half : lo;
        len -= half;
    }
    /* t at the right end of the domain: back to the last non-empty span. */
    while (lo > p && !(u[lo] < u[lo + 1])) --lo;
    return lo;
}

cj_status cj_bsp_check_param(const cj_bspline *c, double t, const char *what) {
    if (!isfinite(t)) return cj_fail(CJ_ERR_NONFINITE, "%s is not finite", what);
    const double a = c->knots[c->degree], b = c->knots[c->npts];
    if (t < a || t > b)
        return cj_fail(CJ_ERR_RANGE, "%s = %.17g is outside the domain [%.17g, %.17g]", what, t, a,
                       b);
    return CJ_OK;
}

cj_status cj_bspline_find_span(const cj_bspline *c, double t, int *span) {
    assert(span != NULL);
    cj_status st = cj_bspline_check(c);
    if (st) return st;
    if ((st = cj_bsp_check_param(c, t, "parameter t"))) return st;
    *span = cj_bsp_span(c, t);
    return CJ_OK;
}

void cj_bsp_local(const cj_bspline *c, int span, double *loc) {
    const int q = c->degree, hd = cj_bsp_hdim(c);
    for (int j = 0; j <= q; ++j) cj_bsp_hpoint(c, span - q + j, loc + j * hd);
}

void cj_bsp_deboor(const double *knots, int q, int span, int hd, double *loc, double t,
                   const double *xs) {
    for (int r = 1; r <= q; ++r) {
        const double x = xs ? xs[r - 1] : t;
        for (int j = q; j >= r; --j) {
            const int i = span - q + j;
            const double lo = knots[i], hi = knots[i + q + 1 - r];
            const double den = hi - lo;
            const double a = (x - lo) / den, b = (hi - x) / den;
            double *dst = loc + j * hd;
            const double *prev = dst - hd;
            for (int k = 0; k < hd; ++k) dst[k] = b * prev[k] + a * dst[k];
        }
    }
}

void cj_bsp_from_homogeneous(const double *h, int npts, int dim, int rational, double *pts,
                             double *w) {
    const int hd = dim + (rational != 0);
    for (int i = 0; i < npts; ++i) {
        const double *src = h + (size_t)i * (size_t)hd;
        if (rational) {
            w[i] = src[dim];
            for (int k = 0; k < dim; ++k) pts[i * dim + k] = src[k] / src[dim];
        } else {
            for (int k = 0; k < dim; ++k) pts[i * dim + k] = src[k];
        }
    }
}

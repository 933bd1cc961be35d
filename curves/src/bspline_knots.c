/* B-spline knot insertion (Boehm), refinement and removal within a tolerance, all on
 * homogeneous points. See casteljau/bspline.h. */
#include "bspline_internal.h"
#include "error_internal.h"

#include <assert.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

cj_status cj_bsp_h_alloc(cj_bsp_h *a, int p, int dim, int rational, int cap) {
    const int hd = dim + (rational != 0);
    a->p = p;
    a->dim = dim;
    a->rational = rational != 0;
    a->n1 = 0;
    a->h = malloc(sizeof(double) * (size_t)cap * (size_t)hd);
    a->u = malloc(sizeof(double) * ((size_t)cap + (size_t)p + 1));
    if (!a->h || !a->u) {
        cj_bsp_h_free(a);
        return cj_fail(CJ_ERR_NOMEM, "no memory for a B-spline of %d points", cap);
    }
    return CJ_OK;
}

void cj_bsp_h_free(cj_bsp_h *a) {
    free(a->h);
    free(a->u);
    a->h = a->u = NULL;
}

void cj_bsp_h_from_view(cj_bsp_h *a, const cj_bspline *c) {
    const int hd = cj_bsp_hdim(c);
    a->n1 = c->npts;
    for (int i = 0; i < c->npts; ++i) cj_bsp_hpoint(c, i, a->h + (size_t)i * (size_t)hd);
    memcpy(a->u, c->knots, sizeof(double) * (size_t)(c->npts + c->degree + 1));
}

void cj_bsp_h_to_view(const cj_bsp_h *a, double *pts, double *w, double *knots) {
    cj_bsp_from_homogeneous(a->h, a->n1, a->dim, a->rational, pts, w);
    memcpy(knots, a->u, sizeof(double) * (size_t)(a->n1 + a->p + 1));
}

/* Largest k in [p, n1-1] with u[k] <= x. */
static int insert_span(const double *u, int p, int n1, double x) {
    int k = p;
    while (k + 1 <= n1 - 1 && u[k + 1] <= x) ++k;
    return k;
}

void cj_bsp_insert_once(const cj_bsp_h *src, double x, cj_bsp_h *dst) {
    const int p = src->p, n1 = src->n1, hd = src->dim + src->rational;
    const double *u = src->u, *h = src->h;
    const int k = insert_span(u, p, n1, x);
    int s = 0;
    for (int i = k; i >= 0 && u[i] == x; --i) ++s;
    dst->p = p;
    dst->dim = src->dim;
    dst->rational = src->rational;
    dst->n1 = n1 + 1;
    double *g = dst->h;
    for (int i = 0; i <= k - p; ++i) memcpy(g + i * hd, h + i * hd, sizeof(double) * (size_t)hd);
    for (int i = k - p + 1; i <= k - s; ++i) {
        const double den = u[i + p] - u[i];
        const double a = (x - u[i]) / den, b = (u[i + p] - x) / den;
        for (int j = 0; j < hd; ++j) g[i * hd + j] = a * h[i * hd + j] + b * h[(i - 1) * hd + j];
    }
    for (int i = k - s + 1; i <= n1; ++i)
        memcpy(g + i * hd, h + (i - 1) * hd, sizeof(double) * (size_t)hd);
    memcpy(dst->u, u, sizeof(double) * (size_t)(k + 1));
    dst->u[k + 1] = x;
    memcpy(dst->u + k + 2, u + k + 1, sizeof(double) * (size_t)(n1 + p - k));
}

/* Euclidean distance of two dehomogenised-layout coordinate vectors (first dim entries). */
static double dist(const double *a, const double *b, int dim) {
    double s = 0.0, m = 0.0;
    for (int k = 0; k < dim; ++k) m = fmax(m, fabs(a[k] - b[k]));
    if (m == 0.0) return 0.0;
    for (int k = 0; k < dim; ++k) {
        const double q = (a[k] - b[k]) / m;
        s += q * q;
    }
    return m * sqrt(s) * (1.0 + 4 * CJ_UNIT_ROUNDOFF);
}

int cj_bsp_remove_once(const cj_bsp_h *src, double x, cj_bsp_h *dst, cj_bsp_h *scratch,
                       double *err) {
    const int p = src->p, n1 = src->n1, d = src->dim, hd = d + src->rational;
    const double *u = src->u, *P = src->h;
    int r = n1 + p; /* last index holding x */
    while (u[r] != x) --r;
    int s = 0;
    for (int i = r; i >= 0 && u[i] == x; --i) ++s;
    const int lo = r - p, hi = r - s; /* the equations P_i = a_i Q_i + b_i Q_{i-1}, i in lo..hi */
    double *Q = dst->h;
    dst->p = p;
    dst->dim = d;
    dst->rational = src->rational;
    dst->n1 = n1 - 1;
    /* Unchanged points: Q_j = P_j below lo, Q_j = P_{j+1} from hi on. */
    memcpy(Q, P, sizeof(double) * (size_t)(lo * hd));
    memcpy(Q + hi * hd, P + (hi + 1) * hd, sizeof(double) * (size_t)((n1 - 1 - hi) * hd));
    const int unknowns = hi - lo, left = unknowns / 2;
    for (int i = lo; i < lo + left; ++i) { /* forwards: Q_i = (P_i - b_i Q_{i-1}) / a_i */
        const double den = u[i + p + 1] - u[i];
        const double a = (x - u[i]) / den, b = (u[i + p + 1] - x) / den;
        for (int j = 0; j < hd; ++j) Q[i * hd + j] = (P[i * hd + j] - b * Q[(i - 1) * hd + j]) / a;
    }
    for (int i = hi; i > lo + left; --i) { /* backwards: Q_{i-1} = (P_i - a_i Q_i) / b_i */
        const double den = u[i + p + 1] - u[i];
        const double a = (x - u[i]) / den, b = (u[i + p + 1] - x) / den;
        for (int j = 0; j < hd; ++j) Q[(i - 1) * hd + j] = (P[i * hd + j] - a * Q[i * hd + j]) / b;
    }
    /* Knots without the copy at r. */
    memcpy(dst->u, u, sizeof(double) * (size_t)r);
    memcpy(dst->u + r, u + r + 1, sizeof(double) * (size_t)(n1 + p - r));
    *err = INFINITY;
    for (int i = 0; i < (n1 - 1) * hd; ++i)
        if (!isfinite(Q[i])) return -1;
    if (src->rational)
        for (int i = 0; i < n1 - 1; ++i)
            if (!(Q[i * hd + d] > 0.0)) return -1;
    /* Re-insert x and compare with the original points: the difference curve has these
     * differences as control points, so their largest norm bounds the deviation. */
    cj_bsp_insert_once(dst, x, scratch);
    const double *R = scratch->h;
    double e = 0.0;
    if (!src->rational) {
        for (int i = 0; i < n1; ++i) e = fmax(e, dist(P + i * hd, R + i * hd, d));
    } else {
        double da = 0.0, dw = 0.0, wmin = INFINITY, pmax = 0.0;
        for (int i = 0; i < n1; ++i) {
            da = fmax(da, dist(P + i * hd, R + i * hd, d));
            dw = fmax(dw, fabs(P[i * hd + d] - R[i * hd + d]));
            wmin = fmin(wmin, P[i * hd + d]);
        }
        for (int i = 0; i < n1 - 1; ++i) {
            double n2 = 0.0;
            for (int k = 0; k < d; ++k) {
                const double c = Q[i * hd + k] / Q[i * hd + d];
                n2 += c * c;
            }
            pmax = fmax(pmax, sqrt(n2));
        }
        e = (da + pmax * (1.0 + 4 * CJ_UNIT_ROUNDOFF) * dw) / wmin * (1.0 + 8 * CJ_UNIT_ROUNDOFF);
    }
    if (!isfinite(e)) return -1;
    *err = e;
    return 0;
}

static cj_status check_outputs(const cj_bspline *c, double *out_w) {
    if ((c->weights != NULL) != (out_w != NULL))
        return cj_fail(CJ_ERR_ARGUMENT, "output weights %s for a %s", out_w ? "given" : "missing",
                       c->weights ? "NURBS" : "polynomial B-spline");
    return CJ_OK;
}

/* Validates xs (finite, in the domain, non-decreasing, final multiplicities <= p). */
static cj_status check_insertions(const cj_bspline *c, const double *xs, int nx) {
    const int p = c->degree, nk = c->npts + p + 1;
    for (int j = 0; j < nx; ++j) {
        cj_status st = cj_bsp_check_param(c, xs[j], "inserted knot");
        if (st) return st;
        if (j > 0 && xs[j] < xs[j - 1])
            return cj_fail(CJ_ERR_ARGUMENT, "inserted knot %d (%.17g) is below the previous one", j,
                           xs[j]);
        if (j == 0 || xs[j] != xs[j - 1]) {
            int m = cj_bsp_multiplicity(c->knots, nk, xs[j]);
            for (int i = j; i < nx && xs[i] == xs[j]; ++i) ++m;
            if (m > p)
                return cj_fail(CJ_ERR_ARGUMENT,
                               "inserting knot %.17g would raise its multiplicity to %d, above "
                               "the degree %d",
                               xs[j], m, p);
        }
    }
    return CJ_OK;
}

cj_status cj_bspline_refine(const cj_bspline *c, const double *xs, int nx, double *out_pts,
                            double *out_w, double *out_knots) {
    assert(out_pts != NULL && out_knots != NULL && (nx == 0 || xs != NULL));
    cj_status st = cj_bspline_check(c);
    if (st) return st;
    if ((st = check_outputs(c, out_w))) return st;
    if (nx < 0) return cj_fail(CJ_ERR_ARGUMENT, "knot count %d is negative", nx);
    if ((st = check_insertions(c, xs, nx))) return st;
    const int rational = c->weights != NULL, cap = c->npts + nx;
    cj_bsp_h a, b;
    if ((st = cj_bsp_h_alloc(&a, c->degree, c->dim, rational, cap))) return st;
    if ((st = cj_bsp_h_alloc(&b, c->degree, c->dim, rational, cap))) {
        cj_bsp_h_free(&a);
        return st;
    }
    cj_bsp_h_from_view(&a, c);
    for (int j = 0; j < nx; ++j) {
        cj_bsp_insert_once(&a, xs[j], &b);
        cj_bsp_h t = a;
        a = b;
        b = t;
    }
    cj_bsp_h_to_view(&a, out_pts, out_w, out_knots);
    cj_bsp_h_free(&a);
    cj_bsp_h_free(&b);
    return CJ_OK;
}

cj_status cj_bspline_insert_knot(const cj_bspline *c, double x, int r, double *out_pts,
                                 double *out_w, double *out_knots) {
    cj_status st = cj_bspline_check(c);
    if (st) return st;
    if (r < 0) return cj_fail(CJ_ERR_ARGUMENT, "insertion count %d is negative", r);
    if (r > c->degree)
        return cj_fail(CJ_ERR_ARGUMENT,
                       "inserting knot %.17g %d times would raise its multiplicity above the "
                       "degree %d",
                       x, r, c->degree);
    double xs[CJ_BSPLINE_MAX_DEGREE + 1];
    for (int j = 0; j < r; ++j) xs[j] = x;
    return cj_bspline_refine(c, xs, r, out_pts, out_w, out_knots);
}

cj_status cj_bspline_remove_knot(const cj_bspline *c, double x, int r, double tol, double *out_pts,
                                 double *out_w, double *out_knots, int *removed, double *error) {
    assert(out_pts != NULL && out_knots != NULL && removed != NULL);
    cj_status st = cj_bspline_check(c);
    if (st) return st;
    if ((st = check_outputs(c, out_w))) return st;
    if (!isfinite(x)) return cj_fail(CJ_ERR_NONFINITE, "knot to remove is not finite");
    if (isnan(tol)) return cj_fail(CJ_ERR_NONFINITE, "removal tolerance is NaN");
    if (!(tol >= 0.0)) return cj_fail(CJ_ERR_ARGUMENT, "removal tolerance %g is negative", tol);
    if (r < 0) return cj_fail(CJ_ERR_ARGUMENT, "removal count %d is negative", r);
    const int p = c->degree, nk = c->npts + p + 1;
    if (!(x > c->knots[p] && x < c->knots[c->npts]))
        return cj_fail(CJ_ERR_RANGE, "knot %.17g to remove is not inside the domain (%.17g, %.17g)",
                       x, c->knots[p], c->knots[c->npts]);
    const int mult = cj_bsp_multiplicity(c->knots, nk, x);
    if (mult == 0) return cj_fail(CJ_ERR_ARGUMENT, "knot %.17g is not in the knot vector", x);
    if (r > mult) r = mult;
    const int rational = c->weights != NULL;
    cj_bsp_h cur, next, scratch;
    if ((st = cj_bsp_h_alloc(&cur, p, c->dim, rational, c->npts + 1))) return st;
    if ((st = cj_bsp_h_alloc(&next, p, c->dim, rational, c->npts + 1))) {
        cj_bsp_h_free(&cur);
        return st;
    }
    if ((st = cj_bsp_h_alloc(&scratch, p, c->dim, rational, c->npts + 1))) {
        cj_bsp_h_free(&cur);
        cj_bsp_h_free(&next);
        return st;
    }
    cj_bsp_h_from_view(&cur, c);
    double total = 0.0;
    int done = 0;
    while (done < r) {
        double e;
        if (cj_bsp_remove_once(&cur, x, &next, &scratch, &e) != 0) break;
        if (!(total + e <= tol)) break;
        total += e;
        ++done;
        cj_bsp_h t = cur;
        cur = next;
        next = t;
    }
    if (done > 0) {
        cj_bsp_h_to_view(&cur, out_pts, out_w, out_knots);
    } else { /* the input as it was, bit for bit (no round trip through w d / w) */
        memcpy(out_pts, c->pts, sizeof(double) * (size_t)c->npts * (size_t)c->dim);
        if (out_w) memcpy(out_w, c->weights, sizeof(double) * (size_t)c->npts);
        memcpy(out_knots, c->knots, sizeof(double) * (size_t)nk);
    }
    cj_bsp_h_free(&cur);
    cj_bsp_h_free(&next);
    cj_bsp_h_free(&scratch);
    *removed = done;
    if (error) *error = total;
    return CJ_OK;
}

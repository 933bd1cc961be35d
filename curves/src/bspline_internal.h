/* Private: shared pieces of the B-spline modules (local homogeneous points, de Boor kernels). */
#ifndef CASTELJAU_BSPLINE_INTERNAL_H
#define CASTELJAU_BSPLINE_INTERNAL_H

#include "casteljau/bspline.h"

/* Homogeneous dimension: dim for a polynomial B-spline, dim+1 for a NURBS. */
#define CJ_BSP_MAX_HDIM CJ_MAX_DIM
/* Work space of one span: p+1 homogeneous points. */
#define CJ_BSP_LOCAL ((CJ_BSPLINE_MAX_DEGREE + 1) * CJ_BSP_MAX_HDIM)

static inline int cj_bsp_hdim(const cj_bspline *c) {
    return c->dim + (c->weights != NULL);
}

/* Homogeneous point i, (w d, w) for a NURBS, d for a polynomial B-spline, into h[hdim]. */
static inline void cj_bsp_hpoint(const cj_bspline *c, int i, double *h) {
    const int d = c->dim;
    const double *p = c->pts + (size_t)i * (size_t)d;
    if (c->weights) {
        const double w = c->weights[i];
        for (int k = 0; k < d; ++k) h[k] = w * p[k];
        h[d] = w;
    } else {
        for (int k = 0; k < d; ++k) h[k] = p[k];
    }
}

/* Copies the q+1 homogeneous points d_{s-q}..d_s of span s into loc[(q+1)*hd]. */
void cj_bsp_local(const cj_bspline *c, int span, double *loc);

/* de Boor of degree q on span s (knots t): loc holds the points of indices s-q..s (hd
 * coordinates each) and is overwritten; the value ends in loc[q*hd..]. xs (may be NULL: all
 * levels at t) gives the argument of level r = 1..q in xs[r-1] (blossom). */
void cj_bsp_deboor(const double *knots, int q, int span, int hd, double *loc, double t,
                   const double *xs);

/* Span index of t, which must lie in the domain (already checked). */
int cj_bsp_span(const cj_bspline *c, double t);

/* One de Boor pyramid of degree p on span s at t over loc[(p+1)*hd] (overwritten), read off at
 * level p-j for each order j <= jtop: the remaining j+1 points are the de Boor points of the
 * degree-j spline x -> B(t^(p-j), x^j) (B the blossom), whose j-th derivative (j levels of
 * differences (j-l+1)(d_i - d_{i-1}) / (t_{i+j+1-l} - t_i)) times C(p, j) is c^(j)(t); into
 * out[j*hd + k]. sums = 1 runs the same recurrences on magnitudes (sums instead of
 * differences): the bound's M; sums = 2 adds 4 eta to every sum (the subnormal slack). */
void cj_bsp_pyramid(const double *knots, int p, int s, int hd, double *loc, double t, int jtop,
                    int sums, double *out);

/* Homogeneous derivatives 0..kmax of span s at t into h[(kmax+1)*hd], as
 * cj_bspline_eval_derivs computes them (bspline_eval.c). Returns the first order that
 * overflowed, or -1. */
int cj_bsp_homogeneous_derivs(const cj_bspline *c, int s, double t, int kmax, double *h);

/* The arguments of cj_bspline_eval_derivs and cj_bspline_derivs_error_bound (bspline_eval.c): a
 * valid curve, t in its domain, 0 <= kmax <= CJ_BSPLINE_MAX_DERIV; the error names the fault. */
cj_status cj_bsp_check_derivs(const cj_bspline *c, double t, int kmax);

/* The rounding bound of cj_bsp_homogeneous_derivs per order and homogeneous coordinate into
 * out[(kmax+1)*hd]: gamma(6p - j + 2 + extra) M_j inflated, plus the subnormal slack (extra:
 * roundings more on the point coordinates, 1 for the products w d of a NURBS). */
void cj_bsp_pyramid_bound(const cj_bspline *c, int s, double t, int kmax, int extra, double *out);

/* cj_bsp_pyramid_bound on given local points loc[(p+1)*hd] of span s (knots: the whole vector),
 * extra roundings on coordinates k < dim: for callers whose points are not a cj_bspline view
 * (the rows of a surface). */
void cj_bsp_local_pyramid_bound(const double *knots, int p, int s, int hd, int dim,
                                const double *loc, double t, int kmax, int extra, double *out);

/* Multiplicity of the value x in the knot vector. */
int cj_bsp_multiplicity(const double *knots, int nknots, double x);

/* Parameter check: finite and in the domain, else CJ_ERR_NONFINITE / CJ_ERR_RANGE naming what. */
cj_status cj_bsp_check_param(const cj_bspline *c, double t, const char *what);

/* Writes homogeneous points h[npts*hd] back to a view's layout: pts (and weights for a NURBS,
 * hd = dim+1: d = A/w). */
void cj_bsp_from_homogeneous(const double *h, int npts, int dim, int rational, double *pts,
                             double *w);

/* A curve as plain homogeneous arrays, for the algorithms that rebuild it (insertion, removal,
 * elevation). Owned by whoever filled it. */
typedef struct cj_bsp_h {
    int p, dim, rational, n1; /* degree, dimension, weights present, number of points */
    double *h;                /* n1 * (dim + rational) homogeneous coordinates */
    double *u;                /* n1 + p + 1 knots */
} cj_bsp_h;

/* Allocates room for cap points and cap + p + 1 knots (n1 = 0); CJ_ERR_NOMEM on failure. */
cj_status cj_bsp_h_alloc(cj_bsp_h *a, int p, int dim, int rational, int cap);
void cj_bsp_h_free(cj_bsp_h *a);
/* Fills a from a validated view (a must have room for c->npts points). */
void cj_bsp_h_from_view(cj_bsp_h *a, const cj_bspline *c);
/* Writes a to caller buffers (pts, weights when rational, knots). */
void cj_bsp_h_to_view(const cj_bsp_h *a, double *pts, double *w, double *knots);

/* One Boehm insertion of x (in the domain; multiplicity after it <= p is the caller's check)
 * from src into dst (room for src->n1 + 1 points). */
void cj_bsp_insert_once(const cj_bsp_h *src, double x, cj_bsp_h *dst);

/* One removal of the interior knot x (present) from src into dst (room for src->n1 points);
 * *err gets the deviation bound documented at cj_bspline_remove_knot. scratch needs room for
 * src->n1 + 1 points. Returns 0, or -1 when no candidate exists (non-finite points, weight
 * <= 0), with *err = INFINITY. */
int cj_bsp_remove_once(const cj_bsp_h *src, double x, cj_bsp_h *dst, cj_bsp_h *scratch,
                       double *err);

/* Interpolation at the given parameters ts[npts] (increasing, ts[0] = 0, ts[npts-1] = 1) with
 * optional end derivatives, any dimension (the surface code passes whole rows as one point):
 * out_pts[(npts + ends) * dim], out_knots[npts + ends + p + 1]. */
cj_status cj_bsp_interp_solve(const double *pts, int npts, int dim, int p, const double *ts,
                              const double *d_start, const double *d_end, double *out_pts,
                              double *out_knots);

/* Validates a knot vector of npts points of degree p (the rules of cj_bspline_check), naming
 * the vector `name` ("knot", "u knot") in messages. */
cj_status cj_bsp_check_knots(const double *knots, int npts, int p, const char *name);

/* Bézier decomposition of a (wide, any dimension) polynomial curve: every breakpoint of the
 * domain raised to multiplicity p by Boehm insertion, then the p+1 points of every non-empty
 * span. pieces receives npieces*(p+1)*hd doubles (room for cj_bsp_h pieces of the count of
 * non-empty spans), breaks npieces+1 values (may be NULL). Allocates its work space. */
cj_status cj_bsp_h_decompose(const cj_bsp_h *src, double *pieces, double *breaks, int *npieces);

#endif

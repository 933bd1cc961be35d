/* Tensor-product B-spline / NURBS surfaces: evaluation, knot insertion, Bézier patches and grid
 * interpolation, by treating whole rows (or columns) of homogeneous points as the points of one
 * wide curve. See casteljau/bspline_surface.h. */
#include "casteljau/bspline_surface.h"
#include "bspline_internal.h"
#include "bspline_surface_internal.h"
#include "error_internal.h"

#include <assert.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

cj_status cj_bspline_surface_check(const cj_bspline_surface *s) {
    assert(s != NULL);
    const int p = s->deg_u, q = s->deg_v;
    if (p < 0 || q < 0 || p > CJ_PATCH_MAX_DEGREE || q > CJ_PATCH_MAX_DEGREE)
        return cj_fail(CJ_ERR_DEGREE, "surface degrees (%d, %d) are outside 0..%d", p, q,
                       CJ_PATCH_MAX_DEGREE);
    if (s->npts_u < p + 1 || s->npts_v < q + 1)
        return cj_fail(CJ_ERR_EMPTY,
                       "%d x %d control points are too few for degrees (%d, %d) (need %d x %d)",
                       s->npts_u, s->npts_v, p, q, p + 1, q + 1);
    assert(s->pts != NULL && s->knots_u != NULL && s->knots_v != NULL);
    cj_status st = cj_bsp_check_knots(s->knots_u, s->npts_u, p, "u knot");
    if (!st) st = cj_bsp_check_knots(s->knots_v, s->npts_v, q, "v knot");
    if (st) return st;
    const int nu = s->npts_u;
    for (int j = 0; j < s->npts_v; ++j)
        for (int i = 0; i < nu; ++i) {
            const double *d = s->pts + 3 * ((size_t)j * (size_t)nu + (size_t)i);
            if (!isfinite(d[0]) || !isfinite(d[1]) || !isfinite(d[2]))
                return cj_fail(CJ_ERR_NONFINITE, "control point (%d, %d) is not finite", i, j);
            if (s->weights) {
                const double w = s->weights[(size_t)j * (size_t)nu + (size_t)i];
                if (!isfinite(w))
                    return cj_fail(CJ_ERR_NONFINITE, "weight (%d, %d) is not finite", i, j);
                if (!(w > 0.0))
                    return cj_fail(CJ_ERR_ARGUMENT,
                                   "weight (%d, %d) is %.17g; weights must be positive", i, j, w);
            }
        }
    return CJ_OK;
}

/* Homogeneous point (i, j) into h[hd]. */
static void hpoint(const cj_bspline_surface *s, int i, int j, double *h) {
    const size_t k = (size_t)j * (size_t)s->npts_u + (size_t)i;
    const double *d = s->pts + 3 * k;
    const double w = s->weights ? s->weights[k] : 1.0;
    for (int c = 0; c < 3; ++c) h[c] = s->weights ? w * d[c] : d[c];
    if (s->weights) h[3] = w;
}

/* A curve view used only for its knots (span search, parameter check). */
static cj_bspline knot_view(const double *knots, int npts, int p) {
    return cj_bspline_view(p, 1, npts, NULL, NULL, knots);
}

cj_status cj_bspline_surface_eval(const cj_bspline_surface *s, double u, double v, double *out) {
    assert(out != NULL);
    cj_status st = cj_bspline_surface_check(s);
    if (st) return st;
    const cj_bspline cu = knot_view(s->knots_u, s->npts_u, s->deg_u);
    const cj_bspline cv = knot_view(s->knots_v, s->npts_v, s->deg_v);
    if ((st = cj_bsp_check_param(&cu, u, "parameter u"))) return st;
    if ((st = cj_bsp_check_param(&cv, v, "parameter v"))) return st;
    const int p = s->deg_u, q = s->deg_v, hd = s->weights ? 4 : 3;
    const int su = cj_bsp_span(&cu, u), sv = cj_bsp_span(&cv, v);
    double row[(CJ_PATCH_MAX_DEGREE + 1) * 4], col[(CJ_PATCH_MAX_DEGREE + 1) * 4];
    for (int jj = 0; jj <= q; ++jj) {
        for (int ii = 0; ii <= p; ++ii) hpoint(s, su - p + ii, sv - q + jj, row + ii * hd);
        cj_bsp_deboor(s->knots_u, p, su, hd, row, u, NULL);
        memcpy(col + jj * hd, row + p * hd, sizeof(double) * (size_t)hd);
    }
    cj_bsp_deboor(s->knots_v, q, sv, hd, col, v, NULL);
    const double *r = col + q * hd;
    for (int c = 0; c < 3; ++c) out[c] = s->weights ? r[c] / r[3] : r[c];
    return CJ_OK;
}

cj_status cj_bspline_surface_error_bound(const cj_bspline_surface *s, double u, double v,
                                         double *bound) {
    assert(bound != NULL);
    cj_status st = cj_bspline_surface_check(s);
    if (st) return st;
    const cj_bspline cu = knot_view(s->knots_u, s->npts_u, s->deg_u);
    const cj_bspline cv = knot_view(s->knots_v, s->npts_v, s->deg_v);
    if ((st = cj_bsp_check_param(&cu, u, "parameter u"))) return st;
    if ((st = cj_bsp_check_param(&cv, v, "parameter v"))) return st;
    const int p = s->deg_u, q = s->deg_v, hd = s->weights ? 4 : 3;
    const int su = cj_bsp_span(&cu, u), sv = cj_bsp_span(&cv, v);
    double row[(CJ_PATCH_MAX_DEGREE + 1) * 4], mrow[(CJ_PATCH_MAX_DEGREE + 1) * 4];
    double col[(CJ_PATCH_MAX_DEGREE + 1) * 4], mcol[(CJ_PATCH_MAX_DEGREE + 1) * 4];
    double dmax[4] = {0, 0, 0, 0};
    for (int jj = 0; jj <= q; ++jj) {
        for (int ii = 0; ii <= p; ++ii) {
            hpoint(s, su - p + ii, sv - q + jj, row + ii * hd);
            for (int c = 0; c < hd; ++c) {
                mrow[ii * hd + c] = fabs(row[ii * hd + c]);
                dmax[c] = fmax(dmax[c], mrow[ii * hd + c]);
            }
        }
        cj_bsp_deboor(s->knots_u, p, su, hd, row, u, NULL);
        cj_bsp_deboor(s->knots_u, p, su, hd, mrow, u, NULL);
        memcpy(col + jj * hd, row + p * hd, sizeof(double) * (size_t)hd);
        memcpy(mcol + jj * hd, mrow + p * hd, sizeof(double) * (size_t)hd);
    }
    cj_bsp_deboor(s->knots_v, q, sv, hd, col, v, NULL);
    cj_bsp_deboor(s->knots_v, q, sv, hd, mcol, v, NULL);
    const double eta = 0x1p-1074, uu = CJ_UNIT_ROUNDOFF;
    const int n = 5 * (p + q) + (s->weights != NULL);
    const double g = cj_gamma(n), inflate = 1.0 + cj_gamma(n + 8);
    double e[4];
    for (int c = 0; c < hd; ++c) {
        e[c] = (g * mcol[q * hd + c] * inflate + 4.0 * (p + q + 2) * eta * (1.0 + dmax[c])) *
               (1.0 + 4 * uu);
        if (!isfinite(e[c]))
            return cj_fail(CJ_ERR_RANGE, "error bound of coordinate %d at (%.17g, %.17g) overflows",
                           c, u, v);
    }
    if (!s->weights) {
        memcpy(bound, e, 3 * sizeof(double));
        return CJ_OK;
    }
    const double w = col[q * hd + 3], ew = e[3];
    if (!(w > 2.0 * ew))
        return cj_fail(CJ_ERR_RANGE, "weight sum %g at (%.17g, %.17g) is within its error bound %g",
                       w, u, v, ew);
    for (int c = 0; c < 3; ++c) {
        const double qv = fabs(col[q * hd + c] / w) * (1.0 + 2 * uu);
        const double cmax = (qv + e[c] / w) / (1.0 - ew / w) * (1.0 + 4 * uu);
        bound[c] = (uu * qv + (e[c] + cmax * ew) / w + eta) * (1.0 + 8 * uu);
    }
    return CJ_OK;
}

int cj_bsurf_spans(const double *knots, int npts, int p) {
    int n = 0;
    for (int i = p; i < npts; ++i) n += knots[i] < knots[i + 1];
    return n;
}

cj_status cj_bspline_surface_patch_count(const cj_bspline_surface *s, int *count) {
    assert(count != NULL);
    cj_status st = cj_bspline_surface_check(s);
    if (st) return st;
    *count = cj_bsurf_spans(s->knots_u, s->npts_u, s->deg_u) *
             cj_bsurf_spans(s->knots_v, s->npts_v, s->deg_v);
    return CJ_OK;
}

/* The surface as a wide curve in direction dir: point i (along dir) holds the homogeneous
 * points of its whole row/column, in order of the other index. */
cj_status cj_bsurf_wide(const cj_bspline_surface *s, int dir, cj_bsp_h *w, int extra) {
    const int hd = s->weights ? 4 : 3;
    const int n = dir ? s->npts_v : s->npts_u, other = dir ? s->npts_u : s->npts_v;
    const int p = dir ? s->deg_v : s->deg_u;
    cj_status st = cj_bsp_h_alloc(w, p, hd * other, 0, n + extra);
    if (st) return st;
    w->n1 = n;
    for (int a = 0; a < n; ++a)
        for (int b = 0; b < other; ++b)
            hpoint(s, dir ? b : a, dir ? a : b,
                   w->h + ((size_t)a * (size_t)other + (size_t)b) * hd);
    memcpy(w->u, dir ? s->knots_v : s->knots_u, sizeof(double) * (size_t)(n + p + 1));
    return CJ_OK;
}

/* Writes wide homogeneous points back (point a along dir, b across) to the cj_patch-like
 * layout with n along dir. */
void cj_bsurf_unwide(const cj_bsp_h *w, int dir, int other, int rational, double *pts, double *wt) {
    const int hd = rational ? 4 : 3, n = w->n1, nu = dir ? other : n;
    for (int a = 0; a < n; ++a)
        for (int b = 0; b < other; ++b) {
            const double *h = w->h + ((size_t)a * (size_t)other + (size_t)b) * hd;
            const size_t k =
                dir ? (size_t)a * (size_t)nu + (size_t)b : (size_t)b * (size_t)nu + (size_t)a;
            for (int c = 0; c < 3; ++c) pts[3 * k + c] = rational ? h[c] / h[3] : h[c];
            if (rational) wt[k] = h[3];
        }
}

cj_status cj_bspline_surface_insert_knot(const cj_bspline_surface *s, int dir, double x, int r,
                                         double *out_pts, double *out_w, double *out_knots) {
    assert(out_pts != NULL && out_knots != NULL);
    cj_status st = cj_bspline_surface_check(s);
    if (st) return st;
    if (dir != 0 && dir != 1)
        return cj_fail(CJ_ERR_ARGUMENT, "direction %d is not 0 (u) or 1 (v)", dir);
    if ((s->weights != NULL) != (out_w != NULL))
        return cj_fail(CJ_ERR_ARGUMENT, "output weights %s for a %s surface",
                       out_w ? "given" : "missing", s->weights ? "NURBS" : "polynomial");
    const int n = dir ? s->npts_v : s->npts_u, p = dir ? s->deg_v : s->deg_u;
    const double *knots = dir ? s->knots_v : s->knots_u;
    const cj_bspline kv = knot_view(knots, n, p);
    if ((st = cj_bsp_check_param(&kv, x, dir ? "inserted v knot" : "inserted u knot"))) return st;
    if (r < 0) return cj_fail(CJ_ERR_ARGUMENT, "insertion count %d is negative", r);
    const int m = cj_bsp_multiplicity(knots, n + p + 1, x);
    if (m + r > p)
        return cj_fail(CJ_ERR_ARGUMENT,
                       "inserting %s knot %.17g %d times would raise its multiplicity to %d, above "
                       "the degree %d",
                       dir ? "v" : "u", x, r, m + r, p);
    cj_bsp_h a = {0}, b = {0};
    if ((st = cj_bsurf_wide(s, dir, &a, r)) || (st = cj_bsp_h_alloc(&b, p, a.dim, 0, n + r))) {
        cj_bsp_h_free(&a);
        return st;
    }
    for (int k = 0; k < r; ++k) {
        cj_bsp_insert_once(&a, x, &b);
        cj_bsp_h t = a;
        a = b;
        b = t;
    }
    cj_bsurf_unwide(&a, dir, dir ? s->npts_u : s->npts_v, s->weights != NULL, out_pts, out_w);
    memcpy(out_knots, a.u, sizeof(double) * (size_t)(n + r + p + 1));
    cj_bsp_h_free(&a);
    cj_bsp_h_free(&b);
    return CJ_OK;
}

cj_status cj_bspline_surface_to_patches(const cj_bspline_surface *s, double *pts, double *weights,
                                        double *ub, double *vb, int cap, int *count) {
    assert(pts != NULL);
    int total;
    cj_status st = cj_bspline_surface_patch_count(s, &total);
    if (st) return st;
    if ((s->weights != NULL) != (weights != NULL))
        return cj_fail(CJ_ERR_ARGUMENT, "patch weights %s for a %s surface",
                       weights ? "given" : "missing", s->weights ? "NURBS" : "polynomial");
    if (total > cap)
        return cj_fail(CJ_ERR_BUFFER, "the surface has %d Bézier patches, the buffer holds %d",
                       total, cap);
    const int p = s->deg_u, q = s->deg_v, nv = s->npts_v, hd = s->weights ? 4 : 3;
    const int su = cj_bsurf_spans(s->knots_u, s->npts_u, p), sv = cj_bsurf_spans(s->knots_v, nv, q);
    cj_bsp_h w = {0}, col = {0};
    double *upieces = NULL, *vpieces = NULL;
    if ((st = cj_bsurf_wide(s, 0, &w, 0))) return st;
    const size_t wide_u = (size_t)nv * (size_t)hd; /* coordinates of one wide u-point */
    upieces = malloc(sizeof(double) * (size_t)su * (size_t)(p + 1) * wide_u);
    if ((st = cj_bsp_h_alloc(&col, q, hd * (p + 1), 0, nv))) goto done;
    vpieces = malloc(sizeof(double) * (size_t)sv * (size_t)(q + 1) * (size_t)(hd * (p + 1)));
    if (!upieces || !vpieces) {
        st = cj_fail(CJ_ERR_NOMEM, "no memory for %d Bézier patches", total);
        goto done;
    }
    int nup = 0, nvp = 0;
    if ((st = cj_bsp_h_decompose(&w, upieces, ub, &nup))) goto done;
    for (int a = 0; a < nup; ++a) {
        /* Column j of u-piece a: its p+1 homogeneous points (i' = 0..p) side by side. */
        const double *piece = upieces + (size_t)a * (size_t)(p + 1) * wide_u;
        col.n1 = nv;
        for (int j = 0; j < nv; ++j)
            for (int i = 0; i <= p; ++i)
                memcpy(col.h + ((size_t)j * (size_t)(p + 1) + (size_t)i) * hd,
                       piece + (size_t)i * wide_u + (size_t)j * hd, sizeof(double) * (size_t)hd);
        memcpy(col.u, s->knots_v, sizeof(double) * (size_t)(nv + q + 1));
        if ((st = cj_bsp_h_decompose(&col, vpieces, a == 0 ? vb : NULL, &nvp))) goto done;
        for (int b = 0; b < nvp; ++b) {
            const size_t k = (size_t)b * (size_t)nup + (size_t)a;
            double *P = pts + 3 * (size_t)(p + 1) * (size_t)(q + 1) * k;
            double *W = weights ? weights + (size_t)(p + 1) * (size_t)(q + 1) * k : NULL;
            for (int jj = 0; jj <= q; ++jj)
                for (int i = 0; i <= p; ++i) {
                    const double *h =
                        vpieces +
                        (((size_t)b * (size_t)(q + 1) + (size_t)jj) * (size_t)(p + 1) + (size_t)i) *
                            hd;
                    const size_t o = (size_t)jj * (size_t)(p + 1) + (size_t)i;
                    for (int c = 0; c < 3; ++c) P[3 * o + c] = W ? h[c] / h[3] : h[c];
                    if (W) W[o] = h[3];
                }
        }
    }
    if (count) *count = nup * nvp;
done:
    cj_bsp_h_free(&w);
    cj_bsp_h_free(&col);
    free(upieces);
    free(vpieces);
    return st;
}

/* Parameters of one direction: the mean over the other direction's lines of cj_fit_params. */
static cj_status grid_params(const double *grid, int nu, int nv, int dir, cj_fit_param kind,
                             double *out) {
    const int n = dir ? nv : nu, lines = dir ? nu : nv;
    double *line = malloc(sizeof(double) * 3 * (size_t)n), *t = malloc(sizeof(double) * (size_t)n);
    cj_status st = (!line || !t) ? cj_fail(CJ_ERR_NOMEM, "no memory for grid parameters") : CJ_OK;
    for (int a = 0; a < n && !st; ++a) out[a] = 0.0;
    for (int l = 0; l < lines && !st; ++l) {
        for (int a = 0; a < n; ++a) {
            const size_t k =
                dir ? (size_t)a * (size_t)nu + (size_t)l : (size_t)l * (size_t)nu + (size_t)a;
            memcpy(line + 3 * a, grid + 3 * k, 3 * sizeof(double));
        }
        st = cj_fit_params(line, n, 3, kind, t);
        if (st) {
            char msg[400];
            snprintf(msg, sizeof msg, "%s", cj_last_error());
            st = cj_fail(st, "grid %s %d: %s", dir ? "column" : "row", l, msg);
        }
        for (int a = 0; a < n && !st; ++a) out[a] += t[a] / lines;
    }
    if (!st) {
        out[0] = 0.0;
        out[n - 1] = 1.0;
    }
    free(line);
    free(t);
    return st;
}

cj_status cj_bspline_surface_interpolate(const double *grid, int nu, int nv, int deg_u, int deg_v,
                                         cj_fit_param kind, double *out_pts, double *knots_u,
                                         double *knots_v, double *ubar, double *vbar) {
    assert(grid != NULL && out_pts != NULL && knots_u != NULL && knots_v != NULL);
    if (deg_u < 1 || deg_v < 1 || deg_u > CJ_PATCH_MAX_DEGREE || deg_v > CJ_PATCH_MAX_DEGREE)
        return cj_fail(CJ_ERR_DEGREE, "surface degrees (%d, %d) are outside 1..%d", deg_u, deg_v,
                       CJ_PATCH_MAX_DEGREE);
    if (nu < deg_u + 1 || nv < deg_v + 1)
        return cj_fail(CJ_ERR_EMPTY, "a %d x %d grid is too small for degrees (%d, %d)", nu, nv,
                       deg_u, deg_v);
    for (int j = 0; j < nv; ++j)
        for (int i = 0; i < nu; ++i)
            for (int c = 0; c < 3; ++c)
                if (!isfinite(grid[3 * ((size_t)j * (size_t)nu + (size_t)i) + c]))
                    return cj_fail(CJ_ERR_NONFINITE, "grid point (%d, %d) is not finite", i, j);
    double *tu = malloc(sizeof(double) * (size_t)nu), *tv = malloc(sizeof(double) * (size_t)nv);
    double *rows = malloc(sizeof(double) * 3 * (size_t)nu * (size_t)nv);
    double *tmp = malloc(sizeof(double) * 3 * (size_t)nu * (size_t)nv);
    cj_status st =
        (!tu || !tv || !rows || !tmp) ? cj_fail(CJ_ERR_NOMEM, "no memory for a grid") : CJ_OK;
    if (!st) st = grid_params(grid, nu, nv, 0, kind, tu);
    if (!st) st = grid_params(grid, nu, nv, 1, kind, tv);
    if (!st) {
        /* u direction: point i is the column i of the grid (all j), a wide point of 3 nv. */
        for (int i = 0; i < nu; ++i)
            for (int j = 0; j < nv; ++j)
                memcpy(rows + 3 * ((size_t)i * (size_t)nv + (size_t)j),
                       grid + 3 * ((size_t)j * (size_t)nu + (size_t)i), 3 * sizeof(double));
        st = cj_bsp_interp_solve(rows, nu, 3 * nv, deg_u, tu, NULL, NULL, tmp, knots_u);
    }
    if (!st) {
        /* v direction on the result: point j holds row j (all i), a wide point of 3 nu. */
        for (int j = 0; j < nv; ++j)
            for (int i = 0; i < nu; ++i)
                memcpy(rows + 3 * ((size_t)j * (size_t)nu + (size_t)i),
                       tmp + 3 * ((size_t)i * (size_t)nv + (size_t)j), 3 * sizeof(double));
        st = cj_bsp_interp_solve(rows, nv, 3 * nu, deg_v, tv, NULL, NULL, out_pts, knots_v);
    }
    if (!st && ubar) memcpy(ubar, tu, sizeof(double) * (size_t)nu);
    if (!st && vbar) memcpy(vbar, tv, sizeof(double) * (size_t)nv);
    free(tu);
    free(tv);
    free(rows);
    free(tmp);
    return st;
}

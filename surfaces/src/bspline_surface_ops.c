/* Tensor-product B-spline / NURBS surfaces: knot removal and degree elevation in u or v, on the
 * wide curve whose points are whole rows (columns) of homogeneous points, with the bound of the
 * surface's move. See casteljau/bspline_surface.h. */
#include "bspline_internal.h"
#include "bspline_surface_internal.h"
#include "casteljau/bspline_surface.h"
#include "error_internal.h"

#include <assert.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Distinct knot values strictly inside the domain and their multiplicities; returns the count. */
static int interior_breaks(const double *knots, int n, int p, double *vals, int *mult) {
    int nb = 0;
    for (int i = p + 1; i < n; ++i) {
        const double x = knots[i];
        if (!(x > knots[p] && x < knots[n])) continue;
        if (nb > 0 && vals[nb - 1] == x)
            ++mult[nb - 1];
        else {
            vals[nb] = x;
            mult[nb++] = 1;
        }
    }
    return nb;
}

/* Bound of the surface's move when the wide homogeneous net cur becomes next with every wide
 * point within e (Euclidean over the whole row/column): polynomial, e (convex combinations);
 * NURBS, from A/W − A'/W' = (A − A')/W − (A'/W')(W − W')/W with |A − A'|, |W − W'| <= e,
 * W >= min w of cur and |A'/W'| <= P = max |d'| of next: e (1 + P) / wmin. Infinite if a weight
 * of next is not positive. */
static double move_bound(const cj_bsp_h *cur, const cj_bsp_h *next, int rational, double e) {
    if (!rational) return e;
    const size_t ncur = (size_t)cur->n1 * (size_t)cur->dim / 4;
    const size_t nnext = (size_t)next->n1 * (size_t)next->dim / 4;
    double wmin = INFINITY, pmax = 0.0;
    for (size_t k = 0; k < ncur; ++k) wmin = fmin(wmin, cur->h[4 * k + 3]);
    for (size_t k = 0; k < nnext; ++k) {
        const double *h = next->h + 4 * k;
        if (!(h[3] > 0.0)) return INFINITY;
        const double x = h[0] / h[3], y = h[1] / h[3], z = h[2] / h[3];
        pmax = fmax(pmax, sqrt(x * x + y * y + z * z));
    }
    return e * (1.0 + pmax) * (1.0 + 8 * CJ_UNIT_ROUNDOFF) / wmin * (1.0 + 2 * CJ_UNIT_ROUNDOFF);
}

static cj_status check_dir_out(const cj_bspline_surface *s, int dir, const double *out_w) {
    if (dir != 0 && dir != 1)
        return cj_fail(CJ_ERR_ARGUMENT, "direction %d is not 0 (u) or 1 (v)", dir);
    if ((s->weights != NULL) != (out_w != NULL))
        return cj_fail(CJ_ERR_ARGUMENT, "output weights %s for a %s surface",
                       out_w ? "given" : "missing", s->weights ? "NURBS" : "polynomial");
    return CJ_OK;
}

cj_status cj_bspline_surface_remove_knot(const cj_bspline_surface *s, int dir, double x, int r,
                                         double tol, double *out_pts, double *out_w,
                                         double *out_knots, int *removed, double *error) {
    assert(out_pts != NULL && out_knots != NULL && removed != NULL);
    cj_status st = cj_bspline_surface_check(s);
    if (!st) st = check_dir_out(s, dir, out_w);
    if (st) return st;
    const char *name = dir ? "v" : "u";
    if (!isfinite(x)) return cj_fail(CJ_ERR_NONFINITE, "%s knot to remove is not finite", name);
    if (isnan(tol)) return cj_fail(CJ_ERR_NONFINITE, "removal tolerance is NaN");
    if (!(tol >= 0.0)) return cj_fail(CJ_ERR_ARGUMENT, "removal tolerance %g is negative", tol);
    if (r < 0) return cj_fail(CJ_ERR_ARGUMENT, "removal count %d is negative", r);
    const int n = dir ? s->npts_v : s->npts_u, p = dir ? s->deg_v : s->deg_u;
    const int other = dir ? s->npts_u : s->npts_v, rational = s->weights != NULL;
    const double *knots = dir ? s->knots_v : s->knots_u;
    if (!(x > knots[p] && x < knots[n]))
        return cj_fail(CJ_ERR_RANGE,
                       "%s knot %.17g to remove is not inside the domain (%.17g, %.17g)", name, x,
                       knots[p], knots[n]);
    const int mult = cj_bsp_multiplicity(knots, n + p + 1, x);
    if (mult == 0)
        return cj_fail(CJ_ERR_ARGUMENT, "%s knot %.17g is not in the knot vector", name, x);
    if (r > mult) r = mult;
    cj_bsp_h cur = {0}, next = {0}, scratch = {0};
    const int hd = rational ? 4 : 3;
    if ((st = cj_bsurf_wide(s, dir, &cur, 1)) ||
        (st = cj_bsp_h_alloc(&next, p, hd * other, 0, n + 1)) ||
        (st = cj_bsp_h_alloc(&scratch, p, hd * other, 0, n + 1)))
        goto done;
    double total = 0.0;
    int count = 0;
    while (count < r) {
        double e;
        if (cj_bsp_remove_once(&cur, x, &next, &scratch, &e) != 0) break;
        const double b = move_bound(&cur, &next, rational, e);
        if (!(total + b <= tol)) break;
        total += b;
        ++count;
        cj_bsp_h t = cur;
        cur = next;
        next = t;
    }
    if (count > 0) {
        cj_bsurf_unwide(&cur, dir, other, rational, out_pts, out_w);
        memcpy(out_knots, cur.u, sizeof(double) * (size_t)(n - count + p + 1));
    } else { /* the input bit for bit */
        memcpy(out_pts, s->pts, sizeof(double) * 3 * (size_t)n * (size_t)other);
        if (out_w) memcpy(out_w, s->weights, sizeof(double) * (size_t)n * (size_t)other);
        memcpy(out_knots, knots, sizeof(double) * (size_t)(n + p + 1));
    }
    *removed = count;
    if (error) *error = total;
done:
    cj_bsp_h_free(&cur);
    cj_bsp_h_free(&next);
    cj_bsp_h_free(&scratch);
    return st;
}

cj_status cj_bspline_surface_elevate_count(const cj_bspline_surface *s, int dir, int r,
                                           int *npts_out) {
    assert(npts_out != NULL);
    cj_status st = cj_bspline_surface_check(s);
    if (st) return st;
    if (dir != 0 && dir != 1)
        return cj_fail(CJ_ERR_ARGUMENT, "direction %d is not 0 (u) or 1 (v)", dir);
    const int n = dir ? s->npts_v : s->npts_u, p = dir ? s->deg_v : s->deg_u;
    const double *knots = dir ? s->knots_v : s->knots_u;
    if (r < 0) return cj_fail(CJ_ERR_ARGUMENT, "elevation count %d is negative", r);
    if (p == 0)
        return cj_fail(CJ_ERR_DEGREE, "%s degree 0 (piecewise constant) cannot be elevated",
                       dir ? "v" : "u");
    if (p + r > CJ_PATCH_MAX_DEGREE)
        return cj_fail(CJ_ERR_DEGREE, "elevated %s degree %d exceeds the limit of %d",
                       dir ? "v" : "u", p + r, CJ_PATCH_MAX_DEGREE);
    int total = p + r + 1;
    for (int i = p + 1; i < n; ++i) {
        const double x = knots[i];
        if (!(x > knots[p] && x < knots[n])) continue;
        const int m = cj_bsp_multiplicity(knots, n + p + 1, x);
        if (m > p)
            return cj_fail(CJ_ERR_ARGUMENT,
                           "%s knot %d (%.17g) of multiplicity %d = degree + 1 is a jump; "
                           "elevation needs a continuous surface",
                           dir ? "v" : "u", i, x, m);
        if (knots[i - 1] != x) total += m + r;
    }
    *npts_out = total;
    return CJ_OK;
}

cj_status cj_bspline_surface_elevate(const cj_bspline_surface *s, int dir, int r, double *out_pts,
                                     double *out_w, double *out_knots, double *error) {
    assert(out_pts != NULL && out_knots != NULL);
    int nout;
    cj_status st = cj_bspline_surface_elevate_count(s, dir, r, &nout);
    if (!st) st = check_dir_out(s, dir, out_w);
    if (st) return st;
    const int n = dir ? s->npts_v : s->npts_u, p = dir ? s->deg_v : s->deg_u, q = p + r;
    const int other = dir ? s->npts_u : s->npts_v, rational = s->weights != NULL;
    const int hd = rational ? 4 : 3, wd = hd * other;
    const double *knots = dir ? s->knots_v : s->knots_u;
    const int np = cj_bsurf_spans(knots, n, p), cap = np * q + 2;
    double *pieces = malloc(sizeof(double) * (size_t)np * (size_t)(p + 1) * (size_t)wd);
    double *breaks = malloc(sizeof(double) * ((size_t)np + 1));
    double *vals = malloc(sizeof(double) * (size_t)n);
    int *mult = malloc(sizeof(int) * (size_t)n);
    cj_bsp_h src = {0}, cur = {0}, next = {0}, scratch = {0};
    if (!pieces || !breaks || !vals || !mult) {
        st = cj_fail(CJ_ERR_NOMEM, "no memory to elevate a surface of %d x %d points", s->npts_u,
                     s->npts_v);
        goto done;
    }
    if ((st = cj_bsurf_wide(s, dir, &src, 0)) || (st = cj_bsp_h_alloc(&cur, q, wd, 0, cap)) ||
        (st = cj_bsp_h_alloc(&next, q, wd, 0, cap)) ||
        (st = cj_bsp_h_alloc(&scratch, q, wd, 0, cap)))
        goto done;
    int got;
    if ((st = cj_bsp_h_decompose(&src, pieces, breaks, &got))) goto done;
    assert(got == np);
    /* Elevate every row of every piece as a Bézier curve (exact in exact arithmetic), writing
     * the joined net: clamped, interior knots of multiplicity q. */
    double in[(CJ_PATCH_MAX_DEGREE + 1) * 4], el[(CJ_PATCH_MAX_DEGREE + 1) * 4];
    int o = 0;
    for (int j = 0; j < np; ++j) {
        const int last = j == np - 1 ? q : q - 1;
        const double *pc = pieces + (size_t)j * (size_t)(p + 1) * (size_t)wd;
        for (int b = 0; b < other; ++b) {
            for (int i = 0; i <= p; ++i)
                memcpy(in + i * hd, pc + (size_t)i * (size_t)wd + (size_t)b * (size_t)hd,
                       sizeof(double) * (size_t)hd);
            const cj_bezier piece = cj_bezier_view(p, hd, in);
            if ((st = cj_bezier_elevate(&piece, r, el))) goto done;
            for (int i = 0; i <= last; ++i)
                memcpy(cur.h + (size_t)(o + i) * (size_t)wd + (size_t)b * (size_t)hd, el + i * hd,
                       sizeof(double) * (size_t)hd);
        }
        o += last + 1;
    }
    cur.n1 = o;
    int k = 0;
    for (int i = 0; i <= q; ++i) cur.u[k++] = breaks[0];
    for (int j = 1; j < np; ++j)
        for (int i = 0; i < q; ++i) cur.u[k++] = breaks[j];
    for (int i = 0; i <= q; ++i) cur.u[k++] = breaks[np];
    /* Back to the original continuity: p − m copies of every interior break removed. */
    double total = 0.0;
    const int nb = interior_breaks(knots, n, p, vals, mult);
    for (int v = 0; v < nb; ++v)
        for (int c = 0; c < p - mult[v]; ++c) {
            double e;
            if (cj_bsp_remove_once(&cur, vals[v], &next, &scratch, &e) != 0) {
                st = cj_fail(CJ_ERR_RANGE, "elevation lost the surface removing %s knot %.17g",
                             dir ? "v" : "u", vals[v]);
                goto done;
            }
            total += move_bound(&cur, &next, rational, e);
            cj_bsp_h t = cur;
            cur = next;
            next = t;
        }
    assert(cur.n1 == nout);
    if (!isfinite(total)) {
        st = cj_fail(CJ_ERR_RANGE, "elevation of the surface in %s lost a positive weight",
                     dir ? "v" : "u");
        goto done;
    }
    cj_bsurf_unwide(&cur, dir, other, rational, out_pts, out_w);
    memcpy(out_knots, cur.u, sizeof(double) * (size_t)(nout + q + 1));
    if (error) *error = total;
done:
    free(pieces);
    free(breaks);
    free(vals);
    free(mult);
    cj_bsp_h_free(&src);
    cj_bsp_h_free(&cur);
    cj_bsp_h_free(&next);
    cj_bsp_h_free(&scratch);
    return st;
}

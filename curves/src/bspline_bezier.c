/* B-splines to Bézier pieces and back, degree elevation through the pieces, and the cubic
 * splines of catmull_rom.h as B-splines. See casteljau/bspline.h. */
#include "bspline_internal.h"
#include "error_internal.h"

#include <assert.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

static int count_pieces(const cj_bspline *c) {
    int np = 0;
    for (int s = c->degree; s < c->npts; ++s) np += c->knots[s] < c->knots[s + 1];
    return np;
}

cj_status cj_bspline_bezier_count(const cj_bspline *c, int *npieces) {
    assert(npieces != NULL);
    cj_status st = cj_bspline_check(c);
    if (st) return st;
    *npieces = count_pieces(c);
    return CJ_OK;
}

/* Homogeneous Bézier points of every piece into hb[np*(p+1)*hd] (end points shared bit for
 * bit), breaks into br[np+1] if not NULL. */
static void pieces_homogeneous(const cj_bspline *c, double *hb, double *br) {
    const int p = c->degree, hd = cj_bsp_hdim(c);
    double loc[CJ_BSP_LOCAL], xs[CJ_BSPLINE_MAX_DEGREE];
    int j = 0;
    for (int s = p; s < c->npts; ++s) {
        const double a = c->knots[s], b = c->knots[s + 1];
        if (!(a < b)) continue;
        double *piece = hb + (size_t)j * (size_t)((p + 1) * hd);
        /* A knot of multiplicity p+1 is a jump: the pieces do not share their end points. */
        const int continuous = s == p || cj_bsp_multiplicity(c->knots, c->npts + p + 1, a) <= p;
        for (int i = 0; i <= p; ++i) {
            if (i == 0 && j > 0 && continuous) { /* the previous piece's end, bit for bit */
                memcpy(piece, piece - hd, sizeof(double) * (size_t)hd);
                continue;
            }
            for (int r = 0; r < p; ++r) xs[r] = r < p - i ? a : b;
            cj_bsp_local(c, s, loc);
            cj_bsp_deboor(c->knots, p, s, hd, loc, a, xs);
            memcpy(piece + i * hd, loc + p * hd, sizeof(double) * (size_t)hd);
        }
        if (br) {
            br[j] = a;
            br[j + 1] = b;
        }
        ++j;
    }
}

cj_status cj_bspline_to_bezier(const cj_bspline *c, double *pts, double *w, double *breaks,
                               int cap_pieces, int *npieces) {
    assert(pts != NULL);
    cj_status st = cj_bspline_check(c);
    if (st) return st;
    if ((c->weights != NULL) != (w != NULL))
        return cj_fail(CJ_ERR_ARGUMENT, "piece weights %s for a %s", w ? "given" : "missing",
                       c->weights ? "NURBS" : "polynomial B-spline");
    const int np = count_pieces(c), p = c->degree, d = c->dim;
    if (np > cap_pieces)
        return cj_fail(CJ_ERR_BUFFER, "the curve has %d Bézier pieces, the buffer holds %d", np,
                       cap_pieces);
    if (!c->weights) {
        pieces_homogeneous(c, pts, breaks);
    } else {
        const int hd = d + 1;
        double *hb = malloc(sizeof(double) * (size_t)np * (size_t)((p + 1) * hd));
        if (!hb) return cj_fail(CJ_ERR_NOMEM, "no memory for %d rational Bézier pieces", np);
        pieces_homogeneous(c, hb, breaks);
        cj_bsp_from_homogeneous(hb, np * (p + 1), d, 1, pts, w);
        free(hb);
    }
    if (npieces) *npieces = np;
    return CJ_OK;
}

cj_status cj_bspline_from_bezier(const double *pts, const double *w, const double *breaks,
                                 int npieces, int degree, int dim, double join_tol, double *out_pts,
                                 double *out_w, double *out_knots) {
    assert(pts != NULL && breaks != NULL && out_pts != NULL && out_knots != NULL);
    const int p = degree;
    if (p < 1 || p > CJ_BSPLINE_MAX_DEGREE)
        return cj_fail(CJ_ERR_DEGREE, "Bézier degree %d is outside 1..%d", p,
                       CJ_BSPLINE_MAX_DEGREE);
    const int maxdim = w ? CJ_MAX_DIM - 1 : CJ_MAX_DIM;
    if (dim < 1 || dim > maxdim)
        return cj_fail(CJ_ERR_DIMENSION, "dimension %d is outside 1..%d", dim, maxdim);
    if (npieces < 1) return cj_fail(CJ_ERR_EMPTY, "no Bézier pieces");
    if ((w != NULL) != (out_w != NULL))
        return cj_fail(CJ_ERR_ARGUMENT, "output weights %s for %s pieces",
                       out_w ? "given" : "missing", w ? "rational" : "polynomial");
    if (isnan(join_tol) || !(join_tol >= 0.0))
        return cj_fail(CJ_ERR_ARGUMENT, "join tolerance %g is not >= 0", join_tol);
    const size_t per = (size_t)(p + 1);
    cj_status st = cj_check_points(pts, (size_t)npieces * per, dim, "Bézier control point");
    if (st) return st;
    if ((st = cj_check_finite(breaks, (size_t)npieces + 1, "break"))) return st;
    if (w) {
        if ((st = cj_check_finite(w, (size_t)npieces * per, "weight"))) return st;
        for (size_t i = 0; i < (size_t)npieces * per; ++i)
            if (!(w[i] > 0.0))
                return cj_fail(CJ_ERR_ARGUMENT, "weight %zu is %.17g; weights must be positive", i,
                               w[i]);
    }
    for (int j = 0; j < npieces; ++j)
        if (!(breaks[j] < breaks[j + 1]))
            return cj_fail(CJ_ERR_ARGUMENT, "breaks %d and %d (%.17g, %.17g) do not increase", j,
                           j + 1, breaks[j], breaks[j + 1]);
    for (int j = 0; j + 1 < npieces; ++j) {
        const double *e = pts + ((size_t)j * per + (size_t)p) * (size_t)dim;
        const double *s = pts + (size_t)(j + 1) * per * (size_t)dim;
        for (int k = 0; k < dim; ++k)
            if (!(fabs(e[k] - s[k]) <= join_tol))
                return cj_fail(CJ_ERR_ARGUMENT,
                               "pieces %d and %d do not meet: coordinate %d differs by %g (join "
                               "tolerance %g)",
                               j, j + 1, k, fabs(e[k] - s[k]), join_tol);
        if (w && !(fabs(w[(size_t)j * per + (size_t)p] - w[(size_t)(j + 1) * per]) <= join_tol))
            return cj_fail(CJ_ERR_ARGUMENT, "pieces %d and %d have different weights at the joint",
                           j, j + 1);
    }
    int o = 0;
    for (int j = 0; j < npieces; ++j) {
        const int last = j == npieces - 1 ? p : p - 1;
        for (int i = 0; i <= last; ++i, ++o) {
            memcpy(out_pts + (size_t)o * (size_t)dim,
                   pts + ((size_t)j * per + (size_t)i) * (size_t)dim, sizeof(double) * (size_t)dim);
            if (w) out_w[o] = w[(size_t)j * per + (size_t)i];
        }
    }
    int k = 0;
    for (int i = 0; i <= p; ++i) out_knots[k++] = breaks[0];
    for (int j = 1; j < npieces; ++j)
        for (int i = 0; i < p; ++i) out_knots[k++] = breaks[j];
    for (int i = 0; i <= p; ++i) out_knots[k++] = breaks[npieces];
    return CJ_OK;
}

/* Distinct interior knot values strictly inside the domain with their multiplicities. */
static int interior_knots(const cj_bspline *c, double *vals, int *mult) {
    const int p = c->degree;
    const double a = c->knots[p], b = c->knots[c->npts];
    int nv = 0;
    for (int i = p + 1; i < c->npts; ++i) {
        const double x = c->knots[i];
        if (!(x > a && x < b)) continue;
        if (nv > 0 && vals[nv - 1] == x)
            ++mult[nv - 1];
        else {
            vals[nv] = x;
            mult[nv++] = 1;
        }
    }
    return nv;
}

cj_status cj_bspline_elevate_count(const cj_bspline *c, int r, int *npts_out) {
    assert(npts_out != NULL);
    cj_status st = cj_bspline_check(c);
    if (st) return st;
    if (r < 0) return cj_fail(CJ_ERR_ARGUMENT, "elevation %d is negative", r);
    if (c->degree + r > CJ_BSPLINE_MAX_DEGREE)
        return cj_fail(CJ_ERR_DEGREE, "elevated degree %d exceeds the limit of %d", c->degree + r,
                       CJ_BSPLINE_MAX_DEGREE);
    int n = c->degree + r + 1;
    const int p = c->degree;
    const double a = c->knots[p], b = c->knots[c->npts];
    for (int i = p + 1; i < c->npts; ++i) {
        const double x = c->knots[i];
        if (x > a && x < b) {
            ++n;
            if (x != c->knots[i - 1]) n += r;
        }
    }
    *npts_out = n;
    return CJ_OK;
}

cj_status cj_bspline_elevate(const cj_bspline *c, int r, double *out_pts, double *out_w,
                             double *out_knots, double *error) {
    assert(out_pts != NULL && out_knots != NULL);
    int nout;
    cj_status st = cj_bspline_elevate_count(c, r, &nout);
    if (st) return st;
    if ((c->weights != NULL) != (out_w != NULL))
        return cj_fail(CJ_ERR_ARGUMENT, "output weights %s for a %s", out_w ? "given" : "missing",
                       c->weights ? "NURBS" : "polynomial B-spline");
    const int p = c->degree, q = p + r, d = c->dim, rational = c->weights != NULL;
    const int hd = d + rational, np = count_pieces(c);
    if (p == 0) return cj_fail(CJ_ERR_DEGREE, "degree 0 (piecewise constant) cannot be elevated");
    for (int i = p + 1; i < c->npts; ++i)
        if (c->knots[i] > c->knots[p] && c->knots[i] < c->knots[c->npts] &&
            cj_bsp_multiplicity(c->knots, c->npts + p + 1, c->knots[i]) > p)
            return cj_fail(CJ_ERR_ARGUMENT,
                           "knot %d (%.17g) of multiplicity %d = degree + 1 is a jump; elevation "
                           "needs a continuous curve",
                           i, c->knots[i], p + 1);
    double *hb = malloc(sizeof(double) * (size_t)np * (size_t)((p + 1) * hd));
    double *eb = malloc(sizeof(double) * (size_t)np * (size_t)((q + 1) * hd));
    double *br = malloc(sizeof(double) * ((size_t)np + 1));
    double *vals = malloc(sizeof(double) * (size_t)c->npts);
    int *mult = malloc(sizeof(int) * (size_t)c->npts);
    cj_bsp_h cur = {0}, next = {0}, scratch = {0};
    const int cap = np * q + 2;
    if (!hb || !eb || !br || !vals || !mult || cj_bsp_h_alloc(&cur, q, d, rational, cap) ||
        cj_bsp_h_alloc(&next, q, d, rational, cap) ||
        cj_bsp_h_alloc(&scratch, q, d, rational, cap)) {
        st = cj_fail(CJ_ERR_NOMEM, "no memory to elevate a B-spline of %d points", c->npts);
        goto done;
    }
    pieces_homogeneous(c, hb, br);
    for (int j = 0; j < np; ++j) {
        cj_bezier piece = cj_bezier_view(p, hd, hb + (size_t)j * (size_t)((p + 1) * hd));
        if ((st = cj_bezier_elevate(&piece, r, eb + (size_t)j * (size_t)((q + 1) * hd)))) goto done;
    }
    /* Join the elevated pieces: clamped, interior knots of multiplicity q. */
    {
        int o = 0;
        for (int j = 0; j < np; ++j) {
            const int last = j == np - 1 ? q : q - 1;
            for (int i = 0; i <= last; ++i, ++o)
                memcpy(cur.h + (size_t)o * (size_t)hd,
                       eb + ((size_t)j * (size_t)(q + 1) + (size_t)i) * (size_t)hd,
                       sizeof(double) * (size_t)hd);
        }
        cur.n1 = o;
        int k = 0;
        for (int i = 0; i <= q; ++i) cur.u[k++] = br[0];
        for (int j = 1; j < np; ++j)
            for (int i = 0; i < q; ++i) cur.u[k++] = br[j];
        for (int i = 0; i <= q; ++i) cur.u[k++] = br[np];
    }
    /* Back to the original continuity: remove p - m copies of each interior knot. */
    double total = 0.0;
    const int nv = interior_knots(c, vals, mult);
    for (int v = 0; v < nv; ++v)
        for (int k = 0; k < p - mult[v]; ++k) {
            double e;
            if (cj_bsp_remove_once(&cur, vals[v], &next, &scratch, &e) != 0) {
                st = cj_fail(CJ_ERR_RANGE, "elevation lost the curve removing knot %.17g", vals[v]);
                goto done;
            }
            total += e;
            cj_bsp_h t = cur;
            cur = next;
            next = t;
        }
    assert(cur.n1 == nout);
    cj_bsp_h_to_view(&cur, out_pts, out_w, out_knots);
    if (error) *error = total;
done:
    free(hb);
    free(eb);
    free(br);
    free(vals);
    free(mult);
    cj_bsp_h_free(&cur);
    cj_bsp_h_free(&next);
    cj_bsp_h_free(&scratch);
    return st;
}

cj_status cj_bspline_from_spline(const double *pts, size_t npts, int dim,
                                 const cj_spline_options *opts, double *out_pts, double *out_knots,
                                 int *npts_out, double *error) {
    assert(pts != NULL && out_pts != NULL && out_knots != NULL && npts_out != NULL);
    const int closed = opts ? opts->closed : 0;
    const size_t nsegs = cj_spline_segment_count(npts, closed);
    if (nsegs == 0)
        return cj_fail(CJ_ERR_EMPTY, "%zu points are too few for a%s spline", npts,
                       closed ? " closed" : "n open");
    if (dim < 1 || dim > CJ_MAX_DIM)
        return cj_fail(CJ_ERR_DIMENSION, "dimension %d is outside 1..%d", dim, CJ_MAX_DIM);
    if (nsegs > 100000000) return cj_fail(CJ_ERR_RANGE, "%zu spline segments are too many", nsegs);
    const int ns = (int)nsegs;
    double *segs = malloc(sizeof(double) * nsegs * 4 * (size_t)dim);
    double *knots = malloc(sizeof(double) * (nsegs + 1));
    cj_bsp_h cur = {0}, next = {0}, scratch = {0};
    cj_status st = CJ_OK;
    if (!segs || !knots || cj_bsp_h_alloc(&cur, 3, dim, 0, 3 * ns + 2) ||
        cj_bsp_h_alloc(&next, 3, dim, 0, 3 * ns + 2) ||
        cj_bsp_h_alloc(&scratch, 3, dim, 0, 3 * ns + 2)) {
        st = cj_fail(CJ_ERR_NOMEM, "no memory for a spline of %zu segments", nsegs);
        goto done;
    }
    if ((st = cj_catmull_rom(pts, npts, dim, opts, segs, nsegs, NULL, knots))) goto done;
    if ((st = cj_bspline_from_bezier(segs, NULL, knots, ns, 3, dim, 0.0, cur.h, NULL, cur.u)))
        goto done;
    cur.n1 = 3 * ns + 1;
    /* One copy of each interior knot goes where the pieces join C^1: the bound of that removal
     * is then rounding noise, far below 2^-30 of the polygon's size (a kink is far above). */
    double scale = 0.0;
    for (int i = 0; i < cur.n1 * dim; ++i) scale = fmax(scale, fabs(cur.h[i]));
    const double tol = ldexp(scale, -30);
    double total = 0.0;
    for (int j = 1; j < ns; ++j) {
        double e;
        if (cj_bsp_remove_once(&cur, knots[j], &next, &scratch, &e) != 0 || !(e <= tol)) continue;
        total += e;
        cj_bsp_h t = cur;
        cur = next;
        next = t;
    }
    memcpy(out_pts, cur.h, sizeof(double) * (size_t)cur.n1 * (size_t)dim);
    memcpy(out_knots, cur.u, sizeof(double) * (size_t)(cur.n1 + 4));
    *npts_out = cur.n1;
    if (error) *error = total;
done:
    free(segs);
    free(knots);
    cj_bsp_h_free(&cur);
    cj_bsp_h_free(&next);
    cj_bsp_h_free(&scratch);
    return st;
}

cj_status cj_bsp_h_decompose(const cj_bsp_h *src, double *pieces, double *breaks, int *npieces) {
    const int p = src->p, hd = src->dim + src->rational, n1 = src->n1;
    const double a = src->u[p], b = src->u[n1];
    /* Insertions needed: every distinct breakpoint in [a, b] up to multiplicity p. */
    int extra = 0;
    for (int i = p; i <= n1; ++i)
        if (i == p || src->u[i] != src->u[i - 1]) {
            const int m = cj_bsp_multiplicity(src->u, n1 + p + 1, src->u[i]);
            if (m < p) extra += p - m;
        }
    cj_bsp_h x = {0}, y = {0};
    cj_status st = cj_bsp_h_alloc(&x, p, src->dim, src->rational, n1 + extra);
    if (!st) st = cj_bsp_h_alloc(&y, p, src->dim, src->rational, n1 + extra);
    if (st) {
        cj_bsp_h_free(&x);
        return st;
    }
    x.n1 = n1;
    memcpy(x.h, src->h, sizeof(double) * (size_t)n1 * (size_t)hd);
    memcpy(x.u, src->u, sizeof(double) * (size_t)(n1 + p + 1));
    for (int i = p; i <= n1; ++i) {
        if (i != p && src->u[i] == src->u[i - 1]) continue;
        const double v = src->u[i];
        if (v < a || v > b) continue;
        for (int m = cj_bsp_multiplicity(x.u, x.n1 + p + 1, v); m < p; ++m) {
            cj_bsp_insert_once(&x, v, &y);
            cj_bsp_h t = x;
            x = y;
            y = t;
        }
    }
    int np = 0;
    for (int s = p; s < x.n1; ++s) {
        if (!(x.u[s] < x.u[s + 1])) continue;
        memcpy(pieces + (size_t)np * (size_t)((p + 1) * hd), x.h + (size_t)(s - p) * (size_t)hd,
               sizeof(double) * (size_t)((p + 1) * hd));
        if (breaks) {
            breaks[np] = x.u[s];
            breaks[np + 1] = x.u[s + 1];
        }
        ++np;
    }
    *npieces = np;
    cj_bsp_h_free(&x);
    cj_bsp_h_free(&y);
    return CJ_OK;
}

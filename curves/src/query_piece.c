/* Curve contexts for the certified queries: validation, interval evaluation of a point and its
 * derivative over a parameter interval, and pieces by exact halving with a tracked error. */
#include "query_internal.h"

#include "error_internal.h"

#include <assert.h>
#include <float.h>

/* Forced inlining: the hot parts (point and derivative evaluations, halving, clipping) are
 * instantiated for cubics and quadratics with the degree as a constant, so that their loops
 * unroll; the general degree runs the same code with a variable bound. */
#define CJ_UNROLLED static inline __attribute__((always_inline))

/* The context for degree n (checked by the caller): a constant for the usual degrees. */
CJ_UNROLLED cj_status init_first_n(cj_qctx *q, const cj_bezier2 *c, int n, const char *what) {
    assert(c->pts);
    double scale = 0.0;
#pragma GCC unroll 8
    for (int i = 0; i <= n; ++i)
        for (int k = 0; k < 2; ++k) {
            double v = c->pts[2 * i + k];
            if (!isfinite(v))
                return cj_fail(CJ_ERR_NONFINITE, "%s: control point %d, coordinate %d is %s", what,
                               i, k, isnan(v) ? "NaN" : "infinite");
            scale = cj_fmax(scale, fabs(v));
        }
    int rational = 0;
    if (c->weights)
        for (int i = 0; i <= n; ++i) {
            double w = c->weights[i];
            if (!isfinite(w))
                return cj_fail(CJ_ERR_NONFINITE, "%s: weight %d is %s", what, i,
                               isnan(w) ? "NaN" : "infinite");
            if (!(w > 0.0))
                return cj_fail(CJ_ERR_ARGUMENT, "%s: weight %d is %g, must be > 0", what, i, w);
            if (w != 1.0) rational = 1;
        }
    if (scale > 0x1p500)
        return cj_fail(CJ_ERR_RANGE,
                       "%s: coordinates up to %g exceed the range the queries "
                       "certify (2^500 = 3.3e150)",
                       what, scale);
    int distinct = 0;
#pragma GCC unroll 8
    for (int i = 1; i <= n && !distinct; ++i)
        distinct = c->pts[2 * i] != c->pts[0] || c->pts[2 * i + 1] != c->pts[1];
    if (!distinct)
        return cj_fail(CJ_ERR_DEGENERATE,
                       "%s: all %d control points coincide (a point, not a "
                       "curve)",
                       what, n + 1);
    q->n = n;
    q->rational = rational;
    q->scale = scale;
    if (!rational) {
        /* exact points and weights 1: the hodograph n (P_{i+1} - P_i) is one rounded difference
         * (stepped outwards) times the exact n (stepped outwards again) */
        double dn = (double)n;
        q->hmag[0] = q->hmag[1] = 0.0;
        q->hmag[2] = 1.0;
        q->dmax = 0.0;
#pragma GCC unroll 8
        for (int i = 0; i <= n; ++i) {
            for (int k = 0; k < 2; ++k) {
                double v = c->pts[2 * i + k];
                q->h[i][k] = cj_iv(v);
                q->hm[i][k] = v;
                q->hmag[k] = cj_fmax(q->hmag[k], fabs(v));
                if (i < n) {
                    double d = c->pts[2 * i + 2 + k] - v;
                    q->dh[i][k] = cj_iv2(cj_down(dn * cj_down(d)), cj_up(dn * cj_up(d)));
                    q->dm[i][k] = dn * d;
                    q->dmax = cj_fmax(q->dmax, fabs(q->dm[i][k]));
                }
            }
            q->h[i][2] = cj_iv(1.0);
            if (i < n) q->dh[i][2] = cj_iv(0.0);
        }
        /* the starting points of the plain evaluations: the control points themselves (exact)
         * and n d for the hodograph (d = P_{i+1} - P_i rounded): off from the exact
         * n (P_{i+1} - P_i) by at most 2u |n d| plus a subnormal rounding, covered by drad */
        q->plain = 1;
        q->hrad = 0.0;
        q->hmax = cj_fmax(q->hmag[0], q->hmag[1]);
        q->drad = cj_up(q->dmax * 0x1p-51 + 0x1p-1070);
        /* c'' = sum (n-1)(dh_{i+1} - dh_i) B_i: bounded by its largest control point */
        for (int k = 0; k < 2; ++k) {
            double mag = 0.0;
#pragma GCC unroll 8
            for (int i = 0; i + 1 < n; ++i)
                mag = cj_fmax(mag, cj_imag(cj_isub(q->dh[i + 1][k], q->dh[i][k])));
            q->d2mag[k] = cj_up(mag * (double)(n > 1 ? n - 1 : 0));
        }
        return CJ_OK;
    }
    q->d2mag[0] = q->d2mag[1] = INFINITY;
    q->plain = 0;
    for (int i = 0; i <= n; ++i) {
        cj_ivl w = cj_iv(rational ? c->weights[i] : 1.0);
        for (int k = 0; k < 2; ++k)
            q->h[i][k] = rational ? cj_imul(cj_iv(c->pts[2 * i + k]), w) : cj_iv(c->pts[2 * i + k]);
        q->h[i][2] = w;
    }
    for (int k = 0; k < 3; ++k) {
        q->hmag[k] = 0.0;
        for (int i = 0; i <= n; ++i) q->hmag[k] = cj_fmax(q->hmag[k], cj_imag(q->h[i][k]));
    }
    for (int i = 0; i < n; ++i)
        for (int k = 0; k < 3; ++k)
            q->dh[i][k] = cj_imul(cj_iv((double)n), cj_isub(q->h[i + 1][k], q->h[i][k]));
    return CJ_OK;
}

cj_status cj_qctx_init_first(cj_qctx *q, const cj_bezier2 *c, const char *what) {
    assert(q && c && what);
    if (c->degree < 0 || c->degree > CJ_QUERY_MAX_DEGREE)
        return cj_fail(CJ_ERR_DEGREE, "%s: degree %d outside 0..%d", what, c->degree,
                       CJ_QUERY_MAX_DEGREE);
    if (c->degree == 3) return init_first_n(q, c, 3, what);
    if (c->degree == 2) return init_first_n(q, c, 2, what);
    return init_first_n(q, c, c->degree, what);
}

cj_status cj_qctx_init(cj_qctx *q, const cj_bezier2 *c, const char *what) {
    cj_status st = cj_qctx_init_first(q, c, what);
    if (st != CJ_OK) return st;
    int n = q->n;
    for (int i = 0; i + 1 < n; ++i)
        for (int k = 0; k < 3; ++k)
            q->ddh[i][k] = cj_imul(cj_iv((double)(n - 1)), cj_isub(q->dh[i + 1][k], q->dh[i][k]));
    for (int i = 0; i + 2 < n; ++i)
        for (int k = 0; k < 3; ++k)
            q->d3h[i][k] = cj_imul(cj_iv((double)(n - 2)), cj_isub(q->ddh[i + 1][k], q->ddh[i][k]));
    return CJ_OK;
}

/* de Casteljau in interval arithmetic: Σ c_i B_i^m(t) for every t in T, per coordinate. */
static void ideval(const cj_ivl (*c)[3], int m, int dims, cj_ivl T, cj_ivl out[3]) {
    cj_ivl w[CJ_QUERY_MAXN + 1][3];
    cj_ivl S = cj_isub(cj_iv(1.0), T);
    for (int i = 0; i <= m; ++i)
        for (int k = 0; k < dims; ++k) w[i][k] = c[i][k];
    if (S.lo >= 0.0 && T.lo >= 0.0) { /* t in [0,1]: products with non-negative factors */
        for (int r = m; r > 0; --r)
            for (int i = 0; i < r; ++i)
                for (int k = 0; k < dims; ++k)
                    w[i][k] = cj_iadd(cj_imul_nonneg(S, w[i][k]), cj_imul_nonneg(T, w[i + 1][k]));
    } else {
        for (int r = m; r > 0; --r)
            for (int i = 0; i < r; ++i)
                for (int k = 0; k < dims; ++k)
                    w[i][k] = cj_iadd(cj_imul(S, w[i][k]), cj_imul(T, w[i + 1][k]));
    }
    for (int k = 0; k < dims; ++k) out[k] = w[0][k];
}

int cj_qctx_eval(const cj_qctx *q, cj_ivl T, cj_ivl p[2], cj_ivl d[2]) {
    int n = q->n, dims = q->rational ? 3 : 2;
    cj_ivl H[3], D[3], unused[2];
    if (!p) p = unused;
    /* a polynomial's derivative does not need the point: one evaluation saved */
    if (q->rational || p != unused)
        ideval((const cj_ivl(*)[3])q->h, n, dims, T, H);
    else
        H[0] = H[1] = H[2] = cj_iv(0.0);
    if (d) {
        if (n == 0)
            D[0] = D[1] = D[2] = cj_iv(0.0);
        else
            ideval((const cj_ivl(*)[3])q->dh, n - 1, dims, T, D);
    }
    if (!q->rational) {
        for (int k = 0; k < 2; ++k) {
            p[k] = H[k];
            if (d) d[k] = D[k];
        }
    } else {
        cj_ivl W = H[2];
        if (!(W.lo > 0.0)) return 0;
        for (int k = 0; k < 2; ++k) {
            p[k] = cj_idiv(H[k], W);
            /* c' = (P' - c w') / w: the quotient rule with the enclosure of c itself */
            if (d) d[k] = cj_idiv(cj_isub(D[k], cj_imul(p[k], D[2])), W);
        }
    }
    for (int k = 0; k < 2; ++k) {
        if (!cj_ifinite(p[k])) return 0;
        if (d && !cj_ifinite(d[k])) return 0;
    }
    return 1;
}

/* De Casteljau in doubles at t on the midpoints of the enclosed points pts[0..n] (coordinates
 * 0 and 1), with a bound of its error. With s = 1 - t (off by at most u) each step s a + t b is
 * off by at most about 3u M (M the largest magnitude, which the convex combinations never
 * exceed), and errors carried in pass through the combination unchanged: n steps, 4u M each,
 * plus the points' own radius r and the subnormal rounding of the products. */
CJ_UNROLLED double plain_decasteljau(const cj_ivl (*pts)[3], int n, double t, double out[2]) {
    double w[CJ_QUERY_MAXN + 1][2], r = 0.0, M = 0.0, s = 1.0 - t;
#pragma GCC unroll 8
    for (int i = 0; i <= n; ++i)
        for (int k = 0; k < 2; ++k) {
            cj_ivl v = pts[i][k];
            double m = cj_imid(v);
            w[i][k] = m;
            r = cj_fmax(r, cj_fmax(m - v.lo, v.hi - m));
            M = cj_fmax(M, fabs(m));
        }
#pragma GCC unroll 8
    for (int lev = n; lev > 0; --lev)
#pragma GCC unroll 8
        for (int i = 0; i < lev; ++i)
            for (int k = 0; k < 2; ++k) w[i][k] = s * w[i][k] + t * w[i + 1][k];
    out[0] = w[0][0];
    out[1] = w[0][1];
    return (r + (double)n * (M * 0x1p-51 + 0x1p-1070)) * (1.0 + 0x1p-40);
}

/* The same from midpoints m[0..n] given with their largest radius r and magnitude M. */
CJ_UNROLLED double plain_decasteljau_mid(const double (*m)[2], int n, double r, double M, double t,
                                         double out[2]) {
    double w[CJ_QUERY_MAXN + 1][2], s = 1.0 - t;
#pragma GCC unroll 8
    for (int i = 0; i <= n; ++i) {
        w[i][0] = m[i][0];
        w[i][1] = m[i][1];
    }
#pragma GCC unroll 8
    for (int lev = n; lev > 0; --lev)
#pragma GCC unroll 8
        for (int i = 0; i < lev; ++i)
            for (int k = 0; k < 2; ++k) w[i][k] = s * w[i][k] + t * w[i + 1][k];
    out[0] = w[0][0];
    out[1] = w[0][1];
    return (r + (double)n * (M * 0x1p-51 + 0x1p-1070)) * (1.0 + 0x1p-40);
}

static double plain_eval_mid(const double (*m)[2], int n, double r, double M, double t,
                             double out[2]) {
    if (n == 3) return plain_decasteljau_mid(m, 3, r, M, t, out);
    if (n == 2) return plain_decasteljau_mid(m, 2, r, M, t, out);
    return plain_decasteljau_mid(m, n, r, M, t, out);
}

static double plain_eval(const cj_ivl (*pts)[3], int n, double t, double out[2]) {
    if (n == 3) return plain_decasteljau(pts, 3, t, out);
    if (n == 2) return plain_decasteljau(pts, 2, t, out);
    return plain_decasteljau(pts, n, t, out);
}

int cj_qctx_point(const cj_qctx *q, double t, cj_ivl p[2]) {
    if (q->rational || !(t >= 0.0 && t <= 1.0)) return cj_qctx_eval(q, cj_iv(t), p, NULL);
    double w[2], e = q->plain
                         ? plain_eval_mid((const double(*)[2])q->hm, q->n, q->hrad, q->hmax, t, w)
                         : plain_eval((const cj_ivl(*)[3])q->h, q->n, t, w);
    for (int k = 0; k < 2; ++k) p[k] = cj_iv2(cj_down(w[k] - e), cj_up(w[k] + e));
    return cj_ifinite(p[0]) && cj_ifinite(p[1]);
}

int cj_qctx_deriv_near(const cj_qctx *q, cj_ivl T, cj_ivl d[2]) {
    int n = q->n;
    if (q->rational || n < 1 || !(T.lo >= 0.0 && T.hi <= 1.0) || !(T.hi - T.lo <= 0x1p-20) ||
        !(q->d2mag[0] < INFINITY && q->d2mag[1] < INFINITY))
        return 0;
    double t = 0.5 * T.lo + 0.5 * T.hi;
    double rad = cj_up(cj_fmax(t - T.lo, T.hi - t));
    /* as cj_qctx_point, on the hodograph (degree n - 1) */
    double w[2], e = q->plain
                         ? plain_eval_mid((const double(*)[2])q->dm, n - 1, q->drad, q->dmax, t, w)
                         : plain_eval((const cj_ivl(*)[3])q->dh, n - 1, t, w);
    for (int k = 0; k < 2; ++k) {
        double spread = cj_up(e + cj_up(q->d2mag[k] * rad));
        d[k] = cj_iv2(cj_down(w[k] - spread), cj_up(w[k] + spread));
    }
    return cj_ifinite(d[0]) && cj_ifinite(d[1]);
}

int cj_qctx_eval2(const cj_qctx *q, cj_ivl T, cj_ivl p[2], cj_ivl d[2], cj_ivl dd[2]) {
    int n = q->n, dims = q->rational ? 3 : 2;
    cj_ivl H[3], D[3], DD[3];
    ideval((const cj_ivl(*)[3])q->h, n, dims, T, H);
    if (n >= 1)
        ideval((const cj_ivl(*)[3])q->dh, n - 1, dims, T, D);
    else
        D[0] = D[1] = D[2] = cj_iv(0.0);
    if (n >= 2)
        ideval((const cj_ivl(*)[3])q->ddh, n - 2, dims, T, DD);
    else
        DD[0] = DD[1] = DD[2] = cj_iv(0.0);
    for (int k = 0; k < 2; ++k) {
        if (!q->rational) {
            p[k] = H[k];
            d[k] = D[k];
            dd[k] = DD[k];
            continue;
        }
        cj_ivl W = H[2];
        if (!(W.lo > 0.0)) return 0;
        p[k] = cj_idiv(H[k], W);
        d[k] = cj_idiv(cj_isub(D[k], cj_imul(p[k], D[2])), W);
        /* c'' = (P'' - 2 c' w' - c w'') / w */
        cj_ivl num = cj_isub(DD[k], cj_imul(cj_iv(2.0), cj_imul(d[k], D[2])));
        dd[k] = cj_idiv(cj_isub(num, cj_imul(p[k], DD[2])), W);
    }
    for (int k = 0; k < 2; ++k)
        if (!cj_ifinite(p[k]) || !cj_ifinite(d[k]) || !cj_ifinite(dd[k])) return 0;
    return 1;
}

int cj_qctx_eval3(const cj_qctx *q, cj_ivl T, cj_ivl p[2], cj_ivl d[2], cj_ivl dd[2],
                  cj_ivl d3[2]) {
    int n = q->n, dims = q->rational ? 3 : 2;
    cj_ivl H[3], D[3], DD[3], D3[3];
    ideval((const cj_ivl(*)[3])q->h, n, dims, T, H);
    D[0] = D[1] = D[2] = DD[0] = DD[1] = DD[2] = D3[0] = D3[1] = D3[2] = cj_iv(0.0);
    if (n >= 1) ideval((const cj_ivl(*)[3])q->dh, n - 1, dims, T, D);
    if (n >= 2) ideval((const cj_ivl(*)[3])q->ddh, n - 2, dims, T, DD);
    if (n >= 3) ideval((const cj_ivl(*)[3])q->d3h, n - 3, dims, T, D3);
    for (int k = 0; k < 2; ++k) {
        if (!q->rational) {
            p[k] = H[k], d[k] = D[k], dd[k] = DD[k], d3[k] = D3[k];
            continue;
        }
        cj_ivl W = H[2];
        if (!(W.lo > 0.0)) return 0;
        p[k] = cj_idiv(H[k], W);
        d[k] = cj_idiv(cj_isub(D[k], cj_imul(p[k], D[2])), W);
        cj_ivl num = cj_isub(DD[k], cj_imul(cj_iv(2.0), cj_imul(d[k], D[2])));
        dd[k] = cj_idiv(cj_isub(num, cj_imul(p[k], DD[2])), W);
        /* c''' = (P''' - 3 c'' w' - 3 c' w'' - c w''') / w */
        cj_ivl t3 = cj_isub(D3[k], cj_imul(cj_iv(3.0), cj_imul(dd[k], D[2])));
        t3 = cj_isub(t3, cj_imul(cj_iv(3.0), cj_imul(d[k], DD[2])));
        d3[k] = cj_idiv(cj_isub(t3, cj_imul(p[k], D3[2])), W);
    }
    for (int k = 0; k < 2; ++k)
        if (!cj_ifinite(p[k]) || !cj_ifinite(d[k]) || !cj_ifinite(dd[k]) || !cj_ifinite(d3[k]))
            return 0;
    return 1;
}

void cj_qpiece_boxes(const cj_qpiece *p, double lo[][2], double hi[][2]) {
    const double *e = p->err;
    for (int i = 0; i <= p->n; ++i) {
        cj_ivl W = cj_iv2(cj_down(p->h[i][2] - e[2]), cj_up(p->h[i][2] + e[2]));
        for (int k = 0; k < 2; ++k) {
            cj_ivl X = cj_iv2(cj_down(p->h[i][k] - e[k]), cj_up(p->h[i][k] + e[k]));
            if (!p->rational) { /* the weight is exactly 1 in every piece */
                lo[i][k] = X.lo;
                hi[i][k] = X.hi;
                continue;
            }
            if (!(W.lo > 0.0)) {
                lo[i][k] = -INFINITY;
                hi[i][k] = INFINITY;
                continue;
            }
            cj_ivl r = cj_idiv(X, W);
            lo[i][k] = r.lo;
            hi[i][k] = r.hi;
        }
    }
}

/* The enclosure of a polynomial piece: its control points are h +- err (weights exactly 1), so
 * min and max of h widened by err and a step outwards. */
CJ_UNROLLED void set_bbox_poly(cj_qpiece *p, int n) {
#pragma GCC unroll 2
    for (int k = 0; k < 2; ++k) {
        double lo = p->h[0][k], hi = lo;
#pragma GCC unroll 8
        for (int i = 1; i <= n; ++i) {
            double v = p->h[i][k];
            lo = v < lo ? v : lo;
            hi = v > hi ? v : hi;
        }
        p->blo[k] = cj_down(lo - p->err[k]);
        p->bhi[k] = cj_up(hi + p->err[k]);
    }
}

/* The enclosure of the whole piece, cached on creation; rational pieces go through the
 * projected boxes. */
static void set_bbox(cj_qpiece *p) {
    int n = p->n;
    if (!p->rational) {
        set_bbox_poly(p, n);
        return;
    }
    double blo[CJ_QUERY_MAXN + 1][2], bhi[CJ_QUERY_MAXN + 1][2];
    cj_qpiece_boxes(p, blo, bhi);
    for (int k = 0; k < 2; ++k) {
        p->blo[k] = INFINITY;
        p->bhi[k] = -INFINITY;
        for (int i = 0; i <= n; ++i) {
            p->blo[k] = cj_fmin(p->blo[k], blo[i][k]);
            p->bhi[k] = cj_fmax(p->bhi[k], bhi[i][k]);
        }
    }
}

void cj_qpiece_root(const cj_qctx *q, cj_qpiece *p) {
    p->n = q->n;
    p->rational = q->rational;
    p->a = 0.0;
    p->b = 1.0;
    p->perr = 0.0;
    /* a polynomial's own control points, exact (hm); a line's enclosed ones below */
    if (q->plain) {
        for (int i = 0; i <= q->n; ++i) {
            p->h[i][0] = q->hm[i][0];
            p->h[i][1] = q->hm[i][1];
            p->h[i][2] = 1.0;
        }
        p->err[0] = p->err[1] = p->err[2] = 0.0;
        if (q->n == 3)
            set_bbox_poly(p, 3);
        else
            set_bbox(p);
        return;
    }
    for (int k = 0; k < 3; ++k) {
        double err = 0.0;
        for (int i = 0; i <= q->n; ++i) {
            cj_ivl v = q->h[i][k];
            double m = cj_imid(v);
            p->h[i][k] = m;
            err = cj_fmax(err, cj_fmax(m - v.lo, v.hi - m));
        }
        p->err[k] = err > 0.0 ? cj_up(err) : 0.0;
    }
    set_bbox(p);
}

/* de Casteljau at 1/2 in place in R (its points are the right piece's at the end), the left
 * piece's points taken off the first column as it goes; dims coordinates averaged, the weight
 * copied. */
CJ_UNROLLED void halve_points(const cj_qpiece *p, int n, int dims, cj_qpiece *L, cj_qpiece *R) {
#pragma GCC unroll 8
    for (int i = 0; i <= n; ++i)
        for (int k = 0; k < 3; ++k) R->h[i][k] = p->h[i][k];
    for (int k = 0; k < 3; ++k) L->h[0][k] = p->h[0][k];
#pragma GCC unroll 8
    for (int r = n; r > 0; --r) {
#pragma GCC unroll 8
        for (int i = 0; i < r; ++i)
            for (int k = 0; k < dims; ++k) R->h[i][k] = 0.5 * (R->h[i][k] + R->h[i + 1][k]);
        for (int k = 0; k < 3; ++k) L->h[n - r + 1][k] = R->h[0][k];
    }
}

CJ_UNROLLED void halve_n(const cj_qpiece *p, int n, const double mag[3], cj_qpiece *L,
                         cj_qpiece *R) {
    if (p->rational)
        halve_points(p, n, 3, L, R);
    else
        halve_points(p, n, 2, L, R);
    /* Each output point went through at most n averagings, each off by at most u times the
     * largest magnitude (the addition) plus 2^-1075 (the halving, in the subnormal range);
     * errors of the inputs pass through averages unchanged. A polynomial's weights stay
     * exactly 1 (they are copied, never averaged). */
    double e[3];
    for (int k = 0; k < 3; ++k) {
        e[k] = p->err[k] + (double)n * ((mag[k] + p->err[k]) * 0x1p-53 + 0x1p-1074);
        e[k] *= 1.0 + 0x1p-40;
    }
    if (!p->rational) e[2] = 0.0;
    /* exact for a dyadic piece; after a clip the midpoint of the exact ends is within perr
     * plus half an ulp (at most 2^-54 below 1) of m */
    double m = 0.5 * (p->a + p->b);
    L->n = R->n = n;
    L->rational = R->rational = p->rational;
    L->a = p->a;
    L->b = m;
    R->a = m;
    R->b = p->b;
    L->perr = R->perr = p->perr > 0.0 ? p->perr + 0x1p-53 : 0.0;
    for (int k = 0; k < 3; ++k) L->err[k] = R->err[k] = e[k];
    if (p->rational) {
        set_bbox(L);
        set_bbox(R);
    } else {
        set_bbox_poly(L, n);
        set_bbox_poly(R, n);
    }
}

void cj_qpiece_halve(const cj_qpiece *p, const double mag[3], cj_qpiece *L, cj_qpiece *R) {
    if (p->n == 3 && !p->rational)
        halve_n(p, 3, mag, L, R);
    else if (p->n == 2 && !p->rational)
        halve_n(p, 2, mag, L, R);
    else
        halve_n(p, p->n, mag, L, R);
}

/* de Casteljau at the double t in place: w becomes the piece right of t (keep_left 0) or left
 * of it (keep_left 1; the same recurrence run from the other end). */
CJ_UNROLLED void split_at(double (*w)[3], int n, double t, int keep_left) {
    double s = 1.0 - t;
    if (!keep_left) {
#pragma GCC unroll 8
        for (int r = n; r > 0; --r)
#pragma GCC unroll 8
            for (int i = 0; i < r; ++i) {
                w[i][0] = s * w[i][0] + t * w[i + 1][0];
                w[i][1] = s * w[i][1] + t * w[i + 1][1];
            }
        return;
    }
#pragma GCC unroll 8
    for (int r = 1; r <= n; ++r)
#pragma GCC unroll 8
        for (int i = n; i >= r; --i) {
            w[i][0] = s * w[i - 1][0] + t * w[i][0];
            w[i][1] = s * w[i - 1][1] + t * w[i][1];
        }
}

CJ_UNROLLED void qpiece_sub_n(const cj_qpiece *p, int n, const double mag[3], double u0, double u1,
                              cj_qpiece *out) {
    double pa = p->a, pb = p->b, perr = p->perr, err[2] = {p->err[0], p->err[1]}; /* out may be p */
    if (out != p)
#pragma GCC unroll 8
        for (int i = 0; i <= n; ++i) {
            out->h[i][0] = p->h[i][0];
            out->h[i][1] = p->h[i][1];
            out->h[i][2] = 1.0;
        }
    int splits = 0;
    if (u0 > 0.0) {
        split_at(out->h, n, u0, 0);
        ++splits;
    }
    /* the relative end rounded up, so that u0 + (1 - u0) s2 >= u1 exactly */
    double s2 = u0 > 0.0 ? cj_up(cj_up(u1 - u0) / cj_down(1.0 - u0)) : u1;
    if (s2 < 1.0) {
        split_at(out->h, n, s2, 1);
        ++splits;
    } else {
        s2 = 1.0;
    }
    /* Each level of a split at t rounds s = 1 - t (at most 2^-54 off, times |x|) and the two
     * products and the sum (2u (|s x| + |t y|)): at most 3.1 u times the largest magnitude,
     * which the convex combinations never exceed; errors carried in pass through. */
    for (int k = 0; k < 2; ++k)
        out->err[k] =
            (err[k] + (double)(splits * n) * ((mag[k] + err[k]) * 3.1 * 0x1p-53 + 0x1p-1073)) *
            (1.0 + 0x1p-40);
    out->err[2] = 0.0;
    out->n = n;
    out->rational = 0;
    /* the exact ends: a* + (b* - a*) u0 and a* + (b* - a*)(u0 + (1 - u0) s2), with a*, b* within
     * perr of a, b; each computed end is within perr plus a few roundings below 2 of them */
    double w0 = pb - pa;
    out->a = pa + w0 * u0;
    out->b = s2 == 1.0 ? pb : pa + w0 * (u0 + (1.0 - u0) * s2);
    out->perr = perr + 0x1p-49;
    set_bbox_poly(out, n);
}

void cj_qpiece_sub(const cj_qpiece *p, const double mag[3], double u0, double u1, cj_qpiece *out) {
    assert(!p->rational && u0 >= 0.0 && u1 <= 1.0 && u0 < u1);
    if (p->n == 3)
        qpiece_sub_n(p, 3, mag, u0, u1, out);
    else if (p->n == 2)
        qpiece_sub_n(p, 2, mag, u0, u1, out);
    else
        qpiece_sub_n(p, p->n, mag, u0, u1, out);
}

void cj_qpiece_bbox(const cj_qpiece *p, double lo[2], double hi[2]) {
    for (int k = 0; k < 2; ++k) {
        lo[k] = p->blo[k];
        hi[k] = p->bhi[k];
    }
}

void cj_qctx_line(cj_qctx *q, const double p[2], const double d[2], double L) {
    q->n = 1;
    q->rational = 0;
    cj_ivl IL = cj_iv(L);
    q->hmag[0] = q->hmag[1] = 0.0;
    q->hmag[2] = 1.0;
    for (int k = 0; k < 2; ++k) {
        cj_ivl off = cj_imul(IL, cj_iv(d[k]));
        q->h[0][k] = cj_isub(cj_iv(p[k]), off);
        q->h[1][k] = cj_iadd(cj_iv(p[k]), off);
        q->dh[0][k] = cj_isub(q->h[1][k], q->h[0][k]);
        q->hmag[k] = cj_fmax(cj_imag(q->h[0][k]), cj_imag(q->h[1][k]));
    }
    q->h[0][2] = q->h[1][2] = cj_iv(1.0);
    q->dh[0][2] = cj_iv(0.0);
    q->d2mag[0] = q->d2mag[1] = 0.0; /* straight: c'' = 0 */
    q->plain = 0;
    q->scale = cj_fmax(q->hmag[0], q->hmag[1]);
}

double cj_query_scale(const cj_bezier2 *c) {
    double s = 0.0;
    if (c->degree < 0 || c->degree > CJ_QUERY_MAX_DEGREE) return 1.0; /* refused later */
    for (int i = 0; i < 2 * (c->degree + 1); ++i)
        if (isfinite(c->pts[i])) s = cj_fmax(s, fabs(c->pts[i]));
    return s;
}

int cj_query_scale_exp(double scale) {
    return scale > 0.0 && scale < 0x1p-200 ? -ilogb(scale) : 0;
}

cj_bezier2 cj_query_scaled(const cj_bezier2 *c, int k, double *buf) {
    for (int i = 0; i < 2 * (c->degree + 1); ++i) buf[i] = ldexp(c->pts[i], k);
    return cj_bezier2_view(c->degree, buf, c->weights);
}

/* The pair search of the certified intersections: separating axes, Krawczyk's test, the
 * tables of roots and contact leaves (the method is described in intersect.c). */
#include "intersect_internal.h"

#include "casteljau/bezier.h"
#include "casteljau/nearest.h"
#include "error_internal.h"

#include <assert.h>
#include <stdlib.h>
#include <string.h>

/* Empties the tables without touching their (large) storage. */
void cj_isect_run_reset(run *R) {
    R->qa = R->qb = NULL;
    R->tol = R->ext_a = R->ext_b = 0.0;
    R->max_boxes = 0;
    R->ca = NULL;
    R->self = R->line = R->capped = R->table_full = R->in_flat = 0;
    R->boxes = 0;
    R->nroots = R->nleaves = R->noverlaps = 0;
}

/* ---- proofs ----------------------------------------------------------------------------- */

/* min and max of v . x over the boxes of a piece, outward rounded. */
static void project(const double lo[][2], const double hi[][2], int n, const double v[2],
                    double *pmin, double *pmax) {
    double mn = INFINITY, mx = -INFINITY;
    for (int i = 0; i <= n; ++i) {
        /* the smallest and largest of v . x over the box, each product and the sum widened */
        double a0 = v[0] >= 0 ? v[0] * lo[i][0] : v[0] * hi[i][0];
        double a1 = v[1] >= 0 ? v[1] * lo[i][1] : v[1] * hi[i][1];
        double b0 = v[0] >= 0 ? v[0] * hi[i][0] : v[0] * lo[i][0];
        double b1 = v[1] >= 0 ? v[1] * hi[i][1] : v[1] * lo[i][1];
        double l = cj_down(cj_down(a0) + cj_down(a1)), h = cj_up(cj_up(b0) + cj_up(b1));
        if (isnan(l) || isnan(h)) l = -INFINITY, h = INFINITY;
        mn = l < mn ? l : mn;
        mx = h > mx ? h : mx;
    }
    *pmin = mn;
    *pmax = mx;
}

/* min and max of v . x over the control points of a polynomial piece, each within err of
 * h: the plain products and sums, widened by what the points' errors move the projection
 * (|v0| e0 + |v1| e1) plus the rounding of the dot products (at most 2.5u (|v0| + |v1|) times
 * the largest coordinate) and a step outwards. */
static inline double poly_margin(const cj_qpiece *p, const double v[2]) {
    double mag = cj_max4(fabs(p->blo[0]), fabs(p->bhi[0]), fabs(p->blo[1]), fabs(p->bhi[1]));
    double av = fabs(v[0]) + fabs(v[1]);
    double margin = fabs(v[0]) * p->err[0] + fabs(v[1]) * p->err[1] + av * mag * 0x1.4p-52;
    return margin * (1.0 + 0x1p-40) + 0x1p-1060;
}

/* Forced inlining: the clip is instantiated for cubics and quadratics with the degrees as
 * constants, so that its loops unroll (half the search's time goes there). */
#define CJ_UNROLLED static inline __attribute__((always_inline))

CJ_UNROLLED void project_poly_n(const cj_qpiece *p, int n, const double v[2], double *pmin,
                                double *pmax) {
    double mn = INFINITY, mx = -INFINITY;
#pragma GCC unroll 8
    for (int i = 0; i <= n; ++i) {
        double d = v[0] * p->h[i][0] + v[1] * p->h[i][1];
        mn = d < mn ? d : mn;
        mx = d > mx ? d : mx;
    }
    double margin = poly_margin(p, v);
    if (!isfinite(margin) || isnan(mn) || isnan(mx)) {
        *pmin = -INFINITY;
        *pmax = INFINITY;
        return;
    }
    *pmin = cj_down(mn - margin);
    *pmax = cj_up(mx + margin);
}

static void project_poly(const cj_qpiece *p, const double v[2], double *pmin, double *pmax) {
    project_poly_n(p, p->n, v, pmin, pmax);
}

/* Bézier clipping (fat lines): the part of polynomial piece p that can meet polynomial piece o.
 * With v normal to o's chord, o lies in the band bmin <= v . x <= bmax (its enclosed control
 * points projected, as in separated). v . p(u) is the Bézier function with control values
 * e_i* = v . P_i*, each within the margin of the computed e_i, so v . p(u) lies within the margin
 * of sum e_i B_i(u), which lies in the convex hull of the points (i/n, e_i). Where that hull
 * misses the band widened by the margin, p cannot meet o. The hull's part in the band spans,
 * in u, from the smallest to the largest of: the i/n whose e_i lie in the band, and the
 * crossings of every segment between two points with the band's edges (the hull's edges are
 * among them). Those are computed in doubles: a crossing's ratio (level - e_i) / (e_j - e_i) is
 * two subtractions and a division, each off by at most u relative, and the abscissas a few
 * roundings more, so padding the range by 2^-48 makes it a superset.
 * Returns -1 if p is proven to miss o, 1 with [*u0, *u1] (in p's own parameter) if the range
 * is a proper part of [0,1], 0 if nothing was learnt. */
CJ_UNROLLED int clip_band_n(const cj_qpiece *p, int n, const double v[2], double omin, double omax,
                            double *u0, double *u1) {
    /* p's projections, each within margin of the exact one */
    double e[CJ_QUERY_MAXN + 1], margin = poly_margin(p, v);
    double mn = INFINITY, mx = -INFINITY;
#pragma GCC unroll 8
    for (int i = 0; i <= n; ++i) {
        e[i] = v[0] * p->h[i][0] + v[1] * p->h[i][1];
        mn = e[i] < mn ? e[i] : mn;
        mx = e[i] > mx ? e[i] : mx;
    }
    double lo = cj_down(omin - margin), hi = cj_up(omax + margin);
    if (!isfinite(lo) || !isfinite(hi) || !isfinite(mn) || !isfinite(mx)) return 0;
    if (mx < lo || mn > hi) return -1; /* the hulls are separated along v */
    double xmin = INFINITY, xmax = -INFINITY, inv = 1.0 / n, xs[CJ_QUERY_MAXN + 1];
    int band[CJ_QUERY_MAXN + 1]; /* -1 below the band, 0 in it, 1 above */
#pragma GCC unroll 8
    for (int i = 0; i <= n; ++i) {
        xs[i] = i * inv;
        band[i] = e[i] < lo ? -1 : e[i] > hi ? 1 : 0;
        if (band[i] == 0) {
            xmin = xs[i] < xmin ? xs[i] : xmin;
            xmax = xs[i] > xmax ? xs[i] : xmax;
        }
    }
#pragma GCC unroll 8
    for (int i = 0; i < n; ++i)
#pragma GCC unroll 8
        for (int j = i + 1; j <= n; ++j) {
            /* a segment meets an edge only if its ends are on two sides of it; its crossing
             * lies between i/n and j/n: no use once both are inside [xmin, xmax] */
            if (band[i] == band[j] || (xs[i] >= xmin && xs[j] <= xmax)) continue;
            for (int side = 0; side < 2; ++side) {
                double level = side ? hi : lo;
                if (!((e[i] < level && e[j] > level) || (e[i] > level && e[j] < level))) continue;
                double r = (level - e[i]) / (e[j] - e[i]);
                double x = xs[i] + (xs[j] - xs[i]) * r;
                xmin = x < xmin ? x : xmin;
                xmax = x > xmax ? x : xmax;
            }
        }
    if (xmin > xmax) return -1;
    *u0 = xmin - 0x1p-48 > 0.0 ? xmin - 0x1p-48 : 0.0;
    *u1 = xmax + 0x1p-48 < 1.0 ? xmax + 0x1p-48 : 1.0;
    return *u0 > 0.0 || *u1 < 1.0;
}

CJ_UNROLLED int clip_range_n(const cj_qpiece *p, int n, const cj_qpiece *o, int no, double *u0,
                             double *u1) {
    double v[2] = {-(o->h[no][1] - o->h[0][1]), o->h[no][0] - o->h[0][0]};
    if (!isfinite(v[0]) || !isfinite(v[1]) || (v[0] == 0.0 && v[1] == 0.0)) return 0;
    double omin, omax;
    project_poly_n(o, no, v, &omin, &omax);
    return clip_band_n(p, n, v, omin, omax, u0, u1);
}

/* The clip for the usual degrees with constant loop bounds, else the general one. */
static int clip_range(const cj_qpiece *p, const cj_qpiece *o, double *u0, double *u1) {
    if (p->n == 3 && o->n == 3) return clip_range_n(p, 3, o, 3, u0, u1);
    if (p->n == 3 && o->n == 2) return clip_range_n(p, 3, o, 2, u0, u1);
    if (p->n == 2 && o->n == 3) return clip_range_n(p, 2, o, 3, u0, u1);
    if (p->n == 2 && o->n == 2) return clip_range_n(p, 2, o, 2, u0, u1);
    return clip_range_n(p, p->n, o, o->n, u0, u1);
}

static int boxes_apart(const cj_qpiece *pa, const cj_qpiece *pb) {
    for (int k = 0; k < 2; ++k)
        if (pa->bhi[k] < pb->blo[k] || pb->bhi[k] < pa->blo[k]) return 1;
    return 0;
}

/* 1 if the hulls of the two pieces are proven disjoint: their enclosing boxes first, then the
 * normals of both chords (fat-line exclusion). */
static int separated(const cj_qpiece *pa, const cj_qpiece *pb) {
    for (int k = 0; k < 2; ++k)
        if (pa->bhi[k] < pb->blo[k] || pb->bhi[k] < pa->blo[k]) return 1;
    int na = pa->n, nb = pb->n;
    double axes[2][2] = {{-(pa->h[na][1] - pa->h[0][1]), pa->h[na][0] - pa->h[0][0]},
                         {-(pb->h[nb][1] - pb->h[0][1]), pb->h[nb][0] - pb->h[0][0]}};
    if (!pa->rational && !pb->rational) {
        for (int k = 0; k < 2; ++k) {
            if (!isfinite(axes[k][0]) || !isfinite(axes[k][1])) continue;
            if (axes[k][0] == 0.0 && axes[k][1] == 0.0) continue;
            double amin, amax, bmin, bmax;
            project_poly(pa, axes[k], &amin, &amax);
            project_poly(pb, axes[k], &bmin, &bmax);
            if (amax < bmin || bmax < amin) return 1;
        }
        return 0;
    }
    double alo[CJ_QUERY_MAXN + 1][2], ahi[CJ_QUERY_MAXN + 1][2];
    double blo[CJ_QUERY_MAXN + 1][2], bhi[CJ_QUERY_MAXN + 1][2];
    cj_qpiece_boxes(pa, alo, ahi);
    cj_qpiece_boxes(pb, blo, bhi);
    axes[0][0] = -(alo[na][1] - alo[0][1]);
    axes[0][1] = alo[na][0] - alo[0][0];
    axes[1][0] = -(blo[nb][1] - blo[0][1]);
    axes[1][1] = blo[nb][0] - blo[0][0];
    for (int k = 0; k < 2; ++k) {
        if (!isfinite(axes[k][0]) || !isfinite(axes[k][1])) continue;
        if (axes[k][0] == 0.0 && axes[k][1] == 0.0) continue;
        double amin, amax, bmin, bmax;
        project((const double(*)[2])alo, (const double(*)[2])ahi, na, axes[k], &amin, &amax);
        project((const double(*)[2])blo, (const double(*)[2])bhi, nb, axes[k], &bmin, &bmax);
        if (amax < bmin || bmax < amin) return 1;
    }
    return 0;
}

/* y a for a double y: the same enclosure as cj_imul(cj_iv(y), a) from two products instead of
 * four (the bounds pair up by y's sign), stepped outwards; a NaN widens to the line. */
static inline cj_ivl scale_ivl(double y, cj_ivl a) {
    double lo = y >= 0.0 ? y * a.lo : y * a.hi, hi = y >= 0.0 ? y * a.hi : y * a.lo;
    if (isnan(lo + hi)) return cj_iv2(-INFINITY, INFINITY);
    return cj_iv2(cj_down(lo), cj_up(hi));
}

/* Krawczyk's operator for F(s,t) = a(s) - b(t) over X: -1 if K misses X (no zero in X), 1 if K
 * lies in the interior of X (exactly one zero in X, and it lies in K), 0 otherwise. */
int cj_isect_krawczyk(const cj_qctx *qa, const cj_qctx *qb, const cj_ivl X[2], cj_ivl K[2]) {
    double m[2] = {cj_imid(X[0]), cj_imid(X[1])};
    cj_ivl pa[2], pb[2], da[2], db[2];
    if (!cj_qctx_deriv_near(qa, X[0], da) && !cj_qctx_eval(qa, X[0], NULL, da)) return 0;
    if (!cj_qctx_deriv_near(qb, X[1], db) && !cj_qctx_eval(qb, X[1], NULL, db)) return 0;
    if (!cj_qctx_point(qa, m[0], pa) || !cj_qctx_point(qb, m[1], pb)) return 0;
    cj_ivl F[2] = {cj_isub(pa[0], pb[0]), cj_isub(pa[1], pb[1])};
    cj_ivl J[2][2] = {{da[0], cj_ineg(db[0])}, {da[1], cj_ineg(db[1])}};
    double Jm[2][2];
    for (int r = 0; r < 2; ++r)
        for (int c = 0; c < 2; ++c) Jm[r][c] = cj_imid(J[r][c]);
    double det = Jm[0][0] * Jm[1][1] - Jm[0][1] * Jm[1][0];
    if (!(fabs(det) > 0.0) || !isfinite(det)) return 0;
    double Y[2][2] = {{Jm[1][1] / det, -Jm[0][1] / det}, {-Jm[1][0] / det, Jm[0][0] / det}};
    for (int r = 0; r < 2; ++r)
        for (int c = 0; c < 2; ++c)
            if (!isfinite(Y[r][c])) return 0;
    for (int r = 0; r < 2; ++r) {
        cj_ivl acc =
            cj_isub(cj_iv(m[r]), cj_iadd(scale_ivl(Y[r][0], F[0]), scale_ivl(Y[r][1], F[1])));
        for (int c = 0; c < 2; ++c) {
            cj_ivl yj = cj_iadd(scale_ivl(Y[r][0], J[0][c]), scale_ivl(Y[r][1], J[1][c]));
            cj_ivl M = cj_isub(cj_iv(r == c ? 1.0 : 0.0), yj);
            acc = cj_iadd(acc, cj_imul(M, cj_isub(X[c], cj_iv(m[c]))));
        }
        K[r] = acc;
    }
    for (int r = 0; r < 2; ++r) {
        if (!cj_ifinite(K[r])) return 0;
        if (K[r].hi < X[r].lo || K[r].lo > X[r].hi) return -1;
    }
    for (int r = 0; r < 2; ++r)
        if (!(K[r].lo > X[r].lo && K[r].hi < X[r].hi)) return 0;
    return 1;
}

/* Plain (unproven) point and derivative of the curve at t from the midpoints of its
 * homogeneous control points: the guesses the proofs start from. */
static void guess_eval(const cj_qctx *q, double t, double p[2], double d[2]) {
    int n = q->n, dims = q->rational ? 3 : 2;
    double w[CJ_QUERY_MAXN + 1][3], H[3] = {0, 0, 1}, D[3] = {0, 0, 0};
    for (int i = 0; i <= n; ++i)
        for (int k = 0; k < dims; ++k) w[i][k] = cj_imid(q->h[i][k]);
    double s = 1.0 - t;
    for (int r = n; r > 0; --r) {
        if (r == 1)
            for (int k = 0; k < dims; ++k) D[k] = (double)n * (w[1][k] - w[0][k]);
        for (int i = 0; i < r; ++i)
            for (int k = 0; k < dims; ++k) w[i][k] = s * w[i][k] + t * w[i + 1][k];
    }
    for (int k = 0; k < dims; ++k) H[k] = w[0][k];
    for (int k = 0; k < 2; ++k) {
        p[k] = H[k] / H[2];
        d[k] = (D[k] - p[k] * D[2]) / H[2];
    }
}

/* Newton on a(s) - b(t) = 0 in plain doubles from m; returns 0 if it broke down (a singular or
 * non-finite step), 1 otherwise (converged or not: the proof decides). */
static int newton_guess(const cj_qctx *qa, const cj_qctx *qb, double m[2]) {
    for (int it = 0; it < 6; ++it) {
        double pa[2], da[2], pb[2], db[2];
        guess_eval(qa, m[0], pa, da);
        guess_eval(qb, m[1], pb, db);
        double f0 = pa[0] - pb[0], f1 = pa[1] - pb[1];
        double det = -da[0] * db[1] + db[0] * da[1];
        if (!(fabs(det) > 0.0) || !isfinite(det)) return 0;
        double ds = (-db[1] * f0 + db[0] * f1) / det, dt = (da[0] * f1 - da[1] * f0) / det;
        if (!isfinite(ds) || !isfinite(dt)) return 0;
        m[0] -= ds;
        m[1] -= dt;
        if (fabs(ds) <= 0x1p-50 * cj_fmax(fabs(m[0]), 0x1p-20) &&
            fabs(dt) <= 0x1p-50 * cj_fmax(fabs(m[1]), 0x1p-20))
            return 1;
    }
    return 1; /* rounding noise above 2^-50 (an ill-conditioned crossing): try it anyway */
}

/* Shrinks an enclosure of a zero already proven unique: K <- K(X) ∩ X while it narrows. A
 * Newton guess in plain doubles is tried first: a tiny box Y around it with K(Y) inside Y holds
 * a zero, which is the unique one of the caller's box when Y meets X, so one or two proofs
 * replace the several iterations of K from X. */
static void refine(const cj_qctx *qa, const cj_qctx *qb, cj_ivl X[2]) {
    double m[2] = {cj_imid(X[0]), cj_imid(X[1])};
    if (newton_guess(qa, qb, m) && X[0].lo <= m[0] && m[0] <= X[0].hi && X[1].lo <= m[1] &&
        m[1] <= X[1].hi) {
        for (int grow = 0; grow < 3; ++grow) {
            double r = grow == 0 ? 0x1p-46 : grow == 1 ? 0x1p-40 : 0x1p-34;
            cj_ivl Y[2], K[2];
            for (int k = 0; k < 2; ++k) {
                double w = r * cj_fmax(fabs(m[k]), 0x1p-16);
                Y[k] = cj_iv2(cj_fmax(X[k].lo, m[k] - w), cj_fmin(X[k].hi, m[k] + w));
            }
            if (cj_isect_krawczyk(qa, qb, Y, K) != 1) continue;
            for (int k = 0; k < 2; ++k) {
                X[k].lo = cj_fmax(Y[k].lo, K[k].lo);
                X[k].hi = cj_fmin(Y[k].hi, K[k].hi);
            }
            return; /* K(Y) is as narrow as the rounding of the proof allows */
        }
    }
    for (int it = 0; it < 12; ++it) {
        cj_ivl K[2];
        int r = cj_isect_krawczyk(qa, qb, X, K);
        if (r < 0) return; /* cannot happen for a box holding the zero; keep what we have */
        double before = cj_iwidth(X[0]) + cj_iwidth(X[1]);
        for (int k = 0; k < 2; ++k) {
            X[k].lo = cj_fmax(X[k].lo, K[k].lo);
            X[k].hi = cj_fmin(X[k].hi, K[k].hi);
        }
        if (cj_iwidth(X[0]) + cj_iwidth(X[1]) >= before) return;
    }
}

/* Records a zero proven unique in U with enclosure K, unless it is outside the domain or the
 * same zero as one recorded before (its enclosure inside the other's uniqueness box). Returns 0
 * if the zero lies outside the domain (so not in the box being examined either). */
int cj_isect_record(run *R, cj_ivl K[2], const cj_ivl U[2]) {
    int at_end = 0;
    for (int k = 0; k < 2; ++k) {
        if (k == 1 && R->line) continue;
        if (K[k].hi < 0.0 || K[k].lo > 1.0) return 0;
        if (K[k].lo <= 0.0 || K[k].hi >= 1.0) {
            at_end = 1;
            K[k].lo = cj_fmax(K[k].lo, 0.0);
            K[k].hi = cj_fmin(K[k].hi, 1.0);
        }
    }
    if (R->self && K[0].hi >= K[1].lo) { /* must be s < t: the diagonal is no intersection */
        if (K[0].lo >= K[1].hi) return 0;
    }
    for (int i = 0; i < R->nroots; ++i) {
        root *o = &R->roots[i];
        if (inside(K, o->U) || inside(o->K, U)) {
            for (int k = 0; k < 2; ++k) {
                o->K[k].lo = cj_fmax(o->K[k].lo, K[k].lo);
                o->K[k].hi = cj_fmin(o->K[k].hi, K[k].hi);
            }
            o->at_end |= at_end;
            return 1;
        }
    }
    if (R->nroots == R->max_roots) {
        R->capped = R->table_full = 1;
        return 1;
    }
    root *r = &R->roots[R->nroots++];
    r->K[0] = K[0];
    r->K[1] = K[1];
    r->U[0] = U[0];
    r->U[1] = U[1];
    r->at_end = at_end;
    return 1;
}

void cj_isect_add_leaf(run *R, cj_ivl S, cj_ivl T, double size, int exact) {
    if (R->nleaves == R->max_leaves) {
        R->capped = R->table_full = 1;
        return;
    }
    leaf *l = &R->leaves[R->nleaves++];
    l->B[0] = S;
    l->B[1] = T;
    l->size = size;
    l->exact = exact;
}

double cj_isect_extent(const cj_qpiece *p) {
    return cj_fmax(p->bhi[0] - p->blo[0], p->bhi[1] - p->blo[1]);
}

/* Tries to settle the box S x T by Krawczyk on the box enlarged by an eighth on each side:
 * -1 no zero in S x T, 1 its one zero recorded, 0 undecided. */
static int settle(run *R, cj_ivl S, cj_ivl T, double min_grow) {
    /* at least min_grow wider on each side: clipping can leave boxes a few ulps wide, where the
     * rounding of the proof itself would keep K from fitting inside (a wider U proves the same
     * zero) */
    double ws = cj_fmax(cj_iwidth(S) / 8, min_grow), wt = cj_fmax(cj_iwidth(T) / 8, min_grow);
    cj_ivl U[2] = {cj_iv2(S.lo - ws, S.hi + ws), cj_iv2(T.lo - wt, T.hi + wt)};
    cj_ivl K[2];
    int r = cj_isect_krawczyk(R->qa, R->qb, U, K);
    if (r < 0) return -1;
    if (r == 0) return 0;
    cj_ivl X[2] = {K[0], K[1]};
    /* after clipping U is often only a few 2^-44 wide, and K from it already about as narrow
     * as the rounding of the proof allows (1e-15..1e-13): refining would not narrow it */
    if (cj_iwidth(K[0]) > 0x1p-42 || cj_iwidth(K[1]) > 0x1p-42) refine(R->qa, R->qb, X);
    cj_ivl box[2] = {S, T};
    if (!meets(X, box)) return -1; /* the one zero of U lies outside S x T */
    if (!cj_isect_record(R, X, U)) return -1;
    return 1;
}

static int in_overlap(const run *R, const cj_qpiece *pa, const cj_qpiece *pb) {
    cj_ivl B[2] = {cj_qpiece_span(pa), cj_qpiece_span(pb)};
    for (int i = 0; i < R->noverlaps; ++i)
        if (inside(B, R->overlap[i])) return 1;
    return 0;
}

/* w . x over a polynomial piece's control points (each within the returned margin of the
 * exact one) if they are strictly monotone, so that the piece itself is monotone along w and
 * covers at least [*cover_lo, *cover_hi] there (its end points' projections); 0 if not. */
static int monotone_along(const cj_qpiece *p, const double w[2], double *cover_lo,
                          double *cover_hi) {
    double margin = poly_margin(p, w), e[CJ_QUERY_MAXN + 1];
    int up = 1, down = 1;
    for (int i = 0; i <= p->n; ++i) {
        e[i] = w[0] * p->h[i][0] + w[1] * p->h[i][1];
        if (i > 0) {
            up &= e[i] - e[i - 1] > 2.0 * margin;
            down &= e[i - 1] - e[i] > 2.0 * margin;
        }
    }
    if (!isfinite(margin) || !(up || down)) return 0;
    *cover_lo = cj_up(cj_fmin(e[0], e[p->n]) + margin);
    *cover_hi = cj_down(cj_fmax(e[0], e[p->n]) - margin);
    return 1;
}

/* Contacts along a flat stretch (a triple root, a near-coincidence) must not be split down to
 * pieces of size tol: there are about length / tol of them. When both pieces lie in a strip of
 * width <= tol along b's chord w, each is clipped to the part of it whose projection on w meets
 * the other's (a point outside cannot lie on the other piece), a few times. If then both are
 * monotone along w, every point p of one has a point q of the other at the same w (or an end
 * point, `overhang` further along w), so |p - q| <= (width + overhang) / |w|: with that <= tol
 * the pair is one contact, every root in it inside the clipped spans. -1 if the pair is proven
 * empty, 1 with the contact's box B and size, 0 if it is to be split as usual. */
static int flat_contact(run *R, const cj_qpiece *pa, const cj_qpiece *pb, cj_ivl B[2],
                        double *size) {
    int nb = pb->n;
    double w[2] = {pb->h[nb][0] - pb->h[0][0], pb->h[nb][1] - pb->h[0][1]}, v[2] = {-w[1], w[0]};
    double len = hypot(w[0], w[1]) * (1.0 - 0x1p-50); /* below |w| = |v| */
    if (!isfinite(len) || !(len > 0.0)) return 0;
    double amin, amax, bmin, bmax;
    project_poly(pa, v, &amin, &amax);
    project_poly(pb, v, &bmin, &bmax);
    if (!(cj_up(cj_fmax(amax, bmax) - cj_fmin(amin, bmin)) <= R->tol * len)) return 0;
    cj_qpiece c[2] = {*pa, *pb};
    for (int round = 0; round < 4; ++round)
        for (int k = 0; k < 2; ++k) {
            cj_qpiece *p = &c[k];
            double omin, omax, u0, u1;
            project_poly(&c[1 - k], w, &omin, &omax);
            int r = clip_band_n(p, p->n, w, omin, omax, &u0, &u1);
            if (r < 0) return -1; /* the pieces' projections on w are apart: no root here */
            if (r > 0 && p->b - p->a > 0x1p-40)
                cj_qpiece_sub(p, k == 0 ? R->qa->hmag : R->qb->hmag, u0, u1, p);
        }
    /* the clipped pieces are parts of the same curves, but their control points are new:
     * the strip is measured again */
    project_poly(&c[0], v, &amin, &amax);
    project_poly(&c[1], v, &bmin, &bmax);
    double width = cj_up(cj_fmax(amax, bmax) - cj_fmin(amin, bmin));
    double cover[2][2], reach[2][2];
    for (int k = 0; k < 2; ++k) {
        if (!monotone_along(&c[k], w, &cover[k][0], &cover[k][1])) return 0;
        project_poly(&c[k], w, &reach[k][0], &reach[k][1]);
    }
    double overhang = 0.0;
    for (int k = 0; k < 2; ++k) {
        overhang = cj_fmax(overhang, cj_up(cover[1 - k][0] - reach[k][0]));
        overhang = cj_fmax(overhang, cj_up(reach[k][1] - cover[1 - k][1]));
    }
    double dev = cj_up(cj_up(width + overhang) / len);
    if (!(dev <= R->tol)) return 0;
    /* a leaf's deviation is reported as 2 sqrt(2) times its size: the size that gives dev */
    B[0] = cj_qpiece_span(&c[0]);
    B[1] = cj_qpiece_span(&c[1]);
    *size = dev * 0x1.6a09e667f3bcdp-2 * (1.0 + 0x1p-50);
    return 1;
}

/* A flat pair may still hold crossings that a little more splitting certifies (y = x^2 against
 * y = 1e-12 at tol 1e-9: two roots 2e-6 apart in a stretch 6e-5 long within tol). The usual
 * search is run on it with a budget of FLAT_BUDGET boxes and no flat contacts inside; 1 if it
 * settled everything (its crossings kept), else 0 with its roots and leaves taken back (they
 * lie in the pair's box, which the contact then covers). */
#define FLAT_BUDGET 256
static int resolve_flat(run *R, const cj_qpiece *pa, const cj_qpiece *pb) {
    int roots = R->nroots, leaves = R->nleaves;
    long max_boxes = R->max_boxes;
    if (R->boxes + FLAT_BUDGET < max_boxes) R->max_boxes = R->boxes + FLAT_BUDGET;
    R->in_flat = 1;
    cj_isect_pair(R, pa, pb);
    R->in_flat = 0;
    R->max_boxes = max_boxes;
    /* the whole search's cap, or tables full (the pass runs again with room): as it stands */
    if (R->table_full || R->boxes > max_boxes) return 1;
    if (!R->capped && R->nleaves == leaves) return 1;
    R->capped = 0;
    R->nroots = roots;
    R->nleaves = leaves;
    return 0;
}

void cj_isect_pair(run *R, const cj_qpiece *pa, const cj_qpiece *pb) {
    /* clipped pieces live here: the clipping loop runs in this frame, only halving recurses */
    cj_qpiece clipped[2];
    int clip_ok = !R->self && !pa->rational && !pb->rational;
    for (;;) {
        if (R->capped) return;
        if (++R->boxes > R->max_boxes) {
            R->capped = 1;
            return;
        }
        if (in_overlap(R, pa, pb)) return;
        /* with clipping, its two projections along the chord normals do separated's work */
        if (clip_ok ? boxes_apart(pa, pb) : separated(pa, pb)) return;
        double ea = cj_isect_extent(pa), eb = cj_isect_extent(pb);
        if (clip_ok && pa->b - pa->a <= EARLY_WIDTH && pb->b - pb->a <= EARLY_WIDTH &&
            ea <= R->ext_a * KRAWCZYK_SIZE && eb <= R->ext_b * KRAWCZYK_SIZE &&
            settle(R, cj_qpiece_span(pa), cj_qpiece_span(pb), 0x1p-44) != 0)
            return;
        /* Bézier clipping first, the larger piece to the other's fat line and then the other
         * way, kept when it removes at least 30 % of a piece: it drops most boxes without a
         * root and shrinks those with a transversal one quadratically, so that Krawczyk is
         * mostly tried once, on a small box holding the root. */
        int clipped_one = 0;
        for (int side = 0; side < 2 && clip_ok && !clipped_one; ++side) {
            int clip_a = (side == 0) == (ea >= eb);
            const cj_qpiece *p = clip_a ? pa : pb, *o = clip_a ? pb : pa;
            double u0, u1;
            int r = clip_range(p, o, &u0, &u1);
            if (r < 0) return;
            /* below 2^-40 the clips' parameter rounding (perr) would start to count */
            if (r == 0 || u1 - u0 > 0.7 || p->b - p->a <= 0x1p-40) continue;
            cj_qpiece *c = &clipped[clip_a ? 0 : 1];
            cj_qpiece_sub(p, clip_a ? R->qa->hmag : R->qb->hmag, u0, u1, c);
            if (clip_a)
                pa = c;
            else
                pb = c;
            clipped_one = 1;
        }
        if (clipped_one) continue;
        break;
    }
    cj_ivl S = cj_qpiece_span(pa), T = cj_qpiece_span(pb);
    double ea = cj_isect_extent(pa), eb = cj_isect_extent(pb);
    /* Krawczyk needs the derivative enclosures to be narrow: try it once the pieces are small
     * against the curves (cheap exclusion does the coarse work). */
    if ((ea <= R->ext_a * KRAWCZYK_SIZE || pa->n <= 1) &&
        (eb <= R->ext_b * KRAWCZYK_SIZE || pb->n <= 1) && settle(R, S, T, 0x1p-44) != 0)
        return;
    if (clip_ok && !R->in_flat && ea <= R->ext_a * KRAWCZYK_SIZE &&
        eb <= R->ext_b * KRAWCZYK_SIZE) {
        cj_ivl B[2];
        double size;
        int flat = flat_contact(R, pa, pb, B, &size);
        if (flat < 0) return;
        if (flat > 0) {
            if (!resolve_flat(R, pa, pb)) cj_isect_add_leaf(R, B[0], B[1], size, 0);
            return;
        }
    }
    int can_a = ea > R->tol && pa->b - pa->a > MIN_WIDTH;
    int can_b = eb > R->tol && pb->b - pb->a > MIN_WIDTH;
    if (!can_a && !can_b) {
        /* clipping may have jumped past the sizes where Krawczyk succeeds on an ill-conditioned
         * crossing: a few wider boxes before calling it a contact */
        if (!R->self && (pa->perr > 0.0 || pb->perr > 0.0))
            for (double grow = 0x1p-36; grow <= 0x1p-20; grow *= 0x1p8)
                if (settle(R, S, T, grow) != 0) return;
        cj_isect_add_leaf(R, S, T, cj_fmax(ea, eb), 0);
        return;
    }
    cj_qpiece h[2];
    if (can_a && (!can_b || ea >= eb)) {
        cj_qpiece_halve(pa, R->qa->hmag, &h[0], &h[1]);
        cj_isect_pair(R, &h[0], pb);
        cj_isect_pair(R, &h[1], pb);
    } else {
        cj_qpiece_halve(pb, R->qb->hmag, &h[0], &h[1]);
        cj_isect_pair(R, pa, &h[0]);
        cj_isect_pair(R, pa, &h[1]);
    }
}

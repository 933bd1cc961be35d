/* Certified nearest point on a plane curve: branch and bound over exact halvings (nearest.h). */
#include "query_internal.h"

#include "casteljau/bezier.h"
#include "casteljau/nearest.h"
#include "casteljau/rational.h"
#include "error_internal.h"

#include <assert.h>

#define MIN_WIDTH  0x1p-52
#define MAX_PIECES 4000000L

typedef struct nrun {
    const cj_qctx *q;
    const cj_bezier2 *c;
    double qp[2];
    double tol;
    double best, best_t;
    double lower;
    long pieces;
} nrun;

/* Proven upper bound of |c(t) - q|; pt gets the rounded point. */
static double upper_at(const nrun *N, double t, double pt[2]) {
    cj_ivl p[2];
    if (!cj_qctx_point(N->q, t, p)) return INFINITY;
    cj_ivl dx = cj_isub(p[0], cj_iv(N->qp[0])), dy = cj_isub(p[1], cj_iv(N->qp[1]));
    double mx = cj_imag(dx), my = cj_imag(dy);
    if (pt) {
        pt[0] = cj_imid(p[0]);
        pt[1] = cj_imid(p[1]);
    }
    return cj_up(sqrt(cj_up(cj_up(mx * mx) + cj_up(my * my))));
}

/* Plain (unproven) c, c' and c'' of a polynomial curve at t by de Casteljau on the control
 * points: the guesses the proofs start from. d holds x y x' y' x'' y''. */
static void poly_derivs(const cj_bezier2 *c, double t, double d[6]) {
    int n = c->degree;
    double w[CJ_QUERY_MAXN + 1][2];
    w[0][0] = c->pts[0];
    w[0][1] = c->pts[1];
    for (int i = 1; i <= n; ++i) w[i][0] = c->pts[2 * i], w[i][1] = c->pts[2 * i + 1];
    d[2] = d[3] = d[4] = d[5] = 0.0;
    double s = 1.0 - t;
    for (int r = n; r > 0; --r) {
        if (r == 2)
            for (int k = 0; k < 2; ++k)
                d[4 + k] = (double)n * (n - 1) * (w[2][k] - 2.0 * w[1][k] + w[0][k]);
        if (r == 1)
            for (int k = 0; k < 2; ++k) d[2 + k] = (double)n * (w[1][k] - w[0][k]);
        for (int i = 0; i < r; ++i)
            for (int k = 0; k < 2; ++k) w[i][k] = s * w[i][k] + t * w[i + 1][k];
    }
    d[0] = w[0][0];
    d[1] = w[0][1];
}

/* Newton on g(t) = (c(t) - q) . c'(t) from t, clamped to [0,1]; returns the polished t. */
static double polish(const nrun *N, double t) {
    const cj_bezier2 *c = N->c;
    for (int it = 0; it < 8; ++it) {
        double d[6];
        if (c->weights) {
            cj_rbezier r = cj_rbezier_view(c->degree, 2, c->pts, c->weights);
            if (cj_rbezier_eval_derivs(&r, t, 2, d) != CJ_OK) break;
        } else {
            poly_derivs(c, t, d);
        }
        double ex = d[0] - N->qp[0], ey = d[1] - N->qp[1];
        double g = ex * d[2] + ey * d[3];
        double gp = d[2] * d[2] + d[3] * d[3] + ex * d[4] + ey * d[5];
        if (!(gp > 0.0)) break;
        double tn = cj_fmin(1.0, cj_fmax(0.0, t - g / gp));
        if (!isfinite(tn) || tn == t) break;
        int done = fabs(tn - t) <= 0x1p-52;
        t = tn;
        if (done) break;
    }
    return t;
}

static void offer(nrun *N, double t) {
    double u = upper_at(N, t, NULL);
    if (u < N->best) {
        N->best = u;
        N->best_t = t;
    }
}

/* Proven lower bound of |x - q| over the hull of the piece's enclosed control points: the
 * larger of the distance to their bounding box and the gap along the direction from q to the
 * nearest point of the chord. */
static double piece_lower(const nrun *N, const cj_qpiece *p) {
    double lo[CJ_QUERY_MAXN + 1][2], hi[CJ_QUERY_MAXN + 1][2];
    cj_qpiece_boxes(p, lo, hi);
    int n = p->n;
    double blo[2] = {INFINITY, INFINITY}, bhi[2] = {-INFINITY, -INFINITY};
    for (int i = 0; i <= n; ++i)
        for (int k = 0; k < 2; ++k) {
            blo[k] = cj_fmin(blo[k], lo[i][k]);
            bhi[k] = cj_fmax(bhi[k], hi[i][k]);
        }
    double g[2];
    for (int k = 0; k < 2; ++k) {
        double below = cj_down(blo[k] - N->qp[k]), above = cj_down(N->qp[k] - bhi[k]);
        g[k] = cj_fmax(0.0, cj_fmax(below, above));
    }
    double box = cj_fmax(
        0.0, cj_down(sqrt(cj_fmax(0.0, cj_down(cj_down(g[0] * g[0]) + cj_down(g[1] * g[1]))))));
    /* direction to the nearest point of the chord (midpoints of the end boxes) */
    double a[2], b[2];
    for (int k = 0; k < 2; ++k) {
        a[k] = 0.5 * lo[0][k] + 0.5 * hi[0][k];
        b[k] = 0.5 * lo[n][k] + 0.5 * hi[n][k];
    }
    double ab[2] = {b[0] - a[0], b[1] - a[1]};
    double len2 = ab[0] * ab[0] + ab[1] * ab[1];
    double lam = len2 > 0 ? ((N->qp[0] - a[0]) * ab[0] + (N->qp[1] - a[1]) * ab[1]) / len2 : 0.0;
    lam = cj_fmin(1.0, cj_fmax(0.0, lam));
    double v[2] = {a[0] + lam * ab[0] - N->qp[0], a[1] + lam * ab[1] - N->qp[1]};
    double gap = 0.0;
    if (isfinite(v[0]) && isfinite(v[1]) && (v[0] != 0.0 || v[1] != 0.0)) {
        double mn = INFINITY;
        for (int i = 0; i <= n; ++i) {
            cj_ivl d =
                cj_iadd(cj_imul(cj_iv(v[0]), cj_isub(cj_iv2(lo[i][0], hi[i][0]), cj_iv(N->qp[0]))),
                        cj_imul(cj_iv(v[1]), cj_isub(cj_iv2(lo[i][1], hi[i][1]), cj_iv(N->qp[1]))));
            mn = cj_fmin(mn, d.lo);
        }
        if (mn > 0.0) {
            double vn = cj_up(sqrt(cj_up(cj_up(v[0] * v[0]) + cj_up(v[1] * v[1]))));
            gap = cj_down(mn / vn);
        }
    }
    return cj_fmax(box, gap);
}

/* The sign pattern of g(u) = (c(u) - q) . c'(u) over a polynomial piece. g has degree 2n - 1
 * with Bernstein coefficients
 *   g_k = sum over i + j = k of C(n,i) C(n-1,j) / C(2n-1,k) (P_i - q) . n (P_{j+1} - P_j),
 * enclosed here (without the positive factors n / C(2n-1,k)) in interval arithmetic over the
 * enclosed P. Returns -1 if some g_k has no proven sign, else the number of sign changes of the
 * sequence, with *first the sign of g_0. By Descartes' rule for the Bernstein basis, 0 changes
 * means g has no root on the piece (the distance is monotone) and 1 change exactly one. */
static int g_signs(const nrun *N, const cj_qpiece *p, int *first) {
    int n = p->n;
    if (p->rational || n < 1 || n > 24) return -1;
    cj_ivl A[CJ_QUERY_MAXN + 1][2], D[CJ_QUERY_MAXN][2];
    for (int i = 0; i <= n; ++i)
        for (int k = 0; k < 2; ++k)
            A[i][k] = cj_iv2(cj_down(p->h[i][k] - p->err[k]), cj_up(p->h[i][k] + p->err[k]));
    for (int j = 0; j < n; ++j)
        for (int k = 0; k < 2; ++k) D[j][k] = cj_isub(A[j + 1][k], A[j][k]);
    for (int i = 0; i <= n; ++i)
        for (int k = 0; k < 2; ++k) A[i][k] = cj_isub(A[i][k], cj_iv(N->qp[k]));
    double binom_n[CJ_QUERY_MAXN + 1], binom_m[CJ_QUERY_MAXN + 1];
    binom_n[0] = binom_m[0] = 1.0; /* exact: C(24, i) < 2^53 */
    for (int i = 1; i <= n; ++i) {
        binom_n[i] = binom_n[i - 1] * (n - i + 1) / i;
        binom_m[i] = i < n ? binom_m[i - 1] * (n - i) / i : 0.0;
    }
    int sign = 0, changes = 0;
    for (int k = 0; k <= 2 * n - 1; ++k) {
        cj_ivl g = cj_iv(0.0);
        for (int i = k - (n - 1) > 0 ? k - (n - 1) : 0; i <= n && i <= k; ++i) {
            int j = k - i;
            cj_ivl dot = cj_iadd(cj_imul(A[i][0], D[j][0]), cj_imul(A[i][1], D[j][1]));
            /* C(n,i) C(n-1,j) <= 2^47: the product of two exact integers, enclosed */
            double w = binom_n[i] * binom_m[j];
            g = cj_iadd(g, cj_imul(cj_iv2(cj_down(w), cj_up(w)), dot));
        }
        int sg = g.lo > 0.0 ? 1 : g.hi < 0.0 ? -1 : 0;
        if (sg == 0) return -1;
        if (k == 0)
            *first = sg;
        else if (sg != sign)
            ++changes;
        sign = sg;
    }
    return changes;
}

/* Enclosure of g(t) = (c(t) - q) . c'(t) at the double t: its sign, 0 if unproven. */
static int g_sign_at(const nrun *N, double t) {
    cj_ivl p[2], d[2];
    if (!cj_qctx_eval(N->q, cj_iv(t), p, d)) return 0;
    cj_ivl g = cj_iadd(cj_imul(cj_isub(p[0], cj_iv(N->qp[0])), d[0]),
                       cj_imul(cj_isub(p[1], cj_iv(N->qp[1])), d[1]));
    return g.lo > 0.0 ? 1 : g.hi < 0.0 ? -1 : 0;
}

/* Proven lower bound of |x - q| over the box [lo, hi]. */
static double box_lower(const nrun *N, const double lo[2], const double hi[2]) {
    double g[2];
    for (int k = 0; k < 2; ++k) {
        double below = cj_down(lo[k] - N->qp[k]), above = cj_down(N->qp[k] - hi[k]);
        g[k] = cj_fmax(0.0, cj_fmax(below, above));
    }
    return cj_fmax(
        0.0, cj_down(sqrt(cj_fmax(0.0, cj_down(cj_down(g[0] * g[0]) + cj_down(g[1] * g[1]))))));
}

static void search(nrun *N, const cj_qpiece *p, double lb) {
    if (!(lb >= 0.0)) lb = 0.0; /* a NaN bound proves nothing */
    if (++N->pieces > MAX_PIECES || lb >= N->best - N->tol || p->b - p->a <= MIN_WIDTH) {
        N->lower = cj_fmin(N->lower, lb);
        return;
    }
    double lb_piece = -1.0; /* a proven lower bound over the piece from the roots of g */
    int first = 0, changes = g_signs(N, p, &first);
    if (changes == 0 || (changes == 1 && first > 0)) {
        /* no local minimum inside: the minimum is at an end, whose control point is c there
         * within err */
        lb_piece = INFINITY;
        for (int e = 0; e <= p->n; e += p->n) {
            if (changes == 0 && (first > 0) != (e == 0)) continue;
            offer(N, e == 0 ? p->a : p->b);
            double lo[2], hi[2];
            for (int k = 0; k < 2; ++k) {
                lo[k] = cj_down(p->h[e][k] - p->err[k]);
                hi[k] = cj_up(p->h[e][k] + p->err[k]);
            }
            lb_piece = cj_fmin(lb_piece, box_lower(N, lo, hi));
        }
    } else if (changes == 1) {
        /* exactly one root t* of g, where g goes from - to +: the one minimum of the piece.
         * A Newton guess, and signs of g proven on both sides of it, enclose t*. */
        double t = polish(N, 0.5 * (p->a + p->b));
        for (double delta = 0x1p-40; delta <= 0x1p-20; delta *= 0x1p10) {
            double lo = cj_fmax(p->a, t - delta), hi = cj_fmin(p->b, t + delta);
            if (!(lo < hi) || g_sign_at(N, lo) >= 0 || g_sign_at(N, hi) <= 0) continue;
            offer(N, t);
            cj_ivl c[2];
            if (!cj_qctx_eval(N->q, cj_iv2(lo, hi), c, NULL)) break;
            double blo[2] = {c[0].lo, c[1].lo}, bhi[2] = {c[0].hi, c[1].hi};
            lb_piece = box_lower(N, blo, bhi);
            break;
        }
    }
    if (lb_piece >= 0.0) {
        lb_piece = cj_fmax(lb, lb_piece);
        if (lb_piece >= N->best - N->tol) {
            N->lower = cj_fmin(N->lower, lb_piece);
            return;
        }
    }
    double m = 0.5 * (p->a + p->b);
    double u = upper_at(N, m, NULL);
    if (u < N->best) {
        N->best = u;
        N->best_t = m;
        offer(N, polish(N, m));
    }
    if (lb >= N->best - N->tol) {
        N->lower = cj_fmin(N->lower, lb);
        return;
    }
    cj_qpiece h[2];
    cj_qpiece_halve(p, N->q->hmag, &h[0], &h[1]);
    double l0 = piece_lower(N, &h[0]), l1 = piece_lower(N, &h[1]);
    if (l0 <= l1) {
        search(N, &h[0], l0);
        search(N, &h[1], l1);
    } else {
        search(N, &h[1], l1);
        search(N, &h[0], l0);
    }
}

static cj_status nearest_impl(const cj_bezier2 *c, const double q[2], double tol, cj_nearest *out) {
    if (cj_nearest_by_roots(c, q, tol, out)) return CJ_OK;
    cj_qctx ctx;
    cj_status st = cj_qctx_init_first(&ctx, c, "curve");
    if (st != CJ_OK) return st;
    if (!isfinite(q[0]) || !isfinite(q[1]))
        return cj_fail(CJ_ERR_NONFINITE, "query point (%g, %g) is not finite", q[0], q[1]);
    double scale = cj_fmax(ctx.scale, cj_fmax(fabs(q[0]), fabs(q[1])));
    if (!isfinite(tol)) return cj_fail(CJ_ERR_NONFINITE, "tol is %s", isnan(tol) ? "NaN" : "inf");
    if (!(tol > 0.0)) return cj_fail(CJ_ERR_ARGUMENT, "tol %g must be > 0", tol);
    if (tol < scale * 0x1p-40)
        return cj_fail(CJ_ERR_ARGUMENT,
                       "tol %g is below what doubles resolve at the scale %g of the curve and "
                       "the point (the smallest is %g)",
                       tol, scale, scale * 0x1p-40);
    nrun N;
    N.q = &ctx;
    N.c = c;
    N.qp[0] = q[0];
    N.qp[1] = q[1];
    N.tol = tol;
    N.best = INFINITY;
    N.best_t = 0.0;
    N.lower = INFINITY;
    N.pieces = 0;
    /* a good first upper bound: the best of a few samples, polished */
    int ns = 2 * c->degree + 2;
    double t0 = 0.0, d0 = INFINITY;
    for (int i = 0; i <= ns; ++i) { /* plain evaluations pick the start; bounds come later */
        double t = (double)i / ns, pt[2];
        cj_status es;
        if (c->weights) {
            cj_rbezier r = cj_rbezier_view(c->degree, 2, c->pts, c->weights);
            es = cj_rbezier_eval(&r, t, pt);
        } else {
            double d[6];
            poly_derivs(c, t, d);
            pt[0] = d[0], pt[1] = d[1], es = CJ_OK;
        }
        double dd = (pt[0] - q[0]) * (pt[0] - q[0]) + (pt[1] - q[1]) * (pt[1] - q[1]);
        if (es == CJ_OK && dd < d0) d0 = dd, t0 = t;
    }
    offer(&N, t0);
    offer(&N, polish(&N, t0));
    cj_qpiece root;
    cj_qpiece_root(&ctx, &root);
    search(&N, &root, piece_lower(&N, &root));
    double lower = cj_fmin(N.lower, N.best);
    if (!isfinite(N.best))
        return cj_fail(CJ_ERR_RANGE, "the curve's distance to the point overflows");
    out->t = N.best_t;
    upper_at(&N, N.best_t, out->point);
    out->distance = N.best;
    out->lower = lower;
    out->pieces = N.pieces;
    if (N.pieces > MAX_PIECES)
        return cj_fail(CJ_ERR_CAP,
                       "nearest point search hit its cap of %ld pieces; the bounds "
                       "written are valid but %g apart",
                       MAX_PIECES, N.best - lower);
    return CJ_OK;
}

cj_status cj_nearest_curve(const cj_bezier2 *c, const double q[2], double tol, cj_nearest *out) {
    assert(c && q && out);
    double sc = cj_fmax(cj_query_scale(c), cj_fmax(fabs(q[0]), fabs(q[1])));
    int k = cj_query_scale_exp(sc);
    if (k == 0) return nearest_impl(c, q, tol, out);
    /* tiny curves: scaled up by 2^k (exact), so the squared distances stay normal */
    double pts[2 * (CJ_QUERY_MAX_DEGREE + 1)], qs[2] = {ldexp(q[0], k), ldexp(q[1], k)};
    cj_bezier2 C = cj_query_scaled(c, k, pts);
    cj_nearest r;
    cj_status st = nearest_impl(&C, qs, ldexp(tol, k), &r);
    if (st != CJ_OK && st != CJ_ERR_CAP) return st;
    r.point[0] = ldexp(r.point[0], -k);
    r.point[1] = ldexp(r.point[1], -k);
    /* scaling down rounds (maybe into subnormals): step the bounds outwards */
    r.distance = cj_up(ldexp(r.distance, -k));
    r.lower = cj_fmax(0.0, cj_down(ldexp(r.lower, -k)));
    *out = r;
    return st;
}

#include "query_oracle.h"

#include <assert.h>
#include <math.h>
#include <stdlib.h>

#define QO_PREC 256
#define QO_MAXN 64

/* Homogeneous de Casteljau at t: H (3 coordinates) and, if D, the derivative of H. */
static void homog(const qo_curve *c, const mpfr_t t, mpfr_t H[3], mpfr_t D[3]) {
    int n = c->n;
    mpfr_t w[QO_MAXN + 1][3], s, a, b;
    mpfr_inits2(QO_PREC, s, a, b, (mpfr_ptr)0);
    mpfr_ui_sub(s, 1, t, MPFR_RNDN);
    for (int i = 0; i <= n; ++i)
        for (int k = 0; k < 3; ++k) {
            mpfr_init2(w[i][k], QO_PREC);
            double wi = c->w ? c->w[i] : 1.0;
            if (k < 2) {
                mpfr_set_d(w[i][k], c->pts[2 * i + k], MPFR_RNDN);
                mpfr_mul_d(w[i][k], w[i][k], wi, MPFR_RNDN);
            } else {
                mpfr_set_d(w[i][k], wi, MPFR_RNDN);
            }
        }
    for (int r = n; r > 0; --r) {
        if (r == 1 && D)
            for (int k = 0; k < 3; ++k) {
                mpfr_sub(D[k], w[1][k], w[0][k], MPFR_RNDN);
                mpfr_mul_ui(D[k], D[k], (unsigned long)n, MPFR_RNDN);
            }
        for (int i = 0; i < r; ++i)
            for (int k = 0; k < 3; ++k) {
                mpfr_mul(a, w[i][k], s, MPFR_RNDN);
                mpfr_mul(b, w[i + 1][k], t, MPFR_RNDN);
                mpfr_add(w[i][k], a, b, MPFR_RNDN);
            }
    }
    if (n == 0 && D)
        for (int k = 0; k < 3; ++k) mpfr_set_ui(D[k], 0, MPFR_RNDN);
    for (int k = 0; k < 3; ++k) mpfr_set(H[k], w[0][k], MPFR_RNDN);
    for (int i = 0; i <= n; ++i)
        for (int k = 0; k < 3; ++k) mpfr_clear(w[i][k]);
    mpfr_clears(s, a, b, (mpfr_ptr)0);
}

void qo_eval(const qo_curve *c, const mpfr_t t, mpfr_t p[2], mpfr_t d[2]) {
    assert(c->n <= QO_MAXN);
    mpfr_t H[3], D[3], tmp;
    for (int k = 0; k < 3; ++k) mpfr_inits2(QO_PREC, H[k], D[k], (mpfr_ptr)0);
    mpfr_init2(tmp, QO_PREC);
    homog(c, t, H, D);
    for (int k = 0; k < 2; ++k) {
        mpfr_div(p[k], H[k], H[2], MPFR_RNDN);
        if (d) { /* (D_k - p_k D_w) / w */
            mpfr_mul(tmp, p[k], D[2], MPFR_RNDN);
            mpfr_sub(d[k], D[k], tmp, MPFR_RNDN);
            mpfr_div(d[k], d[k], H[2], MPFR_RNDN);
        }
    }
    for (int k = 0; k < 3; ++k) mpfr_clears(H[k], D[k], (mpfr_ptr)0);
    mpfr_clear(tmp);
}

double qo_newton(const qo_curve *a, const qo_curve *b, double s0, double t0, mpfr_t s, mpfr_t t) {
    mpfr_t pa[2], pb[2], da[2], db[2], F[2], det, x, y, tmp;
    for (int k = 0; k < 2; ++k) mpfr_inits2(QO_PREC, pa[k], pb[k], da[k], db[k], F[k], (mpfr_ptr)0);
    mpfr_inits2(QO_PREC, det, x, y, tmp, (mpfr_ptr)0);
    mpfr_set_prec(s, QO_PREC);
    mpfr_set_prec(t, QO_PREC);
    mpfr_set_d(s, s0, MPFR_RNDN);
    mpfr_set_d(t, t0, MPFR_RNDN);
    double res = INFINITY, scale = 0.0;
    for (int i = 0; i <= a->n; ++i)
        scale = fmax(scale, fmax(fabs(a->pts[2 * i]), fabs(a->pts[2 * i + 1])));
    for (int it = 0; it < 40; ++it) {
        qo_eval(a, s, pa, da);
        qo_eval(b, t, pb, db);
        for (int k = 0; k < 2; ++k) mpfr_sub(F[k], pa[k], pb[k], MPFR_RNDN);
        res = fabs(mpfr_get_d(F[0], MPFR_RNDN)) + fabs(mpfr_get_d(F[1], MPFR_RNDN));
        /* J = [da, -db]; solve J (ds, dt) = F */
        mpfr_mul(det, da[0], db[1], MPFR_RNDN);
        mpfr_mul(tmp, da[1], db[0], MPFR_RNDN);
        mpfr_sub(det, tmp, det, MPFR_RNDN); /* det(J) = -da0 db1 + db0 da1 */
        if (mpfr_zero_p(det)) break;
        /* ds = (F0 (-db1) - (-db0) F1) / det, dt = (da0 F1 - da1 F0) / det */
        mpfr_mul(x, F[1], db[0], MPFR_RNDN);
        mpfr_mul(tmp, F[0], db[1], MPFR_RNDN);
        mpfr_sub(x, x, tmp, MPFR_RNDN);
        mpfr_div(x, x, det, MPFR_RNDN);
        mpfr_mul(y, da[0], F[1], MPFR_RNDN);
        mpfr_mul(tmp, da[1], F[0], MPFR_RNDN);
        mpfr_sub(y, y, tmp, MPFR_RNDN);
        mpfr_div(y, y, det, MPFR_RNDN);
        mpfr_sub(s, s, x, MPFR_RNDN);
        mpfr_sub(t, t, y, MPFR_RNDN);
        if (res < 1e-72 * scale) break;
    }
    for (int k = 0; k < 2; ++k) mpfr_clears(pa[k], pb[k], da[k], db[k], F[k], (mpfr_ptr)0);
    mpfr_clears(det, x, y, tmp, (mpfr_ptr)0);
    return res;
}

double qo_distance(const qo_curve *c, double t, const double q[2]) {
    mpfr_t T, p[2], d;
    mpfr_inits2(QO_PREC, T, p[0], p[1], d, (mpfr_ptr)0);
    mpfr_set_d(T, t, MPFR_RNDN);
    qo_eval(c, T, p, NULL);
    mpfr_sub_d(p[0], p[0], q[0], MPFR_RNDN);
    mpfr_sub_d(p[1], p[1], q[1], MPFR_RNDN);
    mpfr_hypot(d, p[0], p[1], MPFR_RNDN);
    double r = mpfr_get_d(d, MPFR_RNDN);
    mpfr_clears(T, p[0], p[1], d, (mpfr_ptr)0);
    return r;
}

typedef struct lp {
    long double x, y;
} lp;

static lp leval(const qo_curve *c, long double t) {
    long double w[QO_MAXN + 1][3];
    for (int i = 0; i <= c->n; ++i) {
        long double wi = c->w ? c->w[i] : 1.0L;
        w[i][0] = wi * c->pts[2 * i];
        w[i][1] = wi * c->pts[2 * i + 1];
        w[i][2] = wi;
    }
    for (int r = c->n; r > 0; --r)
        for (int i = 0; i < r; ++i)
            for (int k = 0; k < 3; ++k) w[i][k] = (1 - t) * w[i][k] + t * w[i + 1][k];
    lp p = {w[0][0] / w[0][2], w[0][1] / w[0][2]};
    return p;
}

/* max |c''| bound for a polynomial curve: n(n-1) max |second differences|. Rational curves get
 * a sampled estimate times 4 (only used to flag ambiguity, never to decide a pass). */
static double second_bound(const qo_curve *c) {
    int n = c->n;
    double m = 0.0;
    if (!c->w) {
        for (int i = 0; i + 2 <= n; ++i)
            for (int k = 0; k < 2; ++k)
                m = fmax(m, fabs(c->pts[2 * (i + 2) + k] - 2 * c->pts[2 * (i + 1) + k] +
                                 c->pts[2 * i + k]));
        return (double)n * (n - 1) * m * 1.4142135623730951;
    }
    for (int j = 0; j <= 256; ++j) {
        long double t = j / 256.0L, h = 1e-4L;
        lp a = leval(c, t - h), b = leval(c, t), d = leval(c, t + h);
        m = fmax(m, (double)(hypotl(a.x - 2 * b.x + d.x, a.y - 2 * b.y + d.y) / (h * h)));
    }
    return 4.0 * m;
}

static long double orient(lp a, lp b, lp c) {
    return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

static int crossings(const qo_curve *a, const qo_curve *b, int self, int N, double *st, int cap,
                     double *errbound) {
    lp *pa = malloc(sizeof(lp) * (size_t)(N + 1)), *pb = malloc(sizeof(lp) * (size_t)(N + 1));
    assert(pa && pb);
    for (int i = 0; i <= N; ++i) {
        pa[i] = leval(a, (long double)i / N);
        pb[i] = leval(b, (long double)i / N);
    }
    double h = 1.0 / N;
    *errbound = h * h / 8 * fmax(second_bound(a), second_bound(b));
    /* chunks of 16 segments with bounding boxes prune the segment pairs */
    enum { C = 16 };
    int nch = (N + C - 1) / C, count = 0;
    for (int ca = 0; ca < nch; ++ca) {
        long double ax0 = INFINITY, ax1 = -INFINITY, ay0 = INFINITY, ay1 = -INFINITY;
        int ia0 = ca * C, ia1 = ia0 + C < N ? ia0 + C : N;
        for (int i = ia0; i <= ia1; ++i) {
            ax0 = fminl(ax0, pa[i].x), ax1 = fmaxl(ax1, pa[i].x);
            ay0 = fminl(ay0, pa[i].y), ay1 = fmaxl(ay1, pa[i].y);
        }
        for (int cb = 0; cb < nch; ++cb) {
            long double bx0 = INFINITY, bx1 = -INFINITY, by0 = INFINITY, by1 = -INFINITY;
            int ib0 = cb * C, ib1 = ib0 + C < N ? ib0 + C : N;
            for (int j = ib0; j <= ib1; ++j) {
                bx0 = fminl(bx0, pb[j].x), bx1 = fmaxl(bx1, pb[j].x);
                by0 = fminl(by0, pb[j].y), by1 = fmaxl(by1, pb[j].y);
            }
            if (ax1 < bx0 || bx1 < ax0 || ay1 < by0 || by1 < ay0) continue;
            for (int i = ia0; i < ia1; ++i)
                for (int j = ib0; j < ib1; ++j) {
                    if (self && j < i + 2) continue; /* s < t, neighbours share a sample */
                    long double o1 = orient(pa[i], pa[i + 1], pb[j]);
                    long double o2 = orient(pa[i], pa[i + 1], pb[j + 1]);
                    long double o3 = orient(pb[j], pb[j + 1], pa[i]);
                    long double o4 = orient(pb[j], pb[j + 1], pa[i + 1]);
                    /* half-open segments [start, end): a crossing through a shared sample is
                     * counted once */
                    int ca_ = (o1 < 0) != (o2 < 0), cb_ = (o3 < 0) != (o4 < 0);
                    if (!ca_ || !cb_) continue;
                    if (count < cap) {
                        long double u = o3 / (o3 - o4), v = o1 / (o1 - o2);
                        st[2 * count] = (double)((i + u) / N);
                        st[2 * count + 1] = (double)((j + v) / N);
                    }
                    ++count;
                }
        }
    }
    free(pa);
    free(pb);
    return count;
}

int qo_polyline_crossings(const qo_curve *a, const qo_curve *b, int N, double *st, int cap,
                          double *errbound) {
    return crossings(a, b, 0, N, st, cap, errbound);
}

int qo_polyline_self_crossings(const qo_curve *a, int N, double *st, int cap, double *errbound) {
    return crossings(a, a, 1, N, st, cap, errbound);
}

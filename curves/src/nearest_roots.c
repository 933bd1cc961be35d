/* The certified nearest point of a polynomial curve by the roots of g(t) = (c(t) - q) . c'(t):
 * the fast path of cj_nearest_curve (nearest.c), which falls back to its branch and bound
 * whenever a step here cannot be proven.
 *
 * Why this is a global certificate: |c(t) - q|^2 / 2 has derivative g, so an interior minimiser
 * is a root of g. g is a polynomial of degree m = 2n - 1 whose Bernstein coefficients are
 * computed once, in doubles, with a bound E on their error. [0,1] is split by exact halvings
 * (de Casteljau on the m + 1 scalars, E grown by the rounding of each level) until, on every
 * piece, each coefficient has a proven sign (|g_k| > E) and the sequence changes sign at most
 * once. By Descartes' rule for the Bernstein basis, no change means g has no root on the closed
 * piece; one change from + to - a single simple root where g decreases (a local maximum of the
 * distance); one change from - to + a single simple root where it increases (the piece's only
 * local minimum). So the global minimum is at t = 0, t = 1, or at the minimum of one of the
 * latter pieces; that minimum is bracketed by Newton with proven signs of g on both sides, and
 * the distance over the bracket is bounded below by the distance at its centre minus the
 * bracket's radius times a bound of |c'|. */
#include "query_internal.h"

#include "casteljau/nearest.h"

#include <float.h>
#include <stddef.h>

#define U       0x1p-53
#define MAXM    (2 * CJ_NEAREST_ROOTS_MAXN - 1)
#define MAXDEEP 40  /* halvings: a piece narrower than 2^-40 that is still unresolved gives up */
#define MAXWORK 400 /* pieces examined before giving up (a near-double root, a flat g) */

static inline double maxd(double a, double b) {
    return a > b ? a : b;
}

typedef struct gpiece {
    double a, w; /* the piece is [a, a + w], w a power of two */
    double e;    /* error bound of its coefficients */
    int depth;
    double g[MAXM + 1];
} gpiece;

static double max_abs(const double *g, int m) {
    double M = 0.0;
    for (int k = 0; k <= m; ++k) M = maxd(M, fabs(g[k]));
    return M;
}

/* Halves the piece's coefficients (exact midpoint 1/2): each level of the triangle rounds each
 * average by at most u |value|, and averages never exceed the largest coefficient M in
 * magnitude, so the error grows by at most m u M (padded, plus subnormal rounding). */
static void halve(const gpiece *p, int m, gpiece *left, gpiece *right) {
    double w[MAXM + 1];
    for (int k = 0; k <= m; ++k) w[k] = p->g[k];
    left->g[0] = w[0];
    right->g[m] = w[m];
    for (int lev = 1; lev <= m; ++lev) {
        for (int k = 0; k + lev <= m; ++k) w[k] = 0.5 * (w[k] + w[k + 1]);
        left->g[lev] = w[0];
        right->g[m - lev] = w[m - lev];
    }
    double e = p->e + (double)(m + 1) * (U * max_abs(p->g, m) * 1.0001 + 0x1p-1074);
    double hw = 0.5 * p->w;
    left->a = p->a;
    right->a = p->a + hw; /* exact: dyadic with at most 41 bits after the point */
    left->w = right->w = hw;
    left->e = right->e = e;
    left->depth = right->depth = p->depth + 1;
}

/* g and g' (per unit of the piece's own parameter) at u in [0,1] by de Casteljau; *err bounds
 * the error of the value: with s = 1 - u off by at most u/2 and each combination rounded, a
 * level adds at most 3.1 u M, and the coefficients' error e passes through unchanged. */
static double eval_g(const gpiece *p, int m, double u, double *deriv, double *err) {
    double w[MAXM + 1], s = 1.0 - u;
    for (int k = 0; k <= m; ++k) w[k] = p->g[k];
    double d = 0.0;
    for (int lev = m; lev > 0; --lev) {
        if (lev == 1) d = (double)m * (w[1] - w[0]);
        for (int k = 0; k < lev; ++k) w[k] = s * w[k] + u * w[k + 1];
    }
    if (deriv) *deriv = d;
    if (err) *err = (p->e + (double)m * (3.2 * U * max_abs(p->g, m) + 0x1p-1073)) * 1.0001;
    return w[0];
}

typedef struct best {
    int n;
    const double (*A)[2]; /* P_i - q, each rounded once */
    double aerr;          /* bound of c(t) - q's error by de Casteljau on A, t in [0,1] */
    double upper, t, lower;
    double point[2]; /* c(t) - q at the best t, unrounded back */
} best;

/* Encloses |c(t) - q| at the double t in [0,1]: [*lo, return value]; v gets c(t) - q. De
 * Casteljau on A: with s = 1 - t off by at most u/2, each level adds at most 3.1 u max|A| and the
 * error of A itself (u max|A|) passes through, so n levels stay within aerr. */
static double dist_at(const best *B, double t, double *lo, double v[2]) {
    int n = B->n;
    double w[CJ_NEAREST_ROOTS_MAXN + 1][2], s = 1.0 - t;
    for (int i = 0; i <= n; ++i) w[i][0] = B->A[i][0], w[i][1] = B->A[i][1];
    for (int lev = n; lev > 0; --lev)
        for (int i = 0; i < lev; ++i) {
            w[i][0] = s * w[i][0] + t * w[i + 1][0];
            w[i][1] = s * w[i][1] + t * w[i + 1][1];
        }
    double hi2 = 0.0, lo2 = 0.0;
    for (int k = 0; k < 2; ++k) {
        double mag = cj_up(fabs(w[0][k]) + B->aerr), gap = cj_down(fabs(w[0][k]) - B->aerr);
        gap = maxd(gap, 0.0);
        hi2 = cj_up(hi2 + cj_up(mag * mag));
        lo2 = cj_down(lo2 + cj_down(gap * gap));
    }
    v[0] = w[0][0];
    v[1] = w[0][1];
    *lo = maxd(0.0, cj_down(sqrt(maxd(0.0, lo2))));
    return cj_up(sqrt(hi2));
}

static void offer(best *B, double t, double radius, double speed) {
    double lo, v[2], hi = dist_at(B, t, &lo, v);
    if (hi < B->upper) {
        B->upper = hi;
        B->t = t;
        B->point[0] = v[0];
        B->point[1] = v[1];
    }
    double lb = maxd(0.0, cj_down(lo - cj_up(radius * speed)));
    if (lb < B->lower) B->lower = lb;
}

/* The one minimum of a piece where g goes from - to +: safeguarded Newton in the piece's
 * parameter, then proven signs of g at u - δ and u + δ (or the piece's own ends, whose signs are
 * proven already). Returns 0 if no bracket narrow enough for tol could be proven. */
static int settle_min(best *B, const gpiece *p, int m, double speed, double tol) {
    double lo = 0.0, hi = 1.0, u = 0.5;
    for (int it = 0; it < 60; ++it) {
        double d, g = eval_g(p, m, u, &d, NULL);
        if (g < 0.0)
            lo = u;
        else if (g > 0.0)
            hi = u;
        else
            break;
        double un = d > 0.0 ? u - g / d : -1.0;
        if (fabs(un - u) <= 0x1p-50) { /* converged (a step this small stays in the bracket) */
            u = fmin(hi, fmax(lo, un));
            break;
        }
        if (!(un > lo && un < hi)) un = 0.5 * (lo + hi); /* Newton left the bracket: bisect */
        u = un;
    }
    for (double delta = 0x1p-44; delta <= 0x1p-20; delta *= 0x1p8) {
        double ul = u - delta, uh = u + delta, e;
        if (ul <= 0.0)
            ul = 0.0; /* g_0 < -E: proven */
        else if (!(eval_g(p, m, ul, NULL, &e) < -e))
            continue;
        if (uh >= 1.0)
            uh = 1.0; /* g_m > E: proven */
        else if (!(eval_g(p, m, uh, NULL, &e) > e))
            continue;
        /* the root lies in [a + w ul, a + w uh] (exact reals); t is that centre rounded */
        double t = p->a + p->w * u;
        double radius = cj_up(p->w * maxd(u - ul, uh - u)) + 0x1p-52;
        if (cj_up(radius * speed) > 0.25 * tol) return 0;
        offer(B, t, radius, speed);
        return 1;
    }
    return 0;
}

int cj_nearest_by_roots(const cj_bezier2 *c, const double qp[2], double tol, cj_nearest *out) {
    int n = c->degree;
    if (c->weights || n < 1 || n > CJ_NEAREST_ROOTS_MAXN) return 0;
    int m = 2 * n - 1;
    const double *P = c->pts;
    /* the validation of nearest.c, silently: any input it would refuse goes there */
    double scale = maxd(fabs(qp[0]), fabs(qp[1]));
    int distinct = 0;
    for (int i = 0; i <= n; ++i) {
        double x = P[2 * i], y = P[2 * i + 1];
        scale = maxd(scale, maxd(fabs(x), fabs(y))); /* NaN compares false: caught below */
        if (!(fabs(x) <= 0x1p500 && fabs(y) <= 0x1p500)) return 0;
        distinct |= x != P[0] || y != P[1];
    }
    if (!distinct || !(fabs(qp[0]) <= DBL_MAX && fabs(qp[1]) <= DBL_MAX) ||
        !(tol >= scale * 0x1p-40 && tol > 0.0 && tol <= DBL_MAX))
        return 0;
    /* A_i = P_i - q and D_j = P_{j+1} - P_j, each rounded once; speed bounds |c'| = n |sum
     * D_j B_j| by n times the largest |D_j| (the exact D_j within u |D_j|). */
    double A[CJ_NEAREST_ROOTS_MAXN + 1][2], D[CJ_NEAREST_ROOTS_MAXN][2], speed = 0.0, amax = 0.0;
    for (int i = 0; i <= n; ++i) {
        for (int k = 0; k < 2; ++k) A[i][k] = P[2 * i + k] - qp[k];
        amax = maxd(amax, maxd(fabs(A[i][0]), fabs(A[i][1])));
    }
    for (int j = 0; j < n; ++j) {
        for (int k = 0; k < 2; ++k) D[j][k] = P[2 * j + 2 + k] - P[2 * j + k];
        speed = maxd(speed, fabs(D[j][0]) + fabs(D[j][1]));
    }
    speed = cj_up((double)n * speed * (1.0 + 4.0 * U));
    /* g_k = sum_{i+j=k} C(n,i) C(n-1,j) / C(m,k) A_i . D_j (the positive factor n dropped).
     * Each term carries at most 6 roundings and the sum at most n more, so the error is within
     * (n + 8) u times the sum of the terms' magnitudes. */
    double bn[CJ_NEAREST_ROOTS_MAXN + 1], bn1[CJ_NEAREST_ROOTS_MAXN + 1], bm[MAXM + 1];
    bn[0] = bn1[0] = bm[0] = 1.0; /* exact integers below 2^53 */
    for (int i = 1; i <= n; ++i) {
        bn[i] = bn[i - 1] * (n - i + 1) / i;
        bn1[i] = i < n ? bn1[i - 1] * (n - i) / i : 0.0;
    }
    for (int k = 1; k <= m; ++k) bm[k] = bm[k - 1] * (m - k + 1) / k;
    gpiece stack[MAXDEEP + 2];
    gpiece *root = &stack[0];
    double emax = 0.0;
    for (int k = 0; k <= m; ++k) {
        double g = 0.0, mag = 0.0;
        for (int i = k - (n - 1) > 0 ? k - (n - 1) : 0; i <= n && i <= k; ++i) {
            int j = k - i;
            double w = bn[i] * bn1[j] / bm[k];
            g += w * (A[i][0] * D[j][0] + A[i][1] * D[j][1]);
            mag += w * (fabs(A[i][0] * D[j][0]) + fabs(A[i][1] * D[j][1]));
        }
        root->g[k] = g;
        emax = maxd(emax, mag);
    }
    root->e = ((double)(n + 8) * U * emax + 0x1p-1060) * 1.0001;
    root->a = 0.0;
    root->w = 1.0;
    root->depth = 0;
    best B = {n,
              (const double(*)[2])A,
              ((1.0 + 3.2 * n) * U * amax + n * 0x1p-1073) * 1.0001,
              INFINITY,
              0.0,
              INFINITY,
              {0.0, 0.0}};
    offer(&B, 0.0, 0.0, speed);
    offer(&B, 1.0, 0.0, speed);
    int top = 1, work = 0;
    while (top > 0) {
        gpiece *p = &stack[--top];
        if (++work > MAXWORK || !isfinite(p->e)) return 0;
        int proven = 1, changes = 0;
        for (int k = 0; k <= m && proven; ++k) {
            proven = fabs(p->g[k]) > p->e;
            if (k > 0 && (p->g[k] > 0.0) != (p->g[k - 1] > 0.0)) ++changes;
        }
        if (proven && changes == 0) continue;
        if (proven && changes == 1) {
            if (p->g[0] > 0.0) continue; /* a local maximum */
            if (!settle_min(&B, p, m, speed, tol)) return 0;
            continue;
        }
        if (p->depth >= MAXDEEP) return 0;
        gpiece left, right;
        halve(p, m, &left, &right);
        stack[top++] = right; /* left is examined first */
        stack[top++] = left;
    }
    if (!(B.upper - B.lower <= tol) || !isfinite(B.upper)) return 0;
    out->t = B.t;
    out->point[0] = B.point[0] + qp[0];
    out->point[1] = B.point[1] + qp[1];
    out->distance = B.upper;
    out->lower = B.lower < B.upper ? B.lower : B.upper;
    out->pieces = work;
    return 1;
}

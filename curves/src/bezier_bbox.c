/* Tight bounding box: per coordinate, the extremes of c_k over [0,1] are attained at t = 0,
 * t = 1 or an interior zero of c_k'. The zeros of c_k' are isolated in Bernstein form on
 * [0,1]: by the variation-diminishing property the number of zeros in an interval is at most
 * the number of sign changes V of the coefficients (same parity). V = 0: none, the coordinate
 * is monotone there; V = 1 with a strict sign change at the ends: exactly one simple zero,
 * polished by safeguarded Newton (falling back to bisection); otherwise the interval is split
 * at its midpoint by de Casteljau. At the depth cap (width 2^-CJ_BBOX_MAX_DEPTH) the midpoint
 * is used as a candidate, which moves the candidate by at most that width.
 *
 * A zero can escape the sign tests only by sitting exactly on a split point (the shared
 * coefficient of both halves is then 0); such split points are candidates too. Any other zero
 * lies strictly inside one half, whose end coefficients (the values there) then differ in sign.
 * The box is the hull of c at a set of parameters that contains every interior extremum. */
#include "bezier_internal.h"

#include <assert.h>
#include <math.h>
#include <string.h>

#define CJ_BBOX_MAX_DEPTH    48
#define CJ_BBOX_NEWTON_ITERS 100

typedef struct bbox_acc {
    const double *coord; /* coordinate k of every control point, contiguous, n+1 values */
    int n;
    double lo, hi;
} bbox_acc;

/* Value of a 1D Bernstein polynomial of degree m with coefficients a at u. */
static double bern1(const double *a, int m, double u) {
    double w[CJ_BEZIER_MAX_DEGREE + 1];
    memcpy(w, a, sizeof(double) * (size_t)(m + 1));
    const double s = 1.0 - u;
    for (int r = m; r > 0; --r)
        for (int i = 0; i < r; ++i) w[i] = s * w[i] + u * w[i + 1];
    return w[0];
}

/* Value and derivative of a 1D Bernstein polynomial at u. */
static void bern1_d(const double *a, int m, double u, double *f, double *df) {
    double w[CJ_BEZIER_MAX_DEGREE + 1];
    memcpy(w, a, sizeof(double) * (size_t)(m + 1));
    const double s = 1.0 - u;
    for (int r = m; r > 1; --r)
        for (int i = 0; i < r; ++i) w[i] = s * w[i] + u * w[i + 1];
    if (m == 0) {
        *f = w[0];
        *df = 0.0;
        return;
    }
    *f = s * w[0] + u * w[1];
    *df = (double)m * (w[1] - w[0]);
}

static void candidate(bbox_acc *acc, double t) {
    const double v = bern1(acc->coord, acc->n, t);
    if (v < acc->lo) acc->lo = v;
    if (v > acc->hi) acc->hi = v;
}

static int sign_changes(const double *a, int m) {
    int v = 0, last = 0;
    for (int i = 0; i <= m; ++i) {
        const int s = (a[i] > 0.0) - (a[i] < 0.0);
        if (s == 0) continue;
        if (last != 0 && s != last) ++v;
        last = s;
    }
    return v;
}

/* The single simple zero of a (degree m) in (0,1), given a[0] and a[m] of strictly opposite
 * signs: Newton steps kept inside the shrinking bracket, bisection when a step leaves it. */
static double polish(const double *a, int m) {
    double ua = 0.0, ub = 1.0;
    const int sa = a[0] > 0.0 ? 1 : -1;
    double u = 0.5;
    for (int it = 0; it < CJ_BBOX_NEWTON_ITERS && ub - ua > 0x1p-53; ++it) {
        double f, df;
        bern1_d(a, m, u, &f, &df);
        if (f == 0.0) return u;
        if ((f > 0.0 ? 1 : -1) == sa)
            ua = u;
        else
            ub = u;
        double next = df != 0.0 ? u - f / df : 0.5 * (ua + ub);
        if (!(next > ua && next < ub)) next = 0.5 * (ua + ub);
        if (next == u) break;
        u = next;
    }
    return u;
}

/* Isolates the zeros of the derivative coefficients a (degree m) on [t0,t1]. `stack` holds
 * CJ_BBOX_MAX_DEPTH rows of m+1 doubles for the right halves waiting to be visited. */
static void isolate(bbox_acc *acc, double *a, int m, double *stack) {
    struct pending {
        double t0, t1;
        int depth;
    } todo[CJ_BBOX_MAX_DEPTH + 1];
    int top = 0;
    double t0 = 0.0, t1 = 1.0;
    int depth = 0;
    for (;;) {
        const int v = sign_changes(a, m);
        int leaf = 1;
        if (v == 0) {
            /* monotone on [t0,t1]: no extremum strictly inside */
        } else if (v == 1 && a[0] != 0.0 && a[m] != 0.0) {
            /* exactly one simple zero inside */
            candidate(acc, t0 + (t1 - t0) * polish(a, m));
        } else if (depth >= CJ_BBOX_MAX_DEPTH) {
            candidate(acc, 0.5 * (t0 + t1));
        } else {
            leaf = 0;
        }
        if (leaf) {
            if (top == 0) return;
            --top;
            t0 = todo[top].t0;
            t1 = todo[top].t1;
            depth = todo[top].depth;
            memcpy(a, stack + (size_t)top * (size_t)(m + 1), sizeof(double) * (size_t)(m + 1));
            continue;
        }
        /* Split at the midpoint: left half into a, right half pushed. */
        double *right = stack + (size_t)top * (size_t)(m + 1);
        double w[CJ_BEZIER_MAX_DEGREE + 1];
        memcpy(w, a, sizeof(double) * (size_t)(m + 1));
        for (int r = m;; --r) {
            a[m - r] = w[0];
            right[r] = w[r];
            if (r == 0) break;
            for (int i = 0; i < r; ++i) w[i] = 0.5 * (w[i] + w[i + 1]);
        }
        const double mid = 0.5 * (t0 + t1);
        /* A zero exactly on the split point hides from both halves' strict sign tests. */
        if (right[0] == 0.0) candidate(acc, mid);
        todo[top].t0 = mid;
        todo[top].t1 = t1;
        todo[top].depth = depth + 1;
        ++top;
        t1 = mid;
        ++depth;
    }
}

cj_status cj_bezier_bbox(const cj_bezier *c, double *lo, double *hi) {
    assert(lo != NULL && hi != NULL);
    cj_status st = cj_bezier_check(c, CJ_BEZIER_MAX_DEGREE);
    if (st) return st;
    const int n = c->degree, d = c->dim;
    double outlo[CJ_MAX_DIM], outhi[CJ_MAX_DIM];
    double coord[CJ_BEZIER_MAX_DEGREE + 1], deriv[CJ_BEZIER_MAX_DEGREE];
    double stack[CJ_BBOX_MAX_DEPTH * CJ_BEZIER_MAX_DEGREE];
    for (int k = 0; k < d; ++k) {
        for (int i = 0; i <= n; ++i) coord[i] = c->pts[(size_t)i * d + k];
        bbox_acc acc = {coord, n, fmin(coord[0], coord[n]), fmax(coord[0], coord[n])};
        if (n >= 2) {
            /* c_k' = n Σ Δb_i B_i^{n-1}; the positive factor n (and the 1/2 that keeps the
             * difference of two huge coordinates finite) does not move the zeros. */
            for (int i = 0; i < n; ++i) deriv[i] = 0.5 * coord[i + 1] - 0.5 * coord[i];
            isolate(&acc, deriv, n - 1, stack);
        }
        outlo[k] = acc.lo;
        outhi[k] = acc.hi;
    }
    memcpy(lo, outlo, sizeof(double) * (size_t)d);
    memcpy(hi, outhi, sizeof(double) * (size_t)d);
    return CJ_OK;
}

/* Distance oracle for bench_flatten: max over the curve of the distance to a polyline.
 *
 * On a parameter interval [a,b] every curve point lies in the convex hull of the piece's control
 * points P_i, and the distance to one segment S_j is a convex function, so
 *     d(c(m)) <= max_{t in [a,b]} d(c(t)) <= min_j max_i dist(P_i, S_j)
 * (d = distance to the polyline, m the midpoint; the right side converges quadratically as the
 * pieces shrink). Branch and bound keeps lo = the largest d attained at a midpoint so far and
 * splits every piece whose upper bound exceeds lo + gap; pieces are cut by long-double de
 * Casteljau, and distances are taken in long double (64-bit mantissa: 11 more bits than the
 * double inputs), so the enclosure is exact up to rounding ~1e-19 relative, far below the gaps
 * reported. Distances are first taken over a window of segments around the last nearest one (a
 * subset: the minimum over it is >= the true one, so it is a valid upper bound); the whole
 * polyline is scanned whenever the windowed value could raise lo, and for the upper bound of
 * pieces that stay unresolved after a few halvings. */
#include "flatten_oracle.h"

#include <math.h>
#include <string.h>

#define ORACLE_MAX_DEPTH 60
#define ORACLE_WINDOW    6
/* Pieces this deep take the whole polyline for their upper bound. */
#define ORACLE_FULL_DEPTH 16

typedef struct piece {
    long double a, b;
    long double p[8];
    int depth;
} piece;

static long double seg_dist2(const long double *q, const double *a, const double *b) {
    const long double abx = (long double)b[0] - a[0], aby = (long double)b[1] - a[1];
    const long double ab2 = abx * abx + aby * aby;
    long double u = ab2 > 0 ? ((q[0] - a[0]) * abx + (q[1] - a[1]) * aby) / ab2 : 0;
    if (u < 0) u = 0;
    if (u > 1) u = 1;
    const long double dx = q[0] - (a[0] + u * abx), dy = q[1] - (a[1] + u * aby);
    return dx * dx + dy * dy;
}

static long double window_dist(const long double *q, const double *pts, size_t np, size_t *hint) {
    const size_t lo = *hint > ORACLE_WINDOW ? *hint - ORACLE_WINDOW : 0;
    const size_t hi = *hint + ORACLE_WINDOW < np - 1 ? *hint + ORACLE_WINDOW : np - 1;
    long double best = INFINITY;
    for (size_t j = lo; j < hi; ++j) {
        const long double d = seg_dist2(q, pts + 2 * j, pts + 2 * j + 2);
        if (d < best) best = d, *hint = j;
    }
    return sqrtl(best);
}

static long double full_dist(const long double *q, const double *pts, size_t np, size_t *hint) {
    long double best = INFINITY;
    for (size_t j = 0; j + 1 < np; ++j) {
        const long double d = seg_dist2(q, pts + 2 * j, pts + 2 * j + 2);
        if (d < best) best = d, *hint = j;
    }
    return sqrtl(best);
}

/* min over the segments j (a window around hint, or all) of max_i dist(P_i, S_j). */
static long double hull_dist(int n, const long double *P, const double *pts, size_t np, size_t hint,
                             int all) {
    size_t lo = hint > ORACLE_WINDOW ? hint - ORACLE_WINDOW : 0;
    size_t hi = hint + ORACLE_WINDOW < np - 1 ? hint + ORACLE_WINDOW : np - 1;
    if (all) lo = 0, hi = np - 1;
    long double best = INFINITY;
    for (size_t j = lo; j < hi; ++j) {
        long double worst = 0;
        for (int i = 0; i <= n && worst < best; ++i) {
            const long double d = seg_dist2(P + 2 * i, pts + 2 * j, pts + 2 * j + 2);
            if (d > worst) worst = d;
        }
        if (worst < best) best = worst;
    }
    return sqrtl(best);
}

/* Splits the control points p (degree n) at 1/2 into l and r; m receives c(1/2). */
static void halve(int n, const long double *p, long double *l, long double *r, long double *m) {
    long double w[8];
    memcpy(w, p, sizeof(long double) * 2 * (size_t)(n + 1));
    for (int k = 0; k < 2; ++k) l[k] = w[k], r[2 * n + k] = w[2 * n + k];
    for (int lev = 1; lev <= n; ++lev) {
        for (int i = 0; i + lev <= n; ++i)
            for (int k = 0; k < 2; ++k) w[2 * i + k] = 0.5L * (w[2 * i + k] + w[2 * i + 2 + k]);
        for (int k = 0; k < 2; ++k) {
            l[2 * lev + k] = w[k];
            r[2 * (n - lev) + k] = w[2 * (n - lev) + k];
        }
    }
    m[0] = w[0], m[1] = w[1];
}

cj_oracle_dev cj_oracle_curve_polyline(int n, const double *p, const double *pts, size_t np,
                                       double rel_gap, double scale) {
    piece stack[ORACLE_MAX_DEPTH + 2];
    int top = 0;
    const long double gap = (long double)rel_gap * scale;
    long double lo = 0, hi_unresolved = 0;
    size_t hint = 0;
    /* the curve's end points count too (they are points of the curve) */
    for (int e = 0; e < 2; ++e) {
        const long double q[2] = {p[e ? 2 * n : 0], p[e ? 2 * n + 1 : 1]};
        const long double d = full_dist(q, pts, np, &hint);
        if (d > lo) lo = d;
    }
    hint = 0;
    stack[0].a = 0, stack[0].b = 1, stack[0].depth = 0;
    for (int i = 0; i < 2 * (n + 1); ++i) stack[0].p[i] = p[i];
    top = 1;
    while (top > 0) {
        piece cur = stack[--top];
        long double l[8], r[8], m[2];
        halve(n, cur.p, l, r, m);
        long double rad2 = 0;
        for (int i = 0; i <= n; ++i) {
            const long double dx = cur.p[2 * i] - m[0], dy = cur.p[2 * i + 1] - m[1];
            if (dx * dx + dy * dy > rad2) rad2 = dx * dx + dy * dy;
        }
        long double d = window_dist(m, pts, np, &hint);
        if (d > lo) {
            d = full_dist(m, pts, np, &hint);
            if (d > lo) lo = d;
        }
        long double ub = hull_dist(n, cur.p, pts, np, hint, cur.depth >= ORACLE_FULL_DEPTH);
        if (d + sqrtl(rad2) < ub) ub = d + sqrtl(rad2);
        if (ub <= lo + gap) continue;
        if (cur.depth >= ORACLE_MAX_DEPTH) {
            if (ub > hi_unresolved) hi_unresolved = ub;
            continue;
        }
        /* right half below the left one: the walk goes left to right (the hint follows) */
        const long double mid = 0.5L * (cur.a + cur.b);
        piece *R = &stack[top++], *L = &stack[top++];
        R->a = mid, R->b = cur.b, R->depth = cur.depth + 1;
        L->a = cur.a, L->b = mid, L->depth = cur.depth + 1;
        memcpy(R->p, r, sizeof r);
        memcpy(L->p, l, sizeof l);
    }
    cj_oracle_dev out;
    out.lo = (double)lo;
    const long double hi = lo + gap > hi_unresolved ? lo + gap : hi_unresolved;
    out.hi = (double)hi;
    if ((long double)out.hi < hi) out.hi = nextafter(out.hi, INFINITY);
    if ((long double)out.lo > lo) out.lo = nextafter(out.lo, 0.0);
    return out;
}

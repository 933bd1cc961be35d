/* Convex hull of a 2D control polygon: Andrew's monotone chain with the points ordered by
 * (y, x), which starts the hull at the lowest-then-leftmost point and walks it
 * counter-clockwise. The orientation test is exact: a floating-point determinant with a
 * static error filter, and an error-free expansion when the filter cannot decide. */
#include "bezier_internal.h"
#include "eft_internal.h"

#include <assert.h>
#include <math.h>
#include <stdlib.h>

typedef struct hull_pt {
    double x, y;
    int idx;
} hull_pt;

/* Sign of the exact sum of m doubles (m <= 16), by Shewchuk's grow-expansion: the running
 * expansion stays non-overlapping with components in increasing magnitude, so its sign is the
 * sign of its last non-zero component. Exact barring overflow. */
static int exact_sum_sign(const double *v, int m) {
    double e[16];
    int len = 0;
    for (int i = 0; i < m; ++i) {
        double q = v[i];
        for (int j = 0; j < len; ++j) {
            double s, err;
            cj_two_sum(q, e[j], &s, &err);
            e[j] = err;
            q = s;
        }
        e[len++] = q;
    }
    for (int j = len - 1; j >= 0; --j)
        if (e[j] != 0.0) return e[j] > 0.0 ? 1 : -1;
    return 0;
}

/* Sign of the orientation determinant (a-o) x (b-o): +1 counter-clockwise, -1 clockwise,
 * 0 collinear. Exact. */
static int orient2d(const hull_pt *o, const hull_pt *a, const hull_pt *b) {
    const double l = (a->x - o->x) * (b->y - o->y), r = (a->y - o->y) * (b->x - o->x);
    const double det = l - r;
    /* Shewchuk's first-stage bound for this form: (3 + 16u) u (|l| + |r|). */
    const double bound = (3.0 + 16.0 * CJ_UNIT_ROUNDOFF) * CJ_UNIT_ROUNDOFF * (fabs(l) + fabs(r));
    if (det > bound) return 1;
    if (-det > bound) return -1;
    /* Exact: (a-o)x(b-o) = ax*by - ax*oy - ox*by - ay*bx + ay*ox + oy*bx (the ox*oy cancel),
     * each product split exactly into two doubles. */
    double terms[12];
    const double f[6][2] = {{a->x, b->y},  {-a->x, o->y}, {-o->x, b->y},
                            {-a->y, b->x}, {a->y, o->x},  {o->y, b->x}};
    for (int i = 0; i < 6; ++i) cj_two_prod(f[i][0], f[i][1], &terms[2 * i], &terms[2 * i + 1]);
    return exact_sum_sign(terms, 12);
}

static int cmp_yx(const void *pa, const void *pb) {
    const hull_pt *a = pa, *b = pb;
    if (a->y != b->y) return a->y < b->y ? -1 : 1;
    if (a->x != b->x) return a->x < b->x ? -1 : 1;
    return (a->idx > b->idx) - (a->idx < b->idx);
}

cj_status cj_bezier_hull2d(const cj_bezier *c, int *idx, int *count) {
    assert(idx != NULL && count != NULL);
    cj_status st = cj_bezier_check(c, CJ_BEZIER_MAX_DEGREE);
    if (st) return st;
    if (c->dim != 2)
        return cj_fail(CJ_ERR_DIMENSION, "hull2d needs a 2D curve, got dimension %d", c->dim);
    const int np = c->degree + 1;
    hull_pt p[CJ_BEZIER_MAX_DEGREE + 1];
    for (int i = 0; i < np; ++i) {
        p[i].x = c->pts[2 * i];
        p[i].y = c->pts[2 * i + 1];
        p[i].idx = i;
    }
    qsort(p, (size_t)np, sizeof p[0], cmp_yx);
    /* Coincident points: keep the first in (y, x, index) order, i.e. the lowest index. */
    int m = 0;
    for (int i = 0; i < np; ++i)
        if (m == 0 || p[i].x != p[m - 1].x || p[i].y != p[m - 1].y) p[m++] = p[i];
    if (m == 1) {
        idx[0] = p[0].idx;
        *count = 1;
        return CJ_OK;
    }
    /* Chain up the right side, then down the left side; strict left turns only, so collinear
     * points are dropped. */
    int h[2 * (CJ_BEZIER_MAX_DEGREE + 1)];
    int k = 0;
    for (int i = 0; i < m; ++i) {
        while (k >= 2 && orient2d(&p[h[k - 2]], &p[h[k - 1]], &p[i]) <= 0) --k;
        h[k++] = i;
    }
    for (int i = m - 2, lower = k + 1; i >= 0; --i) {
        while (k >= lower && orient2d(&p[h[k - 2]], &p[h[k - 1]], &p[i]) <= 0) --k;
        h[k++] = i;
    }
    --k; /* the last point repeats the first; all collinear leaves the two extremes */
    for (int i = 0; i < k; ++i) idx[i] = p[h[i]].idx;
    *count = k;
    return CJ_OK;
}

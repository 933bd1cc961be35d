/* Trimming an offset: its self-intersections cut it into spans; a span whose points are closer
 * to the curve than the offset distance (a swallowtail past two cusps, or a part that crossed
 * over another part of the curve) is dropped, the rest kept and joined (offset.h). */
#include "casteljau/bezier.h"
#include "casteljau/intersect.h"
#include "casteljau/nearest.h"
#include "casteljau/offset.h"
#include "error_internal.h"

#include <assert.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define RES_CAP 64

typedef struct cuts {
    double *t;
    int n, cap;
} cuts;

static int add_cut(cuts *C, double t) {
    if (C->n == C->cap) {
        int cap = C->cap ? 2 * C->cap : 64;
        double *p = realloc(C->t, (size_t)cap * sizeof *p);
        if (!p) return -1;
        C->t = p;
        C->cap = cap;
    }
    C->t[C->n++] = t;
    return 0;
}

static int cmp_double(const void *a, const void *b) {
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* The cubic of piece k on [a, b] (0 <= a < b <= 1) into out[8], by two de Casteljau splits. */
static void sub_cubic(const double *piece, double a, double b, double out[8]) {
    double w[4][2];
    for (int i = 0; i < 4; ++i) w[i][0] = piece[2 * i], w[i][1] = piece[2 * i + 1];
    /* right part at a: [a, 1] */
    if (a > 0.0) {
        double r[4][2], t[4][2];
        memcpy(t, w, sizeof t);
        for (int k = 0; k < 2; ++k) r[3][k] = t[3][k];
        for (int lev = 3; lev > 0; --lev) {
            for (int i = 0; i < lev; ++i)
                for (int k = 0; k < 2; ++k) t[i][k] = (1 - a) * t[i][k] + a * t[i + 1][k];
            for (int k = 0; k < 2; ++k) r[lev - 1][k] = t[lev - 1][k];
        }
        memcpy(w, r, sizeof w);
        b = (b - a) / (1 - a);
    }
    if (b < 1.0) {
        double l[4][2], t[4][2];
        memcpy(t, w, sizeof t);
        for (int k = 0; k < 2; ++k) l[0][k] = t[0][k];
        for (int lev = 3; lev > 0; --lev) {
            for (int i = 0; i < lev; ++i)
                for (int k = 0; k < 2; ++k) t[i][k] = (1 - b) * t[i][k] + b * t[i + 1][k];
            for (int k = 0; k < 2; ++k) l[4 - lev][k] = t[0][k];
        }
        memcpy(w, l, sizeof w);
    }
    for (int i = 0; i < 4; ++i) out[2 * i] = w[i][0], out[2 * i + 1] = w[i][1];
}

static void eval_cubic(const double *p, double t, double out[2]) {
    double s = 1 - t;
    for (int k = 0; k < 2; ++k)
        out[k] = s * s * s * p[k] + 3 * s * s * t * p[2 + k] + 3 * s * t * t * p[4 + k] +
                 t * t * t * p[6 + k];
}

/* Point of the offset at the global parameter tau in [0, np]. */
static void eval_at(const double *pieces, int np, double tau, double out[2]) {
    int k = (int)floor(tau);
    if (k >= np) k = np - 1;
    if (k < 0) k = 0;
    eval_cubic(pieces + 8 * k, tau - k, out);
}

/* 1 if the crossing (s on piece i, t on piece j) is the joint of consecutive pieces (or of the
 * last and the first of a closed offset): their shared end points, not a crossing. */
static int is_joint(const double *pieces, int np, int i, int j, const cj_isect *r) {
    const double *a = pieces + 8 * i, *b = pieces + 8 * j;
    if (j == i + 1 && r->s_hi >= 1.0 && r->t_lo <= 0.0 && a[6] == b[0] && a[7] == b[1]) return 1;
    if (i == 0 && j == np - 1 && r->s_lo <= 0.0 && r->t_hi >= 1.0 && a[0] == b[6] && a[1] == b[7])
        return 1;
    return 0;
}

cj_status cj_offset_trim(const cj_bezier2 *c, double d, double tol, const double *pieces, int np,
                         double deviation, double *out, int *newline, int cap, int *nout,
                         int *dropped) {
    assert(c && pieces && nout && (out || cap == 0));
    *nout = 0;
    if (dropped) *dropped = 0;
    if (np < 1) return cj_fail(CJ_ERR_EMPTY, "offset trim: no pieces");
    double scale = 0.0;
    for (int i = 0; i < 8 * np; ++i) {
        if (!isfinite(pieces[i]))
            return cj_fail(CJ_ERR_NONFINITE, "offset trim: piece %d, coordinate %d is not finite",
                           i / 8, i % 8);
        scale = fmax(scale, fabs(pieces[i]));
    }
    if (!isfinite(d)) return cj_fail(CJ_ERR_NONFINITE, "offset trim: distance d is not finite");
    if (!isfinite(deviation) || deviation < 0)
        return cj_fail(CJ_ERR_ARGUMENT, "offset trim: deviation %g must be finite and >= 0",
                       deviation);
    if (!isfinite(tol) || !(tol > 0.0) || tol < scale * 0x1p-36)
        return cj_fail(CJ_ERR_ARGUMENT,
                       "offset trim: tol %g must be finite, > 0 and at least %g (2^-36 times the "
                       "offset's scale)",
                       tol, scale * 0x1p-36);
    cuts C = {NULL, 0, 0};
    cj_isect res[RES_CAP];
    cj_status st = CJ_OK;
    double itol = fmax(tol * 0x1p-10, scale * 0x1p-38);
    if (add_cut(&C, 0.0) || add_cut(&C, (double)np)) goto nomem;
    for (int i = 0; i < np && st == CJ_OK; ++i) {
        cj_bezier2 A = cj_bezier2_view(3, pieces + 8 * i, NULL);
        int n = 0;
        /* a piece whose four points coincide (an offset collapsed to a point) crosses nothing
         * the pieces around it do not */
        int distinct = 0;
        for (int k = 1; k < 4; ++k)
            distinct |= A.pts[2 * k] != A.pts[0] || A.pts[2 * k + 1] != A.pts[1];
        if (!distinct) continue;
        st = cj_intersect_self(&A, itol, res, RES_CAP, &n);
        if (st != CJ_OK) break;
        for (int r = 0; r < n; ++r)
            if (add_cut(&C, i + res[r].s) || add_cut(&C, i + res[r].t)) goto nomem;
        for (int j = i + 1; j < np; ++j) {
            cj_bezier2 B = cj_bezier2_view(3, pieces + 8 * j, NULL);
            int dj = 0;
            for (int k = 1; k < 4; ++k)
                dj |= B.pts[2 * k] != B.pts[0] || B.pts[2 * k + 1] != B.pts[1];
            if (!dj) continue;
            st = cj_intersect_curves(&A, &B, itol, res, RES_CAP, &n);
            if (st != CJ_OK) break;
            for (int r = 0; r < n; ++r) {
                if (is_joint(pieces, np, i, j, &res[r])) continue;
                if (add_cut(&C, i + res[r].s) || add_cut(&C, j + res[r].t)) goto nomem;
            }
        }
    }
    if (st != CJ_OK) goto done;
    qsort(C.t, (size_t)C.n, sizeof *C.t, cmp_double);
    int m = 0; /* distinct cuts */
    for (int i = 0; i < C.n; ++i)
        if (m == 0 || C.t[i] > C.t[m - 1] + 0x1p-40) C.t[m++] = C.t[i];
    C.n = m;
    /* A span is dropped when a point of it is proven nearer to the curve than |d| by more than
     * the offset's deviation and the query's tolerance allow: it lies where the raw offset ran
     * past the curve's evolute or crossed over another part of the curve. */
    double margin = 2.0 * (deviation + tol), ntol = fmax(tol * 0.25, scale * 0x1p-38);
    int count = 0, last_kept = -1;
    double last_end[2] = {0, 0};
    for (int s = 0; s + 1 < C.n; ++s) {
        double a = C.t[s], b = C.t[s + 1], mid[2];
        eval_at(pieces, np, 0.5 * (a + b), mid);
        cj_nearest nr;
        st = cj_nearest_curve(c, mid, ntol, &nr);
        if (st != CJ_OK) goto done;
        if (nr.distance < fabs(d) - margin) {
            if (dropped) ++*dropped;
            continue;
        }
        int first = 1;
        for (int k = (int)floor(a); k < np && k < b; ++k) {
            double la = fmax(a - k, 0.0), lb = fmin(b - k, 1.0);
            if (!(lb > la)) continue;
            if (count < cap) {
                double *o = out + 8 * count;
                sub_cubic(pieces + 8 * k, la, lb, o);
                int nl = 0;
                if (first) {
                    /* continues the last kept span when it ended where this one starts (the two
                     * sides of a removed loop meet at its crossing) */
                    nl = last_kept < 0 || hypot(o[0] - last_end[0], o[1] - last_end[1]) > tol;
                    if (!nl) o[0] = last_end[0], o[1] = last_end[1];
                } else {
                    o[0] = last_end[0], o[1] = last_end[1];
                }
                if (newline) newline[count] = nl;
                last_end[0] = o[6];
                last_end[1] = o[7];
            }
            first = 0;
            ++count;
        }
        last_kept = s;
    }
    *nout = count;
    if (count > cap)
        st = cj_fail(CJ_ERR_BUFFER, "offset trim: %d pieces do not fit in %d", count, cap);
    goto done;
nomem:
    st = cj_fail(CJ_ERR_NOMEM, "offset trim: the list of cuts");
done:
    free(C.t);
    return st;
}

/* The outline of a stroke: both offsets joined by end caps (open curves) or closed at the seam
 * (closed curves), every loop closing bit for bit (offset.h, cj_offset_outline). */
#include "casteljau/offset.h"
#include "casteljau/rational.h"
#include "error_internal.h"
#include "offset_internal.h"

#include <assert.h>
#include <math.h>
#include <string.h>

#define PI 3.14159265358979323846

typedef struct obuf {
    double *pts;
    int *newline;
    int cap, count;
    double deviation;
} obuf;

static void push(obuf *o, const double q[8], int newline) {
    if (o->count < o->cap) {
        memcpy(o->pts + 8 * (size_t)o->count, q, 8 * sizeof(double));
        if (o->newline) o->newline[o->count] = newline;
    }
    ++o->count;
}

static void segment(const double P[2], const double Q[2], double q[8]) {
    q[0] = P[0], q[1] = P[1];
    q[2] = P[0] + (Q[0] - P[0]) / 3.0, q[3] = P[1] + (Q[1] - P[1]) / 3.0;
    q[4] = Q[0] - (Q[0] - P[0]) / 3.0, q[5] = Q[1] - (Q[1] - P[1]) / 3.0;
    q[6] = Q[0], q[7] = Q[1];
}

/* Unit tangent of c at t (0 or 1). */
static int tangent(const cj_bezier2 *c, double t, double T[2]) {
    double v[4];
    cj_status st;
    if (c->weights) {
        cj_rbezier r = cj_rbezier_view(c->degree, 2, c->pts, c->weights);
        st = cj_rbezier_eval_derivs(&r, t, 1, v);
    } else {
        cj_bezier b = cj_bezier_view(c->degree, 2, c->pts);
        st = cj_bezier_eval_derivs(&b, t, 1, v);
    }
    double l = hypot(v[2], v[3]);
    if (st != CJ_OK || !(l > 0.0)) return 0;
    T[0] = v[2] / l, T[1] = v[3] / l;
    return 1;
}

/* Reverses pieces [a, b) of the buffer in place (order and direction). */
static void reverse(obuf *o, int a, int b) {
    if (b > o->cap) return; /* counting only */
    for (int i = a, j = b - 1; i <= j; ++i, --j) {
        double qi[8], qj[8];
        memcpy(qi, o->pts + 8 * (size_t)i, sizeof qi);
        memcpy(qj, o->pts + 8 * (size_t)j, sizeof qj);
        for (int k = 0; k < 4; ++k) {
            o->pts[8 * (size_t)i + 2 * k] = qj[6 - 2 * k];
            o->pts[8 * (size_t)i + 2 * k + 1] = qj[7 - 2 * k];
            o->pts[8 * (size_t)j + 2 * k] = qi[6 - 2 * k];
            o->pts[8 * (size_t)j + 2 * k + 1] = qi[7 - 2 * k];
        }
    }
}

/* The offset at signed distance s appended; returns the status (CJ_ERR_BUFFER only counts). */
static cj_status offset_into(obuf *o, const cj_bezier2 *c, double s, double tol, int *cusps,
                             int *n) {
    int room = o->cap - o->count, np = 0, cs = 0;
    double dev = 0.0;
    double *at = room > 0 ? o->pts + 8 * (size_t)o->count : NULL;
    cj_status st = cj_offset_curve(c, s, tol, at, NULL, room > 0 ? room : 0, &np, &dev, &cs);
    if (st == CJ_ERR_BUFFER || (st == CJ_OK && !at && np > 0))
        st = CJ_OK; /* counted: the caller reports the buffer */
    if (st != CJ_OK) return st;
    if (o->newline && room > 0)
        for (int i = 0; i < np && i < room; ++i) o->newline[o->count + i] = 0;
    o->count += np;
    o->deviation = fmax(o->deviation, dev);
    *cusps += cs;
    *n = np;
    return CJ_OK;
}

static const double *piece_at(const obuf *o, int i) {
    return i < o->cap ? o->pts + 8 * (size_t)i : NULL;
}

/* Appends the arc pieces about C from A to B turning by sweep. */
static void arc(obuf *o, const double C[2], double r, const double A[2], const double B[2],
                double sweep, double tol) {
    double q[8 * CJ_OFFSET_ARC_MAX], bound;
    int n = cj_offset_arc(C, r, A, B, sweep, tol, q, &bound);
    for (int i = 0; i < n; ++i) push(o, q + 8 * i, 0);
    o->deviation = fmax(o->deviation, bound);
}

/* Closes the loop of pieces [first, o->count) (the offset at signed distance s of a closed
 * curve, seam at C = c(0) = c(1)). */
static void close_seam(obuf *o, int first, const double C[2], const double T0[2],
                       const double T1[2], double s, double tol) {
    const double *q0 = piece_at(o, first), *ql = piece_at(o, o->count - 1);
    if (!q0 || !ql) { /* counting only: a join takes at most an arc's pieces */
        o->count += CJ_OFFSET_ARC_MAX;
        return;
    }
    double A[2] = {ql[6], ql[7]}, B[2] = {q0[0], q0[1]};
    double gap = hypot(A[0] - B[0], A[1] - B[1]);
    if (gap <= tol * 0x1p-8) { /* a smooth closure: snap the last end onto the first start */
        double *w = o->pts + 8 * (size_t)(o->count - 1);
        w[4] += B[0] - A[0], w[5] += B[1] - A[1];
        w[6] = B[0], w[7] = B[1];
        o->deviation += gap;
        return;
    }
    double turn = T1[0] * T0[1] - T1[1] * T0[0];
    int convex = s > 0 ? turn < 0 : turn > 0;
    if (convex) {
        double a[2] = {A[0] - C[0], A[1] - C[1]}, b[2] = {B[0] - C[0], B[1] - C[1]};
        double ang = atan2(a[0] * b[1] - a[1] * b[0], a[0] * b[0] + a[1] * b[1]);
        arc(o, C, fabs(s), A, B, ang, tol);
    } else { /* through the corner: inside the stroke */
        double q[8];
        segment(A, C, q);
        push(o, q, 0);
        segment(C, B, q);
        push(o, q, 0);
    }
}

/* An end cap at E (tangent T out of the curve) from A to B (A = E + w N, B = E - w N). */
static void end_cap(obuf *o, cj_offset_cap cap, const double E[2], const double T[2], double w,
                    const double A[2], const double B[2], double tol) {
    double q[8];
    if (cap == CJ_OFFSET_CAP_BUTT) {
        segment(A, B, q);
        push(o, q, 0);
    } else if (cap == CJ_OFFSET_CAP_SQUARE) {
        double A2[2] = {A[0] + w * T[0], A[1] + w * T[1]},
               B2[2] = {B[0] + w * T[0], B[1] + w * T[1]};
        segment(A, A2, q);
        push(o, q, 0);
        segment(A2, B2, q);
        push(o, q, 0);
        segment(B2, B, q);
        push(o, q, 0);
    } else {
        arc(o, E, w, A, B, -PI, tol);
    }
}

cj_status cj_offset_outline(const cj_bezier2 *c, double w, double tol, cj_offset_cap cap,
                            double *pts, int *newline, int cap_pieces, int *npieces,
                            double *deviation, int *cusps) {
    assert(c && npieces && deviation && (pts || cap_pieces == 0));
    if (!(w > 0.0) || !isfinite(w))
        return cj_fail(CJ_ERR_ARGUMENT, "outline half-width w = %g must be finite and > 0", w);
    if (cap != CJ_OFFSET_CAP_BUTT && cap != CJ_OFFSET_CAP_ROUND && cap != CJ_OFFSET_CAP_SQUARE)
        return cj_fail(CJ_ERR_ARGUMENT, "outline cap %d is not butt (0), round (1) or square (2)",
                       (int)cap);
    obuf o = {pts, newline, cap_pieces, 0, 0.0};
    int cs = 0, nl = 0, nr = 0, n = c->degree;
    cj_status st = offset_into(&o, c, w, tol, &cs, &nl);
    if (st != CJ_OK) return st;
    if (newline && cap_pieces > 0) newline[0] = 1;
    double T0[2], T1[2];
    if (!tangent(c, 0.0, T0) || !tangent(c, 1.0, T1))
        return cj_fail(CJ_ERR_DEGENERATE, "curve: the derivative vanishes at an end");
    const double S[2] = {c->pts[0], c->pts[1]}, E[2] = {c->pts[2 * n], c->pts[2 * n + 1]};
    int closed = S[0] == E[0] && S[1] == E[1];
    if (closed) {
        close_seam(&o, 0, S, T0, T1, w, tol);
        int first = o.count;
        if ((st = offset_into(&o, c, -w, tol, &cs, &nr)) != CJ_OK) return st;
        close_seam(&o, first, S, T0, T1, -w, tol);
        reverse(&o, first, o.count);
        if (newline && first < cap_pieces) newline[first] = 1;
    } else {
        int first = o.count;
        if ((st = offset_into(&o, c, -w, tol, &cs, &nr)) != CJ_OK) return st;
        reverse(&o, first, o.count);
        /* the end cap goes between the +w offset and the reversed -w one: built after it, then
         * rotated into place */
        const double *ql = piece_at(&o, first - 1), *qr = piece_at(&o, first);
        const double *qe = piece_at(&o, o.count - 1);
        if (ql && qr && qe && o.count <= o.cap) {
            double A[2] = {ql[6], ql[7]}, B[2] = {qr[0], qr[1]};
            int before = o.count;
            end_cap(&o, cap, E, T1, w, A, B, tol);
            int ncap = o.count - before;
            if (o.count <= o.cap) { /* rotate [first, count) so the cap comes first */
                double tmp[8 * (CJ_OFFSET_ARC_MAX + 3)];
                memcpy(tmp, o.pts + 8 * (size_t)before, 8 * sizeof(double) * (size_t)ncap);
                memmove(o.pts + 8 * (size_t)(first + ncap), o.pts + 8 * (size_t)first,
                        8 * sizeof(double) * (size_t)(before - first));
                memcpy(o.pts + 8 * (size_t)first, tmp, 8 * sizeof(double) * (size_t)ncap);
            }
            const double *q2 = piece_at(&o, o.count - 1), *q0 = piece_at(&o, 0);
            if (q2 && q0 && o.count < o.cap) {
                double A2[2] = {q2[6], q2[7]}, B2[2] = {q0[0], q0[1]};
                double mT0[2] = {-T0[0], -T0[1]};
                end_cap(&o, cap, S, mT0, w, A2, B2, tol);
            } else {
                o.count += CJ_OFFSET_ARC_MAX;
            }
        } else {
            o.count += 2 * CJ_OFFSET_ARC_MAX; /* counting only: two caps at most this */
        }
        if (newline)
            for (int i = 1; i < o.count && i < cap_pieces; ++i) newline[i] = 0;
    }
    *npieces = o.count;
    *deviation = o.deviation;
    if (cusps) *cusps = cs;
    if (o.count > cap_pieces)
        return cj_fail(CJ_ERR_BUFFER, "outline needs at most %d pieces, room for %d", o.count,
                       cap_pieces);
    return CJ_OK;
}

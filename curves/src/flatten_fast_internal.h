/* Private: the planar fast path of near-optimal flattening (flatten_fast.c), shared with its
 * measured placement for few segments (flatten_fast_small.c). See flatten_fast.c for the method
 * and its rounding analysis. */
#ifndef CASTELJAU_FLATTEN_FAST_INTERNAL_H
#define CASTELJAU_FLATTEN_FAST_INTERNAL_H

#include "flatten_internal.h"

#include <math.h>

typedef struct fpt {
    double x, y, dx, dy; /* c(t), c'(t) in the scaled coordinates */
} fpt;

/* Point and first derivative at t in Bernstein form: c(t) = Σ B_i(t) b_i and
 * c'(t) = Σ B^(n-1)_i(t) q_i with q_i = n (b_{i+1} - b_i) (computed once per curve, in dq). The
 * weights are products of s = 1 - t and t, positive and summing to 1 up to rounding, so the
 * errors stay within the few u of the top comment's rounding paragraph. */
/* a * b + c, fused where the hardware has it (one rounding instead of two; the bounds above
 * count two). */
#ifdef __FMA__
#define FAST_MADD(a, b, c) fma(a, b, c)
#else
#define FAST_MADD(a, b, c) ((a) * (b) + (c))
#endif

static inline __attribute__((always_inline)) void eval_pd(const double *p, const double *dq, int n,
                                                          double t, fpt *o) {
    const double s = 1.0 - t;
    const double ss = s * s, st = s * t, tt = t * t;
    if (n == 3) {
        const double w0 = ss * s, w1 = 3.0 * (ss * t), w2 = 3.0 * (st * t), w3 = tt * t;
        const double v1 = 2.0 * st;
        o->x = FAST_MADD(w3, p[6], FAST_MADD(w2, p[4], FAST_MADD(w1, p[2], w0 * p[0])));
        o->y = FAST_MADD(w3, p[7], FAST_MADD(w2, p[5], FAST_MADD(w1, p[3], w0 * p[1])));
        o->dx = FAST_MADD(tt, dq[4], FAST_MADD(v1, dq[2], ss * dq[0]));
        o->dy = FAST_MADD(tt, dq[5], FAST_MADD(v1, dq[3], ss * dq[1]));
    } else {
        const double w1 = 2.0 * st;
        o->x = FAST_MADD(tt, p[4], FAST_MADD(w1, p[2], ss * p[0]));
        o->y = FAST_MADD(tt, p[5], FAST_MADD(w1, p[3], ss * p[1]));
        o->dx = FAST_MADD(t, dq[2], s * dq[0]);
        o->dy = FAST_MADD(t, dq[3], s * dq[1]);
    }
}

/* max over t in [0,1] of |t(1-t)(A(1-t) + B t)| plus the rounding margin (see the top). */
static inline double hump_max(double A, double B) {
    const double R = sqrt(A * A - A * B + B * B);
    const double m2 = 2.0 * A - B;
    const double q = m2 + (m2 >= 0.0 ? R : -R);
    double best = 0.0;
    if (q != 0.0) {
        const double a3 = 3.0 * (A - B);
        const double r[2] = {a3 != 0.0 ? q / a3 : -1.0, A / q};
        for (int i = 0; i < 2; ++i) {
            const double t = r[i];
            if (t > 0.0 && t < 1.0) {
                const double e = fabs(t * (1.0 - t) * (A + (B - A) * t));
                if (e > best) best = e;
            }
        }
    }
    return best + 16.0 * CJ_UNIT_ROUNDOFF * (fabs(A) + fabs(B));
}

typedef struct fast_ctx {
    const cj_fl_curve *fc;
    const double *p; /* scaled control points, stride 2 */
    double dq[6];    /* n (b_{i+1} - b_i), the derivative's control points, stride 2 */
    int n;
    double inv_n; /* 1 / n */
    double down;  /* 2^-escale: caller units -> scaled */
    double tol_s; /* tol_eff in scaled units */
    double lo_s;  /* accept_lo in scaled units */
    double tol_eff, accept_lo;
} fast_ctx;

/* The general bounds (a)-(d) on the de Casteljau subcurve on [a,b], in scaled units. Kept out of
 * line: its work space is large, and the common path should not pay for the stack frame. */
double cj_fl_fast_general_dev(const fast_ctx *cx, double a, double b);

/* Square of a deviation bound (scaled units) of the piece [a,b] between the break points P (at
 * a) and Q (at b). Squares and one division instead of square roots: the common case costs
 * no root at all. Squaring and the division add a few u relative to the deviation, which is at
 * most about the curve's size, so inside the slack. Returns +INFINITY only on overflow. */
static inline __attribute__((always_inline)) double
piece_dev2(const fast_ctx *cx, double a, double b, const fpt *P, const fpt *Q) {
    const double k = (b - a) * cx->inv_n;
    const double vx = Q->x - P->x, vy = Q->y - P->y;
    const double L2 = vx * vx + vy * vy;
    /* b_1 - b_0 = k c'(a): cross and dot with v */
    const double c1 = k * (vx * P->dy - vy * P->dx), d1 = k * (vx * P->dx + vy * P->dy);
    double A, B, d2;
    if (cx->n == 3) {
        /* b_3 - b_2 = k c'(b); b_2 - b_0 = v - (b_3 - b_2): cross -c2, dot d2 */
        const double c2 = k * (vx * Q->dy - vy * Q->dx);
        d2 = L2 - k * (vx * Q->dx + vy * Q->dy);
        A = 3.0 * c1;
        B = -3.0 * c2;
    } else {
        d2 = d1;
        A = B = 2.0 * c1;
    }
    if (!(L2 > 0.0)) {
        const double g = cj_fl_fast_general_dev(cx, a, b);
        return g * g;
    }
    const int inside = d1 >= 0.0 && d1 <= L2 && d2 >= 0.0 && d2 <= L2;
    if (inside) {
        /* max |t(1-t)(A(1-t) + B t)| <= max(|A|, |B|) / 4: exact when A = B (an arc symmetric
         * about its chord), and enough for most pieces; the exact maximum otherwise. The
         * rounding margin 16 u (|A| + |B|) <= 32 u max(|A|, |B|) is folded into the factor. */
        const double aA = fabs(A), aB = fabs(B);
        const double M = (0.25 + 32.0 * CJ_UNIT_ROUNDOFF) * (aA > aB ? aA : aB);
        const double D2 = M * M / L2;
        if (D2 <= cx->tol_s * cx->tol_s) return D2;
    }
    const double E = hump_max(A, B);
    const double E2 = E * E / L2;
    if (inside || E2 > cx->tol_s * cx->tol_s) return E2;
    /* Some control point projects beyond an end of the chord. E, the largest distance from the
     * chord's line, is a lower bound; the projection parameter is a polynomial with Bernstein
     * coefficients d_i / L2, so the curve reaches at most O = max(-dmin, dmax - L2) / |v| past
     * an end, and sqrt(E^2 + O^2) bounds the distance to the segment. */
    const double dmin = d1 < d2 ? (d1 < 0.0 ? d1 : 0.0) : (d2 < 0.0 ? d2 : 0.0);
    const double dmax = d1 > d2 ? (d1 > L2 ? d1 : L2) : (d2 > L2 ? d2 : L2);
    const double O = -dmin > dmax - L2 ? -dmin : dmax - L2;
    const double EO2 = (E * E + O * O) / L2 * (1.0 + 16.0 * CJ_UNIT_ROUNDOFF);
    if (EO2 <= cx->tol_s * cx->tol_s) return EO2;
    const double g = cj_fl_fast_general_dev(cx, a, b);
    return g * g;
}

/* ---- the plan (see flatten_fast.c: the parabola model of the integral of sqrt|κ|) ---------- */

#define FAST_F_K 0.38

static inline double approx_f_inv(double a) {
    return a * (1.0 - FAST_F_K + sqrt(FAST_F_K * FAST_F_K + a * a * (1.0 / 16.0)));
}

typedef struct fast_quad {
    double t0, dt;  /* cubic parameters: t = t0 + u dt */
    double val;     /* ∫ sqrt(κ) ds of the model (scaled units) */
    double inv_val; /* 1 / val (0 when val is) */
    double a0, da;  /* F(x0), F(x1) - F(x0) */
    double y0, ysc; /* F^-1(a0), 1 / (F^-1(a1) - F^-1(a0)) */
    /* Filled by plan_init: planned point j (its target j step of the integral) lies on this
     * quadratic while j < jlim, at t = c0 + c1 F^-1(alpha + j beta), clamped to [t0, t0 + dt]. */
    double alpha, beta, c0, c1;
    size_t jlim;
} fast_quad;

/* The planned break points: equal steps of the model's integral over the quadratics. */
typedef struct fast_plan {
    fast_quad *qs;
    int nq;
    size_t m; /* planned segments */
    int qi;   /* quadratic of the last target */
} fast_plan;

/* Planned point j (1 <= j; m and later are the end, 1.0). Called with increasing j. */
static inline double plan_next(fast_plan *pl, size_t j) {
    if (j >= pl->m) return 1.0;
    while (j >= pl->qs[pl->qi].jlim && pl->qi < pl->nq - 1) pl->qi++;
    const fast_quad *q = &pl->qs[pl->qi];
    const double t = q->c0 + q->c1 * approx_f_inv(q->alpha + (double)j * q->beta);
    const double hi = q->t0 + q->dt;
    return t < q->t0 ? q->t0 : (t < hi ? (t < 1.0 ? t : 1.0) : (hi < 1.0 ? hi : 1.0));
}

/* ---- certification and emission ----------------------------------------------------------- */

typedef struct fast_run {
    fast_ctx cx;
    cj_fl_emitter *em;
    double up;
    int direct;        /* inner points go straight into em->out (no sink) */
    size_t direct_end; /* while em->count is below this (room and the segment cap) */
    double worst2;     /* square of the largest certified deviation (scaled units) */
} fast_run;

/* Emits the end point or a point into a sink (cj_fl_emit's checks); out of line. */
cj_status cj_fl_fast_emit_slow(fast_run *fr, double b, const fpt *Q);

static inline __attribute__((always_inline)) cj_status emit_break(fast_run *fr, double b,
                                                                  const fpt *Q) {
    cj_fl_emitter *e = fr->em;
    if (b < 1.0 && fr->direct && e->count < fr->direct_end) {
        /* inner points into the caller's buffer, where it has room: cj_fl_emit's work without
         * its checks for the first point of a sequence piece (the first point is emitted
         * before) and without tracking the last point (the end point, emitted last, sets it) */
        e->out[2 * e->count] = Q->x * fr->up;
        e->out[2 * e->count + 1] = Q->y * fr->up;
        e->count++;
        return CJ_OK;
    }
    return cj_fl_fast_emit_slow(fr, b, Q);
}

/* [a, b] failed with squared bound D2: shortens it until certified and emits it, moving *pa and
 * *P to its end (see flatten_fast.c). */
cj_status cj_fl_fast_repair(fast_run *fr, double *pa, fpt *P, double b, const fpt *Q, double D2);

/* Plans of at most this many segments take the measured second placement. */
#define FAST_SMALL_MAX 24

/* The plan pl of m (2 <= m <= FAST_SMALL_MAX) segments between the break points first (t = 0)
 * and last (t = 1), measured and placed again (flatten_fast_small.c). */
cj_status cj_fl_fast_run_small(fast_run *fr, fast_plan *pl, const fpt *first, const fpt *last,
                               size_t m);

#endif

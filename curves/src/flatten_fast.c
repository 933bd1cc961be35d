/* Near-optimal flattening of planar polynomial quadratics and cubics at the cost of the
 * unguaranteed methods.
 *
 * The general near-optimal method (flatten_run.c) recomputes each trial piece's control points
 * by two de Casteljau splits and bounds it by (a)-(d) of flatten.h. For a planar polynomial
 * curve of degree n <= 3 both are replaced by closed forms:
 *
 *  - Control points from the ends: the piece on [a,b] (h = b - a) of a curve of degree n <= 3
 *    is its Hermite interpolant, b_0 = c(a), b_1 = c(a) + h c'(a)/n, b_{n-1} = c(b) - h c'(b)/n,
 *    b_n = c(b). Each break point is evaluated once (point and derivative, one de Casteljau
 *    triangle) and shared by the two pieces that meet there.
 *  - The exact deviation: with v = b_n - b_0, the signed distance of c(t) from the chord's line
 *    is a polynomial vanishing at both ends, e(t) = t(1-t) L(t) / |v|, L(t) = A(1-t) + B t with
 *    A = 3 v x (b_1 - b_0), B = 3 v x (b_2 - b_0) (cubic) or A = B = 2 v x (b_1 - b_0)
 *    (quadratic). Its largest magnitude on [0,1] is at a root of
 *    e'(t) ∝ 3(A-B) t^2 + 2(B-2A) t + A, whose discriminant 4(A^2 - AB + B^2) never vanishes
 *    unless e = 0, so the roots are simple and well separated (|e''| = 2 sqrt(A^2-AB+B^2) there)
 *    and the value at a computed root is within a few u (|A|+|B|) of the maximum; 16 u (|A|+|B|)
 *    is added. When every control point projects into the chord segment, every curve point
 *    does (the curve lies in their hull), so the distance to the line is the distance to the
 *    segment and max|e| is the piece's Hausdorff distance from its chord (see flatten.h), exact
 *    up to rounding: no slack from a bound, so each accepted segment carries nearly the whole
 *    tolerance. Otherwise (near cusps, control points running past their chord) max|e| is a
 *    lower bound that rejects a piece that is too long; the projection onto the chord is a
 *    polynomial with Bernstein coefficients d_i / |v|^2 (d_i = (b_i - b_0).v), so the curve
 *    reaches at most O = max(-min d_i, max d_i - |v|^2) / |v| past an end of the chord and
 *    sqrt(max|e|^2 + O^2) bounds the distance; where that does not certify the piece, the
 *    general bounds (a)-(d) on its de Casteljau subcurve do.
 *
 * The common case needs no square root: max |t(1-t)(A(1-t) + B t)| <= max(|A|, |B|)/4, exact
 * when A = B, is compared in squares with tol^2 |v|^2 first; the exact maximum is taken only
 * where that does not certify the piece.
 *
 * Segment placement (below): all break points are placed up front at equal steps of a
 * closed-form estimate of ∫ sqrt(|κ|) ds (the parabola model), aiming at FAST_TARGET tol per
 * segment, so the spacing follows ∫ sqrt(|κ|/(8 tol)) ds; each segment is then certified as
 * above, and the few the bound rejects (the h^2 law undershoots near inflections) are shortened
 * until certified, the walk resuming from there towards the next planned point. Plans of few
 * segments are certified first and placed again from the measured bounds
 * (flatten_fast_small.c).
 *
 * Rounding: the break points and derivatives come from the Bernstein sums of eval_pd on the
 * scaled control points (|coordinates| < 1), whose weights are positive products of s = 1 - t
 * (rounded once) and t: each weight is within ~4 u of its exact value relative to itself, so a
 * point is within ~(n+7) u and a derivative within ~(n+7) u of n max|b_{i+1} - b_i| of the
 * exact values (the de Casteljau triangle's ~3n u, for about half its operations), the computed
 * Hermite control points within ~(6n+2) u, and the chord arithmetic adds a few u. The curve with
 * the computed control points is within that distance of the true piece (a convex combination), so
 * the bound plus fc->slack = 32 (n+2) u max|coord| holds for the true piece; the general bound's
 * subcurve ends differ from our break points by as little, also inside the slack. */
#include "flatten_fast_internal.h"

#include <math.h>
#include <stdint.h>

/* Exponent range where 2^escale and 2^-escale are normal doubles, so that scaling by them is an
 * exact multiplication. */
#define FAST_MAX_ESCALE 1000

int cj_fl_fast_applies(const cj_fl_curve *fc) {
    return !fc->rational && fc->d == 2 && (fc->n == 2 || fc->n == 3) &&
           fc->escale >= -FAST_MAX_ESCALE && fc->escale <= FAST_MAX_ESCALE;
}

/* 2^e for |e| <= FAST_MAX_ESCALE (a normal double), built from its bits (no libm call). */
static inline double pow2(int e) {
    const union {
        uint64_t u;
        double d;
    } v = {(uint64_t)(1023 + e) << 52};
    return v.d;
}

/* The general bounds (a)-(d) on the de Casteljau subcurve on [a,b], in scaled units. Kept out of
 * line: its work space is large, and the common path should not pay for the stack frame. */
__attribute__((noinline)) double cj_fl_fast_general_dev(const fast_ctx *cx, double a, double b) {
    double sub[CJ_FL_WORK];
    cj_fl_subcurve(cx->fc, a, b, sub);
    const double D = cj_fl_piece_bound_refined(cx->fc, sub, cx->accept_lo, INFINITY,
                                               CJ_FL_REFINE_GAIN, cx->tol_eff);
    return D * cx->down;
}

static inline void end_point(const fast_ctx *cx, fpt *o) {
    const double *p = cx->p;
    const int n = cx->n;
    o->x = p[2 * n];
    o->y = p[2 * n + 1];
    o->dx = (double)n * (p[2 * n] - p[2 * n - 2]);
    o->dy = (double)n * (p[2 * n + 1] - p[2 * n - 1]);
}

/* ---- placement: the integral of sqrt|κ| by the parabola model ------------------------------
 *
 * A quadratic q(u) = p0 (1-u)^2 + 2 p1 u (1-u) + p2 u^2 with d01 = p1 - p0, d12 = p2 - p1,
 * g = d01 - d12 and W = d01 x d12 has q' = 2 (d01 - u g), q' x q'' = 4 W (constant), and the
 * component of q'/2 across g is the constant |W|/|g|. With x = (u |g|^2 - d01.g) / |W| (a
 * linear coordinate along the parabola's axis, 0 at its vertex),
 *     |q'| = 2 (|W|/|g|) sqrt(1 + x^2),
 *     sqrt(κ) ds = sqrt(|q' x q''|) |q'|^(-1/2) du = sqrt(2) |W| |g|^(-3/2) (1 + x^2)^(-1/4) dx,
 * so ∫ sqrt(κ) ds over [u0, u1] is sqrt(2) |W| |g|^(-3/2) (F(x1) - F(x0)) with
 * F(x) = ∫_0^x (1 + s^2)^(-1/4) ds (odd; F ~ x near 0, ~ 2 sqrt(x) far out). F and its inverse
 * are replaced by closed forms of the right shape at both ends, fitted on [1e-3, 1e4]:
 *     F(x) ~ x / (1 - r^(1/4)/2 + (r + x^2)^(1/4)/2), r = 2.2     (derivative within -3.2/+1.2 %)
 *     F^-1(a) ~ a (1 - k + sqrt(k^2 + a^2/16)),        k = 0.38    (derivative within -0.04/+0.5 %)
 * The points are placed at equal steps of the (approximate) integral; nothing about the
 * guarantee rests on these estimates: every segment is certified afterwards, and the few that
 * fail are split. A cubic is cut into a few equal parameter pieces, each modelled by the
 * quadratic with its end points and the midpoint-matching inner control point
 * (b0 + b3)/2 + h (c'(a) - c'(b))/4 (the parameter correspondence is linear). */

#define FAST_F_R       2.2
#define FAST_MAX_QUADS 16
/* Share of the tolerance a model quadratic may miss its piece of the cubic by. 0.15 (0.3 before
 * issue 20's fourth pass) gives plans of few segments a model close enough that their measured
 * second placement is rejected less often: at tol 1 a fifth more quadratics paid back by fewer
 * repairs (at tol 0.01 most cubics use all FAST_MAX_QUADS either way). */
#define FAST_QUAD_TOL 0.15
/* Segments are placed for this share of the tolerance (their estimated deviation): a little
 * below 1 so that the estimate's spread rarely fails the certificate. */
#define FAST_TARGET 0.90
/* Plans of at least FAST_MANY segments aim lower: there the per-segment work dominates the time
 * and the count's whole-number rounding costs nothing, so fewer rejected segments (one in nine
 * at 0.90, near inflections) are worth 1 % more segments. */
#define FAST_MANY        64
#define FAST_TARGET_MANY 0.88

/* The exact inverse of approx_f_inv (to 2e-4 relative): the closed form for F as a start,
 * then one Newton step on approx_f_inv. Placing points by approx_f_inv between end values from
 * this keeps the parabola's ends where they are. */
static inline double approx_f(double x) {
    const double c = 1.0 - 0.5 * sqrt(sqrt(FAST_F_R));
    double a = x / (c + 0.5 * sqrt(sqrt(FAST_F_R + x * x)));
    for (int it = 0; it < 1; ++it) {
        /* y' = 1 - k + r + a^2 / (16 r): one division for the step (y - x) / y' */
        const double a2 = a * a * (1.0 / 16.0);
        const double r = sqrt(FAST_F_K * FAST_F_K + a2);
        const double w = 1.0 - FAST_F_K + r;
        a -= (a * w - x) * r / (w * r + a2);
    }
    return a;
}

/* The model parabola through P (at t0) and Q (at t0 + dt). */
static void quad_params(const fpt *P, const fpt *Q, int n, double t0, double dt, fast_quad *q) {
    q->t0 = t0;
    q->dt = dt;
    double d01x, d01y, d12x, d12y;
    if (n == 3) {
        const double mx = 0.5 * (P->x + Q->x) + 0.25 * dt * (P->dx - Q->dx);
        const double my = 0.5 * (P->y + Q->y) + 0.25 * dt * (P->dy - Q->dy);
        d01x = mx - P->x, d01y = my - P->y;
        d12x = Q->x - mx, d12y = Q->y - my;
    } else {
        d01x = 0.5 * P->dx, d01y = 0.5 * P->dy;
        d12x = 0.5 * Q->dx, d12y = 0.5 * Q->dy;
    }
    const double gx = d01x - d12x, gy = d01y - d12y;
    const double W = fabs(d01x * d12y - d01y * d12x);
    const double g2 = gx * gx + gy * gy;
    q->val = 0.0;
    q->inv_val = 0.0;
    q->a0 = 0.0, q->da = 0.0, q->y0 = 0.0, q->ysc = 0.0;
    if (!(W > 0.0) || !(g2 > 0.0)) return;
    const double inv_w = 1.0 / W;
    const double x0 = -(d01x * gx + d01y * gy) * inv_w, x1 = -(d12x * gx + d12y * gy) * inv_w;
    const double a0 = approx_f(x0), a1 = approx_f(x1);
    const double gn = sqrt(g2);
    const double val = 1.4142135623730951 * W / (gn * sqrt(gn)) * (a1 - a0);
    const double y0 = approx_f_inv(a0), y1 = approx_f_inv(a1);
    if (!(val > 0.0) || !isfinite(val) || !(y1 > y0)) return;
    q->val = val;
    q->inv_val = 1.0 / val;
    q->a0 = a0, q->da = a1 - a0;
    q->y0 = y0, q->ysc = 1.0 / (y1 - y0);
}

/* ---- certification ------------------------------------------------------------------------ */

/* Emits the end point or a point into a sink (cj_fl_emit's checks); out of line. */
__attribute__((noinline)) cj_status cj_fl_fast_emit_slow(fast_run *fr, double b, const fpt *Q) {
    cj_fl_emitter *e = fr->em;
    double pt[2];
    if (b == 1.0) {
        cj_fl_end(fr->cx.fc, fr->cx.n, pt);
    } else {
        pt[0] = Q->x * fr->up;
        pt[1] = Q->y * fr->up;
    }
    if (cj_fl_emit(e, pt, b)) return cj_fl_cap_fail(e, "near-optimal");
    return CJ_OK;
}

#define FAST_MAX_SPLIT_DEPTH 64

/* Certifies [a,b] (break points P, Q) and emits Q; a piece the bound rejects is cut into equal
 * parts (as many as the model h^2 scaling of its deviation asks for, at least 2), each
 * certified in turn. */
static cj_status certify(fast_run *fr, double a, const fpt *P, double b, const fpt *Q, int depth) {
    const double D2 = piece_dev2(&fr->cx, a, b, P, Q);
    if (D2 <= fr->cx.tol_s * fr->cx.tol_s) {
        if (D2 > fr->worst2) fr->worst2 = D2;
        return emit_break(fr, b, Q);
    }
    const double D = sqrt(D2);
    if (!isfinite(D))
        return cj_fail(CJ_ERR_RANGE, "flatness bound overflows: coordinates too large");
    double k = ceil(sqrt(D / (FAST_TARGET * fr->cx.tol_s)));
    if (!(k >= 2.0)) k = 2.0;
    if (k > 16.0) k = 16.0;
    const int parts = (int)k;
    if (depth >= FAST_MAX_SPLIT_DEPTH || !(a + (b - a) / k > a))
        return cj_fail(CJ_ERR_RANGE,
                       "tolerance %.3g cannot be reached in double precision near t = %.17g",
                       fr->cx.tol_eff, a);
    fpt L = *P;
    double ta = a;
    for (int i = 1; i <= parts; ++i) {
        fpt R;
        const double tb = i == parts ? b : a + (b - a) * (double)i / k;
        if (i == parts)
            R = *Q;
        else
            eval_pd(fr->cx.p, fr->cx.dq, fr->cx.n, tb, &R);
        const cj_status st = certify(fr, ta, &L, tb, &R, depth + 1);
        if (st) return st;
        L = R;
        ta = tb;
    }
    return CJ_OK;
}

/* Turns the share of the integral on each quadratic into a closed form in the point's index:
 * target j step lies on quadratic i while it is below the sum of the integrals up to i, at
 * share s = (j step - start) / val of it, parameter t0 + dt (F^-1(a0 + s da) - y0) ysc. */
static void plan_init(fast_plan *pl, fast_quad *qs, int nq, size_t m, double step) {
    pl->qs = qs;
    pl->nq = nq;
    pl->m = m;
    pl->qi = 0;
    double start = 0.0;
    for (int i = 0; i < nq; ++i) {
        fast_quad *q = &qs[i];
        const double end = start + q->val;
        /* the first j whose target reaches the end (every j for the last quadratic) */
        double jl = i == nq - 1 ? (double)m : ceil(end / step);
        if (!(jl <= (double)m)) jl = (double)m; /* also NaN: 0 / 0 on a curve of no length */
        if (jl < 0.0) jl = 0.0;
        while (jl > 0.0 && step * (jl - 1.0) >= end) jl -= 1.0;
        while (step * jl < end && jl < (double)m) jl += 1.0;
        q->jlim = i == nq - 1 ? m : (size_t)jl;
        if (q->val > 0.0) {
            const double r = q->da * q->inv_val;
            q->alpha = q->a0 - start * r;
            q->beta = step * r;
            q->c1 = q->dt * q->ysc;
            q->c0 = q->t0 - q->y0 * q->c1;
        } else {
            q->alpha = q->beta = q->c1 = 0.0;
            q->c0 = q->t0 + q->dt;
        }
        start = end;
    }
}

#define FAST_REPAIR_TRIES 6

static inline int e_count_lt(const cj_fl_emitter *e, size_t lim) {
    return e->count < lim;
}

/* [a, b] failed with squared bound D2: the model underestimated the deviation there (near
 * inflections the h^2 law of the sqrt(κ) integral undershoots by up to ~15 %). The segment is
 * shortened (deviation ~ h^2.5 between the arc's h^2 and an inflection's h^3) until it is
 * certified, and emitted; the caller resumes from its end towards the next planned point. After
 * FAST_REPAIR_TRIES the piece is cut into certified equal parts instead (cusps). */
cj_status cj_fl_fast_repair(fast_run *fr, double *pa, fpt *P, double b, const fpt *Q, double D2) {
    const fast_ctx *cx = &fr->cx;
    const double a = *pa, goal2 = 0.96 * 0.96 * cx->tol_s * cx->tol_s;
    double h = b - a;
    for (int it = 0; it < FAST_REPAIR_TRIES; ++it) {
        /* (goal / D)^(1/2): the h^2 law's step, shorter than the h^2.5 law's (goal / D)^(2/5)
         * by a few percent, at one square root instead of a pow */
        double f = sqrt(sqrt(goal2 / D2));
        if (!(f <= 0.97)) f = 0.97;
        if (f < 0.1) f = 0.1;
        h *= f;
        const double bn = a + h;
        if (!(bn > a)) break;
        fpt R;
        eval_pd(cx->p, cx->dq, cx->n, bn, &R);
        D2 = piece_dev2(cx, a, bn, P, &R);
        if (D2 <= cx->tol_s * cx->tol_s) {
            if (D2 > fr->worst2) fr->worst2 = D2;
            const cj_status st = emit_break(fr, bn, &R);
            if (st) return st;
            *pa = bn;
            *P = R;
            return CJ_OK;
        }
    }
    const cj_status st = certify(fr, a, P, b, Q, 0);
    if (st) return st;
    *pa = b;
    *P = *Q;
    return CJ_OK;
}

cj_status cj_fl_run_fast(const cj_fl_curve *fc, double tol_eff, cj_fl_emitter *em, double *bound) {
    fast_run fr;
    fast_ctx *cx = &fr.cx;
    cx->fc = fc;
    cx->p = fc->hom;
    cx->n = fc->n;
    cx->inv_n = 1.0 / (double)fc->n;
    cx->down = pow2(-fc->escale);
    fr.up = pow2(fc->escale);
    fr.em = em;
    fr.worst2 = 0.0;
    cx->tol_eff = tol_eff;
    cx->accept_lo = 0.95 * tol_eff;
    cx->tol_s = tol_eff * cx->down;
    cx->lo_s = cx->accept_lo * cx->down;
    double pt[2];
    cj_fl_end(fc, 0, pt);
    if (cj_fl_emit(em, pt, 0.0)) return cj_fl_cap_fail(em, "near-optimal");
    fr.direct = !em->sink && em->out != NULL;
    fr.direct_end = em->cap_points < em->max_points ? em->cap_points : em->max_points;
    const double *p = cx->p;
    for (int i = 0; i < 2 * cx->n; ++i) cx->dq[i] = (double)cx->n * (p[i + 2] - p[i]);
    /* The model: nq equal parameter pieces, as many as the cubic's third difference asks for
     * (a quadratic models a piece with error ~ |Δ^3 b| h^3 / 20; the pieces need not be within
     * the tolerance, only close enough for the curvature estimate). */
    int nq = 1;
    if (cx->n == 3) {
        const double ex = p[6] - 3.0 * p[4] + 3.0 * p[2] - p[0];
        const double ey = p[7] - 3.0 * p[5] + 3.0 * p[3] - p[1];
        const double e = sqrt(ex * ex + ey * ey) * (1.0 / 20.0);
        /* nq = ceil(cbrt(r3)) in 1..FAST_MAX_QUADS, by comparing cubes (no cbrt call) */
        const double r3 = e / (FAST_QUAD_TOL * cx->tol_s);
        while (nq < FAST_MAX_QUADS && (double)(nq * nq * nq) < r3) ++nq;
    }
    fast_quad qs[FAST_MAX_QUADS];
    fpt brk[FAST_MAX_QUADS + 1];
    double total = 0.0;
    eval_pd(p, cx->dq, cx->n, 0.0, &brk[0]);
    for (int i = 1; i <= nq; ++i) {
        if (i == nq)
            end_point(cx, &brk[i]);
        else
            eval_pd(p, cx->dq, cx->n, (double)i / nq, &brk[i]);
        quad_params(&brk[i - 1], &brk[i], cx->n, (double)(i - 1) / nq, 1.0 / nq, &qs[i - 1]);
        total += qs[i - 1].val;
    }
    /* ∫ sqrt(κ) ds = m sqrt(8 dev) for m equal segments of deviation dev */
    double per = sqrt(8.0 * FAST_TARGET * cx->tol_s);
    if (total >= (double)FAST_MANY * per) per = sqrt(8.0 * FAST_TARGET_MANY * cx->tol_s);
    double mf = ceil(total / per);
    if (!(mf >= 1.0)) mf = 1.0;
    if (!(mf <= (double)em->max_points)) return cj_fl_cap_fail(em, "near-optimal");
    const size_t m = (size_t)mf;
    fast_plan pl;
    plan_init(&pl, qs, nq, m, total / mf);
    if (m >= 2 && m <= FAST_SMALL_MAX) {
        const cj_status st = cj_fl_fast_run_small(&fr, &pl, &brk[0], &brk[nq], m);
        if (st) return st;
        *bound = sqrt(fr.worst2) * fr.up + fc->slack;
        return CJ_OK;
    }
    const double tol2 = cx->tol_s * cx->tol_s;
    /* inner points go straight into the caller's buffer below this count */
    const size_t dend = fr.direct ? fr.direct_end : 0;
    double a = 0.0, prev = 0.0, worst2 = 0.0;
    fpt P = brk[0];
    size_t j = 1;
    int qi = 0;
    while (j < m) {
        while (j >= qs[qi].jlim && qi < nq - 1) qi++;
        const fast_quad *q = &qs[qi];
        const double lo = q->t0, hi = q->t0 + q->dt < 1.0 ? q->t0 + q->dt : 1.0;
        const size_t jend = q->jlim;
        /* The planned points on this quadratic: one square root, one evaluation and the
         * certificate each; the branch to the repair is rarely taken. */
        for (; j < jend; ++j) {
            double t = q->c0 + q->c1 * approx_f_inv(q->alpha + (double)j * q->beta);
            t = t > lo ? t : lo;
            t = t < hi ? t : hi;
            if (t >= 1.0) {
                j = m;
                break;
            }
            fpt Q;
            eval_pd(p, cx->dq, cx->n, t, &Q);
            const double D2 = piece_dev2(cx, a, t, &P, &Q);
            if (__builtin_expect(D2 > tol2, 0)) {
                fr.worst2 = fr.worst2 > worst2 ? fr.worst2 : worst2;
                const cj_status st = cj_fl_fast_repair(&fr, &a, &P, t, &Q, D2);
                if (st) return st;
                worst2 = fr.worst2;
                /* resume at the next planned point at least half a planned step ahead */
                pl.qi = qi;
                double bj = t;
                while (bj < 1.0 && !(bj - a >= 0.5 * (bj - prev))) {
                    prev = bj;
                    bj = plan_next(&pl, ++j);
                }
                if (bj >= 1.0) j = m;
                break;
            }
            worst2 = D2 > worst2 ? D2 : worst2;
            if (e_count_lt(em, dend)) {
                em->out[2 * em->count] = Q.x * fr.up;
                em->out[2 * em->count + 1] = Q.y * fr.up;
                em->count++;
            } else {
                const cj_status st = cj_fl_fast_emit_slow(&fr, t, &Q);
                if (st) return st;
            }
            a = t;
            prev = t;
            P = Q;
        }
    }
    fr.worst2 = fr.worst2 > worst2 ? fr.worst2 : worst2;
    /* the last segment, to the exact end point */
    while (a < 1.0) {
        const fpt Q = brk[nq];
        const double D2 = piece_dev2(cx, a, 1.0, &P, &Q);
        if (D2 <= tol2) {
            if (D2 > fr.worst2) fr.worst2 = D2;
            const cj_status st = emit_break(&fr, 1.0, &Q);
            if (st) return st;
            break;
        }
        const cj_status st = cj_fl_fast_repair(&fr, &a, &P, 1.0, &Q, D2);
        if (st) return st;
    }
    *bound = sqrt(fr.worst2) * fr.up + fc->slack;
    return CJ_OK;
}

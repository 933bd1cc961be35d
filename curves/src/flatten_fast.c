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
 * Segment lengths are chosen as in the general method: grown from the previous step until the
 * deviation lies in [0.95, 1] tol (secant on sqrt(deviation), which is linear in the step
 * on curved pieces), so the spacing follows ∫ sqrt(|κ|/(8 tol)) ds.
 *
 * Rounding: the break points and derivatives come from one de Casteljau triangle on the scaled
 * control points (|coordinates| < 1): each is within ~3n u of the exact value relative to the
 * largest coordinate, the computed Hermite control points within ~(6n+2) u, and the chord
 * arithmetic adds a few u. The curve with the computed control points is within that distance
 * of the true piece (a convex combination), so the bound plus fc->slack = 32 (n+2) u max|coord|
 * holds for the true piece; the general bound's subcurve ends differ from our break points by
 * as little, also inside the slack. */
#include "flatten_internal.h"

#include <math.h>

/* Exponent range where 2^escale and 2^-escale are normal doubles, so that scaling by them is an
 * exact multiplication. */
#define FAST_MAX_ESCALE 1000

int cj_fl_fast_applies(const cj_fl_curve *fc) {
    return !fc->rational && fc->d == 2 && (fc->n == 2 || fc->n == 3) &&
           fc->escale >= -FAST_MAX_ESCALE && fc->escale <= FAST_MAX_ESCALE;
}

typedef struct fpt {
    double x, y, dx, dy; /* c(t), c'(t) in the scaled coordinates */
} fpt;

/* Point and first derivative at t (one de Casteljau triangle). */
static inline void eval_pd(const double *p, int n, double t, fpt *o) {
    const double s = 1.0 - t;
    if (n == 3) {
        const double ax0 = s * p[0] + t * p[2], ay0 = s * p[1] + t * p[3];
        const double ax1 = s * p[2] + t * p[4], ay1 = s * p[3] + t * p[5];
        const double ax2 = s * p[4] + t * p[6], ay2 = s * p[5] + t * p[7];
        const double bx0 = s * ax0 + t * ax1, by0 = s * ay0 + t * ay1;
        const double bx1 = s * ax1 + t * ax2, by1 = s * ay1 + t * ay2;
        o->x = s * bx0 + t * bx1;
        o->y = s * by0 + t * by1;
        o->dx = 3.0 * (bx1 - bx0);
        o->dy = 3.0 * (by1 - by0);
    } else {
        const double ax0 = s * p[0] + t * p[2], ay0 = s * p[1] + t * p[3];
        const double ax1 = s * p[2] + t * p[4], ay1 = s * p[3] + t * p[5];
        o->x = s * ax0 + t * ax1;
        o->y = s * ay0 + t * ay1;
        o->dx = 2.0 * (ax1 - ax0);
        o->dy = 2.0 * (ay1 - ay0);
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
    int n;
    double down;  /* 2^-escale: caller units -> scaled */
    double tol_s; /* tol_eff in scaled units */
    double lo_s;  /* accept_lo in scaled units */
    double tol_eff, accept_lo;
} fast_ctx;

/* The general bounds (a)-(d) on the de Casteljau subcurve on [a,b], in scaled units. Kept out of
 * line: its work space is large, and the common path should not pay for the stack frame. */
static __attribute__((noinline)) double general_dev(const fast_ctx *cx, double a, double b) {
    double sub[CJ_FL_WORK];
    cj_fl_subcurve(cx->fc, a, b, sub);
    const double D = cj_fl_piece_bound_refined(cx->fc, sub, cx->accept_lo, INFINITY,
                                               CJ_FL_REFINE_GAIN, cx->tol_eff);
    return D * cx->down;
}

/* Deviation bound (scaled units) of the piece [a,b] between the break points P (at a) and Q (at
 * b). Returns +INFINITY only on overflow. */
static double piece_dev(const fast_ctx *cx, double a, double b, const fpt *P, const fpt *Q) {
    const double h = b - a, k = h / (double)cx->n;
    const double vx = Q->x - P->x, vy = Q->y - P->y;
    const double L2 = vx * vx + vy * vy;
    const double u1x = k * P->dx, u1y = k * P->dy; /* b_1 - b_0 */
    const double c1 = vx * u1y - vy * u1x, d1 = vx * u1x + vy * u1y;
    double A, B, dmin = d1 < 0.0 ? d1 : 0.0, dmax = d1 > L2 ? d1 : L2;
    if (cx->n == 3) {
        const double u2x = k * Q->dx, u2y = k * Q->dy; /* b_3 - b_2 */
        const double c2 = vx * u2y - vy * u2x, d2 = L2 - (vx * u2x + vy * u2y);
        /* b_2 - b_0 = v - u2: cross -c2, dot d2 */
        if (d2 < dmin) dmin = d2;
        if (d2 > dmax) dmax = d2;
        A = 3.0 * c1;
        B = -3.0 * c2;
    } else {
        A = B = 2.0 * c1;
    }
    if (!(L2 > 0.0)) return general_dev(cx, a, b);
    const double E = hump_max(A, B) / sqrt(L2);
    if (dmin >= 0.0 && dmax <= L2) return E;
    /* Some control point projects beyond an end of the chord. E, the largest distance from the
     * chord's line, is a lower bound; the projection parameter is a polynomial with Bernstein
     * coefficients d_i / L2, so the curve reaches at most O = max(-dmin, dmax - L2) / |v| past
     * an end, and sqrt(E^2 + O^2) bounds the distance to the segment. */
    if (E > cx->tol_s) return E;
    const double O = fmax(-dmin, dmax - L2) / sqrt(L2);
    const double EO = sqrt(E * E + O * O) + 4.0 * CJ_UNIT_ROUNDOFF * (E + O);
    if (EO <= cx->tol_s) return EO;
    return general_dev(cx, a, b);
}

static inline void end_point(const fast_ctx *cx, fpt *o) {
    const double *p = cx->p;
    const int n = cx->n;
    o->x = p[2 * n];
    o->y = p[2 * n + 1];
    o->dx = (double)n * (p[2 * n] - p[2 * n - 2]);
    o->dy = (double)n * (p[2 * n + 1] - p[2 * n - 1]);
}

cj_status cj_fl_run_fast(const cj_fl_curve *fc, double tol_eff, cj_fl_emitter *em, double *bound) {
    fast_ctx cx;
    cx.fc = fc;
    cx.p = fc->hom;
    cx.n = fc->n;
    cx.down = ldexp(1.0, -fc->escale);
    const double up = ldexp(1.0, fc->escale);
    cx.tol_eff = tol_eff;
    cx.accept_lo = 0.95 * tol_eff;
    cx.tol_s = tol_eff * cx.down;
    cx.lo_s = cx.accept_lo * cx.down;
    const double target = 0.975 * cx.tol_s, starget = sqrt(target);
    double pt[2];
    cj_fl_end(fc, 0, pt);
    if (cj_fl_emit(em, pt, 0.0)) return cj_fl_cap_fail(em, "near-optimal");
    const double K = cj_fl_wang_coefficient(fc);
    if (!isfinite(K))
        return cj_fail(CJ_ERR_RANGE, "flatness bound overflows: coordinates too large");
    double h = K > 0.0 ? 1.5 / sqrt(K / tol_eff) : 1.0;
    if (h > 1.0) h = 1.0;
    double a = 0.0, hprev = 0.0, worst = 0.0;
    fpt P;
    eval_pd(cx.p, cx.n, 0.0, &P);
    while (a < 1.0) {
        const double hmax = 1.0 - a;
        if (h > hmax) h = hmax;
        double lo = 0.0, Dlo = 0.0, hi = 0.0, Dhi = 0.0, blo = 0.0;
        int have_lo = 0, have_hi = 0;
        double hacc, Dacc, bacc;
        fpt Q, Qlo = P, Qacc;
        for (int it = 0;; ++it) {
            const double b = h >= hmax ? 1.0 : a + h;
            if (!(b > a))
                return cj_fail(CJ_ERR_RANGE,
                               "tolerance %.3g cannot be reached in double precision near "
                               "t = %.17g",
                               tol_eff, a);
            if (b == 1.0)
                end_point(&cx, &Q);
            else
                eval_pd(cx.p, cx.n, b, &Q);
            const double D = piece_dev(&cx, a, b, &P, &Q);
            if (!isfinite(D))
                return cj_fail(CJ_ERR_RANGE, "flatness bound overflows: coordinates too large");
            if (D <= cx.tol_s) {
                if (b == 1.0 || D >= cx.lo_s) {
                    hacc = h, Dacc = D, bacc = b, Qacc = Q;
                    break;
                }
                lo = h, Dlo = D, blo = b, have_lo = 1, Qlo = Q;
            } else {
                hi = h, Dhi = D, have_hi = 1;
            }
            if (have_lo && (it >= 40 || (have_hi && hi - lo <= 1e-3 * lo))) {
                hacc = lo, Dacc = Dlo, bacc = blo, Qacc = Qlo;
                break;
            }
            double hn;
            if (have_lo && have_hi) {
                /* secant on sqrt(D), linear in h on curved pieces; kept inside the bracket */
                const double sl = sqrt(Dlo), sh = sqrt(Dhi);
                hn = sh > sl ? lo + (hi - lo) * (starget - sl) / (sh - sl) : 0.5 * (lo + hi);
                const double mar = 0.05 * (hi - lo);
                if (!(hn > lo + mar && hn < hi - mar)) hn = 0.5 * (lo + hi);
            } else if (have_lo) {
                hn = D > 0.0 ? h * starget / sqrt(D) : 4.0 * h;
                if (hn < 1.02 * h) hn = 1.02 * h;
                if (hn > 4.0 * h) hn = 4.0 * h;
            } else {
                hn = h * starget / sqrt(D);
                if (!(hn <= 0.9 * h)) hn = 0.9 * h;
                if (hn < 0.05 * h) hn = 0.05 * h;
            }
            h = hn < hmax ? hn : hmax;
        }
        if (Dacc > worst) worst = Dacc;
        if (bacc == 1.0) {
            cj_fl_end(fc, fc->n, pt);
        } else {
            pt[0] = Qacc.x * up;
            pt[1] = Qacc.y * up;
        }
        if (cj_fl_emit(em, pt, bacc)) return cj_fl_cap_fail(em, "near-optimal");
        a = bacc;
        P = Qacc;
        double hn = Dacc > 0.0 && bacc < 1.0 ? hacc * fmin(1.5, sqrt(target / Dacc)) : hacc;
        if (hprev > 0.0) hn *= fmax(0.7, fmin(1.4, hacc / hprev));
        hprev = hacc;
        h = hn;
    }
    *bound = worst * up + fc->slack;
    return CJ_OK;
}

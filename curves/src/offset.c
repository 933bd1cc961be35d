/* Offset curves as proven Hermite cubics, and degree reduction with a proven bound (offset.h). */
#include "query_internal.h"

#include "casteljau/offset.h"
#include "casteljau/rational.h"
#include "error_internal.h"
#include "offset_internal.h"

#include <assert.h>
#include <lapacke.h>
#include <string.h>

#define MAX_DEPTH     20 /* halvings of the curve's parameter interval */
#define MAX_SUB_DEPTH 12 /* halvings of a piece's interval in its proof */

typedef struct orun {
    const cj_qctx *q;
    const cj_bezier2 *c;
    double d, tol;
    double *pts, *breaks;
    int cap, count;
    double deviation;
    int cusps;
    double last_sign; /* sign of 1 + d κ at the last piece end written */
    cj_status status;
    double bad_t;
} orun;

/* o(t), o'(t) and 1 + d κ(t) in doubles (for building pieces; the proof is separate). Returns 0
 * where c' vanishes. */
static int offset_at(const orun *R, double t, double o[2], double od[2], double *stretch) {
    double v[6];
    const cj_bezier2 *c = R->c;
    cj_status st;
    if (c->weights) {
        cj_rbezier r = cj_rbezier_view(c->degree, 2, c->pts, c->weights);
        st = cj_rbezier_eval_derivs(&r, t, 2, v);
    } else {
        cj_bezier b = cj_bezier_view(c->degree, 2, c->pts);
        st = cj_bezier_eval_derivs(&b, t, 2, v);
    }
    if (st != CJ_OK) return 0;
    double sp2 = v[2] * v[2] + v[3] * v[3], sp = sqrt(sp2);
    if (!(sp > 0.0)) return 0;
    double N[2] = {-v[3] / sp, v[2] / sp};
    double cross = v[2] * v[5] - v[3] * v[4]; /* c' x c'' = κ |c'|^3 */
    double kappa = cross / (sp2 * sp);
    /* N' = -κ |c'| T = -κ c' */
    o[0] = v[0] + R->d * N[0];
    o[1] = v[1] + R->d * N[1];
    od[0] = v[2] * (1.0 - R->d * kappa);
    od[1] = v[3] * (1.0 - R->d * kappa);
    *stretch = 1.0 - R->d * kappa;
    return isfinite(o[0]) && isfinite(o[1]) && isfinite(od[0]) && isfinite(od[1]);
}

/* Encloses o(T) = c + d N and, if od, o'(T) = c' + d N'; 0 where |c'| may vanish on T. */
static int offset_encl(const orun *R, cj_ivl T, cj_ivl o[2], cj_ivl od[2]) {
    cj_ivl p[2], d1[2], d2[2];
    if (!cj_qctx_eval2(R->q, T, p, d1, d2)) return 0;
    cj_ivl sp2 = cj_iadd(cj_isqr(d1[0]), cj_isqr(d1[1]));
    if (!(sp2.lo > 0.0)) return 0;
    cj_ivl sp = cj_isqrt(sp2);
    cj_ivl D = cj_iv(R->d);
    cj_ivl N[2] = {cj_idiv(cj_ineg(d1[1]), sp), cj_idiv(d1[0], sp)};
    for (int k = 0; k < 2; ++k) o[k] = cj_iadd(p[k], cj_imul(D, N[k]));
    if (od) {
        /* N' = J (c''/|c'| - c' (c'.c'')/|c'|^3), J the +90 degree turn */
        cj_ivl dot = cj_iadd(cj_imul(d1[0], d2[0]), cj_imul(d1[1], d2[1]));
        cj_ivl sp3 = cj_imul(sp2, sp);
        cj_ivl g[2];
        for (int k = 0; k < 2; ++k)
            g[k] = cj_isub(cj_idiv(d2[k], sp), cj_idiv(cj_imul(d1[k], dot), sp3));
        cj_ivl Np[2] = {cj_ineg(g[1]), g[0]};
        for (int k = 0; k < 2; ++k) od[k] = cj_iadd(d1[k], cj_imul(D, Np[k]));
    }
    for (int k = 0; k < 2; ++k)
        if (!cj_ifinite(o[k]) || (od && !cj_ifinite(od[k]))) return 0;
    return 1;
}

/* Encloses o''(T) = c'' + d N'' with N = J T̂, T̂ = c'/s, s = |c'|:
 *   T̂' = P / s,  P = c'' - T̂ (T̂ . c''),  s' = T̂ . c'',
 *   T̂'' = (P' - T̂' s') / s,  P' = c''' - T̂' (T̂ . c'') - T̂ (T̂' . c'' + T̂ . c'''). */
static int offset_encl2(const orun *R, cj_ivl T, cj_ivl odd[2]) {
    cj_ivl p[2], c1[2], c2[2], c3[2];
    if (!cj_qctx_eval3(R->q, T, p, c1, c2, c3)) return 0;
    cj_ivl s2 = cj_iadd(cj_isqr(c1[0]), cj_isqr(c1[1]));
    if (!(s2.lo > 0.0)) return 0;
    cj_ivl s = cj_isqrt(s2), t[2], P[2], tp[2], Pp[2], tpp[2];
    for (int k = 0; k < 2; ++k) t[k] = cj_idiv(c1[k], s);
    cj_ivl tc2 = cj_iadd(cj_imul(t[0], c2[0]), cj_imul(t[1], c2[1]));
    for (int k = 0; k < 2; ++k) {
        P[k] = cj_isub(c2[k], cj_imul(t[k], tc2));
        tp[k] = cj_idiv(P[k], s);
    }
    cj_ivl tpc2 = cj_iadd(cj_imul(tp[0], c2[0]), cj_imul(tp[1], c2[1]));
    cj_ivl tc3 = cj_iadd(cj_imul(t[0], c3[0]), cj_imul(t[1], c3[1]));
    for (int k = 0; k < 2; ++k) {
        Pp[k] = cj_isub(cj_isub(c3[k], cj_imul(tp[k], tc2)), cj_imul(t[k], cj_iadd(tpc2, tc3)));
        tpp[k] = cj_idiv(cj_isub(Pp[k], cj_imul(tp[k], tc2)), s);
    }
    cj_ivl D = cj_iv(R->d);
    odd[0] = cj_iadd(c2[0], cj_imul(D, cj_ineg(tpp[1])));
    odd[1] = cj_iadd(c2[1], cj_imul(D, tpp[0]));
    return cj_ifinite(odd[0]) && cj_ifinite(odd[1]);
}

/* q'' over U: 6 Σ Δ²q_i B_i^1(u). */
static void cubic_dd(const double q[8], cj_ivl U, cj_ivl dd[2]) {
    cj_ivl S = cj_isub(cj_iv(1.0), U);
    for (int k = 0; k < 2; ++k) {
        cj_ivl a =
            cj_isub(cj_iadd(cj_iv(q[4 + k]), cj_iv(q[k])), cj_imul(cj_iv(2.0), cj_iv(q[2 + k])));
        cj_ivl b = cj_isub(cj_iadd(cj_iv(q[6 + k]), cj_iv(q[2 + k])),
                           cj_imul(cj_iv(2.0), cj_iv(q[4 + k])));
        dd[k] = cj_imul(cj_iv(6.0), cj_iadd(cj_imul(S, a), cj_imul(U, b)));
    }
}

/* Cubic q and its derivative over U (intervals), control points exact doubles. */
static void cubic_encl(const double q[8], cj_ivl U, cj_ivl v[2], cj_ivl dv[2]) {
    cj_ivl S = cj_isub(cj_iv(1.0), U);
    for (int k = 0; k < 2; ++k) {
        cj_ivl w[4];
        for (int i = 0; i < 4; ++i) w[i] = cj_iv(q[2 * i + k]);
        if (dv) {
            cj_ivl h[3];
            for (int i = 0; i < 3; ++i) h[i] = cj_imul(cj_iv(3.0), cj_isub(w[i + 1], w[i]));
            for (int r = 2; r > 0; --r)
                for (int i = 0; i < r; ++i) h[i] = cj_iadd(cj_imul(S, h[i]), cj_imul(U, h[i + 1]));
            dv[k] = h[0];
        }
        for (int r = 3; r > 0; --r)
            for (int i = 0; i < r; ++i) w[i] = cj_iadd(cj_imul(S, w[i]), cj_imul(U, w[i + 1]));
        v[k] = w[0];
    }
}

/* Proven bound of max |q(u) - o(a + (b-a) u)| over u in U (recursively refined); returns +inf
 * when it cannot be proven below tol within the depth. Second-order Taylor form around the
 * midpoint m: |e(m)| + |e'(m)| r + |e''(U)| r^2 / 2 per coordinate, r = |U| / 2, with
 * e' = q' - (b-a) o' and e'' = q'' - (b-a)^2 o''. */
static double prove(const orun *R, const double q[8], double a, double b, cj_ivl U, int depth) {
    double m = cj_imid(U);
    cj_ivl A = cj_iv(a), W = cj_isub(cj_iv(b), A);
    cj_ivl qm[2], qdm[2], om[2], odm[2];
    cubic_encl(q, cj_iv(m), qm, qdm);
    if (!offset_encl(R, cj_iadd(A, cj_imul(W, cj_iv(m))), om, odm)) return INFINITY;
    /* the error at the midpoint itself cannot shrink by refining U: give up early */
    double pm2 = 0.0;
    for (int k = 0; k < 2; ++k) {
        double em = cj_imag(cj_isub(qm[k], om[k]));
        pm2 += em * em;
    }
    if (!(sqrt(pm2) <= 0.9 * R->tol)) return INFINITY;
    cj_ivl T = cj_iadd(A, cj_imul(W, U)), qdd[2], odd[2];
    cubic_dd(q, U, qdd);
    int ok = offset_encl2(R, T, odd);
    double e2 = 0.0;
    if (ok) {
        double r = 0.5 * cj_iwidth(U) * (1.0 + 0x1p-50);
        cj_ivl W2 = cj_imul(W, W);
        for (int k = 0; k < 2; ++k) {
            double e0 = cj_imag(cj_isub(qm[k], om[k]));
            double e1 = cj_imag(cj_isub(qdm[k], cj_imul(W, odm[k])));
            double e2k = cj_imag(cj_isub(qdd[k], cj_imul(W2, odd[k])));
            double bound = cj_up(e0 + cj_up(cj_up(e1 * r) + cj_up(cj_up(e2k * r) * r * 0.5)));
            bound = cj_up(bound);
            e2 = cj_up(e2 + cj_up(bound * bound));
        }
    }
    double e = ok ? cj_up(sqrt(e2)) : INFINITY;
    if (e <= R->tol) return e;
    if (depth >= MAX_SUB_DEPTH) return INFINITY;
    cj_ivl L = cj_iv2(U.lo, m), Rr = cj_iv2(m, U.hi);
    double el = prove(R, q, a, b, L, depth + 1);
    if (!(el <= R->tol)) return INFINITY;
    return fmax(el, prove(R, q, a, b, Rr, depth + 1));
}

static void emit(orun *R, const double q[8], double e, double a, double b, double stretch_b) {
    if (R->count < R->cap && R->pts) memcpy(R->pts + 8 * (size_t)R->count, q, 8 * sizeof(double));
    if (R->count < R->cap && R->breaks) {
        R->breaks[R->count] = a;
        R->breaks[R->count + 1] = b;
    }
    ++R->count;
    R->deviation = fmax(R->deviation, e);
    double s = stretch_b > 0 ? 1.0 : stretch_b < 0 ? -1.0 : 0.0;
    if (s != 0.0 && R->last_sign != 0.0 && s != R->last_sign) ++R->cusps;
    if (s != 0.0) R->last_sign = s;
}

/* Pieces for [a,b], whose end values oa/oda (at a) are passed in so that neighbours share
 * bit-identical end points. */
static void piece(orun *R, double a, double b, const double oa[2], const double oda[2], int depth) {
    if (R->status != CJ_OK) return;
    double ob[2], odb[2], sb;
    if (!offset_at(R, b, ob, odb, &sb)) {
        R->status = CJ_ERR_DEGENERATE;
        R->bad_t = b;
        return;
    }
    double h = (b - a) / 3.0;
    double q[8] = {oa[0],
                   oa[1],
                   oa[0] + h * oda[0],
                   oa[1] + h * oda[1],
                   ob[0] - h * odb[0],
                   ob[1] - h * odb[1],
                   ob[0],
                   ob[1]};
    double e = INFINITY;
    int finite = 1;
    for (int i = 0; i < 8; ++i) finite &= isfinite(q[i]);
    if (finite) e = prove(R, q, a, b, cj_iv2(0.0, 1.0), 0);
    if (e <= R->tol) {
        emit(R, q, e, a, b, sb);
        return;
    }
    if (depth >= MAX_DEPTH) {
        R->status = CJ_ERR_CAP;
        R->bad_t = a;
        return;
    }
    double m = 0.5 * (a + b), om[2], odm[2], sm;
    if (!offset_at(R, m, om, odm, &sm)) {
        R->status = CJ_ERR_DEGENERATE;
        R->bad_t = m;
        return;
    }
    piece(R, a, m, oa, oda, depth + 1);
    piece(R, m, b, om, odm, depth + 1);
}

/* Cusps of a polynomial curve: the local minima of |c'|^2 over 64 n samples, refined by golden
 * section, where |c'| <= 2^-24 n times the control points' extent (a cusp to the resolution at
 * which the proofs fail). At most 8, sorted. */
static int find_cusps(const cj_bezier2 *c, double ext, double *cusp) {
    int n = c->degree, ns = 64 * n, count = 0;
    cj_bezier b = cj_bezier_view(n, 2, c->pts);
    double prev2 = INFINITY, prev = INFINITY, v[4];
    for (int i = 0; i <= ns + 1 && count < 8; ++i) {
        double g = INFINITY;
        if (i <= ns && cj_bezier_eval_derivs(&b, (double)i / ns, 1, v) == CJ_OK)
            g = v[2] * v[2] + v[3] * v[3];
        if (i >= 2 && prev <= prev2 && prev <= g && i - 1 > 0 && i - 1 < ns) {
            double lo = (double)(i - 2) / ns, hi = (double)i / ns;
            for (int it = 0; it < 80; ++it) {
                double m1 = lo + 0.381966011250105 * (hi - lo),
                       m2 = hi - 0.381966011250105 * (hi - lo);
                double g1 = INFINITY, g2 = INFINITY;
                if (cj_bezier_eval_derivs(&b, m1, 1, v) == CJ_OK) g1 = v[2] * v[2] + v[3] * v[3];
                if (cj_bezier_eval_derivs(&b, m2, 1, v) == CJ_OK) g2 = v[2] * v[2] + v[3] * v[3];
                if (g1 < g2)
                    hi = m2;
                else
                    lo = m1;
            }
            double t = 0.5 * (lo + hi);
            if (cj_bezier_eval_derivs(&b, t, 1, v) == CJ_OK &&
                sqrt(v[2] * v[2] + v[3] * v[3]) <= 0x1p-24 * n * ext &&
                (count == 0 || t > cusp[count - 1]))
                cusp[count++] = t;
        }
        prev2 = prev;
        prev = g;
    }
    return count;
}

/* The offset of a polynomial curve with cusps t_k (where c' = 0 and N flips): the proven pieces
 * on [0, t_1 - δ], [t_1 + δ, t_2 - δ], ..., and between them the arc of radius |d| about c(t_k)
 * from o(t_k - δ) to o(t_k + δ), turning the way the curve turns there (the sign of its
 * curvature on both sides), as proven cubic arcs (offset_internal.h). δ keeps c within tol / 4
 * of c(t_k) on [t_k - δ, t_k + δ]: |c(t) - c(t_k)| <= δ |c'(t_k)| + δ^2 M2 / 2, M2 = n (n - 1)
 * max |Δ^2 P| bounding |c''|. The true offset there lies within that of the circle about c(t_k),
 * so the arc stands for it (completing the jump of N at an exact cusp), within its radial bound
 * plus tol / 4. Restarts the run R; CJ_ERR_DEGENERATE when no cusp explains the failure. */
static cj_status offset_cusps(orun *R, double tol) {
    const cj_bezier2 *c = R->c;
    int n = c->degree;
    double ext = 0.0, M2 = 0.0;
    for (int i = 0; i <= n; ++i)
        for (int k = 0; k < 2; ++k) ext = fmax(ext, fabs(c->pts[2 * i + k] - c->pts[k]));
    for (int i = 0; i + 2 <= n; ++i)
        M2 = fmax(M2, hypot(c->pts[2 * i + 4] - 2 * c->pts[2 * i + 2] + c->pts[2 * i],
                            c->pts[2 * i + 5] - 2 * c->pts[2 * i + 3] + c->pts[2 * i + 1]));
    M2 *= n * (n - 1) * (1.0 + 0x1p-40);
    double cusp[8];
    int nc = find_cusps(c, ext, cusp);
    if (nc == 0 || !(M2 > 0.0)) return CJ_ERR_DEGENERATE;
    cj_bezier b = cj_bezier_view(n, 2, c->pts);
    double lo_t[9], hi_t[9], delta[8];
    for (int k = 0; k < nc; ++k) {
        double v[4];
        if (cj_bezier_eval_derivs(&b, cusp[k], 1, v) != CJ_OK) return CJ_ERR_DEGENERATE;
        double g = hypot(v[2], v[3]) * (1.0 + 0x1p-40), eps = 0.25 * tol;
        /* the largest δ with δ g + δ^2 M2 / 2 <= eps */
        delta[k] = (-g + sqrt(g * g + 2.0 * M2 * eps)) / M2 * (1.0 - 0x1p-30);
        if (!(delta[k] > 0.0)) return CJ_ERR_DEGENERATE;
    }
    for (int k = 0; k < nc; ++k) {
        lo_t[k] = k == 0 ? 0.0 : cusp[k - 1] + delta[k - 1];
        hi_t[k] = cusp[k] - delta[k];
        if (!(hi_t[k] > lo_t[k])) return CJ_ERR_DEGENERATE; /* a cusp at an end, or two too close */
    }
    lo_t[nc] = cusp[nc - 1] + delta[nc - 1];
    hi_t[nc] = 1.0;
    if (!(hi_t[nc] > lo_t[nc])) return CJ_ERR_DEGENERATE;
    R->count = 0;
    R->deviation = 0.0;
    R->cusps = 0;
    R->status = CJ_OK;
    for (int k = 0; k <= nc; ++k) {
        double oa[2], oda[2], sa;
        if (!offset_at(R, lo_t[k], oa, oda, &sa)) return CJ_ERR_DEGENERATE;
        if (k > 0) { /* the arc from the previous span's end to this one's start */
            double A[2], C[2], kap = 0.0;
            if (R->count >= 1 && R->count <= R->cap && R->pts)
                memcpy(A, R->pts + 8 * (size_t)(R->count - 1) + 6, sizeof A);
            else {
                double od[2], s;
                offset_at(R, hi_t[k - 1], A, od, &s);
            }
            cj_bezier_eval(&b, CJ_EVAL_DECASTELJAU, cusp[k - 1], C);
            for (int side = 0; side < 2; ++side) {
                double w[6];
                double t = side ? lo_t[k] : hi_t[k - 1];
                if (cj_bezier_eval_derivs(&b, t, 2, w) == CJ_OK) {
                    double sp = hypot(w[2], w[3]);
                    kap += (w[2] * w[5] - w[3] * w[4]) / (sp * sp * sp);
                }
            }
            double a0[2] = {A[0] - C[0], A[1] - C[1]}, b0[2] = {oa[0] - C[0], oa[1] - C[1]};
            double ang = atan2(a0[0] * b0[1] - a0[1] * b0[0], a0[0] * b0[0] + a0[1] * b0[1]);
            const double two_pi = 6.283185307179586;
            if (kap >= 0 && ang <= 0) ang += two_pi;
            if (kap < 0 && ang >= 0) ang -= two_pi;
            double arc[8 * CJ_OFFSET_ARC_MAX], bound;
            int na = cj_offset_arc(C, fabs(R->d), A, oa, ang, 0.75 * tol, arc, &bound);

            for (int i = 0; i < na; ++i) {
                double t0 = hi_t[k - 1] + (lo_t[k] - hi_t[k - 1]) * i / na;
                double t1 =
                    i + 1 == na ? lo_t[k] : hi_t[k - 1] + (lo_t[k] - hi_t[k - 1]) * (i + 1) / na;
                emit(R, arc + 8 * i, bound + 0.25 * tol, t0, t1, 0.0);
            }
            /* the next span starts at the arc's end, which is oa bit for bit */
        }
        piece(R, lo_t[k], hi_t[k], oa, oda, 0);
        if (R->status != CJ_OK) return R->status;
    }
    return CJ_OK;
}

cj_status cj_offset_curve(const cj_bezier2 *c, double d, double tol, double *pts, double *breaks,
                          int cap_pieces, int *npieces, double *deviation, int *cusps) {
    assert(c && npieces && deviation && (pts || cap_pieces == 0));
    cj_qctx q;
    cj_status st = cj_qctx_init(&q, c, "curve");
    if (st != CJ_OK) return st;
    if (!isfinite(d)) return cj_fail(CJ_ERR_NONFINITE, "offset distance d is %g", d);
    if (!isfinite(tol)) return cj_fail(CJ_ERR_NONFINITE, "tol is %g", tol);
    double scale = q.scale + fabs(d);
    if (!(tol > 0.0) || tol < scale * 0x1p-40)
        return cj_fail(CJ_ERR_ARGUMENT,
                       "tol %g must be > 0 and at least %g (2^-40 times the scale %g of the "
                       "curve and the distance)",
                       tol, scale * 0x1p-40, scale);
    if (c->degree < 1)
        return cj_fail(CJ_ERR_DEGENERATE, "curve: degree 0 is a point, it has no offset");
    orun R;
    memset(&R, 0, sizeof R);
    R.q = &q;
    R.c = c;
    R.d = d;
    R.tol = tol;
    R.pts = pts;
    R.breaks = breaks;
    R.cap = cap_pieces;
    double o0[2], od0[2], s0;
    if (!offset_at(&R, 0.0, o0, od0, &s0))
        return cj_fail(CJ_ERR_DEGENERATE, "curve: the derivative vanishes at t = 0, where the "
                                          "normal (so the offset) is undefined");
    R.last_sign = s0 > 0 ? 1.0 : s0 < 0 ? -1.0 : 0.0;
    /* the first split at the curve's own inflections and extremes is left to the adaptivity */
    piece(&R, 0.0, 1.0, o0, od0, 0);
    if ((R.status == CJ_ERR_DEGENERATE || R.status == CJ_ERR_CAP) && !c->weights) {
        /* a cusp of the curve itself: offset around it and join by an arc (offset_cusps) */
        double bad = R.bad_t;
        cj_status cs = offset_cusps(&R, tol);
        if (cs == CJ_OK) goto done;
        R.status = cs == CJ_ERR_BUFFER ? CJ_ERR_CAP : R.status;
        R.bad_t = bad;
    }
    if (R.status == CJ_ERR_DEGENERATE)
        return cj_fail(CJ_ERR_DEGENERATE,
                       "curve: the derivative vanishes near t = %.17g, where "
                       "the normal (so the offset) is undefined",
                       R.bad_t);
    if (R.status == CJ_ERR_CAP)
        return cj_fail(CJ_ERR_CAP,
                       "offset: no proof within %g after %d halvings near t = %.17g "
                       "(a cusp of the curve, or tol too small for its curvature)",
                       tol, MAX_DEPTH, R.bad_t);
done:
    *npieces = R.count;
    *deviation = R.deviation;
    if (cusps) *cusps = R.cusps;
    if (R.count > cap_pieces && pts)
        return cj_fail(CJ_ERR_BUFFER, "offset needs %d pieces, room for %d", R.count, cap_pieces);
    return CJ_OK;
}

/* ---- degree reduction ------------------------------------------------------------------- */

static double binom(int n, int k) {
    double r = 1.0;
    for (int i = 1; i <= k; ++i) r = r * (n - k + i) / i;
    return r;
}

cj_status cj_bezier_reduce(const cj_bezier *c, int m, double *out, double *bound) {
    assert(c && out && bound);
    cj_status st = cj_bezier_check(c, CJ_QUERY_MAX_DEGREE);
    if (st != CJ_OK) return st;
    int n = c->degree, dim = c->dim;
    if (m < 1 || m >= n)
        return cj_fail(CJ_ERR_DEGREE,
                       "target degree %d must be in 1..%d (the curve's degree %d "
                       "minus one)",
                       m, n - 1, n);
    enum { M = CJ_QUERY_MAX_DEGREE + 1 };
    double r[M * CJ_MAX_DIM];
    memcpy(r, c->pts, sizeof(double) * (size_t)dim);
    memcpy(r + (size_t)m * dim, c->pts + (size_t)n * dim, sizeof(double) * (size_t)dim);
    if (m > 1) {
        /* least squares for the inner points: rows i = 0..n of the elevation E (n+1 x m+1),
         * E[i][j] = C(m,j) C(n-m,i-j) / C(n,i), with the end columns moved to the right side */
        double A[M * M], B[M * CJ_MAX_DIM];
        int nu = m - 1;
        for (int i = 0; i <= n; ++i) {
            double e0 = 0, em = 0;
            for (int j = 0; j <= m; ++j) {
                double e = (i - j >= 0 && i - j <= n - m)
                               ? binom(m, j) * binom(n - m, i - j) / binom(n, i)
                               : 0.0;
                if (j == 0)
                    e0 = e;
                else if (j == m)
                    em = e;
                else
                    A[i * nu + (j - 1)] = e;
            }
            for (int k = 0; k < dim; ++k)
                B[i * dim + k] = c->pts[i * dim + k] - e0 * c->pts[k] - em * c->pts[n * dim + k];
        }
        lapack_int info = LAPACKE_dgels(LAPACK_ROW_MAJOR, 'N', n + 1, nu, dim, A, nu, B, dim);
        if (info != 0)
            return cj_fail(CJ_ERR_SINGULAR, "degree reduction: least squares failed (%d)",
                           (int)info);
        for (int j = 0; j < nu; ++j)
            for (int k = 0; k < dim; ++k) r[(j + 1) * dim + k] = B[j * dim + k];
    }
    for (int i = 0; i < (m + 1) * dim; ++i)
        if (!isfinite(r[i]))
            return cj_fail(CJ_ERR_RANGE, "degree reduction: control points overflow");
    /* the proof: elevate back and compare control points */
    double e[M * CJ_MAX_DIM];
    cj_bezier R = cj_bezier_view(m, dim, r);
    st = cj_bezier_elevate(&R, n - m, e);
    if (st != CJ_OK) return st;
    double dev = 0.0, scale = 0.0;
    for (int i = 0; i <= n; ++i) {
        double s2 = 0.0;
        for (int k = 0; k < dim; ++k) {
            double diff = c->pts[i * dim + k] - e[i * dim + k];
            s2 += diff * diff;
            scale = fmax(scale, fmax(fabs(c->pts[i * dim + k]), fabs(e[i * dim + k])));
        }
        dev = fmax(dev, sqrt(s2));
    }
    memcpy(out, r, sizeof(double) * (size_t)(m + 1) * dim);
    *bound = dev * (1.0 + 0x1p-48) + 4.0 * (n + 2) * 0x1p-53 * scale;
    return CJ_OK;
}

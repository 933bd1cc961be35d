/* Flattening: validation, homogeneous subcurves and the proven flatness / Wang bounds. */
#include "flatten_internal.h"

#include <assert.h>
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <string.h>

/* 2^e for -1022 <= e <= 1023 (a normal double), built from its bits. */
static inline double pow2_normal(int e) {
    const uint64_t bits = (uint64_t)(1023 + e) << 52;
    double v;
    memcpy(&v, &bits, sizeof v);
    return v;
}

cj_status cj_fl_init(cj_fl_curve *fc, const cj_bezier *c, const double *weights) {
    assert(fc != NULL && c != NULL);
    cj_status st = cj_bezier_check(c, CJ_BEZIER_MAX_DEGREE);
    if (st) return st;
    const int n = c->degree, d = c->dim;
    if (weights) {
        if (d > CJ_RBEZIER_MAX_DIM)
            return cj_fail(CJ_ERR_DIMENSION,
                           "rational curve dimension %d is outside 1..%d (one slot holds the "
                           "weight)",
                           d, CJ_RBEZIER_MAX_DIM);
        for (int i = 0; i <= n; ++i) {
            if (!isfinite(weights[i]))
                return cj_fail(CJ_ERR_NONFINITE, "weight %d is %s", i,
                               isnan(weights[i]) ? "NaN" : "infinite");
            if (!(weights[i] > 0.0))
                return cj_fail(CJ_ERR_ARGUMENT, "weight %d is %.17g, weights must be > 0", i,
                               weights[i]);
        }
    }
    fc->n = n;
    fc->d = d;
    fc->rational = weights != NULL;
    fc->pts = c->pts;
    fc->s2 = n <= 1000 ? pow2_normal(1 - n) : ldexp(1.0, 1 - n);
    fc->D = d + (weights != NULL);
    /* Coordinates and weights are scaled by powers of two (exact) to magnitudes near 1, so
     * that squared distances in the bounds neither overflow nor underflow; results are scaled
     * back by fc->escale. */
    double maxabs = 0.0, wmaxs = 1.0;
    for (int i = 0; i <= n; ++i) {
        for (int k = 0; k < d; ++k)
            if (fabs(c->pts[i * d + k]) > maxabs) maxabs = fabs(c->pts[i * d + k]);
        if (weights && (i == 0 || weights[i] > wmaxs)) wmaxs = weights[i];
    }
    int ew = 0;
    fc->escale = 0;
    if (maxabs >= DBL_MIN) {
        /* frexp's exponent read from the bits (maxabs is normal, possibly infinite; a
         * non-finite coordinate was rejected above) */
        uint64_t bits;
        memcpy(&bits, &maxabs, sizeof bits);
        fc->escale = (int)((bits >> 52) & 0x7ff) - 1022;
    } else if (maxabs > 0.0) {
        (void)frexp(maxabs, &fc->escale);
    }
    if (weights) (void)frexp(wmaxs, &ew);
    if (!weights && fc->escale > -1000 && fc->escale < 1000) {
        /* 2^-escale is a normal double here, so the product is exactly ldexp's result. */
        const double f = pow2_normal(-fc->escale);
        for (int i = 0; i < (n + 1) * d; ++i) fc->hom[i] = c->pts[i] * f;
    } else {
        for (int i = 0; i <= n; ++i) {
            const double wi = weights ? ldexp(weights[i], -ew) : 1.0;
            for (int k = 0; k < d; ++k) {
                const double x = ldexp(c->pts[i * d + k], -fc->escale);
                fc->hom[i * fc->D + k] = weights ? wi * x : x;
            }
            if (weights) fc->hom[i * fc->D + d] = wi;
        }
    }
    /* Rounding allowance: the subcurve (two de Casteljau splits, <= ~8 n u), the refinement's
     * two halvings (<= 2 n u), the division by the weight and the point-to-chord arithmetic
     * (O(d) u) each lose that much relative to the coordinates' magnitude; 32 (n+2) u
     * max|coordinate| covers all of them with a wide margin. */
    fc->slack = 32.0 * (double)(n + 2) * CJ_UNIT_ROUNDOFF * maxabs;
    if (weights) {
        double wmin = weights[0], wmax = weights[0];
        for (int i = 1; i <= n; ++i) {
            if (weights[i] < wmin) wmin = weights[i];
            if (weights[i] > wmax) wmax = weights[i];
        }
        /* Homogeneous arithmetic loses relative to max w_i |b_i|, then divides by a weight. */
        fc->slack *= 2.0 * wmax / wmin;
    }
    return CJ_OK;
}

/* Splits in place: w holds (m+1) points of D coords; keeps the part [0,t] (left=1) or [t,1]. */
static void split_keep(double *w, int m, int D, double t, int left) {
    const double s = 1.0 - t;
    if (left) {
        /* left points: first entry of each level, computed from the back. */
        for (int r = 1; r <= m; ++r)
            for (int i = m; i >= r; --i)
                for (int k = 0; k < D; ++k)
                    w[i * D + k] = s * w[(i - 1) * D + k] + t * w[i * D + k];
    } else {
        for (int r = m; r > 0; --r)
            for (int i = 0; i < r * D; ++i) w[i] = s * w[i] + t * w[i + D];
    }
}

void cj_fl_subcurve(const cj_fl_curve *fc, double a, double b, double *sub) {
    const int n = fc->n, D = fc->D;
    memcpy(sub, fc->hom, sizeof(double) * (size_t)(n + 1) * (size_t)D);
    if (b < 1.0) split_keep(sub, n, D, b, 1);
    if (a > 0.0) split_keep(sub, n, D, a / b, 0);
}

void cj_fl_split_half(const double *src, int n, int D, double *left, double *right) {
    double w[CJ_FL_WORK];
    memcpy(w, src, sizeof(double) * (size_t)(n + 1) * (size_t)D);
    for (int r = n;; --r) {
        memcpy(left + (size_t)(n - r) * D, w, sizeof(double) * (size_t)D);
        memcpy(right + (size_t)r * D, w + (size_t)r * D, sizeof(double) * (size_t)D);
        if (r == 0) break;
        for (int i = 0; i < r * D; ++i) w[i] = 0.5 * (w[i] + w[i + D]);
    }
}

/* Point i in the scaled coordinates. */
static void point_scaled(const cj_fl_curve *fc, const double *h, int i, double *out) {
    const int d = fc->d, D = fc->D;
    if (fc->rational) {
        const double w = h[i * D + d];
        for (int k = 0; k < d; ++k) out[k] = h[i * D + k] / w;
    } else {
        for (int k = 0; k < d; ++k) out[k] = h[i * D + k];
    }
}

void cj_fl_point(const cj_fl_curve *fc, const double *h, int i, double *out) {
    point_scaled(fc, h, i, out);
    for (int k = 0; k < fc->d; ++k) out[k] = ldexp(out[k], fc->escale);
}

void cj_fl_end(const cj_fl_curve *fc, int i, double *out) {
    memcpy(out, fc->pts + (size_t)i * (size_t)fc->d, sizeof(double) * (size_t)fc->d);
}

void cj_fl_eval(const cj_fl_curve *fc, double t, double *out) {
    double w[CJ_FL_WORK];
    const int n = fc->n, D = fc->D;
    memcpy(w, fc->hom, sizeof(double) * (size_t)(n + 1) * (size_t)D);
    split_keep(w, n, D, t, 0); /* w[0] = c(t) */
    cj_fl_point(fc, w, 0, out);
}

static double norm(const double *v, int d) {
    double s = 0.0;
    for (int k = 0; k < d; ++k) s += v[k] * v[k];
    return sqrt(s);
}

static double norm2(const double *v, int d) {
    double s = 0.0;
    for (int k = 0; k < d; ++k) s += v[k] * v[k];
    return s;
}

/* The bounds (a)-(c); *mid receives the distance of c(1/2) from the chord's line in the scaled
 * coordinates (a lower estimate of the true deviation, used only to decide whether refining
 * can pay). */
static double cheap_bound(const cj_fl_curve *fc, const double *sub, double *mid) {
    const int n = fc->n, d = fc->d, D = fc->D;
    *mid = 0.0;
    if (n <= 1) return 0.0; /* a segment (rational or not) is its own chord */
    /* Squared magnitudes throughout; one square root per bound at the end. */
    double pbuf[CJ_FL_WORK];
    double w[CJ_BEZIER_MAX_DEGREE + 1];
    const double *p = sub; /* Euclidean points, stride d */
    if (fc->rational) {
        for (int i = 0; i <= n; ++i) {
            point_scaled(fc, sub, i, pbuf + i * d);
            w[i] = sub[i * D + d];
        }
        p = pbuf;
        /* Standard form w_0 = w_n by the Möbius reparametrisation w_i -> w_i λ^i (same curve),
         * which makes the min-weight and weight-share factors below as small as possible. */
        const double lam = pow(w[0] / w[n], 1.0 / (double)n);
        double f = 1.0;
        for (int i = 0; i <= n; ++i) {
            w[i] *= f;
            f *= lam;
        }
    }
    const double *b0 = p, *bn = p + n * d;
    double v[CJ_MAX_DIM], L2 = 0.0;
    for (int k = 0; k < d; ++k) {
        v[k] = bn[k] - b0[k];
        L2 += v[k] * v[k];
    }
    const double invL2 = L2 > 0.0 ? 1.0 / L2 : 0.0;
    double maxdist2 = 0.0; /* max_i dist(b_i, S)^2 */
    double maxq2 = 0.0;    /* max_j |q_j|^2 for the perpendicular part */
    double mq2 = 0.0;      /* the same for the parametric error (polynomials) */
    int inside = 1;
    const double nn1 = (double)n * (double)(n - 1);
    double emid[CJ_MAX_DIM] = {0.0}, wmid = 0.0, binom = 1.0; /* Σ C(n,i) w_i e_i, Σ C(n,i) w_i */
    for (int i = 1; i < n; ++i) {
        double r[CJ_MAX_DIM], e[CJ_MAX_DIM];
        double s = 0.0;
        for (int k = 0; k < d; ++k) {
            r[k] = p[i * d + k] - b0[k];
            s += r[k] * v[k];
        }
        s *= invL2;
        for (int k = 0; k < d; ++k) e[k] = r[k] - s * v[k];
        const double e2 = norm2(e, d);
        double dist2;
        if (s < 0.0) {
            dist2 = norm2(r, d);
            inside = 0;
        } else if (s > 1.0) {
            double q[CJ_MAX_DIM];
            for (int k = 0; k < d; ++k) q[k] = p[i * d + k] - bn[k];
            dist2 = norm2(q, d);
            inside = 0;
        } else {
            dist2 = e2;
        }
        if (dist2 > maxdist2) maxdist2 = dist2;
        binom = binom * (double)(n - i + 1) / (double)i;
        const double bw = fc->rational ? binom * sub[i * D + d] : binom;
        for (int k = 0; k < d; ++k) emid[k] += bw * e[k];
        wmid += bw;
        /* q_{i-1} = w_i e_i n(n-1) / (i (n-i)) */
        const double coef = nn1 / ((double)i * (double)(n - i));
        const double wi = fc->rational ? w[i] : 1.0;
        const double q2 = wi * wi * coef * coef * e2;
        if (q2 > maxq2) maxq2 = q2;
        if (!fc->rational) {
            /* (b') parametric error e_i = b_i - chord(i/n), valid without projection */
            const double ti = (double)i / (double)n;
            for (int k = 0; k < d; ++k) e[k] = r[k] - ti * v[k];
            const double m2 = coef * coef * norm2(e, d);
            if (m2 > mq2) mq2 = m2;
        }
    }
    double wmin = 1.0, wE = 1.0, wI = 1.0;
    if (fc->rational) {
        wmin = w[0];
        wE = w[0] < w[n] ? w[0] : w[n];
        wI = 0.0;
        for (int i = 0; i <= n; ++i) {
            if (w[i] < wmin) wmin = w[i];
            if (i > 0 && i < n && w[i] > wI) wI = w[i];
        }
    }
    {
        const double wends = fc->rational ? sub[d] + sub[n * D + d] : 2.0;
        *mid = sqrt(norm2(emid, d)) / (wmid + wends); /* scaled coordinates */
    }
    /* (a) convexity: dist(c(t), S) <= g max_i dist(b_i, S). */
    const double s2 = fc->s2;
    const double g = wI * (1.0 - s2) / (wE * s2 + wI * (1.0 - s2));
    double best = g * sqrt(maxdist2);
    /* (b) factoring t(1-t) out of the perpendicular numerator (valid when every control point
     * projects onto S, so that distance to the line is distance to the segment). */
    if (inside) {
        const double bb = sqrt(maxq2) / (4.0 * wmin);
        if (bb < best) best = bb;
    }
    if (!fc->rational) {
        /* (c) second differences: |c - chord| <= n(n-1)/8 max|Δ² b|. */
        double md2 = 0.0;
        for (int i = 0; i + 2 <= n; ++i) {
            double e[CJ_MAX_DIM];
            for (int k = 0; k < d; ++k)
                e[k] = p[i * d + k] - 2.0 * p[(i + 1) * d + k] + p[(i + 2) * d + k];
            const double m2 = norm2(e, d);
            if (m2 > md2) md2 = m2;
        }
        const double bp = sqrt(mq2) / 4.0, bc = nn1 * sqrt(md2) / 8.0;
        if (bp < best) best = bp;
        if (bc < best) best = bc;
    }
    return ldexp(best, fc->escale);
}

double cj_fl_piece_bound(const cj_fl_curve *fc, const double *sub) {
    double mid;
    return cheap_bound(fc, sub, &mid);
}

/* Fixed data of one refinement: the chord S = a + [0,1] v in scaled coordinates. */
typedef struct refine_ctx {
    const cj_fl_curve *fc;
    double a[CJ_MAX_DIM], v[CJ_MAX_DIM];
    double invL2;
    double stop2; /* squared distance above which the piece is rejected anyway */
    double best;  /* largest part bound so far */
    double end2;  /* squared distance of the previous part's last point (this part's first) */
    int frame;    /* planar: points are (x, y[, w]) in the chord's frame (see refined_bound) */
    double L2;    /* |v|^2 */
} refine_ctx;

/* Squared distance from S of the point with chord coordinates (x, y): a + x v + y v⊥/|v|. */
static double frame_dist2(const refine_ctx *cx, double x, double y) {
    const double ex = x < 0.0 ? x : (x > 1.0 ? x - 1.0 : 0.0);
    return y * y + ex * ex * cx->L2;
}

/* Squared distance from S of point i (homogeneous h) in the caller's coordinates; tracks the
 * end and inner weights of rational parts. */
static double general_dist2(const refine_ctx *cx, const double *h, int i, int end, double *wE,
                            double *wI) {
    const cj_fl_curve *fc = cx->fc;
    const int d = fc->d;
    double p[CJ_MAX_DIM], sp = 0.0;
    if (fc->rational) {
        const double wi = h[d];
        for (int k = 0; k < d; ++k) p[k] = h[k] / wi;
        if (end)
            *wE = (i == 0 || wi < *wE) ? wi : *wE;
        else if (wi > *wI)
            *wI = wi;
    } else {
        for (int k = 0; k < d; ++k) p[k] = h[k];
    }
    for (int k = 0; k < d; ++k) {
        p[k] -= cx->a[k];
        sp += p[k] * cx->v[k];
    }
    sp *= cx->invL2;
    if (sp < 0.0) sp = 0.0;
    if (sp > 1.0) sp = 1.0;
    double e2 = 0.0;
    for (int k = 0; k < d; ++k) {
        const double e = p[k] - sp * cx->v[k];
        e2 += e * e;
    }
    return e2;
}

/* Bound of one part (control points h, homogeneous) on its distance to S; see below. */
static void refine_part(refine_ctx *cx, const double *h) {
    const cj_fl_curve *fc = cx->fc;
    const int n = fc->n, D = fc->D;
    double dE2 = 0.0, dI2 = 0.0, wE = 0.0, wI = 0.0;
    for (int i = 0; i <= n; ++i, h += D) {
        const int end = i == 0 || i == n;
        if (i == 0 && !fc->rational) { /* parts are visited left to right and share ends */
            dE2 = cx->end2;
            continue;
        }
        double e2;
        if (cx->frame) {
            if (fc->rational) {
                const double wi = h[2];
                e2 = frame_dist2(cx, h[0] / wi, h[1] / wi);
                if (end)
                    wE = (i == 0 || wi < wE) ? wi : wE;
                else if (wi > wI)
                    wI = wi;
            } else {
                e2 = frame_dist2(cx, h[0], h[1]);
            }
        } else {
            e2 = general_dist2(cx, h, i, end, &wE, &wI);
        }
        if (end) {
            if (e2 > dE2) dE2 = e2;
            if (i == n) cx->end2 = e2;
        } else if (e2 > dI2) {
            dI2 = e2;
        }
    }
    if (dE2 <= cx->best * cx->best && dI2 <= cx->best * cx->best) return; /* bj <= best */
    const double dE = sqrt(dE2), dI = sqrt(dI2);
    const double sigma = fc->rational ? wE * fc->s2 / (wE * fc->s2 + wI * (1.0 - fc->s2)) : fc->s2;
    const double bj = dI > dE ? dE + (1.0 - sigma) * (dI - dE) : dE;
    if (bj > cx->best) cx->best = bj;
}
/* Splits the part h at 1/2 (each level 0.5 (x + y), one rounding, so a halving loses at most
 * n u max|coordinate|) and refines both halves, depth more levels. */
static void refine_rec(refine_ctx *cx, const double *h, int depth) {
    if (depth == 0) {
        refine_part(cx, h);
        return;
    }
    const int n = cx->fc->n, D = cx->fc->D;
    double L[(CJ_FL_REFINE_MAX_DEGREE + 1) * (CJ_MAX_DIM + 1)];
    double R[(CJ_FL_REFINE_MAX_DEGREE + 1) * (CJ_MAX_DIM + 1)];
    for (int i = 0; i < (n + 1) * D; ++i) R[i] = h[i];
    for (int r = n; r > 0; --r) {
        for (int k = 0; k < D; ++k) L[(n - r) * D + k] = R[k];
        for (int i = 0; i < r * D; ++i) R[i] = 0.5 * (R[i] + R[i + D]);
    }
    for (int k = 0; k < D; ++k) L[n * D + k] = R[k];
    refine_rec(cx, L, depth - 1);
    if (cx->best * cx->best > cx->stop2) return;
    refine_rec(cx, R, depth - 1);
}

/* Refinement (d): the piece halved (de Casteljau) CJ_FL_REFINE_LEVELS times into 2^k parts;
 * each part lies in the convex hull of its own control points and dist(., S) is convex, so on
 * part j
 *     dist(c(t), S) <= dE_j + (1 - σ_j) max(0, dI_j - dE_j),
 * dE_j the larger distance of the part's end points (points of the curve), dI_j the largest
 * of its inner control points, σ_j the smallest weight share of the end points (2^(1-n) for
 * polynomials, wE s / (wE s + wI (1-s)) with the part's own weights for rational ones). This
 * converges to max dist(c(t), S) as the parts shrink (their hulls close in on the curve).
 * Rounding: k more halvings lose k n u max|coordinate|, inside the allowance fc->slack.
 * Stops early (returning a value > stop) once a part exceeds stop. */
static double refined_bound(const cj_fl_curve *fc, const double *sub, double stop) {
    const int n = fc->n, d = fc->d;
    refine_ctx cx;
    cx.fc = fc;
    point_scaled(fc, sub, 0, cx.a);
    point_scaled(fc, sub, n, cx.v);
    double L2 = 0.0;
    for (int k = 0; k < d; ++k) {
        cx.v[k] -= cx.a[k];
        L2 += cx.v[k] * cx.v[k];
    }
    cx.invL2 = L2 > 0.0 ? 1.0 / L2 : 0.0;
    const double st = ldexp(stop, -fc->escale);
    cx.stop2 = st * st;
    cx.best = 0.0;
    cx.end2 = 0.0; /* the first part starts at the chord's own end point */
    cx.L2 = L2;
    cx.frame = d == 2 && L2 > 0.0;
    if (cx.frame) {
        /* Planar: the (homogeneous) control points in the chord's frame, x along v (0 and 1 at
         * the ends of S), y the signed distance from its line; the map is linear, so it commutes
         * with the halvings, and each part point's distance from S costs a few flops. Rounding:
         * O(u) relative to max|coordinate| more, inside the allowance. */
        const int D = fc->D;
        const double invL = 1.0 / sqrt(L2);
        double T[(CJ_FL_REFINE_MAX_DEGREE + 1) * 3];
        for (int i = 0; i <= n; ++i) {
            const double *h = sub + i * D;
            const double w = fc->rational ? h[2] : 1.0;
            const double rx = h[0] - w * cx.a[0], ry = h[1] - w * cx.a[1];
            T[i * D] = (rx * cx.v[0] + ry * cx.v[1]) * cx.invL2;
            T[i * D + 1] = (cx.v[0] * ry - cx.v[1] * rx) * invL;
            if (fc->rational) T[i * D + 2] = w;
        }
        refine_rec(&cx, T, CJ_FL_REFINE_LEVELS);
    } else {
        refine_rec(&cx, sub, CJ_FL_REFINE_LEVELS);
    }
    return ldexp(cx.best, fc->escale);
}

double cj_fl_piece_bound_refined(const cj_fl_curve *fc, const double *sub, double refine_above,
                                 double refine_below, double min_gain, double stop) {
    double mid;
    const double cheap = cheap_bound(fc, sub, &mid);
    /* Refining cannot go below the distance of c(1/2), so it cannot pay when that is close. */
    if (!(cheap > refine_above) || !(cheap <= refine_below) || fc->n <= 1 ||
        fc->n > CJ_FL_REFINE_MAX_DEGREE || !(cheap > min_gain * ldexp(mid, fc->escale)))
        return cheap;
    const double r = refined_bound(fc, sub, stop < cheap ? stop : cheap);
    return r < cheap ? r : cheap;
}

double cj_fl_wang_coefficient(const cj_fl_curve *fc) {
    const int n = fc->n, d = fc->d, D = fc->D;
    if (n <= 1) return 0.0;
    const double nn1 = (double)n * (double)(n - 1);
    if (!fc->rational) {
        double M = 0.0;
        for (int i = 0; i + 2 <= n; ++i) {
            double e[CJ_MAX_DIM];
            for (int k = 0; k < d; ++k)
                e[k] =
                    fc->hom[i * D + k] - 2.0 * fc->hom[(i + 1) * D + k] + fc->hom[(i + 2) * D + k];
            const double m2 = norm(e, d);
            if (m2 > M) M = m2;
        }
        return ldexp(nn1 * M / 8.0, fc->escale);
    }
    /* Rational: with o the centre of the control points' box, P = Σ w_i (b_i - o) B_i and
     * W = Σ w_i B_i, the chord point c_L = P_L / W_L of the linear interpolants satisfies
     * c - c_L = ((P - P_L) - (c_L - o)(W - W_L)) / W, so on a step of length h
     * |c - c_L| <= h^2/8 (max|P''| + R max|W''|) / w_min. */
    double lo[CJ_MAX_DIM], hi[CJ_MAX_DIM], o[CJ_MAX_DIM], pt[CJ_MAX_DIM];
    for (int i = 0; i <= n; ++i) {
        point_scaled(fc, fc->hom, i, pt);
        for (int k = 0; k < d; ++k) {
            if (i == 0 || pt[k] < lo[k]) lo[k] = pt[k];
            if (i == 0 || pt[k] > hi[k]) hi[k] = pt[k];
        }
    }
    for (int k = 0; k < d; ++k) o[k] = 0.5 * (lo[k] + hi[k]);
    double R = 0.0, Mwb = 0.0, Mw = 0.0, wmin = fc->hom[d];
    for (int i = 0; i <= n; ++i) {
        point_scaled(fc, fc->hom, i, pt);
        for (int k = 0; k < d; ++k) pt[k] -= o[k];
        const double r = norm(pt, d);
        if (r > R) R = r;
        if (fc->hom[i * D + d] < wmin) wmin = fc->hom[i * D + d];
    }
    for (int i = 0; i + 2 <= n; ++i) {
        double e[CJ_MAX_DIM];
        const double w0 = fc->hom[i * D + d], w1 = fc->hom[(i + 1) * D + d],
                     w2 = fc->hom[(i + 2) * D + d];
        for (int k = 0; k < d; ++k)
            e[k] = (fc->hom[i * D + k] - w0 * o[k]) - 2.0 * (fc->hom[(i + 1) * D + k] - w1 * o[k]) +
                   (fc->hom[(i + 2) * D + k] - w2 * o[k]);
        const double m2 = norm(e, d);
        if (m2 > Mwb) Mwb = m2;
        const double mw = fabs(w0 - 2.0 * w1 + w2);
        if (mw > Mw) Mw = mw;
    }
    return ldexp(nn1 * (Mwb + R * Mw) / (8.0 * wmin), fc->escale);
}

/* Compensated de Casteljau (Graillat, Langlois & Louvet, "Algorithms for accurate, validated
 * and fast polynomial evaluation", Japan J. Indust. Appl. Math. 26, 2009): each convex
 * combination is split by error-free transformations into its rounded value and its exact
 * rounding error; the errors are propagated by a second de Casteljau triangle and added back at
 * the end. For t in [0,1] and barring underflow the result is as accurate as de Casteljau run
 * in twice the working precision, then rounded (their Theorem):
 *
 *     |res - c(t)| <= u |c(t)| + 2 gamma(3n)^2 Σ|b_i| B_i^n(t).
 *
 * Algorithm. 1 - t = r + rho exactly (TwoSum). At level j, entry i (b̂ = the plain triangle):
 *     r b̂_i = s + ps,  t b̂_{i+1} = v + pv   (TwoProd, exact with fma)
 *     s + v = b̂_i^(j) + sig                    (TwoSum, exact)
 * so the local error of the level is e = ps + pv + sig + rho b̂_i exactly, and the exact triangle
 * is b = b̂ + ∂ with ∂_i^(j) = (1-t) ∂_i^(j-1) + t ∂_{i+1}^(j-1) + e_i^(j), ∂^(0) = 0. The
 * kernel runs this recurrence in floating point as
 *     w = fl((ps + pv) + fma(rho, b̂_i, sig)),   ∂̂_i^(j) = fma(r, ∂̂_i, fma(t, ∂̂_{i+1}, w)),
 * i.e. with r for 1 - t (dropping rho ∂̂, |rho| <= u|r|), and returns res = fl(b̂_0 + ∂̂_0).
 *
 * A-posteriori bound (derived here; it is what `bound` returns). Let
 *     M_i^(j) = |e_i^(j)| + (|r| + |rho|) M_i^(j-1) + |t| M_{i+1}^(j-1),   M^(0) = 0,
 * where |e| means |ps| + |pv| + |sig| + |rho b̂_i|. Counting roundings: ŵ = e(1+θ2) (two
 * roundings), the two fmas add one each, so ∂̂^(j) = r∂̂_i(1+θ1) + t∂̂_{i+1}(1+θ2) + e(1+θ4), and
 * by induction |∂̂^(j)| <= (1+γ(2j+2)) M^(j). The error E = ∂̂ - ∂ then satisfies
 *     E^(j) = (1-t)E_i + t E_{i+1} + rθ1∂̂_i - rho∂̂_i + tθ2∂̂_{i+1} + eθ4,
 * whose local terms are at most γ(2)(1+γ(2n)) M_i^(j) + γ(4)|e_i^(j)|. Propagated to the apex
 * with the weights |1-t| <= |r| + |rho| and |t| that M itself uses, level j contributes at most
 * γ(2)(1+γ(2n)) M_0^(n), and the e terms together at most γ(4) M_0^(n), so
 *     |res - c(t)| <= u|res| + γ(2n+4)(1+γ(2n)) M_0^(n).
 * The kernel computes M in floating point (about 4 roundings per level, all of non-negative
 * terms, so M <= (1+γ(4n+6)) M̂) and returns
 *     bound = (u|res| + γ(3n+4)(1+γ(3n+4)) M̂)(1+4u) + underflow allowance:
 * the extra n u of first order in γ(3n+4) pays for every second-order term above and for the
 * roundings of this formula (for any n < 2^40). It holds for any finite t, not just [0,1].
 * Typically M̂ ~ 3nu Σ|b_i|B_i(|t|), so the bound is ~9n^2 u^2 Σ|b_i|B_i(|t|) + u|res|: below
 * the a-priori 18n^2 u^2 Σ|b_i|B_i + u|c| for n >= 2 and much smaller when errors cancel.
 *
 * Underflow. When a product falls below 2^-1022 TwoProd is no longer error-free and every
 * rounding may add an absolute error of eta/2 = 2^-1075. At most 8 such roundings per entry and
 * level (2 TwoProds, the fma with rho, the two ∂ fmas, 3 in M) each grow by at most
 * A = |1-t| + |t| per level, hence the allowance 8 (n+1) eta A^n. */
#include "bezier_internal.h"
#include "eft_internal.h"
#include "eval_internal.h"

#include <assert.h>
#include <math.h>

double cj_underflow_allowance(int n, double t, double ops) {
    if (n == 0) return 0.0; /* a constant is returned without any operation */
    double growth = 1.0;
    if (t < 0.0 || t > 1.0) {
        const double a = (fabs(1.0 - t) + fabs(t)) * (1.0 + 0x1p-50);
        growth = pow(a, (double)n) * (1.0 + 0x1p-50);
    }
    return ops * (double)(n + 1) * CJ_ETA * growth;
}

/* One entry of one level: the rounded combination and the floating-point local error. */
#define CJ_COMP_STEP(b0, b1, sum, w)                                                               \
    do {                                                                                           \
        double s_, ps_, v_, pv_, sig_;                                                             \
        cj_two_prod(r, (b0), &s_, &ps_);                                                           \
        cj_two_prod(t, (b1), &v_, &pv_);                                                           \
        cj_two_sum(s_, v_, &(sum), &sig_);                                                         \
        (w) = (ps_ + pv_) + fma(rho, (b0), sig_);                                                  \
    } while (0)

/* The kernel with the dimension as a compile-time constant at each call site below, so that
 * the inner loops unroll; no copy of the control points (the first level reads them). */
CJ_ALWAYS_INLINE void comp_run(const double *restrict p, int n, int d, double t,
                               double *restrict out) {
    if (n == 0) {
        for (int k = 0; k < d; ++k) out[k] = p[k];
        return;
    }
    double b[CJ_BEZIER_WORK], db[CJ_BEZIER_WORK];
    double r, rho;
    cj_two_sum(1.0, -t, &r, &rho);
    for (int i = 0; i < n * d; ++i) {
        double w;
        CJ_COMP_STEP(p[i], p[i + d], b[i], w);
        db[i] = w; /* ∂^(0) = 0 */
    }
    for (int lvl = n - 1; lvl > 0; --lvl)
        for (int i = 0; i < lvl * d; ++i) {
            double sum, w;
            CJ_COMP_STEP(b[i], b[i + d], sum, w);
            db[i] = fma(r, db[i], fma(t, db[i + d], w));
            b[i] = sum;
        }
    for (int k = 0; k < d; ++k) out[k] = b[k] + db[k];
}

/* The same arithmetic (bit-identical result) plus the magnitude recurrence M. */
#define CJ_COMP_STEP_M(b0, b1, sum, w, e)                                                          \
    do {                                                                                           \
        double s_, ps_, v_, pv_, sig_;                                                             \
        cj_two_prod(r, (b0), &s_, &ps_);                                                           \
        cj_two_prod(t, (b1), &v_, &pv_);                                                           \
        cj_two_sum(s_, v_, &(sum), &sig_);                                                         \
        (w) = (ps_ + pv_) + fma(rho, (b0), sig_);                                                  \
        (e) = fabs(ps_) + fabs(pv_) + fabs(sig_) + fabs(rho * (b0));                               \
    } while (0)

CJ_ALWAYS_INLINE void comp_run_bound(const double *restrict p, int n, int d, double t,
                                     double *restrict out, double *restrict bound) {
    if (n == 0) {
        for (int k = 0; k < d; ++k) {
            out[k] = p[k];
            bound[k] = 0.0; /* a constant is returned exactly */
        }
        return;
    }
    double b[CJ_BEZIER_WORK], db[CJ_BEZIER_WORK], m[CJ_BEZIER_WORK];
    double r, rho;
    cj_two_sum(1.0, -t, &r, &rho);
    const double ar = fabs(r) + fabs(rho), at = fabs(t);
    for (int i = 0; i < n * d; ++i) {
        double w, e;
        CJ_COMP_STEP_M(p[i], p[i + d], b[i], w, e);
        db[i] = w;
        m[i] = e;
    }
    for (int lvl = n - 1; lvl > 0; --lvl)
        for (int i = 0; i < lvl * d; ++i) {
            double sum, w, e;
            CJ_COMP_STEP_M(b[i], b[i + d], sum, w, e);
            db[i] = fma(r, db[i], fma(t, db[i + d], w));
            m[i] = e + ar * m[i] + at * m[i + d];
            b[i] = sum;
        }
    const double g = cj_gamma(3 * n + 4);
    const double uf = cj_underflow_allowance(n, t, 8.0);
    for (int k = 0; k < d; ++k) {
        out[k] = b[k] + db[k];
        bound[k] = (CJ_UNIT_ROUNDOFF * fabs(out[k]) + g * (1.0 + g) * m[k]) *
                       (1.0 + 4.0 * CJ_UNIT_ROUNDOFF) +
                   uf;
    }
}

void cj_compensated_kernel(const cj_bezier *c, double t, double *out, double *bound) {
    const int n = c->degree;
    if (bound) {
        switch (c->dim) {
        case 2:
            comp_run_bound(c->pts, n, 2, t, out, bound);
            break;
        case 3:
            comp_run_bound(c->pts, n, 3, t, out, bound);
            break;
        default:
            comp_run_bound(c->pts, n, c->dim, t, out, bound);
            break;
        }
        return;
    }
#define CJ_COMP_DIM(d)                                                                             \
    do {                                                                                           \
        if (n == 3) /* cubics: fully unrolled, the triangle in registers; same bits */             \
            comp_run(c->pts, 3, d, t, out);                                                        \
        else                                                                                       \
            comp_run(c->pts, n, d, t, out);                                                        \
    } while (0)
    switch (c->dim) {
    case 1:
        CJ_COMP_DIM(1);
        break;
    case 2:
        CJ_COMP_DIM(2);
        break;
    case 3:
        CJ_COMP_DIM(3);
        break;
    case 4:
        CJ_COMP_DIM(4);
        break;
    default:
        comp_run(c->pts, n, c->dim, t, out);
        break;
    }
#undef CJ_COMP_DIM
}

cj_status cj_bezier_eval_compensated(const cj_bezier *c, double t, double *out, double *bound) {
    assert(out != NULL);
    cj_status st = cj_bezier_check(c, CJ_BEZIER_MAX_DEGREE);
    if (st) return st;
    if ((st = cj_check_param(t, "parameter t"))) return st;
    double v[CJ_MAX_DIM], b[CJ_MAX_DIM];
    cj_compensated_kernel(c, t, v, bound ? b : NULL);
    if ((st = cj_check_value(v, c->dim, t))) return st;
    cj_copy_point(out, v, c->dim);
    if (bound) cj_copy_point(bound, b, c->dim);
    return CJ_OK;
}

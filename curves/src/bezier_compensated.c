/* Compensated de Casteljau (Graillat, Langlois & Louvet, "Algorithms for accurate, validated
 * and fast polynomial evaluation", 2009): each convex combination is split by error-free
 * transformations into its rounded value and its exact rounding error; the errors are
 * propagated by a second de Casteljau triangle and added back at the end. The result is as
 * accurate as de Casteljau run in twice the working precision, then rounded:
 *
 *     |res - c(t)| <= u |c(t)| + 2 gamma(3n)^2 Σ|b_i| B_i^n(t).
 *
 * A-posteriori bound. Write 1 - t = r + rho exactly (TwoSum). The exact triangle satisfies
 * b_i^(j) = b̂_i^(j) + ∂_i^(j) with
 *     ∂_i^(j) = (1-t) ∂_i^(j-1) + t ∂_{i+1}^(j-1) + e_i^(j),
 *     e_i^(j) = π_s + π_v + σ + rho b̂_i^(j-1)          (π, σ: exact product and sum errors).
 * The algorithm evaluates this recurrence in floating point with r for 1-t; the rounding of
 * each level costs at most gamma(3) relative to the magnitude recurrence
 *     M_i^(j) = |e_i^(j)| + (|r| + |rho|) M_i^(j-1) + |t| M_{i+1}^(j-1),
 * and dropping rho·∂ costs at most u M. Summing over n levels and the final rounding:
 *     |res - c(t)| <= u |res| + gamma(3n+4) (1 + gamma(3n+4)) M_0^(n),
 * all evaluated in floating point and inflated by (1 + 4u) so the computed bound is an
 * upper bound of the exact one. */
#include "bezier_internal.h"
#include "eft_internal.h"

#include <assert.h>
#include <math.h>
#include <string.h>

void cj_compensated_kernel(const cj_bezier *c, double t, double *out, double *bound) {
    const int n = c->degree, d = c->dim;
    const size_t count = (size_t)(n + 1) * (size_t)d;
    double b[CJ_BEZIER_WORK], db[CJ_BEZIER_WORK];
    double r, rho;
    cj_two_sum(1.0, -t, &r, &rho);
    memcpy(b, c->pts, sizeof(double) * count);
    memset(db, 0, sizeof(double) * count);
    if (!bound) {
        for (int lvl = n; lvl > 0; --lvl)
            for (int i = 0; i < lvl * d; ++i) {
                double s, ps, v, pv, sum, sig;
                cj_two_prod(r, b[i], &s, &ps);
                cj_two_prod(t, b[i + d], &v, &pv);
                cj_two_sum(s, v, &sum, &sig);
                const double w = (ps + pv) + fma(rho, b[i], sig);
                db[i] = fma(r, db[i], fma(t, db[i + d], w));
                b[i] = sum;
            }
        for (int k = 0; k < d; ++k) out[k] = b[k] + db[k];
        return;
    }
    double m[CJ_BEZIER_WORK];
    memset(m, 0, sizeof(double) * count);
    const double ar = fabs(r) + fabs(rho), at = fabs(t);
    for (int lvl = n; lvl > 0; --lvl)
        for (int i = 0; i < lvl * d; ++i) {
            double s, ps, v, pv, sum, sig;
            cj_two_prod(r, b[i], &s, &ps);
            cj_two_prod(t, b[i + d], &v, &pv);
            cj_two_sum(s, v, &sum, &sig);
            const double w = (ps + pv) + fma(rho, b[i], sig);
            const double e = fabs(ps) + fabs(pv) + fabs(sig) + fabs(rho * b[i]);
            db[i] = fma(r, db[i], fma(t, db[i + d], w));
            m[i] = e + ar * m[i] + at * m[i + d];
            b[i] = sum;
        }
    const double g = cj_gamma(3 * n + 4);
    for (int k = 0; k < d; ++k) {
        out[k] = b[k] + db[k];
        bound[k] = (CJ_UNIT_ROUNDOFF * fabs(out[k]) + g * (1.0 + g) * m[k]) *
                   (1.0 + 4.0 * CJ_UNIT_ROUNDOFF);
    }
}

cj_status cj_bezier_eval_compensated(const cj_bezier *c, double t, double *out, double *bound) {
    assert(out != NULL);
    cj_status st = cj_bezier_check(c, CJ_BEZIER_MAX_DEGREE);
    if (st) return st;
    if ((st = cj_check_param(t, "parameter t"))) return st;
    cj_compensated_kernel(c, t, out, bound);
    return CJ_OK;
}

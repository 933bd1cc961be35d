/* Circular arcs as cubic pieces with a proven radial bound (offset_internal.h). */
#include "offset_internal.h"
#include "query_internal.h"

#include <math.h>
#include <string.h>

#define PI 3.14159265358979323846

/* Proven max | |q(u) - C| - r | over u in [0,1]: |q - C|^2 is a degree-6 polynomial whose Bernstein
 * coefficients sum_{i+j=k} C(3,i) C(3,j) / C(6,k) (P_i - C).(P_j - C) enclose its range. */
static double radial_bound(const double q[8], const double C[2], double r) {
    static const double b3[4] = {1, 3, 3, 1}, b6[7] = {1, 6, 15, 20, 15, 6, 1};
    cj_ivl P[4][2];
    for (int i = 0; i < 4; ++i)
        for (int k = 0; k < 2; ++k) P[i][k] = cj_isub(cj_iv(q[2 * i + k]), cj_iv(C[k]));
    double lo = INFINITY, hi = -INFINITY;
    for (int k = 0; k <= 6; ++k) {
        cj_ivl s = cj_iv(0.0);
        for (int i = 0; i <= 3; ++i) {
            int j = k - i;
            if (j < 0 || j > 3) continue;
            cj_ivl dot = cj_iadd(cj_imul(P[i][0], P[j][0]), cj_imul(P[i][1], P[j][1]));
            s = cj_iadd(s, cj_imul(cj_iv(b3[i] * b3[j]), dot));
        }
        s = cj_idiv(s, cj_iv(b6[k]));
        lo = fmin(lo, s.lo);
        hi = fmax(hi, s.hi);
    }
    double rlo = lo > 0 ? cj_down(sqrt(lo)) : 0.0, rhi = cj_up(sqrt(fmax(hi, 0.0)));
    return fmax(cj_up(r - rlo), cj_up(rhi - r));
}

int cj_offset_arc(const double C[2], double r, const double A[2], const double B[2], double sweep,
                  double tol, double *out, double *bound) {
    double a0 = atan2(A[1] - C[1], A[0] - C[0]);
    int n = (int)ceil(fabs(sweep) / (0.5 * PI) - 1e-9);
    if (n < 1) n = 1;
    for (;; n *= 2) {
        if (n > CJ_OFFSET_ARC_MAX) n = CJ_OFFSET_ARC_MAX;
        double step = sweep / n, h = 4.0 / 3.0 * tan(fabs(step) / 4.0) * r, worst = 0.0;
        double sg = sweep >= 0 ? 1.0 : -1.0;
        for (int i = 0; i < n; ++i) {
            double f0 = a0 + step * i, f1 = a0 + step * (i + 1), *q = out + 8 * i;
            double p0[2] = {C[0] + r * cos(f0), C[1] + r * sin(f0)};
            double p3[2] = {C[0] + r * cos(f1), C[1] + r * sin(f1)};
            if (i == 0)
                memcpy(p0, A, sizeof p0);
            else
                memcpy(p0, out + 8 * (i - 1) + 6, sizeof p0); /* bit for bit */
            if (i == n - 1) memcpy(p3, B, sizeof p3);
            q[0] = p0[0], q[1] = p0[1];
            q[2] = p0[0] - sg * h * sin(f0), q[3] = p0[1] + sg * h * cos(f0);
            q[4] = p3[0] + sg * h * sin(f1), q[5] = p3[1] - sg * h * cos(f1);
            q[6] = p3[0], q[7] = p3[1];
            worst = fmax(worst, radial_bound(q, C, r));
        }
        *bound = worst;
        if (worst <= tol || n == CJ_OFFSET_ARC_MAX) return n;
    }
}

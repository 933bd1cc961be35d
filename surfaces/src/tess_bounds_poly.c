/* Second-derivative bounds of a polynomial patch over boxes, from its difference nets.
 *
 * WHY. The bound of a triangle needs Muu >= |S_uu|, Muv >= |S_uv|, Mvv >= |S_vv| over a box B
 * (a grid cell, a strip, a zipper triangle's own box). Splitting the control net down to B and
 * differencing it (then dividing by B's widths) costs four generic de Casteljau splits per box.
 * Differencing commutes with restriction: the second u-differences of the net restricted to B
 * are wu^2 times the restriction to B of the second u-differences of the whole net (likewise
 * Δ_uΔ_v with wu wv, Δ²_v with wv^2). So the patch's three difference nets are formed ONCE,
 *     Duu_ij = Δ²_u b_ij (degree (m-2, n)), Duv_ij = Δ_uΔ_v b_ij (m-1, n-1),
 *     Dvv_ij = Δ²_v b_ij (m, n-2),
 * and over B the Bernstein coefficients of S_uu / (m(m-1)) (etc.) in the PATCH's parameters are
 * the restrictions of these nets to B: no division by the box's widths, and a grid cell reuses
 * the restriction in v of its strip (cj_tess_strip_restrict) and only restricts in u (degree
 * m-2, m-1 and m curves: a few dozen lerps). By the convex hull property,
 *     |S_uu| <= m(m-1) max |restricted Duu|  on B  (and m n, n(n-1) for S_uv, S_vv).
 * ROUNDING (proven, per coordinate; the norm adds sqrt 3): a difference (b2 - 2 b1) + b0 or
 * (b11 - b10) - (b01 - b00) is off by <= 8u times the sum of its terms' magnitudes (mag); a
 * restriction to [a,b] is two de Casteljau splits, each level a convex combination
 * s x + t y (s = fl(1 - t)) off by <= 4u max(|x|, |y|) and not amplifying earlier errors, over
 * at most 2(m + n) levels in all, hence off by <= gamma(8(m + n) + 8) A with A the largest
 * |coordinate| of the computed net plus its differencing error. The additive term err_* below
 * is the sum of both; the norms' own rounding is a factor (1 + 4u). As in the rest of the
 * tessellator, the rounding of the split parameters (a/b, which moves B by an ulp) is
 * ignored. */
#include "casteljau/tessellate.h"
#include "patch_internal.h"
#include "tessellate_internal.h"

#include <assert.h>
#include <math.h>
#include <string.h>

/* Restricts the curve of `deg`+1 points (dimension 3, point stride `stride` doubles) to
 * [a, b] subset of [0, 1], in place. */
static void restrict_curve(double *p, int deg, size_t stride, double a, double b) {
    if (deg <= 0) return;
    if (b < 1.0) { /* keep [0, b]: p[i] becomes the i-th point of the left part */
        const double t = b, s = 1.0 - b;
        for (int r = 1; r <= deg; ++r)
            for (int i = deg; i >= r; --i)
                for (int k = 0; k < 3; ++k)
                    p[stride * (size_t)i + (size_t)k] =
                        s * p[stride * (size_t)(i - 1) + (size_t)k] +
                        t * p[stride * (size_t)i + (size_t)k];
    }
    if (a > 0.0) { /* keep the part [a/b, 1] of what is left */
        const double t = b < 1.0 ? a / b : a, s = 1.0 - t;
        for (int r = 1; r <= deg; ++r)
            for (int i = 0; i <= deg - r; ++i)
                for (int k = 0; k < 3; ++k)
                    p[stride * (size_t)i + (size_t)k] = s * p[stride * (size_t)i + (size_t)k] +
                                                        t * p[stride * (size_t)(i + 1) + (size_t)k];
    }
}

/* Largest Euclidean norm among `count` 3D points. */
static double max_norm(const double *p, int count) {
    double mx = 0.0;
    for (int q = 0; q < count; ++q) {
        const double x = p[3 * q], y = p[3 * q + 1], z = p[3 * q + 2];
        const double n2 = x * x + y * y + z * z;
        if (n2 > mx) mx = n2;
    }
    return sqrt(mx);
}

void cj_tess_diff_setup(ptess *P) {
    assert(!P->rational);
    const int m = P->m, n = P->n, m1 = m + 1;
    const double *h = P->h;
#define B(i, j, k) h[3 * ((j)*m1 + (i)) + (k)]
    double a_uu = 0.0, a_uv = 0.0, a_vv = 0.0; /* largest |coordinate| */
    double g_uu = 0.0, g_uv = 0.0, g_vv = 0.0; /* largest term magnitude sum */
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i + 2 <= m; ++i)
            for (int k = 0; k < 3; ++k) {
                const double d = (B(i + 2, j, k) - 2.0 * B(i + 1, j, k)) + B(i, j, k);
                const double g =
                    fabs(B(i + 2, j, k)) + 2.0 * fabs(B(i + 1, j, k)) + fabs(B(i, j, k));
                P->duu[3 * (j * (m - 1) + i) + k] = d;
                a_uu = fmax(a_uu, fabs(d));
                g_uu = fmax(g_uu, g);
            }
    for (int j = 0; j + 1 <= n; ++j)
        for (int i = 0; i + 1 <= m; ++i)
            for (int k = 0; k < 3; ++k) {
                const double d =
                    (B(i + 1, j + 1, k) - B(i + 1, j, k)) - (B(i, j + 1, k) - B(i, j, k));
                const double g = fabs(B(i + 1, j + 1, k)) + fabs(B(i + 1, j, k)) +
                                 fabs(B(i, j + 1, k)) + fabs(B(i, j, k));
                P->duv[3 * (j * m + i) + k] = d;
                a_uv = fmax(a_uv, fabs(d));
                g_uv = fmax(g_uv, g);
            }
    for (int j = 0; j + 2 <= n; ++j)
        for (int i = 0; i <= m; ++i)
            for (int k = 0; k < 3; ++k) {
                const double d = (B(i, j + 2, k) - 2.0 * B(i, j + 1, k)) + B(i, j, k);
                const double g =
                    fabs(B(i, j + 2, k)) + 2.0 * fabs(B(i, j + 1, k)) + fabs(B(i, j, k));
                P->dvv[3 * (j * m1 + i) + k] = d;
                a_vv = fmax(a_vv, fabs(d));
                g_vv = fmax(g_vv, g);
            }
#undef B
    const double gr = cj_gamma(8 * (m + n) + 8), s3 = sqrt(3.0);
    P->err_uu = s3 * (gr * (a_uu + 8.0 * U_ROUND * g_uu) + 8.0 * U_ROUND * g_uu);
    P->err_uv = s3 * (gr * (a_uv + 8.0 * U_ROUND * g_uv) + 8.0 * U_ROUND * g_uv);
    P->err_vv = s3 * (gr * (a_vv + 8.0 * U_ROUND * g_vv) + 8.0 * U_ROUND * g_vv);
}

/* Restricts the net d of (deg_u+1) x (deg_v+1) points (3D) to [v0,v1] in v, into out. */
static void restrict_v(const double *d, int deg_u, int deg_v, double v0, double v1, double *out) {
    const int cnt = (deg_u + 1) * (deg_v + 1);
    memcpy(out, d, sizeof(double) * 3 * (size_t)cnt);
    for (int i = 0; i <= deg_u; ++i)
        restrict_curve(out + 3 * i, deg_v, 3 * (size_t)(deg_u + 1), v0, v1);
}

void cj_tess_strip_restrict(const ptess *P, double v0, double v1, tess_strip *s) {
    const int m = P->m, n = P->n;
    s->v0 = v0;
    s->v1 = v1;
    if (m >= 2) restrict_v(P->duu, m - 2, n, v0, v1, s->uu);
    if (m >= 1 && n >= 1) restrict_v(P->duv, m - 1, n - 1, v0, v1, s->uv);
    if (n >= 2) restrict_v(P->dvv, m, n - 2, v0, v1, s->vv);
}

/* max norm of the strip net (deg_u+1) x (rows) restricted to [u0,u1] in u. */
static double cell_norm(const double *d, int deg_u, int rows, double u0, double u1) {
    double w[(CJ_PATCH_MAX_DEGREE + 1) * (CJ_PATCH_MAX_DEGREE + 1) * 3];
    const int cnt = (deg_u + 1) * rows;
    memcpy(w, d, sizeof(double) * 3 * (size_t)cnt);
    for (int j = 0; j < rows; ++j) restrict_curve(w + 3 * (j * (deg_u + 1)), deg_u, 3, u0, u1);
    return max_norm(w, cnt);
}

dbounds cj_tess_cell_bounds(const ptess *P, const tess_strip *s, double u0, double u1) {
    const int m = P->m, n = P->n;
    const double inf = 1.0 + 4.0 * U_ROUND;
    dbounds b = {0.0, 0.0, 0.0};
    if (m >= 2)
        b.uu = (cell_norm(s->uu, m - 2, n + 1, u0, u1) + P->err_uu) * inf * (double)(m * (m - 1));
    if (m >= 1 && n >= 1)
        b.uv = (cell_norm(s->uv, m - 1, n, u0, u1) + P->err_uv) * inf * (double)(m * n);
    if (n >= 2)
        b.vv = (cell_norm(s->vv, m, n - 1, u0, u1) + P->err_vv) * inf * (double)(n * (n - 1));
    return b;
}

dbounds cj_tess_strip_bounds(const ptess *P, double u0, double u1, double v0, double v1) {
    tess_strip s;
    cj_tess_strip_restrict(P, v0, v1, &s);
    return cj_tess_cell_bounds(P, &s, u0, u1);
}

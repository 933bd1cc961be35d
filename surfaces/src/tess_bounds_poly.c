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

/* Restricts the net d of (deg_u+1) x (deg_v+1) points (3D) to [u0,u1] in u, into out. */
static void restrict_u(const double *d, int deg_u, int deg_v, double u0, double u1, double *out) {
    const int cnt = (deg_u + 1) * (deg_v + 1);
    memcpy(out, d, sizeof(double) * 3 * (size_t)cnt);
    for (int j = 0; j <= deg_v; ++j) restrict_curve(out + 3 * j * (deg_u + 1), deg_u, 3, u0, u1);
}

void cj_tess_ustrip_restrict(const ptess *P, double u0, double u1, tess_strip *s) {
    const int m = P->m, n = P->n;
    s->v0 = u0; /* the strip's range, here in u */
    s->v1 = u1;
    if (m >= 2) restrict_u(P->duu, m - 2, n, u0, u1, s->uu);
    if (m >= 1 && n >= 1) restrict_u(P->duv, m - 1, n - 1, u0, u1, s->uv);
    if (n >= 2) restrict_u(P->dvv, m, n - 2, u0, u1, s->vv);
}

/* max norm of the u-strip net (cols) x (deg_v+1) restricted to [v0,v1] in v. */
static double vcell_norm(const double *d, int cols, int deg_v, double v0, double v1) {
    double w[(CJ_PATCH_MAX_DEGREE + 1) * (CJ_PATCH_MAX_DEGREE + 1) * 3];
    const int cnt = cols * (deg_v + 1);
    memcpy(w, d, sizeof(double) * 3 * (size_t)cnt);
    for (int i = 0; i < cols; ++i) restrict_curve(w + 3 * i, deg_v, 3 * (size_t)cols, v0, v1);
    return max_norm(w, cnt);
}

dbounds cj_tess_ucell_bounds(const ptess *P, const tess_strip *s, double v0, double v1) {
    const int m = P->m, n = P->n;
    const double inf = 1.0 + 4.0 * U_ROUND;
    dbounds b = {0.0, 0.0, 0.0};
    if (m >= 2)
        b.uu = (vcell_norm(s->uu, m - 1, n, v0, v1) + P->err_uu) * inf * (double)(m * (m - 1));
    if (m >= 1 && n >= 1)
        b.uv = (vcell_norm(s->uv, m, n - 1, v0, v1) + P->err_uv) * inf * (double)(m * n);
    if (n >= 2)
        b.vv = (vcell_norm(s->vv, m + 1, n - 2, v0, v1) + P->err_vv) * inf * (double)(n * (n - 1));
    return b;
}

dbounds cj_tess_strip_bounds(const ptess *P, double u0, double u1, double v0, double v1) {
    tess_strip s;
    cj_tess_strip_restrict(P, v0, v1, &s);
    return cj_tess_cell_bounds(P, &s, u0, u1);
}

/* ---- walking a strip cell by cell (u degree <= 3, v degree <= 3: bicubic, biquadratic and
 * lower) ----------------------------------------------------------------------------------- *
 * WHY. Along a strip the cells [u_i, u_{i+1}] share their grid lines. The restriction of a row
 * curve p (degree d <= 3, in u) to [a,b] has the coefficients given by its blossom,
 *     d = 1: p(a), p(b);   d = 2: p(a), B(a,b), p(b);   d = 3: p(a), B(a,a,b), B(a,b,b), p(b),
 * and de Casteljau at a line t gives p(t) and the last level's points Q0(t) = B(t,..,t,0),
 * Q1(t) = B(t,..,t,1), from which B(a,b) = (1-b) Q0(a) + b Q1(a) (d = 2) and
 * B(a,a,b) = (1-b) Q0(a) + b Q1(a), B(a,b,b) = (1-a) Q0(b) + a Q1(b) (d = 3). So each grid line
 * is evaluated once per strip (cj_tess_line) and a cell costs one or two lerps per row
 * (cj_tess_cell_walk) instead of two de Casteljau splits. Every coefficient is still a chain of
 * at most d convex combinations after the strip's restriction in v (<= 2n levels), within the
 * gamma(8(m + n) + 8) rounding term of the difference nets: the bound is the one proven above,
 * evaluated on the same coefficients (up to rounding). */

/* max of two finite values, inline (fmax is a library call) */
static inline double maxd(double x, double y) {
    return x > y ? x : y;
}

static inline void lerp3(const double *x, const double *y, double t, double *out) {
    const double s = 1.0 - t;
    out[0] = s * x[0] + t * y[0];
    out[1] = s * x[1] + t * y[1];
    out[2] = s * x[2] + t * y[2];
}

static inline double norm3(const double *x) {
    return sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
}

int cj_tess_walkable(const ptess *P) {
    return !P->rational && P->m <= 3 && P->n <= 3;
}

/* One net at line t: `count` curves of degree deg <= 3, point k of curve c at
 * net + 3 (c cstride + k pstride). */
static void line_net(const double *net, int deg, int count, int pstride, int cstride, double t,
                     double (*pt)[3][3], double *nrm) {
    double mx = 0.0;
    for (int c = 0; c < count; ++c) {
        const double *p0 = net + 3 * c * cstride, *p1 = p0 + 3 * pstride, *p2 = p1 + 3 * pstride,
                     *p3 = p2 + 3 * pstride;
        double(*o)[3] = pt[c];
        switch (deg) {
        case 0:
            memcpy(o[0], p0, 3 * sizeof(double));
            break;
        case 1:
            lerp3(p0, p1, t, o[0]);
            break;
        case 2:
            lerp3(p0, p1, t, o[1]);
            lerp3(p1, p2, t, o[2]);
            lerp3(o[1], o[2], t, o[0]);
            break;
        default: {
            double l[3][3];
            lerp3(p0, p1, t, l[0]);
            lerp3(p1, p2, t, l[1]);
            lerp3(p2, p3, t, l[2]);
            lerp3(l[0], l[1], t, o[1]);
            lerp3(l[1], l[2], t, o[2]);
            lerp3(o[1], o[2], t, o[0]);
        }
        }
        mx = maxd(mx, norm3(o[0]));
    }
    *nrm = mx;
}

/* Line t of a strip walked in u (dir 0: a v-strip, rows are curves in u) or in v (dir 1: a
 * u-strip, columns are curves in v). Net uu has m-1 columns and n+1 rows, uv m and n, vv m+1
 * and n-1. */
static void line_dir(const ptess *P, const tess_strip *s, double t, int dir, tess_line *L) {
    const int m = P->m, n = P->n;
    const int cols[3] = {m - 1, m, m + 1}, rows[3] = {n + 1, n, n - 1};
    const double *net[3] = {s->uu, s->uv, s->vv};
    const int have[3] = {m >= 2, m >= 1 && n >= 1, n >= 2};
    L->t = t;
    for (int k = 0; k < 3; ++k) {
        L->nrm[k] = 0.0;
        L->deg[k] = dir ? rows[k] - 1 : cols[k] - 1;
        L->count[k] = dir ? cols[k] : rows[k];
        if (!have[k]) {
            L->deg[k] = -1;
            continue;
        }
        if (dir)
            line_net(net[k], rows[k] - 1, cols[k], cols[k], 1, t, L->pt[k], &L->nrm[k]);
        else
            line_net(net[k], cols[k] - 1, rows[k], 1, cols[k], t, L->pt[k], &L->nrm[k]);
    }
}

void cj_tess_line(const ptess *P, const tess_strip *s, double t, tess_line *L) {
    line_dir(P, s, t, 0, L);
}

void cj_tess_uline(const ptess *P, const tess_strip *s, double t, tess_line *L) {
    line_dir(P, s, t, 1, L);
}

/* Largest norm among the interior coefficients of one net's rows over [A->t, B->t]. */
static double cell_interior(const double (*pa)[3][3], const double (*pb)[3][3], int deg, int rows,
                            double a, double b) {
    double mx = 0.0, c[3];
    if (deg < 2) return 0.0;
    for (int j = 0; j < rows; ++j) {
        lerp3(pa[j][1], pa[j][2], b, c); /* B(a,b) or B(a,a,b) */
        mx = maxd(mx, norm3(c));
        if (deg == 3) {
            lerp3(pb[j][1], pb[j][2], a, c); /* B(a,b,b) */
            mx = maxd(mx, norm3(c));
        }
    }
    return mx;
}

dbounds cj_tess_cell_walk(const ptess *P, const tess_line *A, const tess_line *B) {
    const int m = P->m, n = P->n;
    const double inf = 1.0 + 4.0 * U_ROUND, a = A->t, b = B->t;
    const double err[3] = {P->err_uu, P->err_uv, P->err_vv};
    const double scale[3] = {(double)(m * (m - 1)), (double)(m * n), (double)(n * (n - 1))};
    double r[3] = {0.0, 0.0, 0.0};
    for (int k = 0; k < 3; ++k) {
        if (A->deg[k] < 0) continue;
        const double x = maxd(maxd(A->nrm[k], B->nrm[k]),
                              cell_interior(A->pt[k], B->pt[k], A->deg[k], A->count[k], a, b));
        r[k] = (x + err[k]) * inf * scale[k];
    }
    const dbounds out = {r[0], r[1], r[2]};
    return out;
}

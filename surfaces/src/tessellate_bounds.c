/* Proven bounds of the patch tessellation: second-derivative bounds of control nets (the
 * polynomial case), the rational triangle bound, and the edge-flatness count. Kept apart from
 * the mesh building because this is where the proof of tessellate.h lives, line by line. */
#include "casteljau/tessellate.h"
#include "patch_internal.h"
#include "tessellate_internal.h"

#include <assert.h>
#include <math.h>
#include <string.h>

/* Norm of a difference vector (dimension d) inflated by 8u times the magnitude of its terms
 * (covers the rounding of the difference and of the norm). */
static double diff_norm(const double *d, const double *mag, int dim) {
    double e2 = 0.0;
    for (int k = 0; k < dim; ++k) {
        const double e = fabs(d[k]) + 8.0 * U_ROUND * mag[k];
        e2 += e * e;
    }
    return sqrt(e2) * (1.0 + 4.0 * U_ROUND);
}

/* Second-derivative bounds of a polynomial net of dimension dim (1..3) and degree (m,n) over
 * [0,1]^2. */
static dbounds net_bounds(const double *h, int dim, int m, int n) {
    dbounds b = {0.0, 0.0, 0.0};
    const int m1 = m + 1;
#define P(i, j) (h + dim * ((j)*m1 + (i)))
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= m; ++i) {
            double d[3], mag[3];
            if (i + 2 <= m) {
                for (int k = 0; k < dim; ++k) {
                    d[k] = (P(i + 2, j)[k] - 2.0 * P(i + 1, j)[k]) + P(i, j)[k];
                    mag[k] = fabs(P(i + 2, j)[k]) + 2.0 * fabs(P(i + 1, j)[k]) + fabs(P(i, j)[k]);
                }
                const double x = diff_norm(d, mag, dim);
                if (x > b.uu) b.uu = x;
            }
            if (j + 2 <= n) {
                for (int k = 0; k < dim; ++k) {
                    d[k] = (P(i, j + 2)[k] - 2.0 * P(i, j + 1)[k]) + P(i, j)[k];
                    mag[k] = fabs(P(i, j + 2)[k]) + 2.0 * fabs(P(i, j + 1)[k]) + fabs(P(i, j)[k]);
                }
                const double x = diff_norm(d, mag, dim);
                if (x > b.vv) b.vv = x;
            }
            if (i + 1 <= m && j + 1 <= n) {
                for (int k = 0; k < dim; ++k) {
                    d[k] = (P(i + 1, j + 1)[k] - P(i + 1, j)[k]) - (P(i, j + 1)[k] - P(i, j)[k]);
                    mag[k] = fabs(P(i + 1, j + 1)[k]) + fabs(P(i + 1, j)[k]) +
                             fabs(P(i, j + 1)[k]) + fabs(P(i, j)[k]);
                }
                const double x = diff_norm(d, mag, dim);
                if (x > b.uv) b.uv = x;
            }
        }
#undef P
    b.uu *= (double)m * (double)(m - 1);
    b.vv *= (double)n * (double)(n - 1);
    b.uv *= (double)m * (double)n;
    return b;
}

int cj_tess_edge_segments(const double *pts, int degree, double tol, int cap) {
    assert(pts != NULL);
    if (degree < 2) return 1;
    double mx = 0.0;
    for (int a = 0; a + 2 <= degree; ++a) {
        double d[3], mag[3];
        for (int k = 0; k < 3; ++k) {
            d[k] = (pts[3 * (a + 2) + k] - 2.0 * pts[3 * (a + 1) + k]) + pts[3 * a + k];
            mag[k] = fabs(pts[3 * (a + 2) + k]) + 2.0 * fabs(pts[3 * (a + 1) + k]) +
                     fabs(pts[3 * a + k]);
        }
        const double x = diff_norm(d, mag, 3);
        if (x > mx) mx = x;
    }
    const double m2 = mx * (double)degree * (double)(degree - 1);
    if (m2 == 0.0) return 1;
    const double k = ceil(sqrt(m2 / (8.0 * tol)));
    if (!(k <= (double)cap)) return cap + 1;
    return k < 1.0 ? 1 : (int)k;
}

/* Homogeneous rational bound (see RATIONAL BOUND, (Q)) of a box from its homogeneous sub-net:
 * out[0..2] = effective second-derivative bounds (M_Y + R M_w) / wlo in the box's local
 * coordinates, out[3] = the constant rounding term 2 (sqrt(3) eY + R ew) / wlo. */
void cj_tess_homog_bounds(const ptess *P, const double *sub, double out[4]) {
    const int m = P->m, n = P->n;
    const int count = (m + 1) * (n + 1);
    double wmin = INFINITY, lo[3] = {INFINITY, INFINITY, INFINITY},
           hi[3] = {-INFINITY, -INFINITY, -INFINITY}, pmax = 0.0;
    for (int q = 0; q < count; ++q) {
        const double w = sub[4 * q + 3];
        wmin = fmin(wmin, w);
        for (int k = 0; k < 3; ++k) {
            const double x = sub[4 * q + k] / w;
            lo[k] = fmin(lo[k], x);
            hi[k] = fmax(hi[k], x);
            pmax = fmax(pmax, fabs(x));
        }
    }
    const double ew = P->suberr_w;
    const double wlow = (wmin - ew) * (1.0 - 4.0 * U_ROUND);
    if (!(wlow > 0.0)) {
        out[0] = out[1] = out[2] = out[3] = INFINITY;
        return;
    }
    double c[3], cmax = 0.0;
    for (int k = 0; k < 3; ++k) {
        c[k] = 0.5 * (lo[k] + hi[k]);
        cmax = fmax(cmax, fabs(c[k]));
    }
    double Y[(CJ_PATCH_MAX_DEGREE + 1) * (CJ_PATCH_MAX_DEGREE + 1) * 3],
        W[(CJ_PATCH_MAX_DEGREE + 1) * (CJ_PATCH_MAX_DEGREE + 1)];
    double r2 = 0.0, ymag = 0.0;
    for (int q = 0; q < count; ++q) {
        const double w = sub[4 * q + 3];
        double d2 = 0.0;
        for (int k = 0; k < 3; ++k) {
            Y[3 * q + k] = sub[4 * q + k] - c[k] * w;
            ymag = fmax(ymag, fabs(sub[4 * q + k]) + fabs(c[k]) * w);
            const double x = sub[4 * q + k] / w - c[k];
            d2 += x * x;
        }
        r2 = fmax(r2, d2);
        W[q] = w;
    }
    /* R: the computed distances round (a few ulps), the computed points b'_ij are off the
     * exact ones by <= (suberr_x + |b'| suberr_w) / w per coordinate */
    const double R = (sqrt(r2) * (1.0 + 8.0 * U_ROUND) +
                      sqrt(3.0) * (P->suberr_x + pmax * ew) / wlow + 4.0 * U_ROUND * pmax) *
                     (1.0 + 4.0 * U_ROUND);
    const double eY = P->suberr_x + cmax * ew + cj_gamma(3) * ymag;
    const dbounds by = net_bounds(Y, 3, m, n), bw = net_bounds(W, 1, m, n);
    const double inf = 1.0 + 16.0 * U_ROUND;
    out[0] = (by.uu + R * bw.uu) / wlow * inf;
    out[1] = (by.uv + R * bw.uv) / wlow * inf;
    out[2] = (by.vv + R * bw.vv) / wlow * inf;
    out[3] = 2.0 * (sqrt(3.0) * eY + R * ew) / wlow * inf;
}

/* RATIONAL BOUND. The patch is S = X / w with X (3D) and w > 0 polynomial patches: the
 * numerator and denominator of the homogeneous net (w_ij b_ij, w_ij). Take a triangle T with
 * parameter vertices p_i inside a box B (its grid cell, or its own (u,v) box), local
 * coordinates (s,t) in [0,1]^2 on B, barycentric coordinates λ_i(x), mesh vertices V_i, and
 * wlo <= w <= whi on B (the smallest and largest coefficient of B's weight sub-net: Bernstein
 * coefficients, all > 0). Two bounds, each on the distance from S(x) to a point of the mesh
 * triangle; the smaller is kept (bF when it is needed at all: see floor below).
 *
 * (L) bF, on |S(x) - Lm(x)|, Lm the mesh's linear interpolant of the V_i. Take the affine map
 * L(s,t) = A + Bs + Ct (3D coefficients) computed from the V_i. Then
 *     S - L = (X - w L) / w = F / w,    F = X - w L,
 * and F is a POLYNOMIAL patch of degree (m+1, n+1): writing L in bilinear Bernstein form
 * (its corner values L_ab, a, b in {0,1}) and using B_i^m B_a^1 = c(i,a) B_{i+a}^{m+1} with
 * c(i,0) = (m+1-i)/(m+1), c(i,1) = (i+1)/(m+1), its Bernstein coefficients are
 *     F_kl = Σ_{a,b} cu(k,a) cv(l,b) (X_{k-a,l-b} - w_{k-a,l-b} L_ab),
 * cu(k,0) = (m+1-k)/(m+1), cu(k,1) = k/(m+1) (terms with k-a or l-b out of range absent), X, w
 * the coefficients of B's homogeneous sub-net. For x in T,
 *     |F(x)| <= |F(x) - Σ λ_i F(p_i)| + max_i |F(p_i)|,
 * the first term bounded by the polynomial case's interpolation bound IB(F) = (Fuu ds^2 +
 * 2 Fuv ds dt + Fvv dt^2) / 8 with the second differences of F's net (degree m+1, n+1) and the
 * triangle's extents ds, dt in local coordinates; and F(p_i) = w(p_i) (S(p_i) - L(p_i)), where
 * |S(p_i) - L(p_i)| <= |S(p_i) - V_i| + |V_i - L(p_i)| <= verterr + e, verterr the rounding of
 * a vertex and e >= max_i |V_i - L(p_i)| (computed, plus its rounding). Since L and Lm are both
 * affine, |L - Lm| <= e on T (its max is at a vertex). So
 *     |S(x) - Lm(x)| <= [ IB(F) + whi (verterr + e) ] / wlo + e.
 * F's second derivatives are w S_uu + 2 w_u (S_u - L_u) + w_uu (S - L) etc., so the weight's
 * variation enters only through S_u - L_u and S - L, which vanish as the triangle shrinks: as
 * tight as the polynomial bound (and 0 along a cylinder's straight direction).
 *
 * (Q) bQ, on |S(x) - Q(x)|, Q(x) = Xl / wl = Σ μ_i V_i with Xl = Σ λ_i X(p_i), wl = Σ λ_i w(p_i),
 * μ_i = λ_i w(p_i) / wl >= 0 summing to 1: a point of the triangle (the homogeneous linear
 * interpolant, projected). For any point c, with Y = X - c w (net w_ij (b_ij - c)) and
 * Yl = Xl - c wl its interpolant:
 *     S - Q = Y/w - Yl/wl = (Y - Yl)/w + (Yl/wl)(wl - w)/w = [(Y - Yl) - (Q - c)(w - wl)] / w,
 * so |S - Q| <= (|Y - Yl| + R |w - wl|) / wlo with R >= |Q - c|: both are interpolation errors
 * of polynomial patches, bounded from the second differences of B's sub-nets of Y (3D) and w
 * (scalar): the polynomial formula with M = (M_Y + R M_w) / wlo (cj_tess_homog_bounds). c is the
 * centre of the box of B's Euclidean sub-net points b'_ij and R = max |b'_ij - c| (the exact
 * vertices lie on the patch over B, in the hull of the b'_ij, and Q is in their triangle), so
 * Y = w (b - c) is small on B and R M_w is of third order. The mesh's vertices are off the
 * exact ones by <= verterr, which moves Q by as much. Exact for a rational-linear
 * parametrisation (a segment with unequal end weights), where (L) pays for the uneven speed;
 * (L) is better where the weight varies across a straight direction.
 *
 * Both are distances from S(x) to a point of the mesh triangle, so min(bF, bQ) bounds the
 * distance surface -> mesh; as x -> Lm(x) and x -> Q(x) both map T onto the mesh triangle, it
 * also bounds mesh -> surface. Rounding: the sub-net is exact up to suberr_x (numerator
 * coordinates) and suberr_w (weights) per coefficient (at most 2(m+n) levels of s a + t b);
 * forming F_kl (Y) adds gamma(8) (gamma(3)) of its terms' magnitudes; a polynomial whose
 * coefficients move by eps per coordinate moves by <= eps everywhere (partition of unity), so
 * its interpolation error by <= 2 sqrt(3) eps (3D norm) (2 eps for w), which is added. The
 * rounding of the split parameters (moving B by a few ulps) is ignored, as in the polynomial
 * case. A triangle degenerate in (u,v) gets bQ only; wlo <= 0 gives +INF.
 * in_cell: B is the grid cell loaded in P->cellnet (cj_tess_load_cell); otherwise the triangle's
 * own (u,v) box (the whole square for a triangle without area in u or v). Returns min(bF, bQ), or
 * just bQ when bQ <= floor (the largest bound so far: the triangle cannot raise it). */
double cj_tess_rational_tri_bound(ptess *P, const double *ua, const double *ub, const double *uc,
                                  const double *pa, const double *pb, const double *pc, int in_cell,
                                  double floor) {
    const int m = P->m, n = P->n, m1 = m + 1, n1 = n + 1;
    const double *uv[3] = {ua, ub, uc}, *V[3] = {pa, pb, pc};
    double box[4];
    const double *net;
    double qb[4];
    if (in_cell) {
        memcpy(box, P->cellbox, sizeof box);
        memcpy(qb, P->cellq, sizeof qb);
        net = P->cellnet;
    } else {
        box[0] = fmin(fmin(ua[0], ub[0]), uc[0]);
        box[1] = fmax(fmax(ua[0], ub[0]), uc[0]);
        box[2] = fmin(fmin(ua[1], ub[1]), uc[1]);
        box[3] = fmax(fmax(ua[1], ub[1]), uc[1]);
        if (!(box[1] > box[0] && box[3] > box[2])) {
            box[0] = box[2] = 0.0;
            box[1] = box[3] = 1.0;
        }
        cj_patch_sub_h(P->h, 4, m, n, box[0], box[1], box[2], box[3], P->trinet);
        net = P->trinet;
        cj_tess_homog_bounds(P, net, qb);
    }
    const double wu = box[1] - box[0], wv = box[3] - box[2];
    double st[3][2];
    for (int i = 0; i < 3; ++i) {
        st[i][0] = (uv[i][0] - box[0]) / wu;
        st[i][1] = (uv[i][1] - box[2]) / wv;
    }
    const double ds = (fmax(fmax(ua[0], ub[0]), uc[0]) - fmin(fmin(ua[0], ub[0]), uc[0])) / wu *
                      (1.0 + 4.0 * U_ROUND);
    const double dt = (fmax(fmax(ua[1], ub[1]), uc[1]) - fmin(fmin(ua[1], ub[1]), uc[1])) / wv *
                      (1.0 + 4.0 * U_ROUND);
    const double bq = ((qb[0] * ds * ds + 2.0 * qb[1] * ds * dt + qb[2] * dt * dt) * 0.125 *
                           (1.0 + 8.0 * U_ROUND) +
                       qb[3] + P->verterr) *
                      (1.0 + 8.0 * U_ROUND);
    if (!(bq > floor)) return bq; /* cannot raise the patch's bound: bF is not needed */
    /* L through the three vertices in local coordinates */
    const double d1s = st[1][0] - st[0][0], d1t = st[1][1] - st[0][1];
    const double d2s = st[2][0] - st[0][0], d2t = st[2][1] - st[0][1];
    const double det = d1s * d2t - d1t * d2s;
    if (!(det != 0.0) || !isfinite(det)) return bq; /* no triangle in (u,v): no L */
    double A[3], Bc[3], C[3];
    for (int k = 0; k < 3; ++k) {
        const double e1 = V[1][k] - V[0][k], e2 = V[2][k] - V[0][k];
        Bc[k] = (e1 * d2t - e2 * d1t) / det;
        C[k] = (e2 * d1s - e1 * d2s) / det;
        A[k] = V[0][k] - Bc[k] * st[0][0] - C[k] * st[0][1];
    }
    /* e >= max_i |V_i - L(p_i)|: the computed residual plus its rounding (and that of s_i,
     * t_i, a few ulps of the coordinates in [0,1]) */
    double e = 0.0;
    for (int i = 0; i < 3; ++i) {
        double e2 = 0.0;
        for (int k = 0; k < 3; ++k) {
            const double r = (A[k] + Bc[k] * st[i][0] + C[k] * st[i][1]) - V[i][k];
            const double mag = fabs(A[k]) + 2.0 * (fabs(Bc[k]) + fabs(C[k])) + fabs(V[i][k]);
            const double x = fabs(r) + 8.0 * U_ROUND * mag;
            e2 += x * x;
        }
        e = fmax(e, sqrt(e2) * (1.0 + 4.0 * U_ROUND));
    }
    double Lc[2][2][3], lmax = 0.0; /* corner values L_ab */
    for (int a = 0; a < 2; ++a)
        for (int b = 0; b < 2; ++b)
            for (int k = 0; k < 3; ++k) {
                Lc[a][b][k] = A[k] + Bc[k] * a + C[k] * b;
                lmax = fmax(lmax, fabs(Lc[a][b][k]));
            }
    /* F's net, degree (m+1, n+1), stride 3 */
    double wlo = INFINITY, whi = 0.0, fmag = 0.0;
    for (int q = 0; q < m1 * n1; ++q) {
        wlo = fmin(wlo, net[4 * q + 3]);
        whi = fmax(whi, net[4 * q + 3]);
    }
    double *F = P->fnet;
    for (int l = 0; l <= n1; ++l)
        for (int k = 0; k <= m1; ++k) {
            double f[3] = {0.0, 0.0, 0.0}, mag = 0.0;
            for (int a = 0; a < 2; ++a) {
                const int i = k - a;
                if (i < 0 || i > m) continue;
                const double cu = a ? (double)k / m1 : (double)(m1 - k) / m1;
                for (int b = 0; b < 2; ++b) {
                    const int j = l - b;
                    if (j < 0 || j > n) continue;
                    const double cv = b ? (double)l / n1 : (double)(n1 - l) / n1;
                    const double *h = net + 4 * (j * m1 + i);
                    const double c = cu * cv;
                    for (int d = 0; d < 3; ++d) {
                        f[d] += c * (h[d] - h[3] * Lc[a][b][d]);
                        mag = fmax(mag, fabs(h[d]) + h[3] * lmax);
                    }
                }
            }
            memcpy(F + 3 * (l * (m1 + 1) + k), f, sizeof f);
            fmag = fmax(fmag, mag);
        }
    wlo = (wlo - P->suberr_w) * (1.0 - 4.0 * U_ROUND);
    whi = (whi + P->suberr_w) * (1.0 + 4.0 * U_ROUND);
    if (!(wlo > 0.0)) return INFINITY;
    const double eF = P->suberr_x + P->suberr_w * lmax + cj_gamma(8) * fmag;
    const dbounds fb = net_bounds(F, 3, m1, n1);
    const double ib = (fb.uu * ds * ds + 2.0 * fb.uv * ds * dt + fb.vv * dt * dt) * 0.125 *
                          (1.0 + 8.0 * U_ROUND) +
                      2.0 * sqrt(3.0) * eF;
    const double bf = ((ib + whi * (P->verterr + e)) / wlo + e) * (1.0 + 8.0 * U_ROUND);
    return fmin(bf, bq);
}

/* Loads the homogeneous sub-net of the grid cell [u0,u1]x[v0,v1] for cj_tess_rational_tri_bound. */
void cj_tess_load_cell(ptess *P, double u0, double u1, double v0, double v1) {
    cj_patch_sub_h(P->h, 4, P->m, P->n, u0, u1, v0, v1, P->cellnet);
    P->cellbox[0] = u0;
    P->cellbox[1] = u1;
    P->cellbox[2] = v0;
    P->cellbox[3] = v1;
    cj_tess_homog_bounds(P, P->cellnet, P->cellq);
}

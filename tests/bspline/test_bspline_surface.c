/* Tensor-product B-spline and NURBS surfaces: evaluation against an MPFR oracle (products of
 * Cox–de Boor basis functions, 2300 bits), Bézier patches that reproduce their spans and share
 * boundary control points bit for bit, knot insertion in u and v that leaves the surface in
 * place, grid interpolation through its points, and refused input named. */
#include "bsp_surf.h"
#include "bsp_test.h"
#include "oracle_bspline.h"

#include "casteljau/bspline_surface.h"
#include "casteljau/patch.h"
#include "casteljau/status.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { MAXN = BSP_SURF_MAXN };

static void knots(cj_rng *r, double *k, int n, int p, int clamped) {
    double x = cj_rng_range(r, -1, 1);
    for (int i = 0; i < n + p + 1; ++i) {
        if (i) x += cj_rng_int(r, 0, 3) == 0 ? 0.0 : cj_rng_range(r, 0.2, 1.0);
        k[i] = x;
    }
    if (clamped) {
        for (int i = 0; i < p; ++i) k[i] = k[p];
        for (int i = n + 1; i < n + p + 1; ++i) k[i] = k[n];
    }
    if (!(k[p] < k[n]))
        for (int i = n; i < n + p + 1; ++i) k[i] = k[p] + 1 + (i - n);
    for (int i = 1; i < n + p + 1; ++i) {
        if (k[i] < k[i - 1]) k[i] = k[i - 1];
        if (i > p && k[i] == k[i - p - 1]) k[i] = nextafter(k[i], INFINITY);
    }
}

static const double TOL = 1e-13;

static void test_eval_and_patches(cj_rng *r) {
    static bsp_surf s;
    static double pp[3 * 25 * MAXN * MAXN * 4], pw[25 * MAXN * MAXN * 4], ub[MAXN + 1],
        vb[MAXN + 1];
    double worst_eval = 0, worst_patch = 0, worst_ratio = 0;
    int npatches = 0, edges = 0;
    mpfr_t u, v;
    mpfr_inits2(CJ_ORACLE_BSP_PREC, u, v, (mpfr_ptr)0);
    for (int rep = 0; rep < 40; ++rep) {
        bsp_surf_generate(r, &s, rep, knots);
        const cj_bspline_surface sv = bsp_surf_view(&s);
        BSP_CHECK(cj_bspline_surface_check(&sv) == CJ_OK, "%s: %s", s.what, cj_last_error());
        const double u0 = s.ku[s.p], u1 = s.ku[s.nu], v0 = s.kv[s.q], v1 = s.kv[s.nv];
        for (int k = 0; k < 10; ++k) {
            const double a = k == 0 ? u0 : (k == 1 ? u1 : u0 + (u1 - u0) * cj_rng_unit(r));
            const double b = k == 0 ? v0 : (k == 1 ? v1 : v0 + (v1 - v0) * cj_rng_unit(r));
            double x[3];
            cj_status st = cj_bspline_surface_eval(&sv, fmin(a, u1), fmin(b, v1), x);
            BSP_CHECK(st == CJ_OK, "%s: eval: %s", s.what, cj_last_error());
            mpfr_set_d(u, fmin(a, u1), MPFR_RNDN);
            mpfr_set_d(v, fmin(b, v1), MPFR_RNDN);
            double gaps[3], bound[3];
            const double g = bsp_surf_gap_exact(&s, u, v, x, gaps);
            st = cj_bspline_surface_error_bound(&sv, fmin(a, u1), fmin(b, v1), bound);
            BSP_CHECK(st == CJ_OK, "%s: bound: %s", s.what, cj_last_error());
            for (int c = 0; c < 3; ++c) {
                BSP_CHECK(gaps[c] <= bound[c],
                          "%s: S(%g, %g) coordinate %d off by %.3g, bound %.3g", s.what, a, b, c,
                          gaps[c], bound[c]);
                if (bound[c] > 0) worst_ratio = fmax(worst_ratio, gaps[c] / bound[c]);
            }
            worst_eval = fmax(worst_eval, g);
        }
        int n = 0;
        cj_status st = cj_bspline_surface_patch_count(&sv, &n);
        int n2 = -1;
        st = cj_bspline_surface_to_patches(&sv, pp, s.rational ? pw : NULL, ub, vb, n, &n2);
        BSP_CHECK(st == CJ_OK && n2 == n, "%s: patches: %s", s.what, cj_last_error());
        if (st) continue;
        int nsu = 0;
        for (int i = s.p; i < s.nu; ++i) nsu += s.ku[i] < s.ku[i + 1];
        const int per = (s.p + 1) * (s.q + 1);
        for (int k = 0; k < n; ++k) {
            const int a = k % nsu, b = k / nsu;
            const cj_patch patch =
                cj_patch_view(s.p, s.q, pp + 3 * per * k, s.rational ? pw + per * k : NULL);
            for (int e = 0; e < 5; ++e) {
                const double su = e / 4.0, tv = (4 - e) / 4.0 * 0.5 + 0.25 * (e % 2);
                double x[3];
                st = cj_patch_eval(&patch, CJ_EVAL_DECASTELJAU, su, tv, x);
                BSP_CHECK(st == CJ_OK, "%s: patch eval: %s", s.what, cj_last_error());
                mpfr_set_d(u, ub[a + 1], MPFR_RNDN);
                mpfr_sub_d(u, u, ub[a], MPFR_RNDN);
                mpfr_mul_d(u, u, su, MPFR_RNDN);
                mpfr_add_d(u, u, ub[a], MPFR_RNDN);
                mpfr_set_d(v, vb[b + 1], MPFR_RNDN);
                mpfr_sub_d(v, v, vb[b], MPFR_RNDN);
                mpfr_mul_d(v, v, tv, MPFR_RNDN);
                mpfr_add_d(v, v, vb[b], MPFR_RNDN);
                /* At a jump knot the oracle takes the right-hand side; stay inside the span. */
                if ((su == 1.0 && a + 1 < nsu) || (tv == 1.0)) continue;
                const double g = bsp_surf_gap_exact(&s, u, v, x, NULL);
                BSP_CHECK(g <= TOL, "%s: patch %d at (%g, %g) off by %.3g", s.what, k, su, tv, g);
                worst_patch = fmax(worst_patch, g);
            }
            /* The right neighbour shares the boundary column bit for bit (continuous in u). */
            int mult = 0;
            for (int i = 0; i < s.nu + s.p + 1; ++i) mult += s.ku[i] == ub[a + 1];
            if (a + 1 < nsu && mult <= s.p) {
                const double *nb = pp + 3 * per * (k + 1);
                for (int jj = 0; jj <= s.q; ++jj)
                    BSP_CHECK(memcmp(pp + 3 * per * k + 3 * (jj * (s.p + 1) + s.p),
                                     nb + 3 * jj * (s.p + 1), 3 * sizeof(double)) == 0,
                              "%s: patches %d and %d differ on their shared edge", s.what, k,
                              k + 1);
                ++edges;
            }
        }
        npatches += n;
        if (n > 1) {
            st = cj_bspline_surface_to_patches(&sv, pp, s.rational ? pw : NULL, NULL, NULL, n - 1,
                                               NULL);
            BSP_CHECK(st == CJ_ERR_BUFFER, "%s: short buffer gave %d", s.what, st);
        }
    }
    mpfr_clears(u, v, (mpfr_ptr)0);
    printf("surfaces: 40 random surfaces (degrees 1..4, clamped/unclamped, repeated knots, half "
           "NURBS) evaluate within %.3g of the exact value, always within "
           "cj_bspline_surface_error_bound (largest error/bound %.3g); %d Bézier patches "
           "reproduce their spans within %.3g; %d shared edges bit-identical\n",
           worst_eval, worst_ratio, npatches, worst_patch, edges);
}

static void test_insert(cj_rng *r) {
    static bsp_surf s;
    static double op[3 * (MAXN + 4) * MAXN], ow[(MAXN + 4) * MAXN], ok[MAXN + 16];
    double worst = 0;
    for (int rep = 0; rep < 30; ++rep) {
        bsp_surf_generate(r, &s, rep, knots);
        const cj_bspline_surface sv = bsp_surf_view(&s);
        const int dir = rep % 2;
        const double *k = dir ? s.kv : s.ku;
        const int n = dir ? s.nv : s.nu, p = dir ? s.q : s.p;
        const double x = k[p] + (k[n] - k[p]) * cj_rng_unit(r);
        int m = 0;
        for (int i = 0; i < n + p + 1; ++i) m += k[i] == x;
        const int times = p - m;
        cj_status st =
            cj_bspline_surface_insert_knot(&sv, dir, x, times, op, s.rational ? ow : NULL, ok);
        BSP_CHECK(st == CJ_OK, "%s: insert: %s", s.what, cj_last_error());
        if (st) continue;
        cj_bspline_surface f = sv;
        f.pts = op;
        f.weights = s.rational ? ow : NULL;
        if (dir) {
            f.npts_v += times;
            f.knots_v = ok;
        } else {
            f.npts_u += times;
            f.knots_u = ok;
        }
        for (int j = 0; j < 12; ++j) {
            const double a = s.ku[s.p] + (s.ku[s.nu] - s.ku[s.p]) * cj_rng_unit(r);
            const double b = s.kv[s.q] + (s.kv[s.nv] - s.kv[s.q]) * cj_rng_unit(r);
            double x0[3], x1[3];
            cj_bspline_surface_eval(&sv, a, b, x0);
            st = cj_bspline_surface_eval(&f, a, b, x1);
            for (int c = 0; c < 3; ++c) {
                BSP_CHECK(st == CJ_OK && fabs(x0[c] - x1[c]) <= TOL,
                          "%s: insertion moved S by %.3g", s.what, fabs(x0[c] - x1[c]));
                worst = fmax(worst, fabs(x0[c] - x1[c]));
            }
        }
    }
    cj_status st = cj_bspline_surface_insert_knot(&(cj_bspline_surface){1, 1, 2, 2, s.pts, NULL,
                                                                        (double[]){0, 0, 1, 1},
                                                                        (double[]){0, 0, 1, 1}},
                                                  0, 0.5, 2, op, NULL, ok);
    BSP_CHECK(st == CJ_ERR_ARGUMENT && strstr(cj_last_error(), "u knot 0.5"), "over-insertion: %s",
              cj_last_error());
    printf("insertion: 30 surfaces refined up to multiplicity p in u or v move by at most %.3g "
           "(12 parameters each); over-insertion refused\n",
           worst);
}

static void test_interpolate(cj_rng *r) {
    enum { NU = 9, NV = 7 };
    static double grid[3 * NU * NV], P[3 * NU * NV], ku[NU + 8], kv[NV + 8], ubar[NU], vbar[NV];
    double worst = 0;
    for (int rep = 0; rep < 6; ++rep) {
        for (int j = 0; j < NV; ++j)
            for (int i = 0; i < NU; ++i) {
                double *g = grid + 3 * (j * NU + i);
                g[0] = i + 0.2 * cj_rng_range(r, -1, 1);
                g[1] = j + 0.2 * cj_rng_range(r, -1, 1);
                g[2] = sin(0.7 * i) * cos(0.5 * j) + 0.1 * cj_rng_range(r, -1, 1);
            }
        const int p = 1 + rep % 4, q = 1 + (rep + 1) % 4;
        cj_status st = cj_bspline_surface_interpolate(grid, NU, NV, p, q, (cj_fit_param)(rep % 3),
                                                      P, ku, kv, ubar, vbar);
        BSP_CHECK(st == CJ_OK, "grid interpolation (%d,%d): %s", p, q, cj_last_error());
        if (st) continue;
        const cj_bspline_surface s = {p, q, NU, NV, P, NULL, ku, kv};
        for (int j = 0; j < NV; ++j)
            for (int i = 0; i < NU; ++i) {
                double x[3];
                cj_bspline_surface_eval(&s, ubar[i], vbar[j], x);
                for (int c = 0; c < 3; ++c) {
                    const double e = fabs(x[c] - grid[3 * (j * NU + i) + c]);
                    BSP_CHECK(e <= 1e-12, "grid (%d,%d) point (%d,%d) missed by %.3g", p, q, i, j,
                              e);
                    worst = fmax(worst, e);
                }
            }
    }
    double bad[3 * 4] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, NAN};
    double P2[12], k2[8], k3[8];
    cj_status st =
        cj_bspline_surface_interpolate(bad, 2, 2, 1, 1, CJ_FIT_CHORD, P2, k2, k3, NULL, NULL);
    BSP_CHECK(st == CJ_ERR_NONFINITE && strstr(cj_last_error(), "(1, 1)"), "NaN grid point: %s",
              cj_last_error());
    printf("grid interpolation: 6 grids of 9 x 7 points (degrees 1..4, the three parametrisations) "
           "pass through every point within %.3g; a NaN grid point is refused by (i, j)\n",
           worst);
}

static void test_refusals(void) {
    double pts[3 * 9] = {0}, w[9] = {1, 1, 1, 1, 0, 1, 1, 1, 1};
    double ku[] = {0, 0, 0, 1, 1, 1}, kv[] = {0, 0, 0, 1, 1, 1}, bad[] = {0, 0, 0, 2, 1, 1};
    cj_bspline_surface s = {2, 2, 3, 3, pts, w, ku, kv};
    BSP_CHECK(cj_bspline_surface_check(&s) == CJ_ERR_ARGUMENT &&
                  strstr(cj_last_error(), "weight (1, 1)"),
              "zero weight: %s", cj_last_error());
    w[4] = 1;
    s.knots_v = bad;
    BSP_CHECK(cj_bspline_surface_check(&s) == CJ_ERR_ARGUMENT &&
                  strstr(cj_last_error(), "v knot 4"),
              "decreasing v knots: %s", cj_last_error());
    s.knots_v = kv;
    pts[3 * 5 + 2] = NAN;
    BSP_CHECK(cj_bspline_surface_check(&s) == CJ_ERR_NONFINITE && strstr(cj_last_error(), "(2, 1)"),
              "NaN point: %s", cj_last_error());
    pts[3 * 5 + 2] = 0;
    double x[3];
    BSP_CHECK(cj_bspline_surface_eval(&s, 1.5, 0.5, x) == CJ_ERR_RANGE, "u outside the domain");
    s.npts_u = 2;
    BSP_CHECK(cj_bspline_surface_check(&s) == CJ_ERR_EMPTY, "too few points");
    printf("refusals: zero weight, decreasing v knots, NaN point (named by (i, j)), u outside the "
           "domain, too few points\n");
}

int main(void) {
    const uint64_t seed = cj_test_seed("test_bspline_surface", 31);
    cj_rng r;
    cj_rng_init(&r, seed);
    test_eval_and_patches(&r);
    test_insert(&r);
    test_interpolate(&r);
    test_refusals();
    mpfr_free_cache();
    if (bsp_failures) {
        printf("%d failure(s)\n", bsp_failures);
        return 1;
    }
    printf("test_bspline_surface: all checks passed\n");
    return 0;
}

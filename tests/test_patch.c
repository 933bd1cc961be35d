/* Tensor-product Bézier patches: partial derivatives against finite differences and an
 * independent Bernstein-sum oracle, the convex hull property, affine invariance, subdivision,
 * elevation, iso and boundary curves, the compensated evaluation against MPFR, the normal and
 * its limit at the teapot's collapsed points, and the bad-input contract. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "casteljau/patch.h"
#include "casteljau/patchset.h"
#include "rng.h"

#include <math.h>
#include <mpfr.h>
#include <stdio.h>
#include <string.h>

#ifndef CJ_TEAPOT_PATH
#define CJ_TEAPOT_PATH "data/teapot.bpt"
#endif

static uint64_t seed;

/* ---- independent oracle: direct Bernstein sums with derivative bases ------------------ */

static double binom(int n, int k) {
    double r = 1.0;
    for (int i = 1; i <= k; ++i) r = r * (n - k + i) / i;
    return r;
}

/* d^a/dt^a of B_i^n(t) by the formula n!/(n-a)! Σ_k (-1)^(a-k) C(a,k) B_{i-k}^{n-a}(t). */
static double bern_d(int n, int i, int a, double t) {
    if (a > n) return 0.0;
    double f = 1.0;
    for (int q = 0; q < a; ++q) f *= n - q;
    double s = 0.0;
    for (int k = 0; k <= a; ++k) {
        const int ii = i - k, nn = n - a;
        if (ii < 0 || ii > nn) continue;
        const double b = binom(nn, ii) * pow(t, ii) * pow(1.0 - t, nn - ii);
        s += ((a - k) % 2 ? -1.0 : 1.0) * binom(a, k) * b;
    }
    return f * s;
}

/* D^{a,b} of a polynomial patch by the Bernstein sum. */
static void oracle_deriv(const cj_patch *p, int a, int b, double u, double v, double out[3]) {
    const int m = p->deg_u, n = p->deg_v;
    out[0] = out[1] = out[2] = 0.0;
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= m; ++i) {
            const double w = bern_d(m, i, a, u) * bern_d(n, j, b, v);
            for (int k = 0; k < 3; ++k) out[k] += w * p->pts[3 * (j * (m + 1) + i) + k];
        }
}

static void random_net(cj_rng *r, int m, int n, double *pts, double *w) {
    for (int q = 0; q < (m + 1) * (n + 1); ++q) {
        const int i = q % (m + 1), j = q / (m + 1);
        pts[3 * q + 0] = (double)i / (m ? m : 1) + cj_rng_range(r, -0.3, 0.3);
        pts[3 * q + 1] = (double)j / (n ? n : 1) + cj_rng_range(r, -0.3, 0.3);
        pts[3 * q + 2] = cj_rng_range(r, -0.5, 0.5);
        if (w) w[q] = cj_rng_range(r, 0.5, 2.0);
    }
}

static double dist3(const double *a, const double *b) {
    return sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                (a[2] - b[2]) * (a[2] - b[2]));
}

static void test_derivatives(void **state) {
    (void)state;
    cj_rng r;
    cj_rng_init(&r, seed);
    int checked = 0;
    for (int c = 0; c < 60; ++c) {
        const int m = cj_rng_int(&r, 1, 6), n = cj_rng_int(&r, 1, 6);
        const int rational = c % 3 == 2;
        double pts[49 * 3], w[49];
        random_net(&r, m, n, pts, rational ? w : NULL);
        cj_patch p = cj_patch_view(m, n, pts, rational ? w : NULL);
        const double u = cj_rng_range(&r, 0.05, 0.95), v = cj_rng_range(&r, 0.05, 0.95);
        double d[3 * 9];
        assert_int_equal(cj_patch_eval_derivs(&p, u, v, 2, 2, d), CJ_OK);
        /* finite differences of the evaluator (h = 1e-4, central: error O(h^2)) */
        const double h = 1e-4;
        double pp[3], pm[3], mp[3], mm[3], p0[3], up[3], um[3], vp[3], vm[3];
        cj_patch_eval(&p, CJ_EVAL_COMPENSATED, u, v, p0);
        cj_patch_eval(&p, CJ_EVAL_COMPENSATED, u + h, v, up);
        cj_patch_eval(&p, CJ_EVAL_COMPENSATED, u - h, v, um);
        cj_patch_eval(&p, CJ_EVAL_COMPENSATED, u, v + h, vp);
        cj_patch_eval(&p, CJ_EVAL_COMPENSATED, u, v - h, vm);
        cj_patch_eval(&p, CJ_EVAL_COMPENSATED, u + h, v + h, pp);
        cj_patch_eval(&p, CJ_EVAL_COMPENSATED, u + h, v - h, pm);
        cj_patch_eval(&p, CJ_EVAL_COMPENSATED, u - h, v + h, mp);
        cj_patch_eval(&p, CJ_EVAL_COMPENSATED, u - h, v - h, mm);
        for (int k = 0; k < 3; ++k) {
            const double fu = (up[k] - um[k]) / (2 * h), fv = (vp[k] - vm[k]) / (2 * h);
            const double fuu = (up[k] - 2 * p0[k] + um[k]) / (h * h);
            const double fvv = (vp[k] - 2 * p0[k] + vm[k]) / (h * h);
            const double fuv = (pp[k] - pm[k] - mp[k] + mm[k]) / (4 * h * h);
            const double tol1 = 1e-5 * (1 + fabs(fu)), tol2 = 2e-3 * (1 + fabs(fuu) + fabs(fvv));
            if (fabs(d[3 * 3 + k] - fu) > tol1 || fabs(d[3 * 1 + k] - fv) > 1e-5 * (1 + fabs(fv)) ||
                fabs(d[3 * 6 + k] - fuu) > tol2 || fabs(d[3 * 2 + k] - fvv) > tol2 ||
                fabs(d[3 * 4 + k] - fuv) > 2e-3 * (1 + fabs(fuv)))
                fail_msg("seed %llu case %d (deg %d,%d rational %d): derivative vs finite "
                         "difference, coord %d",
                         (unsigned long long)seed, c, m, n, rational, k);
        }
        if (!rational) /* exact oracle for every order up to 3 */
            for (int a = 0; a <= 2; ++a)
                for (int b = 0; b <= 2; ++b) {
                    double o[3];
                    oracle_deriv(&p, a, b, u, v, o);
                    double mag = 1.0;
                    for (int k = 0; k < 3; ++k) mag = fmax(mag, fabs(o[k]));
                    for (int k = 0; k < 3; ++k)
                        if (fabs(d[3 * (a * 3 + b) + k] - o[k]) > 1e-11 * mag * pow(7.0, a + b))
                            fail_msg("seed %llu case %d: D^{%d,%d} coord %d = %.17g, oracle %.17g",
                                     (unsigned long long)seed, c, a, b, k, d[3 * (a * 3 + b) + k],
                                     o[k]);
                }
        ++checked;
    }
    printf("derivatives: %d patches (deg 1..6, 1/3 rational): D^{a,b} a,b<=2 vs central "
           "differences and (polynomial) vs the Bernstein-sum oracle\n",
           checked);
}

static void test_convex_hull_and_affine(void **state) {
    (void)state;
    cj_rng r;
    cj_rng_init(&r, seed + 1);
    double worst_aff = 0.0;
    for (int c = 0; c < 40; ++c) {
        const int m = cj_rng_int(&r, 1, 5), n = cj_rng_int(&r, 1, 5), rational = c & 1;
        double pts[36 * 3], w[36], tp[36 * 3];
        random_net(&r, m, n, pts, rational ? w : NULL);
        cj_patch p = cj_patch_view(m, n, pts, rational ? w : NULL);
        /* random affine map x -> A x + t */
        double A[9], t[3];
        for (int k = 0; k < 9; ++k) A[k] = cj_rng_range(&r, -2, 2);
        for (int k = 0; k < 3; ++k) t[k] = cj_rng_range(&r, -5, 5);
        const int N = (m + 1) * (n + 1);
        for (int q = 0; q < N; ++q)
            for (int k = 0; k < 3; ++k)
                tp[3 * q + k] = A[3 * k] * pts[3 * q] + A[3 * k + 1] * pts[3 * q + 1] +
                                A[3 * k + 2] * pts[3 * q + 2] + t[k];
        cj_patch tpch = cj_patch_view(m, n, tp, rational ? w : NULL);
        for (int s = 0; s < 30; ++s) {
            const double u = cj_rng_unit(&r), v = cj_rng_unit(&r);
            double x[3], y[3];
            assert_int_equal(cj_patch_eval(&p, CJ_EVAL_DECASTELJAU, u, v, x), CJ_OK);
            /* support function test in 26 directions */
            for (int dx = -1; dx <= 1; ++dx)
                for (int dy = -1; dy <= 1; ++dy)
                    for (int dz = -1; dz <= 1; ++dz) {
                        double mx = -INFINITY;
                        for (int q = 0; q < N; ++q)
                            mx = fmax(mx,
                                      dx * pts[3 * q] + dy * pts[3 * q + 1] + dz * pts[3 * q + 2]);
                        if (dx * x[0] + dy * x[1] + dz * x[2] > mx + 1e-13)
                            fail_msg("seed %llu case %d: S(%g,%g) outside the hull of the net "
                                     "(direction %d,%d,%d)",
                                     (unsigned long long)seed + 1, c, u, v, dx, dy, dz);
                    }
            assert_int_equal(cj_patch_eval(&tpch, CJ_EVAL_DECASTELJAU, u, v, y), CJ_OK);
            double ax[3];
            for (int k = 0; k < 3; ++k)
                ax[k] = A[3 * k] * x[0] + A[3 * k + 1] * x[1] + A[3 * k + 2] * x[2] + t[k];
            const double e = dist3(ax, y) / (1 + fabs(ax[0]) + fabs(ax[1]) + fabs(ax[2]));
            worst_aff = fmax(worst_aff, e);
            if (e > 1e-13)
                fail_msg("seed %llu case %d: affine invariance off by %.3g",
                         (unsigned long long)seed + 1, c, e);
        }
    }
    printf("convex hull (26 support directions) and affine invariance on 40 patches x 30 points "
           "(worst relative affine mismatch %.2g)\n",
           worst_aff);
}

static void test_subdivision_elevation_iso(void **state) {
    (void)state;
    cj_rng r;
    cj_rng_init(&r, seed + 2);
    for (int c = 0; c < 30; ++c) {
        const int m = cj_rng_int(&r, 1, 5), n = cj_rng_int(&r, 1, 5), rational = c % 3 == 0;
        const int N = (m + 1) * (n + 1);
        double pts[36 * 3], w[36];
        random_net(&r, m, n, pts, rational ? w : NULL);
        cj_patch p = cj_patch_view(m, n, pts, rational ? w : NULL);
        const double t = cj_rng_range(&r, 0.1, 0.9);
        double lp[36 * 3], lw[36], rp[36 * 3], rw[36];
        for (int dir = 0; dir < 2; ++dir) {
            if (dir == 0)
                assert_int_equal(cj_patch_split_u(&p, t, lp, lw, rp, rw), CJ_OK);
            else
                assert_int_equal(cj_patch_split_v(&p, t, lp, lw, rp, rw), CJ_OK);
            cj_patch L = cj_patch_view(m, n, lp, rational ? lw : NULL);
            cj_patch R = cj_patch_view(m, n, rp, rational ? rw : NULL);
            /* the shared column/row is bit-identical */
            for (int q = 0; q < (dir == 0 ? n + 1 : m + 1); ++q) {
                const int li = dir == 0 ? q * (m + 1) + m : n * (m + 1) + q;
                const int ri = dir == 0 ? q * (m + 1) : q;
                assert_memory_equal(lp + 3 * li, rp + 3 * ri, 3 * sizeof(double));
            }
            for (int s = 0; s < 20; ++s) {
                const double a = cj_rng_unit(&r), b = cj_rng_unit(&r);
                double x[3], y[3], z[3];
                cj_patch_eval(&L, CJ_EVAL_DECASTELJAU, a, b, x);
                cj_patch_eval(&p, CJ_EVAL_DECASTELJAU, dir == 0 ? t * a : a, dir == 0 ? b : t * b,
                              y);
                cj_patch_eval(&R, CJ_EVAL_DECASTELJAU, a, b, z);
                double y2[3];
                cj_patch_eval(&p, CJ_EVAL_DECASTELJAU, dir == 0 ? t + (1 - t) * a : a,
                              dir == 0 ? b : t + (1 - t) * b, y2);
                if (dist3(x, y) > 1e-13 || dist3(z, y2) > 1e-13)
                    fail_msg("seed %llu case %d dir %d: split halves differ from the patch",
                             (unsigned long long)seed + 2, c, dir);
            }
        }
        /* sub-patch and elevation */
        double sp[36 * 3], sw[36], ep[81 * 3], ew[81];
        const double u0 = cj_rng_range(&r, 0, 0.4), u1 = cj_rng_range(&r, 0.6, 1);
        const double v0 = cj_rng_range(&r, 0, 0.4), v1 = cj_rng_range(&r, 0.6, 1);
        assert_int_equal(cj_patch_subpatch(&p, u0, u1, v0, v1, sp, sw), CJ_OK);
        const int ru = cj_rng_int(&r, 0, 3), rv = cj_rng_int(&r, 0, 3);
        assert_int_equal(cj_patch_elevate(&p, ru, rv, ep, ew), CJ_OK);
        cj_patch S = cj_patch_view(m, n, sp, rational ? sw : NULL);
        cj_patch E = cj_patch_view(m + ru, n + rv, ep, rational ? ew : NULL);
        for (int s = 0; s < 20; ++s) {
            const double a = cj_rng_unit(&r), b = cj_rng_unit(&r);
            double x[3], y[3], e[3], f[3];
            cj_patch_eval(&S, CJ_EVAL_DECASTELJAU, a, b, x);
            cj_patch_eval(&p, CJ_EVAL_DECASTELJAU, u0 + (u1 - u0) * a, v0 + (v1 - v0) * b, y);
            cj_patch_eval(&E, CJ_EVAL_DECASTELJAU, a, b, e);
            cj_patch_eval(&p, CJ_EVAL_DECASTELJAU, a, b, f);
            if (dist3(x, y) > 1e-12 || dist3(e, f) > 1e-13)
                fail_msg("seed %llu case %d: sub-patch (%.3g) or elevation (%.3g) mismatch",
                         (unsigned long long)seed + 2, c, dist3(x, y), dist3(e, f));
        }
        /* iso curves and boundaries */
        double iso[7 * 3], isow[7];
        const double uu = cj_rng_unit(&r), vv = cj_rng_unit(&r);
        assert_int_equal(cj_patch_iso_u(&p, uu, iso, isow), CJ_OK);
        for (int s = 0; s <= 4; ++s) {
            double x[3], y[3];
            const double b = s / 4.0;
            if (!rational) {
                cj_bezier cv = cj_bezier_view(n, 3, iso);
                cj_bezier_eval_decasteljau(&cv, b, x);
            } else { /* evaluate the rational curve by hand */
                double num[3] = {0, 0, 0}, den = 0;
                for (int j = 0; j <= n; ++j) {
                    const double bb = binom(n, j) * pow(b, j) * pow(1 - b, n - j) * isow[j];
                    den += bb;
                    for (int k = 0; k < 3; ++k) num[k] += bb * iso[3 * j + k];
                }
                for (int k = 0; k < 3; ++k) x[k] = num[k] / den;
            }
            cj_patch_eval(&p, CJ_EVAL_DECASTELJAU, uu, b, y);
            if (dist3(x, y) > 1e-13)
                fail_msg("seed %llu case %d: iso_u curve off the patch",
                         (unsigned long long)seed + 2, c);
        }
        assert_int_equal(cj_patch_iso_v(&p, vv, iso, isow), CJ_OK);
        int deg;
        double bd[7 * 3], bw[7];
        assert_int_equal(cj_patch_boundary(&p, CJ_PATCH_EDGE_V1, bd, bw, &deg), CJ_OK);
        assert_int_equal(deg, m);
        assert_memory_equal(bd, pts + 3 * n * (m + 1), 3 * (m + 1) * sizeof(double));
        assert_int_equal(cj_patch_boundary(&p, CJ_PATCH_EDGE_U1, bd, bw, &deg), CJ_OK);
        assert_int_equal(deg, n);
        for (int j = 0; j <= n; ++j)
            assert_memory_equal(bd + 3 * j, pts + 3 * (j * (m + 1) + m), 24);
        (void)N;
    }
    printf("split in u and v (shared column bit-identical), sub-patches, elevation, iso curves "
           "and boundaries on 30 patches (1/3 rational)\n");
}

/* Exact value of one coordinate of a polynomial patch at double (u,v) in 512-bit MPFR. */
static double mpfr_patch(const cj_patch *p, int k, double u, double v) {
    mpfr_t acc, bu, bv, t, s, x;
    mpfr_inits2(512, acc, bu, bv, t, s, x, (mpfr_ptr)0);
    mpfr_set_zero(acc, 1);
    const int m = p->deg_u, n = p->deg_v;
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= m; ++i) {
            /* B_i^m(u) exactly: C(m,i) u^i (1-u)^(m-i) */
            mpfr_set_d(t, u, MPFR_RNDN);
            mpfr_pow_ui(bu, t, (unsigned long)i, MPFR_RNDN);
            mpfr_ui_sub(s, 1, t, MPFR_RNDN);
            mpfr_pow_ui(s, s, (unsigned long)(m - i), MPFR_RNDN);
            mpfr_mul(bu, bu, s, MPFR_RNDN);
            mpfr_mul_d(bu, bu, binom(m, i), MPFR_RNDN);
            mpfr_set_d(t, v, MPFR_RNDN);
            mpfr_pow_ui(bv, t, (unsigned long)j, MPFR_RNDN);
            mpfr_ui_sub(s, 1, t, MPFR_RNDN);
            mpfr_pow_ui(s, s, (unsigned long)(n - j), MPFR_RNDN);
            mpfr_mul(bv, bv, s, MPFR_RNDN);
            mpfr_mul_d(bv, bv, binom(n, j), MPFR_RNDN);
            mpfr_set_d(x, p->pts[3 * (j * (m + 1) + i) + k], MPFR_RNDN);
            mpfr_mul(x, x, bu, MPFR_RNDN);
            mpfr_mul(x, x, bv, MPFR_RNDN);
            mpfr_add(acc, acc, x, MPFR_RNDN);
        }
    const double r = mpfr_get_d(acc, MPFR_RNDN);
    mpfr_clears(acc, bu, bv, t, s, x, (mpfr_ptr)0);
    return r;
}

static void test_compensated_vs_mpfr(void **state) {
    (void)state;
    cj_rng r;
    cj_rng_init(&r, seed + 3);
    double worst_c = 0.0, worst_d = 0.0;
    int n_cases = 0;
    for (int c = 0; c < 40; ++c) {
        const int m = cj_rng_int(&r, 2, 8), n = cj_rng_int(&r, 2, 8);
        double pts[81 * 3];
        /* ill-conditioned: (u - a)^m (v - b)^n style cancellation, written in Bernstein form
         * (coefficients (-a)^{m-i}(1-a)^i ...) plus large alternating offsets in y */
        const double a = cj_rng_range(&r, 0.3, 0.7), b = cj_rng_range(&r, 0.3, 0.7);
        for (int j = 0; j <= n; ++j)
            for (int i = 0; i <= m; ++i) {
                double *q = pts + 3 * (j * (m + 1) + i);
                q[0] = pow(-a, m - i) * pow(1 - a, i) * pow(-b, n - j) * pow(1 - b, j) * 1e6;
                q[1] = ((i + j) % 2 ? -1.0 : 1.0) * 1e8 + cj_rng_range(&r, -1, 1);
                q[2] = cj_rng_range(&r, -1, 1);
            }
        cj_patch p = cj_patch_view(m, n, pts, NULL);
        for (int s = 0; s < 10; ++s) {
            const double u = a + cj_rng_range(&r, -1e-3, 1e-3),
                         v = b + cj_rng_range(&r, -1e-3, 1e-3);
            double xc[3], xd[3];
            cj_patch_eval(&p, CJ_EVAL_COMPENSATED, u, v, xc);
            cj_patch_eval(&p, CJ_EVAL_DECASTELJAU, u, v, xd);
            for (int k = 0; k < 2; ++k) {
                const double ex = mpfr_patch(&p, k, u, v);
                /* Σ|b|BB */
                double mag = 0.0;
                for (int j = 0; j <= n; ++j)
                    for (int i = 0; i <= m; ++i)
                        mag += fabs(pts[3 * (j * (m + 1) + i) + k]) * binom(m, i) * pow(u, i) *
                               pow(1 - u, m - i) * binom(n, j) * pow(v, j) * pow(1 - v, n - j);
                const double g = cj_gamma(3 * (m + n));
                const double bound_c = CJ_UNIT_ROUNDOFF * fabs(ex) + 4 * g * g * mag;
                const double bound_d = g * mag;
                const double ec = fabs(xc[k] - ex), ed = fabs(xd[k] - ex);
                if (ec > bound_c * 1.01)
                    fail_msg("seed %llu case %d: compensated error %.3g > bound %.3g (coord %d)",
                             (unsigned long long)seed + 3, c, ec, bound_c, k);
                if (ed > bound_d * 1.01)
                    fail_msg("seed %llu case %d: de Casteljau error %.3g > bound %.3g",
                             (unsigned long long)seed + 3, c, ed, bound_d);
                if (ex != 0.0) {
                    worst_c = fmax(worst_c, ec / fabs(ex));
                    worst_d = fmax(worst_d, ed / fabs(ex));
                }
                ++n_cases;
            }
        }
    }
    printf("compensated patch evaluation vs MPFR on %d ill-conditioned values: within "
           "u|S| + 4 gamma(3(m+n))^2 Σ|b|BB (worst relative error %.2g; plain de Casteljau "
           "%.2g)\n",
           n_cases, worst_c, worst_d);
    assert_true(worst_c < worst_d); /* the compensated scheme must actually help here */
}

static double angle(const double *a, const double *b) {
    double c[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
    return atan2(sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]),
                 a[0] * b[0] + a[1] * b[1] + a[2] * b[2]);
}

static void test_normals_teapot_poles(void **state) {
    (void)state;
    cj_patchset *set;
    assert_int_equal(cj_patchset_load_bpt(CJ_TEAPOT_PATH, NULL, &set), CJ_OK);
    assert_int_equal((int)set->count, 32);
    int checked = 0;
    /* lid knob patches 20..23 and bottom patches 28..31 have the edge v = 0 collapsed */
    const int poles[8] = {20, 21, 22, 23, 28, 29, 30, 31};
    for (int q = 0; q < 8; ++q) {
        const cj_patch *p = &set->patches[poles[q]];
        const double expect_z = poles[q] < 28 ? 1.0 : -1.0; /* lid top: up; bottom: down */
        for (int s = 0; s <= 4; ++s) {
            const double u = s / 4.0;
            double n0[3], n1[3], n2[3];
            int order;
            assert_int_equal(cj_patch_normal(p, u, 0.0, n0, &order), CJ_OK);
            assert_true(order >= 1);
            for (int k = 0; k < 3; ++k) assert_true(isfinite(n0[k]));
            assert_true(fabs(sqrt(n0[0] * n0[0] + n0[1] * n0[1] + n0[2] * n0[2]) - 1) < 1e-14);
            /* by symmetry the pole normal is the axis */
            if (fabs(n0[2] - expect_z) > 1e-12)
                fail_msg("patch %d at (%g,0): normal (%g,%g,%g), expected z = %g", poles[q], u,
                         n0[0], n0[1], n0[2], expect_z);
            /* continuity: nearby interior normals converge to it */
            assert_int_equal(cj_patch_normal(p, u, 1e-3, n1, NULL), CJ_OK);
            assert_int_equal(cj_patch_normal(p, u, 1e-6, n2, NULL), CJ_OK);
            if (!(angle(n0, n2) < 1e-4 && angle(n0, n2) <= angle(n0, n1) + 1e-15 &&
                  angle(n0, n1) < 0.1))
                fail_msg(
                    "patch %d at u=%g: normal not continuous (angles %.3g at 1e-3, %.3g at 1e-6)",
                    poles[q], u, angle(n0, n1), angle(n0, n2));
            ++checked;
        }
    }
    /* regular points: n = S_u x S_v / |.| from the oracle derivatives */
    for (int q = 0; q < 32; ++q) {
        const cj_patch *p = &set->patches[q];
        double su[3], sv[3], n[3];
        oracle_deriv(p, 1, 0, 0.37, 0.61, su);
        oracle_deriv(p, 0, 1, 0.37, 0.61, sv);
        double c[3] = {su[1] * sv[2] - su[2] * sv[1], su[2] * sv[0] - su[0] * sv[2],
                       su[0] * sv[1] - su[1] * sv[0]};
        assert_int_equal(cj_patch_normal(p, 0.37, 0.61, n, NULL), CJ_OK);
        assert_true(angle(n, c) < 1e-12);
    }
    /* a collapsed u = 0 edge (rule S_u x S_uv) and a patch collapsed to a point */
    double cone[3 * 9] = {0, 0, 1, 1,  0, 0, 2, 0, -1, 0, 0, 1, 1, 1,
                          0, 2, 2, -1, 0, 0, 1, 0, 1,  0, 0, 2, -1};
    cj_patch pc = cj_patch_view(2, 2, cone, NULL);
    double n0[3], n1[3];
    int order;
    assert_int_equal(cj_patch_normal(&pc, 0.0, 0.5, n0, &order), CJ_OK);
    assert_true(order >= 1);
    assert_int_equal(cj_patch_normal(&pc, 1e-7, 0.5, n1, NULL), CJ_OK);
    assert_true(angle(n0, n1) < 1e-5);
    double pt[3 * 4] = {1, 2, 3, 1, 2, 3, 1, 2, 3, 1, 2, 3};
    cj_patch pp = cj_patch_view(1, 1, pt, NULL);
    assert_int_equal(cj_patch_normal(&pp, 0.5, 0.5, n0, NULL), CJ_ERR_DEGENERATE);
    cj_patchset_destroy(set);
    printf("normals: %d points on the teapot's collapsed lid/bottom edges are unit, axial and "
           "continuous (angle < 1e-4 at distance 1e-6); regular normals = S_u x S_v on 32 patches; "
           "a collapsed u = 0 edge; a point patch is DEGENERATE\n",
           checked);
}

static void test_bad_input(void **state) {
    (void)state;
    double pts[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, NAN};
    double w[4] = {1, 1, -1, 1}, out[3];
    cj_patch p = cj_patch_view(1, 1, pts, NULL);
    assert_int_equal(cj_patch_eval(&p, CJ_EVAL_DECASTELJAU, 0.5, 0.5, out), CJ_ERR_NONFINITE);
    assert_non_null(strstr(cj_last_error(), "i=1, j=1"));
    pts[11] = 0;
    p.weights = w;
    assert_int_equal(cj_patch_eval(&p, CJ_EVAL_DECASTELJAU, 0.5, 0.5, out), CJ_ERR_ARGUMENT);
    assert_non_null(strstr(cj_last_error(), "weight (i=0, j=1)"));
    p.weights = NULL;
    assert_int_equal(cj_patch_eval(&p, CJ_EVAL_HORNER, 0.5, 0.5, out), CJ_ERR_ARGUMENT);
    assert_int_equal(cj_patch_eval(&p, CJ_EVAL_DECASTELJAU, NAN, 0.5, out), CJ_ERR_NONFINITE);
    assert_int_equal(cj_patch_split_u(&p, 1.5, pts, NULL, NULL, NULL), CJ_ERR_RANGE);
    assert_int_equal(cj_patch_subpatch(&p, 0.5, 0.2, 0, 1, out, NULL), CJ_ERR_RANGE);
    cj_patch big = cj_patch_view(CJ_PATCH_MAX_DEGREE + 1, 1, pts, NULL);
    assert_int_equal(cj_patch_eval(&big, CJ_EVAL_DECASTELJAU, 0.5, 0.5, out), CJ_ERR_DEGREE);
    cj_patch neg = cj_patch_view(-1, 1, pts, NULL);
    assert_int_equal(cj_patch_check(&neg), CJ_ERR_EMPTY);
    double d[3 * 4];
    assert_int_equal(cj_patch_eval_derivs(&p, 0.5, 0.5, -1, 1, d), CJ_ERR_ARGUMENT);
    assert_int_equal(cj_patch_elevate(&p, CJ_PATCH_MAX_DEGREE, 0, d, NULL), CJ_ERR_DEGREE);
    printf("bad input: NaN point (named i,j), weight <= 0, unsupported method, NaN parameter, "
           "split/sub-patch ranges, degree limits, negative orders\n");
}

int main(void) {
    seed = cj_test_seed("test_patch", 20261121);
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_derivatives),
        cmocka_unit_test(test_convex_hull_and_affine),
        cmocka_unit_test(test_subdivision_elevation_iso),
        cmocka_unit_test(test_compensated_vs_mpfr),
        cmocka_unit_test(test_normals_teapot_poles),
        cmocka_unit_test(test_bad_input),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

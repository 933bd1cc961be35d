/* Tensor-product B-spline and NURBS surface operations against the MPFR oracle (products of
 * Cox–de Boor basis functions, 2300 bits): degree elevation in u or v leaves the surface in place
 * within the evaluation bound plus the reported bound, knot removal within a tolerance moves it
 * at most the reported bound, partial derivatives of every order stay within their proven bound,
 * and refused input is named. */
#include "bsp_surf.h"
#include "bsp_test.h"
#include "oracle_bspline.h"

#include "casteljau/bspline_surface.h"
#include "casteljau/status.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { MAXN = BSP_SURF_MAXN, BIGN = BSP_SURF_CAP };

static unsigned long binom_ul(int n, int i) {
    unsigned long b = 1;
    for (int j = 1; j <= i; ++j) b = b * (unsigned long)(n - i + j) / (unsigned long)j;
    return b;
}

/* Random knots: runs of equal values (multiplicity 1..p, mostly 1) spaced 0.2..1 apart, with
 * p+1 equal end knots when clamped; so the domain is non-empty and no interior knot is a jump. */
static void knots(cj_rng *r, double *k, int n, int p, int clamped) {
    const int total = n + p + 1;
    double x = cj_rng_range(r, -1, 1);
    int i = 0;
    if (clamped)
        for (; i <= p; ++i) k[i] = x;
    while (i < (clamped ? n : total)) {
        x += cj_rng_range(r, 0.2, 1.0);
        int m = cj_rng_int(r, 0, 3) == 0 ? cj_rng_int(r, 1, p) : 1;
        for (; m > 0 && i < (clamped ? n : total); --m) k[i++] = x;
    }
    if (clamped) {
        x += cj_rng_range(r, 0.2, 1.0);
        for (; i < total; ++i) k[i] = x;
    }
    if (!(k[p] < k[n])) /* a run across the domain: split it */
        for (i = n; i < total; ++i) k[i] += 0.5;
}

/* Largest (|S(u,v) − F(u,v)| − eval bound of F) / (allowed) at ntest random (u, v): the new
 * surface F evaluated, compared with the exact S. */
static double worst_ratio(cj_rng *r, const bsp_surf *s, const bsp_surf *f, double allowed,
                          int ntest) {
    const cj_bspline_surface fv = bsp_surf_view(f);
    double worst = 0;
    for (int t = 0; t < ntest; ++t) {
        const double u = s->ku[s->p] + (s->ku[s->nu] - s->ku[s->p]) * cj_rng_unit(r);
        const double v = s->kv[s->q] + (s->kv[s->nv] - s->kv[s->q]) * cj_rng_unit(r);
        const double uu = fmin(u, s->ku[s->nu]), vv = fmin(v, s->kv[s->nv]);
        double x[3], b[3];
        cj_status st = cj_bspline_surface_eval(&fv, uu, vv, x);
        if (!st) st = cj_bspline_surface_error_bound(&fv, uu, vv, b);
        BSP_CHECK(st == CJ_OK, "%s: eval of the result: %s", s->what, cj_last_error());
        if (st) return INFINITY;
        const double gap = bsp_surf_gap(s, uu, vv, x, NULL);
        const double ratio = gap / (allowed + fmax(b[0], fmax(b[1], b[2])));
        worst = fmax(worst, ratio);
    }
    return worst;
}

/* Rounding of the conversions the bounds leave out (re-refinement, Bézier elevation): a few
 * hundred units of the largest homogeneous coordinate, times wmax/wmin for a NURBS. */
static double conversion_slack(const bsp_surf *s) {
    double dmax = 0, wmin = INFINITY, wmax = 0;
    for (int i = 0; i < s->nu * s->nv; ++i) {
        for (int c = 0; c < 3; ++c) dmax = fmax(dmax, fabs(s->pts[3 * i + c]));
        wmin = fmin(wmin, s->w[i]);
        wmax = fmax(wmax, s->w[i]);
    }
    return 512 * CJ_UNIT_ROUNDOFF * (1 + dmax) * (s->rational ? wmax / wmin : 1.0);
}

static void test_elevate(cj_rng *r) {
    static bsp_surf s, f;
    double worst = 0, worst_err = 0;
    int cases = 0;
    for (int rep = 0; rep < 40; ++rep) {
        bsp_surf_generate(r, &s, rep, knots);
        const cj_bspline_surface sv = bsp_surf_view(&s);
        const int dir = rep % 2, times = 1 + rep % 3;
        int n2;
        cj_status st = cj_bspline_surface_elevate_count(&sv, dir, times, &n2);
        BSP_CHECK(st == CJ_OK, "%s: elevate count: %s", s.what, cj_last_error());
        if (st) continue;
        f = s;
        double err = -1;
        st = cj_bspline_surface_elevate(&sv, dir, times, f.pts, s.rational ? f.w : NULL,
                                        dir ? f.kv : f.ku, &err);
        BSP_CHECK(st == CJ_OK && err >= 0, "%s: elevate by %d in %c: %s", s.what, times,
                  dir ? 'v' : 'u', cj_last_error());
        if (st) continue;
        if (dir) {
            f.q += times;
            f.nv = n2;
        } else {
            f.p += times;
            f.nu = n2;
        }
        const cj_bspline_surface fv = bsp_surf_view(&f);
        BSP_CHECK(cj_bspline_surface_check(&fv) == CJ_OK, "%s: elevated surface invalid: %s",
                  s.what, cj_last_error());
        const double ratio = worst_ratio(r, &s, &f, err + conversion_slack(&s), 16);
        BSP_CHECK(ratio <= 1.0, "%s: elevation by %d in %c moved S beyond its bound (ratio %.3g)",
                  s.what, times, dir ? 'v' : 'u', ratio);
        worst = fmax(worst, ratio);
        worst_err = fmax(worst_err, err);
        ++cases;
    }
    /* refusals: degree 0, a jump, a negative count */
    s.p = 0;
    s.q = 1;
    s.nu = 2;
    s.nv = 2;
    s.rational = 0;
    memcpy(s.ku, (double[]){0, 1, 2}, sizeof(double) * 3);
    memcpy(s.kv, (double[]){0, 0, 1, 1}, sizeof(double) * 4);
    cj_bspline_surface sv = bsp_surf_view(&s);
    int n2;
    BSP_CHECK(cj_bspline_surface_elevate_count(&sv, 0, 1, &n2) == CJ_ERR_DEGREE &&
                  strstr(cj_last_error(), "u degree 0"),
              "degree 0: %s", cj_last_error());
    BSP_CHECK(cj_bspline_surface_elevate_count(&sv, 1, -1, &n2) == CJ_ERR_ARGUMENT,
              "negative count");
    s.p = 1;
    s.nu = 4;
    memcpy(s.ku, (double[]){0, 0, 1, 1, 2, 2}, sizeof(double) * 6);
    sv = bsp_surf_view(&s);
    BSP_CHECK(cj_bspline_surface_elevate_count(&sv, 0, 1, &n2) == CJ_ERR_ARGUMENT &&
                  strstr(cj_last_error(), "jump"),
              "jump: %s", cj_last_error());
    printf("elevation: %d random surfaces (degrees 1..4 elevated by 1..3 in u or v, clamped and "
           "unclamped, repeated knots, half NURBS) stay within the evaluation bound plus the "
           "reported bound (largest ratio %.3g, largest reported bound %.3g) at 16 (u, v) each "
           "against MPFR; degree 0, a jump and a negative count refused\n",
           cases, worst, worst_err);
}

static void test_remove(cj_rng *r) {
    static bsp_surf s, g, f;
    static double ip[3 * BIGN * BIGN], iw[BIGN * BIGN], ik[BIGN + 40];
    double worst_back = 0, worst_ratio_tol = 0;
    int exact = 0, partial = 0;
    for (int rep = 0; rep < 40; ++rep) {
        bsp_surf_generate(r, &s, rep, knots);
        const cj_bspline_surface sv = bsp_surf_view(&s);
        const int dir = rep % 2;
        const double *k = dir ? s.kv : s.ku;
        const int n = dir ? s.nv : s.nu, p = dir ? s.q : s.p;
        /* 1. insert a fresh knot (once or twice), then remove it with a tight tolerance: all
         * copies go and the surface is back within the bound */
        double x = k[p] + (k[n] - k[p]) * (0.25 + 0.5 * cj_rng_unit(r));
        int m = 0;
        for (int i = 0; i < n + p + 1; ++i) m += k[i] == x;
        const int times = m < p ? 1 + (p - m > 1 && rep % 3 == 0) : 0;
        if (times == 0) continue;
        cj_status st =
            cj_bspline_surface_insert_knot(&sv, dir, x, times, ip, s.rational ? iw : NULL, ik);
        BSP_CHECK(st == CJ_OK, "%s: insert: %s", s.what, cj_last_error());
        g = s;
        memcpy(g.pts, ip,
               sizeof(double) * 3 * (size_t)(g.nu + (dir ? 0 : times)) *
                   (size_t)(g.nv + (dir ? times : 0)));
        memcpy(g.w, iw,
               sizeof(double) * (size_t)(g.nu + (dir ? 0 : times)) *
                   (size_t)(g.nv + (dir ? times : 0)));
        if (!s.rational)
            for (int i = 0; i < BIGN * BIGN; ++i) g.w[i] = 1.0;
        if (dir) {
            g.nv += times;
            memcpy(g.kv, ik, sizeof(double) * (size_t)(g.nv + g.q + 1));
        } else {
            g.nu += times;
            memcpy(g.ku, ik, sizeof(double) * (size_t)(g.nu + g.p + 1));
        }
        const cj_bspline_surface gv = bsp_surf_view(&g);
        f = g;
        int removed = -1;
        double err = -1;
        st =
            cj_bspline_surface_remove_knot(&gv, dir, x, times, 1e-9, f.pts, s.rational ? f.w : NULL,
                                           dir ? f.kv : f.ku, &removed, &err);
        BSP_CHECK(st == CJ_OK && removed == times && err >= 0 && err <= 1e-9,
                  "%s: removing the %d inserted copies of %c knot %.17g: status %d, removed %d, "
                  "bound %.3g (%s)",
                  s.what, times, dir ? 'v' : 'u', x, (int)st, removed, err, cj_last_error());
        if (st || removed != times) continue;
        if (dir)
            f.nv -= times;
        else
            f.nu -= times;
        const double back = worst_ratio(r, &g, &f, err + conversion_slack(&g), 8);
        BSP_CHECK(back <= 1.0, "%s: removal moved S beyond its bound (ratio %.3g)", s.what, back);
        worst_back = fmax(worst_back, back);
        ++exact;
        /* 2. an original interior knot with a loose tolerance: whatever goes, S moves at most
         * the reported bound (<= tol) */
        int idx = -1;
        for (int i = p + 1; i < n; ++i)
            if (k[i] > k[p] && k[i] < k[n]) idx = i;
        if (idx < 0) continue;
        const double tol = 4.0;
        f = s;
        st =
            cj_bspline_surface_remove_knot(&sv, dir, k[idx], p, tol, f.pts, s.rational ? f.w : NULL,
                                           dir ? f.kv : f.ku, &removed, &err);
        BSP_CHECK(st == CJ_OK && err <= tol, "%s: loose removal: %s (bound %.3g)", s.what,
                  cj_last_error(), err);
        if (st || removed == 0) continue;
        if (dir)
            f.nv -= removed;
        else
            f.nu -= removed;
        const double ratio = worst_ratio(r, &s, &f, err + conversion_slack(&s), 8);
        BSP_CHECK(ratio <= 1.0,
                  "%s: loose removal of %d moved S beyond the bound %.3g (ratio %.3g)", s.what,
                  removed, err, ratio);
        worst_ratio_tol = fmax(worst_ratio_tol, ratio);
        ++partial;
    }
    /* tol = 0 on a generic surface removes nothing and returns the input bit for bit */
    bsp_surf_generate(r, &s, 2, knots);
    s.nu = 6;
    s.p = 2;
    memcpy(s.ku, (double[]){0, 0, 0, 1, 2, 3, 4, 4, 4}, sizeof(double) * 9);
    const cj_bspline_surface sv = bsp_surf_view(&s);
    int removed = -1;
    double err = -1;
    f = s;
    cj_status st =
        cj_bspline_surface_remove_knot(&sv, 0, 2.0, 1, 0.0, f.pts, NULL, f.ku, &removed, &err);
    BSP_CHECK(st == CJ_OK && removed == 0 && err == 0 &&
                  !memcmp(f.pts, s.pts, sizeof(double) * 3 * (size_t)(s.nu * s.nv)),
              "tol 0: removed %d (%s)", removed, cj_last_error());
    BSP_CHECK(cj_bspline_surface_remove_knot(&sv, 0, 2.5, 1, 1.0, f.pts, NULL, f.ku, &removed,
                                             &err) == CJ_ERR_ARGUMENT &&
                  strstr(cj_last_error(), "u knot 2.5"),
              "absent knot: %s", cj_last_error());
    BSP_CHECK(cj_bspline_surface_remove_knot(&sv, 0, 4.0, 1, 1.0, f.pts, NULL, f.ku, &removed,
                                             &err) == CJ_ERR_RANGE,
              "end knot: %s", cj_last_error());
    BSP_CHECK(cj_bspline_surface_remove_knot(&sv, 1, s.kv[s.q + 1], 1, NAN, f.pts, NULL, f.kv,
                                             &removed, &err) == CJ_ERR_NONFINITE,
              "NaN tolerance");
    BSP_CHECK(cj_bspline_surface_remove_knot(&sv, 2, 2.0, 1, 1.0, f.pts, NULL, f.ku, &removed,
                                             &err) == CJ_ERR_ARGUMENT,
              "direction 2");
    printf("removal: %d surfaces with 1-2 inserted copies of a u or v knot lose them all under "
           "tol 1e-9 and return within bound (largest ratio %.3g); %d original knots removed "
           "under tol 4 move S at most the reported bound (largest ratio %.3g), against MPFR; "
           "tol 0 keeps the input bit for bit; absent knot, end knot, NaN tolerance, bad "
           "direction refused\n",
           exact, worst_back, partial, worst_ratio_tol);
}

enum { KMAX = 6 };

/* Exact partials S_{u^k v^l} (k <= ku, l <= kv) at (u, v) into ex[(k (kv+1) + l) 3 + c] (mpfr,
 * initialised): basis derivatives N_i^(k) as the derivatives of the unit-coefficient curves
 * (cj_obsp_eval), the tensor sums of the homogeneous partials, the quotient rule, all in MPFR. */
static void oracle_partials(const bsp_surf *s, double u, double v, int ku, int kv, mpfr_t *ex) {
    static double unit[BIGN];
    mpfr_t Du[BIGN][KMAX + 1], Dv[BIGN][KMAX + 1], H[(KMAX + 1) * (KMAX + 1)][4], t, z, mu, mv;
    mpfr_inits2(CJ_ORACLE_BSP_PREC, t, z, mu, mv, (mpfr_ptr)0);
    mpfr_set_d(mu, u, MPFR_RNDN);
    mpfr_set_d(mv, v, MPFR_RNDN);
    for (int dir = 0; dir < 2; ++dir) {
        const int n = dir ? s->nv : s->nu, kk = dir ? kv : ku;
        for (int i = 0; i < n; ++i) {
            memset(unit, 0, sizeof unit);
            unit[i] = 1.0;
            const cj_obsp c = {dir ? s->q : s->p, 1, n, unit, NULL, dir ? s->kv : s->ku};
            mpfr_t *D = dir ? Dv[i] : Du[i];
            for (int k = 0; k <= kk; ++k) mpfr_init2(D[k], CJ_ORACLE_BSP_PREC);
            cj_obsp_eval(&c, 0, dir ? mv : mu, kk, D, NULL);
        }
    }
    const int nl = kv + 1;
    for (int k = 0; k <= ku; ++k)
        for (int l = 0; l <= kv; ++l) {
            mpfr_t *h = H[k * nl + l];
            for (int c = 0; c < 4; ++c)
                mpfr_init2(h[c], CJ_ORACLE_BSP_PREC), mpfr_set_ui(h[c], 0, MPFR_RNDN);
            for (int j = 0; j < s->nv; ++j)
                for (int i = 0; i < s->nu; ++i) {
                    const int o = j * s->nu + i;
                    mpfr_mul(t, Du[i][k], Dv[j][l], MPFR_RNDN);
                    mpfr_mul_d(t, t, s->rational ? s->w[o] : 1.0, MPFR_RNDN);
                    mpfr_add(h[3], h[3], t, MPFR_RNDN);
                    for (int c = 0; c < 3; ++c) {
                        mpfr_mul_d(z, t, s->pts[3 * o + c], MPFR_RNDN);
                        mpfr_add(h[c], h[c], z, MPFR_RNDN);
                    }
                }
        }
    for (int k = 0; k <= ku; ++k)
        for (int l = 0; l <= kv; ++l)
            for (int c = 0; c < 3; ++c) {
                mpfr_ptr x = ex[(k * nl + l) * 3 + c];
                mpfr_set(x, H[k * nl + l][c], MPFR_RNDN);
                for (int a = 0; a <= k; ++a)
                    for (int b = 0; b <= l; ++b) {
                        if (!a && !b) continue;
                        mpfr_mul(t, H[a * nl + b][3], ex[((k - a) * nl + l - b) * 3 + c],
                                 MPFR_RNDN);
                        mpfr_mul_ui(t, t, (unsigned long)(binom_ul(k, a) * binom_ul(l, b)),
                                    MPFR_RNDN);
                        mpfr_sub(x, x, t, MPFR_RNDN);
                    }
                mpfr_div(x, x, H[0][3], MPFR_RNDN);
            }
    for (int i = 0; i < s->nu; ++i)
        for (int k = 0; k <= ku; ++k) mpfr_clear(Du[i][k]);
    for (int j = 0; j < s->nv; ++j)
        for (int l = 0; l <= kv; ++l) mpfr_clear(Dv[j][l]);
    for (int k = 0; k < (ku + 1) * nl; ++k)
        for (int c = 0; c < 4; ++c) mpfr_clear(H[k][c]);
    mpfr_clears(t, z, mu, mv, (mpfr_ptr)0);
}

/* A parameter of the domain of a knot vector: random, or (one time in four) an interior knot. */
static double draw_param(cj_rng *r, const double *k, int n, int p) {
    if (cj_rng_int(r, 0, 3) == 0 && n > p + 1) {
        const double x = k[cj_rng_int(r, p + 1, n - 1)];
        if (x > k[p] && x < k[n]) return x;
    }
    return fmin(k[p] + (k[n] - k[p]) * cj_rng_unit(r), k[n]);
}

static void test_derivs(cj_rng *r) {
    static bsp_surf s;
    double worst = 0, loosest = 0;
    int checked = 0, bitwise = 1;
    mpfr_t ex[(KMAX + 1) * (KMAX + 1) * 3];
    for (int i = 0; i < (KMAX + 1) * (KMAX + 1) * 3; ++i) mpfr_init2(ex[i], CJ_ORACLE_BSP_PREC);
    for (int rep = 0; rep < 40; ++rep) {
        bsp_surf_generate(r, &s, rep, knots);
        const cj_bspline_surface sv = bsp_surf_view(&s);
        const int ku = s.p + 1, kv = s.q + 1, nl = kv + 1;
        for (int t = 0; t < 6; ++t) {
            const double u = draw_param(r, s.ku, s.nu, s.p), v = draw_param(r, s.kv, s.nv, s.q);
            double d[(KMAX + 1) * (KMAX + 1) * 3], b[(KMAX + 1) * (KMAX + 1) * 3], x[3];
            cj_status st = cj_bspline_surface_eval_derivs(&sv, u, v, ku, kv, d);
            if (!st) st = cj_bspline_surface_derivs_error_bound(&sv, u, v, ku, kv, b);
            BSP_CHECK(st == CJ_OK, "%s: derivatives at (%.17g, %.17g): %s", s.what, u, v,
                      cj_last_error());
            if (st) continue;
            cj_bspline_surface_eval(&sv, u, v, x);
            bitwise &= !memcmp(x, d, sizeof x);
            oracle_partials(&s, u, v, ku, kv, ex);
            double scale = 1;
            for (int i = 0; i < 3 * (ku + 1) * nl; ++i) scale = fmax(scale, fabs(d[i]));
            for (int k = 0; k <= ku; ++k)
                for (int l = 0; l <= kv; ++l)
                    for (int c = 0; c < 3; ++c) {
                        const int i = (k * nl + l) * 3 + c;
                        mpfr_sub_d(ex[i], ex[i], d[i], MPFR_RNDN);
                        const double gap = fabs(mpfr_get_d(ex[i], MPFR_RNDU));
                        /* + eta: orders above the degree are exact zeros whose oracle value is
                         * 2^-2300-small noise, rounded up to the least subnormal */
                        BSP_CHECK(gap <= b[i] + 0x1p-1074,
                                  "%s: S_u%dv%d[%d] at (%.17g, %.17g) off by %.3g > bound %.3g",
                                  s.what, k, l, c, u, v, gap, b[i]);
                        if (b[i] > 0) worst = fmax(worst, gap / b[i]);
                        loosest = fmax(loosest, b[i] / scale);
                        ++checked;
                    }
        }
    }
    for (int i = 0; i < (KMAX + 1) * (KMAX + 1) * 3; ++i) mpfr_clear(ex[i]);
    BSP_CHECK(loosest < 1e-9, "derivative bounds vacuous: %.3g of the largest derivative", loosest);
    BSP_CHECK(bitwise, "the point (order (0, 0)) differs from cj_bspline_surface_eval");
    /* refusals */
    const cj_bspline_surface sv = bsp_surf_view(&s);
    double d[3 * 18 * 18];
    BSP_CHECK(cj_bspline_surface_eval_derivs(&sv, s.ku[s.p], s.kv[s.q], 17, 0, d) ==
                      CJ_ERR_ARGUMENT &&
                  strstr(cj_last_error(), "(17, 0)"),
              "order 17: %s", cj_last_error());
    BSP_CHECK(cj_bspline_surface_derivs_error_bound(&sv, s.ku[s.p] - 1, s.kv[s.q], 1, 1, d) ==
                  CJ_ERR_RANGE,
              "u outside: %s", cj_last_error());
    BSP_CHECK(cj_bspline_surface_eval_derivs(&sv, s.ku[s.p], NAN, 1, 1, d) == CJ_ERR_NONFINITE,
              "NaN v: %s", cj_last_error());
    printf("partial derivatives: 40 random surfaces, 6 (u, v) each (a quarter at interior knots), "
           "all orders up to (p+1, q+1): %d values within cj_bspline_surface_derivs_error_bound of "
           "the MPFR tensor oracle (largest error/bound %.3g, largest bound %.3g of the largest "
           "derivative); order (0, 0) bit-identical to cj_bspline_surface_eval; order 17, u "
           "outside the domain, NaN v refused\n",
           checked, worst, loosest);
}

int main(void) {
    const uint64_t seed = cj_test_seed("test_bspline_surface_ops", 22);
    cj_rng r;
    cj_rng_init(&r, seed);
    test_elevate(&r);
    test_remove(&r);
    test_derivs(&r);
    mpfr_free_cache();
    if (bsp_failures) {
        printf("%d failure(s)\n", bsp_failures);
        return 1;
    }
    printf("test_bspline_surface_ops: all checks passed\n");
    return 0;
}

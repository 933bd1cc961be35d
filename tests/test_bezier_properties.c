/* Seeded property suite for Bézier curves: at least CASES random curves per property, degrees
 * 1..20, dimensions 2 and 3 (2D only where the property is planar). Tolerances are derived
 * from the library's published error bounds (cj_bezier_error_bound, the compensated
 * a-posteriori bound) and from explicit rounding counts, never a bare fixed epsilon.
 * A failure names the property, the seed and the case number; CJ_SEED=<n> replays. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "casteljau/bezier.h"
#include "casteljau/transform.h"
#include "rng.h"

#include <inttypes.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bezier_properties.h"

uint64_t g_seed;

void rng_for(cj_rng *r, int property) {
    cj_rng_init(r, g_seed ^ (0x9e3779b97f4a7c15ull * (uint64_t)(property + 1)));
}

/* Random curve: degree 1..20, dim 2 or 3 (or forced), coordinates in [-s, s] with s a random
 * power of ten between 1e-3 and 1e3. */
void random_curve(cj_rng *r, rcurve *rc, int dim) {
    rc->n = cj_rng_int(r, 1, MAXDEG);
    rc->d = dim ? dim : cj_rng_int(r, 2, 3);
    const double s = pow(10.0, cj_rng_int(r, -3, 3));
    rc->mag = 0;
    for (int i = 0; i < (rc->n + 1) * rc->d; ++i) {
        rc->p[i] = cj_rng_range(r, -s, s);
        rc->mag = fmax(rc->mag, fabs(rc->p[i]));
    }
    rc->c = cj_bezier_view(rc->n, rc->d, rc->p);
}

void ev(const cj_bezier *c, double t, double *out) {
    assert_int_equal(cj_bezier_eval_decasteljau(c, t, out), CJ_OK);
}

void bnd(const cj_bezier *c, double t, double *out) {
    assert_int_equal(cj_bezier_error_bound(c, CJ_EVAL_DECASTELJAU, t, out), CJ_OK);
}

double maxabs(const double *v, int m) {
    double r = 0;
    for (int i = 0; i < m; ++i) r = fmax(r, fabs(v[i]));
    return r;
}

/* A dyadic parameter k/2^10 in [0,1]: products and 1-t are then exact. */
double dyadic(cj_rng *r) {
    return cj_rng_int(r, 0, 1024) / 1024.0;
}

/* ---- basis ------------------------------------------------------------------------------- */

static void prop_basis(void **state) {
    (void)state;
    cj_rng r;
    rng_for(&r, 1);
    for (int cs = 0; cs < CASES; ++cs) {
        const int n = cj_rng_int(&r, 1, MAXDEG);
        const double t = cj_rng_unit(&r);
        double e[MAXDEG + 1], ones[MAXDEG + 1];
        for (int i = 0; i <= n; ++i) ones[i] = 1.0;
        cj_bezier c1 = cj_bezier_view(n, 1, ones);
        const cj_eval_method methods[] = {CJ_EVAL_DECASTELJAU, CJ_EVAL_BERNSTEIN, CJ_EVAL_HORNER,
                                          CJ_EVAL_COMPENSATED};
        for (int m = 0; m < 4; ++m) {
            double sum, b;
            assert_int_equal(cj_bezier_eval(&c1, methods[m], t, &sum), CJ_OK);
            assert_int_equal(cj_bezier_error_bound(&c1, methods[m], t, &b), CJ_OK);
            if (!(fabs(sum - 1.0) <= b))
                PFAIL("basis sums to one", cs, "method %d n %d t %.17g: sum - 1 = %.3g > %.3g", m,
                      n, t, sum - 1.0, b);
        }
        /* Each B_i^n(t) through a unit control vector: non-negative, and equal to the closed
         * form C(n,i) t^i (1-t)^(n-i) computed here in long double. */
        long double binom = 1;
        for (int i = 0; i <= n; ++i) {
            memset(e, 0, sizeof e);
            e[i] = 1.0;
            cj_bezier ci = cj_bezier_view(n, 1, e);
            double v, b;
            ev(&ci, t, &v);
            bnd(&ci, t, &b);
            const long double ref = binom * powl(t, i) * powl(1.0L - t, n - i);
            if (v < 0.0) PFAIL("basis non-negative", cs, "B_%d^%d(%.17g) = %.3g", i, n, t, v);
            if (!(fabsl(v - ref) <= b + 1e-17L + 64 * U * ref))
                PFAIL("basis closed form", cs, "B_%d^%d(%.17g) = %.17g vs %.17Lg", i, n, t, v, ref);
            binom = binom * (n - i) / (i + 1);
        }
    }
    printf("basis: %d cases x 4 methods sum to one within their bounds; %d x (n+1) basis "
           "functions non-negative and match the closed form\n",
           CASES, CASES);
}

/* ---- convex hull ------------------------------------------------------------------------- */

static void prop_convex_hull(void **state) {
    (void)state;
    cj_rng r;
    rng_for(&r, 2);
    int n2 = 0, n3 = 0;
    for (int cs = 0; cs < CASES; ++cs) {
        rcurve rc;
        random_curve(&r, &rc, 0);
        const int d = rc.d;
        int idx[MAXPTS], count = 0;
        if (d == 2) {
            assert_int_equal(cj_bezier_hull2d(&rc.c, idx, &count), CJ_OK);
            ++n2;
        } else {
            ++n3;
        }
        for (int j = 0; j < 32; ++j) {
            const double t = cj_rng_unit(&r);
            double p[3], e[3];
            ev(&rc.c, t, p);
            bnd(&rc.c, t, e);
            const double em = maxabs(e, d);
            if (d == 2 && count >= 3) {
                for (int h = 0; h < count; ++h) {
                    const double *a = rc.p + 2 * idx[h], *b = rc.p + 2 * idx[(h + 1) % count];
                    const double ex = b[0] - a[0], ey = b[1] - a[1];
                    const double px = p[0] - a[0], py = p[1] - a[1];
                    const double cr = ex * py - ey * px;
                    const double tol = (fabs(ex) + fabs(ey)) * em +
                                       8 * U * (fabs(ex) + fabs(ey)) * (fabs(px) + fabs(py) + em);
                    if (cr < -tol)
                        PFAIL("convex hull 2D", cs, "c(%.17g) outside hull edge %d by %.3g", t, h,
                              -cr);
                }
            } else if (d == 3) {
                /* Support functions in 8 random directions plus the 3 axes. */
                for (int q = 0; q < 11; ++q) {
                    double u[3] = {q == 8, q == 9, q == 10};
                    if (q < 8)
                        for (int k = 0; k < 3; ++k) u[k] = cj_rng_range(&r, -1, 1);
                    double sup = -INFINITY, up = 0, ul1 = 0;
                    for (int i = 0; i <= rc.n; ++i) {
                        double s = 0;
                        for (int k = 0; k < 3; ++k) s += u[k] * rc.p[3 * i + k];
                        sup = fmax(sup, s);
                    }
                    for (int k = 0; k < 3; ++k) {
                        up += u[k] * p[k];
                        ul1 += fabs(u[k]);
                    }
                    const double tol = ul1 * em + 8 * U * ul1 * rc.mag;
                    if (up > sup + tol)
                        PFAIL("convex hull 3D", cs, "u.c(%.17g) exceeds support by %.3g", t,
                              up - sup);
                }
            }
        }
    }
    printf("convex hull: %d 2D curves inside their control hull, %d 3D curves within 11 "
           "support functions, 32 samples each\n",
           n2, n3);
}

/* ---- affine invariance ------------------------------------------------------------------- */

static void prop_affine(void **state) {
    (void)state;
    cj_rng r;
    rng_for(&r, 3);
    int far = 0;
    for (int cs = 0; cs < CASES; ++cs) {
        rcurve rc;
        random_curve(&r, &rc, 0);
        const int d = rc.d, np = rc.n + 1;
        double L[3][3], tr[3];
        const int big = cs % 2;
        far += big;
        for (int i = 0; i < d; ++i) {
            for (int k = 0; k < d; ++k) L[i][k] = cj_rng_range(&r, -2, 2);
            tr[i] = big ? cj_rng_range(&r, -1e8, 1e8) : cj_rng_range(&r, -10, 10);
        }
        double q[MAXPTS * 3];
        if (d == 2) {
            cj_xform2 m = cj_xform2_identity();
            for (int i = 0; i < 2; ++i) {
                for (int k = 0; k < 2; ++k) m.m[i][k] = L[i][k];
                m.m[i][2] = tr[i];
            }
            assert_int_equal(cj_xform2_apply_points(&m, rc.p, (size_t)np, q), CJ_OK);
        } else {
            cj_xform3 m = cj_xform3_identity();
            for (int i = 0; i < 3; ++i) {
                for (int k = 0; k < 3; ++k) m.m[i][k] = L[i][k];
                m.m[i][3] = tr[i];
            }
            assert_int_equal(cj_xform3_apply_points(&m, rc.p, (size_t)np, q), CJ_OK);
        }
        cj_bezier cq = cj_bezier_view(rc.n, d, q);
        double colmax[3] = {0, 0, 0};
        for (int i = 0; i < np; ++i)
            for (int k = 0; k < d; ++k) colmax[k] = fmax(colmax[k], fabs(rc.p[i * d + k]));
        const double g = cj_gamma(d + 1);
        for (int j = 0; j < 8; ++j) {
            const double t = cj_rng_unit(&r);
            double p[3], e0[3], a[3], e1[3];
            ev(&rc.c, t, p);
            bnd(&rc.c, t, e0);
            ev(&cq, t, a);
            bnd(&cq, t, e1);
            for (int i = 0; i < d; ++i) {
                double b = tr[i], lmag = fabs(tr[i]), lerr = 0;
                for (int k = 0; k < d; ++k) {
                    b += L[i][k] * p[k];
                    lmag += fabs(L[i][k]) * colmax[k];
                    lerr += fabs(L[i][k]) * e0[k];
                }
                /* Transformed control points and the transformed value each carry at most
                 * gamma(d+1) * lmag of rounding; the evaluations carry their bounds. */
                const double tol = 2.0 * (e1[i] + lerr + 2.0 * g * lmag);
                if (!(fabs(a[i] - b) <= tol))
                    PFAIL("affine invariance", cs,
                          "coord %d at t %.17g: |%.17g - %.17g| = %.3g > %.3g (translation "
                          "%.3g)",
                          i, t, a[i], b, fabs(a[i] - b), tol, tr[i]);
            }
        }
    }
    printf("affine invariance: %d curves (%d translated by up to 1e8), tolerance from "
           "cj_bezier_error_bound\n",
           CASES, far);
}

/* ---- endpoints --------------------------------------------------------------------------- */

static void prop_endpoints(void **state) {
    (void)state;
    cj_rng r;
    rng_for(&r, 4);
    const cj_eval_method methods[] = {CJ_EVAL_DECASTELJAU, CJ_EVAL_BERNSTEIN, CJ_EVAL_HORNER,
                                      CJ_EVAL_COMPENSATED};
    for (int cs = 0; cs < CASES; ++cs) {
        rcurve rc;
        random_curve(&r, &rc, 0);
        const int n = rc.n, d = rc.d;
        const double *bn = rc.p + n * d;
        for (int m = 0; m < 4; ++m) {
            double a[3], b[3], ea[3], eb[3];
            assert_int_equal(cj_bezier_eval(&rc.c, methods[m], 0.0, a), CJ_OK);
            assert_int_equal(cj_bezier_eval(&rc.c, methods[m], 1.0, b), CJ_OK);
            assert_int_equal(cj_bezier_error_bound(&rc.c, methods[m], 0.0, ea), CJ_OK);
            assert_int_equal(cj_bezier_error_bound(&rc.c, methods[m], 1.0, eb), CJ_OK);
            for (int k = 0; k < d; ++k) {
                /* de Casteljau and compensated interpolate exactly (t = 0, 1 are exact). */
                const int exact = m == 0 || m == 3;
                if (exact ? a[k] != rc.p[k] || b[k] != bn[k]
                          : fabs(a[k] - rc.p[k]) > ea[k] || fabs(b[k] - bn[k]) > eb[k])
                    PFAIL("endpoint interpolation", cs, "method %d coord %d", m, k);
            }
        }
        /* Endpoint tangents: c'(0) = n (b1 - b0), c'(1) = n (bn - b(n-1)), from the hodograph
         * and from eval_derivs; the unit tangent at 0 is parallel to b1 - b0. */
        double h[MAXPTS * 3], dv0[6], dv1[6], tg[3];
        assert_int_equal(cj_bezier_hodograph(&rc.c, 1, h), CJ_OK);
        assert_int_equal(cj_bezier_eval_derivs(&rc.c, 0.0, 1, dv0), CJ_OK);
        assert_int_equal(cj_bezier_eval_derivs(&rc.c, 1.0, 1, dv1), CJ_OK);
        cj_bezier ch = cj_bezier_view(n - 1, d, h);
        double h0[3], h1[3];
        ev(&ch, 0.0, h0);
        ev(&ch, 1.0, h1);
        for (int k = 0; k < d; ++k) {
            const double w0 = n * (rc.p[d + k] - rc.p[k]), w1 = n * (bn[k] - bn[k - d]);
            const double tol = 4 * U * n * rc.mag;
            if (fabs(h0[k] - w0) > tol || fabs(dv0[d + k] - w0) > tol)
                PFAIL("endpoint tangent t=0", cs, "coord %d: %.17g / %.17g vs %.17g", k, h0[k],
                      dv0[d + k], w0);
            if (fabs(h1[k] - w1) > tol || fabs(dv1[d + k] - w1) > tol)
                PFAIL("endpoint tangent t=1", cs, "coord %d: %.17g / %.17g vs %.17g", k, h1[k],
                      dv1[d + k], w1);
        }
        int order;
        assert_int_equal(cj_bezier_tangent(&rc.c, 0.0, tg, &order), CJ_OK);
        double dlen = 0, dot = 0;
        for (int k = 0; k < d; ++k) {
            const double dk = rc.p[d + k] - rc.p[k];
            dlen += dk * dk;
            dot += dk * tg[k];
        }
        if (order != 1 || fabs(dot - sqrt(dlen)) > 8 * U * sqrt(dlen) * d)
            PFAIL("unit tangent at t=0", cs, "order %d, cos = %.17g", order, dot / sqrt(dlen));
    }
    printf("endpoints: %d curves interpolate b0 and bn (4 methods); c'(0), c'(1) = n(b1-b0), "
           "n(bn-bn-1) via hodograph and eval_derivs\n",
           CASES);
}

/* ---- reversal, split, elevation ---------------------------------------------------------- */

static void prop_reverse_split_elevate(void **state) {
    (void)state;
    cj_rng r;
    rng_for(&r, 5);
    for (int cs = 0; cs < CASES; ++cs) {
        rcurve rc;
        random_curve(&r, &rc, 0);
        const int n = rc.n, d = rc.d;
        double rev[MAXPTS * 3], left[MAXPTS * 3], right[MAXPTS * 3], el[MAXPTS * 3];
        assert_int_equal(cj_bezier_reverse(&rc.c, rev), CJ_OK);
        const double ts = dyadic(&r);
        assert_int_equal(cj_bezier_split(&rc.c, ts, left, right), CJ_OK);
        const int rr = cj_rng_int(&r, 1, 5);
        assert_int_equal(cj_bezier_elevate(&rc.c, rr, el), CJ_OK);
        cj_bezier cr = cj_bezier_view(n, d, rev), cl = cj_bezier_view(n, d, left),
                  crt = cj_bezier_view(n, d, right), ce = cj_bezier_view(n + rr, d, el);
        /* Rounding of the new control points: split points are de Casteljau values
         * (gamma(3n) M), elevated points rr convex combinations (gamma(3 rr) M). */
        const double split_pts = cj_gamma(3 * n) * rc.mag, elev_pts = cj_gamma(3 * rr) * rc.mag;
        for (int j = 0; j < 8; ++j) {
            const double u = dyadic(&r);
            double a[3], b[3], ea[3], eb[3];
            /* reversal */
            ev(&cr, u, a);
            bnd(&cr, u, ea);
            ev(&rc.c, 1.0 - u, b);
            bnd(&rc.c, 1.0 - u, eb);
            for (int k = 0; k < d; ++k)
                if (fabs(a[k] - b[k]) > ea[k] + eb[k])
                    PFAIL("reversal symmetry", cs, "u %.17g coord %d: %.3g", u, k,
                          fabs(a[k] - b[k]));
            /* left half: c(ts u) */
            ev(&cl, u, a);
            bnd(&cl, u, ea);
            ev(&rc.c, ts * u, b);
            bnd(&rc.c, ts * u, eb);
            for (int k = 0; k < d; ++k)
                if (fabs(a[k] - b[k]) > 2 * (ea[k] + eb[k] + split_pts))
                    PFAIL("split left half", cs, "ts %.17g u %.17g coord %d: %.3g", ts, u, k,
                          fabs(a[k] - b[k]));
            /* right half: c(ts + (1-ts) u) */
            ev(&crt, u, a);
            bnd(&crt, u, ea);
            ev(&rc.c, ts + (1.0 - ts) * u, b);
            bnd(&rc.c, ts + (1.0 - ts) * u, eb);
            for (int k = 0; k < d; ++k)
                if (fabs(a[k] - b[k]) > 2 * (ea[k] + eb[k] + split_pts))
                    PFAIL("split right half", cs, "ts %.17g u %.17g coord %d: %.3g", ts, u, k,
                          fabs(a[k] - b[k]));
            /* elevation */
            const double t = cj_rng_unit(&r);
            ev(&ce, t, a);
            bnd(&ce, t, ea);
            ev(&rc.c, t, b);
            bnd(&rc.c, t, eb);
            for (int k = 0; k < d; ++k)
                if (fabs(a[k] - b[k]) > 2 * (ea[k] + eb[k] + elev_pts))
                    PFAIL("degree elevation", cs, "r %d t %.17g coord %d: %.3g", rr, t, k,
                          fabs(a[k] - b[k]));
        }
        /* The halves share the split point bit for bit. */
        if (memcmp(left + n * d, right, sizeof(double) * (size_t)d) != 0)
            PFAIL("split continuity", cs, "left[n] != right[0] at ts %.17g", ts);
    }
    printf("reversal, split halves and degree elevation (r = 1..5): %d curves, 8 parameters "
           "each, within error bounds\n",
           CASES);
}

/* ---- derivatives ------------------------------------------------------------------------- */

static void prop_hodograph(void **state) {
    (void)state;
    cj_rng r;
    rng_for(&r, 6);
    for (int cs = 0; cs < CASES; ++cs) {
        rcurve rc;
        random_curve(&r, &rc, 0);
        const int n = rc.n, d = rc.d;
        double h[MAXPTS * 3], h3[MAXPTS * 3];
        assert_int_equal(cj_bezier_hodograph(&rc.c, 1, h), CJ_OK);
        assert_int_equal(cj_bezier_hodograph(&rc.c, 3, h3), CJ_OK);
        cj_bezier ch = cj_bezier_view(n - 1, d, h);
        /* max |c'''| on [0,1] by the convex hull property of the third hodograph. */
        const double d3max = n >= 3 ? maxabs(h3, (n - 2) * d) : 0.0;
        const double hh = 0x1p-12;
        for (int j = 0; j < 4; ++j) {
            /* t = k 2^-20 with room for t +- hh: every parameter below is exact. */
            const double t = cj_rng_int(&r, 4096, (1 << 20) - 4096) * 0x1p-20;
            double dv[6], hv[3], eh[3];
            assert_int_equal(cj_bezier_eval_derivs(&rc.c, t, 1, dv), CJ_OK);
            ev(&ch, t, hv);
            bnd(&ch, t, eh);
            for (int k = 0; k < d; ++k) {
                /* Differencing rounds each hodograph point by <= 2u n M; eval_derivs runs the
                 * same triangle in another order: gamma(3n+2) (2 n M). */
                const double tol =
                    eh[k] + 2 * U * n * rc.mag * 2 + cj_gamma(3 * n + 2) * 2 * n * rc.mag;
                if (fabs(dv[d + k] - hv[k]) > tol)
                    PFAIL("hodograph vs eval_derivs", cs, "t %.17g coord %d: %.17g vs %.17g", t, k,
                          hv[k], dv[d + k]);
            }
            /* Central difference with compensated evaluation: truncation <= hh^2/6 max|c'''|,
             * rounding <= (bound(t+hh) + bound(t-hh)) / (2 hh). */
            double pp[3], pm[3], bp[3], bm[3];
            assert_int_equal(cj_bezier_eval_compensated(&rc.c, t + hh, pp, bp), CJ_OK);
            assert_int_equal(cj_bezier_eval_compensated(&rc.c, t - hh, pm, bm), CJ_OK);
            for (int k = 0; k < d; ++k) {
                const double fd = (pp[k] - pm[k]) / (2 * hh);
                const double tol = hh * hh / 6 * d3max + (bp[k] + bm[k]) / (2 * hh) +
                                   4 * U * fabs(fd) + eh[k] + 4 * U * n * rc.mag;
                if (fabs(fd - hv[k]) > tol)
                    PFAIL("hodograph vs finite differences", cs,
                          "t %.17g coord %d: fd %.17g hodograph %.17g (tol %.3g)", t, k, fd, hv[k],
                          tol);
            }
        }
    }
    printf("hodograph: %d curves x 4 parameters agree with eval_derivs and with central "
           "differences (truncation bounded by the 3rd hodograph)\n",
           CASES);
}

/* ---- linear precision -------------------------------------------------------------------- */

static void prop_linear_precision(void **state) {
    (void)state;
    cj_rng r;
    rng_for(&r, 7);
    for (int cs = 0; cs < CASES; ++cs) {
        const int n = cj_rng_int(&r, 1, MAXDEG), d = cj_rng_int(&r, 2, 3);
        double P[3], V[3], p[MAXPTS * 3], mag = 0;
        for (int k = 0; k < d; ++k) {
            P[k] = cj_rng_range(&r, -100, 100);
            V[k] = cj_rng_range(&r, -100, 100);
            mag = fmax(mag, fabs(P[k]) + fabs(V[k]));
        }
        for (int i = 0; i <= n; ++i)
            for (int k = 0; k < d; ++k) p[i * d + k] = P[k] + ((double)i / n) * V[k];
        cj_bezier c = cj_bezier_view(n, d, p);
        for (int j = 0; j < 8; ++j) {
            const double t = cj_rng_unit(&r);
            double a[3], e[3];
            ev(&c, t, a);
            bnd(&c, t, e);
            for (int k = 0; k < d; ++k) {
                const double want = P[k] + t * V[k];
                /* control points carry 3u mag each, the reference 2u mag */
                if (fabs(a[k] - want) > e[k] + 5 * U * mag)
                    PFAIL("linear precision", cs, "n %d t %.17g coord %d: %.17g vs %.17g", n, t, k,
                          a[k], want);
            }
        }
    }
    printf("linear precision: %d equispaced lines reproduce P + tV\n", CASES);
}

/* ---- variation diminishing --------------------------------------------------------------- */

static int sign_changes(const double *v, int m) {
    int ch = 0, last = 0;
    for (int i = 0; i < m; ++i) {
        const int s = (v[i] > 0) - (v[i] < 0);
        if (!s) continue;
        if (last && s != last) ++ch;
        last = s;
    }
    return ch;
}

static void prop_variation_diminishing(void **state) {
    (void)state;
    cj_rng r;
    rng_for(&r, 8);
    long total_curve = 0, total_poly = 0;
    for (int cs = 0; cs < CASES; ++cs) {
        rcurve rc;
        random_curve(&r, &rc, 2);
        const int n = rc.n;
        /* A random line through a point near the curve: f(p) = nx (x - ox) + ny (y - oy). */
        const double ang = cj_rng_range(&r, 0, 6.283185307179586);
        const double nx = cos(ang), ny = sin(ang);
        double o[2];
        ev(&rc.c, cj_rng_unit(&r), o);
        double fpoly[MAXPTS];
        for (int i = 0; i <= n; ++i)
            fpoly[i] = nx * (rc.p[2 * i] - o[0]) + ny * (rc.p[2 * i + 1] - o[1]);
        const int vpoly = sign_changes(fpoly, n + 1);
        /* Dense sampling: values within their rounding bound of zero count as zero (they
         * cannot be trusted for a sign), so noise cannot invent crossings. */
        enum { NS = 400 };
        double fs[NS + 1];
        for (int j = 0; j <= NS; ++j) {
            const double t = (double)j / NS;
            double p[2], e[2];
            ev(&rc.c, t, p);
            bnd(&rc.c, t, e);
            const double f = nx * (p[0] - o[0]) + ny * (p[1] - o[1]);
            const double tol = fabs(nx) * e[0] + fabs(ny) * e[1] + 4 * U * (2 * rc.mag);
            fs[j] = fabs(f) <= tol ? 0.0 : f;
        }
        const int vcurve = sign_changes(fs, NS + 1);
        if (vcurve > vpoly)
            PFAIL("variation diminishing", cs, "line crosses curve %d times, polygon %d", vcurve,
                  vpoly);
        /* Subdivision is variation diminishing too: the two halves' polygons together cross
         * no more often than the original polygon (noise-level values count as zero). */
        double left[MAXPTS * 2], right[MAXPTS * 2];
        assert_int_equal(cj_bezier_split(&rc.c, 0.5, left, right), CJ_OK);
        double fl[2 * MAXPTS];
        const double ztol = 4 * cj_gamma(3 * n + 4) * 2 * rc.mag;
        for (int i = 0; i <= n; ++i) {
            double a = nx * (left[2 * i] - o[0]) + ny * (left[2 * i + 1] - o[1]);
            double b = nx * (right[2 * i] - o[0]) + ny * (right[2 * i + 1] - o[1]);
            fl[i] = fabs(a) <= ztol ? 0.0 : a;
            fl[n + 1 + i] = fabs(b) <= ztol ? 0.0 : b;
        }
        const int vsub = sign_changes(fl, 2 * n + 2);
        if (vsub > vpoly)
            PFAIL("variation diminishing (subdivision)", cs, "halves %d > polygon %d", vsub, vpoly);
        if (vcurve > vsub)
            PFAIL("variation diminishing (curve vs halves)", cs, "curve %d > halves %d", vcurve,
                  vsub);
        total_curve += vcurve;
        total_poly += vpoly;
    }
    printf("variation diminishing: %d 2D curves vs random lines: %ld curve crossings <= %ld "
           "polygon crossings (per curve, also through subdivision)\n",
           CASES, total_curve, total_poly);
}

/* ---- methods agree ----------------------------------------------------------------------- */

static void prop_methods_agree(void **state) {
    (void)state;
    cj_rng r;
    rng_for(&r, 9);
    const cj_eval_method methods[] = {CJ_EVAL_DECASTELJAU, CJ_EVAL_BERNSTEIN, CJ_EVAL_HORNER};
    for (int cs = 0; cs < CASES; ++cs) {
        rcurve rc;
        random_curve(&r, &rc, 0);
        for (int j = 0; j < 8; ++j) {
            const double t = cj_rng_unit(&r);
            double ref[3], rb[3];
            assert_int_equal(cj_bezier_eval_compensated(&rc.c, t, ref, rb), CJ_OK);
            for (int m = 0; m < 3; ++m) {
                double v[3], b[3];
                assert_int_equal(cj_bezier_eval(&rc.c, methods[m], t, v), CJ_OK);
                assert_int_equal(cj_bezier_error_bound(&rc.c, methods[m], t, b), CJ_OK);
                for (int k = 0; k < rc.d; ++k)
                    if (fabs(v[k] - ref[k]) > b[k] + rb[k])
                        PFAIL("methods agree", cs, "method %d t %.17g coord %d: %.3g > %.3g", m, t,
                              k, fabs(v[k] - ref[k]), b[k] + rb[k]);
            }
        }
    }
    printf("methods agree: %d curves x 8 parameters, de Casteljau/Bernstein/Horner within "
           "bound of compensated\n",
           CASES);
}

int main(void) {
    g_seed = cj_test_seed("bezier properties", 20261121);
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(prop_basis),
        cmocka_unit_test(prop_convex_hull),
        cmocka_unit_test(prop_affine),
        cmocka_unit_test(prop_endpoints),
        cmocka_unit_test(prop_reverse_split_elevate),
        cmocka_unit_test(prop_hodograph),
        cmocka_unit_test(prop_linear_precision),
        cmocka_unit_test(prop_variation_diminishing),
        cmocka_unit_test(prop_methods_agree),
        cmocka_unit_test(prop_bbox),
        cmocka_unit_test(prop_arclength),
        cmocka_unit_test(prop_frames),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

/* test_bezier_properties, continued: the bounding box, the arc length (against an independent
 * graded Gauss-Legendre reference) and the Frenet frames. */
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

/* ---- bounding box ------------------------------------------------------------------------ */

/* Golden-section search for the max of sgn * c_k on [a,b]. */
static double golden_max(const cj_bezier *c, int k, double sgn, double a, double b) {
    const double g = 0.6180339887498949;
    double x1 = b - g * (b - a), x2 = a + g * (b - a), p[3];
    ev(c, x1, p);
    double f1 = sgn * p[k];
    ev(c, x2, p);
    double f2 = sgn * p[k];
    for (int it = 0; it < 80; ++it) {
        if (f1 < f2) {
            a = x1;
            x1 = x2;
            f1 = f2;
            x2 = a + g * (b - a);
            ev(c, x2, p);
            f2 = sgn * p[k];
        } else {
            b = x2;
            x2 = x1;
            f2 = f1;
            x1 = b - g * (b - a);
            ev(c, x1, p);
            f1 = sgn * p[k];
        }
    }
    return fmax(f1, f2);
}

void prop_bbox(void **state) {
    (void)state;
    cj_rng r;
    rng_for(&r, 10);
    enum { NS = 300 };
    static double samples[NS + 1][3];
    int interior = 0;
    for (int cs = 0; cs < CASES; ++cs) {
        rcurve rc;
        random_curve(&r, &rc, 0);
        const int d = rc.d;
        double lo[3], hi[3], emax = 0;
        assert_int_equal(cj_bezier_bbox(&rc.c, lo, hi), CJ_OK);
        for (int j = 0; j <= NS; ++j) {
            double e[3];
            ev(&rc.c, (double)j / NS, samples[j]);
            bnd(&rc.c, (double)j / NS, e);
            emax = fmax(emax, maxabs(e, d));
        }
        const double tol = 2 * emax + 16 * U * rc.mag;
        for (int k = 0; k < d; ++k) {
            for (int s = 0; s < 2; ++s) {
                const double sgn = s ? -1.0 : 1.0;
                const double edge = s ? -lo[k] : hi[k];
                double best = -INFINITY;
                for (int j = 0; j <= NS; ++j) {
                    const double v = sgn * samples[j][k];
                    if (v > edge + tol)
                        PFAIL("bbox contains samples", cs, "coord %d sample %d outside by %.3g", k,
                              j, v - edge);
                    /* refine every local maximum of the samples */
                    const double vl = j > 0 ? sgn * samples[j - 1][k] : -INFINITY;
                    const double vr = j < NS ? sgn * samples[j + 1][k] : -INFINITY;
                    if (v >= vl && v >= vr) {
                        const double a = j > 0 ? (double)(j - 1) / NS : 0.0;
                        const double b = j < NS ? (double)(j + 1) / NS : 1.0;
                        best = fmax(best, fmax(v, golden_max(&rc.c, k, sgn, a, b)));
                        if (j > 0 && j < NS) ++interior;
                    }
                }
                if (!(fabs(best - edge) <= tol + 1e-12 * rc.mag))
                    PFAIL("bbox attained", cs, "coord %d side %d: box %.17g, refined max %.17g", k,
                          s, edge, best);
            }
        }
    }
    printf("bbox: %d curves contain %d dense samples each and every face is attained (%d "
           "interior extrema refined by golden section)\n",
           CASES, NS + 1, interior);
}

/* ---- arc length -------------------------------------------------------------------------- */

/* Reference arc length, independent of the adaptive code: 5-point Gauss-Legendre on a mesh
 * graded towards every local minimum of the speed. Near a minimum ts the speed behaves like
 * sqrt(smin^2 + |c''|^2 (t - ts)^2), a valley of width w = smin / D2 (D2 bounds |c''|); the
 * mesh starts at w/64 around ts and doubles outwards, so the valley is always resolved. The
 * speed is |h(t)| with h the hodograph evaluated by the Volk-Schumaker (Horner) method. */
typedef struct ref_ctx {
    cj_bezier h;
} ref_ctx;

static double ref_speed(const ref_ctx *r, double t) {
    double v[3], s2 = 0;
    assert_int_equal(cj_bezier_eval_horner(&r->h, t, v), CJ_OK);
    for (int k = 0; k < r->h.dim; ++k) s2 += v[k] * v[k];
    return sqrt(s2);
}

static long double gl5(const ref_ctx *r, double a, double b) {
    static const double x[5] = {-0.90617984593866399, -0.53846931010568309, 0.0,
                                0.53846931010568309, 0.90617984593866399};
    static const double w[5] = {0.23692688505618909, 0.47862867049936647, 0.56888888888888889,
                                0.47862867049936647, 0.23692688505618909};
    long double s = 0;
    const double c = 0.5 * (a + b), hw = 0.5 * (b - a);
    for (int q = 0; q < 5; ++q) s += (long double)w[q] * ref_speed(r, c + hw * x[q]);
    return s * hw;
}

static int cmp_double(const void *a, const void *b) {
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Returns the reference; *spread = |mesh - halved mesh|. */
static double ref_length(const cj_bezier *c, double *spread) {
    enum { NS = 512, NU = 64, MAXBP = NU + 1 + 2 * MAXDEG * 48 };
    double hd[MAXPTS * 3], h2[MAXPTS * 3];
    assert_int_equal(cj_bezier_hodograph(c, 1, hd), CJ_OK);
    assert_int_equal(cj_bezier_hodograph(c, 2, h2), CJ_OK);
    double d2 = 0;
    for (int i = 0; i + 1 < c->degree; ++i) {
        double q = 0;
        for (int k = 0; k < c->dim; ++k) q += h2[i * c->dim + k] * h2[i * c->dim + k];
        d2 = fmax(d2, sqrt(q));
    }
    ref_ctx r = {cj_bezier_view(c->degree - 1, c->dim, hd)};
    static double bp[MAXBP];
    int nb = 0;
    for (int j = 0; j <= NU; ++j) bp[nb++] = (double)j / NU;
    double sp[NS + 1];
    for (int j = 0; j <= NS; ++j) sp[j] = ref_speed(&r, (double)j / NS);
    for (int j = 0; j <= NS && d2 > 0; ++j) {
        const double l = j > 0 ? sp[j - 1] : INFINITY, rr = j < NS ? sp[j + 1] : INFINITY;
        if (!(sp[j] <= l && sp[j] <= rr)) continue;
        /* golden-section minimum on the neighbouring samples */
        double a = j > 0 ? (double)(j - 1) / NS : 0.0, b = j < NS ? (double)(j + 1) / NS : 1.0;
        const double g = 0.6180339887498949;
        double x1 = b - g * (b - a), x2 = a + g * (b - a);
        double f1 = ref_speed(&r, x1), f2 = ref_speed(&r, x2);
        for (int it = 0; it < 60; ++it) {
            if (f1 > f2) {
                a = x1, x1 = x2, f1 = f2, x2 = a + g * (b - a), f2 = ref_speed(&r, x2);
            } else {
                b = x2, x2 = x1, f2 = f1, x1 = b - g * (b - a), f1 = ref_speed(&r, x1);
            }
        }
        const double ts = f1 < f2 ? x1 : x2, smin = fmin(f1, f2);
        const double w = fmax(smin / d2, 1e-15);
        if (nb < MAXBP) bp[nb++] = ts;
        for (double off = w / 64; off < 2.0 / NU && nb + 2 <= MAXBP; off *= 2) {
            if (ts - off > 0) bp[nb++] = ts - off;
            if (ts + off < 1) bp[nb++] = ts + off;
        }
    }
    qsort(bp, (size_t)nb, sizeof bp[0], cmp_double);
    long double coarse = 0, fine = 0;
    for (int i = 0; i + 1 < nb; ++i) {
        const double a = bp[i], b = bp[i + 1];
        if (!(b > a)) continue;
        coarse += gl5(&r, a, b);
        fine += gl5(&r, a, 0.5 * (a + b)) + gl5(&r, 0.5 * (a + b), b);
    }
    *spread = (double)fabsl(fine - coarse);
    return (double)fine;
}

void prop_arclength(void **state) {
    (void)state;
    cj_rng r;
    rng_for(&r, 11);
    double worst = 0, worst_spread = 0;
    for (int cs = 0; cs < CASES; ++cs) {
        rcurve rc;
        random_curve(&r, &rc, 0);
        const double tol = 1e-9 * rc.mag * rc.n;
        double len, est;
        const cj_status st = cj_bezier_arclength(&rc.c, 0.0, 1.0, tol, &len, &est);
        if (st != CJ_OK)
            PFAIL("arc length", cs, "status %s (%s)", cj_status_str(st), cj_last_error());
        if (est > tol) PFAIL("arc length", cs, "estimate %.3g above tol %.3g", est, tol);
        double spread;
        const double ref = ref_length(&rc.c, &spread);
        const double err = fabs(len - ref);
        if (err > tol + 2 * spread + 1e-13 * ref)
            PFAIL("arc length vs reference", cs, "%.17g vs %.17g (ref spread %.3g, tol %.3g)", len,
                  ref, spread, tol);
        worst = fmax(worst, err / tol);
        worst_spread = fmax(worst_spread, spread / tol);
    }
    printf("arc length: %d curves within tol of a graded-mesh Gauss-Legendre reference (worst "
           "error/tol %.3g, worst reference spread/tol %.3g)\n",
           CASES, worst, worst_spread);
}

/* ---- frames ------------------------------------------------------------------------------ */

/* Unit tangent, normal and curvature against the textbook formulas evaluated from
 * cj_bezier_eval_derivs. Relative tolerance from first-order perturbation: the derivatives
 * carry about gamma(3n+4) 2^k n^k M of rounding (k = order), so the formulas are trusted to
 * that over the speed; points with speed below 1e-6 of its scale are counted, not compared. */
void prop_frames(void **state) {
    (void)state;
    cj_rng r;
    rng_for(&r, 12);
    int compared = 0, slow = 0;
    for (int cs = 0; cs < CASES; ++cs) {
        rcurve rc;
        random_curve(&r, &rc, 0);
        const int n = rc.n, d = rc.d;
        const double t = cj_rng_unit(&r);
        double dv[9];
        assert_int_equal(cj_bezier_eval_derivs(&rc.c, t, 2, dv), CJ_OK);
        const double *d1 = dv + d, *d2 = dv + 2 * d;
        double sp = 0;
        for (int k = 0; k < d; ++k) sp += d1[k] * d1[k];
        sp = sqrt(sp);
        const double scale1 = 2.0 * n * rc.mag, scale2 = 4.0 * n * n * rc.mag;
        if (sp < 1e-6 * scale1) {
            ++slow;
            continue;
        }
        ++compared;
        const double g = cj_gamma(3 * n + 8);
        double tg[3], nm[3], kap;
        int order;
        assert_int_equal(cj_bezier_tangent(&rc.c, t, tg, &order), CJ_OK);
        const cj_status ns = cj_bezier_normal(&rc.c, t, nm);
        if (n == 1 && d == 3) { /* a 3D line has no principal normal */
            if (ns != CJ_ERR_DEGENERATE) PFAIL("frames", cs, "3D line normal: %d", (int)ns);
        } else if (ns != CJ_OK) {
            PFAIL("unit normal", cs, "status %s", cj_status_str(ns));
        }
        const cj_status ks = cj_bezier_curvature(&rc.c, t, &kap);
        if (order != 1) PFAIL("frames", cs, "tangent order %d at a regular point", order);
        const double rel1 = 8 * g * scale1 / sp;
        const int has_normal = ns == CJ_OK;
        double dot_tn = 0, nn = 0;
        for (int k = 0; k < d; ++k) {
            if (fabs(tg[k] - d1[k] / sp) > rel1)
                PFAIL("unit tangent", cs, "t %.17g coord %d: %.17g vs %.17g", t, k, tg[k],
                      d1[k] / sp);
            if (has_normal) {
                dot_tn += tg[k] * nm[k];
                nn += nm[k] * nm[k];
            }
        }
        if (has_normal && (fabs(dot_tn) > 1e-13 || fabs(nn - 1) > 1e-13))
            PFAIL("unit normal", cs, "T.N = %.3g, |N|^2 - 1 = %.3g", dot_tn, nn - 1);
        double cr;
        if (d == 2) {
            cr = d1[0] * d2[1] - d1[1] * d2[0];
            if (fabs(nm[0] + tg[1]) > 1e-15 || fabs(nm[1] - tg[0]) > 1e-15)
                PFAIL("2D normal", cs, "not the left normal at t %.17g", t);
        } else {
            const double c0 = d1[1] * d2[2] - d1[2] * d2[1], c1 = d1[2] * d2[0] - d1[0] * d2[2],
                         c2 = d1[0] * d2[1] - d1[1] * d2[0];
            cr = sqrt(c0 * c0 + c1 * c1 + c2 * c2);
        }
        const double kref = cr / (sp * sp * sp);
        /* error of the cross product ~ g (|c'| scale2 + |c''| scale1), then divided by sp^3 */
        const double ktol =
            16 * g * (sp * scale2 + scale2 * scale1) / (sp * sp * sp) + 8 * rel1 * fabs(kref);
        if (ks != CJ_OK && ks != CJ_ERR_DEGENERATE)
            PFAIL("curvature", cs, "status %s", cj_status_str(ks));
        if (ks == CJ_OK && fabs(kap - kref) > ktol)
            PFAIL("curvature", cs, "t %.17g: %.17g vs %.17g (tol %.3g)", t, kap, kref, ktol);
    }
    printf("frames: %d of %d random curves compared (tangent, normal, curvature vs eval_derivs "
           "formulas); %d near-zero-speed points skipped\n",
           compared, CASES, slow);
}

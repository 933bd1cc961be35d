/* Catmull-Rom, centripetal/chordal, Kochanek–Bartels and Hermite splines: the seed's matrix
 * form and the Barry–Goldman pyramid as independent oracles, C¹ joints, degenerate input. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "casteljau/bezier.h"
#include "casteljau/catmull_rom.h"
#include "rng.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#define MAXP 40

static double seg_eval(const double *segs, size_t s, int dim, double u, int k, double *out) {
    cj_bezier b = cj_bezier_view(3, dim, segs + s * 4 * (size_t)dim);
    double d[4 * 3];
    assert_int_equal(cj_bezier_eval_derivs(&b, u, k, d), CJ_OK);
    memcpy(out, d + k * dim, sizeof(double) * (size_t)dim);
    return 0.0;
}

static double scale_of(const double *pts, size_t n, int dim) {
    double m = 0.0;
    for (size_t i = 0; i < n * (size_t)dim; ++i) m = fmax(m, fabs(pts[i]));
    return m > 0 ? m : 1.0;
}

/* The seed's matrix form (eq. 126) of uniform Catmull-Rom with tension κ on the segment from
 * p1 to p2 with neighbours p0, p3: c(u) = [u³ u² u 1] M [p0 p1 p2 p3]ᵀ. */
static void seed_matrix_eval(double kap, const double *p0, const double *p1, const double *p2,
                             const double *p3, int dim, double u, double *out) {
    const double M[4][4] = {{-kap, 2 - kap, kap - 2, kap},
                            {2 * kap, kap - 3, 3 - 2 * kap, -kap},
                            {-kap, 0, kap, 0},
                            {0, 1, 0, 0}};
    const double U[4] = {u * u * u, u * u, u, 1};
    for (int k = 0; k < dim; ++k) {
        const double P[4] = {p0[k], p1[k], p2[k], p3[k]};
        double s = 0;
        for (int r = 0; r < 4; ++r)
            for (int c = 0; c < 4; ++c) s += U[r] * M[r][c] * P[c];
        out[k] = s;
    }
}

static void test_uniform_matches_seed_matrix(void **state) {
    (void)state;
    cj_rng rng;
    cj_rng_init(&rng, cj_test_seed("test_catmull_rom/seed_matrix", 3101));
    double worst = 0;
    for (int cas = 0; cas < 200; ++cas) {
        const int dim = cj_rng_int(&rng, 1, 3);
        const size_t n = (size_t)cj_rng_int(&rng, 4, 12);
        double pts[MAXP * 3], segs[MAXP * 12];
        for (size_t i = 0; i < n * (size_t)dim; ++i) pts[i] = cj_rng_range(&rng, -10, 10);
        cj_spline_options o = cj_spline_defaults();
        o.tension = cj_rng_range(&rng, -0.5, 1.5);
        size_t ns = 0;
        assert_int_equal(cj_catmull_rom(pts, n, dim, &o, segs, MAXP, &ns, NULL), CJ_OK);
        assert_int_equal(ns, n - 1);
        const double sc = scale_of(pts, n, dim);
        for (size_t j = 1; j + 2 < n; ++j) /* interior segments have both neighbours */
            for (int q = 0; q <= 10; ++q) {
                const double u = q / 10.0;
                double a[3], b[3];
                seg_eval(segs, j, dim, u, 0, a);
                seed_matrix_eval(o.tension, pts + (j - 1) * dim, pts + j * dim, pts + (j + 1) * dim,
                                 pts + (j + 2) * dim, dim, u, b);
                for (int k = 0; k < dim; ++k) {
                    const double e = fabs(a[k] - b[k]) / sc;
                    worst = fmax(worst, e);
                    if (e > 1e-14)
                        fail_msg("case %d segment %zu u=%g coord %d: %g vs %g", cas, j, u, k, a[k],
                                 b[k]);
                }
            }
        /* End segments: the seed's end tangents κ(p2 − p1), κ(pN − pN−1). */
        for (int k = 0; k < dim; ++k) {
            const double t0 = o.tension * (pts[dim + k] - pts[k]);
            assert_true(fabs(segs[dim + k] - (pts[k] + t0 / 3)) <= 1e-14 * sc);
            const double *pl = pts + (n - 1) * dim, *pm = pts + (n - 2) * dim;
            const double tn = o.tension * (pl[k] - pm[k]);
            const double *last = segs + (n - 2) * 4 * dim;
            assert_true(fabs(last[2 * dim + k] - (pl[k] - tn / 3)) <= 1e-14 * sc);
        }
    }
    printf("uniform Catmull-Rom == seed matrix form (eq. 126) on 200 random splines, worst "
           "relative difference %.2e\n",
           worst);
}

/* Barry–Goldman pyramid: the non-uniform Catmull-Rom point at global knot t in [t1, t2]. */
static void barry_goldman(const double *P0, const double *P1, const double *P2, const double *P3,
                          double t0, double t1, double t2, double t3, double t, int dim,
                          double *out) {
    for (int k = 0; k < dim; ++k) {
        double A1 = ((t1 - t) * P0[k] + (t - t0) * P1[k]) / (t1 - t0);
        double A2 = ((t2 - t) * P1[k] + (t - t1) * P2[k]) / (t2 - t1);
        double A3 = ((t3 - t) * P2[k] + (t - t2) * P3[k]) / (t3 - t2);
        double B1 = ((t2 - t) * A1 + (t - t0) * A2) / (t2 - t0);
        double B2 = ((t3 - t) * A2 + (t - t1) * A3) / (t3 - t1);
        out[k] = ((t2 - t) * B1 + (t - t1) * B2) / (t2 - t1);
    }
}

static void test_nonuniform_match_barry_goldman(void **state) {
    (void)state;
    cj_rng rng;
    cj_rng_init(&rng, cj_test_seed("test_catmull_rom/barry_goldman", 3102));
    double worst = 0;
    for (int cas = 0; cas < 200; ++cas) {
        const int dim = cj_rng_int(&rng, 2, 3);
        const size_t n = (size_t)cj_rng_int(&rng, 4, 10);
        double pts[MAXP * 3], segs[MAXP * 12], knots[MAXP + 1];
        for (size_t i = 0; i < n * (size_t)dim; ++i) pts[i] = cj_rng_range(&rng, -5, 5);
        cj_spline_options o = cj_spline_defaults();
        const double alpha = (cas & 1) ? 1.0 : 0.5;
        o.kind = (cas & 1) ? CJ_SPLINE_CHORDAL : CJ_SPLINE_CENTRIPETAL;
        assert_int_equal(cj_catmull_rom(pts, n, dim, &o, segs, MAXP, NULL, knots), CJ_OK);
        /* knots are |Δp|^α, computed here independently */
        double tk[MAXP];
        tk[0] = 0;
        for (size_t j = 0; j + 1 < n; ++j) {
            double s = 0;
            for (int k = 0; k < dim; ++k) {
                double d = pts[(j + 1) * dim + k] - pts[j * dim + k];
                s += d * d;
            }
            tk[j + 1] = tk[j] + pow(s, alpha / 2);
            assert_true(fabs(knots[j + 1] - tk[j + 1]) <= 1e-13 * tk[j + 1]);
        }
        const double sc = scale_of(pts, n, dim);
        for (size_t j = 1; j + 2 < n; ++j)
            for (int q = 0; q <= 8; ++q) {
                const double u = q / 8.0, t = tk[j] + u * (tk[j + 1] - tk[j]);
                double a[3], b[3];
                seg_eval(segs, j, dim, u, 0, a);
                barry_goldman(pts + (j - 1) * dim, pts + j * dim, pts + (j + 1) * dim,
                              pts + (j + 2) * dim, tk[j - 1], tk[j], tk[j + 1], tk[j + 2], t, dim,
                              b);
                for (int k = 0; k < dim; ++k) {
                    const double e = fabs(a[k] - b[k]) / sc;
                    worst = fmax(worst, e);
                    if (e > 1e-12)
                        fail_msg("case %d (alpha %g) segment %zu u=%g: %.17g vs %.17g", cas, alpha,
                                 j, u, a[k], b[k]);
                }
            }
    }
    printf("centripetal/chordal == Barry-Goldman pyramid on 200 random splines, worst relative "
           "difference %.2e\n",
           worst);
}

/* C¹ at every joint: derivative at the end of segment j (per unit knot) equals that at the
 * start of segment j+1, for every kind and open/closed. */
static void test_c1_joints(void **state) {
    (void)state;
    cj_rng rng;
    cj_rng_init(&rng, cj_test_seed("test_catmull_rom/c1", 3103));
    double worst = 0;
    int checked = 0;
    for (int cas = 0; cas < 400; ++cas) {
        const int dim = cj_rng_int(&rng, 1, 3);
        const size_t n = (size_t)cj_rng_int(&rng, 3, 12);
        double pts[MAXP * 3], segs[MAXP * 12], knots[MAXP + 1];
        for (size_t i = 0; i < n * (size_t)dim; ++i) pts[i] = cj_rng_range(&rng, -3, 3);
        cj_spline_options o = cj_spline_defaults();
        o.kind = (cj_spline_kind)(cas % 4);
        o.closed = (cas / 4) & 1;
        o.tension = o.kind == CJ_SPLINE_KOCHANEK_BARTELS ? cj_rng_range(&rng, -0.5, 0.9)
                                                         : cj_rng_range(&rng, 0.1, 1.0);
        o.bias = o.kind == CJ_SPLINE_KOCHANEK_BARTELS ? cj_rng_range(&rng, -0.9, 0.9) : 0.0;
        size_t ns;
        assert_int_equal(cj_catmull_rom(pts, n, dim, &o, segs, MAXP, &ns, knots), CJ_OK);
        assert_int_equal(ns, o.closed ? n : n - 1);
        const double sc = scale_of(pts, n, dim);
        for (size_t j = 0; j < ns; ++j) {
            /* interpolation: segment j runs from p_j to p_{j+1} exactly */
            const double *s = segs + j * 4 * dim;
            for (int k = 0; k < dim; ++k) {
                assert_true(s[k] == pts[j * dim + k]);
                assert_true(s[3 * dim + k] == pts[((j + 1) % n) * dim + k]);
            }
            if (j + 1 == ns && !o.closed) break;
            const size_t j1 = (j + 1) % ns;
            double d0[3], d1[3];
            seg_eval(segs, j, dim, 1.0, 1, d0);
            seg_eval(segs, j1, dim, 0.0, 1, d1);
            const double h0 = knots[j + 1] - knots[j], h1 = knots[j1 + 1] - knots[j1];
            for (int k = 0; k < dim; ++k) {
                const double e = fabs(d0[k] / h0 - d1[k] / h1) / sc;
                worst = fmax(worst, e);
                if (e > 1e-12)
                    fail_msg("case %d kind %d closed %d joint %zu coord %d: %.17g vs %.17g", cas,
                             (int)o.kind, o.closed, j, k, d0[k] / h0, d1[k] / h1);
            }
            ++checked;
        }
    }
    printf("C1 continuity at %d joints (all kinds, open and closed): worst relative jump %.2e\n",
           checked, worst);
}

static void test_kochanek_bartels(void **state) {
    (void)state;
    const double pts[] = {0, 0, 1, 2, 3, 1, 4, 4, 6, 3};
    double a[5 * 12], b[5 * 12];
    cj_spline_options cr = cj_spline_defaults(), kb = cj_spline_defaults();
    kb.kind = CJ_SPLINE_KOCHANEK_BARTELS;
    kb.tension = 0.0;
    assert_int_equal(cj_catmull_rom(pts, 5, 2, &cr, a, 5, NULL, NULL), CJ_OK);
    assert_int_equal(cj_catmull_rom(pts, 5, 2, &kb, b, 5, NULL, NULL), CJ_OK);
    for (int i = 0; i < 4 * 8; ++i) assert_true(fabs(a[i] - b[i]) <= 1e-15 * 8);
    /* continuity C = 0.5: incoming and outgoing tangents at p_2 from the published formulas */
    kb.continuity = 0.5;
    kb.bias = 0.25;
    kb.tension = 0.2;
    double out[10], in[10];
    assert_int_equal(cj_catmull_rom_tangents(pts, 5, 2, &kb, out, in), CJ_OK);
    const double T = 0.2, C = 0.5, B = 0.25;
    for (int k = 0; k < 2; ++k) {
        const double back = pts[4 + k] - pts[2 + k], fwd = pts[6 + k] - pts[4 + k];
        const double eo =
            (1 - T) * (1 + B) * (1 + C) / 2 * back + (1 - T) * (1 - B) * (1 - C) / 2 * fwd;
        const double ei =
            (1 - T) * (1 + B) * (1 - C) / 2 * back + (1 - T) * (1 - B) * (1 + C) / 2 * fwd;
        assert_true(fabs(out[4 + k] - eo) <= 1e-15 * 8);
        assert_true(fabs(in[4 + k] - ei) <= 1e-15 * 8);
    }
    printf("Kochanek-Bartels: T=C=B=0 equals Catmull-Rom k=0.5; in/out tangents match the "
           "formulas\n");
}

static void test_degenerate_inputs(void **state) {
    (void)state;
    double segs[4 * 12];
    size_t ns = 99;
    /* two points: a straight cubic, for every kind */
    const double two[] = {1, 1, 4, 5};
    for (int kind = 0; kind < 4; ++kind) {
        cj_spline_options o = cj_spline_defaults();
        o.kind = (cj_spline_kind)kind;
        assert_int_equal(cj_catmull_rom(two, 2, 2, &o, segs, 4, &ns, NULL), CJ_OK);
        assert_int_equal(ns, 1);
        for (int i = 1; i <= 2; ++i) { /* inner control points on the line, finite */
            const double *p = segs + 2 * i;
            assert_true(isfinite(p[0]) && isfinite(p[1]));
            assert_true(fabs((p[0] - 1) * 4 - (p[1] - 1) * 3) <= 1e-14);
        }
    }
    /* repeated consecutive points: defined for uniform, named error for centripetal/chordal */
    const double rep[] = {0, 0, 1, 1, 1, 1, 2, 0};
    cj_spline_options o = cj_spline_defaults();
    assert_int_equal(cj_catmull_rom(rep, 4, 2, &o, segs, 4, &ns, NULL), CJ_OK);
    for (int i = 0; i < 3 * 8; ++i) assert_true(isfinite(segs[i]));
    o.kind = CJ_SPLINE_CENTRIPETAL;
    assert_int_equal(cj_catmull_rom(rep, 4, 2, &o, segs, 4, &ns, NULL), CJ_ERR_DEGENERATE);
    assert_non_null(strstr(cj_last_error(), "points 1 and 2"));
    o.kind = CJ_SPLINE_CHORDAL;
    o.closed = 1; /* the closing pair (last, first) must be distinct too */
    const double loop[] = {0, 0, 1, 0, 0, 0};
    assert_int_equal(cj_catmull_rom(loop, 3, 2, &o, segs, 4, &ns, NULL), CJ_ERR_DEGENERATE);
    assert_non_null(strstr(cj_last_error(), "points 2 and 0"));
    /* too few points, bad values, small buffer */
    o = cj_spline_defaults();
    assert_int_equal(cj_catmull_rom(two, 1, 2, &o, segs, 4, &ns, NULL), CJ_ERR_EMPTY);
    o.closed = 1;
    assert_int_equal(cj_catmull_rom(two, 2, 2, &o, segs, 4, &ns, NULL), CJ_ERR_EMPTY);
    o.closed = 0;
    const double bad[] = {0, 0, NAN, 1, 2, 2};
    assert_int_equal(cj_catmull_rom(bad, 3, 2, &o, segs, 4, &ns, NULL), CJ_ERR_NONFINITE);
    assert_non_null(strstr(cj_last_error(), "point 1"));
    assert_int_equal(cj_catmull_rom(rep, 4, 2, &o, segs, 2, &ns, NULL), CJ_ERR_BUFFER);
    o.tension = INFINITY;
    assert_int_equal(cj_catmull_rom(rep, 4, 2, &o, segs, 4, &ns, NULL), CJ_ERR_NONFINITE);
    printf("degenerate inputs: two points -> straight cubic, repeated points defined (uniform) "
           "or named errors\n");
}

static void test_hermite(void **state) {
    (void)state;
    cj_rng rng;
    cj_rng_init(&rng, cj_test_seed("test_catmull_rom/hermite", 3104));
    for (int cas = 0; cas < 100; ++cas) {
        const int dim = cj_rng_int(&rng, 1, 3);
        const size_t n = (size_t)cj_rng_int(&rng, 2, 8);
        double pts[MAXP * 3], tans[MAXP * 3], knots[MAXP], segs[MAXP * 12];
        knots[0] = cj_rng_range(&rng, -2, 2);
        for (size_t j = 0; j < n; ++j) {
            if (j) knots[j] = knots[j - 1] + cj_rng_range(&rng, 0.1, 2);
            for (int k = 0; k < dim; ++k) {
                pts[j * dim + k] = cj_rng_range(&rng, -4, 4);
                tans[j * dim + k] = cj_rng_range(&rng, -4, 4);
            }
        }
        size_t ns;
        assert_int_equal(cj_hermite_spline(pts, tans, knots, n, dim, segs, MAXP, &ns), CJ_OK);
        for (size_t j = 0; j + 1 < n; ++j) {
            const double h = knots[j + 1] - knots[j];
            for (int e = 0; e < 2; ++e) {
                double p[3], d[3];
                seg_eval(segs, j, dim, e, 0, p);
                seg_eval(segs, j, dim, e, 1, d);
                for (int k = 0; k < dim; ++k) {
                    assert_true(fabs(p[k] - pts[(j + e) * dim + k]) <= 1e-14 * 8);
                    if (fabs(d[k] / h - tans[(j + e) * dim + k]) > 1e-12 * (1 + 4 / h))
                        fail_msg("case %d seg %zu end %d: derivative %.17g vs %.17g", cas, j, e,
                                 d[k] / h, tans[(j + e) * dim + k]);
                }
            }
        }
    }
    double one[12];
    const double p0[] = {0, 0, 0}, v0[] = {3, 0, 0}, p1[] = {1, 1, 1}, v1[] = {0, 3, 0};
    assert_int_equal(cj_hermite_segment(p0, v0, p1, v1, 3, one), CJ_OK);
    assert_true(one[3] == 1 && one[7] == 0 && one[10] == 1);
    const double hp[] = {0, 0, 1, 1, 2, 0}, ht[] = {1, 0, 1, 0, 1, 0}, kn[] = {0, 0, 1};
    assert_int_equal(cj_hermite_spline(hp, ht, kn, 3, 2, one, 2, NULL), CJ_ERR_ARGUMENT);
    assert_non_null(strstr(cj_last_error(), "knots 0 and 1"));
    assert_int_equal(cj_hermite_spline(hp, ht, NULL, 1, 2, one, 2, NULL), CJ_ERR_EMPTY);
    printf("Hermite splines: end values and derivatives (global parameter) on 100 random "
           "splines\n");
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_uniform_matches_seed_matrix),
        cmocka_unit_test(test_nonuniform_match_barry_goldman),
        cmocka_unit_test(test_c1_joints),
        cmocka_unit_test(test_kochanek_bartels),
        cmocka_unit_test(test_degenerate_inputs),
        cmocka_unit_test(test_hermite),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

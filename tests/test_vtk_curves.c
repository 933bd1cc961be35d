/* Cross-check against VTK: VTK's own Bézier cell evaluation of our curves (degrees 1..10,
 * polynomial and rational), uniform Catmull-Rom against vtkKochanekSpline, .vtu round trip. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "casteljau/bezier.h"
#include "casteljau/catmull_rom.h"
#include "casteljau/rational.h"
#include "casteljau/vtk_export.h"
#include "rng.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#define NT 1001

static double size_of(const double *pts, int n, int dim) {
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (int i = 0; i <= n; ++i)
        for (int k = 0; k < dim; ++k) {
            lo[k] = fmin(lo[k], pts[i * dim + k]);
            hi[k] = fmax(hi[k], pts[i * dim + k]);
        }
    double s = 0;
    for (int k = 0; k < dim; ++k) s += (hi[k] - lo[k]) * (hi[k] - lo[k]);
    return sqrt(s) > 0 ? sqrt(s) : 1.0;
}

static void test_vtk_evaluates_our_curves(void **state) {
    (void)state;
    cj_rng rng;
    cj_rng_init(&rng, cj_test_seed("test_vtk_curves/eval", 3601));
    static double ts[NT], ours[NT * 3], vtk[NT * 3];
    for (int j = 0; j < NT; ++j) ts[j] = (double)j / (NT - 1);
    double worst_poly[11] = {0}, worst_rat[11] = {0};
    for (int n = 1; n <= 10; ++n)
        for (int rep = 0; rep < 6; ++rep) {
            const int dim = 1 + rep % 3;
            double pts[11 * 3], w[11];
            for (int i = 0; i <= n; ++i) {
                for (int k = 0; k < dim; ++k) pts[i * dim + k] = cj_rng_range(&rng, -100, 100);
                w[i] = exp(cj_rng_range(&rng, log(0.25), log(4.0)));
            }
            const double sz = size_of(pts, n, dim);
            cj_bezier c = cj_bezier_view(n, dim, pts);
            cj_rbezier r = cj_rbezier_view(n, dim, pts, w);
            assert_int_equal(cj_vtk_eval_bezier(&c, ts, NT, vtk), CJ_OK);
            for (int j = 0; j < NT; ++j) {
                assert_int_equal(cj_bezier_eval_decasteljau(&c, ts[j], ours), CJ_OK);
                for (int k = 0; k < 3; ++k) {
                    const double e = fabs((k < dim ? ours[k] : 0.0) - vtk[3 * j + k]) / sz;
                    worst_poly[n] = fmax(worst_poly[n], e);
                    if (e > 1e-12)
                        fail_msg("degree %d rep %d t=%g coord %d: ours %.17g VTK %.17g", n, rep,
                                 ts[j], k, ours[k], vtk[3 * j + k]);
                }
            }
            assert_int_equal(cj_vtk_eval_rbezier(&r, ts, NT, vtk), CJ_OK);
            for (int j = 0; j < NT; ++j) {
                assert_int_equal(cj_rbezier_eval(&r, ts[j], ours), CJ_OK);
                for (int k = 0; k < dim; ++k) {
                    const double e = fabs(ours[k] - vtk[3 * j + k]) / sz;
                    worst_rat[n] = fmax(worst_rat[n], e);
                    if (e > 1e-12)
                        fail_msg("rational degree %d rep %d t=%g coord %d: ours %.17g VTK %.17g", n,
                                 rep, ts[j], k, ours[k], vtk[3 * j + k]);
                }
            }
        }
    printf("VTK_BEZIER_CURVE evaluated by VTK vs ours, 6 curves x %d parameters per degree, "
           "max |diff| / curve size:\n  degree:   ",
           NT);
    for (int n = 1; n <= 10; ++n) printf(" %8d", n);
    printf("\n  poly:     ");
    for (int n = 1; n <= 10; ++n) printf(" %8.1e", worst_poly[n]);
    printf("\n  rational: ");
    for (int n = 1; n <= 10; ++n) printf(" %8.1e", worst_rat[n]);
    printf("\n");
    /* a rational quarter circle: VTK's point lies on the circle too */
    double arc[6], aw[3];
    assert_int_equal(cj_rbezier_ellipse_arc(1, 2, 3, 3, 0, 0.2, 1.7, arc, aw), CJ_OK);
    cj_rbezier ra = cj_rbezier_view(2, 2, arc, aw);
    assert_int_equal(cj_vtk_eval_rbezier(&ra, ts, NT, vtk), CJ_OK);
    double rad = 0;
    for (int j = 0; j < NT; ++j)
        rad = fmax(rad, fabs(hypot(vtk[3 * j] - 1, vtk[3 * j + 1] - 2) - 3));
    assert_true(rad < 1e-14 * 8);
    printf("VTK's evaluation of our rational circle arc: max radius error %.1e\n", rad);
    /* contract: parameters in [0,1], dimension <= 3, degree >= 1 */
    double t2 = 1.5;
    const double p8[8] = {0, 1, 2, 3, 4, 5, 6, 7};
    cj_bezier c1 = cj_bezier_view(1, 2, p8);
    assert_int_equal(cj_vtk_eval_bezier(&c1, &t2, 1, vtk), CJ_ERR_RANGE);
    c1.dim = 4; /* two points of dimension 4: p8 holds them */
    assert_int_equal(cj_vtk_eval_bezier(&c1, ts, 1, vtk), CJ_ERR_DIMENSION);
    c1.dim = 2;
    c1.degree = 0;
    assert_int_equal(cj_vtk_eval_bezier(&c1, ts, 1, vtk), CJ_ERR_DEGREE);
}

static void test_catmull_rom_vs_kochanek(void **state) {
    (void)state;
    cj_rng rng;
    cj_rng_init(&rng, cj_test_seed("test_vtk_curves/kochanek", 3602));
    double worst_int = 0, worst_end = 0;
    int nint = 0;
    for (int cas = 0; cas < 40; ++cas) {
        const int dim = cj_rng_int(&rng, 1, 3);
        const size_t n = (size_t)cj_rng_int(&rng, 4, 12);
        double pts[12 * 3], segs[12 * 12], sz = 0;
        for (size_t i = 0; i < n * (size_t)dim; ++i) {
            pts[i] = cj_rng_range(&rng, -10, 10);
            sz = fmax(sz, fabs(pts[i]));
        }
        cj_spline_options o = cj_spline_defaults(); /* uniform, κ = 0.5 */
        size_t ns;
        assert_int_equal(cj_catmull_rom(pts, n, dim, &o, segs, 12, &ns, NULL), CJ_OK);
        enum { PER = 101 };
        double ts[PER], vk[PER * 3];
        for (size_t s = 0; s < ns; ++s) {
            for (int q = 0; q < PER; ++q) ts[q] = (double)s + (double)q / (PER - 1);
            assert_int_equal(cj_vtk_kochanek_eval(pts, n, dim, 0, 0, 0, 0, ts, PER, vk), CJ_OK);
            cj_bezier b = cj_bezier_view(3, dim, segs + s * 4 * (size_t)dim);
            const int interior = s >= 1 && s + 2 < n;
            for (int q = 0; q < PER; ++q) {
                double p[3];
                cj_bezier_eval_decasteljau(&b, (double)q / (PER - 1), p);
                for (int k = 0; k < dim; ++k) {
                    const double e = fabs(p[k] - vk[q * dim + k]) / sz;
                    if (interior) {
                        worst_int = fmax(worst_int, e);
                        if (e > 1e-12)
                            fail_msg("case %d interior segment %zu u=%d: ours %.17g VTK %.17g", cas,
                                     s, q, p[k], vk[q * dim + k]);
                    } else {
                        worst_end = fmax(worst_end, e);
                    }
                }
            }
            nint += interior;
        }
    }
    printf("uniform Catmull-Rom (k=0.5) vs vtkKochanekSpline (T=C=B=0, by index, end "
           "derivatives prescribed): %d interior segments, max |diff|/size %.1e; end segments "
           "%.1e\n",
           nint, worst_int, worst_end);
}

/* Kochanek–Bartels with random tension, continuity and bias: interior segments agree too. */
static void test_kochanek_bartels_vs_vtk(void **state) {
    (void)state;
    cj_rng rng;
    cj_rng_init(&rng, cj_test_seed("test_vtk_curves/tcb", 3603));
    double worst = 0;
    for (int cas = 0; cas < 40; ++cas) {
        const int dim = cj_rng_int(&rng, 1, 3);
        const size_t n = (size_t)cj_rng_int(&rng, 4, 10);
        double pts[10 * 3], segs[10 * 12], sz = 0;
        for (size_t i = 0; i < n * (size_t)dim; ++i) {
            pts[i] = cj_rng_range(&rng, -10, 10);
            sz = fmax(sz, fabs(pts[i]));
        }
        cj_spline_options o = cj_spline_defaults();
        o.kind = CJ_SPLINE_KOCHANEK_BARTELS;
        o.tension = cj_rng_range(&rng, -1, 1);
        o.continuity = cj_rng_range(&rng, -1, 1);
        o.bias = cj_rng_range(&rng, -1, 1);
        assert_int_equal(cj_catmull_rom(pts, n, dim, &o, segs, 10, NULL, NULL), CJ_OK);
        for (size_t s = 1; s + 2 < n; ++s)
            for (int q = 0; q <= 20; ++q) {
                const double u = q / 20.0, t = (double)s + u;
                double v[3], p[3];
                assert_int_equal(
                    cj_vtk_kochanek_eval(pts, n, dim, o.tension, o.continuity, o.bias, 0, &t, 1, v),
                    CJ_OK);
                cj_bezier b = cj_bezier_view(3, dim, segs + s * 4 * (size_t)dim);
                cj_bezier_eval_decasteljau(&b, u, p);
                for (int k = 0; k < dim; ++k) {
                    const double e = fabs(p[k] - v[k]) / sz;
                    worst = fmax(worst, e);
                    if (e > 1e-12)
                        fail_msg("case %d (T %g C %g B %g) segment %zu u=%g: %.17g vs VTK %.17g",
                                 cas, o.tension, o.continuity, o.bias, s, u, p[k], v[k]);
                }
            }
    }
    printf("Kochanek-Bartels with random T, C, B in [-1,1] vs vtkKochanekSpline, interior "
           "segments of 40 splines: max |diff|/size %.1e\n",
           worst);
}

static void test_vtu_round_trip(void **state) {
    (void)state;
    const char *path = "test_vtk_curves_out.vtu";
    remove(path);
    const double p3[] = {0, 0, 1, 2, 3, 1, 4, 4};
    const double p5[] = {0, 0, 0, 1, 1, 0, 2, 0, 1, 3, 1, 1, 4, 0, 2, 5, 2, 0};
    double arc[6], aw[3];
    assert_int_equal(cj_rbezier_ellipse_arc(0, 0, 2, 1, 0.3, 0, 1.5, arc, aw), CJ_OK);
    const cj_bezier curves[2] = {cj_bezier_view(3, 2, p3), cj_bezier_view(5, 3, p5)};
    const cj_rbezier rc[1] = {cj_rbezier_view(2, 2, arc, aw)};
    assert_int_equal(cj_vtk_write_curves(path, curves, 2, rc, 1), CJ_OK);
    FILE *tmp = fopen("test_vtk_curves_out.vtu.tmp", "rb");
    assert_null(tmp); /* written through a temporary, renamed */
    size_t nc = 0, np = 0;
    int rational = 0;
    assert_int_equal(cj_vtk_read_curves(path, NULL, 0, NULL, NULL, 0, &nc, &np, &rational),
                     CJ_ERR_BUFFER);
    assert_int_equal(nc, 3);
    assert_int_equal(np, 4 + 6 + 3);
    int deg[3];
    double pts[13 * 3], w[13];
    assert_int_equal(cj_vtk_read_curves(path, deg, 3, pts, w, 13, &nc, &np, &rational), CJ_OK);
    assert_true(rational);
    assert_int_equal(deg[0], 3);
    assert_int_equal(deg[1], 5);
    assert_int_equal(deg[2], 2);
    for (int i = 0; i < 4; ++i) { /* bit-exact control points in our order */
        assert_true(pts[3 * i] == p3[2 * i] && pts[3 * i + 1] == p3[2 * i + 1]);
        assert_true(pts[3 * i + 2] == 0 && w[i] == 1);
    }
    for (int i = 0; i < 6; ++i)
        assert_memory_equal(pts + 3 * (4 + i), p5 + 3 * i, 3 * sizeof(double));
    for (int i = 0; i < 3; ++i) {
        assert_true(pts[3 * (10 + i)] == arc[2 * i] && pts[3 * (10 + i) + 1] == arc[2 * i + 1]);
        assert_true(w[10 + i] == aw[i]);
    }
    /* failures: unwritable path leaves nothing, unreadable file, empty input */
    const char *bad = "no_such_dir_for_vtk/out.vtu";
    assert_int_equal(cj_vtk_write_curves(bad, curves, 2, NULL, 0), CJ_ERR_IO);
    assert_null(fopen(bad, "rb"));
    assert_int_equal(cj_vtk_read_curves("no_such_file.vtu", deg, 3, pts, w, 13, &nc, &np, NULL),
                     CJ_ERR_IO);
    assert_int_equal(cj_vtk_write_curves(path, NULL, 0, NULL, 0), CJ_ERR_EMPTY);
    remove(path);
    printf(".vtu round trip: 2 polynomial + 1 rational VTK_BEZIER_CURVE cells read back "
           "bit-exactly (node order and weights), failed writes leave no file\n");
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_vtk_evaluates_our_curves),
        cmocka_unit_test(test_catmull_rom_vs_kochanek),
        cmocka_unit_test(test_kochanek_bartels_vs_vtk),
        cmocka_unit_test(test_vtu_round_trip),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

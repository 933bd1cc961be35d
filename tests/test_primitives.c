/* Plane primitives: lines (parametric/implicit, intersections incl. parallel and coincident),
 * perpendicular bisector, circles and ellipses (parametric tangent vs implicit gradient),
 * regular n-gons, polygon simple/convex/contains tests incl. exactly degenerate cases. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "casteljau/primitives.h"
#include "rng.h"

#include <math.h>
#include <mpfr.h>
#include <stdio.h>
#include <string.h>

#define PI 3.14159265358979323846

static void test_lines(void **state) {
    (void)state;
    cj_rng rng;
    cj_rng_init(&rng, cj_test_seed("test_primitives/lines", 3501));
    double worst = 0;
    for (int cas = 0; cas < 1000; ++cas) {
        const cj_vec2 p = cj_v2(cj_rng_range(&rng, -9, 9), cj_rng_range(&rng, -9, 9));
        const cj_vec2 q = cj_v2(cj_rng_range(&rng, -9, 9), cj_rng_range(&rng, -9, 9));
        const cj_vec2 r = cj_v2(cj_rng_range(&rng, -9, 9), cj_rng_range(&rng, -9, 9));
        const cj_vec2 s = cj_v2(cj_rng_range(&rng, -9, 9), cj_rng_range(&rng, -9, 9));
        cj_line2 l, m;
        cj_iline2 mi;
        assert_int_equal(cj_line2_from_points(p, q, &l), CJ_OK);
        assert_int_equal(cj_line2_from_points(r, s, &m), CJ_OK);
        assert_int_equal(cj_line2_to_implicit(&m, &mi), CJ_OK);
        /* r and s satisfy the implicit form; the normal is unit */
        double dr, ds;
        cj_iline2_distance(&mi, r, &dr);
        cj_iline2_distance(&mi, s, &ds);
        assert_true(fabs(dr) < 1e-13 && fabs(ds) < 1e-13);
        assert_true(fabs(hypot(mi.a, mi.b) - 1) < 1e-15);
        cj_intersection kind;
        double sv;
        cj_vec2 x;
        assert_int_equal(cj_line2_intersect_implicit(&l, CJ_EXTENT_LINE, &mi, &kind, &sv, &x),
                         CJ_OK);
        if (kind != CJ_ISECT_POINT) continue; /* parallel by chance: checked below */
        /* independent: Cramer's rule on p + s(q-p) = r + u(s-r) */
        const double d1x = q.x - p.x, d1y = q.y - p.y, d2x = s.x - r.x, d2y = s.y - r.y;
        const double det = d1x * (-d2y) - d1y * (-d2x);
        const double ss = ((r.x - p.x) * (-d2y) - (r.y - p.y) * (-d2x)) / det;
        const double cond = (fabs(d1x * d2y) + fabs(d1y * d2x)) / fabs(det);
        const double e = fabs(sv - ss) / (1 + fabs(ss));
        worst = fmax(worst, e / cond);
        if (e > 1e-13 * cond) fail_msg("case %d: s %.17g vs %.17g (cond %g)", cas, sv, ss, cond);
        /* extents */
        cj_intersection k2;
        cj_line2_intersect_implicit(&l, CJ_EXTENT_SEGMENT, &mi, &k2, NULL, NULL);
        assert_int_equal(k2, (sv >= 0 && sv <= 1) ? CJ_ISECT_POINT : CJ_ISECT_NONE);
        cj_line2_intersect_implicit(&l, CJ_EXTENT_RAY, &mi, &k2, NULL, NULL);
        assert_int_equal(k2, sv >= 0 ? CJ_ISECT_POINT : CJ_ISECT_NONE);
    }
    /* parallel and coincident */
    cj_line2 l = {cj_v2(0, 1), cj_v2(2, 1)};
    cj_iline2 par = {-1, 2, 0};   /* -x + 2y = 0: parallel to l, through the origin */
    cj_iline2 same = {-1, 2, -2}; /* -x + 2y - 2 = 0 contains (0,1) and (2,2) */
    cj_intersection kind;
    double sv = 42;
    assert_int_equal(cj_line2_intersect_implicit(&l, CJ_EXTENT_LINE, &par, &kind, &sv, NULL),
                     CJ_OK);
    assert_int_equal(kind, CJ_ISECT_NONE);
    assert_int_equal(cj_line2_intersect_implicit(&l, CJ_EXTENT_LINE, &same, &kind, &sv, NULL),
                     CJ_OK);
    assert_int_equal(kind, CJ_ISECT_COINCIDENT);
    /* round trip implicit -> parametric */
    cj_line2 back;
    assert_int_equal(cj_iline2_to_param(&same, &back), CJ_OK);
    double d;
    cj_iline2_distance(&same, back.p, &d);
    assert_true(fabs(d) < 1e-15);
    assert_true(fabs(same.a * back.d.x + same.b * back.d.y) == 0);
    /* degenerate */
    assert_int_equal(cj_line2_from_points(cj_v2(1, 1), cj_v2(1, 1), &l), CJ_ERR_DEGENERATE);
    cj_iline2 zero = {0, 0, 1};
    assert_int_equal(cj_line2_intersect_implicit(&back, CJ_EXTENT_LINE, &zero, &kind, NULL, NULL),
                     CJ_ERR_DEGENERATE);
    assert_int_equal(cj_line2_from_points(cj_v2(NAN, 1), cj_v2(1, 1), &l), CJ_ERR_NONFINITE);
    printf("lines: 1000 random parametric x implicit intersections vs Cramer's rule (worst "
           "error/cond %.1e), segment/ray extents, parallel, coincident\n",
           worst);
}

static void test_bisector(void **state) {
    (void)state;
    cj_rng rng;
    cj_rng_init(&rng, cj_test_seed("test_primitives/bisector", 3502));
    for (int cas = 0; cas < 500; ++cas) {
        const cj_vec2 p = cj_v2(cj_rng_range(&rng, -9, 9), cj_rng_range(&rng, -9, 9));
        const cj_vec2 q = cj_v2(cj_rng_range(&rng, -9, 9), cj_rng_range(&rng, -9, 9));
        cj_line2 b;
        cj_iline2 bi;
        assert_int_equal(cj_perpendicular_bisector(p, q, &b, &bi), CJ_OK);
        for (int k = -2; k <= 2; ++k) { /* points on it are equidistant from p and q */
            const cj_vec2 x = cj_line2_point(&b, k * 0.7);
            const double dp = hypot(x.x - p.x, x.y - p.y), dq = hypot(x.x - q.x, x.y - q.y);
            assert_true(fabs(dp - dq) < 1e-12 * (1 + dp));
            double dist;
            cj_iline2_distance(&bi, x, &dist);
            assert_true(fabs(dist) < 1e-12 * (1 + dp));
        }
        assert_true(fabs(cj_v2_dot(b.d, cj_v2_sub(q, p))) <= 1e-12 * cj_v2_dot(b.d, b.d));
    }
    cj_line2 b;
    assert_int_equal(cj_perpendicular_bisector(cj_v2(1, 2), cj_v2(1, 2), &b, NULL),
                     CJ_ERR_DEGENERATE);
    printf("perpendicular bisector: 500 random pairs, points equidistant, parametric and implicit "
           "forms agree\n");
}

static void test_circle_ellipse_tangent_vs_gradient(void **state) {
    (void)state;
    cj_rng rng;
    cj_rng_init(&rng, cj_test_seed("test_primitives/conics", 3503));
    double worst_dot = 0, worst_f = 0;
    for (int cas = 0; cas < 300; ++cas) {
        cj_ellipse e = {cj_v2(cj_rng_range(&rng, -5, 5), cj_rng_range(&rng, -5, 5)),
                        cj_rng_range(&rng, 0.1, 4), cj_rng_range(&rng, 0.1, 4),
                        cj_rng_range(&rng, -4, 4)};
        cj_circle c = {e.center, e.rx};
        for (int k = 0; k < 16; ++k) {
            const double th = cj_rng_range(&rng, -7, 7);
            cj_vec2 p, d, g, t, n;
            double f;
            assert_int_equal(cj_ellipse_eval(&e, th, &p, &d), CJ_OK);
            assert_int_equal(cj_ellipse_implicit(&e, p, &f, &g), CJ_OK);
            worst_f = fmax(worst_f, fabs(f));
            assert_true(fabs(f) < 1e-14 * 32);
            assert_int_equal(cj_ellipse_frame(&e, th, &t, &n), CJ_OK);
            /* rounding of the point is amplified by the aspect ratio in the gradient */
            const double aspect = fmax(e.rx / e.ry, e.ry / e.rx);
            const double dot = fabs(cj_v2_dot(t, n)) / aspect;
            worst_dot = fmax(worst_dot, dot);
            assert_true(dot < 1e-14);
            /* the left normal of the counter-clockwise tangent points inward: against ∇f */
            assert_true(cj_v2_dot(cj_v2_perp(t), n) < 0);
            /* derivative vs central difference of the parametric form */
            cj_vec2 a, b;
            cj_ellipse_eval(&e, th + 1e-6, &a, NULL);
            cj_ellipse_eval(&e, th - 1e-6, &b, NULL);
            assert_true(fabs((a.x - b.x) / 2e-6 - d.x) < 1e-7 * 8);
            assert_true(fabs((a.y - b.y) / 2e-6 - d.y) < 1e-7 * 8);
            /* circle */
            assert_int_equal(cj_circle_eval(&c, th, &p, &d), CJ_OK);
            assert_int_equal(cj_circle_implicit(&c, p, &f, &g), CJ_OK);
            assert_true(fabs(f) < 1e-13 * 32);
            assert_true(fabs(cj_v2_dot(d, g)) < 1e-13 * 32);
        }
    }
    cj_ellipse bad = {cj_v2(0, 0), 0, 1, 0};
    cj_vec2 p;
    assert_int_equal(cj_ellipse_eval(&bad, 0, &p, NULL), CJ_ERR_DEGENERATE);
    cj_circle badc = {cj_v2(0, 0), NAN};
    assert_int_equal(cj_circle_eval(&badc, 0, &p, NULL), CJ_ERR_NONFINITE);
    printf("circles/ellipses: 4800 points, parametric points satisfy the implicit form (max |f| "
           "%.1e), |tangent . gradient normal|/aspect <= %.1e\n",
           worst_f, worst_dot);
}

static void test_polygons(void **state) {
    (void)state;
    cj_vec2 ng[12];
    assert_int_equal(cj_regular_ngon(cj_v2(1, 2), 3, 7, 0.2, ng), CJ_OK);
    double area;
    assert_int_equal(cj_polygon_area(ng, 7, &area), CJ_OK);
    const double exact = 0.5 * 7 * 9 * sin(2 * PI / 7);
    assert_true(fabs(area - exact) < 1e-13 * exact);
    for (int k = 0; k < 7; ++k) {
        assert_true(fabs(hypot(ng[k].x - 1, ng[k].y - 2) - 3) < 1e-15 * 8);
        const cj_vec2 a = ng[k], b = ng[(k + 1) % 7];
        assert_true(fabs(hypot(b.x - a.x, b.y - a.y) - 6 * sin(PI / 7)) < 1e-14);
    }
    int simple, convex, orient, inside;
    assert_int_equal(cj_polygon_is_convex(ng, 7, &convex, &orient), CJ_OK);
    assert_true(convex && orient == 1);
    assert_int_equal(cj_regular_ngon(cj_v2(0, 0), 1, 2, 0, ng), CJ_ERR_DEGENERATE);

    const cj_vec2 square[4] = {{0, 0}, {2, 0}, {2, 2}, {0, 2}};
    const cj_vec2 bowtie[4] = {{0, 0}, {2, 2}, {2, 0}, {0, 2}};
    const cj_vec2 arrow[5] = {{0, 0}, {4, 0}, {4, 4}, {2, 1}, {0, 4}}; /* simple, not convex */
    const cj_vec2 touch[5] = {{0, 0}, {4, 0}, {2, 0}, {4, 3}, {0, 3}}; /* folds back on edge */
    const cj_vec2 vtouch[6] = {{0, 0}, {4, 0}, {4, 4}, {2, 0}, {0, 4}, {0, 2}}; /* vertex on edge */
    const cj_vec2 coll[4] = {{0, 0}, {1, 0}, {2, 0}, {3, 0}};                   /* all collinear */
    const cj_vec2 cw[4] = {{0, 0}, {0, 2}, {2, 2}, {2, 0}};
    const cj_vec2 withcol[5] = {{0, 0}, {1, 0}, {2, 0}, {2, 2}, {0, 2}}; /* collinear vertex */
    struct {
        const cj_vec2 *v;
        size_t n;
        int simple, convex, orient;
        const char *name;
    } cases[] = {
        {square, 4, 1, 1, 1, "square"},         {bowtie, 4, 0, 0, 0, "bowtie"},
        {arrow, 5, 1, 0, 0, "arrow"},           {touch, 5, 0, 0, 0, "fold-back"},
        {vtouch, 6, 0, 0, 0, "vertex on edge"}, {coll, 4, 0, 0, 0, "collinear"},
        {cw, 4, 1, 1, -1, "clockwise square"},  {withcol, 5, 1, 1, 1, "collinear vertex"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        assert_int_equal(cj_polygon_is_simple(cases[i].v, cases[i].n, &simple), CJ_OK);
        assert_int_equal(cj_polygon_is_convex(cases[i].v, cases[i].n, &convex, &orient), CJ_OK);
        if (simple != cases[i].simple || convex != cases[i].convex || orient != cases[i].orient)
            fail_msg("%s: simple %d convex %d orient %d", cases[i].name, simple, convex, orient);
    }
    /* exact orientation: three exactly collinear points that naive evaluation misjudges */
    const cj_vec2 near[4] = {{0.5, 0.5}, {12, 12}, {24, 24}, {0.5, 7}};
    assert_int_equal(cj_polygon_is_simple(near, 4, &simple), CJ_OK);
    assert_true(simple); /* b lies exactly on segment a-c: collinear vertex, still simple */
    /* Exact orientation near degeneracy: triangles (0.5 + i u, 0.5 + j u), (12, 12), (24, 24)
     * with u = 2^-53; the sign of the determinant is computed exactly here with MPFR. */
    int agree = 0, nonzero = 0;
    for (int i = 0; i < 16; ++i)
        for (int j = 0; j < 16; ++j) {
            const cj_vec2 t[3] = {{0.5 + i * 0x1p-53, 0.5 + j * 0x1p-53}, {12, 12}, {24, 24}};
            mpfr_t ax, ay, bx, by, cx, cy, l, r;
            mpfr_inits2(400, ax, ay, bx, by, cx, cy, l, r, (mpfr_ptr)0);
            mpfr_set_d(ax, t[0].x, MPFR_RNDN);
            mpfr_set_d(ay, t[0].y, MPFR_RNDN);
            mpfr_set_d(bx, t[1].x, MPFR_RNDN);
            mpfr_set_d(by, t[1].y, MPFR_RNDN);
            mpfr_set_d(cx, t[2].x, MPFR_RNDN);
            mpfr_set_d(cy, t[2].y, MPFR_RNDN);
            mpfr_sub(bx, bx, ax, MPFR_RNDN); /* exact at 400 bits */
            mpfr_sub(by, by, ay, MPFR_RNDN);
            mpfr_sub(cx, cx, ax, MPFR_RNDN);
            mpfr_sub(cy, cy, ay, MPFR_RNDN);
            mpfr_mul(l, bx, cy, MPFR_RNDN);
            mpfr_mul(r, by, cx, MPFR_RNDN);
            mpfr_sub(l, l, r, MPFR_RNDN);
            const int exact_sign = mpfr_sgn(l);
            mpfr_clears(ax, ay, bx, by, cx, cy, l, r, (mpfr_ptr)0);
            assert_int_equal(cj_polygon_is_convex(t, 3, &convex, &orient), CJ_OK);
            const int got = convex ? orient : 0;
            if (got != exact_sign)
                fail_msg("triangle i=%d j=%d: orientation %d, exact %d", i, j, got, exact_sign);
            agree++;
            nonzero += exact_sign != 0;
        }
    printf("exact orientation: %d near-collinear triangles agree with MPFR (%d non-degenerate)\n",
           agree, nonzero);
    /* point in polygon */
    assert_int_equal(cj_polygon_contains(arrow, 5, cj_v2(2, 0.5), &inside), CJ_OK);
    assert_true(inside);
    assert_int_equal(cj_polygon_contains(arrow, 5, cj_v2(2, 2), &inside), CJ_OK);
    assert_false(inside); /* in the notch */
    assert_int_equal(cj_polygon_contains(square, 4, cj_v2(2, 1), &inside), CJ_OK);
    assert_true(inside); /* on the boundary */
    assert_int_equal(cj_polygon_contains(square, 4, cj_v2(2.0000001, 1), &inside), CJ_OK);
    assert_false(inside);
    assert_int_equal(cj_polygon_area(square, 2, &area), CJ_ERR_EMPTY);
    printf("polygons: regular 7-gon (area, edges, convex), 8 simple/convex cases incl. bowtie, "
           "fold-back, vertex-on-edge, collinear; exact orientation; point in polygon\n");
}

static void test_random_convex(void **state) {
    (void)state;
    cj_rng rng;
    cj_rng_init(&rng, cj_test_seed("test_primitives/convex", 3504));
    for (int cas = 0; cas < 300; ++cas) {
        const int n = cj_rng_int(&rng, 3, 20);
        double ang[20];
        for (int i = 0; i < n; ++i) ang[i] = cj_rng_range(&rng, 0, 2 * PI);
        for (int i = 1; i < n; ++i) /* sort */
            for (int j = i; j > 0 && ang[j] < ang[j - 1]; --j) {
                double t = ang[j];
                ang[j] = ang[j - 1];
                ang[j - 1] = t;
            }
        cj_vec2 v[20];
        for (int i = 0; i < n; ++i) v[i] = cj_v2(3 * cos(ang[i]), 2 * sin(ang[i]));
        int convex, orient, simple;
        assert_int_equal(cj_polygon_is_convex(v, (size_t)n, &convex, &orient), CJ_OK);
        if (!convex || orient != 1) fail_msg("case %d: convex %d orient %d", cas, convex, orient);
        /* swapping two non-adjacent vertices of a convex polygon (n >= 5) makes it non-simple */
        if (n >= 5) {
            cj_vec2 t = v[0];
            v[0] = v[2];
            v[2] = t;
            assert_int_equal(cj_polygon_is_simple(v, (size_t)n, &simple), CJ_OK);
            assert_false(simple);
        }
    }
    printf("300 random convex polygons on an ellipse recognised; vertex swaps make them "
           "non-simple\n");
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_lines),
        cmocka_unit_test(test_bisector),
        cmocka_unit_test(test_circle_ellipse_tangent_vs_gradient),
        cmocka_unit_test(test_polygons),
        cmocka_unit_test(test_random_convex),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

/* Implicit curves: contouring of circles, ellipses, polynomials and user functions, checked
 * against exact distances computed here; saddle resolution; normals; errors. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "casteljau/implicit.h"
#include "rng.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAXPTS 200000
#define MAXPL  64

typedef struct collect {
    double xy[2 * MAXPTS];
    size_t start[MAXPL], len[MAXPL];
    int closed[MAXPL];
    double res[MAXPL];
    size_t n, used;
    int stop_after; /* > 0: return an error after this many polylines */
} collect;

static collect col;

static cj_status collect_fn(void *user, const double *xy, size_t npts, int closed, double res) {
    collect *c = user;
    if (c->stop_after && (int)c->n >= c->stop_after) return CJ_ERR_IO;
    assert_true(c->n < MAXPL && c->used + npts <= MAXPTS);
    memcpy(c->xy + 2 * c->used, xy, sizeof(double) * 2 * npts);
    c->start[c->n] = c->used;
    c->len[c->n] = npts;
    c->closed[c->n] = closed;
    c->res[c->n] = res;
    c->used += npts;
    c->n++;
    return CJ_OK;
}

static void reset(void) {
    col.n = col.used = 0;
    col.stop_after = 0;
}

/* Largest exact distance from the circle over all vertices and over 8 points inside every
 * chord; also checks the reported residual against |f|/|∇f| computed here. */
static double circle_check(double cx, double cy, double r, double tol, const char *what) {
    double worst = 0;
    for (size_t p = 0; p < col.n; ++p) {
        const double *xy = col.xy + 2 * col.start[p];
        double own = 0;
        for (size_t i = 0; i < col.len[p]; ++i) {
            const double d = hypot(xy[2 * i] - cx, xy[2 * i + 1] - cy);
            own = fmax(own, fabs(d * d - r * r) / (2 * d));
            worst = fmax(worst, fabs(d - r));
            if (i + 1 < col.len[p])
                for (int q = 1; q < 8; ++q) {
                    const double s = q / 8.0;
                    const double x = (1 - s) * xy[2 * i] + s * xy[2 * i + 2];
                    const double y = (1 - s) * xy[2 * i + 1] + s * xy[2 * i + 3];
                    worst = fmax(worst, fabs(hypot(x - cx, y - cy) - r));
                }
        }
        if (col.res[p] < 0.99 * own || col.res[p] > tol)
            fail_msg("%s: polyline %zu reports residual %g, vertices reach %g (tol %g)", what, p,
                     col.res[p], own, tol);
    }
    if (worst > 1.01 * tol + 1e-13) fail_msg("%s: distance %g exceeds tol %g", what, worst, tol);
    return worst;
}

static void test_circle_and_ellipse(void **state) {
    (void)state;
    cj_rng rng;
    cj_rng_init(&rng, cj_test_seed("test_implicit/circles", 3401));
    double worst = 0;
    size_t pts = 0;
    for (int cas = 0; cas < 60; ++cas) {
        const double cx = cj_rng_range(&rng, -1, 1), cy = cj_rng_range(&rng, -1, 1);
        const double r = cj_rng_range(&rng, 0.5, 2.5);
        const double tol = pow(10, -cj_rng_range(&rng, 2, 9));
        const int nx = cj_rng_int(&rng, 4, 64), ny = cj_rng_int(&rng, 4, 64);
        cj_implicit_shape sh;
        cj_implicit f;
        assert_int_equal(cj_implicit_circle(cx, cy, r, &sh, &f), CJ_OK);
        const double box[4] = {cx - r - 0.37, cy - r - 0.21, cx + r + 0.13, cy + r + 0.29};
        cj_contour_options o = {nx, ny, tol, NULL};
        cj_contour_stats st;
        reset();
        assert_int_equal(cj_implicit_contour(&f, box, &o, collect_fn, &col, &st), CJ_OK);
        assert_int_equal(col.n, 1);
        assert_int_equal(st.closed, 1);
        assert_true(col.closed[0]);
        const double *xy = col.xy;
        assert_memory_equal(xy, xy + 2 * (col.len[0] - 1), 2 * sizeof(double));
        char what[64];
        snprintf(what, sizeof what, "circle case %d", cas);
        worst = fmax(worst, circle_check(cx, cy, r, tol, what) / tol);
        pts += st.points;
    }
    printf("60 random circles, grids 4..64, tol 1e-2..1e-9: one closed loop each (first == last "
           "bit-exactly), worst distance/tol %.3f over vertices and chords, %zu vertices\n",
           worst, pts);

    /* rotated ellipse: residual |f|/|∇f| at vertices and chord points, computed here */
    cj_implicit_shape sh;
    cj_implicit f;
    const double ex = 0.2, ey = -0.1, rx = 2, ry = 0.5, rot = 0.7, tol = 1e-6;
    assert_int_equal(cj_implicit_ellipse(ex, ey, rx, ry, rot, &sh, &f), CJ_OK);
    const double box[4] = {-3, -3, 3, 3};
    cj_contour_options o = {20, 20, tol, NULL};
    reset();
    assert_int_equal(cj_implicit_contour(&f, box, &o, collect_fn, &col, NULL), CJ_OK);
    assert_int_equal(col.n, 1);
    double ew = 0;
    for (size_t i = 0; i + 1 < col.len[0]; ++i)
        for (int q = 0; q < 8; ++q) {
            const double s = q / 8.0;
            const double x = (1 - s) * col.xy[2 * i] + s * col.xy[2 * i + 2] - ex;
            const double y = (1 - s) * col.xy[2 * i + 1] + s * col.xy[2 * i + 3] - ey;
            const double u = cos(rot) * x + sin(rot) * y, v = -sin(rot) * x + cos(rot) * y;
            const double fv = u * u / (rx * rx) + v * v / (ry * ry) - 1;
            const double gu = 2 * u / (rx * rx), gv = 2 * v / (ry * ry);
            ew = fmax(ew, fabs(fv) / hypot(gu, gv));
        }
    assert_true(ew <= 1.05 * tol);
    printf("rotated ellipse (2 x 0.5): %zu vertices, max |f|/|grad f| on vertices and chords "
           "%.3g (tol %g)\n",
           col.len[0], ew, tol);
}

/* Graded coefficients of the product of two dense polynomials a[i][j] x^i y^j (deg <= 2). */
static void product_graded(const double a[3][3], const double b[3][3], double *coef) {
    double d[5][5] = {{0}};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            for (int k = 0; k < 3; ++k)
                for (int l = 0; l < 3; ++l) d[i + k][j + l] += a[i][j] * b[k][l];
    size_t at = 0;
    for (int s = 0; s <= 4; ++s)
        for (int j = 0; j <= s; ++j) coef[at++] = d[s - j][j];
}

static void test_polynomial_two_loops(void **state) {
    (void)state;
    /* ((x-1)^2 + y^2 - 1/4) ((x+1)^2 + y^2 - 1/4) */
    const double c1[3][3] = {{0.75, 0, 1}, {-2, 0, 0}, {1, 0, 0}};
    const double c2[3][3] = {{0.75, 0, 1}, {2, 0, 0}, {1, 0, 0}};
    double coef[15];
    product_graded(c1, c2, coef);
    assert_int_equal(cj_implicit_poly_ncoef(4), 15);
    cj_implicit_shape sh;
    cj_implicit f;
    assert_int_equal(cj_implicit_poly(4, coef, &sh, &f), CJ_OK);
    /* the exact gradient agrees with the product rule computed here */
    double v, g[2];
    assert_int_equal(cj_implicit_curve_eval(&f, 0.3, -0.7, &v, g), CJ_OK);
    const double x = 0.3, y = -0.7, A = (x - 1) * (x - 1) + y * y - 0.25,
                 B = (x + 1) * (x + 1) + y * y - 0.25;
    assert_true(fabs(v - A * B) < 1e-14);
    assert_true(fabs(g[0] - (2 * (x - 1) * B + 2 * (x + 1) * A)) < 1e-13);
    assert_true(fabs(g[1] - (2 * y * B + 2 * y * A)) < 1e-13);
    const double box[4] = {-2, -1, 2, 1}, tol = 1e-7;
    cj_contour_options o = {32, 16, tol, NULL};
    reset();
    assert_int_equal(cj_implicit_contour(&f, box, &o, collect_fn, &col, NULL), CJ_OK);
    assert_int_equal(col.n, 2);
    double worst = 0;
    for (size_t p = 0; p < 2; ++p) {
        assert_true(col.closed[p]);
        const double *xy = col.xy + 2 * col.start[p];
        const double cx = xy[0] > 0 ? 1 : -1;
        for (size_t i = 0; i < col.len[p]; ++i) {
            assert_true((xy[2 * i] > 0) == (cx > 0)); /* each loop stays on its circle */
            worst = fmax(worst, fabs(hypot(xy[2 * i] - cx, xy[2 * i + 1]) - 0.5));
        }
    }
    assert_true(worst <= 1.01 * tol);
    printf("bivariate quartic (two circles): 2 closed loops, max vertex distance %.2e (tol %g)\n",
           worst, tol);
}

static double hyper(const void *u, double x, double y) {
    const double s = *(const double *)u;
    return s * (x * y - 0.01);
}

/* One saddle cell: the two hyperbola branches must come out as two separate open polylines,
 * whatever the sign convention of f. */
static void test_saddle_resolution(void **state) {
    (void)state;
    for (int sgn = -1; sgn <= 1; sgn += 2) {
        const double s = sgn;
        cj_implicit f = {hyper, NULL, &s};
        const double box[4] = {-1, -1, 1, 1};
        for (int g = 1; g <= 3; g += 2) {
            cj_contour_options o = {g, g, 1e-6, NULL};
            reset();
            assert_int_equal(cj_implicit_contour(&f, box, &o, collect_fn, &col, NULL), CJ_OK);
            assert_int_equal(col.n, 2);
            for (size_t p = 0; p < 2; ++p) {
                assert_false(col.closed[p]);
                const double *xy = col.xy + 2 * col.start[p];
                const int quadrant = xy[0] > 0;
                for (size_t i = 0; i < col.len[p]; ++i) {
                    assert_true((xy[2 * i] > 0) == quadrant && (xy[2 * i + 1] > 0) == quadrant);
                    assert_true(fabs(xy[2 * i] * xy[2 * i + 1] - 0.01) < 1e-6);
                }
                /* open ends lie on the box boundary */
                const double *e = xy + 2 * (col.len[p] - 1);
                assert_true(fabs(fabs(xy[0]) - 1) == 0 || fabs(fabs(xy[1]) - 1) == 0);
                assert_true(fabs(fabs(e[0]) - 1) == 0 || fabs(fabs(e[1]) - 1) == 0);
            }
        }
    }
    printf("saddle cells (xy = 0.01 on 1x1 and 3x3 grids, both signs of f): two open branches, "
           "never joined across\n");
}

static double circle_cb(const void *u, double x, double y) {
    (void)u;
    return x * x + y * y - 1;
}

static void test_user_function_and_normals(void **state) {
    (void)state;
    cj_implicit f = {circle_cb, NULL, NULL}; /* gradient by central differences */
    const double box[4] = {-1.5, -1.5, 1.5, 1.5}, tol = 1e-8;
    cj_contour_options o = {10, 10, tol, NULL};
    reset();
    assert_int_equal(cj_implicit_contour(&f, box, &o, collect_fn, &col, NULL), CJ_OK);
    assert_int_equal(col.n, 1);
    circle_check(0, 0, 1, tol, "user circle");
    cj_implicit_shape sh;
    cj_implicit fc;
    assert_int_equal(cj_implicit_circle(0, 0, 1, &sh, &fc), CJ_OK);
    double worst_fd = 0;
    for (int k = 0; k < 16; ++k) {
        const double th = k * 0.41, px = cos(th), py = sin(th);
        double n1[2], n2[2];
        assert_int_equal(cj_implicit_curve_normal(&fc, px, py, n1), CJ_OK);
        assert_int_equal(cj_implicit_curve_normal(&f, px, py, n2), CJ_OK);
        assert_true(fabs(n1[0] - px) < 1e-15 && fabs(n1[1] - py) < 1e-15);
        worst_fd = fmax(worst_fd, fmax(fabs(n2[0] - px), fabs(n2[1] - py)));
    }
    assert_true(worst_fd < 1e-9);
    double xy[2] = {1.7, 0.3}, res;
    assert_int_equal(cj_implicit_curve_project(&fc, xy, 1e-12, &res), CJ_OK);
    assert_true(fabs(hypot(xy[0], xy[1]) - 1) < 1e-12);
    assert_int_equal(cj_implicit_curve_normal(&fc, 0, 0, xy), CJ_ERR_DEGENERATE);
    printf("user callback without gradient contours within tol; normals exact for built-ins, "
           "%.1e for central differences\n",
           worst_fd);
}

static double nan_cb(const void *u, double x, double y) {
    (void)u;
    return x > 0.5 ? NAN : x + y;
}

static void test_errors(void **state) {
    (void)state;
    cj_implicit_shape sh;
    cj_implicit f;
    assert_int_equal(cj_implicit_circle(0, 0, 0, &sh, &f), CJ_ERR_DEGENERATE);
    assert_int_equal(cj_implicit_line(0, 0, 1, &sh, &f), CJ_ERR_DEGENERATE);
    assert_int_equal(cj_implicit_ellipse(0, 0, 1, -1, 0, &sh, &f), CJ_ERR_DEGENERATE);
    assert_int_equal(cj_implicit_poly(40, NULL, &sh, &f), CJ_ERR_DEGREE);
    assert_int_equal(cj_implicit_line(1, 2, -0.3, &sh, &f), CJ_OK);
    const double box[4] = {-1, -1, 1, 1}, empty[4] = {1, 0, 1, 1};
    cj_contour_options o = {8, 8, 1e-6, NULL};
    reset();
    assert_int_equal(cj_implicit_contour(&f, box, &o, collect_fn, &col, NULL), CJ_OK);
    assert_int_equal(col.n, 1); /* a line crossing the box: one open polyline */
    assert_false(col.closed[0]);
    assert_int_equal(cj_implicit_contour(&f, empty, &o, collect_fn, &col, NULL), CJ_ERR_DEGENERATE);
    o.tol = 0;
    assert_int_equal(cj_implicit_contour(&f, box, &o, collect_fn, &col, NULL), CJ_ERR_ARGUMENT);
    o.tol = 1e-6;
    o.nx = 5000;
    assert_int_equal(cj_implicit_contour(&f, box, &o, collect_fn, &col, NULL), CJ_ERR_ARGUMENT);
    o.nx = 8;
    cj_implicit g = {nan_cb, NULL, NULL};
    assert_int_equal(cj_implicit_contour(&g, box, &o, collect_fn, &col, NULL), CJ_ERR_NONFINITE);
    assert_non_null(strstr(cj_last_error(), "f(0.75"));
    /* the callback's status stops contouring and is returned */
    const double c1[3][3] = {{0.75, 0, 1}, {-2, 0, 0}, {1, 0, 0}};
    const double c2[3][3] = {{0.75, 0, 1}, {2, 0, 0}, {1, 0, 0}};
    double coef[15];
    product_graded(c1, c2, coef);
    assert_int_equal(cj_implicit_poly(4, coef, &sh, &f), CJ_OK);
    const double box2[4] = {-2, -1, 2, 1};
    reset();
    col.stop_after = 1;
    assert_int_equal(cj_implicit_contour(&f, box2, &o, collect_fn, &col, NULL), CJ_ERR_IO);
    assert_int_equal(col.n, 1);
    printf("implicit errors: degenerate shapes, empty box, tol, grid size, NaN f named, callback "
           "stop\n");
}

/* A caller's allocator receives every work array (grid and polyline buffer) and gets all of it
 * back; the polylines are the same as with malloc. */
typedef struct counting_alloc {
    size_t allocs, frees, live_bytes_peak;
} counting_alloc;

static void *count_alloc(void *user, size_t bytes) {
    counting_alloc *a = user;
    a->allocs++;
    if (bytes > a->live_bytes_peak) a->live_bytes_peak = bytes;
    return malloc(bytes);
}

static void count_free(void *user, void *ptr) {
    counting_alloc *a = user;
    if (ptr) a->frees++;
    free(ptr);
}

static void test_caller_allocator(void **state) {
    (void)state;
    cj_implicit_shape sh;
    cj_implicit f;
    assert_int_equal(cj_implicit_ellipse(0.1, -0.2, 1.5, 0.7, 0.3, &sh, &f), CJ_OK);
    const double box[4] = {-2, -2, 2, 2};
    cj_contour_options plain = {40, 30, 1e-9, NULL};
    reset();
    assert_int_equal(cj_implicit_contour(&f, box, &plain, collect_fn, &col, NULL), CJ_OK);
    const size_t n_plain = col.used;
    static double first[MAXPTS * 2];
    memcpy(first, col.xy, sizeof(double) * 2 * n_plain);

    counting_alloc counts = {0, 0, 0};
    const cj_allocator mine = {count_alloc, count_free, &counts};
    cj_contour_options custom = {40, 30, 1e-9, &mine};
    reset();
    assert_int_equal(cj_implicit_contour(&f, box, &custom, collect_fn, &col, NULL), CJ_OK);
    assert_int_equal(col.used, n_plain);
    assert_memory_equal(col.xy, first, sizeof(double) * 2 * n_plain);
    assert_true(counts.allocs >= 6); /* 5 grid arrays and at least one polyline buffer */
    assert_int_equal(counts.frees, counts.allocs);
    printf("caller allocator: %zu allocations, all freed; %zu points identical to malloc's\n",
           counts.allocs, n_plain);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_circle_and_ellipse),
        cmocka_unit_test(test_polynomial_two_loops),
        cmocka_unit_test(test_saddle_resolution),
        cmocka_unit_test(test_user_function_and_normals),
        cmocka_unit_test(test_errors),
        cmocka_unit_test(test_caller_allocator),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

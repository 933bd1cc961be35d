/* Charts (raster/chart.h): log-axis mapping and decade ticks, markers, lines, legend,
 * annotations and axis titles checked pixel by pixel against the exact geometry computed here
 * from the documented layout (not from the code under test); bad input. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "casteljau/chart.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { W = 400, H = 300 };

static cj_rgba px_at(const cj_framebuffer *fb, int x, int y) {
    return fb->pixels[(ptrdiff_t)y * fb->stride + x];
}
static int is_color(cj_rgba p, cj_rgba c) {
    return abs(p.r - c.r) < 24 && abs(p.g - c.g) < 24 && abs(p.b - c.b) < 24;
}
static int is_white(cj_rgba p) {
    return p.r > 250 && p.g > 250 && p.b > 250;
}
/* The pixel whose centre is nearest to the point (x, y) in panel pixels. */
static cj_rgba near_px(const cj_framebuffer *fb, double x, double y) {
    return px_at(fb, (int)floor(x), (int)floor(y));
}

/* The documented map, computed independently: left 12, right W-12 etc. without text. */
static double ex_x(double lo, double hi, double v) {
    return 12 + (log10(v) - log10(lo)) / (log10(hi) - log10(lo)) * (W - 24);
}
static double ex_y_lin(double lo, double hi, double v) {
    return 12 + (v - lo) / (hi - lo) * (H - 24);
}

static const cj_rgba RED = {220, 20, 20, 255}, GREEN = {20, 160, 20, 255},
                     BLUE = {20, 40, 220, 255};

static void test_log_axis_markers_and_ticks(void **state) {
    (void)state;
    cj_chart *c = NULL;
    assert_int_equal(cj_chart_create(NULL, &c), CJ_OK);
    assert_int_equal(cj_chart_set_axis(c, 0, CJ_CHART_LOG10, "x"), CJ_OK);
    const double x[4] = {2e-3, 1e-2, 1.0, 500.0}, y[4] = {1, 4, 2, 9};
    cj_chart_series_opts o = {NULL, RED, 0.0, CJ_MARKER_CIRCLE, 5.0};
    assert_int_equal(cj_chart_add_series(c, x, y, 4, &o), CJ_OK);
    double lo[2], hi[2];
    assert_int_equal(cj_chart_ranges(c, lo, hi), CJ_OK);
    /* whole decades around [2e-3, 500]; linear y rounded out to the step 2 */
    assert_true(fabs(lo[0] - 1e-3) < 1e-18 && fabs(hi[0] - 1e3) < 1e-9);
    assert_true(lo[1] == 0.0 && hi[1] == 10.0);
    cj_framebuffer *fb = NULL;
    assert_int_equal(cj_framebuffer_create(W, H, 0, NULL, &fb), CJ_OK);
    assert_int_equal(cj_chart_render(c, fb, 0, 0, W, H, NULL), CJ_OK);
    int checked = 0;
    for (int i = 0; i < 4; ++i) {
        const double px = ex_x(1e-3, 1e3, x[i]), py = ex_y_lin(0, 10, y[i]);
        double mx, my;
        assert_int_equal(cj_chart_map(c, W, H, 0, x[i], y[i], &mx, &my), CJ_OK);
        assert_true(fabs(mx - px) < 1e-9 && fabs(my - py) < 1e-9);
        /* inside the disc (distance <= r - 1 from a pixel centre): red; outside r + 1.5: not */
        for (int dy = -8; dy <= 8; ++dy)
            for (int dx = -8; dx <= 8; ++dx) {
                const int ix = (int)floor(px) + dx, iy = (int)floor(py) + dy;
                const double d = hypot(ix + 0.5 - px, iy + 0.5 - py);
                const cj_rgba p = px_at(fb, ix, iy);
                if (d <= 4.0) assert_true(is_color(p, RED)), checked++;
                if (d >= 6.5) assert_false(p.r > 150 && p.g < 100), checked++;
            }
    }
    /* major ticks at every decade reach 5 px below the frame (row bottom-5 = 7, centre 7.5),
     * minor ticks (3 px) do not; between decades that row is white */
    for (int e = -3; e <= 3; ++e) {
        const double t = ex_x(1e-3, 1e3, pow(10.0, e));
        assert_true(near_px(fb, t, 7.5).r < 180);
        if (e < 3) assert_true(is_white(near_px(fb, ex_x(1e-3, 1e3, 3.5 * pow(10.0, e)), 7.5)));
        /* the minor tick at 2x a decade does reach row 10 (centre 10.5) */
        if (e < 3) assert_true(near_px(fb, ex_x(1e-3, 1e3, 2 * pow(10.0, e)), 10.5).r < 180);
        checked += 3;
    }
    printf("log x axis [1e-3, 1e3] auto-ranged; 4 disc markers and 7 decade + minor ticks at "
           "their exact pixel positions (%d pixel checks)\n",
           checked);
    cj_framebuffer_destroy(fb);
    cj_chart_destroy(c);
}

static void test_line_and_marker_shapes(void **state) {
    (void)state;
    cj_chart *c = NULL;
    assert_int_equal(cj_chart_create(NULL, &c), CJ_OK);
    assert_int_equal(cj_chart_set_axis(c, 0, CJ_CHART_LOG10, NULL), CJ_OK);
    assert_int_equal(cj_chart_set_axis(c, 1, CJ_CHART_LOG10, NULL), CJ_OK);
    assert_int_equal(cj_chart_set_range(c, 0, 1e-6, 1), CJ_OK);
    assert_int_equal(cj_chart_set_range(c, 1, 1e-2, 1e4), CJ_OK);
    const double lx[2] = {1e-5, 1e-1}, ly[2] = {1e-1, 1e3};
    cj_chart_series_opts lo = {NULL, GREEN, 3.0, CJ_MARKER_NONE, 0};
    assert_int_equal(cj_chart_add_series(c, lx, ly, 2, &lo), CJ_OK);
    const double sx[3] = {1e-5, 1e-3, 1e-1}, sy[3] = {1e3, 1e3, 1e3};
    const cj_chart_marker mk[3] = {CJ_MARKER_SQUARE, CJ_MARKER_TRIANGLE, CJ_MARKER_DIAMOND};
    for (int i = 0; i < 3; ++i) {
        cj_chart_series_opts so = {NULL, BLUE, 0.0, mk[i], 8.0};
        assert_int_equal(cj_chart_add_series(c, sx + i, sy + i, 1, &so), CJ_OK);
    }
    cj_framebuffer *fb = NULL;
    assert_int_equal(cj_framebuffer_create(W, H, 0, NULL, &fb), CJ_OK);
    assert_int_equal(cj_chart_render(c, fb, 0, 0, W, H, NULL), CJ_OK);
    /* exact pixel positions: x over 6 decades, y over 6 decades */
    double ax = 12 + 1.0 / 6 * (W - 24), ay = 12 + 1.0 / 6 * (H - 24);
    double bx = 12 + 5.0 / 6 * (W - 24), by = 12 + 5.0 / 6 * (H - 24);
    int checked = 0;
    for (int k = 1; k < 20; ++k) {
        const double t = k / 20.0, px = ax + t * (bx - ax), py = ay + t * (by - ay);
        assert_true(is_color(near_px(fb, px, py), GREEN));
        /* 5 px away perpendicular to the line: background or grid (never green) */
        const double L = hypot(bx - ax, by - ay), nx = -(by - ay) / L, ny = (bx - ax) / L;
        const cj_rgba q = near_px(fb, px + 5 * nx, py + 5 * ny);
        assert_false(q.g > 120 && q.r < 100 && q.b < 100);
        checked += 2;
    }
    const double my = 12 + 5.0 / 6 * (H - 24);
    for (int i = 0; i < 3; ++i) {
        const double mx = 12 + (i * 2 + 1) / 6.0 * (W - 24), r = 8.0;
        assert_true(is_color(near_px(fb, mx, my), BLUE));
        const cj_rgba corner = near_px(fb, mx + 0.75 * r, my + 0.75 * r);
        const cj_rgba apex = near_px(fb, mx, my + 0.5 * r), base = near_px(fb, mx, my - 0.8 * r);
        if (mk[i] == CJ_MARKER_SQUARE) assert_true(is_color(corner, BLUE));
        if (mk[i] == CJ_MARKER_DIAMOND) assert_false(is_color(corner, BLUE));
        if (mk[i] == CJ_MARKER_TRIANGLE) {
            assert_true(is_color(apex, BLUE));  /* apex at +r: 2.3 px wide at +r/2 */
            assert_false(is_color(base, BLUE)); /* base at -r/2 */
        }
        checked += 3;
    }
    printf("log-log line (width 3) and square/triangle/diamond markers against their exact "
           "shapes (%d pixel checks)\n",
           checked);
    cj_framebuffer_destroy(fb);
    cj_chart_destroy(c);
}

static int dark_in(const cj_framebuffer *fb, int x0, int y0, int x1, int y1, cj_rgba col) {
    int n = 0;
    for (int y = y0; y <= y1; ++y)
        for (int x = x0; x <= x1; ++x)
            if (is_color(px_at(fb, x, y), col)) n++;
    return n;
}

static void test_legend_notes_titles(void **state) {
    (void)state;
    cj_font *font = NULL;
    if (cj_font_open(NULL, &font) != CJ_OK) {
        printf("no default font: legend/title checks skipped\n");
        skip();
    }
    const cj_rgba ink = {0x20, 0x20, 0x20, 255};
    for (int with = 0; with < 2; ++with) {
        cj_chart *c = NULL;
        assert_int_equal(cj_chart_create(NULL, &c), CJ_OK);
        assert_int_equal(cj_chart_set_axis(c, 0, CJ_CHART_LINEAR, with ? "cost (ns)" : NULL),
                         CJ_OK);
        assert_int_equal(cj_chart_set_axis(c, 1, CJ_CHART_LOG10, with ? "error" : NULL), CJ_OK);
        const double x[2] = {0, 10}, y[2] = {1e-3, 1e-1};
        cj_chart_series_opts o1 = {with ? "first method" : NULL, RED, 2.0, CJ_MARKER_CIRCLE, 4.0};
        cj_chart_series_opts o2 = {with ? "second" : NULL, BLUE, 0.0, CJ_MARKER_SQUARE, 4.0};
        assert_int_equal(cj_chart_add_series(c, x, y, 2, &o1), CJ_OK);
        assert_int_equal(cj_chart_add_series(c, x, y + 1, 1, &o2), CJ_OK);
        if (with) assert_int_equal(cj_chart_annotate(c, 4, 1e-2, "dominated", GREEN), CJ_OK);
        cj_framebuffer *fb = NULL;
        assert_int_equal(cj_framebuffer_create(W, H, 0, NULL, &fb), CJ_OK);
        assert_int_equal(cj_chart_render(c, fb, 0, 0, W, H, font), CJ_OK);
        /* plot area with text: left 74, bottom 48, right W-16, top H-30 */
        const double R = W - 16, T = H - 30;
        /* x title: baseline y = 8, centred: ink in rows 5..18 near the centre; y title above */
        const int xt = dark_in(fb, 150, 5, 300, 18, ink),
                  yt = dark_in(fb, 4, (int)T + 6, 70, H - 3, ink);
        if (!with) {
            assert_int_equal(xt, 0);
            assert_int_equal(yt, 0);
        } else {
            assert_true(xt > 10 && yt > 10);
            double w1 = 0, w2 = 0;
            assert_int_equal(cj_font_measure(font, 12, "first method", &w1, NULL, NULL), CJ_OK);
            assert_int_equal(cj_font_measure(font, 12, "second", &w2, NULL, NULL), CJ_OK);
            const double bw = fmax(w1, w2) + 44, bh = 2 * 16.0 + 8;
            const double bxl = R - 6 - bw, btop = T - 6;
            /* entry 0: red marker at (bxl+18, btop-12) and line sample; entry 1: blue square */
            assert_true(is_color(near_px(fb, bxl + 18, btop - 12), RED));
            assert_true(is_color(near_px(fb, bxl + 8, btop - 12), RED));
            assert_true(is_color(near_px(fb, bxl + 18, btop - 28), BLUE));
            assert_false(is_color(near_px(fb, bxl + 8, btop - 28), BLUE)); /* scatter: no line */
            /* label ink right of the samples, inside the box */
            assert_true(dark_in(fb, (int)bxl + 36, (int)(btop - 16), (int)(bxl + bw), (int)btop - 4,
                                ink) > 5);
            /* legend box frame (grey) passes through its corners */
            int frame_r = 255;
            for (int dx = -1; dx <= 1; ++dx)
                frame_r = fmin(frame_r, near_px(fb, bxl + dx, btop - bh / 2).r);
            assert_true(frame_r < 215); /* grey 160 at >= half coverage */
            /* annotation: ring of radius 6 around the mapped point, text up-right of it */
            double ax, ay;
            assert_int_equal(cj_chart_map(c, W, H, 1, 4, 1e-2, &ax, &ay), CJ_OK);
            assert_true(fabs(ax - (74 + 0.4 * (R - 74))) < 1e-9);
            assert_true(fabs(ay - (48 + 0.5 * (T - 48))) < 1e-9);
            int ring = 0;
            for (int k = 0; k < 8; ++k) {
                /* a 1 px anti-aliased ring: its pixel is clearly green, the centre is not */
                const cj_rgba q =
                    near_px(fb, ax + 6 * cos(k * 0.785398), ay + 6 * sin(k * 0.785398));
                ring += q.g > q.r + 50 && q.g > q.b + 50;
            }
            assert_true(ring >= 7);
            const cj_rgba in = near_px(fb, ax + 2.5, ay + 0.5); /* on the red line: not green */
            assert_false(in.g > in.r + 50);
            assert_true(dark_in(fb, (int)ax + 8, (int)ay + 5, (int)ax + 80, (int)ay + 18, GREEN) >
                        10);
        }
        cj_framebuffer_destroy(fb);
        cj_chart_destroy(c);
    }
    printf("axis titles present only when set; legend entries (line+marker, marker only) and "
           "label at the documented place; annotation ring and text around the mapped point\n");
    cj_font_close(font);
}

static void test_legend_outside(void **state) {
    (void)state;
    cj_font *font = NULL;
    if (cj_font_open(NULL, &font) != CJ_OK) skip();
    cj_chart *c = NULL;
    assert_int_equal(cj_chart_create(NULL, &c), CJ_OK);
    assert_int_equal(cj_chart_set_legend(c, CJ_LEGEND_OUTSIDE), CJ_OK);
    const double x[2] = {0, 10}, y[2] = {0, 10};
    cj_chart_series_opts o = {"only", RED, 0.0, CJ_MARKER_CIRCLE, 4.0};
    assert_int_equal(cj_chart_add_series(c, x, y, 2, &o), CJ_OK);
    const cj_chart_rect r = cj_chart_layout(c, W, H, 1);
    assert_true(r.right == W - 16 - CJ_CHART_LEGEND_WIDTH && r.top == H - 30);
    cj_framebuffer *fb = NULL;
    assert_int_equal(cj_framebuffer_create(W, H, 0, NULL, &fb), CJ_OK);
    assert_int_equal(cj_chart_render(c, fb, 0, 0, W, H, font), CJ_OK);
    /* the series' last point sits on the plot area's upper right corner; the legend marker
     * 12 + 18 px right of it and 12 px down; nothing red between them */
    assert_true(is_color(near_px(fb, r.right - 1.5, r.top - 1.5), RED));
    assert_true(is_color(near_px(fb, r.right + 30, r.top - 12), RED));
    assert_false(is_color(near_px(fb, r.right + 8, r.top - 12), RED));
    printf("outside legend: plot area narrowed by %g px, entry right of it\n",
           CJ_CHART_LEGEND_WIDTH);
    cj_framebuffer_destroy(fb);
    cj_chart_destroy(c);
    cj_font_close(font);
}

static void test_bad_input(void **state) {
    (void)state;
    cj_chart *c = NULL;
    assert_int_equal(cj_chart_create(NULL, &c), CJ_OK);
    double lo[2], hi[2];
    assert_int_equal(cj_chart_ranges(c, lo, hi), CJ_ERR_EMPTY);
    const double x[2] = {1, NAN}, y[2] = {1, 2}, z[2] = {-1, 2};
    cj_chart_series_opts o = {"a", RED, 1.0, CJ_MARKER_NONE, 0};
    assert_int_equal(cj_chart_add_series(c, x, y, 0, &o), CJ_ERR_EMPTY);
    assert_int_equal(cj_chart_add_series(c, x, y, 2, &o), CJ_ERR_NONFINITE);
    o.line_width = 0;
    assert_int_equal(cj_chart_add_series(c, y, y, 2, &o), CJ_ERR_RANGE);
    o.marker = CJ_MARKER_COUNT_;
    o.marker_radius = 3;
    assert_int_equal(cj_chart_add_series(c, y, y, 2, &o), CJ_ERR_RANGE);
    o.marker = CJ_MARKER_CIRCLE;
    assert_int_equal(cj_chart_add_series(c, z, y, 2, &o), CJ_OK);
    assert_int_equal(cj_chart_set_axis(c, 0, CJ_CHART_LOG10, NULL), CJ_OK);
    cj_framebuffer *fb = NULL;
    assert_int_equal(cj_framebuffer_create(W, H, 0, NULL, &fb), CJ_OK);
    assert_int_equal(cj_chart_render(c, fb, 0, 0, W, H, NULL), CJ_ERR_RANGE); /* x = -1 on log */
    assert_int_equal(cj_chart_set_axis(c, 0, CJ_CHART_LINEAR, NULL), CJ_OK);
    assert_int_equal(cj_chart_render(c, fb, 0, 0, W, H, NULL), CJ_OK);
    assert_int_equal(cj_chart_render(c, fb, 300, 0, W, H, NULL), CJ_ERR_RANGE);
    assert_int_equal(cj_chart_render(c, fb, 0, 0, 100, 80, NULL), CJ_ERR_RANGE);
    assert_int_equal(cj_chart_set_range(c, 1, 2, 2), CJ_ERR_DEGENERATE);
    assert_int_equal(cj_chart_set_range(c, 1, 0, INFINITY), CJ_ERR_NONFINITE);
    assert_int_equal(cj_chart_set_axis(c, 2, CJ_CHART_LINEAR, NULL), CJ_ERR_ARGUMENT);
    assert_int_equal(cj_chart_set_legend(c, CJ_LEGEND_COUNT_), CJ_ERR_RANGE);
    assert_int_equal(cj_chart_annotate(c, 1, NAN, "x", RED), CJ_ERR_NONFINITE);
    assert_int_equal(cj_chart_annotate(c, 1, 1, "", RED), CJ_ERR_RANGE);
    char longt[CJ_CHART_MAX_TEXT + 2];
    memset(longt, 'a', sizeof longt - 1);
    longt[sizeof longt - 1] = 0;
    assert_int_equal(cj_chart_set_title(c, longt), CJ_ERR_RANGE);
    printf("bad input: empty, NaN, no line nor marker, unknown marker, <= 0 on a log axis, "
           "rectangle outside/too small, empty/NaN range, bad axis, long text\n");
    cj_framebuffer_destroy(fb);
    cj_chart_destroy(c);
}

/* Notes at one point: their texts take the upper right, lower right, upper left and lower left
 * places in turn (chart.h), and a fifth, with no free place, is its ring alone. */
static void test_notes_do_not_overlap(void **state) {
    (void)state;
    cj_font *font = NULL;
    if (cj_font_open(NULL, &font) != CJ_OK) {
        printf("no default font: note placement not checked\n");
        return;
    }
    static const cj_rgba COLS[5] = {{220, 20, 20, 255},
                                    {20, 160, 20, 255},
                                    {20, 40, 220, 255},
                                    {200, 20, 200, 255},
                                    {20, 170, 170, 255}};
    cj_chart *c = NULL;
    assert_int_equal(cj_chart_create(NULL, &c), CJ_OK);
    const double x[2] = {0, 10}, y[2] = {0, 10};
    const cj_chart_series_opts o = {NULL, {0, 0, 0, 255}, 0.0, CJ_MARKER_CIRCLE, 0.5};
    assert_int_equal(cj_chart_add_series(c, x, y, 2, &o), CJ_OK);
    for (int k = 0; k < 5; ++k) assert_int_equal(cj_chart_annotate(c, 5, 5, "MMM", COLS[k]), CJ_OK);
    cj_framebuffer *fb = NULL;
    assert_int_equal(cj_framebuffer_create(W, H, 0, NULL, &fb), CJ_OK);
    assert_int_equal(cj_chart_render(c, fb, 0, 0, W, H, font), CJ_OK);
    double ax, ay, adv = 0, asc = 0, desc = 0;
    assert_int_equal(cj_chart_map(c, W, H, 1, 5, 5, &ax, &ay), CJ_OK);
    assert_int_equal(cj_font_measure(font, 11.0, "MMM", &adv, &asc, &desc), CJ_OK);
    /* the documented boxes: [x0, x1] x [baseline - descent, baseline + ascent] */
    const double bx[4] = {ax + 8, ax + 8, ax - 8 - adv, ax - 8 - adv},
                 by[4] = {ay + 6, ay - 6 - asc, ay + 6, ay - 6 - asc};
    for (int k = 0; k < 4; ++k) {
        const int x0 = (int)floor(bx[k]), x1 = (int)ceil(bx[k] + adv),
                  y0 = (int)floor(by[k] - desc), y1 = (int)ceil(by[k] + asc);
        for (int j = 0; j < 5; ++j) {
            const int ink = dark_in(fb, x0, y0, x1, y1, COLS[j]);
            if (j == k && ink <= 10) fail_msg("note %d: no text in its place %d", k, k);
            if (j != k && ink > 0) fail_msg("note %d's colour in place %d", j, k);
        }
    }
    /* the fifth note: its colour only on its ring (within 7.5 px of the point) */
    int stray = 0;
    for (int py = 0; py < H; ++py)
        for (int px = 0; px < W; ++px)
            if (is_color(px_at(fb, px, py), COLS[4]) && hypot(px + 0.5 - ax, py + 0.5 - ay) > 7.5)
                stray++;
    assert_int_equal(stray, 0);
    printf("five notes at one point: four texts in the four documented places, none overlapping; "
           "the fifth is its ring alone\n");
    cj_framebuffer_destroy(fb);
    cj_chart_destroy(c);
    cj_font_close(font);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_log_axis_markers_and_ticks),
        cmocka_unit_test(test_line_and_marker_shapes),
        cmocka_unit_test(test_legend_notes_titles),
        cmocka_unit_test(test_legend_outside),
        cmocka_unit_test(test_notes_do_not_overlap),
        cmocka_unit_test(test_bad_input),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

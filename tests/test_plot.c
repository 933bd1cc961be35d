#define _POSIX_C_SOURCE 200809L /* setenv */
/* Plots (raster/plot.h) and text (raster/text.h): curve pixels against the exact curve, equal
 * aspect, clipping to the panel, hull fill and construction point, bad input, fonts. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "casteljau/plot.h"
#include "casteljau/text.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static cj_rgba px_at(const cj_framebuffer *fb, int x, int y) {
    return fb->pixels[(ptrdiff_t)y * fb->stride + x];
}

/* Cubic by the explicit Bernstein formula (independent of the library's de Casteljau). */
static void cubic_at(const double *b, double t, double *out) {
    const double s = 1 - t;
    const double w[4] = {s * s * s, 3 * s * s * t, 3 * s * t * t, t * t * t};
    out[0] = out[1] = 0;
    for (int i = 0; i < 4; ++i) {
        out[0] += w[i] * b[2 * i];
        out[1] += w[i] * b[2 * i + 1];
    }
}

/* A plot whose data-to-pixel map is the identity: view = the framebuffer, no margin, no axes. */
static cj_plot *identity_plot(int w, int h) {
    cj_plot *p = NULL;
    assert_int_equal(cj_plot_create(NULL, &p), CJ_OK);
    cj_plot_set_axes(p, 0);
    assert_int_equal(cj_plot_set_margin(p, 0), CJ_OK);
    assert_int_equal(cj_plot_set_view(p, 0, 0, w, h), CJ_OK);
    return p;
}

static void test_curve_pixels_follow_the_curve(void **state) {
    (void)state;
    const int W = 240, H = 160;
    const double b[8] = {10, 10, 60, 190, 170, -40, 230, 140};
    const double width = 2.0;
    cj_plot *p = identity_plot(W, H);
    cj_plot_bezier_opts o = cj_plot_bezier_defaults();
    o.color = cj_rgba_make(255, 0, 0, 255);
    o.width = width;
    o.control_polygon = 0;
    o.control_points = 0;
    cj_bezier c = cj_bezier_view(3, 2, b);
    assert_int_equal(cj_plot_add_bezier(p, &c, &o), CJ_OK);
    cj_framebuffer *fb = NULL;
    assert_int_equal(cj_framebuffer_create(W, H, 0, NULL, &fb), CJ_OK);
    assert_int_equal(cj_plot_render(p, fb, 0, 0, W, H, NULL), CJ_OK);

    enum { NS = 20001 };
    static double samp[NS][2];
    for (int i = 0; i < NS; ++i) cubic_at(b, (double)i / (NS - 1), samp[i]);
    /* (1) every tinted pixel is within width/2 + 1/2 (pixel footprint) + 0.25 (flattening)
     *     + sampling slack of the exact curve; */
    double worst = 0;
    long tinted = 0;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            cj_rgba q = px_at(fb, x, y);
            if (q.r - q.g <= 25) continue; /* white, or coverage below 10 % */
            ++tinted;
            double best = INFINITY;
            for (int i = 0; i < NS; ++i)
                best = fmin(best, hypot(samp[i][0] - (x + 0.5), samp[i][1] - (y + 0.5)));
            worst = fmax(worst, best);
        }
    assert_true(tinted > 200);
    assert_true(worst <= width / 2 + 0.5 + 0.25 + 0.05);
    /* (2) the pixel containing each curve point is strongly covered. */
    int weakest = 255;
    for (int i = 0; i < NS; i += 7) {
        int x = (int)floor(samp[i][0]), y = (int)floor(samp[i][1]);
        if (x < 0 || y < 0 || x >= W || y >= H) continue;
        cj_rgba q = px_at(fb, x, y);
        if (q.r - q.g < weakest) weakest = q.r - q.g;
    }
    assert_true(weakest > 100);
    printf("test_plot: %ld curve pixels, farthest %.3f px from the exact cubic (limit %.2f); "
           "every curve point's pixel covered (min red-green %d)\n",
           tinted, worst, width / 2 + 0.8, weakest);
    cj_framebuffer_destroy(fb);
    cj_plot_destroy(p);
}

/* A rational quadratic with weights 1, cos(45°), 1 is an exact quarter circle: its pixels must
 * lie within the stroke's reach of the circle |p - c| = r (an independent description). */
static void test_rational_quarter_circle(void **state) {
    (void)state;
    const int W = 200, H = 200;
    const double cx = 20, cy = 20, r = 160;
    const double b[6] = {cx + r, cy, cx + r, cy + r, cx, cy + r};
    const double w[3] = {1, sqrt(0.5), 1};
    cj_plot *p = identity_plot(W, H);
    cj_plot_bezier_opts o = cj_plot_bezier_defaults();
    o.color = cj_rgba_make(255, 0, 0, 255);
    o.width = 1.5;
    o.control_polygon = 0;
    o.control_points = 0;
    cj_rbezier c = cj_rbezier_view(2, 2, b, w);
    assert_int_equal(cj_plot_add_rbezier(p, &c, &o), CJ_OK);
    const double bad_w[3] = {1, 0, 1};
    cj_rbezier cb = cj_rbezier_view(2, 2, b, bad_w);
    assert_int_equal(cj_plot_add_rbezier(p, &cb, &o), CJ_ERR_ARGUMENT);
    cj_framebuffer *fb = NULL;
    assert_int_equal(cj_framebuffer_create(W, H, 0, NULL, &fb), CJ_OK);
    assert_int_equal(cj_plot_render(p, fb, 0, 0, W, H, NULL), CJ_OK);
    double worst = 0;
    long tinted = 0;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            cj_rgba q = px_at(fb, x, y);
            if (q.r - q.g <= 25) continue;
            ++tinted;
            const double px = x + 0.5, py = y + 0.5;
            /* distance to the quarter arc: radial where the angle is inside [0, 90°] */
            double d = (px >= cx && py >= cy)
                           ? fabs(hypot(px - cx, py - cy) - r)
                           : fmin(hypot(px - cx - r, py - cy), hypot(px - cx, py - cy - r));
            worst = fmax(worst, d);
        }
    /* pixels along the arc: ~ (pi/2) r long, at least one per unit length */
    assert_true(tinted > 250);
    assert_true(worst <= o.width / 2 + 0.5 + 0.25 + 1e-9);
    printf("test_plot: rational quarter circle r = %g: %ld pixels, farthest %.3f px from the "
           "circle (limit %.2f)\n",
           r, tinted, worst, o.width / 2 + 0.75);
    cj_framebuffer_destroy(fb);
    cj_plot_destroy(p);
}

static void test_rect_equal_aspect_and_clip(void **state) {
    (void)state;
    cj_plot *p = NULL;
    assert_int_equal(cj_plot_create(NULL, &p), CJ_OK);
    cj_implicit_shape shape;
    cj_implicit f;
    assert_int_equal(cj_implicit_circle(3, -2, 1.5, &shape, &f), CJ_OK);
    const double box[4] = {0, -5, 6, 1};
    const cj_rgba blue = cj_rgba_make(0, 0, 255, 255);
    assert_int_equal(cj_plot_add_implicit(p, &f, box, 0, blue, 2.0), CJ_OK);
    cj_framebuffer *fb = NULL;
    assert_int_equal(cj_framebuffer_create(400, 260, 0, NULL, &fb), CJ_OK);
    const cj_rgba magenta = cj_rgba_make(255, 0, 255, 255);
    cj_framebuffer_clear(fb, magenta);
    const int x0 = 30, y0 = 20, w = 330, h = 200;
    assert_int_equal(cj_plot_render(p, fb, x0, y0, w, h, NULL), CJ_OK);
    int lo[2] = {1 << 30, 1 << 30}, hi[2] = {-1, -1};
    for (int y = 0; y < fb->height; ++y)
        for (int x = 0; x < fb->width; ++x) {
            cj_rgba q = px_at(fb, x, y);
            int inside = x >= x0 && x < x0 + w && y >= y0 && y < y0 + h;
            if (!inside) {
                assert_memory_equal(&q, &magenta, sizeof q); /* nothing drawn outside */
                continue;
            }
            if (q.b > 200 && q.r < 90 && q.g < 90) { /* the circle's stroke */
                if (x < lo[0]) lo[0] = x;
                if (y < lo[1]) lo[1] = y;
                if (x > hi[0]) hi[0] = x;
                if (y > hi[1]) hi[1] = y;
            }
        }
    const int dx = hi[0] - lo[0], dy = hi[1] - lo[1];
    assert_true(dx > 50);
    assert_true(abs(dx - dy) <= 1);
    printf("test_plot: circle drawn %d x %d px in a %dx%d panel (equal aspect), nothing outside "
           "the panel touched\n",
           dx, dy, w, h);
    cj_framebuffer_destroy(fb);
    cj_plot_destroy(p);
}

/* Rows padded for cache reasons (CJ_FB_PADDED) must not change a single pixel: the panel is
 * drawn on its own canvas and composited into the target by the target's stride. */
static void test_padded_rows_render_identically(void **state) {
    (void)state;
    cj_plot *p = NULL;
    assert_int_equal(cj_plot_create(NULL, &p), CJ_OK);
    const double pts[] = {0, 0, 1, 2.4, 3.2, 2.6, 4, 0.2};
    cj_bezier c = cj_bezier_view(3, 2, pts);
    cj_plot_bezier_opts o = cj_plot_bezier_defaults();
    o.construction = 1;
    o.construction_t = 0.25;
    assert_int_equal(cj_plot_add_bezier(p, &c, &o), CJ_OK);
    assert_int_equal(cj_plot_set_title(p, "padded"), CJ_OK);
    cj_framebuffer *plain = NULL, *padded = NULL;
    assert_int_equal(cj_framebuffer_create(256, 160, 0, NULL, &plain), CJ_OK);
    assert_int_equal(cj_framebuffer_create(256, 160, CJ_FB_PADDED, NULL, &padded), CJ_OK);
    assert_true(padded->stride != padded->width); /* the case under test */
    const cj_rgba bg = cj_rgba_make(10, 20, 30, 255);
    cj_framebuffer_clear(plain, bg);
    cj_framebuffer_clear(padded, bg);
    assert_int_equal(cj_plot_render(p, plain, 8, 6, 240, 150, NULL), CJ_OK);
    assert_int_equal(cj_plot_render(p, padded, 8, 6, 240, 150, NULL), CJ_OK);
    long differing = 0, drawn = 0;
    for (int y = 0; y < 160; ++y)
        for (int x = 0; x < 256; ++x) {
            cj_rgba a = px_at(plain, x, y), b = px_at(padded, x, y);
            differing += memcmp(&a, &b, sizeof a) != 0;
            drawn += memcmp(&a, &bg, sizeof a) != 0;
        }
    assert_true(drawn > 1000);
    assert_int_equal(differing, 0);
    printf("test_plot: a plot renders identically into padded rows (stride %td for width 256), "
           "%ld pixels drawn\n",
           padded->stride, drawn);
    cj_framebuffer_destroy(plain);
    cj_framebuffer_destroy(padded);
    cj_plot_destroy(p);
}

static void test_hull_and_construction(void **state) {
    (void)state;
    const int W = 200, H = 200;
    const double b[8] = {20, 20, 40, 180, 180, 180, 180, 20};
    cj_plot *p = identity_plot(W, H);
    cj_plot_bezier_opts o = cj_plot_bezier_defaults();
    o.hull = 1;
    o.control_polygon = 0;
    o.construction = 1;
    o.construction_t = 0.25;
    cj_bezier c = cj_bezier_view(3, 2, b);
    assert_int_equal(cj_plot_add_bezier(p, &c, &o), CJ_OK);
    cj_framebuffer *fb = NULL;
    assert_int_equal(cj_framebuffer_create(W, H, 0, NULL, &fb), CJ_OK);
    assert_int_equal(cj_plot_render(p, fb, 0, 0, W, H, NULL), CJ_OK);
    /* Inside the hull, away from every stroke: tinted, not white. Outside: white. */
    cj_rgba in = px_at(fb, 150, 60), out = px_at(fb, 5, 195);
    assert_true(in.r < 245 && in.b > in.r);
    assert_true(out.r == 255 && out.g == 255 && out.b == 255);
    /* The construction's end point c(0.25) (explicit formula) carries the red marker. */
    double q[2];
    cubic_at(b, 0.25, q);
    cj_rgba m = px_at(fb, (int)floor(q[0]), (int)floor(q[1]));
    assert_true(m.r > 150 && m.g < 90 && m.b < 90);
    printf("test_plot: hull interior tinted (%d,%d,%d), outside white, c(0.25) marker red\n", in.r,
           in.g, in.b);
    cj_framebuffer_destroy(fb);
    cj_plot_destroy(p);
}

static void test_bad_input(void **state) {
    (void)state;
    cj_plot *p = NULL;
    assert_int_equal(cj_plot_create(NULL, &p), CJ_OK);
    cj_framebuffer *fb = NULL;
    assert_int_equal(cj_framebuffer_create(100, 100, 0, NULL, &fb), CJ_OK);
    assert_int_equal(cj_plot_render(p, fb, 0, 0, 100, 100, NULL), CJ_ERR_EMPTY);
    const double p3[6] = {0, 0, 0, 1, 1, 1};
    cj_bezier c3 = cj_bezier_view(1, 3, p3);
    assert_int_equal(cj_plot_add_bezier(p, &c3, NULL), CJ_ERR_DIMENSION);
    double bad[4] = {0, 0, NAN, 1};
    cj_bezier cn = cj_bezier_view(1, 2, bad);
    assert_int_equal(cj_plot_add_bezier(p, &cn, NULL), CJ_ERR_NONFINITE);
    const double ok[4] = {0, 0, 1, 1};
    cj_bezier c = cj_bezier_view(1, 2, ok);
    cj_plot_bezier_opts o = cj_plot_bezier_defaults();
    o.construction = 1;
    o.construction_t = 1.5;
    assert_int_equal(cj_plot_add_bezier(p, &c, &o), CJ_ERR_RANGE);
    o = cj_plot_bezier_defaults();
    o.nframes = CJ_PLOT_MAX_FRAMES + 1;
    assert_int_equal(cj_plot_add_bezier(p, &c, &o), CJ_ERR_RANGE);
    o = cj_plot_bezier_defaults();
    o.width = 0;
    assert_int_equal(cj_plot_add_bezier(p, &c, &o), CJ_ERR_RANGE);
    assert_int_equal(cj_plot_add_polyline(p, ok, 1, 0, o.color, 1, 0), CJ_ERR_EMPTY);
    assert_int_equal(cj_plot_add_points(p, bad, 2, o.color, 3), CJ_ERR_NONFINITE);
    const double twice[4] = {1, 1, 1, 1};
    assert_int_equal(cj_plot_add_spline(p, twice, 1, NULL, o.color, 2, 1), CJ_ERR_EMPTY);
    assert_int_equal(cj_plot_set_view(p, 1, 0, 1, 2), CJ_ERR_DEGENERATE);
    assert_int_equal(cj_plot_set_margin(p, -1), CJ_ERR_RANGE);
    assert_int_equal(cj_plot_item_count(p), 0); /* nothing was added by failing calls */
    /* All data at one point: shown in a view centred on it (a one-point item is valid). */
    assert_int_equal(cj_plot_add_points(p, twice, 2, o.color, 3), CJ_OK);
    cj_framebuffer_clear(fb, cj_rgba_make(255, 255, 255, 255));
    assert_int_equal(cj_plot_render(p, fb, 0, 0, 100, 100, NULL), CJ_OK);
    {
        const cj_rgba centre = fb->pixels[50 * fb->stride + 50];
        if (centre.r == 255 && centre.g == 255 && centre.b == 255)
            fail_msg("the single point is not drawn at the centre of its view");
    }
    assert_int_equal(cj_plot_add_bezier(p, &c, NULL), CJ_OK);
    assert_int_equal(cj_plot_render(p, fb, 0, 0, 11, 100, NULL), CJ_ERR_RANGE);  /* too small */
    assert_int_equal(cj_plot_render(p, fb, 0, 0, 12, 12, NULL), CJ_OK);          /* tiny: bare */
    assert_int_equal(cj_plot_render(p, fb, 50, 50, 60, 60, NULL), CJ_ERR_RANGE); /* sticks out */
    assert_int_equal(cj_plot_render(p, fb, 0, 0, 100, 100, NULL), CJ_OK);
    cj_framebuffer_destroy(fb);
    cj_plot_destroy(p);
    printf("test_plot: bad curves, options, rectangles refused with the documented statuses\n");
}

static void test_fonts(void **state) {
    (void)state;
    cj_font *font = NULL;
    assert_int_equal(cj_font_open(NULL, &font), CJ_OK);
    double a1 = 0, a2 = 0, asc = 0, desc = 0;
    assert_int_equal(cj_font_measure(font, 14, "1", &a1, &asc, &desc), CJ_OK);
    assert_int_equal(cj_font_measure(font, 14, "10", &a2, NULL, NULL), CJ_OK);
    assert_true(a1 > 3 && a2 > a1 + 3 && asc > 8 && desc > 1);
    assert_int_equal(cj_font_measure(font, 2, "1", &a1, NULL, NULL), CJ_ERR_RANGE);
    assert_int_equal(cj_font_measure(font, 14, "\xff", &a1, NULL, NULL), CJ_ERR_PARSE);
    cj_framebuffer *fb = NULL;
    assert_int_equal(cj_framebuffer_create(80, 40, 0, NULL, &fb), CJ_OK);
    cj_framebuffer_clear(fb, cj_rgba_make(255, 255, 255, 255));
    double adv = 0;
    assert_int_equal(cj_font_measure(font, 16, "Hg", &adv, &asc, &desc), CJ_OK);
    assert_int_equal(cj_font_draw(font, fb, 10, 15, 16, cj_rgba_make(0, 0, 0, 255), "Hg"), CJ_OK);
    long inked = 0;
    for (int y = 0; y < fb->height; ++y)
        for (int x = 0; x < fb->width; ++x)
            if (px_at(fb, x, y).r < 250) {
                ++inked;
                assert_true(x >= 10 && x <= 10 + adv + 1);
                assert_true(y >= 15 - desc - 1 && y <= 15 + asc + 1);
            }
    assert_true(inked > 30);
    assert_int_equal(cj_font_draw(font, fb, NAN, 1, 16, cj_rgba_make(0, 0, 0, 255), "x"),
                     CJ_ERR_NONFINITE);
    cj_font_close(font);
    cj_framebuffer_destroy(fb);

    assert_int_equal(cj_font_open("/nonexistent/font.ttf", &font), CJ_ERR_IO);
    assert_non_null(strstr(cj_last_error(), "/nonexistent/font.ttf"));
    setenv("CJ_FONT", "/nonexistent/env.ttf", 1);
    assert_int_equal(cj_font_open(NULL, &font), CJ_ERR_UNSUPPORTED);
    assert_non_null(strstr(cj_last_error(), "CJ_FONT"));
    unsetenv("CJ_FONT");
    printf("test_plot: font found, text inked (%ld px) inside its measured box, missing fonts "
           "reported\n",
           inked);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_curve_pixels_follow_the_curve),
        cmocka_unit_test(test_rational_quarter_circle),
        cmocka_unit_test(test_rect_equal_aspect_and_clip),
        cmocka_unit_test(test_hull_and_construction),
        cmocka_unit_test(test_bad_input),
        cmocka_unit_test(test_fonts),
        cmocka_unit_test(test_padded_rows_render_identically),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

/* Part of test_raster_lines (see test_raster_lines.c): anti-aliased lines, wide strokes
 * (coverage against exact areas and supersampling, clipping, errors, curves), exact-area fills,
 * and framebuffer strokes against the visit form's coverage. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "casteljau/framebuffer.h"
#include "casteljau/line.h"
#include "raster_lines_test.h"
#include "rng.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- anti-aliased and wide lines ------------------------------------------------------------ */

#define CW 160
#define CH 120
static float g_cov[CH][CW];
static void cov_collect(void *user, int x, int y, float c) {
    (void)user;
    assert_true(x >= 0 && x < CW && y >= 0 && y < CH);
    assert_true(c > 0.0f && c <= 1.0f + 1e-6f);
    g_cov[y][x] += c;
}
static double cov_total(void) {
    double t = 0;
    for (int y = 0; y < CH; ++y)
        for (int x = 0; x < CW; ++x) t += g_cov[y][x];
    return t;
}

void test_wu(void **state) {
    (void)state;
    cj_line_rect clip = {0, 0, CW - 1, CH - 1};
    cj_rng r;
    cj_rng_init(&r, g_seed + 4);
    static float a[CH][CW];
    for (int i = 0; i < 300; ++i) {
        double x0 = cj_rng_range(&r, 5, CW - 5), y0 = cj_rng_range(&r, 5, CH - 5);
        double x1 = cj_rng_range(&r, 5, CW - 5), y1 = cj_rng_range(&r, 5, CH - 5);
        memset(g_cov, 0, sizeof g_cov);
        assert_int_equal(cj_line_aa_visit(x0, y0, x1, y1, clip, cov_collect, NULL), CJ_OK);
        double major = fmax(fabs(x1 - x0), fabs(y1 - y0));
        if (fabs(cov_total() - major) > 1e-4 * (1 + major))
            fail_msg("Wu total %g vs major length %g (seed %llu case %d)", cov_total(), major,
                     (unsigned long long)g_seed, i);
        memcpy(a, g_cov, sizeof a);
        /* Mirror x -> CW - x maps pixel x to CW-1-x. */
        memset(g_cov, 0, sizeof g_cov);
        cj_line_aa_visit(CW - x0, y0, CW - x1, y1, clip, cov_collect, NULL);
        for (int y = 0; y < CH; ++y)
            for (int x = 0; x < CW; ++x)
                if (fabs(a[y][x] - g_cov[y][CW - 1 - x]) > 1e-4)
                    fail_msg("Wu mirror asymmetric at (%d,%d) (seed %llu case %d)", x, y,
                             (unsigned long long)g_seed, i);
    }
    printf("Wu: 300 random AA lines, total coverage == major length, mirror symmetric\n");
}

static double stroke_total(const cj_vec2 *p, size_t n, int closed, cj_line_stroke st) {
    cj_line_rect clip = {0, 0, CW - 1, CH - 1};
    size_t need = cj_line_stroke_work_size(clip);
    void *work = malloc(need);
    memset(g_cov, 0, sizeof g_cov);
    assert_int_equal(
        cj_line_stroke_polyline_visit(p, n, closed, &st, clip, work, need, cov_collect, NULL),
        CJ_OK);
    free(work);
    return cov_total();
}

void test_stroke_area(void **state) {
    (void)state;
    cj_rng r;
    cj_rng_init(&r, g_seed + 5);
    static float a[CH][CW];
    const double pi = 3.141592653589793;
    for (int i = 0; i < 200; ++i) {
        double w = i < 20 ? cj_rng_range(&r, 0.2, 1.0) : cj_rng_range(&r, 1.0, 16.0);
        double ang = cj_rng_range(&r, 0, 2 * pi), len = cj_rng_range(&r, 20, 80);
        cj_vec2 c = {CW / 2.0 + cj_rng_range(&r, -5, 5), CH / 2.0 + cj_rng_range(&r, -5, 5)};
        cj_vec2 p[2] = {{c.x - 0.5 * len * cos(ang), c.y - 0.5 * len * sin(ang)},
                        {c.x + 0.5 * len * cos(ang), c.y + 0.5 * len * sin(ang)}};
        cj_line_stroke st = cj_line_stroke_defaults(w);
        const cj_line_cap caps[3] = {CJ_CAP_BUTT, CJ_CAP_ROUND, CJ_CAP_SQUARE};
        st.cap = caps[i % 3];
        double expect = len * w + (st.cap == CJ_CAP_ROUND    ? pi * w * w / 4
                                   : st.cap == CJ_CAP_SQUARE ? w * w
                                                             : 0.0);
        double got = stroke_total(p, 2, 0, st);
        if (fabs(got - expect) > 1e-4 * expect + 1e-3)
            fail_msg("stroke w=%g len=%g cap %d: coverage %g, area %g (seed %llu case %d)", w, len,
                     (int)st.cap, got, expect, (unsigned long long)g_seed, i);
        memcpy(a, g_cov, sizeof a);
        cj_vec2 q[2] = {p[1], p[0]};
        stroke_total(q, 2, 0, st);
        for (int y = 0; y < CH; ++y)
            for (int x = 0; x < CW; ++x) assert_true(fabs(a[y][x] - g_cov[y][x]) < 1e-5);
        cj_vec2 m[2] = {{CW - p[0].x, p[0].y}, {CW - p[1].x, p[1].y}};
        stroke_total(m, 2, 0, st);
        for (int y = 0; y < CH; ++y)
            for (int x = 0; x < CW; ++x)
                if (fabs(a[y][x] - g_cov[y][CW - 1 - x]) > 1e-4)
                    fail_msg("stroke mirror asymmetric at (%d,%d) (seed %llu case %d)", x, y,
                             (unsigned long long)g_seed, i);
    }
    /* Joins of an L: union areas 4hL (miter), 4hL - h^2/2 (bevel), 4hL - h^2 + pi h^2/4. */
    double h = 6, L = 60;
    cj_vec2 l[3] = {{30, 30}, {30 + L, 30}, {30 + L, 30 + L}};
    const cj_line_join joins[3] = {CJ_JOIN_MITER, CJ_JOIN_BEVEL, CJ_JOIN_ROUND};
    const double areas[3] = {4 * h * L, 4 * h * L - h * h / 2, 4 * h * L - h * h + pi * h * h / 4};
    for (int j = 0; j < 3; ++j) {
        cj_line_stroke st = cj_line_stroke_defaults(2 * h);
        st.cap = CJ_CAP_BUTT;
        st.join = joins[j];
        double got = stroke_total(l, 3, 0, st);
        assert_true(fabs(got - areas[j]) < 1e-4 * areas[j]);
    }
    /* Closed square of side 40, miter joins: outer minus inner square. */
    cj_vec2 sq[4] = {{40, 40}, {80, 40}, {80, 80}, {40, 80}};
    cj_line_stroke st = cj_line_stroke_defaults(4);
    st.join = CJ_JOIN_MITER;
    double got = stroke_total(sq, 4, 1, st);
    assert_true(fabs(got - (44.0 * 44 - 36.0 * 36)) < 1e-4 * (44.0 * 44 - 36.0 * 36));
    /* Closed two-point polylines (with and without the repeated first point): a capsule. */
    cj_vec2 two[3] = {{40, 40}, {80, 40}, {40, 40}};
    st = cj_line_stroke_defaults(4);
    for (size_t n = 2; n <= 3; ++n) {
        got = stroke_total(two, n, 1, st);
        assert_true(fabs(got - (40 * 4 + pi * 4)) < 1e-4 * (40 * 4 + pi * 4));
    }
    /* A tiny closed triangle under a wide stroke: every rectangle covers the centre, which must
     * stay fully covered (coverage 1 at the pixel of the centroid). */
    cj_vec2 tri[3] = {{80, 60}, {83, 60}, {81.5, 62.5}};
    st = cj_line_stroke_defaults(12);
    stroke_total(tri, 3, 1, st);
    assert_true(fabs(g_cov[60][81] - 1.0f) < 1e-5);
    printf("strokes: 200 random widths 0.2..16 and caps, coverage == exact area (1e-4), reversal "
           "and mirror symmetric; miter/bevel/round L joins and a closed square == exact area "
           "(1e-4)\n");
}

/* Per-pixel coverage against an independent oracle: 32x32 point samples per pixel of the
 * exact shape (a capsule for round caps, a rectangle for butt caps). */
static int in_stroke(double px, double py, cj_vec2 a, cj_vec2 b, double h, int round) {
    double dx = b.x - a.x, dy = b.y - a.y, L2 = dx * dx + dy * dy;
    double t = ((px - a.x) * dx + (py - a.y) * dy) / L2;
    if (!round && (t < 0 || t > 1)) return 0;
    t = t < 0 ? 0 : (t > 1 ? 1 : t);
    double qx = a.x + t * dx - px, qy = a.y + t * dy - py;
    return qx * qx + qy * qy <= h * h;
}

void test_stroke_pixels_supersampled(void **state) {
    (void)state;
    cj_rng r;
    cj_rng_init(&r, g_seed + 6);
    double worst = 0, sum = 0;
    long count = 0;
    for (int i = 0; i < 16; ++i) {
        double w = cj_rng_range(&r, 0.3, 8), ang = cj_rng_range(&r, 0, 6.283185307179586);
        double len = cj_rng_range(&r, 5, 40);
        cj_vec2 a = {cj_rng_range(&r, 50, 110), cj_rng_range(&r, 40, 80)};
        cj_vec2 b = {a.x + len * cos(ang), a.y + len * sin(ang)};
        cj_vec2 p[2] = {a, b};
        cj_line_stroke st = cj_line_stroke_defaults(w);
        int round = i & 1;
        st.cap = round ? CJ_CAP_ROUND : CJ_CAP_BUTT;
        stroke_total(p, 2, 0, st);
        int x0 = (int)floor(fmin(a.x, b.x) - w - 1), x1 = (int)ceil(fmax(a.x, b.x) + w + 1);
        int y0 = (int)floor(fmin(a.y, b.y) - w - 1), y1 = (int)ceil(fmax(a.y, b.y) + w + 1);
        for (int y = y0; y <= y1; ++y)
            for (int x = x0; x <= x1; ++x) {
                int in = 0;
                for (int sy = 0; sy < 32; ++sy)
                    for (int sx = 0; sx < 32; ++sx)
                        in += in_stroke(x + (sx + 0.5) / 32, y + (sy + 0.5) / 32, a, b, 0.5 * w,
                                        round);
                double err = fabs(in / 1024.0 - g_cov[y][x]);
                if (err > worst) worst = err;
                sum += err;
                count++;
                if (err > 0.02)
                    fail_msg("stroke pixel (%d,%d): coverage %g, supersampled %g (seed %llu case "
                             "%d)",
                             x, y, g_cov[y][x], in / 1024.0, (unsigned long long)g_seed, i);
            }
    }
    assert_true(sum / count < 0.001);
    printf("strokes: %ld pixels of 16 random strokes vs 32x32 supersampling: max |diff| %.4f, "
           "mean %.5f\n",
           count, worst, sum / count);
}

void test_stroke_clip_and_errors(void **state) {
    (void)state;
    cj_vec2 p[2] = {{-1e9, -1e9}, {1e9, 1e9}};
    cj_line_stroke st = cj_line_stroke_defaults(3);
    double got = stroke_total(p, 2, 0, st);
    /* The band |y - x| <= 1.5 sqrt(2) inside the 160x120 window: 120 * 3 sqrt(2) minus the
     * triangle cut off at x < 0 (legs 1.5 sqrt(2): area 2.25). */
    double expect = 120 * 3 * sqrt(2.0) - 2.25;
    assert_true(fabs(got - expect) < 1e-4 * expect);
    cj_line_rect clip = {0, 0, CW - 1, CH - 1};
    size_t need = cj_line_stroke_work_size(clip);
    void *work = malloc(need);
    cj_vec2 bad[2] = {{0, 0}, {NAN, 1}};
    assert_int_equal(
        cj_line_stroke_polyline_visit(bad, 2, 0, &st, clip, work, need, cov_collect, NULL),
        CJ_ERR_NONFINITE);
    assert_int_equal(
        cj_line_stroke_polyline_visit(p, 0, 0, &st, clip, work, need, cov_collect, NULL),
        CJ_ERR_EMPTY);
    assert_int_equal(
        cj_line_stroke_polyline_visit(p, 2, 0, &st, clip, work, need - 1, cov_collect, NULL),
        CJ_ERR_BUFFER);
    st.width = 0;
    assert_int_equal(
        cj_line_stroke_polyline_visit(p, 2, 0, &st, clip, work, need, cov_collect, NULL),
        CJ_ERR_RANGE);
    st.width = NAN;
    assert_int_equal(
        cj_line_stroke_polyline_visit(p, 2, 0, &st, clip, work, need, cov_collect, NULL),
        CJ_ERR_NONFINITE);
    st = cj_line_stroke_defaults(2);
    st.miter_limit = 0.5;
    assert_int_equal(
        cj_line_stroke_polyline_visit(p, 2, 0, &st, clip, work, need, cov_collect, NULL),
        CJ_ERR_RANGE);
    free(work);

    /* A straight cubic (collinear, evenly spaced control points) strokes like its chord. */
    cj_framebuffer *f1, *f2;
    assert_int_equal(cj_framebuffer_create(CW, CH, 0, NULL, &f1), CJ_OK);
    assert_int_equal(cj_framebuffer_create(CW, CH, 0, NULL, &f2), CJ_OK);
    cj_framebuffer_clear(f1, cj_rgba_make(255, 255, 255, 255));
    cj_framebuffer_clear(f2, cj_rgba_make(255, 255, 255, 255));
    const double cub[8] = {10, 10, 50, 40, 90, 70, 130, 100};
    cj_bezier c = cj_bezier_view(3, 2, cub);
    st = cj_line_stroke_defaults(5);
    double bound = -1;
    cj_rgba ink = cj_rgba_make(0, 0, 200, 200);
    assert_int_equal(cj_line_stroke_bezier(f1, &c, 0.25, &st, ink, &bound), CJ_OK);
    assert_true(bound >= 0 && bound <= 0.25);
    cj_vec2 chord[2] = {{10, 10}, {130, 100}};
    assert_int_equal(cj_line_stroke_polyline(f2, chord, 2, 0, &st, ink), CJ_OK);
    int maxdiff = 0;
    for (int i = 0; i < CW * CH; ++i) {
        int d = abs(f1->pixels[i].r - f2->pixels[i].r) + abs(f1->pixels[i].b - f2->pixels[i].b);
        if (d > maxdiff) maxdiff = d;
    }
    assert_true(maxdiff <= 2);
    const double c3[6] = {0, 0, 0, 1, 1, 1};
    cj_bezier c3d = cj_bezier_view(1, 3, c3);
    assert_int_equal(cj_line_stroke_bezier(f1, &c3d, 0.25, &st, ink, NULL), CJ_ERR_DIMENSION);
    cj_framebuffer_destroy(f1);
    cj_framebuffer_destroy(f2);
    printf("strokes: (-1e9,-1e9)-(1e9,1e9) width 3 clipped to the window, bad input refused, a "
           "straight cubic strokes like its chord (max channel diff %d)\n",
           maxdiff);
}

/* Curves through flattening: a rational quarter circle (exact conic) of radius 40 stroked with
 * width 4 and butt caps covers the quarter annulus, area 2 pi R (within 0.5%: the polyline is
 * within 0.25 px of the arc); a two-piece sequence covers like one curve. */
static double ink_total(const cj_framebuffer *fb) {
    double t = 0;
    for (int y = 0; y < fb->height; ++y)
        for (int x = 0; x < fb->width; ++x) t += fb->pixels[y * fb->stride + x].r / 255.0;
    return t;
}

void test_stroke_curves(void **state) {
    (void)state;
    cj_framebuffer *fb;
    assert_int_equal(cj_framebuffer_create(CW, CH, CJ_FB_PADDED, NULL, &fb), CJ_OK);
    cj_framebuffer_clear(fb, cj_rgba_make(0, 0, 0, 255));
    const double R = 40, cx = 60, cy = 30;
    const double pts[6] = {cx + R, cy, cx + R, cy + R, cx, cy + R};
    const double wts[3] = {1, sqrt(0.5), 1};
    cj_rbezier arc = {2, 2, pts, wts};
    cj_line_stroke st = cj_line_stroke_defaults(4);
    st.cap = CJ_CAP_BUTT;
    double bound = -1;
    cj_rgba white = cj_rgba_make(255, 255, 255, 255);
    assert_int_equal(cj_line_stroke_rbezier(fb, &arc, 0.25, &st, white, &bound), CJ_OK);
    double area = ink_total(fb), expect = 2 * 3.141592653589793 * R;
    assert_true(bound > 0 && bound <= 0.25);
    assert_true(fabs(area - expect) < 0.005 * expect);
    /* Sequence: the two halves of a straight cubic stroke like the whole. */
    cj_framebuffer_clear(fb, cj_rgba_make(0, 0, 0, 255));
    const double h1[8] = {10, 10, 20, 20, 30, 30, 40, 40}, h2[8] = {40, 40, 50, 50, 60, 60, 70, 70};
    cj_flatten_piece seq[2] = {{cj_bezier_view(3, 2, h1), NULL}, {cj_bezier_view(3, 2, h2), NULL}};
    assert_int_equal(cj_line_stroke_sequence(fb, seq, 2, 0.25, &st, white, NULL), CJ_OK);
    double seq_area = ink_total(fb), line_area = 60 * sqrt(2.0) * 4;
    assert_true(fabs(seq_area - line_area) < 0.005 * line_area);
    assert_int_equal(cj_line_stroke_rbezier(fb, &arc, 0.0, &st, white, NULL), CJ_ERR_RANGE);
    assert_int_equal(cj_line_stroke_rbezier(fb, &arc, NAN, &st, white, NULL), CJ_ERR_NONFINITE);
    cj_framebuffer_destroy(fb);
    printf("curves: rational quarter circle R=40 w=4 covers %.2f px^2 (2 pi R = %.2f, bound %.3f); "
           "2-piece sequence %.2f vs %.2f; bad tolerances refused\n",
           area, expect, bound, seq_area, line_area);
}

/* Fills: exact area of a convex polygon (20-gon: the fan is split into pieces) and of a disc. */
void test_fills(void **state) {
    (void)state;
    cj_framebuffer *fb;
    assert_int_equal(cj_framebuffer_create(CW, CH, 0, NULL, &fb), CJ_OK);
    cj_rgba white = cj_rgba_make(255, 255, 255, 255);
    cj_framebuffer_clear(fb, cj_rgba_make(0, 0, 0, 255));
    cj_vec2 poly[20];
    double area = 0;
    for (int i = 0; i < 20; ++i) {
        double a = 2 * 3.141592653589793 * i / 20;
        poly[i] = cj_v2(70.3 + 30 * cos(a), 55.7 + 30 * sin(a));
    }
    for (int i = 0; i < 20; ++i) area += cj_v2_cross(poly[i], poly[(i + 1) % 20]) / 2;
    assert_int_equal(cj_line_fill_convex(fb, poly, 20, white), CJ_OK);
    double got = ink_total(fb);
    assert_true(fabs(got - area) < 1e-3 * area);
    cj_framebuffer_clear(fb, cj_rgba_make(0, 0, 0, 255));
    assert_int_equal(cj_line_fill_disc(fb, cj_v2(40.25, 50.6), 17.5, white), CJ_OK);
    double disc = ink_total(fb), exact = 3.141592653589793 * 17.5 * 17.5;
    assert_true(fabs(disc - exact) < 1e-3 * exact);
    cj_vec2 concave[4] = {{0, 0}, {10, 0}, {2, 2}, {0, 10}};
    assert_int_equal(cj_line_fill_convex(fb, concave, 4, white), CJ_ERR_ARGUMENT);
    assert_int_equal(cj_line_fill_convex(fb, concave, 2, white), CJ_ERR_EMPTY);
    assert_int_equal(cj_line_fill_disc(fb, cj_v2(1, 1), 0, white), CJ_ERR_RANGE);
    cj_framebuffer_destroy(fb);
    printf("fills: convex 20-gon %.3f vs shoelace %.3f, disc %.3f vs pi r^2 %.3f; concave "
           "refused\n",
           got, area, disc, exact);
}

/* Strokes into a framebuffer (single steep segments take a narrow sheared coverage plane) blend
 * exactly the coverage the visit form reports (full plane): the same cells get the same sums. */
void test_stroke_fb_matches_visit(void **state) {
    (void)state;
    cj_rng r;
    cj_rng_init(&r, g_seed + 13);
    cj_framebuffer *fb;
    assert_int_equal(cj_framebuffer_create(CW, CH, 0, NULL, &fb), CJ_OK);
    long compared = 0;
    for (int i = 0; i < 300; ++i) {
        const double w = cj_rng_range(&r, 0.3, 20), ang = cj_rng_range(&r, 0, 6.283185307179586);
        const double len = cj_rng_range(&r, 0.5, 100);
        const cj_vec2 a = {cj_rng_range(&r, -10, CW + 10), cj_rng_range(&r, -10, CH + 10)};
        cj_vec2 p[2] = {a, {a.x + len * cos(ang), a.y + len * sin(ang)}};
        cj_line_stroke st = cj_line_stroke_defaults(w);
        st.cap = (cj_line_cap)(i % 3);
        const cj_rgba bg = cj_rgba_make(10, 20, 30, 255);
        const cj_rgba ink = cj_rgba_make(200, 150, 100, (uint8_t)(1 + i % 255));
        cj_framebuffer_clear(fb, bg);
        assert_int_equal(cj_line_stroke_polyline(fb, p, 2, 0, &st, ink), CJ_OK);
        stroke_total(p, 2, 0, st);
        for (int y = 0; y < CH; ++y)
            for (int x = 0; x < CW; ++x) {
                cj_rgba expect = bg;
                const float cov = g_cov[y][x];
                if (cov > 1e-6f) {
                    cj_rgba sc = ink;
                    sc.a = cov >= 1.0f ? ink.a : (uint8_t)((float)ink.a * cov + 0.5f);
                    if (sc.a != 0) expect = cj_rgba_over(sc, bg);
                }
                const cj_rgba got = fb->pixels[(ptrdiff_t)y * fb->stride + x];
                if (memcmp(&got, &expect, sizeof got) != 0)
                    fail_msg("stroke w=%g cap %d (%g,%g)-(%g,%g): pixel (%d,%d) %d,%d,%d,%d vs "
                             "visit coverage %g -> %d,%d,%d,%d (seed %llu case %d)",
                             w, (int)st.cap, p[0].x, p[0].y, p[1].x, p[1].y, x, y, got.r, got.g,
                             got.b, got.a, cov, expect.r, expect.g, expect.b, expect.a,
                             (unsigned long long)g_seed, i);
                ++compared;
            }
    }
    cj_framebuffer_destroy(fb);
    printf("strokes: 300 random single segments (steep and shallow, in and out of the window, "
           "widths 0.3..20, all caps) drawn into a framebuffer == the visit form's coverage "
           "blended (%ld pixels, exact)\n",
           compared);
}

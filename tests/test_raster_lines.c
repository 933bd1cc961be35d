/* raster/: the framebuffer (origin, blending) and lines (exact Bresenham against a GMP rational
 * midpoint reference, clipping, Wu anti-aliasing, wide strokes). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "casteljau/framebuffer.h"
#include "casteljau/line.h"
#include "raster_lines_test.h"
#include "rng.h"

#include <gmp.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

uint64_t g_seed; /* also read by raster_strokes.c */

/* ---- the reference: exact rational midpoint rule -------------------------------------------
 * Major axis u (x when |dx| >= |dy|). For each u between the ends the minor coordinate is
 * round-half-up of the exact v0 + (u - u0) dv/du, i.e. floor((2 v0 du + 2 (u-u0) dv + du)/(2 du))
 * with du made positive by negating numerator and denominator; computed in GMP integers. */
static long long ref_minor(long long u0, long long v0, long long u1, long long v1, long long u) {
    mpz_t num, den, t;
    mpz_inits(num, den, t, NULL);
    mpz_set_si(den, u1 - u0);
    mpz_set_si(num, v0);
    mpz_mul(num, num, den);
    mpz_mul_si(num, num, 2);
    mpz_set_si(t, u - u0);
    mpz_mul_si(t, t, v1 - v0);
    mpz_mul_si(t, t, 2);
    mpz_add(num, num, t);
    mpz_add(num, num, den);
    mpz_mul_si(den, den, 2);
    if (mpz_sgn(den) < 0) {
        mpz_neg(den, den);
        mpz_neg(num, num);
    }
    mpz_fdiv_q(t, num, den);
    long long r = mpz_get_si(t);
    mpz_clears(num, den, t, NULL);
    return r;
}

typedef struct pix {
    int x, y;
} pix;

typedef struct pixset {
    pix *p;
    size_t n, cap;
} pixset;

static void ps_add(pixset *s, int x, int y) {
    if (s->n == s->cap) {
        s->cap = s->cap ? 2 * s->cap : 256;
        s->p = realloc(s->p, s->cap * sizeof *s->p);
        assert_non_null(s->p);
    }
    s->p[s->n].x = x;
    s->p[s->n].y = y;
    s->n++;
}

static void collect(void *user, int x, int y) {
    ps_add(user, x, y);
}

static int pix_cmp(const void *a, const void *b) {
    const pix *p = a, *q = b;
    if (p->y != q->y) return p->y < q->y ? -1 : 1;
    if (p->x != q->x) return p->x < q->x ? -1 : 1;
    return 0;
}

static void ps_sort(pixset *s) {
    if (s->n > 1) qsort(s->p, s->n, sizeof *s->p, pix_cmp);
}

/* Reference pixels of the line restricted to clip (iterates the major axis over the window). */
static void reference(long long x0, long long y0, long long x1, long long y1, cj_line_rect clip,
                      pixset *out) {
    long long adx = llabs(x1 - x0), ady = llabs(y1 - y0);
    if (adx == 0 && ady == 0) {
        if (x0 >= clip.x0 && x0 <= clip.x1 && y0 >= clip.y0 && y0 <= clip.y1)
            ps_add(out, (int)x0, (int)y0);
        return;
    }
    int xmajor = adx >= ady;
    long long u0 = xmajor ? x0 : y0, u1 = xmajor ? x1 : y1;
    long long v0 = xmajor ? y0 : x0, v1 = xmajor ? y1 : x1;
    long long ulo = u0 < u1 ? u0 : u1, uhi = u0 < u1 ? u1 : u0;
    long long clo = xmajor ? clip.x0 : clip.y0, chi = xmajor ? clip.x1 : clip.y1;
    long long vlo = xmajor ? clip.y0 : clip.x0, vhi = xmajor ? clip.y1 : clip.x1;
    if (clo > ulo) ulo = clo;
    if (chi < uhi) uhi = chi;
    for (long long u = ulo; u <= uhi; ++u) {
        long long v = ref_minor(u0, v0, u1, v1, u);
        if (v < vlo || v > vhi) continue;
        if (xmajor)
            ps_add(out, (int)u, (int)v);
        else
            ps_add(out, (int)v, (int)u);
    }
}

static const cj_line_rect big = {-1000000, -1000000, 1000000, 1000000};

static void check_line(long long x0, long long y0, long long x1, long long y1, cj_line_rect clip,
                       const char *what) {
    pixset got = {0}, rev = {0}, ref = {0};
    long long visited = -1, visited_rev = -1;
    assert_int_equal(cj_line_visit(x0, y0, x1, y1, clip, collect, &got, &visited), CJ_OK);
    assert_int_equal(cj_line_visit(x1, y1, x0, y0, clip, collect, &rev, &visited_rev), CJ_OK);
    reference(x0, y0, x1, y1, clip, &ref);
    int ok = visited == (long long)got.n && visited_rev == (long long)rev.n;
    /* Steps: consecutive visited pixels differ by exactly one along the major axis. */
    long long adx = llabs(x1 - x0), ady = llabs(y1 - y0);
    for (size_t i = 1; ok && i < got.n; ++i) {
        int ddx = abs(got.p[i].x - got.p[i - 1].x), ddy = abs(got.p[i].y - got.p[i - 1].y);
        ok = adx >= ady ? (ddx == 1 && ddy <= 1) : (ddy == 1 && ddx <= 1);
    }
    ps_sort(&got);
    ps_sort(&rev);
    ps_sort(&ref);
    ok = ok && got.n == ref.n && rev.n == ref.n &&
         (got.n == 0 || memcmp(got.p, ref.p, got.n * sizeof *got.p) == 0) &&
         (rev.n == 0 || memcmp(rev.p, ref.p, rev.n * sizeof *rev.p) == 0);
    if (!ok)
        fail_msg("%s: line (%lld,%lld)-(%lld,%lld) clip [%d,%d]x[%d,%d]: got %zu pixels, reversed "
                 "%zu, reference %zu (seed %llu)",
                 what, x0, y0, x1, y1, clip.x0, clip.x1, clip.y0, clip.y1, got.n, rev.n, ref.n,
                 (unsigned long long)g_seed);
    free(got.p);
    free(rev.p);
    free(ref.p);
}

/* Every line between two points of a 9x9 grid (all octants, all tie patterns), unclipped:
 * reference pixels, order independence, count max(|dx|,|dy|)+1, one step per major pixel. */
static void test_exhaustive_small(void **state) {
    (void)state;
    size_t lines = 0;
    for (int a = 0; a < 81; ++a)
        for (int b = 0; b < 81; ++b) {
            long long x0 = a % 9 - 4, y0 = a / 9 - 4, x1 = b % 9 - 4, y1 = b / 9 - 4;
            check_line(x0, y0, x1, y1, big, "grid");
            long long n;
            cj_line_visit(x0, y0, x1, y1, big, NULL, NULL, &n);
            long long adx = llabs(x1 - x0), ady = llabs(y1 - y0);
            assert_int_equal(n, (adx > ady ? adx : ady) + 1);
            ++lines;
        }
    /* The tie rule, by hand: (0,0)-(2,1) passes y = 1/2 at x = 1, rounded up to (1,1). */
    pixset s = {0};
    cj_line_visit(0, 0, 2, 1, big, collect, &s, NULL);
    assert_int_equal(s.n, 3);
    assert_true(s.p[1].x == 1 && s.p[1].y == 1);
    free(s.p);
    printf("lines: %zu grid lines match the GMP midpoint reference (round half up), both "
           "orders, count max(|dx|,|dy|)+1\n",
           lines);
}

/* Seeded random lines, long ones, in all octants; clipped to random rectangles. */
static void test_random_and_clipped(void **state) {
    (void)state;
    cj_rng r;
    cj_rng_init(&r, g_seed);
    int octants[8] = {0};
    for (int i = 0; i < 3000; ++i) {
        long long x0 = cj_rng_int(&r, -300, 300), y0 = cj_rng_int(&r, -300, 300);
        long long x1 = cj_rng_int(&r, -300, 300), y1 = cj_rng_int(&r, -300, 300);
        int oct = (x1 > x0) | (y1 > y0) << 1 | (llabs(x1 - x0) > llabs(y1 - y0)) << 2;
        octants[oct]++;
        check_line(x0, y0, x1, y1, big, "random");
        cj_line_rect clip = {cj_rng_int(&r, -200, 0), cj_rng_int(&r, -200, 0),
                             cj_rng_int(&r, 0, 200), cj_rng_int(&r, 0, 200)};
        check_line(x0, y0, x1, y1, clip, "random clipped");
    }
    for (int k = 0; k < 8; ++k) assert_true(octants[k] > 100);
    printf("lines: 3000 random lines in all 8 octants, unclipped and clipped, match reference\n");
}

/* Huge coordinates: the clipped pixels are the reference's pixels inside the window, and the
 * work (callback invocations) is only the visible pixels. */
static void test_huge_clipping(void **state) {
    (void)state;
    cj_line_rect clip = {0, 0, 99, 99};
    long long n = -1;
    assert_int_equal(cj_line_visit_d(-1e9, -1e9, 1e9, 1e9, clip, NULL, NULL, &n), CJ_OK);
    assert_int_equal(n, 100);
    pixset s = {0};
    assert_int_equal(
        cj_line_visit(-1000000000, -1000000000, 1000000000, 1000000000, clip, collect, &s, &n),
        CJ_OK);
    assert_int_equal(s.n, 100);
    for (size_t i = 0; i < s.n; ++i) assert_true(s.p[i].x == s.p[i].y);
    free(s.p);
    cj_rng r;
    cj_rng_init(&r, g_seed + 1);
    const long long M[3] = {1000000000LL, 1LL << 40, 1LL << 52};
    for (int i = 0; i < 600; ++i) {
        long long m = M[i % 3];
        /* Lines through the window: pick a visible point and a direction, extend both ways. */
        long long px = cj_rng_int(&r, -50, 150), py = cj_rng_int(&r, -50, 150);
        double ang = cj_rng_range(&r, 0, 6.283185307179586);
        long long x0 = px + (long long)(cos(ang) * (double)m * 0.9);
        long long y0 = py + (long long)(sin(ang) * (double)m * 0.9);
        long long x1 = px - (long long)(cos(ang) * (double)m * 0.7);
        long long y1 = py - (long long)(sin(ang) * (double)m * 0.7);
        check_line(x0, y0, x1, y1, clip, "huge clipped");
    }
    printf("clipping: (-1e9,-1e9)-(1e9,1e9) costs exactly its 100 visible pixels; 600 lines with "
           "ends up to 2^52 equal the reference restricted to the window\n");
}

/* Counts anti-aliased visits (the callback is required, so refusal is checked by a count). */
static void cov_count(void *user, int x, int y, float c) {
    (void)x, (void)y, (void)c;
    ++*(int *)user;
}

static void test_nonfinite_refused(void **state) {
    (void)state;
    int aa_visits = 0;
    cj_line_rect clip = {0, 0, 9, 9};
    pixset s = {0};
    const double bad[3] = {NAN, INFINITY, -INFINITY};
    for (int k = 0; k < 3; ++k)
        for (int c = 0; c < 4; ++c) {
            double v[4] = {1, 2, 3, 4};
            v[c] = bad[k];
            assert_int_equal(cj_line_visit_d(v[0], v[1], v[2], v[3], clip, collect, &s, NULL),
                             CJ_ERR_NONFINITE);
            assert_int_equal(cj_line_aa_visit(v[0], v[1], v[2], v[3], clip, cov_count, &aa_visits),
                             CJ_ERR_NONFINITE);
        }
    assert_int_equal(s.n, 0);
    assert_int_equal(aa_visits, 0);
    assert_int_equal(cj_line_visit_d(1e300, 0, 0, 0, clip, collect, &s, NULL), CJ_ERR_RANGE);
    assert_int_equal(cj_line_visit(0, 0, (1LL << 52) + 1, 0, clip, collect, &s, NULL),
                     CJ_ERR_RANGE);
    assert_int_equal(s.n, 0);
    /* Double end points map to the pixel containing them. */
    assert_int_equal(cj_line_visit_d(-0.5, 0.25, 4.99, 2.75, big, collect, &s, NULL), CJ_OK);
    pixset ref = {0};
    reference(-1, 0, 4, 2, big, &ref);
    ps_sort(&s);
    ps_sort(&ref);
    assert_int_equal(s.n, ref.n);
    assert_memory_equal(s.p, ref.p, s.n * sizeof *s.p);
    free(s.p);
    free(ref.p);
    printf("lines: NaN/Inf end points refused (CJ_ERR_NONFINITE), beyond 2^52 CJ_ERR_RANGE, "
           "nothing visited\n");
}

/* ---- framebuffer -------------------------------------------------------------------------- */

static long g_allocs;
static void *count_alloc(void *user, size_t n) {
    (void)user;
    g_allocs++;
    return malloc(n);
}
static void count_free(void *user, void *p) {
    (void)user;
    if (p) g_allocs--;
    free(p);
}

static void test_framebuffer_basics(void **state) {
    (void)state;
    cj_framebuffer *fb = NULL;
    assert_int_equal(cj_framebuffer_create(0, 10, 0, NULL, &fb), CJ_ERR_RANGE);
    assert_int_equal(cj_framebuffer_create(10, CJ_FRAMEBUFFER_MAX_SIDE + 1, 0, NULL, &fb),
                     CJ_ERR_RANGE);
    assert_int_equal(cj_framebuffer_create(10, 10, 0x80, NULL, &fb), CJ_ERR_ARGUMENT);
    assert_null(fb);
    cj_allocator al = {count_alloc, count_free, NULL};
    assert_int_equal(cj_framebuffer_create(7, 5, CJ_FB_DEPTH, &al, &fb), CJ_OK);
    assert_true(fb->width == 7 && fb->height == 5 && fb->depth != NULL);
    for (int i = 0; i < 35; ++i) assert_true(fb->depth[i] == 1.0f && fb->pixels[i].a == 0);
    cj_rgba red = cj_rgba_make(255, 0, 0, 255), blue = cj_rgba_make(0, 0, 255, 255), got;
    /* Origin lower-left: (0,0) is the first pixel in memory and the LAST row of a file. */
    assert_int_equal(cj_framebuffer_setpixel(fb, 0, 0, red), 1);
    assert_int_equal(cj_framebuffer_setpixel(fb, 6, 4, blue), 1);
    assert_true(fb->pixels[0].r == 255);
    assert_true(cj_framebuffer_row_top(fb, 4)[0].r == 255);
    assert_true(cj_framebuffer_row_top(fb, 0)[6].b == 255);
    assert_int_equal(cj_framebuffer_setpixel(fb, 7, 0, red), 0);
    assert_int_equal(cj_framebuffer_setpixel(fb, -1, 0, red), 0);
    assert_int_equal(cj_framebuffer_getpixel(fb, 0, 5, &got), CJ_ERR_RANGE);
    assert_int_equal(cj_framebuffer_getpixel(fb, 6, 4, &got), CJ_OK);
    assert_true(got.b == 255 && got.r == 0);
    /* A line drawn into the framebuffer covers exactly the visited pixels, opaque or blended,
     * including clipped lines (pointer-stepping loop vs callback loop). */
    cj_framebuffer_destroy(fb);
    fb = NULL;
    cj_rng r;
    cj_rng_init(&r, g_seed + 2);
    for (int i = 0; i < 400; ++i) {
        /* Half the cases in a framebuffer with padded rows (stride > width). */
        if (i == 0 || i == 200) {
            cj_framebuffer_destroy(fb);
            assert_int_equal(cj_framebuffer_create(64, 48, i ? CJ_FB_PADDED : 0u, &al, &fb), CJ_OK);
            assert_true(i ? fb->stride > 64 && fb->stride % 32 == 16 : fb->stride == 64);
        }
        cj_line_rect clip = cj_line_rect_of(fb);
        long long x0 = cj_rng_int(&r, -100, 160), y0 = cj_rng_int(&r, -100, 150);
        long long x1 = cj_rng_int(&r, -100, 160), y1 = cj_rng_int(&r, -100, 150);
        cj_rgba bg = cj_rgba_make(10, 20, 30, 255), c = cj_rgba_make(200, 100, 50, 255);
        if (i & 1) c.a = 128;
        cj_framebuffer_clear(fb, bg);
        assert_int_equal(cj_line_draw(fb, x0, y0, x1, y1, c), CJ_OK);
        pixset s = {0};
        cj_line_visit(x0, y0, x1, y1, clip, collect, &s, NULL);
        cj_rgba expect = cj_rgba_over(c, bg);
        size_t marked = 0;
        for (int y = 0; y < 48; ++y)
            for (int x = 0; x < 64; ++x) {
                cj_rgba p = fb->pixels[y * fb->stride + x];
                if (memcmp(&p, &bg, 4) != 0) {
                    assert_memory_equal(&p, &expect, 4);
                    marked++;
                }
            }
        assert_int_equal(marked, s.n);
        free(s.p);
        /* Stroke and Wu output lands in the right place whatever the stride. */
        if (i % 50 == 1) {
            cj_framebuffer_clear(fb, bg);
            cj_vec2 pts[2] = {{20.5, 10.0}, {20.5, 30.0}};
            cj_line_stroke st = cj_line_stroke_defaults(1);
            st.cap = CJ_CAP_BUTT;
            cj_line_stroke_polyline(fb, pts, 2, 0, &st, cj_rgba_make(255, 255, 255, 255));
            cj_line_draw_aa(fb, 40.5, 5.0, 40.5, 26.0, cj_rgba_make(255, 255, 255, 255));
            for (int y = 0; y < 48; ++y)
                for (int x = 0; x < 64; ++x) {
                    int on = (x == 20 && y >= 10 && y < 30) || (x == 40 && y >= 5 && y <= 25);
                    cj_rgba p = fb->pixels[y * fb->stride + x];
                    assert_int_equal(p.r, on ? 255 : 10);
                }
        }
    }
    cj_framebuffer_destroy(fb);
    assert_int_equal(g_allocs, 0);
    printf("framebuffer: size/flag checks, origin lower-left, file row order, out-of-range "
           "ignored, 400 fb lines == visited set (plain and padded rows), allocator balanced\n");
}

/* Blending against the exact rational definition: the result channel is the integer nearest
 * to (c_s a_s 255 + c_d a_d (255 - a_s)) / (a_s 255 + a_d (255 - a_s)), halves up. */
static void test_blend_exact(void **state) {
    (void)state;
    cj_rng r;
    cj_rng_init(&r, g_seed + 3);
    for (int i = 0; i < 200000; ++i) {
        cj_rgba s = cj_rgba_make((uint8_t)cj_rng_int(&r, 0, 255), (uint8_t)cj_rng_int(&r, 0, 255),
                                 (uint8_t)cj_rng_int(&r, 0, 255), (uint8_t)cj_rng_int(&r, 0, 255));
        cj_rgba d = cj_rgba_make((uint8_t)cj_rng_int(&r, 0, 255), (uint8_t)cj_rng_int(&r, 0, 255),
                                 (uint8_t)cj_rng_int(&r, 0, 255), (uint8_t)cj_rng_int(&r, 0, 255));
        if (i % 7 == 0) d.a = 255;
        cj_rgba o = cj_rgba_over(s, d);
        long A = (long)s.a * 255 + (long)d.a * (255 - s.a);
        if (s.a == 0) {
            assert_memory_equal(&o, &d, 4);
            continue;
        }
        /* alpha: nearest to A/255 */
        long ea = 2L * o.a * 255 - 2 * A;
        assert_true(labs(ea) <= 255 && (labs(ea) < 255 || ea > 0));
        const uint8_t sc[3] = {s.r, s.g, s.b}, dc[3] = {d.r, d.g, d.b}, oc[3] = {o.r, o.g, o.b};
        for (int k = 0; k < 3; ++k) {
            long num = (long)sc[k] * s.a * 255 + (long)dc[k] * d.a * (255 - s.a);
            long e = 2L * oc[k] * A - 2 * num; /* 2A (out - exact) */
            if (!(labs(e) <= A && (labs(e) < A || e > 0)))
                fail_msg("blend s=(%d,%d,%d,%d) d=(%d,%d,%d,%d) channel %d: %d (seed %llu)", s.r,
                         s.g, s.b, s.a, d.r, d.g, d.b, d.a, k, oc[k], (unsigned long long)g_seed);
        }
        if (s.a == 255) assert_memory_equal(&o, &s, 4);
    }
    printf("blend: 200000 random source-over pairs exactly rounded (halves up) vs the rational "
           "formula\n");
}

int main(void) {
    g_seed = cj_test_seed("test_raster_lines", 20261121);
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_exhaustive_small),
        cmocka_unit_test(test_random_and_clipped),
        cmocka_unit_test(test_huge_clipping),
        cmocka_unit_test(test_nonfinite_refused),
        cmocka_unit_test(test_framebuffer_basics),
        cmocka_unit_test(test_blend_exact),
        cmocka_unit_test(test_wu),
        cmocka_unit_test(test_stroke_area),
        cmocka_unit_test(test_stroke_pixels_supersampled),
        cmocka_unit_test(test_stroke_clip_and_errors),
        cmocka_unit_test(test_stroke_curves),
        cmocka_unit_test(test_stroke_fb_matches_visit),
        cmocka_unit_test(test_fills),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

/* bench_lines: line drawing speed of raster/, single core.
 *
 * For major-axis lengths 4..1000: exact Bresenham lines (opaque stores, blended, and through
 * the visit callback), Wu anti-aliased lines, and exact-area strokes of widths 1, 3 and 10.
 * Lines of each length come from a fixed pool of 4096 random lines in all 8 octants (mixed),
 * inside a 1024x1024 framebuffer (no clipping). Each figure is the median of 7 repeats.
 * "Mpx/s" counts pixels along the line: max(|dx|,|dy|)+1 per line (for every method, so the
 * columns compare cost per unit of length; AA and strokes touch more pixels than that).
 * Peer: when built with cairo (bench/areas/flatten.cmake), the same lines stroked by cairo 1.16
 * (ARGB32 image surface of the same size, same widths, butt caps, miter joins, default
 * antialiasing, opaque colour) in the same run, interleaved with ours repeat by repeat.
 * Usage: bench_lines [scale]   (scale multiplies the work per repeat, default 1). */
#define _POSIX_C_SOURCE 200809L /* clock_gettime */
#include "casteljau/framebuffer.h"
#include "casteljau/line.h"

#include <stdio.h>
#include <stdlib.h>
#ifdef CJ_HAVE_CAIRO
#include <cairo.h>
#endif
#include <string.h>
#include <time.h>
#include "bench_clock.h"

#define POOL    4096
#define SIDE    1024
#define REPEATS 7

typedef struct seg {
    long long x0, y0, x1, y1;
} seg;

static seg pool[POOL];
static volatile long long sink_count;

static unsigned long long rng_state = 0x9e3779b97f4a7c15ull;
static unsigned long long rnd(void) {
    rng_state ^= rng_state << 13;
    rng_state ^= rng_state >> 7;
    rng_state ^= rng_state << 17;
    return rng_state;
}
static long long rnd_in(long long lo, long long hi) {
    return lo + (long long)(rnd() % (unsigned long long)(hi - lo + 1));
}

/* Lines of major length L in all octants, mixed, inside the framebuffer. */
static void make_pool(int L) {
    for (int i = 0; i < POOL; ++i) {
        long long du = L, dv = rnd_in(0, L);
        if (rnd() & 1) du = -du;
        if (rnd() & 1) dv = -dv;
        long long dx = du, dy = dv;
        if (rnd() & 1) dx = dv, dy = du;
        long long x0 = dx >= 0 ? rnd_in(0, SIDE - 1 - dx) : rnd_in(-dx, SIDE - 1);
        long long y0 = dy >= 0 ? rnd_in(0, SIDE - 1 - dy) : rnd_in(-dy, SIDE - 1);
        pool[i].x0 = x0;
        pool[i].y0 = y0;
        pool[i].x1 = x0 + dx;
        pool[i].y1 = y0 + dy;
    }
}

static void count_pixel(void *user, int x, int y) {
    (void)x, (void)y;
    ++*(long long *)user;
}
static void count_cover(void *user, int x, int y, float c) {
    (void)x, (void)y, (void)c;
    ++*(long long *)user;
}

enum {
    M_BRES,
    M_BRES_PAD,
    M_BRES_BLEND,
    M_VISIT,
    M_WU,
    M_WU_PAD,
    M_STROKE1,
    M_STROKE3,
    M_STROKE10,
#ifdef CJ_HAVE_CAIRO
    M_CAIRO1,
    M_CAIRO3,
    M_CAIRO10,
#endif
    M_COUNT
};
static const char *const names[M_COUNT] = {
    "bresenham",    "bresenham padded", "bresenham a=128", "visit callback", "wu aa",
    "wu aa padded", "stroke w=1",       "stroke w=3",      "stroke w=10",
#ifdef CJ_HAVE_CAIRO
    "cairo w=1",    "cairo w=3",        "cairo w=10",
#endif
};

#ifdef CJ_HAVE_CAIRO
static cairo_t *g_cairo;
#endif

/* Draws lines [0, n) of the pool with method m; returns seconds. */
static double run(cj_framebuffer *fb, int m, long long n) {
    cj_rgba opaque = cj_rgba_make(20, 40, 200, 255), half = cj_rgba_make(200, 40, 20, 128);
    cj_line_rect clip = cj_line_rect_of(fb);
    cj_line_stroke st = cj_line_stroke_defaults(m == M_STROKE1 ? 1 : m == M_STROKE3 ? 3 : 10);
#ifdef CJ_HAVE_CAIRO
    if (m >= M_CAIRO1) {
        cairo_set_line_width(g_cairo, m == M_CAIRO1 ? 1 : m == M_CAIRO3 ? 3 : 10);
        double t0 = cj_bench_thread_cpu();
        for (long long i = 0; i < n; ++i) {
            const seg *s = &pool[i % POOL];
            cairo_move_to(g_cairo, (double)s->x0 + 0.5, (double)s->y0 + 0.5);
            cairo_line_to(g_cairo, (double)s->x1 + 0.5, (double)s->y1 + 0.5);
            cairo_stroke(g_cairo);
        }
        return cj_bench_thread_cpu() - t0;
    }
#endif
    st.join = CJ_JOIN_MITER;
    st.cap = CJ_CAP_BUTT;
    long long cnt = 0;
    double t0 = cj_bench_thread_cpu();
    for (long long i = 0; i < n; ++i) {
        const seg *s = &pool[i % POOL];
        switch (m) {
        case M_BRES:
        case M_BRES_PAD:
            cj_line_draw(fb, s->x0, s->y0, s->x1, s->y1, opaque);
            break;
        case M_BRES_BLEND:
            cj_line_draw(fb, s->x0, s->y0, s->x1, s->y1, half);
            break;
        case M_VISIT:
            cj_line_visit(s->x0, s->y0, s->x1, s->y1, clip, count_pixel, &cnt, NULL);
            break;
        case M_WU:
        case M_WU_PAD:
            cj_line_draw_aa(fb, (double)s->x0 + 0.3, (double)s->y0 + 0.6, (double)s->x1 + 0.7,
                            (double)s->y1 + 0.2, opaque);
            break;
        default: {
            cj_vec2 p[2] = {{(double)s->x0 + 0.5, (double)s->y0 + 0.5},
                            {(double)s->x1 + 0.5, (double)s->y1 + 0.5}};
            cj_line_stroke_polyline(fb, p, 2, 0, &st, opaque);
        }
        }
    }
    double t = cj_bench_thread_cpu() - t0;
    sink_count += cnt;
    return t;
}

int main(int argc, char **argv) {
    double scale = argc > 1 ? atof(argv[1]) : 1.0;
    if (!(scale > 0)) scale = 1.0;
    cj_framebuffer *fb, *fbp;
    if (cj_framebuffer_create(SIDE, SIDE, 0, NULL, &fb) != CJ_OK) return 1;
    if (cj_framebuffer_create(SIDE, SIDE, CJ_FB_PADDED, NULL, &fbp) != CJ_OK) return 1;
    cj_framebuffer_clear(fb, cj_rgba_make(255, 255, 255, 255));
    cj_framebuffer_clear(fbp, cj_rgba_make(255, 255, 255, 255));
#ifdef CJ_HAVE_CAIRO
    cairo_surface_t *csurf = cairo_image_surface_create(CAIRO_FORMAT_ARGB32, SIDE, SIDE);
    g_cairo = cairo_create(csurf);
    cairo_set_source_rgb(g_cairo, 1, 1, 1);
    cairo_paint(g_cairo);
    cairo_set_source_rgba(g_cairo, 200 / 255.0, 40 / 255.0, 20 / 255.0, 1.0);
    cairo_set_line_cap(g_cairo, CAIRO_LINE_CAP_BUTT);
    cairo_set_line_join(g_cairo, CAIRO_LINE_JOIN_MITER);
#endif
    /* Warm the stroke scratch (allocated on first use). */
    cj_vec2 w[2] = {{1, 1}, {2, 2}};
    cj_line_stroke ws = cj_line_stroke_defaults(1);
    cj_line_stroke_polyline(fb, w, 2, 0, &ws, cj_rgba_make(0, 0, 0, 255));

    const int lengths[] = {4, 16, 64, 256, 1000};
    printf("bench_lines: %dx%d RGBA8, pool of %d random lines per length (all octants mixed), "
           "median of %d repeats, single core\n",
           SIDE, SIDE, POOL, REPEATS);
    printf("Mpx/s = million pixels of line length (max(|dx|,|dy|)+1) per second of thread CPU "
           "time;\n\"padded\" = CJ_FB_PADDED rows (stride %td pixels instead of %d)\n\n",
           fbp->stride, SIDE);
    printf("%-16s", "method");
    for (size_t k = 0; k < sizeof lengths / sizeof lengths[0]; ++k)
        printf(" | L=%-4d Mpx/s  ns/line", lengths[k]);
    printf("\n");
    static double table[M_COUNT][5][2];
    for (size_t k = 0; k < sizeof lengths / sizeof lengths[0]; ++k) {
        int L = lengths[k];
        make_pool(L);
        long long nn[M_COUNT];
        static double times[M_COUNT][REPEATS];
        for (int m = 0; m < M_COUNT; ++m) {
            /* Work per repeat: ~20M length pixels for Bresenham, less for the costlier ones. */
            double budget = (m <= M_VISIT ? 1e7 : m <= M_WU_PAD ? 3e6 : 1e6) * scale;
            nn[m] = (long long)(budget / (L + 1));
            if (nn[m] < POOL) nn[m] = POOL;
        }
        /* Repeats interleaved over the methods, so that a busy machine slows them alike. */
        for (int r = 0; r < REPEATS; ++r)
            for (int m = 0; m < M_COUNT; ++m) {
                cj_framebuffer *target = m == M_BRES_PAD || m == M_WU_PAD ? fbp : fb;
                times[m][r] = run(target, m, nn[m]);
            }
        for (int m = 0; m < M_COUNT; ++m) {
            const long long n = nn[m];
            double t = cj_bench_median(times[m], REPEATS);
            table[m][k][0] = (double)n * (L + 1) / t * 1e-6;
            table[m][k][1] = t / (double)n * 1e9;
        }
    }
    for (int m = 0; m < M_COUNT; ++m) {
        printf("%-16s", names[m]);
        for (size_t k = 0; k < 5; ++k) printf(" | %12.1f %8.1f", table[m][k][0], table[m][k][1]);
        printf("\n");
    }

    /* Clipping: a line from (-1e9,-1e9) to (1e9,1e9) costs its 1024 visible pixels. */
    {
        long long n = 200000, visited = 0;
        double t0 = cj_bench_thread_cpu();
        for (long long i = 0; i < n; ++i)
            cj_line_draw(fb, -1000000000LL, -1000000000LL + (i & 7), 1000000000LL, 1000000000LL,
                         cj_rgba_make(0, 0, 0, 255));
        double t = cj_bench_thread_cpu() - t0;
        cj_line_visit(-1000000000LL, -1000000000LL, 1000000000LL, 1000000000LL, cj_line_rect_of(fb),
                      count_pixel, &visited, NULL);
        printf("\nclipped (-1e9,-1e9)-(1e9,1e9): %lld visible pixels, %.0f ns per line "
               "(%.1f Mpx/s of visible pixels)\n",
               visited, t / (double)n * 1e9, (double)n * (double)visited / t * 1e-6);
        long long c = 0;
        cj_vec2 p[2] = {{-1e9, -1e9}, {1e9, 1e9}};
        cj_line_stroke st = cj_line_stroke_defaults(3);
        n = 2000;
        t0 = cj_bench_thread_cpu();
        for (long long i = 0; i < n; ++i)
            cj_line_stroke_polyline(fb, p, 2, 0, &st, cj_rgba_make(0, 0, 0, 255));
        t = cj_bench_thread_cpu() - t0;
        (void)count_cover;
        printf("clipped stroke w=3 (-1e9,-1e9)-(1e9,1e9): %.1f us per stroke\n",
               t / (double)n * 1e6);
        sink_count += c;
    }
#ifdef CJ_HAVE_CAIRO
    printf("\nours / cairo speed (Mpx/s ratio, > 1 = ours faster):\n");
    for (int wi = 0; wi < 3; ++wi) {
        printf("%-16s", wi == 0 ? "w=1" : wi == 1 ? "w=3" : "w=10");
        for (size_t k = 0; k < 5; ++k)
            printf(" | %21.2fx", table[M_STROKE1 + wi][k][0] / table[M_CAIRO1 + wi][k][0]);
        printf("\n");
    }
    cairo_destroy(g_cairo);
    cairo_surface_destroy(csurf);
#endif
    cj_framebuffer_destroy(fb);
    cj_framebuffer_destroy(fbp);
    return 0;
}

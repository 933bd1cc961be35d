/* Drawing primitives of the plot canvas (see plot_internal.h). */
#include "plot_internal.h"

#include "casteljau/line.h"
#include "error_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

cj_status cj_plot_canvas_init(cj_plot_canvas *cv, int w, int h) {
    memset(cv, 0, sizeof *cv);
    cj_status st = cj_framebuffer_create(w, h, 0, NULL, &cv->fb);
    if (st) return st;
    cv->cover = calloc((size_t)w * (size_t)h, sizeof *cv->cover);
    if (!cv->cover) {
        cj_plot_canvas_free(cv);
        return cj_fail(CJ_ERR_NOMEM, "no memory for a %dx%d coverage plane", w, h);
    }
    return CJ_OK;
}

void cj_plot_canvas_free(cj_plot_canvas *cv) {
    cj_framebuffer_destroy(cv->fb);
    free(cv->cover);
    free(cv->poly);
    free(cv->vec);
    memset(cv, 0, sizeof *cv);
}

cj_status cj_plot_canvas_reserve(cj_plot_canvas *cv, size_t n) {
    if (n <= cv->poly_cap) return CJ_OK;
    size_t cap = n + n / 2 + 16;
    double *p = realloc(cv->poly, cap * 2 * sizeof *p);
    if (!p) return cj_fail(CJ_ERR_NOMEM, "no memory for a polyline of %zu points", n);
    cv->poly = p;
    cv->poly_cap = cap;
    return CJ_OK;
}

static int clampi(double v, int lo, int hi) {
    if (!(v > lo)) return lo;
    if (v > hi) return hi;
    return (int)v;
}

/* Strokes through the raster/ stroker (line.h): round joins and caps, exact-distance coverage
 * maximised over the pieces, blended once. */
cj_status cj_plot_stroke(cj_plot_canvas *cv, const double *xy, size_t n, int closed, cj_rgba c,
                         double width) {
    if (n == 0) return CJ_OK;
    if (n > cv->vec_cap) {
        size_t cap = n + n / 2 + 16;
        cj_vec2 *v = realloc(cv->vec, cap * sizeof *v);
        if (!v) return cj_fail(CJ_ERR_NOMEM, "no memory for a polyline of %zu points", n);
        cv->vec = v;
        cv->vec_cap = cap;
    }
    for (size_t i = 0; i < n; ++i) cv->vec[i] = cj_v2(xy[2 * i], xy[2 * i + 1]);
    cj_raster_stroke style = cj_raster_stroke_default(width);
    return cj_raster_stroke_polyline(cv->fb, cv->vec, n, closed, &style, c);
}

void cj_plot_disc(cj_plot_canvas *cv, double x, double y, double r, cj_rgba c) {
    if (!isfinite(x) || !isfinite(y)) return;
    const int w = cv->fb->width, h = cv->fb->height;
    int i0 = clampi(floor(x - r - 1), 0, w - 1), i1 = clampi(ceil(x + r + 1), 0, w - 1);
    int j0 = clampi(floor(y - r - 1), 0, h - 1), j1 = clampi(ceil(y + r + 1), 0, h - 1);
    if (x + r + 1 < 0 || x - r - 1 > w || y + r + 1 < 0 || y - r - 1 > h) return;
    for (int j = j0; j <= j1; ++j)
        for (int i = i0; i <= i1; ++i) {
            double d = hypot(i + 0.5 - x, j + 0.5 - y);
            double cov = r + 0.5 - d;
            if (cov > 0) cj_framebuffer_blend_coverage(cv->fb, i, j, c, (float)fmin(cov, 1.0));
        }
}

void cj_plot_fill_convex(cj_plot_canvas *cv, const double *xy, size_t n, cj_rgba c) {
    if (n < 3) return;
    double area = 0, lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
    for (size_t k = 0; k < n; ++k) {
        size_t l = (k + 1) % n;
        area += xy[2 * k] * xy[2 * l + 1] - xy[2 * l] * xy[2 * k + 1];
        for (int a = 0; a < 2; ++a) {
            lo[a] = fmin(lo[a], xy[2 * k + a]);
            hi[a] = fmax(hi[a], xy[2 * k + a]);
        }
    }
    if (!isfinite(area) || area == 0) return;
    const double sgn = area > 0 ? 1.0 : -1.0;
    const int w = cv->fb->width, h = cv->fb->height;
    int i0 = clampi(floor(lo[0]), 0, w - 1), i1 = clampi(ceil(hi[0]), 0, w - 1);
    int j0 = clampi(floor(lo[1]), 0, h - 1), j1 = clampi(ceil(hi[1]), 0, h - 1);
    for (int j = j0; j <= j1; ++j)
        for (int i = i0; i <= i1; ++i) {
            int inside = 0;
            for (int sy = 0; sy < 4; ++sy)
                for (int sx = 0; sx < 4; ++sx) {
                    const double px = i + (sx + 0.5) / 4, py = j + (sy + 0.5) / 4;
                    int in = 1;
                    for (size_t k = 0; k < n && in; ++k) {
                        size_t l = (k + 1) % n;
                        double cr = (xy[2 * l] - xy[2 * k]) * (py - xy[2 * k + 1]) -
                                    (xy[2 * l + 1] - xy[2 * k + 1]) * (px - xy[2 * k]);
                        if (sgn * cr < 0) in = 0;
                    }
                    inside += in;
                }
            if (inside) cj_framebuffer_blend_coverage(cv->fb, i, j, c, (float)inside / 16.0f);
        }
}

cj_status cj_plot_arrow(cj_plot_canvas *cv, double x0, double y0, double x1, double y1, cj_rgba c,
                        double width) {
    const double dx = x1 - x0, dy = y1 - y0, len = hypot(dx, dy);
    if (!(len > 0)) return CJ_OK;
    const double ux = dx / len, uy = dy / len;
    double head = fmin(3.0 * width + 7.0, 0.5 * len);
    const double half = 0.42 * head;
    double shaft[4] = {x0, y0, x1 - ux * head * 0.8, y1 - uy * head * 0.8};
    cj_status st = cj_plot_stroke(cv, shaft, 2, 0, c, width);
    if (st) return st;
    const double bx = x1 - ux * head, by = y1 - uy * head;
    double tri[6] = {x1, y1, bx - uy * half, by + ux * half, bx + uy * half, by - ux * half};
    cj_plot_fill_convex(cv, tri, 3, c);
    return CJ_OK;
}

void cj_plot_blank_outside(cj_plot_canvas *cv, double x0, double y0, double x1, double y1,
                           cj_rgba c) {
    const int w = cv->fb->width, h = cv->fb->height;
    const int i0 = (int)floor(x0), i1 = (int)ceil(x1), j0 = (int)floor(y0), j1 = (int)ceil(y1);
    for (int j = 0; j < h; ++j)
        for (int i = 0; i < w; ++i)
            if (i < i0 || i > i1 || j < j0 || j > j1)
                cv->fb->pixels[(ptrdiff_t)j * cv->fb->stride + i] = c;
}

/* Drawing primitives of the plot canvas (see plot_internal.h). */
#include "plot_internal.h"

#include "casteljau/line.h"
#include "error_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

cj_status cj_plot_canvas_init(cj_plot_canvas *cv, int w, int h) {
    memset(cv, 0, sizeof *cv);
    cv->w = w;
    cv->h = h;
    cj_status st = cj_framebuffer_create(w, h, 0, NULL, &cv->fb);
    if (st) return st;
    cv->cover = calloc((size_t)w * (size_t)h, sizeof *cv->cover);
    if (!cv->cover) {
        cj_plot_canvas_free(cv);
        return cj_fail(CJ_ERR_NOMEM, "no memory for a %dx%d coverage plane", w, h);
    }
    return CJ_OK;
}

void cj_plot_canvas_init_painter(cj_plot_canvas *cv, int w, int h, const cj_plot_painter *painter,
                                 double ox, double oy) {
    memset(cv, 0, sizeof *cv);
    cv->painter = painter;
    cv->ox = ox;
    cv->oy = oy;
    cv->w = w;
    cv->h = h;
}

/* Panel coordinates to the painter's, into cv->pxy (n points; xy is left as it is). */
static cj_status to_painter(cj_plot_canvas *cv, const double *xy, size_t n) {
    if (n > cv->pxy_cap) {
        size_t cap = n + n / 2 + 16;
        double *p = realloc(cv->pxy, cap * 2 * sizeof *p);
        if (!p) return cj_fail(CJ_ERR_NOMEM, "no memory for a polyline of %zu points", n);
        cv->pxy = p;
        cv->pxy_cap = cap;
    }
    for (size_t i = 0; i < n; ++i) {
        cv->pxy[2 * i] = xy[2 * i] + cv->ox;
        cv->pxy[2 * i + 1] = xy[2 * i + 1] + cv->oy;
    }
    return CJ_OK;
}

static void keep_first(cj_plot_canvas *cv, cj_status st) {
    if (st && !cv->paint_status) cv->paint_status = st;
}

void cj_plot_clear(cj_plot_canvas *cv, cj_rgba c) {
    if (cv->painter) {
        const double r[8] = {0, 0, cv->w, 0, cv->w, cv->h, 0, cv->h};
        cj_plot_fill_convex(cv, r, 4, c);
        return;
    }
    cj_framebuffer_clear(cv->fb, c);
}

cj_status cj_plot_text(cj_plot_canvas *cv, cj_font *font, double x, double y, double size,
                       cj_rgba c, const char *utf8) {
    if (!cv->painter) return cj_font_draw(font, cv->fb, x, y, size, c, utf8);
    double adv = 0;
    cj_status st = cj_font_measure(font, size, utf8, &adv, NULL, NULL);
    if (st) return st;
    return cv->painter->text(cv->painter->user, x + cv->ox, y + cv->oy, size, adv, c, utf8);
}

void cj_plot_canvas_free(cj_plot_canvas *cv) {
    cj_framebuffer_destroy(cv->fb);
    free(cv->cover);
    free(cv->poly);
    free(cv->vec);
    free(cv->pxy);
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
    if (cv->painter) {
        cj_status st = to_painter(cv, xy, n);
        return st ? st : cv->painter->stroke(cv->painter->user, cv->pxy, n, closed, c, width);
    }
    if (n > cv->vec_cap) {
        size_t cap = n + n / 2 + 16;
        cj_vec2 *v = realloc(cv->vec, cap * sizeof *v);
        if (!v) return cj_fail(CJ_ERR_NOMEM, "no memory for a polyline of %zu points", n);
        cv->vec = v;
        cv->vec_cap = cap;
    }
    for (size_t i = 0; i < n; ++i) cv->vec[i] = cj_v2(xy[2 * i], xy[2 * i + 1]);
    cj_line_stroke style = cj_line_stroke_defaults(width);
    return cj_line_stroke_polyline(cv->fb, cv->vec, n, closed, &style, c);
}

void cj_plot_disc(cj_plot_canvas *cv, double x, double y, double r, cj_rgba c) {
    if (!isfinite(x) || !isfinite(y)) return;
    if (cv->painter) {
        keep_first(cv, cv->painter->disc(cv->painter->user, x + cv->ox, y + cv->oy, r, c));
        return;
    }
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
    if (cv->painter) {
        cj_status st = to_painter(cv, xy, n);
        keep_first(cv, st ? st : cv->painter->fill(cv->painter->user, cv->pxy, n, c));
        return;
    }
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
    if (cv->painter) { /* four bands around the frame, rounded outwards as below */
        const double W = cv->w, H = cv->h, i0 = floor(x0), i1 = ceil(x1) + 1, j0 = floor(y0),
                     j1 = ceil(y1) + 1;
        const double bands[4][8] = {{0, 0, W, 0, W, j0, 0, j0},
                                    {0, j1, W, j1, W, H, 0, H},
                                    {0, j0, i0, j0, i0, j1, 0, j1},
                                    {i1, j0, W, j0, W, j1, i1, j1}};
        for (int k = 0; k < 4; ++k)
            if (bands[k][4] > bands[k][0] && bands[k][5] > bands[k][1])
                cj_plot_fill_convex(cv, bands[k], 4, c);
        return;
    }
    const int w = cv->fb->width, h = cv->fb->height;
    const int i0 = (int)floor(x0), i1 = (int)ceil(x1), j0 = (int)floor(y0), j1 = (int)ceil(y1);
    for (int j = 0; j < h; ++j)
        for (int i = 0; i < w; ++i)
            if (i < i0 || i > i1 || j < j0 || j > j1)
                cv->fb->pixels[(ptrdiff_t)j * cv->fb->stride + i] = c;
}

/* Drawing primitives of the plot canvas (see plot_internal.h). */
#include "plot_internal.h"

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

static void cover_segment(cj_plot_canvas *cv, double ax, double ay, double bx, double by, double hw,
                          int *bb) {
    const int w = cv->fb->width, h = cv->fb->height;
    const double ext = hw + 1.0;
    int i0 = clampi(floor(fmin(ax, bx) - ext), 0, w - 1);
    int i1 = clampi(ceil(fmax(ax, bx) + ext), 0, w - 1);
    int j0 = clampi(floor(fmin(ay, by) - ext), 0, h - 1);
    int j1 = clampi(ceil(fmax(ay, by) + ext), 0, h - 1);
    if (fmax(ax, bx) + ext < 0 || fmin(ax, bx) - ext > w || fmax(ay, by) + ext < 0 ||
        fmin(ay, by) - ext > h)
        return;
    const double dx = bx - ax, dy = by - ay;
    const double len2 = dx * dx + dy * dy;
    const double len = sqrt(len2);
    for (int j = j0; j <= j1; ++j) {
        const double py = j + 0.5;
        /* Only the x range where the distance to the segment's line can be < ext. */
        int a = i0, b = i1;
        if (len > 0 && fabs(dy) > 1e-12) {
            /* line: |(p - A) x D| / len < ext  ->  x range on this row */
            double xc = ax + (py - ay) * dx / dy;
            double half = ext * len / fabs(dy);
            double lo = fmax(fmin(xc - half, xc + half), fmin(ax, bx) - ext);
            double hi = fmin(fmax(xc - half, xc + half), fmax(ax, bx) + ext);
            a = clampi(floor(lo), i0, i1);
            b = clampi(ceil(hi), i0, i1);
        }
        float *row = cv->cover + (size_t)j * (size_t)w;
        for (int i = a; i <= b; ++i) {
            const double px = i + 0.5;
            double u = len2 > 0 ? ((px - ax) * dx + (py - ay) * dy) / len2 : 0.0;
            u = u < 0 ? 0 : u > 1 ? 1 : u;
            const double ex = px - (ax + u * dx), ey = py - (ay + u * dy);
            const double d = sqrt(ex * ex + ey * ey);
            double c = hw + 0.5 - d;
            if (c <= 0) continue;
            if (c > 1) c = 1;
            if ((float)c > row[i]) row[i] = (float)c;
        }
        if (a < bb[0]) bb[0] = a;
        if (b > bb[1]) bb[1] = b;
    }
    if (j0 < bb[2]) bb[2] = j0;
    if (j1 > bb[3]) bb[3] = j1;
}

cj_status cj_plot_stroke(cj_plot_canvas *cv, const double *xy, size_t n, int closed, cj_rgba c,
                         double width) {
    if (n == 0) return CJ_OK;
    for (size_t i = 0; i < 2 * n; ++i)
        if (!isfinite(xy[i]))
            return cj_fail(CJ_ERR_NONFINITE, "stroke point %zu is not finite", i / 2);
    if (width < 1.0) {
        c.a = (uint8_t)lround(c.a * fmax(width, 0.0));
        width = 1.0;
    }
    const double hw = width / 2;
    int bb[4] = {cv->fb->width, -1, cv->fb->height, -1};
    if (n == 1) cover_segment(cv, xy[0], xy[1], xy[0], xy[1], hw, bb);
    for (size_t i = 0; i + 1 < n; ++i)
        cover_segment(cv, xy[2 * i], xy[2 * i + 1], xy[2 * i + 2], xy[2 * i + 3], hw, bb);
    if (closed && n > 2) cover_segment(cv, xy[2 * n - 2], xy[2 * n - 1], xy[0], xy[1], hw, bb);
    for (int j = bb[2]; j <= bb[3]; ++j) {
        float *row = cv->cover + (size_t)j * (size_t)cv->fb->width;
        for (int i = bb[0]; i <= bb[1]; ++i)
            if (row[i] > 0.0f) {
                cj_framebuffer_blend_coverage(cv->fb, i, j, c, row[i]);
                row[i] = 0.0f;
            }
    }
    return CJ_OK;
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
            if (i < i0 || i > i1 || j < j0 || j > j1) cv->fb->pixels[(size_t)j * w + i] = c;
}

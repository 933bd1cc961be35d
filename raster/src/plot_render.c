/* Rendering a whole plot: the data box, the layout of the panel (margins, title, tick labels,
 * with a bare fallback for a small rectangle), the data-to-pixel map, grid, items, frame,
 * ticks and title, then the copy into the caller's framebuffer; or the same drawing handed to
 * a painter (casteljau/plot_paint.h) for vector output. */
#include "casteljau/plot.h"
#include "casteljau/plot_paint.h"

#include "error_internal.h"
#include "plot_items_internal.h"

#include <assert.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

static void grow_box(double *box, const double *pts, size_t n) {
    for (size_t i = 0; i < n; ++i) {
        if (pts[2 * i] < box[0]) box[0] = pts[2 * i];
        if (pts[2 * i + 1] < box[1]) box[1] = pts[2 * i + 1];
        if (pts[2 * i] > box[2]) box[2] = pts[2 * i];
        if (pts[2 * i + 1] > box[3]) box[3] = pts[2 * i + 1];
    }
}

/* ---- axes ----------------------------------------------------------------------------- */

/* A "nice" step (1, 2 or 5 times a power of ten) giving about `target` intervals on span. */
static double nice_step(double span, double target) {
    double raw = span / target;
    double p = pow(10.0, floor(log10(raw)));
    double m = raw / p;
    double nice = m < 1.5 ? 1.0 : m < 3.5 ? 2.0 : m < 7.5 ? 5.0 : 10.0;
    return nice * p;
}

/* Formats k*step as a short label with the decimals the step needs; U+2212 for minus. */
static void format_tick(double v, double step, char *buf, size_t size) {
    if (fabs(v) < step * 1e-6) v = 0.0;
    char tmp[64];
    double mag = fmax(fabs(v), step);
    if (mag >= 1e6 || step < 1e-4) {
        snprintf(tmp, sizeof tmp, "%.3g", v);
    } else {
        int dec = (int)ceil(-log10(step) - 1e-9);
        if (dec < 0) dec = 0;
        snprintf(tmp, sizeof tmp, "%.*f", dec, v);
    }
    if (tmp[0] == '-')
        snprintf(buf, size, "\xe2\x88\x92%s", tmp + 1);
    else
        snprintf(buf, size, "%s", tmp);
}

typedef struct ticks {
    double first, step;
    int count;
} ticks;

static ticks make_ticks(double lo, double hi, double target) {
    ticks t = {0.0, 0.0, 0};
    /* A span beyond the double range (or none) has no sensible ticks; the count is converted
     * to int only when it is a number in range (a NaN or huge count is undefined). */
    if (!(hi - lo > 0.0) || !isfinite(hi - lo)) return t;
    t.step = nice_step(hi - lo, target);
    if (!(t.step > 0.0) || !isfinite(t.step)) return t;
    t.first = ceil(lo / t.step - 1e-9) * t.step;
    const double count = floor((hi - t.first) / t.step + 1e-9) + 1.0;
    t.count = count >= 0.0 ? (count <= 100.0 ? (int)count : 100) : 0;
    return t;
}

static cj_status widest_label(cj_font *font, double size, ticks t, double *w) {
    *w = 0.0;
    for (int i = 0; i < t.count; ++i) {
        char buf[80];
        double adv = 0.0;
        format_tick(t.first + i * t.step, t.step, buf, sizeof buf);
        cj_status st = cj_font_measure(font, size, buf, &adv, NULL, NULL);
        if (st) return st;
        if (adv > *w) *w = adv;
    }
    return CJ_OK;
}

/* One tick: its mark seg (a segment) and, with a font, the label of v whose baseline starts at
 * x - align * (the label's advance), y (align 0.5 centres it on x, 1 ends it at x). */
static cj_status draw_tick(cj_plot_canvas *cv, cj_font *font, double size, cj_rgba ink,
                           const double seg[4], double v, double step, double x, double align,
                           double y) {
    cj_status st = cj_plot_stroke(cv, seg, 2, 0, ink, 1.0);
    if (st || !font) return st;
    char buf[80];
    double adv = 0;
    format_tick(v, step, buf, sizeof buf);
    st = cj_font_measure(font, size, buf, &adv, NULL, NULL);
    if (!st) st = cj_plot_text(cv, font, x - align * adv, y, size, ink, buf);
    return st;
}

/* ---- render --------------------------------------------------------------------------- */

/* The layout and the drawing, into fb (painter NULL) or through the painter (fb NULL). */
static cj_status plot_draw(const cj_plot *plot, cj_framebuffer *fb, int x0, int y0, int w, int h,
                           cj_font *font_in, const cj_plot_painter *painter) {
    assert(plot && (fb || painter));
    if (fb && (x0 < 0 || y0 < 0 || w < 12 || h < 12 || w > fb->width - x0 || h > fb->height - y0))
        return cj_fail(CJ_ERR_RANGE,
                       "plot rectangle %dx%d at (%d, %d) is not a rectangle of at least 12x12 "
                       "pixels inside the %dx%d framebuffer",
                       w, h, x0, y0, fb->width, fb->height);
    if (!fb && (x0 < 0 || y0 < 0 || w < 12 || h < 12))
        return cj_fail(CJ_ERR_RANGE,
                       "plot rectangle %dx%d at (%d, %d) is not a rectangle of at least 12x12 "
                       "pixels",
                       w, h, x0, y0);
    double box[4] = {INFINITY, INFINITY, -INFINITY, -INFINITY};
    if (plot->has_view) {
        memcpy(box, plot->view, sizeof box);
    } else {
        if (plot->count == 0) return cj_fail(CJ_ERR_EMPTY, "the plot has no items");
        for (size_t i = 0; i < plot->count; ++i) {
            const plot_item *it = &plot->items[i];
            grow_box(box, it->pts, it->npts);
            if (it->type == ITEM_SPLINE) grow_box(box, it->segs, 4 * it->nsegs);
        }
        double dx = box[2] - box[0], dy = box[3] - box[1];
        if (!(dx > 0.0) && !(dy > 0.0)) {
            /* A single point (a one-point item): a view centred on it. */
            const double half = fmax(1.0, 0.05 * fmax(fabs(box[0]), fabs(box[1])));
            box[0] -= half, box[1] -= half, box[2] += half, box[3] += half;
            dx = dy = 2.0 * half;
        }
        /* A flat box (all data on a horizontal or vertical line) gets the other side's span. */
        if (!(dx > 0.0)) box[0] -= dy / 2, box[2] += dy / 2;
        if (!(dy > 0.0)) box[1] -= dx / 2, box[3] += dx / 2;
    }

    const double unit = fmin(w, h);
    const double label_size = fmin(16.0, fmax(10.0, 0.028 * unit));
    double title_size = label_size * 1.25;
    const double tick_len = 5.0;
    /* Layout; a rectangle too small for the text falls back to a bare plot (no axes, no
     * text, 2 px margin) before giving up. */
    cj_font *font = font_in;
    int axes = plot->axes;
    double margin = plot->margin;
    double left, right, top, bottom, ax0, ay0, ax1, ay1, pad;
    double lab_asc = 0.0, lab_desc = 0.0;
    cj_status st = CJ_OK;
    for (int attempt = 0;; ++attempt) {
        left = right = top = bottom = margin;
        if (font && plot->title) {
            double a = 0, d = 0;
            double adv = 0;
            if ((st = cj_font_measure(font, title_size, plot->title, &adv, NULL, NULL))) return st;
            /* A title wider than the panel is set smaller (down to 8 px), then clipped. */
            const double room = w - 2 * margin;
            if (adv > room && room > 0) title_size = fmax(8.0, floor(title_size * room / adv));
            if ((st = cj_font_measure(font, title_size, plot->title, NULL, &a, &d))) return st;
            top += a + d + 4.0;
        }
        if (axes) {
            left += tick_len;
            bottom += tick_len;
            if (font) {
                double wl = 0;
                if ((st = cj_font_measure(font, label_size, "0", NULL, &lab_asc, &lab_desc)))
                    return st;
                ticks ty = make_ticks(box[1], box[3], 5.0);
                if ((st = widest_label(font, label_size, ty, &wl))) return st;
                left += wl + 4.0;
                bottom += lab_asc + lab_desc + 2.0;
                right += wl / 2; /* the last x label is centred on the right edge */
            }
        }
        /* Padding inside the frame so that strokes and markers are not cut by it. */
        double widest = 6.0;
        for (size_t i = 0; i < plot->count; ++i)
            if (plot->items[i].width > widest) widest = plot->items[i].width;
        pad = plot->has_view ? 0.0 : widest + 4.0;
        ax0 = left, ay0 = bottom, ax1 = w - right, ay1 = h - top;
        if (ax1 - ax0 >= 2 * pad + 8 && ay1 - ay0 >= 2 * pad + 8) break;
        if ((attempt == 1 || (!axes && !font && margin <= 2.0)) && ax1 - ax0 >= 8 &&
            ay1 - ay0 >= 8) {
            /* Tiny: a plot whose strokes may touch its edge rather than no plot at all. */
            pad = fmax(0.0, 0.5 * (fmin(ax1 - ax0, ay1 - ay0) - 8.0));
            break;
        }
        if (attempt == 1 || (!axes && !font && margin <= 2.0))
            return cj_fail(CJ_ERR_RANGE, "plot rectangle %dx%d is too small for its contents", w,
                           h);
        axes = 0;
        font = NULL;
        margin = fmin(margin, 2.0);
    }
    xform x;
    x.s =
        fmin((ax1 - ax0 - 2 * pad) / (box[2] - box[0]), (ay1 - ay0 - 2 * pad) / (box[3] - box[1]));
    x.cx = 0.5 * (box[0] + box[2]);
    x.cy = 0.5 * (box[1] + box[3]);
    x.ox = 0.5 * (ax0 + ax1);
    x.oy = 0.5 * (ay0 + ay1);
    if (!(x.s > 0.0) || !isfinite(x.s))
        return cj_fail(CJ_ERR_DEGENERATE, "plotted data span cannot be scaled to pixels");

    cj_plot_canvas cv;
    if (painter)
        cj_plot_canvas_init_painter(&cv, w, h, painter, x0, y0);
    else if ((st = cj_plot_canvas_init(&cv, w, h)))
        return st;
    cv.arrow_len = fmax(36.0, fmin(90.0, 0.16 * fmin(ax1 - ax0, ay1 - ay0)));
    cj_plot_clear(&cv, plot->background);

    const double vx0 = x.cx + (ax0 - x.ox) / x.s, vx1 = x.cx + (ax1 - x.ox) / x.s;
    const double vy0 = x.cy + (ay0 - x.oy) / x.s, vy1 = x.cy + (ay1 - x.oy) / x.s;
    ticks tx = make_ticks(vx0, vx1, fmax(2.0, (ax1 - ax0) / 75.0));
    ticks ty = make_ticks(vy0, vy1, fmax(2.0, (ay1 - ay0) / 70.0));
    const cj_rgba grid = cj_rgba_make(0xe6, 0xe6, 0xe6, 255);
    const cj_rgba ink = cj_rgba_make(0x40, 0x40, 0x40, 255);
    if (axes) {
        for (int i = 0; !st && i < tx.count; ++i) {
            double px = x.ox + x.s * (tx.first + i * tx.step - x.cx);
            double seg[4] = {px, ay0, px, ay1};
            st = cj_plot_stroke(&cv, seg, 2, 0, grid, 1.0);
        }
        for (int i = 0; !st && i < ty.count; ++i) {
            double py = x.oy + x.s * (ty.first + i * ty.step - x.cy);
            double seg[4] = {ax0, py, ax1, py};
            st = cj_plot_stroke(&cv, seg, 2, 0, grid, 1.0);
        }
    }
    for (size_t i = 0; !st && i < plot->count; ++i)
        st = cj_plot_draw_item(&cv, &x, &plot->items[i]);
    if (!st && axes) {
        /* Blank out anything outside the frame (arrows may reach out), then frame and ticks. */
        cj_plot_blank_outside(&cv, ax0, ay0, ax1, ay1, plot->background);
        double frame[8] = {ax0, ay0, ax1, ay0, ax1, ay1, ax0, ay1};
        st = cj_plot_stroke(&cv, frame, 4, 1, ink, 1.0);
        for (int i = 0; !st && i < tx.count; ++i) {
            const double v = tx.first + i * tx.step, px = x.ox + x.s * (v - x.cx);
            const double seg[4] = {px, ay0, px, ay0 - tick_len};
            st = draw_tick(&cv, font, label_size, ink, seg, v, tx.step, px, 0.5,
                           ay0 - tick_len - 2 - lab_asc);
        }
        for (int i = 0; !st && i < ty.count; ++i) {
            const double v = ty.first + i * ty.step, py = x.oy + x.s * (v - x.cy);
            const double seg[4] = {ax0, py, ax0 - tick_len, py};
            st = draw_tick(&cv, font, label_size, ink, seg, v, ty.step, ax0 - tick_len - 3, 1.0,
                           py - 0.35 * label_size);
        }
    }
    if (!st && font && plot->title) {
        double adv = 0, a = 0;
        st = cj_font_measure(font, title_size, plot->title, &adv, &a, NULL);
        if (!st)
            st = cj_plot_text(&cv, font, 0.5 * (ax0 + ax1) - adv / 2, h - margin - a, title_size,
                              cj_rgba_make(0x20, 0x20, 0x20, 255), plot->title);
    }
    if (!st) st = cv.paint_status;
    if (!st && fb) {
        for (int row = 0; row < h; ++row)
            memcpy(fb->pixels + (ptrdiff_t)(y0 + row) * fb->stride + x0,
                   cv.fb->pixels + (ptrdiff_t)row * cv.fb->stride, (size_t)w * sizeof(cj_rgba));
    }
    cj_plot_canvas_free(&cv);
    return st;
}

cj_status cj_plot_render(const cj_plot *plot, cj_framebuffer *fb, int x0, int y0, int w, int h,
                         cj_font *font) {
    assert(fb);
    return plot_draw(plot, fb, x0, y0, w, h, font, NULL);
}

cj_status cj_plot_paint(const cj_plot *plot, int x0, int y0, int w, int h, cj_font *font,
                        const cj_plot_painter *painter) {
    assert(painter && painter->stroke && painter->fill && painter->disc && painter->text);
    return plot_draw(plot, NULL, x0, y0, w, h, font, painter);
}

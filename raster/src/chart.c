/* Data charts with linear/log axes, series with markers, legend and notes (see chart.h). */
#include "casteljau/chart.h"

#include "error_internal.h"
#include "plot_internal.h"

#include <assert.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct series {
    double *xy; /* 2n values */
    size_t n;
    cj_chart_series_opts o;
    char label[CJ_CHART_MAX_TEXT + 1];
} series;

typedef struct note {
    double x, y;
    cj_rgba color;
    char text[CJ_CHART_MAX_TEXT + 1];
} note;

struct cj_chart {
    cj_allocator alloc;
    cj_chart_scale scale[2];
    int has_range[2];
    double lo[2], hi[2];
    char axis_title[2][CJ_CHART_MAX_TEXT + 1];
    char title[CJ_CHART_MAX_TEXT + 1];
    series s[CJ_CHART_MAX_SERIES];
    size_t ns;
    note notes[CJ_CHART_MAX_NOTES];
    size_t nn;
    cj_chart_legend legend;
};

static void *std_alloc(void *u, size_t b) {
    (void)u;
    return malloc(b);
}
static void std_free(void *u, void *p) {
    (void)u;
    free(p);
}

cj_status cj_chart_create(const cj_allocator *alloc, cj_chart **out) {
    assert(out);
    cj_allocator a = alloc ? *alloc : (cj_allocator){std_alloc, std_free, NULL};
    cj_chart *c = a.alloc(a.user, sizeof *c);
    if (!c) return cj_fail(CJ_ERR_NOMEM, "no memory for a chart");
    memset(c, 0, sizeof *c);
    c->alloc = a;
    *out = c;
    return CJ_OK;
}

void cj_chart_destroy(cj_chart *c) {
    if (!c) return;
    for (size_t i = 0; i < c->ns; ++i) c->alloc.free(c->alloc.user, c->s[i].xy);
    c->alloc.free(c->alloc.user, c);
}

static cj_status copy_text(char *dst, const char *src, const char *what) {
    if (!src) {
        dst[0] = 0;
        return CJ_OK;
    }
    size_t n = strlen(src);
    if (n > CJ_CHART_MAX_TEXT)
        return cj_fail(CJ_ERR_RANGE, "%s of %zu bytes is longer than %d", what, n,
                       CJ_CHART_MAX_TEXT);
    memcpy(dst, src, n + 1);
    return CJ_OK;
}

cj_status cj_chart_set_axis(cj_chart *c, int axis, cj_chart_scale scale, const char *title) {
    assert(c);
    if (axis < 0 || axis > 1)
        return cj_fail(CJ_ERR_ARGUMENT, "axis %d is neither 0 (x) nor 1 (y)", axis);
    if (scale != CJ_CHART_LINEAR && scale != CJ_CHART_LOG10)
        return cj_fail(CJ_ERR_ARGUMENT, "unknown axis scale %d", (int)scale);
    cj_status st = copy_text(c->axis_title[axis], title, "axis title");
    if (st) return st;
    c->scale[axis] = scale;
    return CJ_OK;
}

cj_status cj_chart_set_range(cj_chart *c, int axis, double lo, double hi) {
    assert(c);
    if (axis < 0 || axis > 1)
        return cj_fail(CJ_ERR_ARGUMENT, "axis %d is neither 0 (x) nor 1 (y)", axis);
    if (!isfinite(lo) || !isfinite(hi))
        return cj_fail(CJ_ERR_NONFINITE, "axis range [%g, %g] is not finite", lo, hi);
    if (!(lo < hi)) return cj_fail(CJ_ERR_DEGENERATE, "axis range [%g, %g] is empty", lo, hi);
    c->has_range[axis] = 1;
    c->lo[axis] = lo;
    c->hi[axis] = hi;
    return CJ_OK;
}

cj_status cj_chart_set_legend(cj_chart *c, cj_chart_legend where) {
    assert(c);
    if ((int)where < 0 || where >= CJ_LEGEND_COUNT_)
        return cj_fail(CJ_ERR_RANGE, "unknown legend position %d", (int)where);
    c->legend = where;
    return CJ_OK;
}

cj_status cj_chart_set_title(cj_chart *c, const char *title) {
    assert(c);
    return copy_text(c->title, title, "chart title");
}

cj_status cj_chart_add_series(cj_chart *c, const double *x, const double *y, size_t n,
                              const cj_chart_series_opts *o) {
    assert(c && o && (n == 0 || (x && y)));
    if (n == 0) return cj_fail(CJ_ERR_EMPTY, "series with no points");
    if (c->ns >= CJ_CHART_MAX_SERIES)
        return cj_fail(CJ_ERR_CAP, "more than %d series in one chart", CJ_CHART_MAX_SERIES);
    for (size_t i = 0; i < n; ++i)
        if (!isfinite(x[i]) || !isfinite(y[i]))
            return cj_fail(CJ_ERR_NONFINITE, "series point %zu (%g, %g) is not finite", i, x[i],
                           y[i]);
    if (!(o->line_width >= 0.0 && o->line_width <= 16.0))
        return cj_fail(CJ_ERR_RANGE, "series line width %g is outside [0, 16]", o->line_width);
    if ((int)o->marker < 0 || o->marker >= CJ_MARKER_COUNT_)
        return cj_fail(CJ_ERR_RANGE, "unknown marker %d", (int)o->marker);
    if (o->marker == CJ_MARKER_NONE && o->line_width == 0.0)
        return cj_fail(CJ_ERR_RANGE, "series with neither a line nor markers");
    if (o->marker != CJ_MARKER_NONE && !(o->marker_radius > 0.0 && o->marker_radius <= 16.0))
        return cj_fail(CJ_ERR_RANGE, "marker radius %g is outside (0, 16]", o->marker_radius);
    series *s = &c->s[c->ns];
    cj_status st = copy_text(s->label, o->label, "series label");
    if (st) return st;
    s->xy = c->alloc.alloc(c->alloc.user, 2 * n * sizeof *s->xy);
    if (!s->xy) return cj_fail(CJ_ERR_NOMEM, "no memory for a series of %zu points", n);
    for (size_t i = 0; i < n; ++i) s->xy[2 * i] = x[i], s->xy[2 * i + 1] = y[i];
    s->n = n;
    s->o = *o;
    s->o.label = NULL;
    c->ns++;
    return CJ_OK;
}

cj_status cj_chart_annotate(cj_chart *c, double x, double y, const char *text, cj_rgba color) {
    assert(c && text);
    if (!isfinite(x) || !isfinite(y))
        return cj_fail(CJ_ERR_NONFINITE, "annotation at (%g, %g) is not finite", x, y);
    if (!text[0]) return cj_fail(CJ_ERR_RANGE, "annotation with empty text");
    if (c->nn >= CJ_CHART_MAX_NOTES)
        return cj_fail(CJ_ERR_CAP, "more than %d annotations in one chart", CJ_CHART_MAX_NOTES);
    note *nt = &c->notes[c->nn];
    cj_status st = copy_text(nt->text, text, "annotation");
    if (st) return st;
    nt->x = x, nt->y = y, nt->color = color;
    c->nn++;
    return CJ_OK;
}

cj_chart_rect cj_chart_layout(const cj_chart *c, int w, int h, int with_text) {
    assert(c);
    cj_chart_rect r;
    if (!with_text) {
        r.left = r.bottom = 12.0, r.right = w - 12.0, r.top = h - 12.0;
    } else {
        r.left = 74.0, r.bottom = 48.0, r.right = w - 16.0;
        if (c->legend == CJ_LEGEND_OUTSIDE) r.right -= CJ_CHART_LEGEND_WIDTH;
        r.top = h - (c->title[0] ? 48.0 : 30.0);
    }
    return r;
}

/* Nice linear step: 1, 2 or 5 times a power of ten, about span/5. */
static double nice_step(double span) {
    double raw = span / 5.0, p = pow(10.0, floor(log10(raw))), m = raw / p;
    return (m < 1.5 ? 1.0 : m < 3.5 ? 2.0 : m < 7.5 ? 5.0 : 10.0) * p;
}

cj_status cj_chart_ranges(const cj_chart *c, double lo[2], double hi[2]) {
    assert(c && lo && hi);
    for (int a = 0; a < 2; ++a) {
        const int log = c->scale[a] == CJ_CHART_LOG10;
        double l = INFINITY, h = -INFINITY;
        for (size_t i = 0; i < c->ns; ++i)
            for (size_t k = 0; k < c->s[i].n; ++k) {
                const double v = c->s[i].xy[2 * k + a];
                if (log && !(v > 0.0))
                    return cj_fail(CJ_ERR_RANGE,
                                   "series %zu point %zu has %s = %g on a logarithmic axis", i, k,
                                   a ? "y" : "x", v);
                l = fmin(l, v), h = fmax(h, v);
            }
        if (c->has_range[a]) {
            l = c->lo[a], h = c->hi[a];
            if (log && !(l > 0.0))
                return cj_fail(CJ_ERR_RANGE, "logarithmic %s range starts at %g <= 0",
                               a ? "y" : "x", l);
        } else if (!(l <= h)) {
            return cj_fail(CJ_ERR_EMPTY, "chart has no series and no %s range", a ? "y" : "x");
        } else if (log) {
            double e0 = floor(log10(l)), e1 = ceil(log10(h));
            if (e1 <= e0) e1 = e0 + 1;
            l = pow(10.0, e0), h = pow(10.0, e1);
        } else {
            if (!(h > l)) {
                const double d = fmax(1.0, fabs(l) * 0.1);
                l -= d, h += d;
            }
            const double st = nice_step(h - l);
            l = floor(l / st) * st, h = ceil(h / st) * st;
        }
        lo[a] = l, hi[a] = h;
    }
    return CJ_OK;
}

typedef struct mapping {
    cj_chart_rect r;
    int log[2];
    double f0[2], f1[2];
} mapping;

static double fwd(const mapping *m, int a, double v) {
    const double f = m->log[a] ? log10(v) : v;
    const double t = (f - m->f0[a]) / (m->f1[a] - m->f0[a]);
    return a == 0 ? m->r.left + t * (m->r.right - m->r.left)
                  : m->r.bottom + t * (m->r.top - m->r.bottom);
}

static cj_status make_mapping(const cj_chart *c, int w, int h, int text, mapping *m) {
    double lo[2], hi[2];
    cj_status st = cj_chart_ranges(c, lo, hi);
    if (st) return st;
    m->r = cj_chart_layout(c, w, h, text);
    for (int a = 0; a < 2; ++a) {
        m->log[a] = c->scale[a] == CJ_CHART_LOG10;
        m->f0[a] = m->log[a] ? log10(lo[a]) : lo[a];
        m->f1[a] = m->log[a] ? log10(hi[a]) : hi[a];
    }
    return CJ_OK;
}

cj_status cj_chart_map(const cj_chart *c, int w, int h, int with_text, double x, double y,
                       double *px, double *py) {
    assert(c && px && py);
    mapping m;
    cj_status st = make_mapping(c, w, h, with_text, &m);
    if (st) return st;
    *px = fwd(&m, 0, x);
    *py = fwd(&m, 1, y);
    return CJ_OK;
}

static void marker(cj_plot_canvas *cv, cj_chart_marker mk, double x, double y, double r,
                   cj_rgba col) {
    switch (mk) {
    case CJ_MARKER_CIRCLE:
        cj_plot_disc(cv, x, y, r, col);
        break;
    case CJ_MARKER_SQUARE: {
        double q[8] = {x - r, y - r, x + r, y - r, x + r, y + r, x - r, y + r};
        cj_plot_fill_convex(cv, q, 4, col);
        break;
    }
    case CJ_MARKER_TRIANGLE: {
        double q[6] = {
            x,          y + r, x - 0.8660254037844386 * r, y - 0.5 * r, x + 0.8660254037844386 * r,
            y - 0.5 * r};
        cj_plot_fill_convex(cv, q, 3, col);
        break;
    }
    case CJ_MARKER_DIAMOND: {
        double q[8] = {x, y - r, x + r, y, x, y + r, x - r, y};
        cj_plot_fill_convex(cv, q, 4, col);
        break;
    }
    default:
        break;
    }
}

static cj_status text_at(cj_font *f, cj_plot_canvas *cv, double x, double y, double size,
                         double align, cj_rgba col, const char *s) {
    double adv = 0;
    cj_status st = cj_font_measure(f, size, s, &adv, NULL, NULL);
    if (st) return st;
    return cj_plot_text(cv, f, x - align * adv, y, size, col, s);
}

/* Major ticks of an axis: values v[0..n-1] (at most 64) and whether each is labelled. */
static int major_ticks(const mapping *m, int a, double *v, int *lab) {
    int n = 0;
    if (m->log[a]) {
        const int e0 = (int)ceil(m->f0[a] - 1e-9), e1 = (int)floor(m->f1[a] + 1e-9);
        const int every = (e1 - e0) > 10 ? (e1 - e0 + 9) / 10 : 1;
        for (int e = e0; e <= e1 && n < 64; ++e, ++n) {
            v[n] = pow(10.0, e);
            lab[n] = (e - e0) % every == 0;
        }
    } else {
        const double st = nice_step(m->f1[a] - m->f0[a]);
        for (double t = ceil(m->f0[a] / st - 1e-9);
             t * st <= m->f1[a] * (1 + 1e-12) + 1e-300 && n < 64; t += 1.0, ++n) {
            v[n] = t * st;
            if (fabs(v[n]) < 1e-9 * st) v[n] = 0.0;
            lab[n] = 1;
        }
    }
    return n;
}

static void tick_label(const mapping *m, int a, double v, char *buf, size_t cap) {
    if (m->log[a])
        snprintf(buf, cap, "1e%d", (int)lround(log10(v)));
    else
        snprintf(buf, cap, "%g", v);
}

/* The layout and the drawing, into fb (painter NULL) or through the painter (fb NULL). */
static cj_status chart_draw(const cj_chart *c, cj_framebuffer *fb, int x0, int y0, int w, int h,
                            cj_font *font, const cj_plot_painter *painter) {
    assert(c && (fb || painter));
    if (x0 < 0 || y0 < 0 || w < 120 || h < 90 ||
        (fb && (w > fb->width - x0 || h > fb->height - y0)))
        return fb ? cj_fail(CJ_ERR_RANGE,
                            "chart rectangle %dx%d at (%d, %d) is not a rectangle of at least "
                            "120x90 pixels inside the %dx%d framebuffer",
                            w, h, x0, y0, fb->width, fb->height)
                  : cj_fail(CJ_ERR_RANGE,
                            "chart rectangle %dx%d at (%d, %d) is not a rectangle of at least "
                            "120x90 pixels",
                            w, h, x0, y0);
    mapping m;
    cj_status st = make_mapping(c, w, h, font != NULL, &m);
    if (st) return st;
    cj_plot_canvas cv;
    if (painter)
        cj_plot_canvas_init_painter(&cv, w, h, painter, x0, y0);
    else if ((st = cj_plot_canvas_init(&cv, w, h)))
        return st;
    const cj_rgba white = cj_rgba_make(255, 255, 255, 255),
                  ink = cj_rgba_make(0x20, 0x20, 0x20, 255),
                  grid = cj_rgba_make(0xe4, 0xe4, 0xe4, 255);
    cj_plot_clear(&cv, white);
    const cj_chart_rect r = m.r;
    double tv[2][64];
    int tl[2][64], nt[2];
    for (int a = 0; a < 2; ++a) nt[a] = major_ticks(&m, a, tv[a], tl[a]);
    /* grid */
    for (int a = 0; !st && a < 2; ++a)
        for (int i = 0; !st && i < nt[a]; ++i) {
            const double p = fwd(&m, a, tv[a][i]);
            double seg[4] = {p, r.bottom, p, r.top};
            if (a) seg[0] = r.left, seg[1] = p, seg[2] = r.right, seg[3] = p;
            st = cj_plot_stroke(&cv, seg, 2, 0, grid, 1.0);
        }
    /* series: lines first, then markers on top */
    for (size_t i = 0; !st && i < c->ns; ++i) {
        const series *s = &c->s[i];
        if (s->o.line_width > 0.0 && s->n >= 2) {
            if ((st = cj_plot_canvas_reserve(&cv, s->n))) break;
            for (size_t k = 0; k < s->n; ++k) {
                cv.poly[2 * k] = fwd(&m, 0, s->xy[2 * k]);
                cv.poly[2 * k + 1] = fwd(&m, 1, s->xy[2 * k + 1]);
            }
            double *pts = cv.poly;
            st = cj_plot_stroke(&cv, pts, s->n, 0, s->o.color, s->o.line_width);
        }
    }
    for (size_t i = 0; !st && i < c->ns; ++i) {
        const series *s = &c->s[i];
        for (size_t k = 0; k < s->n && s->o.marker != CJ_MARKER_NONE; ++k)
            marker(&cv, s->o.marker, fwd(&m, 0, s->xy[2 * k]), fwd(&m, 1, s->xy[2 * k + 1]),
                   s->o.marker_radius, s->o.color);
    }
    /* frame, ticks, labels */
    if (!st) {
        cj_plot_blank_outside(&cv, r.left, r.bottom, r.right, r.top, white);
        double frame[8] = {r.left, r.bottom, r.right, r.bottom, r.right, r.top, r.left, r.top};
        st = cj_plot_stroke(&cv, frame, 4, 1, ink, 1.0);
    }
    const double ls = 12.0;
    for (int a = 0; !st && a < 2; ++a) {
        for (int i = 0; !st && i < nt[a]; ++i) {
            const double p = fwd(&m, a, tv[a][i]);
            double seg[4] = {p, r.bottom, p, r.bottom - 5};
            if (a) seg[0] = r.left, seg[1] = p, seg[2] = r.left - 5, seg[3] = p;
            st = cj_plot_stroke(&cv, seg, 2, 0, ink, 1.0);
            if (!st && font && tl[a][i]) {
                char buf[40];
                tick_label(&m, a, tv[a][i], buf, sizeof buf);
                st = a ? text_at(font, &cv, r.left - 8, p - 0.35 * ls, ls, 1.0, ink, buf)
                       : text_at(font, &cv, p, r.bottom - 8 - ls, ls, 0.5, ink, buf);
            }
        }
        /* minor ticks 2..9 x each decade when there are few decades */
        if (m.log[a] && m.f1[a] - m.f0[a] <= 8.0)
            for (int e = (int)floor(m.f0[a]); !st && e < (int)ceil(m.f1[a]); ++e)
                for (int k = 2; !st && k <= 9; ++k) {
                    const double fv = e + log10((double)k);
                    if (fv < m.f0[a] || fv > m.f1[a]) continue;
                    const double p = fwd(&m, a, k * pow(10.0, e));
                    double seg[4] = {p, r.bottom, p, r.bottom - 3};
                    if (a) seg[0] = r.left, seg[1] = p, seg[2] = r.left - 3, seg[3] = p;
                    st = cj_plot_stroke(&cv, seg, 2, 0, ink, 1.0);
                }
    }
    /* annotations: the ring, and the text at the first of four places beside it that does not
     * overlap an earlier note's text (notes of nearby points would print over each other) */
    double placed[CJ_CHART_MAX_NOTES][4]; /* text boxes drawn so far: x0, y0, x1, y1 */
    int nplaced = 0;
    for (size_t i = 0; !st && i < c->nn; ++i) {
        const note *nt_ = &c->notes[i];
        const double px = fwd(&m, 0, nt_->x), py = fwd(&m, 1, nt_->y);
        if (px < r.left - 0.5 || px > r.right + 0.5 || py < r.bottom - 0.5 || py > r.top + 0.5)
            continue; /* outside the plot area */
        double ring[2 * 24];
        for (int k = 0; k < 24; ++k)
            ring[2 * k] = px + 6 * cos(k * 0.2617993877991494),
                     ring[2 * k + 1] = py + 6 * sin(k * 0.2617993877991494);
        st = cj_plot_stroke(&cv, ring, 24, 1, nt_->color, 1.0);
        if (st || !font) continue;
        double adv = 0, asc = 0, desc = 0;
        st = cj_font_measure(font, 11.0, nt_->text, &adv, &asc, &desc);
        for (int k = 0; !st && k < 4; ++k) {
            const double x = k < 2 ? px + 8 : px - 8 - adv, y = k % 2 ? py - 6 - asc : py + 6;
            const double box[4] = {x, y - desc, x + adv, y + asc};
            int free = 1;
            for (int j = 0; j < nplaced && free; ++j)
                free = box[2] <= placed[j][0] || box[0] >= placed[j][2] || box[3] <= placed[j][1] ||
                       box[1] >= placed[j][3];
            if (!free) continue;
            memcpy(placed[nplaced++], box, sizeof box);
            st = text_at(font, &cv, x, y, 11.0, 0.0, nt_->color, nt_->text);
            break;
        }
    }
    /* legend: inside the upper right corner, one row of 16 px per labelled series */
    if (!st && font) {
        int rows = 0;
        double wmax = 0;
        for (size_t i = 0; !st && i < c->ns; ++i)
            if (c->s[i].label[0]) {
                double adv = 0;
                st = cj_font_measure(font, ls, c->s[i].label, &adv, NULL, NULL);
                wmax = fmax(wmax, adv);
                rows++;
            }
        if (!st && rows) {
            const double bw = wmax + 44, bh = rows * 16.0 + 8;
            double bx = r.right - 6 - bw, by = r.top - 6 - bh;
            if (c->legend == CJ_LEGEND_UPPER_LEFT || c->legend == CJ_LEGEND_LOWER_LEFT)
                bx = r.left + 6;
            if (c->legend == CJ_LEGEND_LOWER_LEFT || c->legend == CJ_LEGEND_LOWER_RIGHT)
                by = r.bottom + 6;
            if (c->legend == CJ_LEGEND_OUTSIDE) bx = r.right + 12, by = r.top - bh;
            double box[8] = {bx, by, bx + bw, by, bx + bw, by + bh, bx, by + bh};
            cj_plot_fill_convex(&cv, box, 4, cj_rgba_make(255, 255, 255, 230));
            st = cj_plot_stroke(&cv, box, 4, 1, cj_rgba_make(0xa0, 0xa0, 0xa0, 255), 1.0);
            int row = 0;
            for (size_t i = 0; !st && i < c->ns; ++i) {
                const series *s = &c->s[i];
                if (!s->label[0]) continue;
                const double cy = by + bh - 12 - 16.0 * row++;
                if (s->o.line_width > 0.0) {
                    double seg[4] = {bx + 6, cy, bx + 30, cy};
                    st = cj_plot_stroke(&cv, seg, 2, 0, s->o.color, s->o.line_width);
                }
                if (s->o.marker != CJ_MARKER_NONE)
                    marker(&cv, s->o.marker, bx + 18, cy, fmin(s->o.marker_radius, 6.0),
                           s->o.color);
                if (!st) st = text_at(font, &cv, bx + 36, cy - 0.35 * ls, ls, 0.0, ink, s->label);
            }
        }
    }
    /* titles: chart title centred on top, x title under the labels, y title above the axis */
    if (!st && font && c->title[0])
        st = text_at(font, &cv, 0.5 * (r.left + r.right), h - 22, 15.0, 0.5, ink, c->title);
    if (!st && font && c->axis_title[0][0])
        st = text_at(font, &cv, 0.5 * (r.left + r.right), 8, ls, 0.5, ink, c->axis_title[0]);
    if (!st && font && c->axis_title[1][0])
        st = text_at(font, &cv, 8, r.top + 14, ls, 0.0, ink, c->axis_title[1]);
    if (!st) st = cv.paint_status;
    if (!st && fb)
        for (int row = 0; row < h; ++row)
            memcpy(fb->pixels + (ptrdiff_t)(y0 + row) * fb->stride + x0,
                   cv.fb->pixels + (ptrdiff_t)row * cv.fb->stride, (size_t)w * sizeof(cj_rgba));
    cj_plot_canvas_free(&cv);
    return st;
}

cj_status cj_chart_render(const cj_chart *c, cj_framebuffer *fb, int x0, int y0, int w, int h,
                          cj_font *font) {
    assert(fb);
    return chart_draw(c, fb, x0, y0, w, h, font, NULL);
}

cj_status cj_chart_paint(const cj_chart *c, int x0, int y0, int w, int h, cj_font *font,
                         const cj_plot_painter *painter) {
    assert(painter && painter->stroke && painter->fill && painter->disc && painter->text);
    return chart_draw(c, NULL, x0, y0, w, h, font, painter);
}

/* casteljau: data charts drawn by our own rasterizer — several series per panel against x and
 * y axes that are each linear or logarithmic (base 10), with decade ticks and labels, line and
 * scatter series with markers, a legend, axis titles, a title and text annotations.
 *
 * Where cj_plot (plot.h) shows geometry with EQUAL ASPECT, a cj_chart maps each axis on its
 * own: the plot area of a w x h panel is
 *     [left, w - right] x [bottom, h - top]        (pixels, y up, see cj_chart_layout)
 * and a value v on an axis with range [lo, hi] lands at
 *     left + (f(v) - f(lo)) / (f(hi) - f(lo)) * (w - left - right),   f = identity or log10
 * (likewise in y). A log axis without a set range spans whole decades around its data
 * (floor(log10 min) .. ceil(log10 max)); a linear one is rounded outwards to its tick step
 * (1, 2 or 5 times a power of ten). Log axes get a tick and a label "1e-6" at every decade
 * (every k-th decade labelled when more than 10) and minor ticks at 2..9 times a decade when
 * there are at most 8 decades; both axes get light grid lines at their major ticks.
 *
 * A chart owns copies of everything given to it. Colours are straight-alpha RGBA. Text uses a
 * cj_font (text.h); with NULL nothing textual is drawn and the margins shrink (see
 * cj_chart_layout). Every add/set function validates its input and leaves the chart unchanged
 * on failure.
 */
#ifndef CASTELJAU_CHART_H
#define CASTELJAU_CHART_H

#include "casteljau/framebuffer.h"
#include "casteljau/status.h"
#include "casteljau/text.h"
#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct cj_chart cj_chart;

typedef enum cj_chart_scale { CJ_CHART_LINEAR = 0, CJ_CHART_LOG10 } cj_chart_scale;

typedef enum cj_chart_marker {
    CJ_MARKER_NONE = 0,
    CJ_MARKER_CIRCLE,   /* filled disc of radius r */
    CJ_MARKER_SQUARE,   /* filled axis-aligned square of half side r */
    CJ_MARKER_TRIANGLE, /* filled upward triangle inscribed in the circle of radius r */
    CJ_MARKER_DIAMOND,  /* filled square of half diagonal r turned by 45 degrees */
    CJ_MARKER_COUNT_
} cj_chart_marker;

/* Longest label/title/annotation accepted, in bytes. */
#define CJ_CHART_MAX_TEXT 256
/* Most series and annotations per chart. */
#define CJ_CHART_MAX_SERIES 32
#define CJ_CHART_MAX_NOTES  64

typedef struct cj_chart_series_opts {
    const char *label;      /* legend entry (copied); NULL or "" = not in the legend */
    cj_rgba color;          /* line and markers */
    double line_width;      /* 0 = scatter (no line); else (0, 16] px, points joined in order */
    cj_chart_marker marker; /* CJ_MARKER_NONE needs line_width > 0 */
    double marker_radius;   /* (0, 16] px when a marker is drawn */
} cj_chart_series_opts;

/* The plot area of a w x h panel, in panel pixels (y up). */
typedef struct cj_chart_rect {
    double left, bottom, right, top; /* x in [left, right], y in [bottom, top] */
} cj_chart_rect;

/* Where the legend goes. OUTSIDE puts it right of the plot area, which then ends
 * CJ_CHART_LEGEND_WIDTH px further left (with text only), so that it never hides data. */
typedef enum cj_chart_legend {
    CJ_LEGEND_UPPER_RIGHT = 0,
    CJ_LEGEND_UPPER_LEFT,
    CJ_LEGEND_LOWER_LEFT,
    CJ_LEGEND_LOWER_RIGHT,
    CJ_LEGEND_OUTSIDE,
    CJ_LEGEND_COUNT_
} cj_chart_legend;
#define CJ_CHART_LEGEND_WIDTH 190.0

/* CJ_ERR_NOMEM. alloc NULL = malloc/free. Axes start linear, untitled, auto range. */
cj_status cj_chart_create(const cj_allocator *alloc, cj_chart **out);
void cj_chart_destroy(cj_chart *chart); /* NULL allowed */

/* axis 0 = x, 1 = y (else CJ_ERR_ARGUMENT). title copied (NULL = none; CJ_ERR_RANGE when longer
 * than CJ_CHART_MAX_TEXT). */
cj_status cj_chart_set_axis(cj_chart *chart, int axis, cj_chart_scale scale, const char *title);
/* Fixed range lo < hi, finite (CJ_ERR_NONFINITE, CJ_ERR_DEGENERATE); both > 0 on a log axis
 * (checked at render: CJ_ERR_RANGE). */
cj_status cj_chart_set_range(cj_chart *chart, int axis, double lo, double hi);
/* CJ_ERR_RANGE for an unknown position. Default CJ_LEGEND_UPPER_RIGHT. */
cj_status cj_chart_set_legend(cj_chart *chart, cj_chart_legend where);
cj_status cj_chart_set_title(cj_chart *chart, const char *title);
/* A series of n >= 1 points (x[i], y[i]), finite (CJ_ERR_EMPTY, CJ_ERR_NONFINITE,
 * CJ_ERR_RANGE for widths/radii/marker, CJ_ERR_CAP past CJ_CHART_MAX_SERIES, CJ_ERR_NOMEM).
 * Points <= 0 on a log axis make cj_chart_render fail with CJ_ERR_RANGE naming the series. */
cj_status cj_chart_add_series(cj_chart *chart, const double *x, const double *y, size_t n,
                              const cj_chart_series_opts *opts);
/* A note at data point (x, y): a ring of radius 6 px around it and the text (11 px) to its upper
 * right: pen at (px + 8, py + 6) on the baseline, y up. Where that text box (advance x ascent +
 * descent) would overlap the text of an earlier note, it goes to the lower right (baseline
 * py - 6 - ascent), else the upper left (ending at px - 8), else the lower left; where all four
 * overlap, the note is drawn as its ring alone. (CJ_ERR_NONFINITE, CJ_ERR_RANGE for empty/long
 * text, CJ_ERR_CAP, CJ_ERR_NOMEM.) */
cj_status cj_chart_annotate(cj_chart *chart, double x, double y, const char *text, cj_rgba color);

/* The plot area for a w x h panel: margins 12 px without text; with text left 74, bottom 48,
 * right 16 (+ CJ_CHART_LEGEND_WIDTH with an outside legend), top 30 (48 when there is a title). */
cj_chart_rect cj_chart_layout(const cj_chart *chart, int w, int h, int with_text);
/* The axis ranges render uses (after auto ranging): lo[0..1], hi[0..1] for x and y.
 * CJ_ERR_EMPTY (no series and a range unset), CJ_ERR_RANGE (a value <= 0 on a log axis). */
cj_status cj_chart_ranges(const cj_chart *chart, double lo[2], double hi[2]);
/* Panel pixel coordinates of data point (x, y) for a w x h panel; statuses of cj_chart_ranges. */
cj_status cj_chart_map(const cj_chart *chart, int w, int h, int with_text, double x, double y,
                       double *px, double *py);

/* Legend geometry (text only): a box of width (widest label + 44) and height (16 rows + 8) with
 * a corner 6 px inside the chosen corner of the plot area (OUTSIDE: its upper left corner 12 px
 * right of the plot area's upper right corner); entry i (0 at the top) has its line
 * sample from box left + 6 to + 30 and its marker centred at (box left + 18, box top - 12 - 16 i),
 * its label at box left + 36. Annotation text: 11 px, pen at (x + 8, y + 6). Axis titles: 12 px,
 * the x title centred under the plot area with its baseline at y = 8, the y title left-aligned
 * at x = 8 with its baseline 14 px above the plot area. Tick labels 12 px.
 *
 * Renders into [x0, x0+w) x [y0, y0+h) of fb (filled white first; nothing outside touched).
 * Draw order: grid, series (clipped to the plot area), frame and ticks, annotations, legend
 * (inside the upper right corner of the plot area), titles. CJ_ERR_RANGE for a rectangle not
 * inside fb or smaller than 120 x 90 px, statuses of cj_chart_ranges, errors of the font. */
cj_status cj_chart_render(const cj_chart *chart, cj_framebuffer *fb, int x0, int y0, int w, int h,
                          cj_font *font);

#ifdef __cplusplus
}
#endif
#endif

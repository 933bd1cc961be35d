/* casteljau: plots painted through caller-supplied drawing callbacks instead of rasterized, for
 * vector output (SVG, PDF through cairo, in the casteljau tool) with exactly the layout of
 * cj_plot_render: the same data box, margins, ticks, labels (measured with the same cj_font),
 * title and items, in the same order; and charts (cj_chart_paint) as cj_chart_render draws them.
 *
 * Coordinates are the pixel coordinates cj_plot_render would use in a framebuffer holding the
 * panel at (x0, y0): origin at the lower-left corner of the image, y UP, one unit per pixel.
 * Colours are straight-alpha RGBA (cj_rgba), blended source-over. Curves arrive already
 * flattened (at CJ_PLOT_FLATTEN_TOL = 0.25 px, as for the raster path), so a painter needs only
 * polylines, convex polygons, discs and text.
 *
 * The painter sees, in order: a fill of the whole panel with the background; the items and the
 * grid; with axes, four background fills covering everything outside the plot frame (the raster
 * path blanks those pixels: arrows may reach out of the frame), then the frame, the ticks and
 * their labels; the title. A callback returning a status other than CJ_OK stops the painting
 * and that status is returned.
 */
#ifndef CASTELJAU_PLOT_PAINT_H
#define CASTELJAU_PLOT_PAINT_H

#include "casteljau/chart.h"
#include "casteljau/plot.h"
#include "casteljau/status.h"
#include "casteljau/text.h"
#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct cj_plot_painter {
    void *user;
    /* A polyline xy[2n] (n >= 1; closed: back to the first point) stroked with round joins and
     * caps, `width` pixels wide. */
    cj_status (*stroke)(void *user, const double *xy, size_t n, int closed, cj_rgba color,
                        double width);
    /* A filled convex polygon xy[2n] (n >= 3, either orientation; also axis-aligned
     * rectangles of the background). */
    cj_status (*fill)(void *user, const double *xy, size_t n, cj_rgba color);
    /* A filled disc of radius r centred at (x, y). */
    cj_status (*disc)(void *user, double x, double y, double r, cj_rgba color);
    /* UTF-8 text at an em size of size_px pixels, the pen starting at (x, y) on the baseline;
     * `advance` is the string's width measured with the plot's cj_font (so a painter using
     * another font can scale to the same width). */
    cj_status (*text)(void *user, double x, double y, double size_px, double advance, cj_rgba color,
                      const char *utf8);
} cj_plot_painter;

/* Paints `plot` as cj_plot_render(plot, fb, x0, y0, w, h, font) would draw it (see above).
 * Same statuses as cj_plot_render (without a framebuffer the rectangle need only be at least
 * 12 x 12 with x0, y0 >= 0), plus whatever a callback returns. */
cj_status cj_plot_paint(const cj_plot *plot, int x0, int y0, int w, int h, cj_font *font,
                        const cj_plot_painter *painter);

/* Paints a chart (casteljau/chart.h) as cj_chart_render(chart, fb, x0, y0, w, h, font) would
 * draw it, in the same way: a white fill of the panel, then grid, series, legend, notes,
 * axes, labels and titles. Same statuses as cj_chart_render (the rectangle need only be at least
 * 120 x 90 with x0, y0 >= 0), plus whatever a callback returns. */
cj_status cj_chart_paint(const cj_chart *chart, int x0, int y0, int w, int h, cj_font *font,
                         const cj_plot_painter *painter);

#ifdef __cplusplus
}
#endif
#endif

/* Private to raster/: the drawing canvas of cj_plot_render and its primitives (anti-aliased
 * strokes with round joins, discs, convex fills, arrows, text). A canvas either rasterizes
 * into its framebuffer or, with a painter (casteljau/plot_paint.h), hands every primitive to
 * the painter's callbacks, offset by (ox, oy): the same layout code drives both. */
#ifndef CASTELJAU_PLOT_INTERNAL_H
#define CASTELJAU_PLOT_INTERNAL_H

#include "casteljau/framebuffer.h"
#include "casteljau/plot_paint.h"
#include "casteljau/status.h"
#include "casteljau/text.h"
#include "casteljau/vec.h"
#include <stddef.h>

typedef struct cj_plot_canvas {
    cj_framebuffer *fb; /* the panel being drawn, w x h */
    float *cover;       /* w*h coverage accumulator of the current stroke, kept at 0 between */
    double *poly;       /* scratch polyline (2 doubles per point) */
    size_t poly_cap, poly_n;
    cj_vec2 *vec; /* scratch points for the stroker */
    size_t vec_cap;
    double arrow_len; /* length of frame arrows in pixels */
    /* painting instead of rasterizing (fb is then NULL) */
    const cj_plot_painter *painter;
    double ox, oy;          /* the panel's corner in the painter's coordinates */
    int w, h;               /* the panel's size */
    cj_status paint_status; /* the first failure of a callback of a void primitive */
    double *pxy;            /* scratch: points moved to the painter's coordinates */
    size_t pxy_cap;
} cj_plot_canvas;

cj_status cj_plot_canvas_init(cj_plot_canvas *cv, int w, int h);
/* A canvas of w x h that paints through `painter`, the panel's corner at (ox, oy). */
void cj_plot_canvas_init_painter(cj_plot_canvas *cv, int w, int h, const cj_plot_painter *painter,
                                 double ox, double oy);
/* Fills the whole canvas with c (the background). */
void cj_plot_clear(cj_plot_canvas *cv, cj_rgba c);
/* Text with the pen at (x, y) on the baseline (cj_font_draw's conventions). */
cj_status cj_plot_text(cj_plot_canvas *cv, cj_font *font, double x, double y, double size,
                       cj_rgba c, const char *utf8);
void cj_plot_canvas_free(cj_plot_canvas *cv);
/* Makes room for n points in cv->poly. */
cj_status cj_plot_canvas_reserve(cj_plot_canvas *cv, size_t n);

/* Strokes the polyline xy[2n] (pixel coordinates, y up; closed: back to the start) with the
 * given width through cj_line_stroke_polyline (round joins and caps, anti-aliased, no double
 * blending where segments meet). */
cj_status cj_plot_stroke(cj_plot_canvas *cv, const double *xy, size_t n, int closed, cj_rgba c,
                         double width);
/* Filled anti-aliased disc of radius r centred at (x, y). */
void cj_plot_disc(cj_plot_canvas *cv, double x, double y, double r, cj_rgba c);
/* Filled convex polygon (either orientation), 4x4 supersampled coverage. */
void cj_plot_fill_convex(cj_plot_canvas *cv, const double *xy, size_t n, cj_rgba c);
/* Arrow from (x0, y0) to the tip (x1, y1): a shaft and a filled head. */
cj_status cj_plot_arrow(cj_plot_canvas *cv, double x0, double y0, double x1, double y1, cj_rgba c,
                        double width);
/* Sets every pixel outside [x0, x1] x [y0, y1] (rounded outwards) to c. */
void cj_plot_blank_outside(cj_plot_canvas *cv, double x0, double y0, double x1, double y1,
                           cj_rgba c);

#endif

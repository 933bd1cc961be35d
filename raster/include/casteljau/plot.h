/* casteljau: 2D plots of curves drawn by our own rasterizer — Bézier curves with their control
 * polygon, control points, convex hull, de Casteljau construction and tangent/normal arrows;
 * Catmull-Rom splines with their knots; implicit curves from their contours; polylines and
 * points; axes with ticks and numeric labels; a title.
 *
 * A cj_plot is a list of items, each with a colour and a stroke width in pixels. It owns copies
 * of all the data given to it (the caller's arrays may be freed after each add call). Rendering
 * fits the data into a rectangle of a framebuffer with a margin, with EQUAL ASPECT (one data
 * unit is the same number of pixels in x and y), y up (the framebuffer origin is the lower-left
 * pixel). The fitted box is the union of every item's points: curve control points (a Bézier
 * curve lies in their hull), spline segments' control points, implicit contours, polylines and
 * points; cj_plot_set_view overrides it.
 *
 * Curves are transformed to pixel space (an affine map, exact for Bézier control points) and
 * flattened there at CJ_PLOT_FLATTEN_TOL = 0.25 px, then stroked anti-aliased. Colours are
 * straight-alpha RGBA (cj_rgba). Text uses a cj_font (casteljau/text.h); pass NULL to render
 * without any text (ticks are still drawn).
 *
 * Every add function validates its input (finite coordinates, counts, widths) and returns a
 * status naming the bad input; on failure the plot is unchanged.
 */
#ifndef CASTELJAU_PLOT_H
#define CASTELJAU_PLOT_H

#include "casteljau/bezier.h"
#include "casteljau/bspline.h"
#include "casteljau/catmull_rom.h"
#include "casteljau/framebuffer.h"
#include "casteljau/implicit.h"
#include "casteljau/rational.h"
#include "casteljau/status.h"
#include "casteljau/text.h"
#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Flattening tolerance in pixels used for every curve. */
#define CJ_PLOT_FLATTEN_TOL 0.25
/* Most tangent/normal frames per Bézier item. */
#define CJ_PLOT_MAX_FRAMES 16
/* Largest stroke width / marker radius in pixels. */
#define CJ_PLOT_MAX_WIDTH 64.0

typedef struct cj_plot cj_plot;

/* Options of a Bézier item (start from cj_plot_bezier_defaults()). */
typedef struct cj_plot_bezier_opts {
    cj_rgba color;         /* the curve */
    double width;          /* stroke width in pixels, (0, CJ_PLOT_MAX_WIDTH] */
    int control_polygon;   /* draw the control polygon (thin, grey) */
    int control_points;    /* draw the control points as markers */
    int hull;              /* fill the convex hull of the control points (translucent) */
    int construction;      /* draw the de Casteljau construction at construction_t */
    double construction_t; /* in [0, 1]; the intermediate polygons of every level and c(t) */
    size_t nframes;        /* tangent (and normal) arrows at frames_t[0..nframes-1] in [0,1] */
    double frames_t[CJ_PLOT_MAX_FRAMES];
    int normals; /* with each tangent arrow also draw the normal arrow */
} cj_plot_bezier_opts;

/* Defaults: colour #1f77b4, width 2.5, control polygon and points on, hull and construction
 * off, no frames, normals on. */
cj_plot_bezier_opts cj_plot_bezier_defaults(void);

/* Creates an empty plot: white background, axes on, no title, margin 12 px. The allocator
 * (NULL = malloc/free) is used for the plot's own storage. CJ_ERR_NOMEM on failure. */
cj_status cj_plot_create(const cj_allocator *alloc, cj_plot **out);
void cj_plot_destroy(cj_plot *plot); /* NULL allowed */

void cj_plot_set_background(cj_plot *plot, cj_rgba color);
void cj_plot_set_axes(cj_plot *plot, int on);
/* Longest title accepted, in bytes (UTF-8): one line of text above a plot. Longer titles would
 * only cost layout time (a 1 MB title took seconds per panel) for text that cannot fit. */
#define CJ_PLOT_MAX_TITLE 1024

/* Title drawn centred above the plot area (copied; NULL or "" = none). CJ_ERR_RANGE for a
 * title longer than CJ_PLOT_MAX_TITLE bytes, CJ_ERR_NOMEM. */
cj_status cj_plot_set_title(cj_plot *plot, const char *title);
/* Blank border in pixels around everything (0..1000, else CJ_ERR_RANGE). */
cj_status cj_plot_set_margin(cj_plot *plot, double px);
/* Data box to show instead of the fitted one (x0 < x1, y0 < y1, finite, else
 * CJ_ERR_NONFINITE / CJ_ERR_DEGENERATE). */
cj_status cj_plot_set_view(cj_plot *plot, double x0, double y0, double x1, double y1);

/* A 2D Bézier curve of any degree (c->dim must be 2, degree <= CJ_BEZIER_MAX_DEGREE).
 * opts NULL = defaults. Statuses: those of cj_bezier_check, CJ_ERR_DIMENSION (dim != 2),
 * CJ_ERR_RANGE (width, construction_t or a frame t out of range, nframes too large),
 * CJ_ERR_NOMEM. A frame at a point where the curve has no tangent (all points equal) is
 * skipped at render time. */
cj_status cj_plot_add_bezier(cj_plot *plot, const cj_bezier *c, const cj_plot_bezier_opts *opts);

/* A 2D rational Bézier curve (weights > 0, see rational.h), with the same options: the hull
 * still contains the curve, the construction shows the rational de Casteljau levels
 * ((1-t) w_i b_i + t w_{i+1} b_{i+1}) / ((1-t) w_i + t w_{i+1}), and a frame is skipped where
 * c'(t) = 0. Statuses: those of cj_rbezier_check, then as cj_plot_add_bezier. */
cj_status cj_plot_add_rbezier(cj_plot *plot, const cj_rbezier *c, const cj_plot_bezier_opts *opts);

/* Drawing options of a B-spline / NURBS curve (cj_plot_add_bspline). */
typedef struct cj_plot_bspline_opts {
    cj_rgba color;       /* the curve and its knot markers */
    double width;        /* stroke width in pixels, (0, CJ_PLOT_MAX_WIDTH] */
    int control_polygon; /* the control polygon (thin, grey) */
    int control_points;  /* a dot at each control point */
    int knot_markers;    /* a disc (radius 3.5 px) on the curve at every distinct domain knot */
} cj_plot_bspline_opts;

/* Defaults: colour #1f77b4, width 2.5, control polygon, points and knot markers on. */
cj_plot_bspline_opts cj_plot_bspline_defaults(void);

/* A 2D B-spline or NURBS curve (casteljau/bspline.h), drawn as its Bézier pieces
 * (cj_bspline_to_bezier, each added as cj_plot_add_bezier / cj_plot_add_rbezier with the
 * options' colour and width), then its control polygon/points (cj_plot_add_polyline), then the
 * knot markers (cj_plot_add_points at c(t) for every piece break). The plot JSON's "bspline"
 * item and the viewer both draw through this. Statuses: CJ_ERR_ARGUMENT (not 2D), those of
 * cj_bspline_check / cj_bspline_to_bezier / cj_bspline_eval, CJ_ERR_RANGE (width),
 * CJ_ERR_NOMEM. */
cj_status cj_plot_add_bspline(cj_plot *plot, const cj_bspline *c, const cj_plot_bspline_opts *opts);

/* An interpolating spline through npts 2D points (cj_catmull_rom with sopts, NULL = classic
 * uniform Catmull-Rom κ = 0.5); show_knots draws the points it passes through as markers.
 * Statuses: those of cj_catmull_rom, CJ_ERR_RANGE (width), CJ_ERR_NOMEM. */
cj_status cj_plot_add_spline(cj_plot *plot, const double *pts, size_t npts,
                             const cj_spline_options *sopts, cj_rgba color, double width,
                             int show_knots);

/* The curve f = 0 inside box = {x0, y0, x1, y1}, contoured with cj_implicit_contour on a
 * grid x grid mesh (0: 64) at tolerance 1e-5 times the box diagonal. The contours are computed
 * now and stored. Statuses: those of cj_implicit_contour (CJ_ERR_CAP is accepted: the
 * contour is stored anyway), CJ_ERR_EMPTY if no part of the curve lies in the box,
 * CJ_ERR_RANGE (width), CJ_ERR_NOMEM. */
cj_status cj_plot_add_implicit(cj_plot *plot, const cj_implicit *f, const double box[4], int grid,
                               cj_rgba color, double width);

/* A polyline through npts >= 2 points xy[2*npts] (closed: back to the first point); markers
 * draws a dot at each vertex. CJ_ERR_EMPTY, CJ_ERR_NONFINITE, CJ_ERR_RANGE, CJ_ERR_NOMEM. */
cj_status cj_plot_add_polyline(cj_plot *plot, const double *xy, size_t npts, int closed,
                               cj_rgba color, double width, int markers);

/* npts >= 1 points drawn as filled discs of the given radius in pixels. */
cj_status cj_plot_add_points(cj_plot *plot, const double *xy, size_t npts, cj_rgba color,
                             double radius);

/* Number of items added so far. */
size_t cj_plot_item_count(const cj_plot *plot);

/* Renders into the rectangle [x0, x0+w) x [y0, y0+h) of fb (pixels outside it are not touched;
 * the rectangle is filled with the background first). font may be NULL (no text). A rectangle
 * too small for the axes and text gets a bare plot (no axes, no text, 2 px margin), and a tiny
 * one (down to 12 x 12 px) a bare plot whose strokes may touch its edge. Data spanning more
 * than the double range (hi - lo overflows) gets no ticks.
 * Data at a single point (and no view) are shown in a view centred on it.
 * Statuses: CJ_ERR_RANGE if the rectangle is not inside fb or is smaller than 12 x 12 px
 * (nothing drawn), CJ_ERR_EMPTY if the plot has no items and no view, errors of the font.
 */
cj_status cj_plot_render(const cj_plot *plot, cj_framebuffer *fb, int x0, int y0, int w, int h,
                         cj_font *font);

#ifdef __cplusplus
}
#endif
#endif

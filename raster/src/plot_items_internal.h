/* Private to the plot sources: the plot object, its items and the data-to-pixel map. plot.c
 * stores the items, plot_items.c draws one item, plot_render.c lays out the panel (fit, axes,
 * text) and draws them all. */
#ifndef CASTELJAU_PLOT_ITEMS_INTERNAL_H
#define CASTELJAU_PLOT_ITEMS_INTERNAL_H

#include "casteljau/plot.h"
#include "plot_internal.h"
#include <stddef.h>

typedef enum item_type {
    ITEM_BEZIER,
    ITEM_SPLINE,
    ITEM_IMPLICIT,
    ITEM_POLYLINE,
    ITEM_POINTS
} item_type;

typedef struct plot_item {
    item_type type;
    cj_rgba color;
    double width;      /* stroke width, or marker radius for ITEM_POINTS */
    double *pts;       /* bezier: control points; spline: knots (input points); polyline,
                          points: vertices; implicit: all contour vertices back to back */
    size_t npts;       /* number of 2D points in pts */
    double *segs;      /* spline: nsegs cubic segments (8 doubles each) */
    size_t nsegs;      /* spline segments; implicit: number of contours */
    size_t *offsets;   /* implicit: contour k has points offsets[k]..offsets[k+1]-1 */
    int *closed_flags; /* implicit: closed flag per contour */
    int closed;        /* polyline */
    int markers;       /* polyline markers, spline knots */
    int degree;        /* bezier */
    double *weights;   /* rational bezier: degree+1 weights; NULL for a polynomial curve */
    cj_plot_bezier_opts bopts;
} plot_item;

struct cj_plot {
    cj_allocator alloc;
    plot_item *items;
    size_t count, cap;
    cj_rgba background;
    int axes;
    char *title;
    double margin;
    int has_view;
    double view[4];
};

/* Data to pixels: a uniform scale about the view's centre. */
typedef struct xform {
    double s;      /* pixels per data unit */
    double ox, oy; /* pixel position of data (cx, cy) */
    double cx, cy;
} xform;

/* Draws one item on the canvas through the map x. */
cj_status cj_plot_draw_item(cj_plot_canvas *cv, const xform *x, const plot_item *it);

#endif

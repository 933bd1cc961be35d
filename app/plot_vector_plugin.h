/* Private to the casteljau tool: the cairo side of vector plots (plot_vector_cairo.c) is the
 * module libcasteljau_cairo.so, opened by plot_vector.c only for an SVG or PDF, so that no
 * other launch maps cairo (and the X11 and xcb libraries it links). The program keeps the
 * layout (cj_plot_paint / cj_chart_paint) and the file; the module paints. It exports
 * CJ_CAIRO_PLUGIN_SYMBOL, returning this table. Only header types of the library cross. */
#ifndef CASTELJAU_APP_PLOT_VECTOR_PLUGIN_H
#define CASTELJAU_APP_PLOT_VECTOR_PLUGIN_H

#include "casteljau/plot_paint.h"

#include <stddef.h>
#include <stdio.h>

enum { PLOT_VECTOR_NONE = 0, PLOT_VECTOR_SVG, PLOT_VECTOR_PDF };

#define PLOT_VECTOR_PLUGIN_ABI 1
#define CJ_CAIRO_PLUGIN_SYMBOL "cj_cairo_plugin_v1"
#define CJ_CAIRO_PLUGIN_FILE   "libcasteljau_cairo.so"

typedef struct plot_vector_surface plot_vector_surface;

typedef struct plot_vector_plugin {
    int abi; /* PLOT_VECTOR_PLUGIN_ABI */
    /* Starts a width x height px page (PLOT_VECTOR_SVG or _PDF) streamed to f, text in the
     * font file font_path, and fills *painter (its user is the surface). NULL with a reason in
     * why when the font cannot be opened or memory runs out. */
    plot_vector_surface *(*begin)(int format, double width, double height, const char *font_path,
                                  FILE *f, cj_plot_painter *painter, char *why, size_t why_size);
    /* Restricts painting to the rectangle whose top-left corner is (x, y_top) in our
     * coordinates (y up), w x h; unclip undoes the last clip. */
    void (*clip)(plot_vector_surface *s, double x, double y_top, double w, double h);
    void (*unclip)(plot_vector_surface *s);
    /* Finishes the page (the last bytes reach f) and frees the surface: CJ_OK, or CJ_ERR_IO /
     * CJ_ERR_NOMEM with cairo's reason (naming path) in why. */
    int (*end)(plot_vector_surface *s, const char *path, char *why, size_t why_size);
} plot_vector_plugin;

#endif

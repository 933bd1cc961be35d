/* The plot document (formats/, library cj_formats; read by `casteljau plot`, the tests and the
 * fuzzer): the JSON plot description (format documented in plot_json.c
 * and the README) parsed with cJSON into cj_plot objects. */
#ifndef CASTELJAU_APP_PLOT_JSON_H
#define CASTELJAU_APP_PLOT_JSON_H

#include "casteljau/bspline.h"
#include "casteljau/chart.h"
#include "casteljau/plot.h"
#include <stddef.h>
#include <stdio.h>

#define PLOT_JSON_MIN_SIDE   64
#define PLOT_JSON_MAX_SIDE   8192
#define PLOT_JSON_MAX_PANELS 64
/* Per-document work limits (plot_json.c explains the counting). */
#define PLOT_JSON_MAX_ITEMS  10000
#define PLOT_JSON_MAX_POINTS 1000000
#define PLOT_JSON_MAX_WORK   2e9
/* Largest JSON file read, in bytes. */
#define PLOT_JSON_MAX_BYTES ((size_t)64 << 20)

typedef struct cj_plot_doc {
    int width, height; /* image size in pixels */
    cj_rgba background;
    int columns; /* panels per row */
    size_t npanels;
    cj_plot *panels[PLOT_JSON_MAX_PANELS];
    cj_chart *charts[PLOT_JSON_MAX_PANELS]; /* a chart panel ("kind": "chart"): panels[i] NULL */
    int single;                             /* the document is one plot (no "panels") */
    size_t failed;  /* set by cj_plot_doc_render on failure: the panel that failed */
    char where[32]; /* cj_plot_doc_where's text */
} cj_plot_doc;

/* Parses a whole document, named `name` in messages (a file name; NULL: "<plot>"). On success
 * returns CJ_OK and fills *doc (free with cj_plot_doc_free). On failure leaves nothing allocated
 * and returns CJ_ERR_PARSE (or CJ_ERR_RANGE, CJ_ERR_NONFINITE, CJ_ERR_NOMEM where the checked-JSON
 * kit's status reaches the entry), with cj_last_error() a one-line reason giving the document,
 * the line and the JSON path of the bad value ("plot.json:7: items[2].points[3] must be an array
 * of 2 numbers, not 1"); a syntax error names its line and column. */
cj_status cj_plot_json_parse(const char *name, const char *text, cj_plot_doc *doc);

void cj_plot_doc_free(cj_plot_doc *doc);

/* Renders every panel into fb (doc->width x doc->height), a grid of doc->columns columns.
 * font may be NULL. Returns CJ_OK or the first failing status (cj_last_error explains; the
 * panel is recorded for cj_plot_doc_where). */
cj_status cj_plot_doc_render(cj_plot_doc *doc, cj_framebuffer *fb, cj_font *font);

/* ---- single-plot pages of curves: the documents the viewer edits ----
 * The one reader of "bezier", "catmull-rom" and "bspline" items (plot_json_curve.c,
 * plot_json_bspline.c) fills this model; the
 * plot reader above draws what it read, the viewer edits it, and cj_plot_json_write_page (the one
 * writer of the plot format, plot_json_write.c) writes it back. */
typedef struct cj_plot_json_curve {
    int spline;     /* 0: a "bezier" item, 1: a "catmull-rom" item */
    double *points; /* 2 * count coordinates (malloc'd, owned) */
    size_t count;
    double *weights; /* bezier: count weights (a rational curve, normalised so the largest is
                        in [1, 2)) or NULL; malloc'd, owned */
    cj_plot_bezier_opts bezier; /* colour and width of either kind; the rest for bezier only */
    cj_spline_options spline_options; /* catmull-rom: kind (not Kochanek-Bartels), tension,
                                         closed */
    int knots;                        /* catmull-rom: markers at the points */
    int bspline;         /* 1: a "bspline" item (spline is 0): a 2D B-spline, or a NURBS when
                            weights (count of them, kept as written) are given */
    int degree;          /* bspline: the degree */
    double *knot_vector; /* bspline: count + degree + 1 knots (malloc'd, owned) */
    cj_plot_bspline_opts bspline_opts; /* bspline: its drawing options */
} cj_plot_json_curve;

typedef struct cj_plot_json_page {
    int width, height; /* pixels, PLOT_JSON_MIN_SIDE..PLOT_JSON_MAX_SIDE (default 800 x 600) */
    cj_rgba background;
    int axes;      /* default 1 */
    double margin; /* pixels, default 12 */
    char *title;   /* malloc'd or NULL */
    int have_view; /* view[] = x0, y0, x1, y1 given */
    double view[4];
    size_t ncurves;
    cj_plot_json_curve *curves; /* malloc'd, owned */
} cj_plot_json_page;

/* Reads a single-plot document (named `name` in messages, as cj_plot_json_parse) whose items are
 * all "bezier", "catmull-rom" or 2D "bspline" (with the same checks and messages as
 * cj_plot_json_parse; a document with panels, a chart or another kind of item is refused, naming
 * it). Returns CJ_OK and fills *page (free with cj_plot_json_page_free), or a status as
 * cj_plot_json_parse's with nothing allocated and the reason in cj_last_error(). */
cj_status cj_plot_json_read_page(const char *name, const char *text, cj_plot_json_page *page);

void cj_plot_json_page_free(cj_plot_json_page *page);

/* One "bezier" item, `item` at `path` ("panels[0].items[3]"), of a document that a caller
 * reads with the JSON kit (doc: its name and lines, scene/src/json_read_internal.h) and edits
 * as a cJSON tree (the query commands, which add their answers to the document): read by the
 * one reader of that item, with its checks and messages, into *out (free with
 * cj_plot_json_curve_free; weights, when given, normalised as for the plot). Errors: those of
 * cj_plot_json_parse for the item. */
struct cj_json_doc;
struct cJSON;
cj_status cj_plot_json_read_bezier(const struct cj_json_doc *doc, const struct cJSON *item,
                                   const char *path, cj_plot_json_curve *out);
void cj_plot_json_curve_free(cj_plot_json_curve *k);

/* Draws curve k into plot as the plot reader does (cj_plot_add_bezier, _rbezier, _spline or
 * _bspline):
 * their status (cj_last_error explains a failure). */
cj_status cj_plot_json_curve_add(cj_plot *plot, const cj_plot_json_curve *k);

/* Writes page as a plot document with cJSON's printer, every number in the shortest form that
 * reads back to the same double, atomically (the old file stays whole on failure): what
 * cj_plot_json_read_page reads back bit-identical and `casteljau plot` draws. Errors:
 * CJ_ERR_UNSUPPORTED (a Kochanek-Bartels spline, which the format cannot describe; the message
 * names the curve), CJ_ERR_NOMEM, CJ_ERR_IO (naming path). */
cj_status cj_plot_json_write_page(const cj_plot_json_page *page, const char *path);

/* The document of `casteljau fit` for a curve: a plot with the title, the fitted B-spline item
 * and (2D data) the n data points as a "points" item, printed with cJSON onto f, numbers in
 * their shortest exact form. Errors: CJ_ERR_NOMEM, CJ_ERR_IO (the stream's error flag). */
cj_status cj_plot_json_print_fit(FILE *f, const cj_bspline *c, const double *data, int n,
                                 const char *title);

/* After cj_plot_doc_render failed: the JSON path of the panel ("panels[3]" or "the plot"). */
const char *cj_plot_doc_where(cj_plot_doc *doc);

#endif

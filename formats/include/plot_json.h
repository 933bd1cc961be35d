/* The plot document (formats/, library cj_formats; read by `casteljau plot`, the tests and the
 * fuzzer): the JSON plot description (format documented in plot_json.c
 * and the README) parsed with cJSON into cj_plot objects. */
#ifndef CASTELJAU_APP_PLOT_JSON_H
#define CASTELJAU_APP_PLOT_JSON_H

#include "casteljau/chart.h"
#include "casteljau/plot.h"
#include <stddef.h>

#define PLOT_JSON_MIN_SIDE   64
#define PLOT_JSON_MAX_SIDE   8192
#define PLOT_JSON_MAX_PANELS 64
/* Per-document work limits (plot_json.c explains the counting). */
#define PLOT_JSON_MAX_ITEMS  10000
#define PLOT_JSON_MAX_POINTS 1000000
#define PLOT_JSON_MAX_WORK   2e9
/* Largest JSON file read, in bytes. */
#define PLOT_JSON_MAX_BYTES ((size_t)64 << 20)

typedef struct plot_doc {
    int width, height; /* image size in pixels */
    cj_rgba background;
    int columns; /* panels per row */
    size_t npanels;
    cj_plot *panels[PLOT_JSON_MAX_PANELS];
    cj_chart *charts[PLOT_JSON_MAX_PANELS]; /* a chart panel ("kind": "chart"): panels[i] NULL */
    int single;                             /* the document is one plot (no "panels") */
    size_t failed;  /* set by plot_doc_render on failure: the panel that failed */
    char where[32]; /* plot_doc_where's text */
} plot_doc;

/* Parses a whole document. On success returns 0 and fills *doc (free with plot_doc_free). On
 * failure returns -1, leaves nothing allocated, and writes a one-line reason naming the JSON
 * path of the bad field ("items[2].points[3] is not a pair of numbers") to why. */
int plot_json_parse(const char *text, plot_doc *doc, char *why, size_t why_size);

void plot_doc_free(plot_doc *doc);

/* Renders every panel into fb (doc->width x doc->height), a grid of doc->columns columns.
 * font may be NULL. Returns CJ_OK or the first failing status (cj_last_error explains; the
 * panel is recorded for plot_doc_where). */
cj_status plot_doc_render(plot_doc *doc, cj_framebuffer *fb, cj_font *font);

/* After plot_doc_render failed: the JSON path of the panel ("panels[3]" or "the plot"). */
const char *plot_doc_where(plot_doc *doc);

#endif

/* Private to formats/: what the readers of the plot document share (plot_json.c: geometry
 * panels, chart_json.c: chart panels, plot_json_curve.c and plot_json_bspline.c: curve items).
 * JSON is checked with the one kit of the scene layer (json_read_internal.h, cj_json_*); this
 * file adds only what is the plot format's own: its colours, its palette, its point budget.
 * Every reader returns 0 on success, or nonzero after reporting through cj_fail a one-line
 * reason "<document>:<line>: <JSON path> ..." (cj_last_error). */
#ifndef CASTELJAU_APP_PLOT_JSON_INTERNAL_H
#define CASTELJAU_APP_PLOT_JSON_INTERNAL_H

#include "plot_json.h"

#include "json_read_internal.h"

#include <cJSON.h>
#include <stddef.h>

typedef struct pj_ctx {
    cj_json_doc doc; /* the document's name and the lines of its values, for messages */
    cj_json_lines lines;
    /* work counted against the document's limits (plot_json.h) */
    size_t items, points;
    double work;
} pj_ctx;

/* Fails at node (its line in the message) with CJ_ERR_PARSE: "<name>:<line>: <message>". */
#define pj_fail(c, node, ...) cj_json_fail(&(c)->doc, node, 0, CJ_ERR_PARSE, __VA_ARGS__)

/* A colour of the plot format ("#rgb", "#rrggbb", "#rrggbbaa" or a CSS name) at node v. */
int pj_parse_color(pj_ctx *c, const cJSON *v, const char *path, cj_rgba *out);
/* [[x, y], ...] with at least min_count points into a new array (caller frees); counted
 * against the document's PLOT_JSON_MAX_POINTS. */
int pj_parse_points(pj_ctx *c, const cJSON *v, const char *path, size_t min_count, double **out,
                    size_t *count);
/* Parses text, the document `name` (NULL: "<plot>"), into *root and readies c for reading it;
 * pj_close(c, root, rc) ends the reading and returns the status of the readers' result rc: 0 is
 * CJ_OK, a kit's status stays, -1 is CJ_ERR_PARSE (cj_last_error() is exact either way). */
cj_status pj_open(pj_ctx *c, const char *name, const char *text, cJSON **root);
cj_status pj_close(pj_ctx *c, cJSON *root, int rc);
/* The status of a reader's result rc, as pj_close returns it. */
cj_status pj_status(int rc);
/* After a library call refused what the document gave: fails at node with "path:
 * <cj_last_error()>" (CJ_ERR_PARSE: the document is refused). */
int pj_lib_fail(pj_ctx *c, const cJSON *node, const char *path);

/* An optional field: when obj has key, runs call with v_ (the value) and p_ (its JSON path)
 * and returns its status from the calling function if call fails; absent, nothing happens. */
#define PJ_OPT(obj, key, path, call)                                                               \
    do {                                                                                           \
        const cJSON *v_ = cJSON_GetObjectItemCaseSensitive(obj, key);                              \
        if (v_) {                                                                                  \
            char p_[CJ_JSON_PATH];                                                                 \
            cj_json_join(p_, path, key);                                                           \
            CJ_JSON_TRY(call);                                                                     \
        }                                                                                          \
    } while (0)

/* The default colour of item i (a palette of eight, by position). */
cj_rgba pj_palette(size_t i);

/* A "bezier" (spline 0) or "catmull-rom" (spline 1) item at path into *out (plot_json_curve.c;
 * free with pj_curve_free); color is its default colour. */
int pj_read_curve(pj_ctx *c, const cJSON *it, const char *path, int spline, cj_rgba color,
                  cj_plot_json_curve *out);
void pj_curve_free(cj_plot_json_curve *k);

/* A chart panel ("kind": "chart", format in chart_json.c) at path; extra_keys (NULL-terminated,
 * may be NULL) are also accepted (the document's own fields when the chart is the document). */
int cj_chart_json_parse(pj_ctx *c, const cJSON *obj, const char *path,
                        const char *const *extra_keys, cj_chart **out);

/* A 2D "bspline" item at path into *out (plot_json_bspline.c; free with pj_curve_free); color
 * is its default colour. */
int pj_read_bspline(pj_ctx *c, const cJSON *it, const char *path, cj_rgba color,
                    cj_plot_json_curve *out);
/* A "bspline" item read and drawn into plot. */
int pj_parse_bspline(pj_ctx *c, const cJSON *it, const char *path, cj_plot *plot, cj_rgba color);

#endif

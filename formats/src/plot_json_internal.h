/* Private to the casteljau tool: helpers shared by the JSON readers of `casteljau plot`
 * (plot_json.c: geometry panels, chart_json.c: chart panels). Every reader returns 0 on
 * success, or -1 after writing a one-line reason naming the JSON path into the context. */
#ifndef CASTELJAU_APP_PLOT_JSON_INTERNAL_H
#define CASTELJAU_APP_PLOT_JSON_INTERNAL_H

#include "plot_json.h"

#include <cJSON.h>
#include <stddef.h>

typedef struct pj_ctx {
    char *why;
    size_t why_size;
    /* work counted against the document's limits (plot_json.h) */
    size_t items, points;
    double work;
} pj_ctx;

#if defined(__GNUC__)
#define PJ_PRINTF(a, b) __attribute__((format(printf, a, b)))
#else
#define PJ_PRINTF(a, b)
#endif

int pj_fail(pj_ctx *c, const char *fmt, ...) PJ_PRINTF(2, 3);
void pj_pathf(char *buf, size_t size, const char *fmt, ...) PJ_PRINTF(3, 4);
/* Fails naming the first field of obj not in the NULL-terminated list allowed. */
int pj_check_keys(pj_ctx *c, const cJSON *obj, const char *path, const char *const *allowed);
int pj_parse_color(pj_ctx *c, const cJSON *v, const char *path, cj_rgba *out);
int pj_parse_number(pj_ctx *c, const cJSON *v, const char *path, double lo, double hi, double *out);
int pj_parse_int(pj_ctx *c, const cJSON *v, const char *path, int lo, int hi, int *out);
int pj_parse_bool(pj_ctx *c, const cJSON *v, const char *path, int *out);
/* A fixed-size array of count numbers. */
int pj_parse_numbers(pj_ctx *c, const cJSON *v, const char *path, int count, double *out);
/* [[x, y], ...] with at least min_count points into a new array (caller frees); counted
 * against PLOT_JSON_MAX_POINTS. */
int pj_parse_points(pj_ctx *c, const cJSON *v, const char *path, size_t min_count, double **out,
                    size_t *count);
/* Fails with "path: <cj_last_error()>". */
int pj_lib_fail(pj_ctx *c, const char *path);
const cJSON *pj_field(const cJSON *obj, const char *key);

/* An optional field: when obj has key, runs call with v_ (the value) and p_ (its JSON path)
 * and returns -1 from the calling function if call fails; absent, nothing happens. */
#define PJ_OPT(obj, key, path, call)                                                               \
    do {                                                                                           \
        const cJSON *v_ = pj_field(obj, key);                                                      \
        if (v_) {                                                                                  \
            char p_[300];                                                                          \
            pj_pathf(p_, sizeof p_, "%s.%s", path, key);                                           \
            if (call) return -1;                                                                   \
        }                                                                                          \
    } while (0)

/* The default colour of item i (a palette of eight, by position). */
cj_rgba pj_palette(size_t i);
/* "JSON syntax error at line L, column C" for the parse error at `at` in text. */
void pj_syntax_error(pj_ctx *c, const char *text, const char *at);

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

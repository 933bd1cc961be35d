/* Chart panels of the JSON plot description (raster/chart.h): a panel (or the whole document)
 * with "kind": "chart" instead of geometry items. Format (every field optional unless marked;
 * unknown fields are errors, reported with their JSON path):
 *   kind         "chart" (required for a chart; "plot" or absent = a geometry panel)
 *   title        string (at most CJ_CHART_MAX_TEXT = 256 bytes)
 *   x, y         axis objects: scale ("linear" | "log", default linear), title (string),
 *                range [lo, hi] (lo < hi; both > 0 on a log axis; default: fitted, whole
 *                decades on a log axis)
 *   legend       "upper right" (default) | "upper left" | "lower left" | "lower right" |
 *                "outside" (right of the plot area)
 *   series       required, 1..CJ_CHART_MAX_SERIES series: points [[x, y], ...] (required,
 *                >= 1; > 0 on log axes), label (legend entry; absent = none), color (default: the
 *                plot's palette of eight by position, pj_palette), line_width (px, 0..16,
 *                default 1.5; 0 = scatter), marker ("circle" default | "square" | "triangle" |
 *                "diamond" | "none"), marker_radius (px, (0, 16], default 4)
 *   annotations  [{at: [x, y] (required), text (required), color (default #404040)}, ...],
 *                at most CJ_CHART_MAX_NOTES
 * A chart panel must be at least 120 x 90 px (cj_chart_render). */
#include "plot_json_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static int parse_text(pj_ctx *c, const cJSON *v, const char *path, const char **out) {
    CJ_JSON_TRY(cj_json_string_at(&c->doc, v, path, out));
    if (strlen(*out) > CJ_CHART_MAX_TEXT)
        return pj_fail(c, v, "%s is longer than %d bytes", path, CJ_CHART_MAX_TEXT);
    return 0;
}

static int parse_axis(pj_ctx *c, const cJSON *ax, const char *path, int axis, cj_chart *ch) {
    static const char *const keys[] = {"scale", "title", "range", NULL};
    CJ_JSON_TRY(cj_json_object(&c->doc, ax, path, keys));
    char p[CJ_JSON_PATH];
    const cJSON *v;
    static const char *const scales[] = {"linear", "log", NULL};
    int log_scale = 0;
    CJ_JSON_TRY(cj_json_enum(&c->doc, ax, path, "scale", scales, &log_scale));
    const cj_chart_scale scale = log_scale ? CJ_CHART_LOG10 : CJ_CHART_LINEAR;
    const char *title = NULL;
    cj_json_join(p, path, "title");
    if ((v = cJSON_GetObjectItemCaseSensitive(ax, "title")))
        CJ_JSON_TRY(parse_text(c, v, p, &title));
    if (cj_chart_set_axis(ch, axis, scale, title)) return pj_lib_fail(c, ax, path);
    if ((v = cJSON_GetObjectItemCaseSensitive(ax, "range"))) {
        double r[2];
        cj_json_join(p, path, "range");
        CJ_JSON_TRY(cj_json_array_at(&c->doc, v, p, 2, r));
        if (scale == CJ_CHART_LOG10 && !(r[0] > 0))
            return pj_fail(c, v->child, "%s[0] = %g is not > 0 on a log axis", p, r[0]);
        if (cj_chart_set_range(ch, axis, r[0], r[1])) return pj_lib_fail(c, v, p);
    }
    return 0;
}

static int parse_series(pj_ctx *c, const cJSON *s, const char *path, size_t index, cj_chart *ch) {
    static const char *const keys[] = {"points", "label",         "color", "line_width",
                                       "marker", "marker_radius", NULL};
    static const char *const markers[] = {"none", "circle", "square", "triangle", "diamond", NULL};
    CJ_JSON_TRY(cj_json_object(&c->doc, s, path, keys));
    char p[CJ_JSON_PATH];
    const cJSON *v;
    cj_chart_series_opts o = {NULL, pj_palette(index), 1.5, CJ_MARKER_CIRCLE, 4.0};
    cj_json_join(p, path, "label");
    if ((v = cJSON_GetObjectItemCaseSensitive(s, "label")))
        CJ_JSON_TRY(parse_text(c, v, p, &o.label));
    cj_json_join(p, path, "color");
    if ((v = cJSON_GetObjectItemCaseSensitive(s, "color")))
        CJ_JSON_TRY(pj_parse_color(c, v, p, &o.color));
    cj_json_join(p, path, "line_width");
    if ((v = cJSON_GetObjectItemCaseSensitive(s, "line_width")))
        CJ_JSON_TRY(cj_json_number_at(&c->doc, v, p, CJ_JSON_IN, 0, 16, &o.line_width));
    cj_json_join(p, path, "marker_radius");
    if ((v = cJSON_GetObjectItemCaseSensitive(s, "marker_radius")))
        CJ_JSON_TRY(cj_json_number_at(&c->doc, v, p, CJ_JSON_IN, 0x1p-10, 16, &o.marker_radius));
    int marker = (int)o.marker;
    CJ_JSON_TRY(cj_json_enum(&c->doc, s, path, "marker", markers, &marker));
    o.marker = (cj_chart_marker)marker;
    if (o.marker == CJ_MARKER_NONE && o.line_width == 0)
        return pj_fail(c, s, "%s has line_width 0 and marker none: nothing to draw", path);
    const cJSON *pts = cJSON_GetObjectItemCaseSensitive(s, "points");
    if (!pts) return pj_fail(c, s, "%s has no points", path);
    cj_json_join(p, path, "points");
    double *xy = NULL;
    size_t n = 0;
    CJ_JSON_TRY(pj_parse_points(c, pts, p, 1, &xy, &n));
    double *x = malloc(2 * n * sizeof *x);
    if (!x) {
        free(xy);
        return cj_json_fail(&c->doc, pts, 0, CJ_ERR_NOMEM, "%s: out of memory", p);
    }
    for (size_t i = 0; i < n; ++i) x[i] = xy[2 * i], x[n + i] = xy[2 * i + 1];
    const int r = cj_chart_add_series(ch, x, x + n, n, &o) ? pj_lib_fail(c, s, path) : 0;
    free(x);
    free(xy);
    return r;
}

static int parse_note(pj_ctx *c, const cJSON *a, const char *path, cj_chart *ch) {
    static const char *const keys[] = {"at", "text", "color", NULL};
    CJ_JSON_TRY(cj_json_object(&c->doc, a, path, keys));
    char p[CJ_JSON_PATH];
    const cJSON *v;
    double at[2];
    const char *text = NULL;
    cj_rgba col = cj_rgba_make(0x40, 0x40, 0x40, 255);
    if (!(v = cJSON_GetObjectItemCaseSensitive(a, "at")))
        return pj_fail(c, a, "%s has no \"at\" point", path);
    cj_json_join(p, path, "at");
    CJ_JSON_TRY(cj_json_array_at(&c->doc, v, p, 2, at));
    if (!(v = cJSON_GetObjectItemCaseSensitive(a, "text")))
        return pj_fail(c, a, "%s has no text", path);
    cj_json_join(p, path, "text");
    CJ_JSON_TRY(parse_text(c, v, p, &text));
    if (!text[0]) return pj_fail(c, v, "%s is empty", p);
    cj_json_join(p, path, "color");
    if ((v = cJSON_GetObjectItemCaseSensitive(a, "color")))
        CJ_JSON_TRY(pj_parse_color(c, v, p, &col));
    return cj_chart_annotate(ch, at[0], at[1], text, col) ? pj_lib_fail(c, a, path) : 0;
}

int cj_chart_json_parse(pj_ctx *c, const cJSON *obj, const char *path,
                        const char *const *extra_keys, cj_chart **out) {
    static const char *const base[] = {"kind",   "title",  "x",          "y",
                                       "legend", "series", "annotations"};
    const char *keys[16];
    size_t nk = 0;
    for (size_t i = 0; i < sizeof base / sizeof base[0]; ++i) keys[nk++] = base[i];
    for (size_t i = 0; extra_keys && extra_keys[i] && nk < 15; ++i) keys[nk++] = extra_keys[i];
    keys[nk] = NULL;
    CJ_JSON_TRY(cj_json_object(&c->doc, obj, path, keys));
    cj_chart *ch = NULL;
    if (cj_chart_create(NULL, &ch)) return pj_lib_fail(c, obj, path);
    char p[CJ_JSON_PATH];
    const cJSON *v;
    int r = 0;
    const char *title = NULL;
    cj_json_join(p, path, "title");
    if (!r && (v = cJSON_GetObjectItemCaseSensitive(obj, "title")))
        r = parse_text(c, v, p, &title) || (cj_chart_set_title(ch, title) && pj_lib_fail(c, v, p));
    for (int a = 0; !r && a < 2; ++a) {
        cj_json_join(p, path, a ? "y" : "x");
        if ((v = cJSON_GetObjectItemCaseSensitive(obj, a ? "y" : "x")))
            r = parse_axis(c, v, p, a, ch);
    }
    if (!r && cJSON_GetObjectItemCaseSensitive(obj, "legend")) {
        static const char *const pos[] = {"upper right", "upper left", "lower left",
                                          "lower right", "outside",    NULL};
        int k = 0;
        r = cj_json_enum(&c->doc, obj, path, "legend", pos, &k) != CJ_OK;
        if (!r) cj_chart_set_legend(ch, (cj_chart_legend)k);
    }
    const cJSON *series = cJSON_GetObjectItemCaseSensitive(obj, "series");
    if (!r && (!series || !cJSON_IsArray(series) || cJSON_GetArraySize(series) < 1 ||
               cJSON_GetArraySize(series) > CJ_CHART_MAX_SERIES))
        r = pj_fail(c, series ? series : obj, "%s.series is not an array of 1 to %d series", path,
                    CJ_CHART_MAX_SERIES);
    size_t i = 0;
    for (const cJSON *s = series ? series->child : NULL; !r && s; s = s->next, ++i) {
        char sp[CJ_JSON_PATH];
        cj_json_join(sp, path, "series");
        cj_json_index(p, sp, i);
        r = parse_series(c, s, p, i, ch);
    }
    const cJSON *notes = cJSON_GetObjectItemCaseSensitive(obj, "annotations");
    if (!r && notes && (!cJSON_IsArray(notes) || cJSON_GetArraySize(notes) > CJ_CHART_MAX_NOTES))
        r = pj_fail(c, notes, "%s.annotations is not an array of at most %d notes", path,
                    CJ_CHART_MAX_NOTES);
    i = 0;
    for (const cJSON *a = notes ? notes->child : NULL; !r && a; a = a->next, ++i) {
        char ap[CJ_JSON_PATH];
        cj_json_join(ap, path, "annotations");
        cj_json_index(p, ap, i);
        r = parse_note(c, a, p, ch);
    }
    /* ranges now, so that a value <= 0 on a log axis is a parse error with a path */
    double lo[2], hi[2];
    if (!r && cj_chart_ranges(ch, lo, hi)) r = pj_lib_fail(c, obj, path);
    if (r) {
        cj_chart_destroy(ch);
        return r;
    }
    *out = ch;
    return 0;
}

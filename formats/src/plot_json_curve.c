/* The one reader of the plot format's editable curve items ("bezier" and "catmull-rom"; "bspline"
 * in plot_json_bspline.c) into
 * cj_plot_json_curve, used by the plot reader (plot_json.c, which draws them) and by the reader of
 * single-plot pages (cj_plot_json_read_page, the viewer's documents). Formats in plot_json.c. */
#include "plot_json_internal.h"

#include "weights.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

void pj_curve_free(cj_plot_json_curve *k) {
    free(k->points);
    free(k->weights);
    free(k->knot_vector);
    k->points = k->weights = k->knot_vector = NULL;
}

static int read_bezier_style(pj_ctx *c, const cJSON *it, const char *path, cj_plot_bezier_opts *o) {
    PJ_OPT(it, "color", path, pj_parse_color(c, v_, p_, &o->color));
    PJ_OPT(it, "width", path, pj_parse_number(c, v_, p_, 0.1, CJ_PLOT_MAX_WIDTH, &o->width));
    PJ_OPT(it, "control_polygon", path, pj_parse_bool(c, v_, p_, &o->control_polygon));
    PJ_OPT(it, "control_points", path, pj_parse_bool(c, v_, p_, &o->control_points));
    PJ_OPT(it, "hull", path, pj_parse_bool(c, v_, p_, &o->hull));
    PJ_OPT(it, "normals", path, pj_parse_bool(c, v_, p_, &o->normals));
    const cJSON *ct = pj_field(it, "construction_t");
    if (ct) {
        char p[300];
        pj_pathf(p, sizeof p, "%s.construction_t", path);
        if (pj_parse_number(c, ct, p, 0.0, 1.0, &o->construction_t)) return -1;
        o->construction = 1;
    }
    const cJSON *ft = pj_field(it, "frames_t");
    if (ft) {
        char p[300];
        pj_pathf(p, sizeof p, "%s.frames_t", path);
        if (!cJSON_IsArray(ft) || cJSON_GetArraySize(ft) > CJ_PLOT_MAX_FRAMES)
            return pj_fail(c, "%s is not an array of at most %d parameters", p, CJ_PLOT_MAX_FRAMES);
        for (const cJSON *e = ft->child; e; e = e->next) {
            char q[320];
            pj_pathf(q, sizeof q, "%s[%zu]", p, o->nframes);
            if (pj_parse_number(c, e, q, 0.0, 1.0, &o->frames_t[o->nframes])) return -1;
            ++o->nframes;
        }
    }
    return 0;
}

static int read_weights(pj_ctx *c, const cJSON *wv, const char *path, size_t n, double **out) {
    char p[300];
    pj_pathf(p, sizeof p, "%s.weights", path);
    double *w = NULL;
    int bad = 0;
    if (!cJSON_IsArray(wv) || (size_t)cJSON_GetArraySize(wv) != n)
        bad = pj_fail(c, "%s is not an array of %zu weights (one per point)", p, n);
    else if (!(w = malloc(n * sizeof *w)))
        bad = pj_fail(c, "%s: out of memory", p);
    else if (pj_parse_numbers(c, wv, p, (int)n, w))
        bad = -1;
    for (size_t i = 0; !bad && i < n; ++i)
        if (!(w[i] > 0)) bad = pj_fail(c, "%s[%zu] = %g is not a positive weight", p, i, w[i]);
    if (!bad && weights_normalize(w, n))
        bad = pj_fail(c, "%s: the weights span more than the double range", p);
    if (bad) {
        free(w);
        return -1;
    }
    *out = w;
    return 0;
}

static int read_bezier(pj_ctx *c, const cJSON *it, const char *path, cj_plot_json_curve *k) {
    static const char *const keys[] = {
        "type", "points",         "color",    "width",   "control_polygon", "control_points",
        "hull", "construction_t", "frames_t", "normals", "weights",         NULL};
    if (pj_check_keys(c, it, path, keys)) return -1;
    if (read_bezier_style(c, it, path, &k->bezier)) return -1;
    const cJSON *pv = pj_field(it, "points");
    if (!pv) return pj_fail(c, "%s: a bezier needs \"points\"", path);
    char p[300];
    pj_pathf(p, sizeof p, "%s.points", path);
    if (pj_parse_points(c, pv, p, 1, &k->points, &k->count)) return -1;
    if (k->count > (size_t)CJ_BEZIER_MAX_DEGREE + 1) {
        pj_fail(c, "%s has %zu points: the degree is at most %d", p, k->count,
                CJ_BEZIER_MAX_DEGREE);
        pj_curve_free(k);
        return -1;
    }
    const cJSON *wv = pj_field(it, "weights");
    if (wv && read_weights(c, wv, path, k->count, &k->weights)) {
        pj_curve_free(k);
        return -1;
    }
    return 0;
}

static int read_spline(pj_ctx *c, const cJSON *it, const char *path, cj_plot_json_curve *k) {
    static const char *const keys[] = {"type", "points", "color", "width", "tension",
                                       "kind", "closed", "knots", NULL};
    if (pj_check_keys(c, it, path, keys)) return -1;
    cj_spline_options *so = &k->spline_options;
    PJ_OPT(it, "color", path, pj_parse_color(c, v_, p_, &k->bezier.color));
    PJ_OPT(it, "width", path, pj_parse_number(c, v_, p_, 0.1, CJ_PLOT_MAX_WIDTH, &k->bezier.width));
    PJ_OPT(it, "tension", path, pj_parse_number(c, v_, p_, -10.0, 10.0, &so->tension));
    PJ_OPT(it, "closed", path, pj_parse_bool(c, v_, p_, &so->closed));
    PJ_OPT(it, "knots", path, pj_parse_bool(c, v_, p_, &k->knots));
    const cJSON *kv = pj_field(it, "kind");
    if (kv) {
        const char *s = cJSON_IsString(kv) ? kv->valuestring : "";
        if (!strcmp(s, "uniform"))
            so->kind = CJ_SPLINE_CATMULL_ROM;
        else if (!strcmp(s, "centripetal"))
            so->kind = CJ_SPLINE_CENTRIPETAL;
        else if (!strcmp(s, "chordal"))
            so->kind = CJ_SPLINE_CHORDAL;
        else
            return pj_fail(c, "%s.kind is not \"uniform\", \"centripetal\" or \"chordal\"", path);
    }
    const cJSON *pv = pj_field(it, "points");
    if (!pv) return pj_fail(c, "%s: a catmull-rom spline needs \"points\"", path);
    char p[300];
    pj_pathf(p, sizeof p, "%s.points", path);
    return pj_parse_points(c, pv, p, so->closed ? 3 : 2, &k->points, &k->count);
}

int pj_read_curve(pj_ctx *c, const cJSON *it, const char *path, int spline, cj_rgba color,
                  cj_plot_json_curve *out) {
    cj_plot_json_curve k;
    memset(&k, 0, sizeof k);
    k.spline = spline;
    k.bezier = cj_plot_bezier_defaults();
    k.bezier.color = color;
    k.spline_options = cj_spline_defaults();
    k.knots = 1;
    if (spline && read_spline(c, it, path, &k)) return -1;
    if (!spline && read_bezier(c, it, path, &k)) return -1;
    *out = k;
    return 0;
}

cj_status cj_plot_json_curve_add(cj_plot *plot, const cj_plot_json_curve *k) {
    if (k->bspline) {
        const cj_bspline b =
            cj_bspline_view(k->degree, 2, (int)k->count, k->points, k->weights, k->knot_vector);
        return cj_plot_add_bspline(plot, &b, &k->bspline_opts);
    }
    if (k->spline)
        return cj_plot_add_spline(plot, k->points, k->count, &k->spline_options, k->bezier.color,
                                  k->bezier.width, k->knots);
    if (k->weights) {
        cj_rbezier rb = cj_rbezier_view((int)k->count - 1, 2, k->points, k->weights);
        return cj_plot_add_rbezier(plot, &rb, &k->bezier);
    }
    cj_bezier b = cj_bezier_view((int)k->count - 1, 2, k->points);
    return cj_plot_add_bezier(plot, &b, &k->bezier);
}

/* ---- single-plot pages -------------------------------------------------------------------- */

void cj_plot_json_page_free(cj_plot_json_page *page) {
    for (size_t i = 0; i < page->ncurves; ++i) pj_curve_free(&page->curves[i]);
    free(page->curves);
    free(page->title);
    page->curves = NULL;
    page->title = NULL;
    page->ncurves = 0;
}

static int read_page(pj_ctx *c, const cJSON *root, cj_plot_json_page *page) {
    static const char *const keys[] = {"width",  "height", "background", "title", "axes",
                                       "margin", "view",   "items",      NULL};
    if (!cJSON_IsObject(root)) return pj_fail(c, "document is not a JSON object");
    if (pj_field(root, "panels")) return pj_fail(c, "document has panels: a page is a single plot");
    const cJSON *kind = pj_field(root, "kind");
    if (kind) return pj_fail(c, "document is a chart: a page is a plot of curves");
    if (pj_check_keys(c, root, "document", keys)) return -1;
    const cJSON *v;
    if ((v = pj_field(root, "width")) &&
        pj_parse_int(c, v, "width", PLOT_JSON_MIN_SIDE, PLOT_JSON_MAX_SIDE, &page->width))
        return -1;
    if ((v = pj_field(root, "height")) &&
        pj_parse_int(c, v, "height", PLOT_JSON_MIN_SIDE, PLOT_JSON_MAX_SIDE, &page->height))
        return -1;
    if ((v = pj_field(root, "background")) && pj_parse_color(c, v, "background", &page->background))
        return -1;
    if ((v = pj_field(root, "axes")) && pj_parse_bool(c, v, "axes", &page->axes)) return -1;
    if ((v = pj_field(root, "margin")) &&
        pj_parse_number(c, v, "margin", 0.0, 1000.0, &page->margin))
        return -1;
    if ((v = pj_field(root, "title"))) {
        if (!cJSON_IsString(v)) return pj_fail(c, "title is not a string");
        const size_t n = strlen(v->valuestring) + 1;
        if (!(page->title = malloc(n))) return pj_fail(c, "title: out of memory");
        memcpy(page->title, v->valuestring, n);
    }
    if ((v = pj_field(root, "view"))) {
        if (pj_parse_numbers(c, v, "view", 4, page->view)) return -1;
        if (!(page->view[0] < page->view[2] && page->view[1] < page->view[3]) ||
            !isfinite(page->view[2] - page->view[0]) || !isfinite(page->view[3] - page->view[1]))
            return pj_fail(c, "view is not [x0, y0, x1, y1] with x0 < x1 and y0 < y1");
        page->have_view = 1;
    }
    const cJSON *items = pj_field(root, "items");
    if (!items) return pj_fail(c, "document: missing \"items\" (the list of things to draw)");
    if (!cJSON_IsArray(items) || cJSON_GetArraySize(items) == 0)
        return pj_fail(c, "items is not a non-empty array of items");
    const size_t n = (size_t)cJSON_GetArraySize(items);
    if (n > PLOT_JSON_MAX_ITEMS)
        return pj_fail(c, "items: the document has more than %d items in all", PLOT_JSON_MAX_ITEMS);
    if (!(page->curves = calloc(n, sizeof *page->curves)))
        return pj_fail(c, "items: out of memory");
    size_t i = 0;
    for (const cJSON *it = items->child; it; it = it->next, ++i) {
        char ip[64];
        pj_pathf(ip, sizeof ip, "items[%zu]", i);
        const cJSON *t = cJSON_IsObject(it) ? pj_field(it, "type") : NULL;
        if (!t || !cJSON_IsString(t)) return pj_fail(c, "%s.type is missing or not a string", ip);
        const int spline = !strcmp(t->valuestring, "catmull-rom");
        if (!strcmp(t->valuestring, "bspline")) {
            if (pj_read_bspline(c, it, ip, pj_palette(i), &page->curves[i])) return -1;
            page->ncurves = i + 1;
            continue;
        }
        if (!spline && strcmp(t->valuestring, "bezier"))
            return pj_fail(c,
                           "%s is a '%s' item: a page holds bezier, catmull-rom and bspline "
                           "items only",
                           ip, t->valuestring);
        if (pj_read_curve(c, it, ip, spline, pj_palette(i), &page->curves[i])) return -1;
        page->ncurves = i + 1;
    }
    return 0;
}

int cj_plot_json_read_page(const char *text, cj_plot_json_page *page, char *why, size_t why_size) {
    pj_ctx c = {why, why_size, 0, 0, 0.0};
    memset(page, 0, sizeof *page);
    page->width = 800;
    page->height = 600;
    page->background = cj_rgba_make(255, 255, 255, 255);
    page->axes = 1;
    page->margin = 12.0;
    const char *end = NULL;
    cJSON *root = cJSON_ParseWithOpts(text, &end, 1);
    if (!root) {
        pj_syntax_error(&c, text, end ? end : cJSON_GetErrorPtr());
        return -1;
    }
    const int rc = read_page(&c, root, page);
    cJSON_Delete(root);
    if (rc) cj_plot_json_page_free(page);
    return rc;
}

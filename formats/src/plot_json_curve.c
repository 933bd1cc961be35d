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
    PJ_OPT(it, "width", path,
           cj_json_number_at(&c->doc, v_, p_, CJ_JSON_IN, 0.1, CJ_PLOT_MAX_WIDTH, &o->width));
    PJ_OPT(it, "control_polygon", path, cj_json_bool_at(&c->doc, v_, p_, &o->control_polygon));
    PJ_OPT(it, "control_points", path, cj_json_bool_at(&c->doc, v_, p_, &o->control_points));
    PJ_OPT(it, "hull", path, cj_json_bool_at(&c->doc, v_, p_, &o->hull));
    PJ_OPT(it, "normals", path, cj_json_bool_at(&c->doc, v_, p_, &o->normals));
    const cJSON *ct = cJSON_GetObjectItemCaseSensitive(it, "construction_t");
    if (ct) {
        char p[CJ_JSON_PATH];
        cj_json_join(p, path, "construction_t");
        CJ_JSON_TRY(cj_json_number_at(&c->doc, ct, p, CJ_JSON_IN, 0.0, 1.0, &o->construction_t));
        o->construction = 1;
    }
    const cJSON *ft = cJSON_GetObjectItemCaseSensitive(it, "frames_t");
    if (ft) {
        char p[CJ_JSON_PATH];
        cj_json_join(p, path, "frames_t");
        if (!cJSON_IsArray(ft) || cJSON_GetArraySize(ft) > CJ_PLOT_MAX_FRAMES)
            return pj_fail(c, ft, "%s is not an array of at most %d parameters", p,
                           CJ_PLOT_MAX_FRAMES);
        for (const cJSON *e = ft->child; e; e = e->next) {
            char q[CJ_JSON_PATH];
            cj_json_index(q, p, o->nframes);
            CJ_JSON_TRY(
                cj_json_number_at(&c->doc, e, q, CJ_JSON_IN, 0.0, 1.0, &o->frames_t[o->nframes]));
            ++o->nframes;
        }
    }
    return 0;
}

static int read_weights(pj_ctx *c, const cJSON *wv, const char *path, size_t n, double **out) {
    char p[CJ_JSON_PATH];
    cj_json_join(p, path, "weights");
    double *w = NULL;
    int bad = 0;
    if (!cJSON_IsArray(wv) || (size_t)cJSON_GetArraySize(wv) != n)
        bad = pj_fail(c, wv, "%s is not an array of %zu weights (one per point)", p, n);
    else if (!(w = malloc(n * sizeof *w)))
        bad = cj_json_fail(&c->doc, wv, 0, CJ_ERR_NOMEM, "%s: out of memory", p);
    else
        bad = cj_json_array_at(&c->doc, wv, p, (int)n, w);
    const cJSON *e = wv->child;
    for (size_t i = 0; !bad && i < n; ++i, e = e->next) {
        char q[CJ_JSON_PATH];
        cj_json_index(q, p, i);
        bad = cj_json_number_at(&c->doc, e, q, CJ_JSON_GT, 0.0, 0.0, &w[i]);
    }
    if (!bad && weights_normalize(w, n))
        bad = pj_fail(c, wv, "%s: the weights span more than the double range", p);
    if (bad) {
        free(w);
        return bad;
    }
    *out = w;
    return 0;
}

static int read_bezier(pj_ctx *c, const cJSON *it, const char *path, cj_plot_json_curve *k) {
    static const char *const keys[] = {
        "type", "points",         "color",    "width",   "control_polygon", "control_points",
        "hull", "construction_t", "frames_t", "normals", "weights",         NULL};
    CJ_JSON_TRY(cj_json_object(&c->doc, it, path, keys));
    CJ_JSON_TRY(read_bezier_style(c, it, path, &k->bezier));
    const cJSON *pv = cJSON_GetObjectItemCaseSensitive(it, "points");
    if (!pv) return pj_fail(c, it, "%s: a bezier needs \"points\"", path);
    char p[CJ_JSON_PATH];
    cj_json_join(p, path, "points");
    CJ_JSON_TRY(pj_parse_points(c, pv, p, 1, &k->points, &k->count));
    cj_status st = CJ_OK;
    if (k->count > (size_t)CJ_BEZIER_MAX_DEGREE + 1)
        st = cj_json_fail(&c->doc, pv, 0, CJ_ERR_RANGE,
                          "%s has %zu points: the degree is at most %d", p, k->count,
                          CJ_BEZIER_MAX_DEGREE);
    const cJSON *wv = cJSON_GetObjectItemCaseSensitive(it, "weights");
    if (!st && wv) st = read_weights(c, wv, path, k->count, &k->weights);
    if (st) {
        pj_curve_free(k);
        return st;
    }
    return 0;
}

static int read_spline(pj_ctx *c, const cJSON *it, const char *path, cj_plot_json_curve *k) {
    static const char *const keys[] = {"type", "points", "color", "width", "tension",
                                       "kind", "closed", "knots", NULL};
    CJ_JSON_TRY(cj_json_object(&c->doc, it, path, keys));
    cj_spline_options *so = &k->spline_options;
    PJ_OPT(it, "color", path, pj_parse_color(c, v_, p_, &k->bezier.color));
    PJ_OPT(
        it, "width", path,
        cj_json_number_at(&c->doc, v_, p_, CJ_JSON_IN, 0.1, CJ_PLOT_MAX_WIDTH, &k->bezier.width));
    PJ_OPT(it, "tension", path,
           cj_json_number_at(&c->doc, v_, p_, CJ_JSON_IN, -10.0, 10.0, &so->tension));
    PJ_OPT(it, "closed", path, cj_json_bool_at(&c->doc, v_, p_, &so->closed));
    PJ_OPT(it, "knots", path, cj_json_bool_at(&c->doc, v_, p_, &k->knots));
    static const char *const kinds[] = {"uniform", "centripetal", "chordal", NULL};
    static const cj_spline_kind kind_of[] = {CJ_SPLINE_CATMULL_ROM, CJ_SPLINE_CENTRIPETAL,
                                             CJ_SPLINE_CHORDAL};
    int kind = -1;
    CJ_JSON_TRY(cj_json_enum(&c->doc, it, path, "kind", kinds, &kind));
    if (kind >= 0) so->kind = kind_of[kind];
    const cJSON *pv = cJSON_GetObjectItemCaseSensitive(it, "points");
    if (!pv) return pj_fail(c, it, "%s: a catmull-rom spline needs \"points\"", path);
    char p[CJ_JSON_PATH];
    cj_json_join(p, path, "points");
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
    CJ_JSON_TRY(spline ? read_spline(c, it, path, &k) : read_bezier(c, it, path, &k));
    *out = k;
    return 0;
}

cj_status cj_plot_json_read_bezier(const cj_json_doc *doc, const cJSON *item, const char *path,
                                   cj_plot_json_curve *out) {
    pj_ctx c;
    memset(&c, 0, sizeof c);
    c.doc = *doc; /* the caller's document and line table, not freed here */
    memset(out, 0, sizeof *out);
    return pj_status(pj_read_curve(&c, item, path, 0, pj_palette(0), out));
}

void cj_plot_json_curve_free(cj_plot_json_curve *k) {
    pj_curve_free(k);
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
    if (!cJSON_IsObject(root)) return pj_fail(c, root, "document is not a JSON object");
    if (cJSON_GetObjectItemCaseSensitive(root, "panels"))
        return pj_fail(c, cJSON_GetObjectItemCaseSensitive(root, "panels"),
                       "document has panels: a page is a single plot");
    const cJSON *kind = cJSON_GetObjectItemCaseSensitive(root, "kind");
    if (kind) return pj_fail(c, kind, "document is a chart: a page is a plot of curves");
    CJ_JSON_TRY(cj_json_object(&c->doc, root, "document", keys));
    const cJSON *v;
    if ((v = cJSON_GetObjectItemCaseSensitive(root, "width")))
        CJ_JSON_TRY(cj_json_int_at(&c->doc, v, "width", PLOT_JSON_MIN_SIDE, PLOT_JSON_MAX_SIDE,
                                   &page->width));
    if ((v = cJSON_GetObjectItemCaseSensitive(root, "height")))
        CJ_JSON_TRY(cj_json_int_at(&c->doc, v, "height", PLOT_JSON_MIN_SIDE, PLOT_JSON_MAX_SIDE,
                                   &page->height));
    if ((v = cJSON_GetObjectItemCaseSensitive(root, "background")))
        CJ_JSON_TRY(pj_parse_color(c, v, "background", &page->background));
    if ((v = cJSON_GetObjectItemCaseSensitive(root, "axes")))
        CJ_JSON_TRY(cj_json_bool_at(&c->doc, v, "axes", &page->axes));
    if ((v = cJSON_GetObjectItemCaseSensitive(root, "margin")))
        CJ_JSON_TRY(
            cj_json_number_at(&c->doc, v, "margin", CJ_JSON_IN, 0.0, 1000.0, &page->margin));
    if ((v = cJSON_GetObjectItemCaseSensitive(root, "title"))) {
        const char *title = NULL;
        CJ_JSON_TRY(cj_json_string_at(&c->doc, v, "title", &title));
        const size_t n = strlen(title) + 1;
        if (!(page->title = malloc(n)))
            return cj_json_fail(&c->doc, v, 0, CJ_ERR_NOMEM, "title: out of memory");
        memcpy(page->title, title, n);
    }
    if ((v = cJSON_GetObjectItemCaseSensitive(root, "view"))) {
        CJ_JSON_TRY(cj_json_array_at(&c->doc, v, "view", 4, page->view));
        if (!(page->view[0] < page->view[2] && page->view[1] < page->view[3]) ||
            !isfinite(page->view[2] - page->view[0]) || !isfinite(page->view[3] - page->view[1]))
            return pj_fail(c, v, "view is not [x0, y0, x1, y1] with x0 < x1 and y0 < y1");
        page->have_view = 1;
    }
    const cJSON *items = cJSON_GetObjectItemCaseSensitive(root, "items");
    if (!items) return pj_fail(c, root, "document: missing \"items\" (the list of things to draw)");
    if (!cJSON_IsArray(items) || cJSON_GetArraySize(items) == 0)
        return pj_fail(c, items, "items is not a non-empty array of items");
    const size_t n = (size_t)cJSON_GetArraySize(items);
    if (n > PLOT_JSON_MAX_ITEMS)
        return pj_fail(c, items, "items: the document has more than %d items in all",
                       PLOT_JSON_MAX_ITEMS);
    if (!(page->curves = calloc(n, sizeof *page->curves)))
        return cj_json_fail(&c->doc, items, 0, CJ_ERR_NOMEM, "items: out of memory");
    size_t i = 0;
    for (const cJSON *it = items->child; it; it = it->next, ++i) {
        char ip[CJ_JSON_PATH];
        cj_json_index(ip, "items", i);
        const cJSON *t = cJSON_IsObject(it) ? cJSON_GetObjectItemCaseSensitive(it, "type") : NULL;
        if (!t || !cJSON_IsString(t))
            return pj_fail(c, t ? t : it, "%s.type is missing or not a string", ip);
        const int spline = !strcmp(t->valuestring, "catmull-rom");
        if (!strcmp(t->valuestring, "bspline")) {
            CJ_JSON_TRY(pj_read_bspline(c, it, ip, pj_palette(i), &page->curves[i]));
            page->ncurves = i + 1;
            continue;
        }
        if (!spline && strcmp(t->valuestring, "bezier"))
            return pj_fail(c, t,
                           "%s is a '%s' item: a page holds bezier, catmull-rom and bspline "
                           "items only",
                           ip, t->valuestring);
        CJ_JSON_TRY(pj_read_curve(c, it, ip, spline, pj_palette(i), &page->curves[i]));
        page->ncurves = i + 1;
    }
    return 0;
}

cj_status cj_plot_json_read_page(const char *name, const char *text, cj_plot_json_page *page) {
    memset(page, 0, sizeof *page);
    page->width = 800;
    page->height = 600;
    page->background = cj_rgba_make(255, 255, 255, 255);
    page->axes = 1;
    page->margin = 12.0;
    pj_ctx c;
    cJSON *root = NULL;
    CJ_JSON_TRY(pj_open(&c, name, text, &root));
    const int rc = read_page(&c, root, page);
    if (rc) cj_plot_json_page_free(page);
    return pj_close(&c, root, rc);
}

/* The JSON plot description, parsed with cJSON (the library never sees JSON: its public API is
 * cj_plot_* in casteljau/plot.h; the file format is a property of the command-line tool).
 *
 * Document (every field optional unless marked; unknown fields are errors):
 *   width, height    image size in pixels, 64..8192 (default 800 x 600; --width/--height win)
 *   background       colour of the image and of every panel ("#fff", "#ffffff", "#ffffff80")
 *   title, axes, margin, view, items   a single plot (see "panel" below), or
 *   panels           [panel, ...]: several plots in a grid of `columns` (default
 *                    ceil(sqrt(count))) columns, filled left to right, top to bottom
 *   kind: "chart"    the document, or any entry of panels, may instead be a data chart with
 *                    log/linear axes, series with markers, legend and annotations: its format
 *                    is documented in chart_json.c (raster/chart.h draws it)
 * Panel:
 *   title            string drawn above the plot (at most CJ_PLOT_MAX_TITLE = 1024 bytes)
 *   axes             true/false: frame, grid, ticks and numeric labels (default true)
 *   margin           pixels of blank border (default 12)
 *   view             [x0, y0, x1, y1] data box to show (default: fitted to the items)
 *   items  required  [item, ...] drawn in order
 * Item (all: "type" required, "color" (default: a palette by position), "width" px):
 *   "bezier"       points [[x,y],...] (>= 1, any degree), weights [w,...] (optional, one
 *                  per point, > 0: a rational curve), control_polygon (true),
 *                  control_points (true), hull (false), construction_t (t in [0,1]: draw the
 *                  de Casteljau construction), frames_t ([t,...]: tangent arrows), normals
 *                  (true: normal arrows with the tangents)
 *   "catmull-rom"  points (>= 2), tension (0.5), kind ("uniform" | "centripetal" |
 *                  "chordal"), closed (false), knots (true: markers at the points)
 *   "implicit"     exactly one of circle [cx,cy,r], ellipse [cx,cy,rx,ry,rot_radians],
 *                  line [a,b,c] (a x + b y + c = 0), poly {"degree": n, "coef": [...]}
 *                  (graded order 1, x, y, x², xy, y², ...); box [x0,y0,x1,y1] (required for
 *                  line and poly; default: the circle's/ellipse's bounding square + 10 %),
 *                  grid (cells per side, default 64)
 *   "bspline"      degree, points, knots (default clamped uniform), weights (optional: a
 *                  NURBS), control_polygon, control_points, knot_markers (all true): drawn as
 *                  its Bézier pieces (plot_json_bspline.c, format in bspline_json.h)
 *   "polyline"     points (>= 2), closed (false), markers (false)
 *   "points"       points (>= 1), radius (4 px)
 * Limits per document (so that any file is rendered in seconds): PLOT_JSON_MAX_ITEMS items,
 * PLOT_JSON_MAX_POINTS points, and PLOT_JSON_MAX_WORK for the implicit curves, counted as
 * (grid + 1)^2 times the number of terms (3 for circle, ellipse, line; (n+1)(n+2)/2 for a
 * degree-n poly); above them the document is refused naming the item that crossed them.
 */
#include "plot_json_internal.h"

#include <cJSON.h>

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* "bezier" and "catmull-rom" items: read by the one curve reader (plot_json_curve.c). */
static int parse_curve(pj_ctx *c, const cJSON *it, const char *path, cj_plot *plot, int spline,
                       cj_rgba color) {
    cj_plot_json_curve k;
    CJ_JSON_TRY(pj_read_curve(c, it, path, spline, color, &k));
    const cj_status st = cj_plot_json_curve_add(plot, &k);
    pj_curve_free(&k);
    return st ? pj_lib_fail(c, it, path) : 0;
}

static int parse_implicit(pj_ctx *c, const cJSON *it, const char *path, cj_plot *plot,
                          cj_rgba color) {
    static const char *const keys[] = {"type", "color", "width", "circle", "ellipse",
                                       "line", "poly",  "box",   "grid",   NULL};
    CJ_JSON_TRY(cj_json_object(&c->doc, it, path, keys));
    double width = 2.5;
    int grid = 64;
    PJ_OPT(it, "color", path, pj_parse_color(c, v_, p_, &color));
    PJ_OPT(it, "width", path,
           cj_json_number_at(&c->doc, v_, p_, CJ_JSON_IN, 0.1, CJ_PLOT_MAX_WIDTH, &width));
    PJ_OPT(it, "grid", path, cj_json_int_at(&c->doc, v_, p_, 4, 1024, &grid));
    const char *kinds[] = {"circle", "ellipse", "line", "poly"};
    int which = -1;
    for (int k = 0; k < 4; ++k)
        if (cJSON_GetObjectItemCaseSensitive(it, kinds[k])) {
            if (which >= 0)
                return pj_fail(c, cJSON_GetObjectItemCaseSensitive(it, kinds[k]),
                               "%s has both \"%s\" and \"%s\": give exactly one curve", path,
                               kinds[which], kinds[k]);
            which = k;
        }
    if (which < 0)
        return pj_fail(c, it,
                       "%s: an implicit item needs one of \"circle\", \"ellipse\", \"line\", "
                       "\"poly\"",
                       path);
    char p[CJ_JSON_PATH];
    cj_json_join(p, path, kinds[which]);
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(it, kinds[which]);
    cj_implicit_shape shape;
    cj_implicit f;
    double box[4], a[5];
    int have_box = 0;
    double *coef = NULL;
    cj_status st = CJ_OK;
    const cJSON *bv = cJSON_GetObjectItemCaseSensitive(it, "box");
    if (bv) {
        char q[CJ_JSON_PATH];
        cj_json_join(q, path, "box");
        CJ_JSON_TRY(cj_json_array_at(&c->doc, bv, q, 4, box));
        if (!(box[0] < box[2] && box[1] < box[3]))
            return pj_fail(c, bv, "%s is not [x0, y0, x1, y1] with x0 < x1 and y0 < y1", q);
        have_box = 1;
    }
    switch (which) {
    case 0:
        CJ_JSON_TRY(cj_json_array_at(&c->doc, v, p, 3, a));
        if (!(a[2] > 0)) return pj_fail(c, v, "%s: the radius %g is not positive", p, a[2]);
        st = cj_implicit_circle(a[0], a[1], a[2], &shape, &f);
        if (!have_box) {
            const double r = 1.1 * a[2];
            box[0] = a[0] - r, box[1] = a[1] - r, box[2] = a[0] + r, box[3] = a[1] + r;
        }
        break;
    case 1:
        CJ_JSON_TRY(cj_json_array_at(&c->doc, v, p, 5, a));
        if (!(a[2] > 0 && a[3] > 0))
            return pj_fail(c, v, "%s: the radii %g, %g are not positive", p, a[2], a[3]);
        st = cj_implicit_ellipse(a[0], a[1], a[2], a[3], a[4], &shape, &f);
        if (!have_box) {
            const double r = 1.1 * fmax(a[2], a[3]);
            box[0] = a[0] - r, box[1] = a[1] - r, box[2] = a[0] + r, box[3] = a[1] + r;
        }
        break;
    case 2:
        CJ_JSON_TRY(cj_json_array_at(&c->doc, v, p, 3, a));
        if (!have_box) return pj_fail(c, it, "%s: a \"line\" needs a \"box\" to be drawn in", path);
        st = cj_implicit_line(a[0], a[1], a[2], &shape, &f);
        break;
    default: {
        static const char *const pkeys[] = {"degree", "coef", NULL};
        CJ_JSON_TRY(cj_json_object(&c->doc, v, p, pkeys));
        int degree = 0;
        char q[CJ_JSON_PATH];
        cj_json_join(q, p, "degree");
        const cJSON *dv = NULL;
        CJ_JSON_TRY(cj_json_require(&c->doc, v, p, "degree", &dv));
        CJ_JSON_TRY(cj_json_int_at(&c->doc, dv, q, 1, 32, &degree));
        size_t nc = cj_implicit_poly_ncoef(degree);
        cj_json_join(q, p, "coef");
        const cJSON *cv = cJSON_GetObjectItemCaseSensitive(v, "coef");
        if (!cv || !cJSON_IsArray(cv) || (size_t)cJSON_GetArraySize(cv) != nc)
            return pj_fail(c, cv ? cv : v, "%s is not an array of %zu numbers (degree %d)", q, nc,
                           degree);
        coef = malloc(nc * sizeof *coef);
        if (!coef) return cj_json_fail(&c->doc, cv, 0, CJ_ERR_NOMEM, "%s: out of memory", q);
        st = cj_json_array_at(&c->doc, cv, q, (int)nc, coef);
        if (st) {
            free(coef);
            return st;
        }
        if (!have_box) {
            free(coef);
            return pj_fail(c, it, "%s: a \"poly\" needs a \"box\" to be drawn in", path);
        }
        st = cj_implicit_poly(degree, coef, &shape, &f);
        break;
    }
    }
    /* Contouring samples the grid's corners (and refines the crossings): the cost is the
     * grid area times the cost of one evaluation, about the number of terms. */
    const double terms = which == 3 && !st ? (double)cj_implicit_poly_ncoef(shape.degree) : 3.0;
    c->work += (double)(grid + 1) * (double)(grid + 1) * terms;
    if (!st && c->work > PLOT_JSON_MAX_WORK) {
        free(coef);
        return pj_fail(c, it,
                       "%s: the document's implicit curves need more than %.0e evaluations of "
                       "terms in all (grid^2 x terms; lower \"grid\" or the degree)",
                       path, PLOT_JSON_MAX_WORK);
    }
    if (!st) st = cj_plot_add_implicit(plot, &f, box, grid, color, width);
    free(coef);
    return st ? pj_lib_fail(c, it, path) : 0;
}

static int parse_polyline(pj_ctx *c, const cJSON *it, const char *path, cj_plot *plot,
                          cj_rgba color, int points_only) {
    static const char *const lkeys[] = {"type",   "points",  "color", "width",
                                        "closed", "markers", NULL};
    static const char *const pkeys[] = {"type", "points", "color", "radius", NULL};
    CJ_JSON_TRY(cj_json_object(&c->doc, it, path, points_only ? pkeys : lkeys));
    double width = points_only ? 4.0 : 2.0;
    int closed = 0, markers = 0;
    PJ_OPT(it, "color", path, pj_parse_color(c, v_, p_, &color));
    PJ_OPT(it, points_only ? "radius" : "width", path,
           cj_json_number_at(&c->doc, v_, p_, CJ_JSON_IN, 0.1, CJ_PLOT_MAX_WIDTH, &width));
    if (!points_only) {
        PJ_OPT(it, "closed", path, cj_json_bool_at(&c->doc, v_, p_, &closed));
        PJ_OPT(it, "markers", path, cj_json_bool_at(&c->doc, v_, p_, &markers));
    }
    const cJSON *pv = cJSON_GetObjectItemCaseSensitive(it, "points");
    if (!pv)
        return pj_fail(c, it, "%s: a %s needs \"points\"", path,
                       points_only ? "points item" : "polyline");
    char p[CJ_JSON_PATH];
    cj_json_join(p, path, "points");
    double *pts = NULL;
    size_t n = 0;
    CJ_JSON_TRY(pj_parse_points(c, pv, p, points_only ? 1 : 2, &pts, &n));
    cj_status st = points_only ? cj_plot_add_points(plot, pts, n, color, width)
                               : cj_plot_add_polyline(plot, pts, n, closed, color, width, markers);
    free(pts);
    return st ? pj_lib_fail(c, it, path) : 0;
}

/* One plot from an object holding title/axes/margin/view/background/items. `prefix` is the
 * JSON path of the object ("" for the document itself). */
static int parse_panel(pj_ctx *c, const cJSON *obj, const char *prefix, cj_rgba background,
                       cj_plot **out) {
    cj_plot *plot = NULL;
    if (cj_plot_create(NULL, &plot)) return pj_lib_fail(c, obj, *prefix ? prefix : "document");
    cj_plot_set_background(plot, background);
    const char *path = *prefix ? prefix : "document";
    int axes = 1;
    double margin = 12.0;
    const cJSON *v;
    int r = 0; /* the status of a failure, returned after the plot is freed */
#define PFAIL                                                                                      \
    do {                                                                                           \
        cj_plot_destroy(plot);                                                                     \
        return r;                                                                                  \
    } while (0)
    char p[CJ_JSON_PATH];
    if ((v = cJSON_GetObjectItemCaseSensitive(obj, "axes"))) {
        cj_json_join(p, prefix, "axes");
        if ((r = cj_json_bool_at(&c->doc, v, p, &axes))) PFAIL;
    }
    cj_plot_set_axes(plot, axes);
    if ((v = cJSON_GetObjectItemCaseSensitive(obj, "margin"))) {
        cj_json_join(p, prefix, "margin");
        if ((r = cj_json_number_at(&c->doc, v, p, CJ_JSON_IN, 0.0, 1000.0, &margin))) PFAIL;
    }
    cj_plot_set_margin(plot, margin);
    if ((v = cJSON_GetObjectItemCaseSensitive(obj, "title"))) {
        cj_json_join(p, prefix, "title");
        const char *title = NULL;
        if ((r = cj_json_string_at(&c->doc, v, p, &title))) PFAIL;
        if (cj_plot_set_title(plot, title)) {
            r = pj_lib_fail(c, v, p);
            PFAIL;
        }
    }
    if ((v = cJSON_GetObjectItemCaseSensitive(obj, "view"))) {
        double b[4];
        cj_json_join(p, prefix, "view");
        if ((r = cj_json_array_at(&c->doc, v, p, 4, b))) PFAIL;
        if (cj_plot_set_view(plot, b[0], b[1], b[2], b[3])) {
            r = pj_lib_fail(c, v, p);
            PFAIL;
        }
    }
    const cJSON *items = cJSON_GetObjectItemCaseSensitive(obj, "items");
    cj_json_join(p, prefix, "items");
    if (!items) {
        r = pj_fail(c, obj, "%s: missing \"items\" (the list of things to draw)", path);
        PFAIL;
    }
    if (!cJSON_IsArray(items) || cJSON_GetArraySize(items) == 0) {
        r = pj_fail(c, items, "%s is not a non-empty array of items", p);
        PFAIL;
    }
    size_t i = 0;
    for (const cJSON *it = items->child; it; it = it->next, ++i) {
        char ip[CJ_JSON_PATH];
        cj_json_index(ip, p, i);
        if (!cJSON_IsObject(it)) {
            r = pj_fail(c, it, "%s is not an object, but %s", ip, cj_json_type_name(it));
            PFAIL;
        }
        const cJSON *t = cJSON_GetObjectItemCaseSensitive(it, "type");
        if (!t || !cJSON_IsString(t)) {
            r = pj_fail(c, t ? t : it,
                        "%s.type is missing or not a string (bezier, bspline, catmull-rom, "
                        "implicit, polyline, points)",
                        ip);
            PFAIL;
        }
        if (++c->items > PLOT_JSON_MAX_ITEMS) {
            r = pj_fail(c, it, "%s: the document has more than %d items in all", ip,
                        PLOT_JSON_MAX_ITEMS);
            PFAIL;
        }
        cj_rgba color = pj_palette(i);
        if (!strcmp(t->valuestring, "bezier"))
            r = parse_curve(c, it, ip, plot, 0, color);
        else if (!strcmp(t->valuestring, "catmull-rom"))
            r = parse_curve(c, it, ip, plot, 1, color);
        else if (!strcmp(t->valuestring, "implicit"))
            r = parse_implicit(c, it, ip, plot, color);
        else if (!strcmp(t->valuestring, "polyline"))
            r = parse_polyline(c, it, ip, plot, color, 0);
        else if (!strcmp(t->valuestring, "points"))
            r = parse_polyline(c, it, ip, plot, color, 1);
        else if (!strcmp(t->valuestring, "bspline"))
            r = pj_parse_bspline(c, it, ip, plot, color);
        else
            r = pj_fail(c, t,
                        "%s.type '%s' is not bezier, bspline, catmull-rom, implicit, polyline or "
                        "points",
                        ip, t->valuestring);
        if (r) PFAIL;
    }
#undef PFAIL
    *out = plot;
    return 0;
}

void cj_plot_doc_free(cj_plot_doc *doc) {
    for (size_t i = 0; i < doc->npanels; ++i) {
        cj_plot_destroy(doc->panels[i]);
        cj_chart_destroy(doc->charts[i]);
    }
    doc->npanels = 0;
}

/* Work of the implicit items of one panel object, added to *work; fails naming the item at
 * which the document's total crosses PLOT_JSON_MAX_WORK. Run over the whole document before
 * anything is contoured, so that a document over the limit costs nothing. Malformed fields
 * are left to the real parse (they count with their defaults here). */
static int prescan_work(pj_ctx *c, const cJSON *panel, const char *prefix, double *work) {
    const cJSON *items = cJSON_GetObjectItemCaseSensitive(panel, "items");
    if (!items || !cJSON_IsArray(items)) return 0;
    size_t i = 0;
    for (const cJSON *it = items->child; it; it = it->next, ++i) {
        const cJSON *t = cJSON_GetObjectItemCaseSensitive(it, "type");
        if (!t || !cJSON_IsString(t) || strcmp(t->valuestring, "implicit")) continue;
        const cJSON *g = cJSON_GetObjectItemCaseSensitive(it, "grid"),
                    *poly = cJSON_GetObjectItemCaseSensitive(it, "poly");
        const double grid = g && cJSON_IsNumber(g) && g->valuedouble >= 4 && g->valuedouble <= 1024
                                ? floor(g->valuedouble)
                                : 64.0;
        double terms = 3.0;
        const cJSON *deg = poly ? cJSON_GetObjectItemCaseSensitive(poly, "degree") : NULL;
        if (deg && cJSON_IsNumber(deg) && deg->valuedouble >= 1 && deg->valuedouble <= 32)
            terms = (double)cj_implicit_poly_ncoef((int)deg->valuedouble);
        *work += (grid + 1) * (grid + 1) * terms;
        if (*work > PLOT_JSON_MAX_WORK)
            return pj_fail(c, it,
                           "%s%sitems[%zu]: the document's implicit curves need more than %.0e "
                           "evaluations of terms in all (grid^2 x terms; lower \"grid\" or the "
                           "degree)",
                           prefix, *prefix ? "." : "", i, PLOT_JSON_MAX_WORK);
    }
    return 0;
}

/* "kind": "chart" (chart_json.c); anything else is read as a geometry panel. */
static int is_chart(const cJSON *obj) {
    const cJSON *k = cJSON_GetObjectItemCaseSensitive(obj, "kind");
    return k && cJSON_IsString(k) && !strcmp(k->valuestring, "chart");
}

cj_status cj_plot_json_parse(const char *name, const char *text, cj_plot_doc *doc) {
    memset(doc, 0, sizeof *doc);
    pj_ctx c;
    cJSON *root = NULL;
    CJ_JSON_TRY(pj_open(&c, name, text, &root));
    int rc = -1; /* a failure's status (-1: CJ_ERR_PARSE), 0 once the document is read */
    static const char *const single[] = {"width",  "height", "background", "title", "axes",
                                         "margin", "view",   "items",      NULL};
    static const char *const multi[] = {"width", "height", "background", "columns", "panels", NULL};
    static const char *const panel_keys[] = {"title", "axes", "margin", "view", "items", NULL};
    const cJSON *panels = NULL, *v;
    int w = 800, h = 600;
    doc->background = cj_rgba_make(255, 255, 255, 255);
    if (!cJSON_IsObject(root)) {
        rc = pj_fail(&c, root, "document is not a JSON object, but %s", cj_json_type_name(root));
        goto done;
    }
    panels = cJSON_GetObjectItemCaseSensitive(root, "panels");
    if (!panels && is_chart(root)) { /* the whole document is one chart */
        static const char *const doc_keys[] = {"width", "height", "background", NULL};
        if ((rc = cj_chart_json_parse(&c, root, "document", doc_keys, &doc->charts[0]))) goto done;
        doc->npanels = 1;
    }
    if (!doc->npanels && (rc = cj_json_object(&c.doc, root, "document", panels ? multi : single)))
        goto done;
    if ((v = cJSON_GetObjectItemCaseSensitive(root, "width")) &&
        (rc = cj_json_int_at(&c.doc, v, "width", PLOT_JSON_MIN_SIDE, PLOT_JSON_MAX_SIDE, &w)))
        goto done;
    if ((v = cJSON_GetObjectItemCaseSensitive(root, "height")) &&
        (rc = cj_json_int_at(&c.doc, v, "height", PLOT_JSON_MIN_SIDE, PLOT_JSON_MAX_SIDE, &h)))
        goto done;
    if ((v = cJSON_GetObjectItemCaseSensitive(root, "background")) &&
        (rc = pj_parse_color(&c, v, "background", &doc->background)))
        goto done;
    doc->width = w;
    doc->height = h;
    {
        double work = 0.0;
        if (panels && cJSON_IsArray(panels)) {
            int k = 0;
            for (const cJSON *pn = panels->child; pn; pn = pn->next, ++k) {
                char p[CJ_JSON_PATH];
                cj_json_index(p, "panels", (size_t)k);
                if (cJSON_IsObject(pn) && (rc = prescan_work(&c, pn, p, &work))) goto done;
            }
        } else if (!panels && (rc = prescan_work(&c, root, "", &work))) {
            goto done;
        }
    }
    if (panels) {
        if (!cJSON_IsArray(panels) || cJSON_GetArraySize(panels) == 0 ||
            cJSON_GetArraySize(panels) > PLOT_JSON_MAX_PANELS) {
            rc = pj_fail(&c, panels, "panels is not an array of 1 to %d panels",
                         PLOT_JSON_MAX_PANELS);
            goto done;
        }
        int n = cJSON_GetArraySize(panels);
        doc->columns = (int)ceil(sqrt((double)n));
        if ((v = cJSON_GetObjectItemCaseSensitive(root, "columns")) &&
            (rc = cj_json_int_at(&c.doc, v, "columns", 1, n, &doc->columns)))
            goto done;
        int i = 0;
        for (const cJSON *pn = panels->child; pn; pn = pn->next, ++i) {
            char p[CJ_JSON_PATH];
            cj_json_index(p, "panels", (size_t)i);
            if (!cJSON_IsObject(pn)) {
                rc = pj_fail(&c, pn, "%s is not an object, but %s", p, cj_json_type_name(pn));
                goto done;
            }
            if (is_chart(pn)) {
                if ((rc = cj_chart_json_parse(&c, pn, p, NULL, &doc->charts[doc->npanels])))
                    goto done;
                doc->npanels++;
                continue;
            }
            if ((rc = cj_json_object(&c.doc, pn, p, panel_keys))) goto done;
            if ((rc = parse_panel(&c, pn, p, doc->background, &doc->panels[doc->npanels])))
                goto done;
            doc->npanels++;
        }
    } else if (doc->npanels == 1) { /* a chart document, parsed above */
        doc->columns = 1;
        doc->single = 1;
    } else {
        doc->columns = 1;
        doc->single = 1;
        if ((rc = parse_panel(&c, root, "", doc->background, &doc->panels[0]))) goto done;
        doc->npanels = 1;
    }
    rc = 0;
done:
    if (rc) cj_plot_doc_free(doc);
    return pj_close(&c, root, rc);
}

const char *cj_plot_doc_where(cj_plot_doc *doc) {
    if (doc->single)
        snprintf(doc->where, sizeof doc->where, "the plot");
    else
        snprintf(doc->where, sizeof doc->where, "panels[%zu]", doc->failed);
    return doc->where;
}

cj_status cj_plot_doc_render(cj_plot_doc *doc, cj_framebuffer *fb, cj_font *font) {
    cj_framebuffer_clear(fb, doc->background);
    const int cols = doc->columns > 0 ? doc->columns : 1;
    const int rows = (int)((doc->npanels + (size_t)cols - 1) / (size_t)cols);
    for (size_t i = 0; i < doc->npanels; ++i) {
        const int col = (int)(i % (size_t)cols), row = (int)(i / (size_t)cols);
        /* Exact integer split of the image; row 0 of the grid is at the top (y up). */
        const int x0 = col * fb->width / cols, x1 = (col + 1) * fb->width / cols;
        const int ytop = fb->height - row * fb->height / rows;
        const int ybot = fb->height - (row + 1) * fb->height / rows;
        cj_status st =
            doc->charts[i]
                ? cj_chart_render(doc->charts[i], fb, x0, ybot, x1 - x0, ytop - ybot, font)
                : cj_plot_render(doc->panels[i], fb, x0, ybot, x1 - x0, ytop - ybot, font);
        if (st) {
            doc->failed = i;
            return st;
        }
    }
    return CJ_OK;
}

/* The "bspline" item of the plot JSON: a B-spline or NURBS curve drawn as its Bézier pieces,
 * with its control polygon and markers at the knots. Fields (bspline_json.h): degree, points,
 * knots (optional), weights (optional); drawing: color, width (2.5), control_polygon (true),
 * control_points (true), knot_markers (true: a disc on the curve at every distinct knot of the
 * domain, so the pieces can be told apart), drawn by cj_plot_add_bspline (the viewer draws its
 * B-splines through the same call). */
#include "bspline_json.h"
#include "plot_json_internal.h"

#include <string.h>

int pj_read_bspline(pj_ctx *c, const cJSON *it, const char *path, cj_rgba color,
                    cj_plot_json_curve *out) {
    static const char *const extra[] = {"color",          "width",        "control_polygon",
                                        "control_points", "knot_markers", NULL};
    cj_bsp_json b;
    const cj_status st =
        cj_bsp_json_parse(&c->doc, it, path, extra, PLOT_JSON_MAX_POINTS - c->points, &b);
    if (st) return st;
    cj_plot_bspline_opts o = cj_plot_bspline_defaults();
    o.color = color;
    int r = 0;
    const cJSON *v;
    char p[CJ_JSON_PATH];
#define BOPT(key, call)                                                                            \
    if (!r && (v = cJSON_GetObjectItemCaseSensitive(it, key))) {                                   \
        cj_json_join(p, path, key);                                                                \
        r = call;                                                                                  \
    }
    BOPT("color", pj_parse_color(c, v, p, &o.color));
    BOPT("width", cj_json_number_at(&c->doc, v, p, CJ_JSON_IN, 0.1, CJ_PLOT_MAX_WIDTH, &o.width));
    BOPT("control_polygon", cj_json_bool_at(&c->doc, v, p, &o.control_polygon));
    BOPT("control_points", cj_json_bool_at(&c->doc, v, p, &o.control_points));
    BOPT("knot_markers", cj_json_bool_at(&c->doc, v, p, &o.knot_markers));
#undef BOPT
    if (!r && b.dim != 2)
        r = pj_fail(c, cJSON_GetObjectItemCaseSensitive(it, "points"),
                    "%s.points: a plotted B-spline needs 2D points, not %d coordinates", path,
                    b.dim);
    if (r) {
        cj_bsp_json_free(&b);
        return r;
    }
    c->points += (size_t)b.npts;
    memset(out, 0, sizeof *out);
    out->bspline = 1;
    out->degree = b.degree;
    out->count = (size_t)b.npts;
    out->points = b.pts; /* the item's arrays change owner */
    out->weights = b.weights;
    out->knot_vector = b.knots;
    out->bspline_opts = o;
    out->bezier = cj_plot_bezier_defaults();
    out->bezier.color = o.color;
    out->bezier.width = o.width;
    return 0;
}

int pj_parse_bspline(pj_ctx *c, const cJSON *it, const char *path, cj_plot *plot, cj_rgba color) {
    cj_plot_json_curve k;
    CJ_JSON_TRY(pj_read_bspline(c, it, path, color, &k));
    const int r = cj_plot_json_curve_add(plot, &k) ? pj_lib_fail(c, it, path) : 0;
    pj_curve_free(&k);
    return r;
}

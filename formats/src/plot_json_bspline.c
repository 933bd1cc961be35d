/* The "bspline" item of the plot JSON: a B-spline or NURBS curve drawn as its Bézier pieces,
 * with its control polygon and markers at the knots. Fields (bspline_json.h): degree, points,
 * knots (optional), weights (optional); drawing: color, width (2.5), control_polygon (true),
 * control_points (true), knot_markers (true: a disc on the curve at every distinct knot of the
 * domain, so the pieces can be told apart), drawn by cj_plot_add_bspline (the viewer draws its
 * B-splines through the same call). */
#include "bspline_json.h"
#include "plot_json_internal.h"

int pj_parse_bspline(pj_ctx *c, const cJSON *it, const char *path, cj_plot *plot, cj_rgba color) {
    static const char *const extra[] = {"color",          "width",        "control_polygon",
                                        "control_points", "knot_markers", NULL};
    bsp_json b;
    char why[400];
    if (bsp_json_parse(it, path, extra, PLOT_JSON_MAX_POINTS - c->points, &b, why, sizeof why))
        return pj_fail(c, "%s", why);
    double width = 2.5;
    int polygon = 1, points = 1, knots = 1, r = 0;
    const cJSON *v;
    char p[300];
#define BOPT(key, call)                                                                            \
    if (!r && (v = pj_field(it, key))) {                                                           \
        pj_pathf(p, sizeof p, "%s.%s", path, key);                                                 \
        r = call;                                                                                  \
    }
    BOPT("color", pj_parse_color(c, v, p, &color));
    BOPT("width", pj_parse_number(c, v, p, 0.1, CJ_PLOT_MAX_WIDTH, &width));
    BOPT("control_polygon", pj_parse_bool(c, v, p, &polygon));
    BOPT("control_points", pj_parse_bool(c, v, p, &points));
    BOPT("knot_markers", pj_parse_bool(c, v, p, &knots));
#undef BOPT
    if (!r && b.dim != 2)
        r = pj_fail(c, "%s.points: a plotted B-spline needs 2D points, not %d coordinates", path,
                    b.dim);
    const cj_bspline s = bsp_json_view(&b);
    c->points += (size_t)b.npts;
    cj_plot_bspline_opts o = cj_plot_bspline_defaults();
    o.color = color;
    o.width = width;
    o.control_polygon = polygon;
    o.control_points = points;
    o.knot_markers = knots;
    if (!r && cj_plot_add_bspline(plot, &s, &o)) r = pj_lib_fail(c, path);
    bsp_json_free(&b);
    return r ? -1 : 0;
}

/* The "bspline" item of the plot JSON: a B-spline or NURBS curve drawn as its Bézier pieces,
 * with its control polygon and markers at the knots. Fields (bspline_json.h): degree, points,
 * knots (optional), weights (optional); drawing: color, width (2.5), control_polygon (true),
 * control_points (true), knot_markers (true: a disc on the curve at every distinct knot of the
 * domain, so the pieces can be told apart). */
#include "bspline_json.h"
#include "plot_json_internal.h"

#include "casteljau/rational.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

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
    int np = 0;
    if (!r && cj_bspline_bezier_count(&s, &np)) r = pj_lib_fail(c, path);
    c->points += (size_t)b.npts;
    const int per = b.degree + 1;
    double *bp = NULL, *bw = NULL, *br = NULL, *kp = NULL;
    if (!r) {
        bp = malloc(sizeof(double) * (size_t)np * (size_t)per * 2);
        bw = b.weights ? malloc(sizeof(double) * (size_t)np * (size_t)per) : NULL;
        br = malloc(sizeof(double) * ((size_t)np + 1));
        kp = malloc(sizeof(double) * ((size_t)np + 1) * 2);
        if (!bp || !br || !kp || (b.weights && !bw)) r = pj_fail(c, "%s: out of memory", path);
    }
    if (!r && cj_bspline_to_bezier(&s, bp, bw, br, np, NULL)) r = pj_lib_fail(c, path);
    cj_plot_bezier_opts o = cj_plot_bezier_defaults();
    o.color = color;
    o.width = width;
    o.control_polygon = 0;
    o.control_points = 0;
    for (int j = 0; j < np && !r; ++j) {
        const cj_bezier pb = cj_bezier_view(b.degree, 2, bp + (size_t)j * (size_t)per * 2);
        const cj_rbezier rb = cj_rbezier_view(b.degree, 2, bp + (size_t)j * (size_t)per * 2,
                                              bw ? bw + (size_t)j * (size_t)per : NULL);
        if (bw ? cj_plot_add_rbezier(plot, &rb, &o) : cj_plot_add_bezier(plot, &pb, &o))
            r = pj_lib_fail(c, path);
    }
    const cj_rgba grey = {150, 150, 150, 255};
    if (!r && (polygon || points) && b.npts >= 2 &&
        cj_plot_add_polyline(plot, b.pts, (size_t)b.npts, 0, polygon ? grey : (cj_rgba){0, 0, 0, 0},
                             1.0, points))
        r = pj_lib_fail(c, path);
    if (!r && knots) {
        for (int j = 0; j <= np && !r; ++j)
            if (cj_bspline_eval(&s, br[j], kp + 2 * j)) r = pj_lib_fail(c, path);
        if (!r && cj_plot_add_points(plot, kp, (size_t)np + 1, color, 3.5))
            r = pj_lib_fail(c, path);
    }
    free(bp);
    free(bw);
    free(br);
    free(kp);
    bsp_json_free(&b);
    return r ? -1 : 0;
}

/* A B-spline or NURBS curve in a plot: its Bézier pieces (so the proven flattening of the
 * Bézier items draws it), its control polygon and points, and a marker on the curve at every
 * distinct knot of the domain. One function for the plot JSON's "bspline" item (formats/) and
 * the viewer (viz/), so the two draw the same pixels. */
#include "casteljau/plot.h"

#include "casteljau/rational.h"
#include "error_internal.h"

#include <stdlib.h>

cj_plot_bspline_opts cj_plot_bspline_defaults(void) {
    cj_plot_bspline_opts o;
    o.color = cj_rgba_make(0x1f, 0x77, 0xb4, 255);
    o.width = 2.5;
    o.control_polygon = 1;
    o.control_points = 1;
    o.knot_markers = 1;
    return o;
}

cj_status cj_plot_add_bspline(cj_plot *plot, const cj_bspline *s,
                              const cj_plot_bspline_opts *opts) {
    if (s->dim != 2)
        return cj_fail(CJ_ERR_ARGUMENT,
                       "plot: a plotted B-spline needs 2D points, not %d coordinates", s->dim);
    int np = 0;
    cj_status st = cj_bspline_bezier_count(s, &np);
    if (st) return st;
    const size_t per = (size_t)s->degree + 1;
    double *bp = malloc(sizeof(double) * (size_t)np * per * 2);
    double *bw = s->weights ? malloc(sizeof(double) * (size_t)np * per) : NULL;
    double *br = malloc(sizeof(double) * ((size_t)np + 1));
    double *kp = malloc(sizeof(double) * ((size_t)np + 1) * 2);
    if (!bp || !br || !kp || (s->weights && !bw))
        st = cj_fail(CJ_ERR_NOMEM, "plot: out of memory for a B-spline of %d pieces", np);
    if (!st) st = cj_bspline_to_bezier(s, bp, bw, br, np, NULL);
    cj_plot_bezier_opts o = cj_plot_bezier_defaults();
    o.color = opts->color;
    o.width = opts->width;
    o.control_polygon = 0;
    o.control_points = 0;
    for (int j = 0; j < np && !st; ++j) {
        const cj_bezier pb = cj_bezier_view(s->degree, 2, bp + (size_t)j * per * 2);
        const cj_rbezier rb = cj_rbezier_view(s->degree, 2, bp + (size_t)j * per * 2,
                                              bw ? bw + (size_t)j * per : NULL);
        st = bw ? cj_plot_add_rbezier(plot, &rb, &o) : cj_plot_add_bezier(plot, &pb, &o);
    }
    const cj_rgba grey = {150, 150, 150, 255};
    if (!st && (opts->control_polygon || opts->control_points) && s->npts >= 2)
        st = cj_plot_add_polyline(plot, s->pts, (size_t)s->npts, 0,
                                  opts->control_polygon ? grey : (cj_rgba){0, 0, 0, 0}, 1.0,
                                  opts->control_points);
    if (!st && opts->knot_markers) {
        for (int j = 0; j <= np && !st; ++j) st = cj_bspline_eval(s, br[j], kp + 2 * j);
        if (!st) st = cj_plot_add_points(plot, kp, (size_t)np + 1, opts->color, 3.5);
    }
    free(bp);
    free(bw);
    free(br);
    free(kp);
    return st;
}

/* Curve documents of the viewer as plot pages: the plot format's one reader and one writer
 * (formats/, plot_json.h) do the JSON; this file only converts between the editor's cj_vdoc and
 * the format's cj_plot_json_page (B-splines and NURBS included). The plot the viewer draws is built
 * from the same conversion, with the same calls the plot reader makes for the written file, so the
 * two pictures are the same pixels. */
#include "casteljau/viewer_model.h"

#include "error_internal.h"
#include "file_internal.h"
#include "plot_json.h"

#include <stdlib.h>
#include <string.h>

/* The plot item of curve c (pts and weights are views into c, not copies). sel: the curve the
 * display's parameter t is shown on. */
static cj_plot_json_curve to_curve(const cj_vcurve *c, const cj_vdoc_display *d, int sel) {
    cj_plot_json_curve k;
    memset(&k, 0, sizeof k);
    if (c->kind == CJ_VCURVE_BSPLINE) {
        k.bspline = 1;
        k.degree = c->degree;
        k.points = c->pts;
        k.count = c->count;
        k.weights = c->weights;
        k.knot_vector = c->knot_vector;
        k.bspline_opts = cj_plot_bspline_defaults();
        k.bspline_opts.color = c->color;
        k.bspline_opts.width = c->width;
        k.bspline_opts.control_polygon = c->control_polygon;
        k.bspline_opts.control_points = c->control_points;
        k.bspline_opts.knot_markers = c->knots;
        return k;
    }
    k.spline = c->kind == CJ_VCURVE_SPLINE;
    k.points = c->pts;
    k.count = c->count;
    k.weights = c->kind == CJ_VCURVE_RATIONAL ? c->weights : NULL;
    k.bezier = cj_plot_bezier_defaults();
    k.bezier.color = c->color;
    k.bezier.width = c->width;
    k.bezier.control_polygon = c->control_polygon;
    k.bezier.control_points = c->control_points;
    k.bezier.hull = c->hull;
    k.bezier.normals = c->normals;
    k.bezier.nframes = c->nframes;
    memcpy(k.bezier.frames_t, c->frames_t, sizeof k.bezier.frames_t);
    if (sel && d->construction) {
        k.bezier.construction = 1;
        k.bezier.construction_t = d->t;
    }
    if (sel && d->frame && k.bezier.nframes < CJ_PLOT_MAX_FRAMES)
        k.bezier.frames_t[k.bezier.nframes++] = d->t;
    k.spline_options = c->spline;
    k.knots = c->knots;
    return k;
}

/* The page of the document: no axes, no margin, the view box. page->curves is allocated (free
 * it alone: the points are the document's). */
static cj_status to_page(const cj_vdoc *doc, const cj_vview *v, const cj_vdoc_display *disp,
                         cj_plot_json_page *page) {
    memset(page, 0, sizeof *page);
    page->width = v->width;
    page->height = v->height;
    page->background = disp->background;
    page->have_view = 1;
    page->view[0] = v->x0, page->view[1] = v->y0, page->view[2] = v->x1, page->view[3] = v->y1;
    page->ncurves = cj_vdoc_curve_count(doc);
    page->curves = calloc(page->ncurves ? page->ncurves : 1, sizeof *page->curves);
    if (!page->curves) return cj_fail(CJ_ERR_NOMEM, "out of memory");
    for (size_t i = 0; i < page->ncurves; ++i)
        page->curves[i] = to_curve(cj_vdoc_curve(doc, i), disp, (long)i == disp->curve);
    return CJ_OK;
}

cj_status cj_vdoc_build_plot(const cj_vdoc *doc, const cj_vview *v, const cj_vdoc_display *disp,
                             cj_plot **out) {
    cj_plot_json_page page;
    cj_status st = to_page(doc, v, disp, &page);
    if (st) return st;
    cj_plot *plot = NULL;
    st = cj_plot_create(NULL, &plot);
    if (!st) {
        cj_plot_set_background(plot, disp->background);
        cj_plot_set_axes(plot, 0);
        st = cj_plot_set_margin(plot, 0.0);
    }
    if (!st) st = cj_plot_set_view(plot, v->x0, v->y0, v->x1, v->y1);
    for (size_t i = 0; !st && i < page.ncurves; ++i)
        st = cj_plot_json_curve_add(plot, &page.curves[i]);
    free(page.curves);
    if (st) {
        cj_plot_destroy(plot);
        return st;
    }
    *out = plot;
    return CJ_OK;
}

cj_status cj_vdoc_save_json(const cj_vdoc *doc, const cj_vview *v, const cj_vdoc_display *disp,
                            const char *path) {
    cj_plot_json_page page;
    cj_status st = to_page(doc, v, disp, &page);
    if (!st) {
        page.axes = 0;
        page.margin = 0.0;
        st = cj_plot_json_write_page(&page, path);
    }
    free(page.curves);
    return st;
}

cj_status cj_vdoc_load_json(const char *path, cj_vdoc **out, cj_vview *v, cj_vdoc_display *disp) {
    char *text = NULL;
    size_t len = 0;
    cj_status st = cj_file_read_all(path, CJ_FILE_MAX_BYTES, "viewer document", &text, &len);
    if (st) return st;
    cj_plot_json_page page;
    st = cj_plot_json_read_page(path, text, &page);
    free(text);
    if (st) return st;
    cj_vdoc *doc = NULL;
    cj_vdoc_display d = {page.background, -1, 0.5, 0, 0};
    st = cj_vdoc_create(&doc);
    for (size_t i = 0; !st && i < page.ncurves; ++i) {
        const cj_plot_json_curve *k = &page.curves[i];
        if (k->bspline) {
            cj_vcurve c = cj_vcurve_init(CJ_VCURVE_BSPLINE, k->count, k->points, k->weights);
            c.degree = k->degree;
            c.knot_vector = k->knot_vector;
            c.color = k->bspline_opts.color;
            c.width = k->bspline_opts.width;
            c.control_polygon = k->bspline_opts.control_polygon;
            c.control_points = k->bspline_opts.control_points;
            c.knots = k->bspline_opts.knot_markers;
            st = cj_vdoc_add_curve(doc, &c);
            if (st) st = cj_fail(st, "%s: items[%zu]: %s", path, i, cj_last_error());
            continue;
        }
        const cj_vcurve_kind kind = k->spline    ? CJ_VCURVE_SPLINE
                                    : k->weights ? CJ_VCURVE_RATIONAL
                                                 : CJ_VCURVE_BEZIER;
        cj_vcurve c = cj_vcurve_init(kind, k->count, k->points, k->weights);
        c.color = k->bezier.color;
        c.width = k->bezier.width;
        if (k->spline) {
            c.spline = k->spline_options;
            c.knots = k->knots;
        } else {
            c.control_polygon = k->bezier.control_polygon;
            c.control_points = k->bezier.control_points;
            c.hull = k->bezier.hull;
            c.normals = k->bezier.normals;
            c.nframes = k->bezier.nframes;
            memcpy(c.frames_t, k->bezier.frames_t, sizeof c.frames_t);
            if (k->bezier.construction) {
                d.curve = (long)i;
                d.t = k->bezier.construction_t;
                d.construction = 1;
            }
        }
        st = cj_vdoc_add_curve(doc, &c);
        if (st) st = cj_fail(st, "%s: items[%zu]: %s", path, i, cj_last_error());
    }
    cj_vview view = {0, 0, 1, 1, page.width, page.height};
    const int have_view = page.have_view;
    if (have_view)
        view.x0 = page.view[0], view.y0 = page.view[1], view.x1 = page.view[2],
        view.y1 = page.view[3];
    cj_plot_json_page_free(&page);
    if (st) {
        cj_vdoc_destroy(doc);
        return st;
    }
    if (!have_view) cj_vview_fit(&view, doc, 0.1);
    cj_vdoc_clear_log(doc); /* a freshly loaded document has nothing to undo */
    *out = doc;
    *v = view;
    *disp = d;
    return CJ_OK;
}

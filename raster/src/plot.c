/* Plots of curves (see casteljau/plot.h): the plot object and its items, each checked and
 * copied when it is added. Drawing lives in plot_items.c, layout and axes in plot_render.c. */
#include "casteljau/plot.h"

#include "casteljau/rational.h"
#include "error_internal.h"
#include "plot_items_internal.h"
#include "raster_internal.h"

#include <assert.h>
#include <math.h>
#include <string.h>

static void *palloc(const cj_plot *p, size_t bytes) {
    return cj_allocator_alloc(&p->alloc, bytes);
}
static void pfree(const cj_plot *p, void *ptr) {
    cj_allocator_free(&p->alloc, ptr);
}

static void item_free(const cj_plot *p, plot_item *it) {
    pfree(p, it->pts);
    pfree(p, it->segs);
    pfree(p, it->offsets);
    pfree(p, it->closed_flags);
    pfree(p, it->weights);
}

cj_plot_bezier_opts cj_plot_bezier_defaults(void) {
    cj_plot_bezier_opts o;
    memset(&o, 0, sizeof o);
    o.color = cj_rgba_make(0x1f, 0x77, 0xb4, 255);
    o.width = 2.5;
    o.control_polygon = 1;
    o.control_points = 1;
    o.hull = 0;
    o.construction = 0;
    o.construction_t = 0.5;
    o.nframes = 0;
    o.normals = 1;
    return o;
}

cj_status cj_plot_create(const cj_allocator *alloc, cj_plot **out) {
    assert(out);
    const cj_allocator a = cj_allocator_resolve(alloc);
    cj_plot *p = cj_allocator_alloc(&a, sizeof *p);
    if (!p) return cj_fail(CJ_ERR_NOMEM, "no memory for a plot");
    memset(p, 0, sizeof *p);
    p->alloc = a;
    p->background = cj_rgba_make(255, 255, 255, 255);
    p->axes = 1;
    p->margin = 12.0;
    *out = p;
    return CJ_OK;
}

void cj_plot_destroy(cj_plot *plot) {
    if (!plot) return;
    for (size_t i = 0; i < plot->count; ++i) item_free(plot, &plot->items[i]);
    pfree(plot, plot->items);
    pfree(plot, plot->title);
    const cj_allocator a = plot->alloc;
    cj_allocator_free(&a, plot);
}

void cj_plot_set_background(cj_plot *plot, cj_rgba color) {
    assert(plot);
    plot->background = color;
}

void cj_plot_set_axes(cj_plot *plot, int on) {
    assert(plot);
    plot->axes = on != 0;
}

cj_status cj_plot_set_title(cj_plot *plot, const char *title) {
    assert(plot);
    char *copy = NULL;
    if (title && *title) {
        size_t n = strlen(title) + 1;
        if (n - 1 > CJ_PLOT_MAX_TITLE)
            return cj_fail(CJ_ERR_RANGE, "title of %zu bytes is longer than %d", n - 1,
                           CJ_PLOT_MAX_TITLE);
        copy = palloc(plot, n);
        if (!copy) return cj_fail(CJ_ERR_NOMEM, "no memory for the plot title");
        memcpy(copy, title, n);
    }
    pfree(plot, plot->title);
    plot->title = copy;
    return CJ_OK;
}

cj_status cj_plot_set_margin(cj_plot *plot, double px) {
    assert(plot);
    if (!(px >= 0.0 && px <= 1000.0))
        return cj_fail(CJ_ERR_RANGE, "plot margin %g px is not between 0 and 1000", px);
    plot->margin = px;
    return CJ_OK;
}

cj_status cj_plot_set_view(cj_plot *plot, double x0, double y0, double x1, double y1) {
    assert(plot);
    const double v[4] = {x0, y0, x1, y1};
    cj_status st = cj_check_finite(v, 4, "plot view");
    if (st) return st;
    if (!(x0 < x1) || !(y0 < y1))
        return cj_fail(CJ_ERR_DEGENERATE, "plot view [%g, %g] x [%g, %g] is empty", x0, x1, y0, y1);
    memcpy(plot->view, v, sizeof v);
    plot->has_view = 1;
    return CJ_OK;
}

size_t cj_plot_item_count(const cj_plot *plot) {
    assert(plot);
    return plot->count;
}

static cj_status check_width(double w, const char *what) {
    if (!(w > 0.0 && w <= CJ_PLOT_MAX_WIDTH))
        return cj_fail(CJ_ERR_RANGE, "%s %g px is not in (0, %g]", what, w, CJ_PLOT_MAX_WIDTH);
    return CJ_OK;
}

/* A new item of the given type, every other field zero (no arrays yet). */
static plot_item item_init(item_type type, cj_rgba color, double width) {
    plot_item it;
    memset(&it, 0, sizeof it);
    it.type = type;
    it.color = color;
    it.width = width;
    return it;
}

/* Appends *it (taking ownership of its arrays); frees them on failure. */
static cj_status push_item(cj_plot *p, plot_item *it) {
    if (p->count == p->cap) {
        size_t cap = p->cap ? 2 * p->cap : 8;
        plot_item *n = palloc(p, cap * sizeof *n);
        if (!n) {
            item_free(p, it);
            return cj_fail(CJ_ERR_NOMEM, "no memory for plot items");
        }
        if (p->count) memcpy(n, p->items, p->count * sizeof *n);
        pfree(p, p->items);
        p->items = n;
        p->cap = cap;
    }
    p->items[p->count++] = *it;
    return CJ_OK;
}

static double *copy_doubles(const cj_plot *p, const double *src, size_t n) {
    double *d = palloc(p, n * sizeof *d);
    if (d && n) memcpy(d, src, n * sizeof *d);
    return d;
}

static cj_status add_bezier(cj_plot *plot, const cj_bezier *c, const double *weights,
                            const cj_plot_bezier_opts *opts) {
    cj_plot_bezier_opts o = opts ? *opts : cj_plot_bezier_defaults();
    cj_status st;
    if (c->dim != 2)
        return cj_fail(CJ_ERR_DIMENSION, "a plotted Bezier curve must be 2D, not %dD", c->dim);
    if ((st = check_width(o.width, "curve width"))) return st;
    if (o.construction && !(o.construction_t >= 0.0 && o.construction_t <= 1.0))
        return cj_fail(CJ_ERR_RANGE, "construction t = %g is not in [0, 1]", o.construction_t);
    if (o.nframes > CJ_PLOT_MAX_FRAMES)
        return cj_fail(CJ_ERR_RANGE, "%zu frames asked, at most %d", o.nframes, CJ_PLOT_MAX_FRAMES);
    for (size_t i = 0; i < o.nframes; ++i)
        if (!(o.frames_t[i] >= 0.0 && o.frames_t[i] <= 1.0))
            return cj_fail(CJ_ERR_RANGE, "frame %zu: t = %g is not in [0, 1]", i, o.frames_t[i]);
    plot_item it = item_init(ITEM_BEZIER, o.color, o.width);
    it.degree = c->degree;
    it.npts = (size_t)c->degree + 1;
    it.bopts = o;
    it.pts = copy_doubles(plot, c->pts, 2 * it.npts);
    if (weights) it.weights = copy_doubles(plot, weights, it.npts);
    if (!it.pts || (weights && !it.weights)) {
        item_free(plot, &it);
        return cj_fail(CJ_ERR_NOMEM, "no memory for %zu control points", it.npts);
    }
    return push_item(plot, &it);
}

cj_status cj_plot_add_bezier(cj_plot *plot, const cj_bezier *c, const cj_plot_bezier_opts *opts) {
    assert(plot && c);
    cj_status st = cj_bezier_check(c, CJ_BEZIER_MAX_DEGREE);
    if (st) return st;
    return add_bezier(plot, c, NULL, opts);
}

cj_status cj_plot_add_rbezier(cj_plot *plot, const cj_rbezier *c, const cj_plot_bezier_opts *opts) {
    assert(plot && c);
    cj_status st = cj_rbezier_check(c);
    if (st) return st;
    cj_bezier b = cj_bezier_view(c->degree, c->dim, c->pts);
    return add_bezier(plot, &b, c->weights, opts);
}

cj_status cj_plot_add_spline(cj_plot *plot, const double *pts, size_t npts,
                             const cj_spline_options *sopts, cj_rgba color, double width,
                             int show_knots) {
    assert(plot && (pts || npts == 0));
    cj_status st = check_width(width, "spline width");
    if (st) return st;
    const int closed = sopts ? sopts->closed : 0;
    size_t nsegs = cj_spline_segment_count(npts, closed);
    plot_item it = item_init(ITEM_SPLINE, color, width);
    it.markers = show_knots != 0;
    it.npts = npts;
    it.segs = palloc(plot, (nsegs ? nsegs : 1) * 8 * sizeof(double));
    it.pts = copy_doubles(plot, pts, 2 * npts);
    if (!it.segs || !it.pts) {
        item_free(plot, &it);
        return cj_fail(CJ_ERR_NOMEM, "no memory for a spline of %zu points", npts);
    }
    st = cj_catmull_rom(pts, npts, 2, sopts, it.segs, nsegs, &it.nsegs, NULL);
    if (st) {
        item_free(plot, &it);
        return st;
    }
    return push_item(plot, &it);
}

typedef struct contour_acc {
    cj_plot *plot;
    plot_item *it;
    size_t cap_pts, cap_lines;
    cj_status oom;
} contour_acc;

static cj_status take_contour(void *user, const double *xy, size_t npts, int closed,
                              double max_residual) {
    (void)max_residual;
    contour_acc *a = user;
    plot_item *it = a->it;
    if (it->npts + npts > a->cap_pts) {
        size_t cap = a->cap_pts * 2 + npts + 64;
        double *n = palloc(a->plot, cap * 2 * sizeof *n);
        if (!n) return a->oom = cj_fail(CJ_ERR_NOMEM, "no memory for contour points");
        if (it->npts) memcpy(n, it->pts, it->npts * 2 * sizeof *n);
        pfree(a->plot, it->pts);
        it->pts = n;
        a->cap_pts = cap;
    }
    if (it->nsegs + 2 > a->cap_lines) {
        size_t cap = a->cap_lines * 2 + 8;
        size_t *no = palloc(a->plot, cap * sizeof *no);
        int *nc = palloc(a->plot, cap * sizeof *nc);
        if (!no || !nc) {
            pfree(a->plot, no);
            pfree(a->plot, nc);
            return a->oom = cj_fail(CJ_ERR_NOMEM, "no memory for contours");
        }
        memcpy(no, it->offsets, (it->nsegs + 1) * sizeof *no);
        if (it->nsegs) memcpy(nc, it->closed_flags, it->nsegs * sizeof *nc);
        pfree(a->plot, it->offsets);
        pfree(a->plot, it->closed_flags);
        it->offsets = no;
        it->closed_flags = nc;
        a->cap_lines = cap;
    }
    memcpy(it->pts + 2 * it->npts, xy, npts * 2 * sizeof *xy);
    it->npts += npts;
    it->closed_flags[it->nsegs] = closed;
    it->offsets[++it->nsegs] = it->npts;
    return CJ_OK;
}

cj_status cj_plot_add_implicit(cj_plot *plot, const cj_implicit *f, const double box[4], int grid,
                               cj_rgba color, double width) {
    assert(plot && f && box);
    cj_status st = check_width(width, "implicit curve width");
    if (st) return st;
    if ((st = cj_check_finite(box, 4, "implicit box"))) return st;
    if (!(box[0] < box[2]) || !(box[1] < box[3]))
        return cj_fail(CJ_ERR_DEGENERATE, "implicit box [%g, %g] x [%g, %g] is empty", box[0],
                       box[2], box[1], box[3]);
    plot_item it = item_init(ITEM_IMPLICIT, color, width);
    it.offsets = palloc(plot, sizeof *it.offsets);
    if (!it.offsets) return cj_fail(CJ_ERR_NOMEM, "no memory for contours");
    it.offsets[0] = 0;
    contour_acc acc = {plot, &it, 0, 1, CJ_OK};
    cj_contour_options co;
    co.nx = co.ny = grid > 0 ? grid : 64;
    co.tol = 1e-5 * hypot(box[2] - box[0], box[3] - box[1]);
    co.alloc = &plot->alloc; /* the contour's work space comes from the plot's allocator */
    st = cj_implicit_contour(f, box, &co, take_contour, &acc, NULL);
    if (st && st != CJ_ERR_CAP) {
        item_free(plot, &it);
        return st;
    }
    if (it.nsegs == 0) {
        item_free(plot, &it);
        return cj_fail(CJ_ERR_EMPTY,
                       "the implicit curve has no point in the box [%g, %g] x "
                       "[%g, %g]",
                       box[0], box[2], box[1], box[3]);
    }
    return push_item(plot, &it);
}

cj_status cj_plot_add_polyline(cj_plot *plot, const double *xy, size_t npts, int closed,
                               cj_rgba color, double width, int markers) {
    assert(plot && (xy || npts == 0));
    if (npts < 2) return cj_fail(CJ_ERR_EMPTY, "a polyline needs 2 points, got %zu", npts);
    cj_status st = cj_check_points(xy, npts, 2, "polyline point");
    if (st) return st;
    if ((st = check_width(width, "polyline width"))) return st;
    plot_item it = item_init(ITEM_POLYLINE, color, width);
    it.closed = closed != 0;
    it.markers = markers != 0;
    it.npts = npts;
    it.pts = copy_doubles(plot, xy, 2 * npts);
    if (!it.pts) return cj_fail(CJ_ERR_NOMEM, "no memory for %zu polyline points", npts);
    return push_item(plot, &it);
}

cj_status cj_plot_add_points(cj_plot *plot, const double *xy, size_t npts, cj_rgba color,
                             double radius) {
    assert(plot && (xy || npts == 0));
    if (npts < 1) return cj_fail(CJ_ERR_EMPTY, "no points to plot");
    cj_status st = cj_check_points(xy, npts, 2, "point");
    if (st) return st;
    if ((st = check_width(radius, "point radius"))) return st;
    plot_item it = item_init(ITEM_POINTS, color, radius);
    it.npts = npts;
    it.pts = copy_doubles(plot, xy, 2 * npts);
    if (!it.pts) return cj_fail(CJ_ERR_NOMEM, "no memory for %zu points", npts);
    return push_item(plot, &it);
}

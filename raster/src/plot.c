/* Plots of curves (see casteljau/plot.h): item storage, fitting, axes, and drawing through
 * flattening and anti-aliased strokes. */
#include "casteljau/plot.h"

#include "casteljau/flatten.h"
#include "casteljau/rational.h"
#include "error_internal.h"
#include "plot_internal.h"
#include "raster_internal.h"

#include <assert.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- storage -------------------------------------------------------------------------- */

typedef enum item_type {
    ITEM_BEZIER,
    ITEM_SPLINE,
    ITEM_IMPLICIT,
    ITEM_POLYLINE,
    ITEM_POINTS
} item_type;

typedef struct plot_item {
    item_type type;
    cj_rgba color;
    double width;      /* stroke width, or marker radius for ITEM_POINTS */
    double *pts;       /* bezier: control points; spline: knots (input points); polyline,
                          points: vertices; implicit: all contour vertices back to back */
    size_t npts;       /* number of 2D points in pts */
    double *segs;      /* spline: nsegs cubic segments (8 doubles each) */
    size_t nsegs;      /* spline segments; implicit: number of contours */
    size_t *offsets;   /* implicit: contour k has points offsets[k]..offsets[k+1]-1 */
    int *closed_flags; /* implicit: closed flag per contour */
    int closed;        /* polyline */
    int markers;       /* polyline markers, spline knots */
    int degree;        /* bezier */
    double *weights;   /* rational bezier: degree+1 weights; NULL for a polynomial curve */
    cj_plot_bezier_opts bopts;
} plot_item;

struct cj_plot {
    cj_allocator alloc;
    plot_item *items;
    size_t count, cap;
    cj_rgba background;
    int axes;
    char *title;
    double margin;
    int has_view;
    double view[4];
};

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
    plot_item it;
    memset(&it, 0, sizeof it);
    it.type = ITEM_BEZIER;
    it.color = o.color;
    it.width = o.width;
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
    plot_item it;
    memset(&it, 0, sizeof it);
    it.type = ITEM_SPLINE;
    it.color = color;
    it.width = width;
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
    plot_item it;
    memset(&it, 0, sizeof it);
    it.type = ITEM_IMPLICIT;
    it.color = color;
    it.width = width;
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
    plot_item it;
    memset(&it, 0, sizeof it);
    it.type = ITEM_POLYLINE;
    it.color = color;
    it.width = width;
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
    plot_item it;
    memset(&it, 0, sizeof it);
    it.type = ITEM_POINTS;
    it.color = color;
    it.width = radius;
    it.npts = npts;
    it.pts = copy_doubles(plot, xy, 2 * npts);
    if (!it.pts) return cj_fail(CJ_ERR_NOMEM, "no memory for %zu points", npts);
    return push_item(plot, &it);
}

/* ---- rendering ------------------------------------------------------------------------ */

typedef struct xform {
    double s;      /* pixels per data unit */
    double ox, oy; /* pixel position of data (cx, cy) */
    double cx, cy;
} xform;

static void to_px(const xform *x, const double *in, double *out) {
    out[0] = x->ox + x->s * (in[0] - x->cx);
    out[1] = x->oy + x->s * (in[1] - x->cy);
}

static void grow_box(double *box, const double *pts, size_t n) {
    for (size_t i = 0; i < n; ++i) {
        if (pts[2 * i] < box[0]) box[0] = pts[2 * i];
        if (pts[2 * i + 1] < box[1]) box[1] = pts[2 * i + 1];
        if (pts[2 * i] > box[2]) box[2] = pts[2 * i];
        if (pts[2 * i + 1] > box[3]) box[3] = pts[2 * i + 1];
    }
}

static cj_rgba with_alpha(cj_rgba c, uint8_t a) {
    c.a = (uint8_t)((unsigned)c.a * a / 255u);
    return c;
}

/* Flattens a 2D Bézier given in pixel coordinates into the scratch polyline. */
/* (An affine map of the control points maps a rational curve exactly too, weights unchanged.) */
static cj_status flatten_px(cj_plot_canvas *cv, const double *ctrl_px, const double *weights,
                            int degree) {
    cj_bezier b = cj_bezier_view(degree, 2, ctrl_px);
    cj_rbezier rb = cj_rbezier_view(degree, 2, ctrl_px, weights);
    cj_flatten_opts fo = cj_flatten_defaults(CJ_FLATTEN_NEAR_OPTIMAL, CJ_PLOT_FLATTEN_TOL);
    size_t n = 0;
    cj_status st = weights ? cj_flatten_rbezier(&rb, &fo, NULL, 0, &n, NULL)
                           : cj_flatten_bezier(&b, &fo, NULL, 0, &n, NULL);
    if (st) return st;
    if ((st = cj_plot_canvas_reserve(cv, n))) return st;
    st = weights ? cj_flatten_rbezier(&rb, &fo, cv->poly, cv->poly_cap, &n, NULL)
                 : cj_flatten_bezier(&b, &fo, cv->poly, cv->poly_cap, &n, NULL);
    if (st) return st;
    cv->poly_n = n;
    return CJ_OK;
}

static const cj_rgba level_colors[] = {{0xff, 0x7f, 0x0e, 255}, {0x2c, 0xa0, 0x2c, 255},
                                       {0xd6, 0x27, 0x28, 255}, {0x94, 0x67, 0xbd, 255},
                                       {0x8c, 0x56, 0x4b, 255}, {0xe3, 0x77, 0xc2, 255},
                                       {0x17, 0xbe, 0xcf, 255}, {0xbc, 0xbd, 0x22, 255}};

static cj_status draw_bezier(cj_plot_canvas *cv, const xform *x, const plot_item *it) {
    const int n = it->degree;
    const size_t np = (size_t)n + 1;
    const cj_plot_bezier_opts *o = &it->bopts;
    double *px = malloc(np * 2 * sizeof *px);
    if (!px) return cj_fail(CJ_ERR_NOMEM, "no memory for %zu control points", np);
    for (size_t i = 0; i < np; ++i) to_px(x, it->pts + 2 * i, px + 2 * i);
    cj_status st = CJ_OK;
    const cj_rgba grey = cj_rgba_make(0x70, 0x70, 0x70, 255);
    cj_bezier c = cj_bezier_view(n, 2, it->pts);

    if (o->hull && n >= 1) {
        int *idx = malloc(np * sizeof *idx);
        double *hull = malloc(np * 2 * sizeof *hull);
        int count = 0;
        if (!idx || !hull) st = cj_fail(CJ_ERR_NOMEM, "no memory for a hull");
        if (!st) st = cj_bezier_hull2d(&c, idx, &count);
        if (!st && count >= 3) {
            for (int k = 0; k < count; ++k) {
                hull[2 * k] = px[2 * idx[k]];
                hull[2 * k + 1] = px[2 * idx[k] + 1];
            }
            cj_plot_fill_convex(cv, hull, (size_t)count, with_alpha(it->color, 36));
            st = cj_plot_stroke(cv, hull, (size_t)count, 1, with_alpha(it->color, 110), 1.0);
        } else if (st == CJ_ERR_DEGENERATE) {
            st = CJ_OK; /* collinear or coincident points: no area to fill */
        }
        free(idx);
        free(hull);
    }
    if (!st && o->control_polygon && n >= 1)
        st = cj_plot_stroke(cv, px, np, 0, with_alpha(grey, 200), 1.25);
    if (!st) st = flatten_px(cv, px, it->weights, n);
    if (!st) st = cj_plot_stroke(cv, cv->poly, cv->poly_n, 0, it->color, it->width);

    if (!st && o->construction && n >= 1) {
        /* The de Casteljau triangle at t: level r has points b_i^r, i = 0..n-r; each level's
         * polygon is drawn in its own colour, its points as small dots. */
        double *tri = malloc(np * 3 * sizeof *tri);
        if (!tri) st = cj_fail(CJ_ERR_NOMEM, "no memory for the construction");
        const double t = o->construction_t;
        /* tri[3i..3i+2] = (x, y, w); rational levels are convex combinations with weights
         * (1-t) w_i, t w_{i+1} (the projection of the homogeneous de Casteljau step). */
        for (size_t i = 0; !st && i < np; ++i) {
            tri[3 * i] = it->pts[2 * i];
            tri[3 * i + 1] = it->pts[2 * i + 1];
            tri[3 * i + 2] = it->weights ? it->weights[i] : 1.0;
        }
        for (int r = 1; !st && r <= n; ++r) {
            for (int i = 0; i + r <= n; ++i) {
                double *a = tri + 3 * i, *b = tri + 3 * (i + 1);
                const double wa = (1.0 - t) * a[2], wb = t * b[2], w = wa + wb;
                for (int k = 0; k < 2; ++k)
                    a[k] = it->weights ? (wa * a[k] + wb * b[k]) / w : (1.0 - t) * a[k] + t * b[k];
                a[2] = w;
            }
            const size_t m = (size_t)(n - r + 1);
            double *lp = malloc(m * 2 * sizeof *lp);
            if (!lp) {
                st = cj_fail(CJ_ERR_NOMEM, "no memory for the construction");
                break;
            }
            for (size_t i = 0; i < m; ++i) to_px(x, tri + 3 * i, lp + 2 * i);
            cj_rgba lc = level_colors[(r - 1) % (int)(sizeof level_colors / sizeof *level_colors)];
            if (m >= 2) st = cj_plot_stroke(cv, lp, m, 0, lc, 1.5);
            for (size_t i = 0; !st && i < m; ++i) {
                if (r == n) {
                    cj_plot_disc(cv, lp[0], lp[1], 5.5, cj_rgba_make(0x20, 0x20, 0x20, 255));
                    cj_plot_disc(cv, lp[0], lp[1], 3.5, cj_rgba_make(0xd6, 0x27, 0x28, 255));
                } else {
                    cj_plot_disc(cv, lp[2 * i], lp[2 * i + 1], 3.0, lc);
                }
            }
            free(lp);
        }
        free(tri);
    }
    if (!st && o->control_points) {
        for (size_t i = 0; i < np; ++i) {
            cj_plot_disc(cv, px[2 * i], px[2 * i + 1], 4.5, cj_rgba_make(0x30, 0x30, 0x30, 255));
            cj_plot_disc(cv, px[2 * i], px[2 * i + 1], 2.75, cj_rgba_make(255, 255, 255, 255));
        }
    }
    for (size_t f = 0; !st && f < o->nframes; ++f) {
        double p[2], tan[2], nor[2], pp[2];
        if (it->weights) {
            /* Rational: c' from the quotient rule; a zero first derivative has no arrow. */
            double d[4];
            cj_rbezier rc = cj_rbezier_view(n, 2, it->pts, it->weights);
            if (cj_rbezier_eval_derivs(&rc, o->frames_t[f], 1, d) != CJ_OK) continue;
            const double len = hypot(d[2], d[3]);
            if (!(len > 0.0)) continue;
            p[0] = d[0], p[1] = d[1], tan[0] = d[2] / len, tan[1] = d[3] / len;
            nor[0] = -tan[1], nor[1] = tan[0];
        } else {
            if (cj_bezier_eval_decasteljau(&c, o->frames_t[f], p) != CJ_OK) continue;
            if (cj_bezier_tangent(&c, o->frames_t[f], tan, NULL) != CJ_OK) continue;
            if (cj_bezier_normal(&c, o->frames_t[f], nor) != CJ_OK) nor[0] = nor[1] = 0.0;
        }
        to_px(x, p, pp);
        const double len = cv->arrow_len;
        st = cj_plot_arrow(cv, pp[0], pp[1], pp[0] + len * tan[0], pp[1] + len * tan[1],
                           cj_rgba_make(0xd6, 0x27, 0x28, 255), 2.0);
        if (!st && o->normals && (nor[0] != 0.0 || nor[1] != 0.0))
            st = cj_plot_arrow(cv, pp[0], pp[1], pp[0] + len * nor[0], pp[1] + len * nor[1],
                               cj_rgba_make(0x2c, 0xa0, 0x2c, 255), 2.0);
        if (!st) cj_plot_disc(cv, pp[0], pp[1], 3.5, cj_rgba_make(0x20, 0x20, 0x20, 255));
    }
    free(px);
    return st;
}

static cj_status draw_spline(cj_plot_canvas *cv, const xform *x, const plot_item *it) {
    cj_status st = CJ_OK;
    double seg[8];
    /* Flatten piece by piece; consecutive pieces share end points, so stroking each piece
     * separately joins them (round joins of the stroker). */
    for (size_t s = 0; !st && s < it->nsegs; ++s) {
        for (int i = 0; i < 4; ++i) to_px(x, it->segs + 8 * s + 2 * i, seg + 2 * i);
        st = flatten_px(cv, seg, NULL, 3);
        if (!st) st = cj_plot_stroke(cv, cv->poly, cv->poly_n, 0, it->color, it->width);
    }
    if (!st && it->markers)
        for (size_t i = 0; i < it->npts; ++i) {
            double p[2];
            to_px(x, it->pts + 2 * i, p);
            cj_plot_disc(cv, p[0], p[1], 5.0, cj_rgba_make(0x20, 0x20, 0x20, 255));
            cj_plot_disc(cv, p[0], p[1], 3.5, it->color);
        }
    return st;
}

static cj_status draw_pointlist(cj_plot_canvas *cv, const xform *x, const double *pts, size_t n,
                                int closed, cj_rgba color, double width) {
    cj_status st = cj_plot_canvas_reserve(cv, n);
    if (st) return st;
    for (size_t i = 0; i < n; ++i) to_px(x, pts + 2 * i, cv->poly + 2 * i);
    return cj_plot_stroke(cv, cv->poly, n, closed, color, width);
}

/* ---- axes ----------------------------------------------------------------------------- */

/* A "nice" step (1, 2 or 5 times a power of ten) giving about `target` intervals on span. */
static double nice_step(double span, double target) {
    double raw = span / target;
    double p = pow(10.0, floor(log10(raw)));
    double m = raw / p;
    double nice = m < 1.5 ? 1.0 : m < 3.5 ? 2.0 : m < 7.5 ? 5.0 : 10.0;
    return nice * p;
}

/* Formats k*step as a short label with the decimals the step needs; U+2212 for minus. */
static void format_tick(double v, double step, char *buf, size_t size) {
    if (fabs(v) < step * 1e-6) v = 0.0;
    char tmp[64];
    double mag = fmax(fabs(v), step);
    if (mag >= 1e6 || step < 1e-4) {
        snprintf(tmp, sizeof tmp, "%.3g", v);
    } else {
        int dec = (int)ceil(-log10(step) - 1e-9);
        if (dec < 0) dec = 0;
        snprintf(tmp, sizeof tmp, "%.*f", dec, v);
    }
    if (tmp[0] == '-')
        snprintf(buf, size, "\xe2\x88\x92%s", tmp + 1);
    else
        snprintf(buf, size, "%s", tmp);
}

typedef struct ticks {
    double first, step;
    int count;
} ticks;

static ticks make_ticks(double lo, double hi, double target) {
    ticks t = {0.0, 0.0, 0};
    /* A span beyond the double range (or none) has no sensible ticks; the count is converted
     * to int only when it is a number in range (a NaN or huge count is undefined). */
    if (!(hi - lo > 0.0) || !isfinite(hi - lo)) return t;
    t.step = nice_step(hi - lo, target);
    if (!(t.step > 0.0) || !isfinite(t.step)) return t;
    t.first = ceil(lo / t.step - 1e-9) * t.step;
    const double count = floor((hi - t.first) / t.step + 1e-9) + 1.0;
    t.count = count >= 0.0 ? (count <= 100.0 ? (int)count : 100) : 0;
    return t;
}

static cj_status widest_label(cj_font *font, double size, ticks t, double *w) {
    *w = 0.0;
    for (int i = 0; i < t.count; ++i) {
        char buf[80];
        double adv = 0.0;
        format_tick(t.first + i * t.step, t.step, buf, sizeof buf);
        cj_status st = cj_font_measure(font, size, buf, &adv, NULL, NULL);
        if (st) return st;
        if (adv > *w) *w = adv;
    }
    return CJ_OK;
}

/* ---- render --------------------------------------------------------------------------- */

cj_status cj_plot_render(const cj_plot *plot, cj_framebuffer *fb, int x0, int y0, int w, int h,
                         cj_font *font_in) {
    assert(plot && fb);
    if (x0 < 0 || y0 < 0 || w < 12 || h < 12 || w > fb->width - x0 || h > fb->height - y0)
        return cj_fail(CJ_ERR_RANGE,
                       "plot rectangle %dx%d at (%d, %d) is not a rectangle of at least 12x12 "
                       "pixels inside the %dx%d framebuffer",
                       w, h, x0, y0, fb->width, fb->height);
    double box[4] = {INFINITY, INFINITY, -INFINITY, -INFINITY};
    if (plot->has_view) {
        memcpy(box, plot->view, sizeof box);
    } else {
        if (plot->count == 0) return cj_fail(CJ_ERR_EMPTY, "the plot has no items");
        for (size_t i = 0; i < plot->count; ++i) {
            const plot_item *it = &plot->items[i];
            grow_box(box, it->pts, it->npts);
            if (it->type == ITEM_SPLINE) grow_box(box, it->segs, 4 * it->nsegs);
        }
        double dx = box[2] - box[0], dy = box[3] - box[1];
        if (!(dx > 0.0) && !(dy > 0.0)) {
            /* A single point (a one-point item): a view centred on it. */
            const double half = fmax(1.0, 0.05 * fmax(fabs(box[0]), fabs(box[1])));
            box[0] -= half, box[1] -= half, box[2] += half, box[3] += half;
            dx = dy = 2.0 * half;
        }
        /* A flat box (all data on a horizontal or vertical line) gets the other side's span. */
        if (!(dx > 0.0)) box[0] -= dy / 2, box[2] += dy / 2;
        if (!(dy > 0.0)) box[1] -= dx / 2, box[3] += dx / 2;
    }

    const double unit = fmin(w, h);
    const double label_size = fmin(16.0, fmax(10.0, 0.028 * unit));
    double title_size = label_size * 1.25;
    const double tick_len = 5.0;
    /* Layout; a rectangle too small for the text falls back to a bare plot (no axes, no
     * text, 2 px margin) before giving up. */
    cj_font *font = font_in;
    int axes = plot->axes;
    double margin = plot->margin;
    double left, right, top, bottom, ax0, ay0, ax1, ay1, pad;
    double lab_asc = 0.0, lab_desc = 0.0;
    cj_status st = CJ_OK;
    for (int attempt = 0;; ++attempt) {
        left = right = top = bottom = margin;
        if (font && plot->title) {
            double a = 0, d = 0;
            double adv = 0;
            if ((st = cj_font_measure(font, title_size, plot->title, &adv, NULL, NULL))) return st;
            /* A title wider than the panel is set smaller (down to 8 px), then clipped. */
            const double room = w - 2 * margin;
            if (adv > room && room > 0) title_size = fmax(8.0, floor(title_size * room / adv));
            if ((st = cj_font_measure(font, title_size, plot->title, NULL, &a, &d))) return st;
            top += a + d + 4.0;
        }
        if (axes) {
            left += tick_len;
            bottom += tick_len;
            if (font) {
                double wl = 0;
                if ((st = cj_font_measure(font, label_size, "0", NULL, &lab_asc, &lab_desc)))
                    return st;
                ticks ty = make_ticks(box[1], box[3], 5.0);
                if ((st = widest_label(font, label_size, ty, &wl))) return st;
                left += wl + 4.0;
                bottom += lab_asc + lab_desc + 2.0;
                right += wl / 2; /* the last x label is centred on the right edge */
            }
        }
        /* Padding inside the frame so that strokes and markers are not cut by it. */
        double widest = 6.0;
        for (size_t i = 0; i < plot->count; ++i)
            if (plot->items[i].width > widest) widest = plot->items[i].width;
        pad = plot->has_view ? 0.0 : widest + 4.0;
        ax0 = left, ay0 = bottom, ax1 = w - right, ay1 = h - top;
        if (ax1 - ax0 >= 2 * pad + 8 && ay1 - ay0 >= 2 * pad + 8) break;
        if ((attempt == 1 || (!axes && !font && margin <= 2.0)) && ax1 - ax0 >= 8 &&
            ay1 - ay0 >= 8) {
            /* Tiny: a plot whose strokes may touch its edge rather than no plot at all. */
            pad = fmax(0.0, 0.5 * (fmin(ax1 - ax0, ay1 - ay0) - 8.0));
            break;
        }
        if (attempt == 1 || (!axes && !font && margin <= 2.0))
            return cj_fail(CJ_ERR_RANGE, "plot rectangle %dx%d is too small for its contents", w,
                           h);
        axes = 0;
        font = NULL;
        margin = fmin(margin, 2.0);
    }
    xform x;
    x.s =
        fmin((ax1 - ax0 - 2 * pad) / (box[2] - box[0]), (ay1 - ay0 - 2 * pad) / (box[3] - box[1]));
    x.cx = 0.5 * (box[0] + box[2]);
    x.cy = 0.5 * (box[1] + box[3]);
    x.ox = 0.5 * (ax0 + ax1);
    x.oy = 0.5 * (ay0 + ay1);
    if (!(x.s > 0.0) || !isfinite(x.s))
        return cj_fail(CJ_ERR_DEGENERATE, "plotted data span cannot be scaled to pixels");

    cj_plot_canvas cv;
    if ((st = cj_plot_canvas_init(&cv, w, h))) return st;
    cv.arrow_len = fmax(36.0, fmin(90.0, 0.16 * fmin(ax1 - ax0, ay1 - ay0)));
    cj_framebuffer_clear(cv.fb, plot->background);

    const double vx0 = x.cx + (ax0 - x.ox) / x.s, vx1 = x.cx + (ax1 - x.ox) / x.s;
    const double vy0 = x.cy + (ay0 - x.oy) / x.s, vy1 = x.cy + (ay1 - x.oy) / x.s;
    ticks tx = make_ticks(vx0, vx1, fmax(2.0, (ax1 - ax0) / 75.0));
    ticks ty = make_ticks(vy0, vy1, fmax(2.0, (ay1 - ay0) / 70.0));
    const cj_rgba grid = cj_rgba_make(0xe6, 0xe6, 0xe6, 255);
    const cj_rgba ink = cj_rgba_make(0x40, 0x40, 0x40, 255);
    if (axes) {
        for (int i = 0; !st && i < tx.count; ++i) {
            double px = x.ox + x.s * (tx.first + i * tx.step - x.cx);
            double seg[4] = {px, ay0, px, ay1};
            st = cj_plot_stroke(&cv, seg, 2, 0, grid, 1.0);
        }
        for (int i = 0; !st && i < ty.count; ++i) {
            double py = x.oy + x.s * (ty.first + i * ty.step - x.cy);
            double seg[4] = {ax0, py, ax1, py};
            st = cj_plot_stroke(&cv, seg, 2, 0, grid, 1.0);
        }
    }
    for (size_t i = 0; !st && i < plot->count; ++i) {
        const plot_item *it = &plot->items[i];
        switch (it->type) {
        case ITEM_BEZIER:
            st = draw_bezier(&cv, &x, it);
            break;
        case ITEM_SPLINE:
            st = draw_spline(&cv, &x, it);
            break;
        case ITEM_IMPLICIT:
            for (size_t k = 0; !st && k < it->nsegs; ++k)
                st = draw_pointlist(&cv, &x, it->pts + 2 * it->offsets[k],
                                    it->offsets[k + 1] - it->offsets[k], it->closed_flags[k],
                                    it->color, it->width);
            break;
        case ITEM_POLYLINE:
            st = draw_pointlist(&cv, &x, it->pts, it->npts, it->closed, it->color, it->width);
            if (!st && it->markers)
                for (size_t k = 0; k < it->npts; ++k) {
                    double p[2];
                    to_px(&x, it->pts + 2 * k, p);
                    cj_plot_disc(&cv, p[0], p[1], 1.5 + it->width, it->color);
                }
            break;
        case ITEM_POINTS:
            for (size_t k = 0; k < it->npts; ++k) {
                double p[2];
                to_px(&x, it->pts + 2 * k, p);
                cj_plot_disc(&cv, p[0], p[1], it->width, it->color);
            }
            break;
        }
    }
    if (!st && axes) {
        /* Blank out anything outside the frame (arrows may reach out), then frame and ticks. */
        cj_plot_blank_outside(&cv, ax0, ay0, ax1, ay1, plot->background);
        double frame[8] = {ax0, ay0, ax1, ay0, ax1, ay1, ax0, ay1};
        st = cj_plot_stroke(&cv, frame, 4, 1, ink, 1.0);
        for (int i = 0; !st && i < tx.count; ++i) {
            double v = tx.first + i * tx.step;
            double px = x.ox + x.s * (v - x.cx);
            double seg[4] = {px, ay0, px, ay0 - tick_len};
            st = cj_plot_stroke(&cv, seg, 2, 0, ink, 1.0);
            if (!st && font) {
                char buf[80];
                double adv = 0;
                format_tick(v, tx.step, buf, sizeof buf);
                st = cj_font_measure(font, label_size, buf, &adv, NULL, NULL);
                if (!st)
                    st = cj_font_draw(font, cv.fb, px - adv / 2, ay0 - tick_len - 2 - lab_asc,
                                      label_size, ink, buf);
            }
        }
        for (int i = 0; !st && i < ty.count; ++i) {
            double v = ty.first + i * ty.step;
            double py = x.oy + x.s * (v - x.cy);
            double seg[4] = {ax0, py, ax0 - tick_len, py};
            st = cj_plot_stroke(&cv, seg, 2, 0, ink, 1.0);
            if (!st && font) {
                char buf[80];
                double adv = 0;
                format_tick(v, ty.step, buf, sizeof buf);
                st = cj_font_measure(font, label_size, buf, &adv, NULL, NULL);
                if (!st)
                    st = cj_font_draw(font, cv.fb, ax0 - tick_len - 3 - adv, py - 0.35 * label_size,
                                      label_size, ink, buf);
            }
        }
    }
    if (!st && font && plot->title) {
        double adv = 0, a = 0;
        st = cj_font_measure(font, title_size, plot->title, &adv, &a, NULL);
        if (!st)
            st = cj_font_draw(font, cv.fb, 0.5 * (ax0 + ax1) - adv / 2, h - margin - a, title_size,
                              cj_rgba_make(0x20, 0x20, 0x20, 255), plot->title);
    }
    if (!st) {
        for (int row = 0; row < h; ++row)
            memcpy(fb->pixels + (ptrdiff_t)(y0 + row) * fb->stride + x0,
                   cv.fb->pixels + (ptrdiff_t)row * cv.fb->stride, (size_t)w * sizeof(cj_rgba));
    }
    cj_plot_canvas_free(&cv);
    return st;
}

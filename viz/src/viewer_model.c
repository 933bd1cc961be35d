/* The 2D editor model: curves and the command log (casteljau/viewer_model.h).
 *
 * Every command stores the curves it removed and the curves it put in their place (deep
 * copies), so undo and redo are plain copies and restore the geometry bit for bit; a point
 * move stores only the two positions. */
#include "casteljau/viewer_model.h"

#include "casteljau/bezier.h"
#include "casteljau/rational.h"
#include "error_internal.h"
#include "viewer_internal.h"

#include <assert.h>
#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct vcmd {
    int is_move;
    size_t at; /* first curve index touched */
    /* replace: curves [at, at+nbefore) were `before`, became `after` */
    size_t nbefore, nafter;
    cj_vcurve *before, *after;
    /* move */
    size_t point;
    double from[2], to[2];
} vcmd;

struct cj_vdoc {
    cj_vcurve *curves;
    size_t count, cap;
    vcmd *log;
    size_t nlog, pos, logcap; /* commands [0, pos) are done, [pos, nlog) undone */
    int drag_open, drag_merge;
};

cj_vcurve cj_vcurve_init(cj_vcurve_kind kind, size_t count, const double *pts,
                         const double *weights) {
    cj_vcurve c;
    memset(&c, 0, sizeof c);
    const cj_plot_bezier_opts d = cj_plot_bezier_defaults();
    c.kind = kind;
    c.count = count;
    c.pts = (double *)pts;
    c.weights = (double *)weights;
    c.spline = cj_spline_defaults();
    c.color = d.color;
    c.width = d.width;
    c.control_polygon = d.control_polygon;
    c.control_points = d.control_points;
    c.hull = d.hull;
    c.normals = d.normals;
    c.knots = 1;
    return c;
}

/* ---- view ---------------------------------------------------------------------------- */

double cj_vview_scale(const cj_vview *v) {
    return fmin((double)v->width / (v->x1 - v->x0), (double)v->height / (v->y1 - v->y0));
}

/* The same operations, in the same order, as the plot's to_px (raster/src/plot.c) with
 * ax0 = ay0 = 0, ax1 = width, ay1 = height and no padding. */
void cj_vview_to_px(const cj_vview *v, double x, double y, double out[2]) {
    const double s = cj_vview_scale(v);
    const double ox = 0.5 * (0.0 + v->width), oy = 0.5 * (0.0 + v->height);
    out[0] = ox + s * (x - 0.5 * (v->x0 + v->x1));
    out[1] = oy + s * (y - 0.5 * (v->y0 + v->y1));
}

void cj_vview_from_px(const cj_vview *v, double px, double py, double out[2]) {
    const double s = cj_vview_scale(v);
    out[0] = 0.5 * (v->x0 + v->x1) + (px - 0.5 * v->width) / s;
    out[1] = 0.5 * (v->y0 + v->y1) + (py - 0.5 * v->height) / s;
}

void cj_vview_fit(cj_vview *v, const cj_vdoc *doc, double border) {
    double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
    for (size_t c = 0; c < doc->count; ++c)
        for (size_t i = 0; i < doc->curves[c].count; ++i)
            for (int k = 0; k < 2; ++k) {
                lo[k] = fmin(lo[k], doc->curves[c].pts[2 * i + k]);
                hi[k] = fmax(hi[k], doc->curves[c].pts[2 * i + k]);
            }
    if (!(lo[0] <= hi[0])) lo[0] = lo[1] = -1.0, hi[0] = hi[1] = 1.0;
    double side = fmax(hi[0] - lo[0], hi[1] - lo[1]);
    if (!(side > 0.0)) side = 2.0;
    const double b = border * side;
    v->x0 = lo[0] - b, v->y0 = lo[1] - b, v->x1 = hi[0] + b, v->y1 = hi[1] + b;
    if (!(v->x1 > v->x0)) v->x0 -= side / 2, v->x1 += side / 2;
    if (!(v->y1 > v->y0)) v->y0 -= side / 2, v->y1 += side / 2;
}

/* ---- curves -------------------------------------------------------------------------- */

static void curve_free(cj_vcurve *c) {
    free(c->pts);
    free(c->weights);
    free(c->knot_vector);
    c->pts = c->weights = c->knot_vector = NULL;
}

static size_t knot_count(const cj_vcurve *c) {
    return c->kind == CJ_VCURVE_BSPLINE ? c->count + (size_t)c->degree + 1 : 0;
}

cj_bspline cj_vcurve_bspline(const cj_vcurve *c) {
    return cj_bspline_view(c->degree, 2, (int)c->count, c->pts, c->weights, c->knot_vector);
}

cj_status cj_vcurve_support(const cj_vcurve *c, size_t i, double *u0, double *u1) {
    if (c->kind != CJ_VCURVE_BSPLINE || i >= c->count)
        return cj_fail(CJ_ERR_ARGUMENT,
                       "viewer: point %zu of a curve that is not a B-spline of "
                       "more points",
                       i);
    const size_t p = (size_t)c->degree;
    *u0 = fmax(c->knot_vector[i], c->knot_vector[p]);
    *u1 = fmin(c->knot_vector[i + p + 1], c->knot_vector[c->count]);
    return CJ_OK;
}

static cj_status curve_copy(const cj_vcurve *src, cj_vcurve *dst) {
    *dst = *src;
    dst->pts = malloc((src->count ? src->count : 1) * 2 * sizeof(double));
    dst->weights = dst->knot_vector = NULL;
    if (src->weights) dst->weights = malloc((src->count ? src->count : 1) * sizeof(double));
    if (src->knot_vector) dst->knot_vector = malloc((knot_count(src) + 1) * sizeof(double));
    if (!dst->pts || (src->weights && !dst->weights) || (src->knot_vector && !dst->knot_vector)) {
        curve_free(dst);
        return cj_fail(CJ_ERR_NOMEM, "viewer: out of memory copying a curve of %zu points",
                       src->count);
    }
    memcpy(dst->pts, src->pts, src->count * 2 * sizeof(double));
    if (src->weights) memcpy(dst->weights, src->weights, src->count * sizeof(double));
    if (src->knot_vector)
        memcpy(dst->knot_vector, src->knot_vector, knot_count(src) * sizeof(double));
    return CJ_OK;
}

static cj_status curve_check(const cj_vcurve *c) {
    const size_t min = c->kind == CJ_VCURVE_SPLINE ? 2 : 1;
    if (c->kind > CJ_VCURVE_BSPLINE)
        return cj_fail(CJ_ERR_ARGUMENT, "viewer: unknown curve kind %d", (int)c->kind);
    if (c->kind == CJ_VCURVE_BSPLINE) {
        if (!c->knot_vector) return cj_fail(CJ_ERR_ARGUMENT, "viewer: a B-spline needs knots");
        if (c->count > (size_t)INT_MAX / 2)
            return cj_fail(CJ_ERR_RANGE, "viewer: a B-spline of %zu points", c->count);
        const cj_bspline b = cj_vcurve_bspline(c);
        cj_status st = cj_bspline_check(&b);
        if (st) return st;
    } else if (c->knot_vector) {
        return cj_fail(CJ_ERR_ARGUMENT, "viewer: only B-splines have knots");
    }
    if (c->count < min)
        return cj_fail(CJ_ERR_RANGE, "viewer: a %s needs at least %zu points, not %zu",
                       c->kind == CJ_VCURVE_SPLINE ? "spline" : "Bezier curve", min, c->count);
    if (c->kind < CJ_VCURVE_SPLINE && c->count > (size_t)CJ_BEZIER_MAX_DEGREE + 1)
        return cj_fail(CJ_ERR_RANGE, "viewer: %zu points: the degree is at most %d", c->count,
                       CJ_BEZIER_MAX_DEGREE);
    for (size_t i = 0; i < 2 * c->count; ++i)
        if (!isfinite(c->pts[i]))
            return cj_fail(CJ_ERR_NONFINITE, "viewer: point %zu has a non-finite coordinate",
                           i / 2);
    if (c->kind == CJ_VCURVE_RATIONAL || (c->kind == CJ_VCURVE_BSPLINE && c->weights)) {
        if (!c->weights) return cj_fail(CJ_ERR_ARGUMENT, "viewer: a rational curve needs weights");
        for (size_t i = 0; i < c->count; ++i)
            if (!(c->weights[i] > 0.0) || !isfinite(c->weights[i]))
                return cj_fail(CJ_ERR_RANGE, "viewer: weight %zu = %g is not positive and finite",
                               i, c->weights[i]);
    } else if (c->weights) {
        return cj_fail(CJ_ERR_ARGUMENT, "viewer: only rational curves have weights");
    }
    if (!(c->width > 0.0 && c->width <= CJ_PLOT_MAX_WIDTH))
        return cj_fail(CJ_ERR_RANGE, "viewer: stroke width %g px out of (0, %g]", c->width,
                       CJ_PLOT_MAX_WIDTH);
    return CJ_OK;
}

cj_status cj_vdoc_create(cj_vdoc **out) {
    assert(out);
    cj_vdoc *d = calloc(1, sizeof *d);
    if (!d) return cj_fail(CJ_ERR_NOMEM, "viewer: out of memory for a document");
    *out = d;
    return CJ_OK;
}

static void cmd_free(vcmd *c) {
    for (size_t i = 0; i < c->nbefore; ++i) curve_free(&c->before[i]);
    for (size_t i = 0; i < c->nafter; ++i) curve_free(&c->after[i]);
    free(c->before);
    free(c->after);
    memset(c, 0, sizeof *c);
}

void cj_vdoc_destroy(cj_vdoc *doc) {
    if (!doc) return;
    for (size_t i = 0; i < doc->count; ++i) curve_free(&doc->curves[i]);
    for (size_t i = 0; i < doc->nlog; ++i) cmd_free(&doc->log[i]);
    free(doc->curves);
    free(doc->log);
    free(doc);
}

size_t cj_vdoc_curve_count(const cj_vdoc *doc) {
    return doc->count;
}
const cj_vcurve *cj_vdoc_curve(const cj_vdoc *doc, size_t i) {
    return i < doc->count ? &doc->curves[i] : NULL;
}
size_t cj_vdoc_undo_depth(const cj_vdoc *doc) {
    return doc->pos;
}
size_t cj_vdoc_redo_depth(const cj_vdoc *doc) {
    return doc->nlog - doc->pos;
}

void cj_vdoc_clear_log(cj_vdoc *doc) {
    for (size_t i = 0; i < doc->nlog; ++i) cmd_free(&doc->log[i]);
    doc->nlog = doc->pos = 0;
    doc->drag_merge = 0;
}

/* Replaces curves [at, at+nremove) by copies of add[0..nadd) (no log). */
static cj_status splice(cj_vdoc *doc, size_t at, size_t nremove, const cj_vcurve *add,
                        size_t nadd) {
    const size_t n = doc->count - nremove + nadd;
    if (n > doc->cap) {
        size_t cap = doc->cap ? doc->cap * 2 : 8;
        while (cap < n) cap *= 2;
        cj_vcurve *nc = realloc(doc->curves, cap * sizeof *nc);
        if (!nc) return cj_fail(CJ_ERR_NOMEM, "viewer: out of memory for %zu curves", n);
        doc->curves = nc;
        doc->cap = cap;
    }
    cj_vcurve tmp[4];
    assert(nadd <= 4);
    for (size_t i = 0; i < nadd; ++i)
        if (curve_copy(&add[i], &tmp[i])) {
            while (i--) curve_free(&tmp[i]);
            return CJ_ERR_NOMEM;
        }
    for (size_t i = 0; i < nremove; ++i) curve_free(&doc->curves[at + i]);
    memmove(doc->curves + at + nadd, doc->curves + at + nremove,
            (doc->count - at - nremove) * sizeof *doc->curves);
    memcpy(doc->curves + at, tmp, nadd * sizeof *tmp);
    doc->count = n;
    return CJ_OK;
}

static cj_status log_push(cj_vdoc *doc, vcmd *c) {
    for (size_t i = doc->pos; i < doc->nlog; ++i) cmd_free(&doc->log[i]);
    doc->nlog = doc->pos;
    if (doc->nlog == doc->logcap) {
        size_t cap = doc->logcap ? doc->logcap * 2 : 64;
        vcmd *nl = realloc(doc->log, cap * sizeof *nl);
        if (!nl) return cj_fail(CJ_ERR_NOMEM, "viewer: out of memory for the undo log");
        doc->log = nl;
        doc->logcap = cap;
    }
    doc->log[doc->nlog++] = *c;
    doc->pos = doc->nlog;
    doc->drag_merge = 0;
    return CJ_OK;
}

/* Records and applies "curves [at, at+nbefore) become after[0..nafter)". Takes ownership of
 * nothing: copies everything. */
static cj_status replace(cj_vdoc *doc, size_t at, size_t nbefore, const cj_vcurve *after,
                         size_t nafter) {
    for (size_t i = 0; i < nafter; ++i) {
        cj_status st = curve_check(&after[i]);
        if (st) return st;
    }
    vcmd c;
    memset(&c, 0, sizeof c);
    c.at = at;
    c.before = calloc(nbefore ? nbefore : 1, sizeof *c.before);
    c.after = calloc(nafter ? nafter : 1, sizeof *c.after);
    cj_status st = (!c.before || !c.after)
                       ? cj_fail(CJ_ERR_NOMEM, "viewer: out of memory for an edit")
                       : CJ_OK;
    for (size_t i = 0; !st && i < nbefore; ++i)
        if (!(st = curve_copy(&doc->curves[at + i], &c.before[i]))) c.nbefore++;
    for (size_t i = 0; !st && i < nafter; ++i)
        if (!(st = curve_copy(&after[i], &c.after[i]))) c.nafter++;
    if (!st) st = splice(doc, at, nbefore, after, nafter);
    if (!st) st = log_push(doc, &c);
    if (st) cmd_free(&c);
    return st;
}

static cj_status need_curve(const cj_vdoc *doc, size_t ci) {
    if (ci >= doc->count)
        return cj_fail(CJ_ERR_ARGUMENT, "viewer: curve %zu does not exist (%zu curves)", ci,
                       doc->count);
    return CJ_OK;
}

static cj_status need_point(const cj_vdoc *doc, size_t ci, size_t i) {
    cj_status st = need_curve(doc, ci);
    if (!st && i >= doc->curves[ci].count)
        st = cj_fail(CJ_ERR_ARGUMENT, "viewer: curve %zu has no point %zu (%zu points)", ci, i,
                     doc->curves[ci].count);
    return st;
}

cj_status cj_vdoc_add_curve(cj_vdoc *doc, const cj_vcurve *c) {
    assert(doc && c);
    return replace(doc, doc->count, 0, c, 1);
}

cj_status cj_vdoc_remove_curve(cj_vdoc *doc, size_t ci) {
    cj_status st = need_curve(doc, ci);
    return st ? st : replace(doc, ci, 1, NULL, 0);
}

void cj_vdoc_begin_drag(cj_vdoc *doc) {
    doc->drag_open = 1;
    doc->drag_merge = 0;
}
void cj_vdoc_end_drag(cj_vdoc *doc) {
    doc->drag_open = doc->drag_merge = 0;
}

cj_status cj_vdoc_move_point(cj_vdoc *doc, size_t ci, size_t i, double x, double y) {
    cj_status st = need_point(doc, ci, i);
    if (st) return st;
    if (!isfinite(x) || !isfinite(y))
        return cj_fail(CJ_ERR_NONFINITE, "viewer: move of point %zu to a non-finite position", i);
    double *p = doc->curves[ci].pts + 2 * i;
    vcmd *last = doc->pos ? &doc->log[doc->pos - 1] : NULL;
    if (doc->drag_merge && last && last->is_move && last->at == ci && last->point == i &&
        doc->pos == doc->nlog) {
        last->to[0] = p[0] = x;
        last->to[1] = p[1] = y;
        return CJ_OK;
    }
    vcmd c;
    memset(&c, 0, sizeof c);
    c.is_move = 1;
    c.at = ci;
    c.point = i;
    c.from[0] = p[0], c.from[1] = p[1];
    c.to[0] = x, c.to[1] = y;
    if ((st = log_push(doc, &c))) return st;
    p[0] = x, p[1] = y;
    doc->drag_merge = doc->drag_open;
    return CJ_OK;
}

/* A working copy of curve ci with room for `extra` more points. */
static cj_status work_copy(const cj_vdoc *doc, size_t ci, size_t extra, cj_vcurve *out) {
    const cj_vcurve *c = &doc->curves[ci];
    cj_vcurve big = *c;
    big.count = c->count + extra;
    *out = *c;
    out->pts = calloc(big.count * 2, sizeof(double));
    out->weights = c->weights ? calloc(big.count, sizeof(double)) : NULL;
    out->knot_vector = c->knot_vector ? calloc(knot_count(&big), sizeof(double)) : NULL;
    if (!out->pts || (c->weights && !out->weights) || (c->knot_vector && !out->knot_vector)) {
        curve_free(out);
        return cj_fail(CJ_ERR_NOMEM, "viewer: out of memory editing curve %zu", ci);
    }
    memcpy(out->pts, c->pts, c->count * 2 * sizeof(double));
    if (c->weights) memcpy(out->weights, c->weights, c->count * sizeof(double));
    if (c->knot_vector) memcpy(out->knot_vector, c->knot_vector, knot_count(c) * sizeof(double));
    return CJ_OK;
}

static cj_status not_bspline(const cj_vdoc *doc, size_t ci, const char *what) {
    if (doc->curves[ci].kind != CJ_VCURVE_BSPLINE) return CJ_OK;
    return cj_fail(CJ_ERR_ARGUMENT,
                   "viewer: curve %zu is a B-spline: %s does not apply (insert a knot)", ci, what);
}

cj_status cj_vdoc_set_weight(cj_vdoc *doc, size_t ci, size_t i, double w) {
    cj_status st = need_point(doc, ci, i);
    if (st) return st;
    const cj_vcurve *src = &doc->curves[ci];
    if (src->kind != CJ_VCURVE_RATIONAL && src->kind != CJ_VCURVE_BSPLINE)
        return cj_fail(CJ_ERR_ARGUMENT, "viewer: curve %zu is not rational: it has no weights", ci);
    cj_vcurve c;
    if ((st = work_copy(doc, ci, 0, &c))) return st;
    if (!c.weights) { /* a polynomial B-spline becomes a NURBS */
        if (!(c.weights = malloc(c.count * sizeof(double)))) {
            curve_free(&c);
            return cj_fail(CJ_ERR_NOMEM, "viewer: out of memory for weights");
        }
        for (size_t k = 0; k < c.count; ++k) c.weights[k] = 1.0;
    }
    c.weights[i] = w;
    st = replace(doc, ci, 1, &c, 1);
    curve_free(&c);
    return st;
}

cj_status cj_vdoc_insert_point(cj_vdoc *doc, size_t ci, size_t i, double x, double y) {
    cj_status st = need_curve(doc, ci);
    if (st) return st;
    if ((st = not_bspline(doc, ci, "inserting a control point"))) return st;
    const size_t n = doc->curves[ci].count;
    if (i > n) return cj_fail(CJ_ERR_ARGUMENT, "viewer: insert at %zu past the end (%zu)", i, n);
    cj_vcurve c;
    if ((st = work_copy(doc, ci, 1, &c))) return st;
    memmove(c.pts + 2 * (i + 1), c.pts + 2 * i, (n - i) * 2 * sizeof(double));
    c.pts[2 * i] = x, c.pts[2 * i + 1] = y;
    if (c.weights) {
        memmove(c.weights + i + 1, c.weights + i, (n - i) * sizeof(double));
        c.weights[i] = 1.0;
    }
    c.count = n + 1;
    st = replace(doc, ci, 1, &c, 1);
    curve_free(&c);
    return st;
}

cj_status cj_vdoc_delete_point(cj_vdoc *doc, size_t ci, size_t i) {
    cj_status st = need_point(doc, ci, i);
    if (st) return st;
    if ((st = not_bspline(doc, ci, "deleting a control point"))) return st;
    cj_vcurve c;
    if ((st = work_copy(doc, ci, 0, &c))) return st;
    const size_t n = c.count;
    memmove(c.pts + 2 * i, c.pts + 2 * (i + 1), (n - i - 1) * 2 * sizeof(double));
    if (c.weights) memmove(c.weights + i, c.weights + i + 1, (n - i - 1) * sizeof(double));
    c.count = n - 1;
    st = replace(doc, ci, 1, &c, 1); /* curve_check refuses too few points */
    curve_free(&c);
    return st;
}

cj_status cj_vdoc_elevate(cj_vdoc *doc, size_t ci) {
    cj_status st = need_curve(doc, ci);
    if (st) return st;
    const cj_vcurve *src = &doc->curves[ci];
    if (src->kind == CJ_VCURVE_SPLINE)
        return cj_fail(CJ_ERR_ARGUMENT, "viewer: curve %zu is a spline: it has no degree", ci);
    if ((st = not_bspline(doc, ci, "Bezier degree elevation"))) return st;
    const size_t n = src->count;
    if (n > (size_t)CJ_BEZIER_MAX_DEGREE)
        return cj_fail(CJ_ERR_RANGE, "viewer: curve %zu already has degree %d", ci,
                       CJ_BEZIER_MAX_DEGREE);
    cj_vcurve c;
    if ((st = work_copy(doc, ci, 1, &c))) return st;
    if (src->kind == CJ_VCURVE_BEZIER) {
        cj_bezier b = cj_bezier_view((int)n - 1, 2, src->pts);
        st = cj_bezier_elevate(&b, 1, c.pts);
    } else {
        /* Elevation is linear in the homogeneous points (w x, w y, w). */
        double *h = malloc((n + 1) * 3 * sizeof(double));
        if (!h) st = cj_fail(CJ_ERR_NOMEM, "viewer: out of memory elevating curve %zu", ci);
        cj_rbezier rb = cj_rbezier_view((int)n - 1, 2, src->pts, src->weights);
        if (!st) st = cj_rbezier_homogeneous(&rb, h);
        if (!st) {
            cj_bezier b = cj_bezier_view((int)n - 1, 3, h);
            double *tmp = malloc((n + 1) * 3 * sizeof(double));
            if (!tmp) st = cj_fail(CJ_ERR_NOMEM, "viewer: out of memory elevating curve %zu", ci);
            if (!st) st = cj_bezier_elevate(&b, 1, tmp);
            for (size_t i = 0; !st && i <= n; ++i) {
                c.weights[i] = tmp[3 * i + 2];
                c.pts[2 * i] = tmp[3 * i] / tmp[3 * i + 2];
                c.pts[2 * i + 1] = tmp[3 * i + 1] / tmp[3 * i + 2];
            }
            free(tmp);
        }
        free(h);
    }
    c.count = n + 1;
    if (!st) st = replace(doc, ci, 1, &c, 1);
    curve_free(&c);
    return st;
}

cj_status cj_vdoc_split(cj_vdoc *doc, size_t ci, double t) {
    cj_status st = need_curve(doc, ci);
    if (st) return st;
    const cj_vcurve *src = &doc->curves[ci];
    if (src->kind == CJ_VCURVE_SPLINE)
        return cj_fail(CJ_ERR_ARGUMENT, "viewer: curve %zu is a spline: split a Bezier curve", ci);
    if ((st = not_bspline(doc, ci, "splitting at t"))) return st;
    if (!(t >= 0.0 && t <= 1.0))
        return cj_fail(CJ_ERR_RANGE, "viewer: split parameter %g is not in [0, 1]", t);
    cj_vcurve two[2];
    if ((st = work_copy(doc, ci, 0, &two[0]))) return st;
    if ((st = work_copy(doc, ci, 0, &two[1]))) {
        curve_free(&two[0]);
        return st;
    }
    const int deg = (int)src->count - 1;
    if (src->kind == CJ_VCURVE_BEZIER) {
        cj_bezier b = cj_bezier_view(deg, 2, src->pts);
        st = cj_bezier_split(&b, t, two[0].pts, two[1].pts);
    } else {
        cj_rbezier rb = cj_rbezier_view(deg, 2, src->pts, src->weights);
        st = cj_rbezier_split(&rb, t, two[0].pts, two[0].weights, two[1].pts, two[1].weights);
    }
    if (!st) st = replace(doc, ci, 1, two, 2);
    curve_free(&two[0]);
    curve_free(&two[1]);
    return st;
}

cj_status cj_vdoc_insert_knot(cj_vdoc *doc, size_t ci, double u) {
    assert(doc);
    cj_status st = need_curve(doc, ci);
    if (st) return st;
    const cj_vcurve *src = &doc->curves[ci];
    if (src->kind != CJ_VCURVE_BSPLINE)
        return cj_fail(CJ_ERR_ARGUMENT, "viewer: curve %zu is not a B-spline: it has no knots", ci);
    cj_vcurve c;
    if ((st = work_copy(doc, ci, 1, &c))) return st;
    const cj_bspline b = cj_vcurve_bspline(src);
    st = cj_bspline_insert_knot(&b, u, 1, c.pts, c.weights, c.knot_vector);
    c.count = src->count + 1;
    if (!st) st = replace(doc, ci, 1, &c, 1);
    curve_free(&c);
    return st;
}

cj_status cj_vdoc_set_style(cj_vdoc *doc, size_t ci, const cj_vcurve *style) {
    cj_status st = need_curve(doc, ci);
    if (st) return st;
    cj_vcurve c;
    if ((st = work_copy(doc, ci, 0, &c))) return st;
    c.color = style->color;
    c.width = style->width;
    c.control_polygon = style->control_polygon;
    c.control_points = style->control_points;
    c.hull = style->hull;
    c.normals = style->normals;
    c.knots = style->knots;
    c.nframes = style->nframes > CJ_PLOT_MAX_FRAMES ? CJ_PLOT_MAX_FRAMES : style->nframes;
    memcpy(c.frames_t, style->frames_t, sizeof c.frames_t);
    st = replace(doc, ci, 1, &c, 1);
    curve_free(&c);
    return st;
}

cj_status cj_vdoc_undo(cj_vdoc *doc) {
    if (!doc->pos) return cj_fail(CJ_ERR_EMPTY, "viewer: nothing to undo");
    vcmd *c = &doc->log[doc->pos - 1];
    if (c->is_move) {
        doc->curves[c->at].pts[2 * c->point] = c->from[0];
        doc->curves[c->at].pts[2 * c->point + 1] = c->from[1];
    } else {
        cj_status st = splice(doc, c->at, c->nafter, c->before, c->nbefore);
        if (st) return st;
    }
    doc->pos--;
    doc->drag_merge = 0;
    return CJ_OK;
}

cj_status cj_vdoc_redo(cj_vdoc *doc) {
    if (doc->pos == doc->nlog) return cj_fail(CJ_ERR_EMPTY, "viewer: nothing to redo");
    vcmd *c = &doc->log[doc->pos];
    if (c->is_move) {
        doc->curves[c->at].pts[2 * c->point] = c->to[0];
        doc->curves[c->at].pts[2 * c->point + 1] = c->to[1];
    } else {
        cj_status st = splice(doc, c->at, c->nbefore, c->after, c->nafter);
        if (st) return st;
    }
    doc->pos++;
    doc->drag_merge = 0;
    return CJ_OK;
}

/* ---- picking ------------------------------------------------------------------------- */

int cj_vdoc_pick(const cj_vdoc *doc, const cj_vview *v, double px, double py, double radius,
                 size_t *ci, size_t *pi) {
    int found = 0;
    double bx = 0, by = 0;
    for (size_t c = 0; c < doc->count; ++c)
        for (size_t i = 0; i < doc->curves[c].count; ++i) {
            double q[2];
            cj_vview_to_px(v, doc->curves[c].pts[2 * i], doc->curves[c].pts[2 * i + 1], q);
            if (!cj_vpick_within(q[0], q[1], px, py, radius)) continue;
            if (!found || cj_vpick_closer(q[0], q[1], bx, by, px, py) < 0) {
                found = 1;
                bx = q[0], by = q[1];
                *ci = c, *pi = i;
            }
        }
    return found;
}

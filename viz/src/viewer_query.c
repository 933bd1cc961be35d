/* The 2D editor's queries (casteljau/viewer_model.h): every curve kind as Bézier pieces, the
 * certified nearest point of the document's curves (snapping) and the intersections between
 * curves. The work is done by nearest.h and intersect.h, piece by piece; this file only maps
 * pieces back to curves and parameters. */
#include "casteljau/viewer_model.h"

#include "casteljau/intersect.h"
#include "casteljau/nearest.h"
#include "error_internal.h"

#include <assert.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

void cj_vpieces_free(cj_vpieces *p) {
    free(p->pts);
    free(p->w);
    free(p->breaks);
    memset(p, 0, sizeof *p);
}

static cj_status pieces_alloc(cj_vpieces *p, int n, int degree, int rational) {
    const size_t per = (size_t)degree + 1;
    p->n = n;
    p->degree = degree;
    p->pts = malloc((size_t)n * per * 2 * sizeof(double));
    p->w = rational ? malloc((size_t)n * per * sizeof(double)) : NULL;
    p->breaks = malloc(((size_t)n + 1) * sizeof(double));
    if (!p->pts || !p->breaks || (rational && !p->w)) {
        cj_vpieces_free(p);
        return cj_fail(CJ_ERR_NOMEM, "viewer: out of memory for %d curve pieces", n);
    }
    return CJ_OK;
}

cj_status cj_vcurve_pieces(const cj_vcurve *c, cj_vpieces *out) {
    assert(c && out);
    memset(out, 0, sizeof *out);
    cj_status st;
    if (c->kind == CJ_VCURVE_BSPLINE) {
        const cj_bspline b = cj_vcurve_bspline(c);
        int n = 0;
        if ((st = cj_bspline_bezier_count(&b, &n))) return st;
        if ((st = pieces_alloc(out, n, c->degree, c->weights != NULL))) return st;
        if ((st = cj_bspline_to_bezier(&b, out->pts, out->w, out->breaks, n, NULL)))
            cj_vpieces_free(out);
        return st;
    }
    if (c->kind == CJ_VCURVE_SPLINE) {
        const size_t n = cj_spline_segment_count(c->count, c->spline.closed);
        if (!n || n > (size_t)1 << 24)
            return cj_fail(CJ_ERR_RANGE, "viewer: a spline of %zu points has no segments",
                           c->count);
        if ((st = pieces_alloc(out, (int)n, 3, 0))) return st;
        size_t got = 0;
        if ((st = cj_catmull_rom(c->pts, c->count, 2, &c->spline, out->pts, n, &got, NULL))) {
            cj_vpieces_free(out);
            return st;
        }
        for (size_t j = 0; j <= n; ++j) out->breaks[j] = (double)j;
        return CJ_OK;
    }
    if ((st = pieces_alloc(out, 1, (int)c->count - 1, c->kind == CJ_VCURVE_RATIONAL))) return st;
    memcpy(out->pts, c->pts, c->count * 2 * sizeof(double));
    if (out->w) memcpy(out->w, c->weights, c->count * sizeof(double));
    out->breaks[0] = 0.0;
    out->breaks[1] = 1.0;
    return CJ_OK;
}

static cj_bezier2 piece(const cj_vpieces *p, int j) {
    const size_t per = (size_t)p->degree + 1;
    return cj_bezier2_view(p->degree, p->pts + (size_t)j * per * 2,
                           p->w ? p->w + (size_t)j * per : NULL);
}

/* The piece's parameter t in [0, 1] as the curve's own parameter. */
static double curve_param(const cj_vpieces *p, int j, double t) {
    const double a = p->breaks[j], b = p->breaks[j + 1];
    return t >= 1.0 ? b : a + t * (b - a);
}

/* The tolerance raised to what the queries accept at the scale of the curve and point. */
static double usable_tol(const cj_bezier2 *c, const double *q, double tol) {
    double scale = q ? fmax(fabs(q[0]), fabs(q[1])) : 0.0;
    for (int i = 0; i < 2 * (c->degree + 1); ++i) scale = fmax(scale, fabs(c->pts[i]));
    return fmax(tol, ldexp(scale, -39));
}

/* The nearest point of curve ci to q, folded into *best (with the pieces of the best curve
 * kept in *bp and the piece in *bj). */
static cj_status snap_curve(const cj_vcurve *cv, size_t ci, const double q[2], double tol,
                            cj_vsnap *best, cj_vpieces *bp, int *bj) {
    cj_vpieces p;
    cj_status st = cj_vcurve_pieces(cv, &p);
    if (st) return st;
    int mine = 0;
    for (int j = 0; j < p.n && !st; ++j) {
        const cj_bezier2 c = piece(&p, j);
        cj_nearest r;
        const cj_status e = cj_nearest_curve(&c, q, usable_tol(&c, q, tol), &r);
        if (e == CJ_ERR_DEGENERATE) continue; /* a piece that is one point */
        if ((st = e)) break;
        best->pieces += r.pieces;
        best->lower = fmin(best->lower, r.lower);
        if (r.distance < best->distance) {
            best->curve = (long)ci;
            best->u = curve_param(&p, j, r.t);
            best->point[0] = r.point[0], best->point[1] = r.point[1];
            best->distance = r.distance;
            *bj = j;
            mine = 1;
        }
    }
    if (mine && !st) {
        cj_vpieces_free(bp);
        *bp = p;
    } else {
        cj_vpieces_free(&p);
    }
    return st;
}

/* Closes a search: the proven distance of the chosen point to its curve's piece. */
static cj_status snap_finish(cj_vsnap *best, cj_vpieces *bp, int bj, cj_status st, cj_vsnap *out) {
    if (!st && best->curve < 0) st = cj_fail(CJ_ERR_EMPTY, "viewer: no curve to snap to");
    if (!st) {
        const cj_bezier2 c = piece(bp, bj);
        cj_nearest r;
        st = cj_nearest_curve(&c, best->point, usable_tol(&c, best->point, 0.0), &r);
        if (!st) best->on_curve = r.distance;
    }
    cj_vpieces_free(bp);
    if (!st) *out = *best;
    return st;
}

static const cj_vsnap no_snap = {-1, 0, {0, 0}, INFINITY, INFINITY, INFINITY, 0};

cj_status cj_vdoc_snap(const cj_vdoc *doc, const double q[2], long skip, double tol,
                       cj_vsnap *out) {
    assert(doc && q && out);
    cj_vsnap best = no_snap;
    cj_vpieces bp = {0, 0, NULL, NULL, NULL};
    int bj = -1;
    cj_status st = CJ_OK;
    for (size_t ci = 0; ci < cj_vdoc_curve_count(doc) && !st; ++ci)
        if ((long)ci != skip) st = snap_curve(cj_vdoc_curve(doc, ci), ci, q, tol, &best, &bp, &bj);
    return snap_finish(&best, &bp, bj, st, out);
}

cj_status cj_vcurve_nearest(const cj_vcurve *c, const double q[2], double tol, cj_vsnap *out) {
    assert(c && q && out);
    cj_vsnap best = no_snap;
    cj_vpieces bp = {0, 0, NULL, NULL, NULL};
    int bj = -1;
    const cj_status st = snap_curve(c, 0, q, tol, &best, &bp, &bj);
    return snap_finish(&best, &bp, bj, st, out);
}

static cj_status push_mark(cj_vmark **out, size_t *n, size_t *cap, const cj_vmark *m) {
    if (*n == *cap) {
        const size_t nc = *cap ? *cap * 2 : 16;
        cj_vmark *g = realloc(*out, nc * sizeof *g);
        if (!g) return cj_fail(CJ_ERR_NOMEM, "viewer: out of memory for %zu intersections", nc);
        *out = g;
        *cap = nc;
    }
    (*out)[(*n)++] = *m;
    return CJ_OK;
}

static int near_mark(const cj_vmark *m, size_t n, size_t a, size_t b, const double p[2], double d) {
    for (size_t i = 0; i < n; ++i)
        if (m[i].a == a && m[i].b == b && fabs(m[i].point[0] - p[0]) <= d &&
            fabs(m[i].point[1] - p[1]) <= d)
            return 1;
    return 0;
}

cj_status cj_vdoc_intersections(const cj_vdoc *doc, double tol, cj_vmark **out, size_t *count,
                                size_t *failed) {
    assert(doc && out && count);
    const size_t nc = cj_vdoc_curve_count(doc);
    cj_vmark *marks = NULL;
    size_t n = 0, cap = 0, bad = 0;
    cj_status st = CJ_OK;
    cj_vpieces *all = calloc(nc ? nc : 1, sizeof *all);
    if (!all) return cj_fail(CJ_ERR_NOMEM, "viewer: out of memory for %zu curves", nc);
    for (size_t i = 0; i < nc && !st; ++i) st = cj_vcurve_pieces(cj_vdoc_curve(doc, i), &all[i]);
    enum { CAP = 64 };
    cj_isect hits[CAP];
    for (size_t a = 0; a < nc && !st; ++a)
        for (size_t b = a + 1; b < nc && !st; ++b)
            for (int i = 0; i < all[a].n && !st; ++i)
                for (int j = 0; j < all[b].n && !st; ++j) {
                    const cj_bezier2 ca = piece(&all[a], i), cb = piece(&all[b], j);
                    int k = 0;
                    const double t = fmax(usable_tol(&ca, NULL, tol), usable_tol(&cb, NULL, tol));
                    const cj_status e = cj_intersect_curves(&ca, &cb, t, hits, CAP, &k);
                    if (e && e != CJ_ERR_BUFFER) {
                        if (e == CJ_ERR_NOMEM) st = e;
                        bad++;
                        continue;
                    }
                    for (int h = 0; h < k && h < CAP && !st; ++h) {
                        /* a crossing at a joint of two pieces is found from both: once */
                        if (hits[h].at_end && near_mark(marks, n, a, b, hits[h].point, 4 * t))
                            continue;
                        const cj_vmark m = {{hits[h].point[0], hits[h].point[1]},
                                            (int)hits[h].kind,
                                            a,
                                            b,
                                            curve_param(&all[a], i, hits[h].s),
                                            curve_param(&all[b], j, hits[h].t)};
                        st = push_mark(&marks, &n, &cap, &m);
                    }
                }
    for (size_t i = 0; i < nc; ++i) cj_vpieces_free(&all[i]);
    free(all);
    if (st) {
        free(marks);
        return st;
    }
    *out = marks;
    *count = n;
    if (failed) *failed = bad;
    return CJ_OK;
}

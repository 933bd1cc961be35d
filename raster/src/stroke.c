/* Wide anti-aliased strokes with exact area coverage: the stroke geometry.
 *
 * The stroke is cut into convex pieces that do not overlap: one rectangle per segment, a wedge
 * (miter quadrilateral, bevel triangle, or circular sector) on the outer side of each join, and
 * the caps (square: rectangle; round: half-disc sector). Where two consecutive rectangles
 * overlap on the inner side of a join, the area of their intersection (again convex) is
 * subtracted. Circular sectors are polygons with at most 0.02 px sagitta whose radius is
 * enlarged so that each triangle has the exact sector area. Each piece adds (or subtracts) the
 * exact area of (pixel square ∩ piece) to every pixel through its edges' signed areas, in a
 * float plane over touched spans (one [lo, hi] per row) that is composited once, clamped to
 * [0, 1], and cleared again for the next call (stroke_cover.c). Pieces of non-adjacent segments
 * that overlap (self-intersections) add up and are clamped at 1. */
#include "casteljau/flatten.h"
#include "casteljau/line.h"
#include "error_internal.h"
#include "raster_internal.h"
#include "stroke_internal.h"

#include <assert.h>
#include <float.h>
#include <limits.h>
#include <math.h>
#include <string.h>

#define CJ_PI_ 3.14159265358979323846

/* min/max without the NaN rules of fmin/fmax (inputs here are finite), so they inline. */
static inline double dmin(double a, double b) {
    return a < b ? a : b;
}
static inline double dmax(double a, double b) {
    return a > b ? a : b;
}

typedef struct stroker {
    cover_target *t;
    double hw; /* half width */
    cj_line_join join;
    cj_line_cap cap;
    double miter_limit;
    double rxlo, rxhi, rylo, ryhi; /* visibility rectangle: target grown by the piece reach */
    int closed;
    size_t npts; /* distinct points so far */
    size_t nseg; /* segments so far */
    /* Closed polylines: intersection of all rectangles so far (inter_ok = 0 once it no longer
     * fits a poly). A point inside every rectangle is counted n times and subtracted n times
     * around the cycle of joins; adding this intersection back makes its count 1. */
    poly inter;
    int inter_ok;
    cj_vec2 first, first_dir, prev, prev_dir;
    poly first_rect, prev_rect; /* clipped rectangles (n == 0: not visible) */
} stroker;

/* Accumulates sign * area(pixel ∩ p) over the pixels of the target (stroke_cover.c). */
static void add_poly(stroker *s, const poly *p, float sign) {
    cj_stroke_cover_poly(s->t, p, sign);
}

/* Circular sector centred at c, radius r, from unit direction u0 turning by phi in [0, pi]
 * (counter-clockwise when ccw, else clockwise), as fans of at most 4 triangles per piece. */
static void add_sector(stroker *s, cj_vec2 c, cj_vec2 u0, double phi, int ccw, double r) {
    if (!(phi > 0.0) || !(r > 0.0)) return;
    double step = 2.0 * acos(dmax(0.0, 1.0 - 0.02 / r));
    if (!(step > 0.0) || step > CJ_PI_ / 8) step = CJ_PI_ / 8;
    int k = (int)ceil(phi / step);
    if (k < 1) k = 1;
    double d = phi / k, sg = ccw ? 1.0 : -1.0;
    double rr = r * sqrt(d / sin(d)); /* each triangle gets the exact sector area */
    double a0 = atan2(u0.y, u0.x);
    poly p;
    p.v[0] = c;
    p.n = 1;
    for (int i = 0; i <= k; ++i) {
        double a = a0 + sg * d * i;
        p.v[p.n++] = cj_v2(c.x + rr * cos(a), c.y + rr * sin(a));
        if (p.n == 6 || i == k) {
            add_poly(s, &p, 1.0f);
            cj_vec2 last = p.v[p.n - 1];
            p.v[1] = last;
            p.n = 2;
        }
    }
}

/* ---- stroke geometry --------------------------------------------------------------------- */

static int visible(const stroker *s, cj_vec2 p) {
    return p.x >= s->rxlo && p.x <= s->rxhi && p.y >= s->rylo && p.y <= s->ryhi;
}

/* Rectangle of the segment a-b (unit direction d), clipped to the visibility rectangle first
 * so that far-away coordinates never enter the per-pixel arithmetic. */
static void segment_rect(const stroker *s, cj_vec2 a, cj_vec2 b, cj_vec2 d, poly *out) {
    double dx = b.x - a.x, dy = b.y - a.y, t0 = 0.0, t1 = 1.0;
    const double p[4] = {-dx, dx, -dy, dy};
    const double q[4] = {a.x - s->rxlo, s->rxhi - a.x, a.y - s->rylo, s->ryhi - a.y};
    out->n = 0;
    for (int k = 0; k < 4; ++k) {
        if (p[k] == 0.0) {
            if (q[k] < 0.0) return;
        } else {
            double r = q[k] / p[k];
            if (p[k] < 0.0) {
                if (r > t0) t0 = r;
            } else if (r < t1) {
                t1 = r;
            }
        }
    }
    if (t0 > t1) return;
    cj_vec2 a2 = t0 > 0.0 ? cj_v2(a.x + t0 * dx, a.y + t0 * dy) : a;
    cj_vec2 b2 = t1 < 1.0 ? cj_v2(a.x + t1 * dx, a.y + t1 * dy) : b;
    cj_vec2 n = cj_v2_scale(cj_v2_perp(d), s->hw);
    out->v[0] = cj_v2_sub(a2, n);
    out->v[1] = cj_v2_sub(b2, n);
    out->v[2] = cj_v2_add(b2, n);
    out->v[3] = cj_v2_add(a2, n);
    out->n = 4;
}

/* subject := subject ∩ clipper (clipper convex, counter-clockwise). Returns 0 if the result
 * would not fit in a poly (then subject is unusable). */
static int clip_convex(const poly *clipper, poly *subject) {
    poly b;
    for (int i = 0, j = clipper->n - 1; i < clipper->n && subject->n > 0; j = i++) {
        cj_vec2 e0 = clipper->v[j], e1 = clipper->v[i];
        double ex = e1.x - e0.x, ey = e1.y - e0.y;
        b.n = 0; /* keep cross(e, p - e0) >= 0: left of the edge */
        for (int q = 0, w = subject->n - 1; q < subject->n; w = q++) {
            cj_vec2 pa = subject->v[w], pb = subject->v[q];
            double fa = ex * (pa.y - e0.y) - ey * (pa.x - e0.x);
            double fb = ex * (pb.y - e0.y) - ey * (pb.x - e0.x);
            if (b.n > POLY_MAX - 2) return 0;
            if ((fa >= 0) != (fb >= 0)) {
                double t = fa / (fa - fb);
                b.v[b.n++] = cj_v2(pa.x + t * (pb.x - pa.x), pa.y + t * (pb.y - pa.y));
            }
            if (fb >= 0) b.v[b.n++] = pb;
        }
        *subject = b;
    }
    return 1;
}

/* Subtracts the intersection of two consecutive rectangles (counted twice otherwise). */
static void subtract_overlap(stroker *s, const poly *r1, const poly *r2) {
    if (r1->n < 3 || r2->n < 3) return;
    poly a = *r2;
    if (clip_convex(r1, &a) && a.n >= 3) add_poly(s, &a, -1.0f);
}

static void add_join(stroker *s, cj_vec2 v, cj_vec2 din, cj_vec2 dout) {
    if (!visible(s, v)) return;
    double cr = cj_v2_cross(din, dout), dt = cj_v2_dot(din, dout);
    if (fabs(cr) < 1e-12 && dt > 0.0) return; /* straight on: the rectangles already meet */
    /* Outer normals: on the right of a left turn, on the left of a right turn. */
    cj_vec2 a = cj_v2_perp(din), b = cj_v2_perp(dout);
    if (cr > 0.0) a = cj_v2_scale(a, -1.0), b = cj_v2_scale(b, -1.0);
    double h = s->hw, ab = cj_v2_dot(a, b);
    if (s->join == CJ_JOIN_ROUND) {
        double phi = acos(dmax(-1.0, dmin(1.0, ab)));
        add_sector(s, v, a, phi, cj_v2_cross(a, din) > 0.0, h);
        return;
    }
    cj_vec2 pa = cj_v2_add(v, cj_v2_scale(a, h)), pb = cj_v2_add(v, cj_v2_scale(b, h));
    poly p;
    p.v[0] = v;
    p.v[1] = pa;
    if (s->join == CJ_JOIN_MITER && 1.0 + ab > 1e-12 && sqrt(2.0 / (1.0 + ab)) <= s->miter_limit) {
        p.v[2] = cj_v2_add(v, cj_v2_scale(cj_v2_add(a, b), h / (1.0 + ab)));
        p.v[3] = pb;
        p.n = 4;
    } else {
        p.v[2] = pb;
        p.n = 3;
    }
    add_poly(s, &p, 1.0f);
}

/* Cap at end point p; d points out of the stroke. */
static void add_cap(stroker *s, cj_vec2 p, cj_vec2 d) {
    if (!visible(s, p)) return;
    cj_vec2 n = cj_v2_perp(d);
    if (s->cap == CJ_CAP_ROUND) {
        add_sector(s, p, n, CJ_PI_, cj_v2_cross(n, d) > 0.0, s->hw);
    } else if (s->cap == CJ_CAP_SQUARE) {
        cj_vec2 hn = cj_v2_scale(n, s->hw), e = cj_v2_add(p, cj_v2_scale(d, s->hw));
        poly c = {{cj_v2_add(p, hn), cj_v2_sub(p, hn), cj_v2_sub(e, hn), cj_v2_add(e, hn)}, 4};
        add_poly(s, &c, 1.0f);
    }
}

static cj_vec2 unit(cj_vec2 a, cj_vec2 b) {
    cj_vec2 d = cj_v2_sub(b, a);
    return cj_v2_scale(d, 1.0 / cj_v2_norm(d));
}

/* The segment prev -> p (direction d) after a join at prev when it is not the first. */
static void segment_to(stroker *s, cj_vec2 p, cj_vec2 d) {
    poly r;
    segment_rect(s, s->prev, p, d, &r);
    add_poly(s, &r, 1.0f);
    s->nseg++;
    if (s->closed) {
        if (s->nseg == 1)
            s->inter = r, s->inter_ok = 1;
        else if (s->inter_ok && s->inter.n >= 3)
            s->inter_ok = r.n >= 3 && clip_convex(&r, &s->inter);
    }
    if (s->npts == 1) {
        s->first_rect = r;
    } else {
        add_join(s, s->prev, s->prev_dir, d);
        subtract_overlap(s, &s->prev_rect, &r);
    }
    s->prev_rect = r;
}

static void stroker_point(stroker *s, cj_vec2 p) {
    if (s->npts == 0) {
        s->first = s->prev = p;
        s->npts = 1;
        return;
    }
    if (p.x == s->prev.x && p.y == s->prev.y) return;
    cj_vec2 d = unit(s->prev, p);
    if (!(isfinite(d.x) && isfinite(d.y))) return; /* distinct but too close to normalise */
    if (s->npts == 1) s->first_dir = d;
    segment_to(s, p, d);
    s->prev = p;
    s->prev_dir = d;
    s->npts++;
}

static void stroker_finish(stroker *s) {
    if (s->npts == 1) { /* a dot */
        if (s->cap == CJ_CAP_ROUND) {
            add_cap(s, s->first, cj_v2(1.0, 0.0));
            add_cap(s, s->first, cj_v2(-1.0, 0.0));
        } else if (s->cap == CJ_CAP_SQUARE && visible(s, s->first)) {
            double h = s->hw, x = s->first.x, y = s->first.y;
            poly c = {{{x - h, y - h}, {x + h, y - h}, {x + h, y + h}, {x - h, y + h}}, 4};
            add_poly(s, &c, 1.0f);
        }
        return;
    }
    if (s->closed) {
        if (s->prev.x != s->first.x || s->prev.y != s->first.y) {
            cj_vec2 d = unit(s->prev, s->first);
            if (isfinite(d.x) && isfinite(d.y)) {
                segment_to(s, s->first, d);
                s->prev_dir = d;
            }
        }
        add_join(s, s->first, s->prev_dir, s->first_dir);
        /* With two segments the closing pair is the pair already subtracted at the other end. */
        if (s->nseg > 2) {
            subtract_overlap(s, &s->prev_rect, &s->first_rect);
            if (s->inter_ok && s->inter.n >= 3) add_poly(s, &s->inter, 1.0f);
        }
    } else {
        add_cap(s, s->first, cj_v2_scale(s->first_dir, -1.0));
        add_cap(s, s->prev, s->prev_dir);
    }
}

/* ---- set-up, validation, composition ------------------------------------------------------ */

static cj_status check_style(const cj_line_stroke *st) {
    if (!isfinite(st->width))
        return cj_fail(CJ_ERR_NONFINITE, "stroke width is %s",
                       isnan(st->width) ? "NaN" : "infinite");
    if (!(st->width > 0.0) || st->width > CJ_LINE_MAX_WIDTH)
        return cj_fail(CJ_ERR_RANGE, "stroke width %g is outside (0, %g]", st->width,
                       CJ_LINE_MAX_WIDTH);
    if (st->join != CJ_JOIN_MITER && st->join != CJ_JOIN_ROUND && st->join != CJ_JOIN_BEVEL)
        return cj_fail(CJ_ERR_ARGUMENT, "stroke join %d is not a cj_line_join", (int)st->join);
    if (st->cap != CJ_CAP_BUTT && st->cap != CJ_CAP_ROUND && st->cap != CJ_CAP_SQUARE)
        return cj_fail(CJ_ERR_ARGUMENT, "stroke cap %d is not a cj_line_cap", (int)st->cap);
    if (!isfinite(st->miter_limit))
        return cj_fail(CJ_ERR_NONFINITE, "miter limit is %s",
                       isnan(st->miter_limit) ? "NaN" : "infinite");
    if (!(st->miter_limit >= 1.0))
        return cj_fail(CJ_ERR_RANGE, "miter limit %g is below 1", st->miter_limit);
    return CJ_OK;
}

static cj_status check_points(const cj_vec2 *pts, size_t n) {
    if (n == 0) return cj_fail(CJ_ERR_EMPTY, "polyline has no points");
    for (size_t i = 0; i < n; ++i) {
        const double c[2] = {pts[i].x, pts[i].y};
        for (int k = 0; k < 2; ++k) {
            if (!isfinite(c[k]))
                return cj_fail(CJ_ERR_NONFINITE, "polyline point %zu: %s is %s", i, k ? "y" : "x",
                               isnan(c[k]) ? "NaN" : "infinite");
            if (fabs(c[k]) > CJ_LINE_COORD_MAX)
                return cj_fail(CJ_ERR_RANGE, "polyline point %zu: %s = %g exceeds 2^52", i,
                               k ? "y" : "x", c[k]);
        }
    }
    return CJ_OK;
}

static void stroker_init(stroker *s, cover_target *t, const cj_line_stroke *st, int closed) {
    memset(s, 0, sizeof *s);
    s->closed = closed;
    s->t = t;
    s->hw = 0.5 * st->width;
    s->join = st->join;
    s->cap = st->cap;
    s->miter_limit = st->miter_limit;
    double k = st->join == CJ_JOIN_MITER && st->miter_limit > 1.5 ? st->miter_limit : 1.5;
    double reach = s->hw * k + 2.0;
    s->rxlo = t->ox - reach;
    s->rxhi = t->ox + t->w + reach;
    s->rylo = t->oy - reach;
    s->ryhi = t->oy + t->h + reach;
    t->ymin = INT_MAX;
    t->ymax = -1;
}

/* Row pitch of the framebuffer's coverage plane: an odd number of 64-byte lines, so that a
 * steep stroke does not map every row to the same cache set. */
static ptrdiff_t cover_pitch(int width) {
    ptrdiff_t cs = ((ptrdiff_t)width + 15) / 16 * 16;
    return (cs / 16) % 2 ? cs : cs + 16;
}

static cj_status fb_target(cj_framebuffer *fb, cover_target *t) {
    if (!fb->cover_) {
        size_t n = (size_t)cover_pitch(fb->width) * (size_t)fb->height;
        float *cover = cj_allocator_alloc(&fb->alloc_, n * sizeof *cover);
        int *lo = cj_allocator_alloc(&fb->alloc_, (size_t)fb->height * sizeof *lo);
        int *hi = cj_allocator_alloc(&fb->alloc_, (size_t)fb->height * sizeof *hi);
        if (!cover || !lo || !hi) {
            cj_allocator_free(&fb->alloc_, cover);
            cj_allocator_free(&fb->alloc_, lo);
            cj_allocator_free(&fb->alloc_, hi);
            return cj_fail(CJ_ERR_NOMEM, "no memory for the %dx%d stroke coverage plane", fb->width,
                           fb->height);
        }
        memset(cover, 0, n * sizeof *cover);
        for (int y = 0; y < fb->height; ++y) lo[y] = INT_MAX, hi[y] = -1;
        fb->cover_ = cover;
        fb->span_lo_ = lo;
        fb->span_hi_ = hi;
    }
    t->cover = fb->cover_;
    t->lo = fb->span_lo_;
    t->hi = fb->span_hi_;
    t->ox = 0;
    t->oy = 0;
    t->w = fb->width;
    t->cs = cover_pitch(fb->width);
    t->sheared = 0;
    t->bx0 = t->bk = 0.0;
    t->h = fb->height;
    return CJ_OK;
}

cj_status cj_line_stroke_polyline(cj_framebuffer *fb, const cj_vec2 *pts, size_t n, int closed,
                                  const cj_line_stroke *style, cj_rgba c) {
    assert(fb && style && (pts || n == 0));
    cj_status st;
    if ((st = check_style(style)) || (st = check_points(pts, n))) return st;
    cover_target t;
    if ((st = fb_target(fb, &t))) return st;
    cj_stroke_narrow_plane(&t, pts, n, closed, style);
    stroker s;
    stroker_init(&s, &t, style, closed);
    for (size_t i = 0; i < n; ++i) stroker_point(&s, pts[i]);
    stroker_finish(&s);
    cj_stroke_compose(&t, fb, c, NULL, NULL);
    return CJ_OK;
}

size_t cj_line_stroke_work_size(cj_line_rect clip) {
    if (clip.x1 < clip.x0 || clip.y1 < clip.y0) return 0;
    size_t w = (size_t)((long long)clip.x1 - clip.x0 + 1);
    size_t h = (size_t)((long long)clip.y1 - clip.y0 + 1);
    return w * h * sizeof(float) + 2 * h * sizeof(int);
}

cj_status cj_line_stroke_polyline_visit(const cj_vec2 *pts, size_t n, int closed,
                                        const cj_line_stroke *style, cj_line_rect clip, void *work,
                                        size_t work_bytes, cj_line_cover_fn fn, void *user) {
    assert(style && fn && (pts || n == 0));
    cj_status st;
    if ((st = check_style(style)) || (st = check_points(pts, n))) return st;
    size_t need = cj_line_stroke_work_size(clip);
    if (need == 0) return CJ_OK;
    assert(work);
    if (work_bytes < need)
        return cj_fail(CJ_ERR_BUFFER, "stroke workspace has %zu bytes, %zu needed", work_bytes,
                       need);
    cover_target t;
    t.ox = clip.x0;
    t.oy = clip.y0;
    t.w = clip.x1 - clip.x0 + 1;
    t.cs = t.w;
    t.sheared = 0;
    t.bx0 = t.bk = 0.0;
    t.h = clip.y1 - clip.y0 + 1;
    t.cover = work;
    t.lo = (int *)(t.cover + (size_t)t.w * (size_t)t.h);
    t.hi = t.lo + t.h;
    memset(t.cover, 0, (size_t)t.w * (size_t)t.h * sizeof(float));
    for (int y = 0; y < t.h; ++y) t.lo[y] = INT_MAX, t.hi[y] = -1;
    stroker s;
    stroker_init(&s, &t, style, closed);
    for (size_t i = 0; i < n; ++i) stroker_point(&s, pts[i]);
    stroker_finish(&s);
    cj_stroke_compose(&t, NULL, cj_rgba_make(0, 0, 0, 0), fn, user);
    return CJ_OK;
}

/* ---- curves --------------------------------------------------------------------------------- */

static void curve_sink(void *user, const double *pt, int dim, size_t piece, double t) {
    (void)dim, (void)piece, (void)t;
    stroker_point(user, cj_v2(pt[0], pt[1]));
}

/* Runs one flattening call (which emits vertices into the stroker) and composites. */
typedef cj_status (*flatten_call)(const void *what, const cj_flatten_opts *opts, void *stroker,
                                  cj_flatten_stats *stats);

static cj_status stroke_flattened(cj_framebuffer *fb, const void *what, flatten_call run,
                                  double tol, const cj_line_stroke *style, cj_rgba c,
                                  double *bound) {
    cover_target t;
    cj_status st = fb_target(fb, &t);
    if (st) return st;
    stroker s;
    stroker_init(&s, &t, style, 0);
    cj_flatten_opts opts = cj_flatten_defaults(CJ_FLATTEN_NEAR_OPTIMAL, tol);
    cj_flatten_stats stats;
    st = run(what, &opts, &s, &stats);
    if (st) {
        cj_stroke_compose(&t, NULL, c, NULL,
                          NULL); /* clear whatever was accumulated, draw nothing */
        return st;
    }
    stroker_finish(&s);
    cj_stroke_compose(&t, fb, c, NULL, NULL);
    if (bound) *bound = stats.bound;
    return CJ_OK;
}

static cj_status run_bezier(const void *what, const cj_flatten_opts *opts, void *s,
                            cj_flatten_stats *stats) {
    return cj_flatten_bezier_cb(what, opts, curve_sink, s, stats);
}
static cj_status run_rbezier(const void *what, const cj_flatten_opts *opts, void *s,
                             cj_flatten_stats *stats) {
    return cj_flatten_rbezier_cb(what, opts, curve_sink, s, stats);
}

typedef struct seq {
    const cj_flatten_piece *pieces;
    size_t count;
} seq;
static cj_status run_sequence(const void *what, const cj_flatten_opts *opts, void *s,
                              cj_flatten_stats *stats) {
    const seq *q = what;
    return cj_flatten_sequence_cb(q->pieces, q->count, opts, curve_sink, s, stats);
}

cj_status cj_line_stroke_bezier(cj_framebuffer *fb, const cj_bezier *curve, double tol,
                                const cj_line_stroke *style, cj_rgba c, double *bound) {
    assert(fb && curve && style);
    cj_status st;
    if ((st = check_style(style))) return st;
    if (curve->dim != 2)
        return cj_fail(CJ_ERR_DIMENSION, "curve dimension %d: strokes need 2D curves", curve->dim);
    return stroke_flattened(fb, curve, run_bezier, tol, style, c, bound);
}

cj_status cj_line_stroke_rbezier(cj_framebuffer *fb, const cj_rbezier *curve, double tol,
                                 const cj_line_stroke *style, cj_rgba c, double *bound) {
    assert(fb && curve && style);
    cj_status st;
    if ((st = check_style(style))) return st;
    if (curve->dim != 2)
        return cj_fail(CJ_ERR_DIMENSION, "curve dimension %d: strokes need 2D curves", curve->dim);
    return stroke_flattened(fb, curve, run_rbezier, tol, style, c, bound);
}

cj_status cj_line_stroke_sequence(cj_framebuffer *fb, const cj_flatten_piece *pieces, size_t count,
                                  double tol, const cj_line_stroke *style, cj_rgba c,
                                  double *bound) {
    assert(fb && style && (pieces || count == 0));
    cj_status st;
    if ((st = check_style(style))) return st;
    for (size_t i = 0; i < count; ++i)
        if (pieces[i].curve.dim != 2)
            return cj_fail(CJ_ERR_DIMENSION, "piece %zu has dimension %d: strokes need 2D curves",
                           i, pieces[i].curve.dim);
    seq q = {pieces, count};
    return stroke_flattened(fb, &q, run_sequence, tol, style, c, bound);
}

/* ---- filled shapes ----------------------------------------------------------------------- */

cj_status cj_line_fill_convex(cj_framebuffer *fb, const cj_vec2 *pts, size_t n, cj_rgba c) {
    assert(fb && (pts || n == 0));
    if (n < 3) return cj_fail(CJ_ERR_EMPTY, "polygon has %zu points, at least 3 needed", n);
    cj_status st = check_points(pts, n);
    if (st) return st;
    int sign = 0;
    for (size_t i = 0; i < n; ++i) {
        cj_vec2 a = pts[i], b = pts[(i + 1) % n], d = pts[(i + 2) % n];
        double cr = cj_v2_cross(cj_v2_sub(b, a), cj_v2_sub(d, b));
        int sg = cr > 0 ? 1 : (cr < 0 ? -1 : 0);
        if (sg && sign && sg != sign)
            return cj_fail(CJ_ERR_ARGUMENT,
                           "polygon is not convex: the turn at point %zu has "
                           "the opposite sign",
                           (i + 1) % n);
        if (sg) sign = sg;
    }
    cover_target t;
    if ((st = fb_target(fb, &t))) return st;
    cj_line_stroke style = cj_line_stroke_defaults(1.0);
    stroker s;
    stroker_init(&s, &t, &style, 0);
    /* A fan of pieces of at most POLY_MAX - 2 vertices around pts[0]: disjoint, areas add. */
    for (size_t i = 1; i + 1 < n;) {
        poly p;
        p.n = 0;
        p.v[p.n++] = pts[0];
        size_t j = i;
        for (; j < n && p.n < POLY_MAX - 2; ++j) p.v[p.n++] = pts[j];
        add_poly(&s, &p, 1.0f);
        i = j - 1;
    }
    cj_stroke_compose(&t, fb, c, NULL, NULL);
    return CJ_OK;
}

cj_status cj_line_fill_disc(cj_framebuffer *fb, cj_vec2 centre, double radius, cj_rgba c) {
    assert(fb);
    cj_status st = check_points(&centre, 1);
    if (st) return st;
    if (!isfinite(radius))
        return cj_fail(CJ_ERR_NONFINITE, "disc radius is %s", isnan(radius) ? "NaN" : "infinite");
    if (!(radius > 0.0) || radius > CJ_LINE_MAX_WIDTH)
        return cj_fail(CJ_ERR_RANGE, "disc radius %g is outside (0, %g]", radius,
                       CJ_LINE_MAX_WIDTH);
    cover_target t;
    if ((st = fb_target(fb, &t))) return st;
    cj_line_stroke style = cj_line_stroke_defaults(2.0 * radius);
    stroker s;
    stroker_init(&s, &t, &style, 0);
    if (visible(&s, centre)) {
        add_sector(&s, centre, cj_v2(1, 0), CJ_PI_, 1, radius);
        add_sector(&s, centre, cj_v2(-1, 0), CJ_PI_, 1, radius);
    }
    cj_stroke_compose(&t, fb, c, NULL, NULL);
    return CJ_OK;
}

/* Wide anti-aliased strokes: union of convex pieces, coverage clamp(1/2 - signed distance).
 *
 * Every piece (segment rectangle, join wedge, round disc, square cap) is rasterised row by row
 * over the pixels whose centre can lie within 1/2 of it, and its coverage is max-combined into a
 * float coverage plane. The max over pieces is the coverage of their union, so overlaps are not
 * counted twice. When the stroke is complete, the touched spans (one [lo, hi] per row) are
 * composited once and the plane is cleared again, leaving it zeroed for the next call. */
#include "casteljau/flatten.h"
#include "casteljau/line.h"
#include "error_internal.h"
#include "raster_internal.h"

#include <assert.h>
#include <float.h>
#include <limits.h>
#include <math.h>
#include <string.h>

typedef struct cover_target {
    float *cover;     /* w*h, zero outside touched spans */
    int *lo, *hi;     /* per row, relative x; empty when lo > hi */
    int ox, oy, w, h; /* pixel (x, y) is cover[(y-oy)*w + (x-ox)] */
    int ymin, ymax;   /* touched rows, relative; empty when ymin > ymax */
} cover_target;

typedef struct stroker {
    cover_target *t;
    double hw;   /* half width actually rasterised (>= 1/2) */
    float scale; /* coverage scale (< 1 for strokes thinner than a pixel) */
    cj_raster_join join;
    cj_raster_cap cap;
    double miter_limit;
    double rxlo, rxhi, rylo, ryhi; /* visibility rectangle: target grown by the piece reach */
    size_t npts;                   /* distinct points so far */
    cj_vec2 first, first_dir, prev, prev_dir;
} stroker;

/* ---- coverage of one piece ------------------------------------------------------------- */

static void touch_rows(cover_target *t, int y) {
    if (y < t->ymin) t->ymin = y;
    if (y > t->ymax) t->ymax = y;
}

/* Pixels of row y (absolute) with centre x in [xlo, xhi] get max(cover, f(centre)). */
typedef double (*sdf_fn)(const void *piece, double px, double py);

static void cover_row(stroker *s, int y, double xlo, double xhi, sdf_fn sdf, const void *piece) {
    cover_target *t = s->t;
    double fx0 = floor(xlo - 0.5), fx1 = floor(xhi + 0.5);
    if (fx0 < t->ox) fx0 = t->ox;
    if (fx1 > t->ox + t->w - 1) fx1 = t->ox + t->w - 1;
    if (fx0 > fx1) return;
    int x0 = (int)fx0 - t->ox, x1 = (int)fx1 - t->ox, ry = y - t->oy;
    float *row = t->cover + (ptrdiff_t)ry * t->w;
    double pyc = y + 0.5;
    int any = 0;
    for (int x = x0; x <= x1; ++x) {
        double d = sdf(piece, x + t->ox + 0.5, pyc);
        double c = 0.5 - d;
        if (!(c > 0.0)) continue;
        float cov = (c >= 1.0 ? 1.0f : (float)c) * s->scale;
        if (cov > row[x]) row[x] = cov;
        if (x < t->lo[ry]) t->lo[ry] = x;
        if (x > t->hi[ry]) t->hi[ry] = x;
        any = 1;
    }
    if (any) touch_rows(t, ry);
}

/* Row range [r0, r1] (absolute) of pixels whose centre may be within 1/2 of [ylo, yhi]. */
static int row_range(const cover_target *t, double ylo, double yhi, int *r0, int *r1) {
    double a = floor(ylo - 0.5), b = floor(yhi + 0.5);
    if (a < t->oy) a = t->oy;
    if (b > t->oy + t->h - 1) b = t->oy + t->h - 1;
    if (a > b) return 0;
    *r0 = (int)a;
    *r1 = (int)b;
    return 1;
}

typedef struct convex {
    cj_vec2 v[5];
    int n;
} convex;

static double sdf_convex(const void *piece, double px, double py) {
    const convex *c = piece;
    double best = DBL_MAX;
    int pos = 0, neg = 0;
    for (int k = 0; k < c->n; ++k) {
        cj_vec2 a = c->v[k], b = c->v[k + 1 == c->n ? 0 : k + 1];
        double ex = b.x - a.x, ey = b.y - a.y, wx = px - a.x, wy = py - a.y;
        double ee = ex * ex + ey * ey, t = 0.0;
        if (ee > 0.0) {
            t = (wx * ex + wy * ey) / ee;
            t = t < 0.0 ? 0.0 : (t > 1.0 ? 1.0 : t);
        }
        double qx = wx - t * ex, qy = wy - t * ey, dd = qx * qx + qy * qy;
        if (dd < best) best = dd;
        double cr = ex * wy - ey * wx;
        pos |= cr > 0.0;
        neg |= cr < 0.0;
    }
    double d = sqrt(best);
    return pos && neg ? d : -d;
}

static void add_convex(stroker *s, const convex *c) {
    double ylo = DBL_MAX, yhi = -DBL_MAX;
    for (int k = 0; k < c->n; ++k) {
        if (c->v[k].y < ylo) ylo = c->v[k].y;
        if (c->v[k].y > yhi) yhi = c->v[k].y;
    }
    int r0, r1;
    if (!row_range(s->t, ylo, yhi, &r0, &r1)) return;
    for (int y = r0; y <= r1; ++y) {
        /* x extent of the polygon inside the band [y, y+1]. */
        double bl = y, bh = y + 1.0, xlo = DBL_MAX, xhi = -DBL_MAX;
        for (int k = 0; k < c->n; ++k) {
            cj_vec2 a = c->v[k], b = c->v[k + 1 == c->n ? 0 : k + 1];
            double t0 = 0.0, t1 = 1.0, dy = b.y - a.y;
            if (dy == 0.0) {
                if (a.y < bl || a.y > bh) continue;
            } else {
                double ta = (bl - a.y) / dy, tb = (bh - a.y) / dy;
                if (ta > tb) {
                    double tmp = ta;
                    ta = tb, tb = tmp;
                }
                if (ta > t0) t0 = ta;
                if (tb < t1) t1 = tb;
                if (t0 > t1) continue;
            }
            double xa = a.x + t0 * (b.x - a.x), xb = a.x + t1 * (b.x - a.x);
            if (xa > xb) {
                double tmp = xa;
                xa = xb, xb = tmp;
            }
            if (xa < xlo) xlo = xa;
            if (xb > xhi) xhi = xb;
        }
        if (xlo <= xhi) cover_row(s, y, xlo, xhi, sdf_convex, c);
    }
}

typedef struct disc {
    double cx, cy, r;
} disc;

static double sdf_disc(const void *piece, double px, double py) {
    const disc *d = piece;
    return hypot(px - d->cx, py - d->cy) - d->r;
}

static void add_disc(stroker *s, cj_vec2 c, double r) {
    disc d = {c.x, c.y, r};
    int r0, r1;
    if (!row_range(s->t, c.y - r, c.y + r, &r0, &r1)) return;
    for (int y = r0; y <= r1; ++y) {
        double dy = c.y < y ? y - c.y : (c.y > y + 1.0 ? c.y - (y + 1.0) : 0.0);
        if (dy > r) continue;
        double half = sqrt(r * r - dy * dy);
        cover_row(s, y, c.x - half, c.x + half, sdf_disc, &d);
    }
}

/* ---- stroke geometry --------------------------------------------------------------------- */

static int visible(const stroker *s, cj_vec2 p) {
    return p.x >= s->rxlo && p.x <= s->rxhi && p.y >= s->rylo && p.y <= s->ryhi;
}

/* Rectangle of the segment a-b (unit direction d), clipped to the visibility rectangle first
 * so that far-away coordinates never enter the per-pixel arithmetic. */
static void add_segment(stroker *s, cj_vec2 a, cj_vec2 b, cj_vec2 d) {
    double dx = b.x - a.x, dy = b.y - a.y, t0 = 0.0, t1 = 1.0;
    const double p[4] = {-dx, dx, -dy, dy};
    const double q[4] = {a.x - s->rxlo, s->rxhi - a.x, a.y - s->rylo, s->ryhi - a.y};
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
    convex c = {{cj_v2_add(a2, n), cj_v2_sub(a2, n), cj_v2_sub(b2, n), cj_v2_add(b2, n)}, 4};
    add_convex(s, &c);
}

static void add_join(stroker *s, cj_vec2 v, cj_vec2 din, cj_vec2 dout) {
    if (!visible(s, v)) return;
    double cr = cj_v2_cross(din, dout), dt = cj_v2_dot(din, dout);
    if (fabs(cr) < 1e-12 && dt > 0.0) return; /* straight on: the rectangles already meet */
    if (s->join == CJ_JOIN_ROUND) {
        add_disc(s, v, s->hw);
        return;
    }
    /* Outer normals: on the right of a left turn, on the left of a right turn. */
    cj_vec2 a = cj_v2_perp(din), b = cj_v2_perp(dout);
    if (cr > 0.0) a = cj_v2_scale(a, -1.0), b = cj_v2_scale(b, -1.0);
    double h = s->hw, ab = cj_v2_dot(a, b);
    cj_vec2 pa = cj_v2_add(v, cj_v2_scale(a, h)), pb = cj_v2_add(v, cj_v2_scale(b, h));
    if (s->join == CJ_JOIN_MITER && 1.0 + ab > 1e-12 && sqrt(2.0 / (1.0 + ab)) <= s->miter_limit) {
        cj_vec2 m = cj_v2_add(v, cj_v2_scale(cj_v2_add(a, b), h / (1.0 + ab)));
        convex c = {{v, pa, m, pb}, 4};
        add_convex(s, &c);
    } else {
        convex c = {{v, pa, pb}, 3};
        add_convex(s, &c);
    }
}

/* Cap at end point p; d points out of the stroke. */
static void add_cap(stroker *s, cj_vec2 p, cj_vec2 d) {
    if (!visible(s, p)) return;
    if (s->cap == CJ_CAP_ROUND) {
        add_disc(s, p, s->hw);
    } else if (s->cap == CJ_CAP_SQUARE) {
        cj_vec2 n = cj_v2_scale(cj_v2_perp(d), s->hw), e = cj_v2_add(p, cj_v2_scale(d, s->hw));
        convex c = {{cj_v2_add(p, n), cj_v2_sub(p, n), cj_v2_sub(e, n), cj_v2_add(e, n)}, 4};
        add_convex(s, &c);
    }
}

static cj_vec2 unit(cj_vec2 a, cj_vec2 b) {
    cj_vec2 d = cj_v2_sub(b, a);
    return cj_v2_scale(d, 1.0 / cj_v2_norm(d));
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
    if (s->npts == 1)
        s->first_dir = d;
    else
        add_join(s, s->prev, s->prev_dir, d);
    add_segment(s, s->prev, p, d);
    s->prev = p;
    s->prev_dir = d;
    s->npts++;
}

static void stroker_finish(stroker *s, int closed) {
    if (s->npts == 1) { /* a dot */
        if (s->cap == CJ_CAP_ROUND)
            add_disc(s, s->first, s->hw);
        else if (s->cap == CJ_CAP_SQUARE && visible(s, s->first)) {
            double h = s->hw, x = s->first.x, y = s->first.y;
            convex c = {{{x - h, y - h}, {x + h, y - h}, {x + h, y + h}, {x - h, y + h}}, 4};
            add_convex(s, &c);
        }
        return;
    }
    if (closed) {
        if (s->prev.x != s->first.x || s->prev.y != s->first.y) {
            cj_vec2 d = unit(s->prev, s->first);
            if (isfinite(d.x) && isfinite(d.y)) {
                add_join(s, s->prev, s->prev_dir, d);
                add_segment(s, s->prev, s->first, d);
                s->prev_dir = d;
            }
        }
        add_join(s, s->first, s->prev_dir, s->first_dir);
    } else {
        add_cap(s, s->first, cj_v2_scale(s->first_dir, -1.0));
        add_cap(s, s->prev, s->prev_dir);
    }
}

/* ---- set-up, validation, composition ------------------------------------------------------ */

static cj_status check_style(const cj_raster_stroke *st) {
    if (!isfinite(st->width))
        return cj_fail(CJ_ERR_NONFINITE, "stroke width is %s",
                       isnan(st->width) ? "NaN" : "infinite");
    if (!(st->width > 0.0) || st->width > CJ_RASTER_MAX_WIDTH)
        return cj_fail(CJ_ERR_RANGE, "stroke width %g is outside (0, %g]", st->width,
                       CJ_RASTER_MAX_WIDTH);
    if (st->join != CJ_JOIN_MITER && st->join != CJ_JOIN_ROUND && st->join != CJ_JOIN_BEVEL)
        return cj_fail(CJ_ERR_ARGUMENT, "stroke join %d is not a cj_raster_join", (int)st->join);
    if (st->cap != CJ_CAP_BUTT && st->cap != CJ_CAP_ROUND && st->cap != CJ_CAP_SQUARE)
        return cj_fail(CJ_ERR_ARGUMENT, "stroke cap %d is not a cj_raster_cap", (int)st->cap);
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
            if (fabs(c[k]) > CJ_RASTER_COORD_MAX)
                return cj_fail(CJ_ERR_RANGE, "polyline point %zu: %s = %g exceeds 2^52", i,
                               k ? "y" : "x", c[k]);
        }
    }
    return CJ_OK;
}

static void stroker_init(stroker *s, cover_target *t, const cj_raster_stroke *st) {
    memset(s, 0, sizeof *s);
    s->t = t;
    double h = 0.5 * st->width;
    s->hw = h < 0.5 ? 0.5 : h;
    s->scale = h < 0.5 ? (float)(2.0 * h) : 1.0f;
    s->join = st->join;
    s->cap = st->cap;
    s->miter_limit = st->miter_limit;
    double reach =
        s->hw * (st->join == CJ_JOIN_MITER && st->miter_limit > 1.5 ? st->miter_limit : 1.5) + 2.0;
    s->rxlo = t->ox - reach;
    s->rxhi = t->ox + t->w + reach;
    s->rylo = t->oy - reach;
    s->ryhi = t->oy + t->h + reach;
    t->ymin = INT_MAX;
    t->ymax = -1;
}

/* Hands every covered pixel to fn (or blends it into fb) and clears the plane behind. */
static void compose(cover_target *t, cj_framebuffer *fb, cj_rgba c, cj_raster_cover_fn fn,
                    void *user) {
    for (int ry = t->ymin; ry <= t->ymax; ++ry) {
        float *row = t->cover + (ptrdiff_t)ry * t->w;
        for (int x = t->lo[ry]; x <= t->hi[ry]; ++x) {
            float cov = row[x];
            if (cov > 0.0f) {
                if (fn) {
                    fn(user, x + t->ox, ry + t->oy, cov);
                } else if (fb) {
                    cj_rgba s = c;
                    s.a = cj_raster_scale_alpha_(c.a, cov);
                    cj_rgba *p = fb->pixels + (ptrdiff_t)(ry + t->oy) * fb->stride + x + t->ox;
                    *p = cj_rgba_over(s, *p);
                }
                row[x] = 0.0f;
            }
        }
        t->lo[ry] = INT_MAX;
        t->hi[ry] = -1;
    }
    t->ymin = INT_MAX;
    t->ymax = -1;
}

static cj_status fb_target(cj_framebuffer *fb, cover_target *t) {
    if (!fb->cover_) {
        size_t n = (size_t)fb->width * (size_t)fb->height;
        float *cover = cj_raster_alloc_(&fb->alloc_, n * sizeof *cover);
        int *lo = cj_raster_alloc_(&fb->alloc_, (size_t)fb->height * sizeof *lo);
        int *hi = cj_raster_alloc_(&fb->alloc_, (size_t)fb->height * sizeof *hi);
        if (!cover || !lo || !hi) {
            cj_raster_free_(&fb->alloc_, cover);
            cj_raster_free_(&fb->alloc_, lo);
            cj_raster_free_(&fb->alloc_, hi);
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
    t->h = fb->height;
    return CJ_OK;
}

cj_status cj_raster_stroke_polyline(cj_framebuffer *fb, const cj_vec2 *pts, size_t n, int closed,
                                    const cj_raster_stroke *style, cj_rgba c) {
    assert(fb && style && (pts || n == 0));
    cj_status st;
    if ((st = check_style(style)) || (st = check_points(pts, n))) return st;
    cover_target t;
    if ((st = fb_target(fb, &t))) return st;
    stroker s;
    stroker_init(&s, &t, style);
    for (size_t i = 0; i < n; ++i) stroker_point(&s, pts[i]);
    stroker_finish(&s, closed);
    compose(&t, fb, c, NULL, NULL);
    return CJ_OK;
}

size_t cj_raster_stroke_work_size(cj_raster_rect clip) {
    if (clip.x1 < clip.x0 || clip.y1 < clip.y0) return 0;
    size_t w = (size_t)((long long)clip.x1 - clip.x0 + 1);
    size_t h = (size_t)((long long)clip.y1 - clip.y0 + 1);
    return w * h * sizeof(float) + 2 * h * sizeof(int);
}

cj_status cj_raster_stroke_polyline_visit(const cj_vec2 *pts, size_t n, int closed,
                                          const cj_raster_stroke *style, cj_raster_rect clip,
                                          void *work, size_t work_bytes, cj_raster_cover_fn fn,
                                          void *user) {
    assert(style && fn && (pts || n == 0));
    cj_status st;
    if ((st = check_style(style)) || (st = check_points(pts, n))) return st;
    size_t need = cj_raster_stroke_work_size(clip);
    if (need == 0) return CJ_OK;
    assert(work);
    if (work_bytes < need)
        return cj_fail(CJ_ERR_BUFFER, "stroke workspace has %zu bytes, %zu needed", work_bytes,
                       need);
    cover_target t;
    t.ox = clip.x0;
    t.oy = clip.y0;
    t.w = clip.x1 - clip.x0 + 1;
    t.h = clip.y1 - clip.y0 + 1;
    t.cover = work;
    t.lo = (int *)(t.cover + (size_t)t.w * (size_t)t.h);
    t.hi = t.lo + t.h;
    memset(t.cover, 0, (size_t)t.w * (size_t)t.h * sizeof(float));
    for (int y = 0; y < t.h; ++y) t.lo[y] = INT_MAX, t.hi[y] = -1;
    stroker s;
    stroker_init(&s, &t, style);
    for (size_t i = 0; i < n; ++i) stroker_point(&s, pts[i]);
    stroker_finish(&s, closed);
    compose(&t, NULL, cj_rgba_make(0, 0, 0, 0), fn, user);
    return CJ_OK;
}

/* ---- curves --------------------------------------------------------------------------------- */

static void curve_sink(void *user, const double *pt, int dim, size_t piece, double t) {
    (void)dim, (void)piece, (void)t;
    stroker_point(user, cj_v2(pt[0], pt[1]));
}

cj_status cj_raster_stroke_bezier(cj_framebuffer *fb, const cj_bezier *curve, double tol,
                                  const cj_raster_stroke *style, cj_rgba c, double *bound) {
    assert(fb && curve && style);
    cj_status st;
    if ((st = check_style(style))) return st;
    if (curve->dim != 2)
        return cj_fail(CJ_ERR_DIMENSION, "curve dimension %d: strokes need 2D curves", curve->dim);
    cover_target t;
    if ((st = fb_target(fb, &t))) return st;
    stroker s;
    stroker_init(&s, &t, style);
    cj_flatten_opts opts = cj_flatten_defaults(CJ_FLATTEN_NEAR_OPTIMAL, tol);
    cj_flatten_stats stats;
    st = cj_flatten_bezier_cb(curve, &opts, curve_sink, &s, &stats);
    if (st) {
        compose(&t, NULL, c, NULL, NULL); /* clear whatever was accumulated, draw nothing */
        return st;
    }
    stroker_finish(&s, 0);
    compose(&t, fb, c, NULL, NULL);
    if (bound) *bound = stats.bound;
    return CJ_OK;
}

/* Wide anti-aliased strokes with exact area coverage.
 *
 * The stroke is cut into convex pieces that do not overlap: one rectangle per segment, a wedge
 * (miter quadrilateral, bevel triangle, or circular sector) on the outer side of each join, and
 * the caps (square: rectangle; round: half-disc sector). Where two consecutive rectangles
 * overlap on the inner side of a join, the area of their intersection (again convex) is
 * subtracted. For every pixel the exact area of (pixel square ∩ piece) is accumulated, computed
 * by clipping the piece to the square (Sutherland-Hodgman) and taking the shoelace area; pixels
 * lying wholly inside a piece are found per row from the piece's x-intervals and get 1 without
 * clipping. Circular sectors are polygons with at most 0.02 px sagitta whose radius is enlarged
 * so that each triangle has the exact sector area. Accumulation goes into a float plane over
 * touched spans (one [lo, hi] per row) which is composited once, clamped to [0, 1], and cleared
 * again for the next call. Pieces of non-adjacent segments that overlap (self-intersections)
 * add up and are clamped at 1. */
#include "casteljau/flatten.h"
#include "casteljau/line.h"
#include "error_internal.h"
#include "raster_internal.h"

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

typedef struct cover_target {
    float *cover;     /* w*h, zero outside touched spans */
    int *lo, *hi;     /* per row, relative x; empty when lo > hi */
    int ox, oy, w, h; /* pixel (x, y) is cover[(y-oy)*cs + (x-ox)] */
    ptrdiff_t cs;     /* row pitch of the plane (padded: see CJ_FB_PADDED) */
    int ymin, ymax;   /* touched rows, relative; empty when ymin > ymax */
    /* Sheared plane (steep single segments, see narrow_plane): row ry holds the cells of
     * columns base(ry) .. base(ry) + cs - 1, base(ry) = floor(bx0 + bk ry); 0 when !sheared. */
    int sheared;
    double bx0, bk;
} cover_target;

/* Offset of cell (ry, x = 0) in the plane. */
static inline ptrdiff_t row_offset(const cover_target *t, int ry) {
    ptrdiff_t o = (ptrdiff_t)ry * t->cs;
    if (t->sheared) o -= (ptrdiff_t)floor(t->bx0 + t->bk * ry);
    return o;
}

#define POLY_MAX 16
typedef struct poly {
    cj_vec2 v[POLY_MAX];
    int n;
} poly;

typedef struct stroker {
    cover_target *t;
    double hw; /* half width */
    cj_raster_join join;
    cj_raster_cap cap;
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

/* ---- exact coverage by signed-area accumulation ---------------------------------------- */

/* Coverage is accumulated per row as differences: pixel x of row y is covered by
 * cov(x) = Σ_{x' <= x} cell[x'], so that one pass over the touched span (compose) turns the cells
 * into coverage. A polygon's coverage of a pixel is the integral of its winding number over the
 * pixel, which is the sum over its edges of each edge's signed share: an edge piece crossing row
 * y from height ya to yb adds, to every pixel x of that row, (ya - yb) times the mean over the
 * piece of the part of [x, x+1] right of the edge, clamp(x + 1 - X(y), 0, 1). With the piece
 * running from x_lo to x_hi (W = x_hi - x_lo) that mean is
 *     F(x) = (R(x + 1 - x_lo) - R(x + 1 - x_hi)) / W,   R(z) = 0, z^2/2, z - 1/2 (z <= 0, <= 1, >
 * 1) (the integral of the ramp over the piece), and x + 1 - X when the piece stays in one column.
 * F rises from 0 left of the piece to 1 right of it, so the piece touches cells floor(x_lo) ..
 * ceil(x_hi) only. Counter-clockwise polygons thus get +area, clockwise ones -area; each piece
 * is added with its sign times its orientation, so pieces add and subtract exactly as areas do.
 * Clipping: edge parts left of the target count as if on its left border (every pixel right of
 * them sees the same ramp value 1), parts right of it touch no pixel of it (but extend the
 * row's span to the border, where the polygon's inside continues). */

/* Rows ahead whose coverage cells and framebuffer lines are prefetched: long steep strokes touch
 * a new line of each per row, and the misses should overlap instead of queueing. */
#define CJ_STROKE_PREFETCH_ROWS 4

static inline double ramp_int(double z) {
    return z <= 0.0 ? 0.0 : (z <= 1.0 ? 0.5 * z * z : z - 0.5);
}

static inline void touch_row(cover_target *t, int ry, int x0, int x1) {
    if (x0 < t->lo[ry]) t->lo[ry] = x0;
    if (x1 > t->hi[ry]) t->hi[ry] = x1;
    if (ry < t->ymin) t->ymin = ry;
    if (ry > t->ymax) t->ymax = ry;
}

/* One edge piece (x0, y0) -> (x1, y1) with 0 <= x <= w (relative coordinates), weight wt. */
static void add_edge_inside(cover_target *t, double x0, double y0, double x1, double y1,
                            double wt) {
    if (y0 == y1) return;
    if (y0 > y1) { /* walk upwards; the sign follows the original direction */
        double tx = x0, ty = y0;
        x0 = x1, y0 = y1, x1 = tx, y1 = ty;
        wt = -wt;
    }
    const double k = (x1 - x0) / (y1 - y0);
    int r0 = (int)floor(y0), r1 = (int)ceil(y1) - 1;
    if (r0 < 0) r0 = 0;
    if (r1 > t->h - 1) r1 = t->h - 1;
    const int w = t->w;
    for (int ry = r0; ry <= r1; ++ry) {
        if (ry + CJ_STROKE_PREFETCH_ROWS <= r1) { /* the cell this edge reaches a few rows up */
            double xp = x0 + ((double)(ry + CJ_STROKE_PREFETCH_ROWS) + 0.5 - y0) * k;
            xp = xp < 0.0 ? 0.0 : (xp > w - 1 ? w - 1 : xp);
            __builtin_prefetch(
                t->cover + row_offset(t, ry + CJ_STROKE_PREFETCH_ROWS) + (ptrdiff_t)xp, 1);
        }
        const double ya = y0 > ry ? y0 : ry, yb = y1 < ry + 1.0 ? y1 : ry + 1.0;
        if (!(yb > ya)) continue;
        double xa = x0 + (ya - y0) * k, xb = x0 + (yb - y0) * k;
        /* rounding must not carry x past the clip lines */
        xa = xa < 0.0 ? 0.0 : (xa > w ? w : xa);
        xb = xb < 0.0 ? 0.0 : (xb > w ? w : xb);
        const double d = (ya - yb) * wt; /* upward pieces: -height */
        const double xl = xa < xb ? xa : xb, xh = xa < xb ? xb : xa;
        float *row = t->cover + row_offset(t, ry);
        int i0 = (int)floor(xl);
        if (i0 >= w) i0 = w - 1; /* an edge on the right border: its cell is the last one */
        const double fi0 = (double)i0;
        if (xh <= fi0 + 1.0) { /* one column: F(i0) = i0 + 1 - mean X */
            const double f = fi0 + 1.0 - 0.5 * (xl + xh);
            row[i0] += (float)(d * f);
            if (i0 + 1 < w) row[i0 + 1] += (float)(d * (1.0 - f));
            touch_row(t, ry, i0, i0 + 1 < w ? i0 + 1 : i0);
            continue;
        }
        const int i1 = (int)ceil(xh); /* F(i1) = 1 */
        const double inv = 1.0 / (xh - xl);
        /* F(i) = (i + 1/2 - xl) / W on the columns whose ramp lies wholly inside the piece
         * (xl <= i <= xh - 1, i.e. m0 .. M), so the cells m0 + 1 .. M all get d / W. */
        const int m0 = (int)ceil(xl), M = (int)floor(xh) - 1;
        double fprev = 0.0;
        for (int i = i0; i <= i1 && i < w; ++i) {
            const double u = (double)i + 1.0;
            const double f = i == i1 ? 1.0 : (ramp_int(u - xl) - ramp_int(u - xh)) * inv;
            row[i] += (float)(d * (f - fprev));
            fprev = f;
            if (i == m0 && M > m0) {
                const float step = (float)(d * inv);
                const int e = M < w - 1 ? M : w - 1;
                for (int j = m0 + 1; j <= e; ++j) row[j] += step;
                i = M;
                fprev = ((double)M + 0.5 - xl) * inv;
            }
        }
        touch_row(t, ry, i0, i1 < w ? i1 : w - 1);
    }
}

/* An edge in relative coordinates: split at the target's left and right borders. */
static void add_edge(cover_target *t, double x0, double y0, double x1, double y1, double wt) {
    const double w = t->w;
    if ((y0 < 0.0 && y1 < 0.0) || (y0 > t->h && y1 > t->h) || y0 == y1) return;
    if (x0 > x1) { /* order by x; the direction (and sign) is kept by swapping both */
        double tx = x0, ty = y0;
        x0 = x1, y0 = y1, x1 = tx, y1 = ty;
        wt = -wt;
    }
    if (x1 > w) { /* the part right of the target: no pixel, but the span reaches the border */
        double yc = x0 >= w ? y0 : y0 + (y1 - y0) * ((w - x0) / (x1 - x0));
        double ylo = yc < y1 ? yc : y1, yhi = yc < y1 ? y1 : yc;
        int r0 = (int)floor(ylo), r1 = (int)ceil(yhi) - 1;
        if (r0 < 0) r0 = 0;
        if (r1 > t->h - 1) r1 = t->h - 1;
        for (int ry = r0; ry <= r1; ++ry) touch_row(t, ry, t->w - 1, t->w - 1);
        if (x0 >= w) return;
        x1 = w, y1 = yc;
    }
    if (x0 < 0.0) { /* the part left of the target counts on its left border */
        double yc = x1 <= 0.0 ? y1 : y0 + (y1 - y0) * ((0.0 - x0) / (x1 - x0));
        add_edge_inside(t, 0.0, y0, 0.0, yc, wt);
        if (x1 <= 0.0) return;
        x0 = 0.0, y0 = yc;
    }
    add_edge_inside(t, x0, y0, x1, y1, wt);
}

/* Accumulates sign * area(pixel ∩ p) over the pixels of the target. */
static void add_poly(stroker *s, const poly *p, float sign) {
    if (p->n < 3) return;
    cover_target *t = s->t;
    double area2 = 0;
    for (int i = 0, j = p->n - 1; i < p->n; j = i++)
        area2 += p->v[j].x * p->v[i].y - p->v[i].x * p->v[j].y;
    if (area2 == 0.0) return;
    const double wt = area2 > 0.0 ? (double)sign : -(double)sign;
    const double ox = t->ox, oy = t->oy;
    for (int i = 0, j = p->n - 1; i < p->n; j = i++)
        add_edge(t, p->v[j].x - ox, p->v[j].y - oy, p->v[i].x - ox, p->v[i].y - oy, wt);
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

static void stroker_init(stroker *s, cover_target *t, const cj_raster_stroke *st, int closed) {
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

/* Hands every covered pixel to fn (or blends it into fb) and clears the plane behind: the
 * running sum of a row's cells is its coverage. */
static void compose(cover_target *t, cj_framebuffer *fb, cj_rgba c, cj_raster_cover_fn fn,
                    void *user) {
    for (int ry = t->ymin; ry <= t->ymax; ++ry) {
        float *row = t->cover + row_offset(t, ry);
        const int lo = t->lo[ry], hi = t->hi[ry];
        t->lo[ry] = INT_MAX;
        t->hi[ry] = -1;
        if (lo > hi) continue;
        double acc = 0.0;
        if (fn || !fb) {
            for (int x = lo; x <= hi; ++x) {
                acc += row[x];
                row[x] = 0.0f;
                float cov = (float)acc;
                if (cov > 1e-6f) { /* below: rounding residue of subtracted overlaps */
                    if (cov > 1.0f) cov = 1.0f;
                    if (fn) fn(user, x + t->ox, ry + t->oy, cov);
                }
            }
            continue;
        }
        cj_rgba *px = fb->pixels + (ptrdiff_t)(ry + t->oy) * fb->stride + t->ox;
        /* Steep strokes touch a new framebuffer line per row: start fetching the lines a few
         * rows ahead (their spans are known), so the misses overlap instead of queueing. */
        for (int k = 1; k <= CJ_STROKE_PREFETCH_ROWS; ++k)
            if (ry + k <= t->ymax && t->lo[ry + k] <= t->hi[ry + k]) {
                __builtin_prefetch(px + (ptrdiff_t)k * fb->stride + t->lo[ry + k], 1);
                __builtin_prefetch(px + (ptrdiff_t)k * fb->stride + t->hi[ry + k], 1);
            }
        for (int x = lo; x <= hi; ++x) {
            acc += row[x];
            row[x] = 0.0f;
            const float cov = (float)acc;
            if (cov > 1e-6f) {
                cj_rgba sc = c;
                sc.a = cj_raster_scale_alpha_(c.a, cov > 1.0f ? 1.0f : cov);
                if (sc.a == 255)
                    px[x] = sc;
                else if (sc.a != 0)
                    px[x] = cj_rgba_over_inl_(sc, px[x]);
            }
        }
    }
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

/* A steep single segment (|dy| >= |dx|) lying wholly inside the target touches a few cells per
 * row of a long column of rows, one plane line per row, each cold in a plane the size of the
 * framebuffer. Its cells fit a narrow band that follows the segment: everything of the stroke
 * (rectangle and caps) lies within R = half width (times sqrt 2 for square caps) of the
 * segment, hence within R / cos θ horizontally of its line (θ from the vertical), so row ry
 * needs only the columns around the line's x in that row. The plane is then addressed with a
 * pitch of that band's width (a few tens of floats) and a per-row base column: the rows of one
 * stroke are contiguous and stay in cache from stroke to stroke. Other strokes keep the full
 * plane. Returns 1 if the target was switched to the sheared addressing. */
static int narrow_plane(cover_target *t, const cj_vec2 *pts, size_t n, int closed,
                        const cj_raster_stroke *style) {
    if (n != 2 || closed) return 0;
    const double x0 = pts[0].x - t->ox, y0 = pts[0].y - t->oy;
    const double dx = pts[1].x - pts[0].x, dy = pts[1].y - pts[0].y;
    if (!(fabs(dy) >= fabs(dx)) || !(fabs(dy) > 0.0)) return 0;
    const double k = dx / dy, len = hypot(dx, dy), hw = 0.5 * style->width;
    const double R = style->cap == CJ_CAP_SQUARE ? hw * 1.4142135623730951 : hw;
    const double half = R * len / fabs(dy) + 0.5 * fabs(k) + 2.0;
    const double W = ceil(2.0 * half) + 2.0;
    if (!(W < (double)t->cs)) return 0;
    /* wholly inside: rows and the band's columns for every row the stroke can reach */
    const double ylo = fmin(y0, y0 + dy) - R - 1.0, yhi = fmax(y0, y0 + dy) + R + 1.0;
    if (!(ylo >= 0.0 && yhi <= t->h)) return 0;
    const double xa = x0 + (ylo - y0) * k, xb = x0 + (yhi - y0) * k;
    if (!(fmin(xa, xb) - half - 1.0 >= 0.0 && fmax(xa, xb) + half + 1.0 <= t->w)) return 0;
    t->sheared = 1;
    t->cs = (ptrdiff_t)W;
    t->bk = k;
    t->bx0 = x0 + (0.5 - y0) * k - half; /* base(ry) = floor(x at the row's middle - half) */
    return 1;
}

cj_status cj_raster_stroke_polyline(cj_framebuffer *fb, const cj_vec2 *pts, size_t n, int closed,
                                    const cj_raster_stroke *style, cj_rgba c) {
    assert(fb && style && (pts || n == 0));
    cj_status st;
    if ((st = check_style(style)) || (st = check_points(pts, n))) return st;
    cover_target t;
    if ((st = fb_target(fb, &t))) return st;
    narrow_plane(&t, pts, n, closed, style);
    stroker s;
    stroker_init(&s, &t, style, closed);
    for (size_t i = 0; i < n; ++i) stroker_point(&s, pts[i]);
    stroker_finish(&s);
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
    compose(&t, NULL, cj_rgba_make(0, 0, 0, 0), fn, user);
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
                                  double tol, const cj_raster_stroke *style, cj_rgba c,
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
        compose(&t, NULL, c, NULL, NULL); /* clear whatever was accumulated, draw nothing */
        return st;
    }
    stroker_finish(&s);
    compose(&t, fb, c, NULL, NULL);
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

cj_status cj_raster_stroke_bezier(cj_framebuffer *fb, const cj_bezier *curve, double tol,
                                  const cj_raster_stroke *style, cj_rgba c, double *bound) {
    assert(fb && curve && style);
    cj_status st;
    if ((st = check_style(style))) return st;
    if (curve->dim != 2)
        return cj_fail(CJ_ERR_DIMENSION, "curve dimension %d: strokes need 2D curves", curve->dim);
    return stroke_flattened(fb, curve, run_bezier, tol, style, c, bound);
}

cj_status cj_raster_stroke_rbezier(cj_framebuffer *fb, const cj_rbezier *curve, double tol,
                                   const cj_raster_stroke *style, cj_rgba c, double *bound) {
    assert(fb && curve && style);
    cj_status st;
    if ((st = check_style(style))) return st;
    if (curve->dim != 2)
        return cj_fail(CJ_ERR_DIMENSION, "curve dimension %d: strokes need 2D curves", curve->dim);
    return stroke_flattened(fb, curve, run_rbezier, tol, style, c, bound);
}

cj_status cj_raster_stroke_sequence(cj_framebuffer *fb, const cj_flatten_piece *pieces,
                                    size_t count, double tol, const cj_raster_stroke *style,
                                    cj_rgba c, double *bound) {
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

cj_status cj_raster_fill_convex(cj_framebuffer *fb, const cj_vec2 *pts, size_t n, cj_rgba c) {
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
    cj_raster_stroke style = cj_raster_stroke_default(1.0);
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
    compose(&t, fb, c, NULL, NULL);
    return CJ_OK;
}

cj_status cj_raster_fill_disc(cj_framebuffer *fb, cj_vec2 centre, double radius, cj_rgba c) {
    assert(fb);
    cj_status st = check_points(&centre, 1);
    if (st) return st;
    if (!isfinite(radius))
        return cj_fail(CJ_ERR_NONFINITE, "disc radius is %s", isnan(radius) ? "NaN" : "infinite");
    if (!(radius > 0.0) || radius > CJ_RASTER_MAX_WIDTH)
        return cj_fail(CJ_ERR_RANGE, "disc radius %g is outside (0, %g]", radius,
                       CJ_RASTER_MAX_WIDTH);
    cover_target t;
    if ((st = fb_target(fb, &t))) return st;
    cj_raster_stroke style = cj_raster_stroke_default(2.0 * radius);
    stroker s;
    stroker_init(&s, &t, &style, 0);
    if (visible(&s, centre)) {
        add_sector(&s, centre, cj_v2(1, 0), CJ_PI_, 1, radius);
        add_sector(&s, centre, cj_v2(-1, 0), CJ_PI_, 1, radius);
    }
    compose(&t, fb, c, NULL, NULL);
    return CJ_OK;
}

/* Exact stroke coverage: signed-area accumulation into the coverage plane, composition, and
 * the narrow plane of steep single segments. */
#include "raster_internal.h"
#include "stroke_internal.h"

#include <limits.h>
#include <math.h>

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
    /* rows clamped in double first: polygon coordinates may be far outside the target */
    const int r0 = (int)floor(y0 > 0.0 ? y0 : 0.0), r1 = (int)ceil(y1 < t->h ? y1 : t->h) - 1;
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
        const int r0 = (int)floor(ylo > 0.0 ? ylo : 0.0);
        const int r1 = (int)ceil(yhi < t->h ? yhi : t->h) - 1;
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
void cj_stroke_cover_poly(cover_target *t, const poly *p, float sign) {
    if (p->n < 3) return;
    double area2 = 0;
    for (int i = 0, j = p->n - 1; i < p->n; j = i++)
        area2 += p->v[j].x * p->v[i].y - p->v[i].x * p->v[j].y;
    if (area2 == 0.0) return;
    const double wt = area2 > 0.0 ? (double)sign : -(double)sign;
    const double ox = t->ox, oy = t->oy;
    for (int i = 0, j = p->n - 1; i < p->n; j = i++)
        add_edge(t, p->v[j].x - ox, p->v[j].y - oy, p->v[i].x - ox, p->v[i].y - oy, wt);
}

/* Hands every covered pixel to fn (or blends it into fb) and clears the plane behind: the
 * running sum of a row's cells is its coverage. */
void cj_stroke_compose(cover_target *t, cj_framebuffer *fb, cj_rgba c, cj_line_cover_fn fn,
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

/* A steep single segment (|dy| >= |dx|) lying wholly inside the target touches a few cells per
 * row of a long column of rows, one plane line per row, each cold in a plane the size of the
 * framebuffer. Its cells fit a narrow band that follows the segment: everything of the stroke
 * (rectangle and caps) lies within R = half width (times sqrt 2 for square caps) of the
 * segment, hence within R / cos θ horizontally of its line (θ from the vertical), so row ry
 * needs only the columns around the line's x in that row. The plane is then addressed with a
 * pitch of that band's width (a few tens of floats) and a per-row base column: the rows of one
 * stroke are contiguous and stay in cache from stroke to stroke. Other strokes keep the full
 * plane. Returns 1 if the target was switched to the sheared addressing. */
int cj_stroke_narrow_plane(cover_target *t, const cj_vec2 *pts, size_t n, int closed,
                           const cj_line_stroke *style) {
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

/* Exact Bresenham lines: integer stepping, exact 128-bit clipping before stepping.
 *
 * Major axis u (x when |dx| >= |dy|), minor axis v; end points ordered so that u0 <= u1,
 * du = u1 - u0 >= |dv|. Step i in [0, du] is the pixel (u0 + i, V(i)) with
 *     V(i) = v0 + floor((2 i dv + du) / (2 du))        (round half up of v0 + i dv/du).
 * The remainder r(i) = (2 i dv + du) mod 2du drives the stepping; for dv < 0 the mirrored
 * remainder 2du - 1 - r is used so that the loop always adds 2|dv| and wraps at 2du. */
#include "casteljau/line.h"
#include "error_internal.h"
#include "raster_internal.h"

#include <assert.h>
#include <math.h>

__extension__ typedef __int128 i128;

typedef struct line_run {
    long long n;           /* pixels to visit (0: nothing visible) */
    int x, y;              /* first visible pixel */
    int ux, uy;            /* major step (1,0) or (0,1) */
    int vx, vy;            /* minor step, (0,±1) or (±1,0) */
    long long e, inc, lim; /* error term in [0, lim), increment 2|dv|, lim = 2du */
} line_run;

static i128 floordiv(i128 a, i128 b) {
    i128 q = a / b;
    if (a % b != 0 && ((a < 0) != (b < 0))) --q;
    return q;
}
static i128 ceildiv(i128 a, i128 b) {
    return -floordiv(-a, b);
}

static cj_status check_coord(long long v, int point, const char *axis) {
    if (v > (long long)CJ_LINE_COORD_MAX || v < -(long long)CJ_LINE_COORD_MAX)
        return cj_fail(CJ_ERR_RANGE, "line end point %d: %s = %lld exceeds 2^52 in magnitude",
                       point, axis, v);
    return CJ_OK;
}

static cj_status check_coord_d(double v, int point, const char *axis, long long *out) {
    if (!isfinite(v))
        return cj_fail(CJ_ERR_NONFINITE, "line end point %d: %s is %s", point, axis,
                       isnan(v) ? "NaN" : "infinite");
    if (fabs(v) > CJ_LINE_COORD_MAX)
        return cj_fail(CJ_ERR_RANGE, "line end point %d: %s = %g exceeds 2^52 in magnitude", point,
                       axis, v);
    *out = (long long)floor(v);
    return CJ_OK;
}

/* Plans the clipped run of the exact line; coordinates already validated. */
static void line_plan(long long x0, long long y0, long long x1, long long y1, cj_line_rect clip,
                      line_run *run) {
    run->n = 0;
    if (clip.x1 < clip.x0 || clip.y1 < clip.y0) return;
    long long adx = x1 > x0 ? x1 - x0 : x0 - x1, ady = y1 > y0 ? y1 - y0 : y0 - y1;
    int xmajor = adx >= ady;
    long long u0, v0, u1, v1, cu0, cu1, cv0, cv1;
    if (xmajor) {
        u0 = x0, v0 = y0, u1 = x1, v1 = y1;
        cu0 = clip.x0, cu1 = clip.x1, cv0 = clip.y0, cv1 = clip.y1;
    } else {
        u0 = y0, v0 = x0, u1 = y1, v1 = x1;
        cu0 = clip.y0, cu1 = clip.y1, cv0 = clip.x0, cv1 = clip.x1;
    }
    if (u0 > u1) {
        long long t = u0;
        u0 = u1, u1 = t;
        t = v0, v0 = v1, v1 = t;
    }
    long long du = u1 - u0, dv = v1 - v0;
    /* Major-axis window. */
    long long ilo = cu0 - u0 > 0 ? cu0 - u0 : 0;
    long long ihi = cu1 - u0 < du ? cu1 - u0 : du;
    if (ilo > ihi) return;
    long long e = 0, vstart = v0;
    if (dv == 0) {
        if (v0 < cv0 || v0 > cv1) return;
    } else if (ilo == 0 && ihi == du && v0 >= cv0 && v0 <= cv1 && v1 >= cv0 && v1 <= cv1) {
        /* Wholly inside (the common case): r(0) = du mod 2du = du, no 128-bit work. */
        e = dv > 0 ? du : du - 1;
    } else {
        /* Minor-axis window: cv0 <= V(i) <= cv1 as exact integer inequalities in i. */
        i128 a = 2 * (i128)dv, two_du = 2 * (i128)du;
        i128 b = two_du * (cv0 - v0) - du;     /* V(i) >= cv0  <=>  a i >= b */
        i128 c = two_du * (cv1 - v0 + 1) - du; /* V(i) <= cv1  <=>  a i <  c */
        i128 lo, hi;
        if (a > 0) {
            lo = ceildiv(b, a);
            hi = ceildiv(c, a) - 1;
        } else {
            hi = floordiv(b, a);
            lo = floordiv(c, a) + 1;
        }
        if (lo > ilo) ilo = lo > ihi ? ihi + 1 : (long long)lo;
        if (hi < ihi) ihi = hi < ilo ? ilo - 1 : (long long)hi;
        if (ilo > ihi) return;
        i128 num = a * ilo + du;
        i128 q = floordiv(num, two_du);
        long long r = (long long)(num - q * two_du);
        vstart = v0 + (long long)q;
        e = dv > 0 ? r : 2 * du - 1 - r;
    }
    long long ustart = u0 + ilo;
    run->n = ihi - ilo + 1;
    run->e = e;
    run->inc = dv > 0 ? 2 * dv : -2 * dv;
    run->lim = 2 * du;
    int s = dv > 0 ? 1 : -1;
    if (xmajor) {
        run->x = (int)ustart, run->y = (int)vstart;
        run->ux = 1, run->uy = 0, run->vx = 0, run->vy = s;
    } else {
        run->x = (int)vstart, run->y = (int)ustart;
        run->ux = 0, run->uy = 1, run->vx = s, run->vy = 0;
    }
}

static cj_status validate_ll(long long x0, long long y0, long long x1, long long y1) {
    cj_status st;
    if ((st = check_coord(x0, 0, "x")) || (st = check_coord(y0, 0, "y")) ||
        (st = check_coord(x1, 1, "x")) || (st = check_coord(y1, 1, "y")))
        return st;
    return CJ_OK;
}

static cj_status to_pixels(double x0, double y0, double x1, double y1, long long out[4]) {
    cj_status st;
    if ((st = check_coord_d(x0, 0, "x", &out[0])) || (st = check_coord_d(y0, 0, "y", &out[1])) ||
        (st = check_coord_d(x1, 1, "x", &out[2])) || (st = check_coord_d(y1, 1, "y", &out[3])))
        return st;
    return CJ_OK;
}

cj_status cj_line_visit(long long x0, long long y0, long long x1, long long y1, cj_line_rect clip,
                        cj_line_pixel_fn fn, void *user, long long *visited) {
    cj_status st = validate_ll(x0, y0, x1, y1);
    if (st) return st;
    line_run run;
    line_plan(x0, y0, x1, y1, clip, &run);
    if (fn) {
        int x = run.x, y = run.y;
        long long e = run.e;
        for (long long k = 0; k < run.n; ++k) {
            fn(user, x, y);
            e += run.inc;
            if (e >= run.lim) {
                e -= run.lim;
                x += run.vx;
                y += run.vy;
            }
            x += run.ux;
            y += run.uy;
        }
    }
    if (visited) *visited = run.n;
    return CJ_OK;
}

cj_status cj_line_visit_d(double x0, double y0, double x1, double y1, cj_line_rect clip,
                          cj_line_pixel_fn fn, void *user, long long *visited) {
    long long p[4] = {0, 0, 0, 0}; /* set by to_pixels on success; zeroed for -O3 flow analysis */
    cj_status st = to_pixels(x0, y0, x1, y1, p);
    if (st) return st;
    return cj_line_visit(p[0], p[1], p[2], p[3], clip, fn, user, visited);
}

static void draw_run(cj_framebuffer *fb, const line_run *run, cj_rgba c) {
    if (run->n == 0) return;
    cj_rgba *p = fb->pixels + (ptrdiff_t)run->y * fb->stride + run->x;
    const ptrdiff_t major = run->ux + (ptrdiff_t)run->uy * fb->stride;
    const ptrdiff_t minor = run->vx + (ptrdiff_t)run->vy * fb->stride;
    const long long inc = run->inc, lim = run->lim;
    long long e = run->e, n = run->n;
    if (c.a == 255) {
        if (inc == 0) {
            for (; n > 0; --n, p += major) *p = c;
            return;
        }
        for (; n > 0; --n) {
            *p = c;
            e += inc;
            if (e >= lim) {
                e -= lim;
                p += minor;
            }
            p += major;
        }
    } else if (c.a != 0) {
        for (; n > 0; --n) {
            *p = cj_rgba_over_inl_(c, *p);
            e += inc;
            if (e >= lim) {
                e -= lim;
                p += minor;
            }
            p += major;
        }
    }
}

cj_status cj_line_draw(cj_framebuffer *fb, long long x0, long long y0, long long x1, long long y1,
                       cj_rgba c) {
    assert(fb);
    cj_status st = validate_ll(x0, y0, x1, y1);
    if (st) return st;
    line_run run;
    line_plan(x0, y0, x1, y1, cj_line_rect_of(fb), &run);
    draw_run(fb, &run, c);
    return CJ_OK;
}

cj_status cj_line_draw_d(cj_framebuffer *fb, double x0, double y0, double x1, double y1,
                         cj_rgba c) {
    assert(fb);
    long long p[4] = {0, 0, 0, 0}; /* set by to_pixels on success; zeroed for -O3 flow analysis */
    cj_status st = to_pixels(x0, y0, x1, y1, p);
    if (st) return st;
    return cj_line_draw(fb, p[0], p[1], p[2], p[3], c);
}

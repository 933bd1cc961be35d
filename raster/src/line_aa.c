/* Anti-aliased thin lines after Xiaolin Wu.
 *
 * In coordinates shifted by -1/2 (pixel centres at integers), with the major axis u and end
 * points ordered u0 <= u1: column U covers [U - 1/2, U + 1/2] of the major axis; its weight is
 * the length of that interval inside [u0, u1], and the minor coordinate v is taken at the middle
 * of that overlap. The weight is split between the two pixels straddling v, 1 - frac(v) below
 * and frac(v) above. The total coverage is therefore exactly u1 - u0. */
#include "casteljau/line.h"
#include "error_internal.h"
#include "raster_internal.h"

#include <assert.h>
#include <math.h>

static cj_status check_point(double x, double y, int point) {
    const double c[2] = {x, y};
    for (int k = 0; k < 2; ++k) {
        if (!isfinite(c[k]))
            return cj_fail(CJ_ERR_NONFINITE, "line end point %d: %s is %s", point, k ? "y" : "x",
                           isnan(c[k]) ? "NaN" : "infinite");
        if (fabs(c[k]) > CJ_LINE_COORD_MAX)
            return cj_fail(CJ_ERR_RANGE, "line end point %d: %s = %g exceeds 2^52 in magnitude",
                           point, k ? "y" : "x", c[k]);
    }
    return CJ_OK;
}

/* Liang-Barsky clip of p + t (q - p), t in [0,1], against [xlo,xhi] x [ylo,yhi]; 0 if nothing
 * is left. */
static int clip_segment(double *t0, double *t1, double px, double py, double dx, double dy,
                        double xlo, double xhi, double ylo, double yhi) {
    const double p[4] = {-dx, dx, -dy, dy};
    const double q[4] = {px - xlo, xhi - px, py - ylo, yhi - py};
    double a = 0.0, b = 1.0;
    for (int k = 0; k < 4; ++k) {
        if (p[k] == 0.0) {
            if (q[k] < 0.0) return 0;
        } else {
            double r = q[k] / p[k];
            if (p[k] < 0.0) {
                if (r > a) a = r;
            } else if (r < b) {
                b = r;
            }
        }
    }
    if (a > b) return 0;
    *t0 = a;
    *t1 = b;
    return 1;
}

typedef struct aa_sink {
    cj_line_cover_fn fn;
    void *user;
    cj_framebuffer *fb;
    cj_rgba c;
} aa_sink;

static void emit(const aa_sink *s, long long x, long long y, float cov, cj_line_rect clip) {
    if (!(cov > 0.0f) || x < clip.x0 || x > clip.x1 || y < clip.y0 || y > clip.y1) return;
    if (s->fn)
        s->fn(s->user, (int)x, (int)y, cov);
    else {
        cj_rgba c = s->c;
        c.a = cj_raster_scale_alpha_(c.a, cov);
        cj_rgba *p = s->fb->pixels + (ptrdiff_t)y * s->fb->stride + (ptrdiff_t)x;
        *p = cj_rgba_over_inl_(c, *p);
    }
}

static cj_status wu(double x0, double y0, double x1, double y1, cj_line_rect clip,
                    const aa_sink *s) {
    cj_status st;
    if ((st = check_point(x0, y0, 0)) || (st = check_point(x1, y1, 1))) return st;
    if (clip.x1 < clip.x0 || clip.y1 < clip.y0) return CJ_OK;
    /* Shift so that pixel centres are integers. */
    x0 -= 0.5, y0 -= 0.5, x1 -= 0.5, y1 -= 0.5;
    int steep = fabs(y1 - y0) > fabs(x1 - x0);
    double u0 = steep ? y0 : x0, v0 = steep ? x0 : y0, u1 = steep ? y1 : x1, v1 = steep ? x1 : y1;
    if (u0 > u1 || (u0 == u1 && v0 > v1)) {
        double t = u0;
        u0 = u1, u1 = t;
        t = v0, v0 = v1, v1 = t;
    }
    double ulo = steep ? clip.y0 : clip.x0, uhi = steep ? clip.y1 : clip.x1;
    double vlo = steep ? clip.x0 : clip.y0, vhi = steep ? clip.x1 : clip.y1;
    /* Clip to the rectangle grown by 2 pixels: what is cut off cannot reach clip. */
    double du = u1 - u0, dv = v1 - v0, t0, t1;
    if (!clip_segment(&t0, &t1, u0, v0, du, dv, ulo - 2, uhi + 2, vlo - 2, vhi + 2)) return CJ_OK;
    double a = t0 > 0 ? u0 + t0 * du : u0, b = t1 < 1 ? u0 + t1 * du : u1;
    double grad = du > 0 ? dv / du : 0.0;
    long long U0 = (long long)floor(a + 0.5), U1 = (long long)floor(b + 0.5);
    for (long long U = U0; U <= U1; ++U) {
        double lo = (double)U - 0.5 > a ? (double)U - 0.5 : a;
        double hi = (double)U + 0.5 < b ? (double)U + 0.5 : b;
        double w = hi - lo;
        if (!(w > 0.0)) continue;
        double v = v0 + grad * (0.5 * (lo + hi) - u0);
        double fv = floor(v), f = v - fv;
        long long V = (long long)fv;
        float c0 = (float)(w * (1.0 - f)), c1 = (float)(w * f);
        if (steep) {
            emit(s, V, U, c0, clip);
            emit(s, V + 1, U, c1, clip);
        } else {
            emit(s, U, V, c0, clip);
            emit(s, U, V + 1, c1, clip);
        }
    }
    return CJ_OK;
}

cj_status cj_line_aa_visit(double x0, double y0, double x1, double y1, cj_line_rect clip,
                           cj_line_cover_fn fn, void *user) {
    assert(fn);
    aa_sink s = {fn, user, NULL, {0, 0, 0, 0}};
    return wu(x0, y0, x1, y1, clip, &s);
}

cj_status cj_line_draw_aa(cj_framebuffer *fb, double x0, double y0, double x1, double y1,
                          cj_rgba c) {
    assert(fb);
    aa_sink s = {NULL, NULL, fb, c};
    return wu(x0, y0, x1, y1, cj_line_rect_of(fb), &s);
}

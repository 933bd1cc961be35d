#define _DEFAULT_SOURCE
#include "vtk_render_check.h"

#include <setjmp.h>
#include <stdarg.h>
#include <cmocka.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define PREC 256

void cj_check_planes_alloc(cj_check_planes *p, int w, int h) {
    const size_t n = (size_t)w * (size_t)h;
    p->w = w;
    p->h = h;
    p->rgba = calloc(4 * n, sizeof *p->rgba);
    p->ids = calloc(n, sizeof *p->ids);
    p->depth = calloc(n, sizeof *p->depth);
    assert_non_null(p->rgba);
    assert_non_null(p->ids);
    assert_non_null(p->depth);
}

void cj_check_planes_free(cj_check_planes *p) {
    free(p->rgba);
    free(p->ids);
    free(p->depth);
    memset(p, 0, sizeof *p);
}

/* ---- exact classification --------------------------------------------------------------- */

static void m_dot(mpfr_t out, mpfr_t a[3], mpfr_t b[3], mpfr_t tmp) {
    mpfr_mul(out, a[0], b[0], MPFR_RNDN);
    mpfr_mul(tmp, a[1], b[1], MPFR_RNDN);
    mpfr_add(out, out, tmp, MPFR_RNDN);
    mpfr_mul(tmp, a[2], b[2], MPFR_RNDN);
    mpfr_add(out, out, tmp, MPFR_RNDN);
}

static void m_cross(mpfr_t out[3], mpfr_t a[3], mpfr_t b[3], mpfr_t tmp) {
    for (int i = 0; i < 3; i++) {
        const int j = (i + 1) % 3, k = (i + 2) % 3;
        mpfr_mul(out[i], a[j], b[k], MPFR_RNDN);
        mpfr_mul(tmp, a[k], b[j], MPFR_RNDN);
        mpfr_sub(out[i], out[i], tmp, MPFR_RNDN);
    }
}

static void m_normalize(mpfr_t v[3], mpfr_t tmp, mpfr_t tmp2) {
    m_dot(tmp2, v, v, tmp);
    mpfr_sqrt(tmp2, tmp2, MPFR_RNDN);
    for (int i = 0; i < 3; i++) mpfr_div(v[i], v[i], tmp2, MPFR_RNDN);
}

/* q(X, Y) > 0 inside, in double, X and Y pixel offsets from the image centre. */
static double q_double(const cj_sphere_oracle *o, double X, double Y) {
    const double xn = 2.0 * X / o->w, yn = 2.0 * Y / o->h;
    const double *C = o->C;
    if (o->cam.projection == CJ_PROJ_ORTHOGRAPHIC) {
        const double dx = xn * o->tx - C[0], dy = yn * o->ty - C[1];
        return o->r * o->r - dx * dx - dy * dy;
    }
    const double D[3] = {xn * o->tx, yn * o->ty, -1.0};
    const double dc = D[0] * C[0] + D[1] * C[1] + D[2] * C[2];
    const double dd = D[0] * D[0] + D[1] * D[1] + 1.0;
    const double k = C[0] * C[0] + C[1] * C[1] + C[2] * C[2] - o->r * o->r;
    return dc * dc - dd * k;
}

/* The conic as an ellipse: fit the exact quadratic q from samples, then centre and axes. */
static void fit_ellipse(cj_sphere_oracle *o) {
    const double hs = 16.0;
    const double f = q_double(o, 0, 0);
    const double xp = q_double(o, hs, 0), xm = q_double(o, -hs, 0);
    const double yp = q_double(o, 0, hs), ym = q_double(o, 0, -hs);
    const double a = (xp + xm - 2 * f) / (2 * hs * hs), d = (xp - xm) / (2 * hs);
    const double c = (yp + ym - 2 * f) / (2 * hs * hs), e = (yp - ym) / (2 * hs);
    const double b = (q_double(o, hs, hs) - q_double(o, hs, -hs) - q_double(o, -hs, hs) +
                      q_double(o, -hs, -hs)) /
                     (4 * hs * hs);
    const double det = 4 * a * c - b * b;
    const double X0 = (-2 * c * d + b * e) / det, Y0 = (b * d - 2 * a * e) / det;
    const double f0 = f + 0.5 * (d * X0 + e * Y0);
    /* (p - c)^T M (p - c) = 1 with M = [[a, b/2], [b/2, c]] / (-f0), positive definite */
    const double ma = a / -f0, mb = 0.5 * b / -f0, mc = c / -f0;
    const double tr = ma + mc, dt = ma * mc - mb * mb;
    const double disc = sqrt(fmax(0.0, tr * tr / 4 - dt));
    const double l1 = tr / 2 + disc, l2 = tr / 2 - disc;
    double e1x = mb, e1y = l1 - ma;
    if (hypot(e1x, e1y) < hypot(l1 - mc, mb)) {
        e1x = l1 - mc;
        e1y = mb;
    }
    double n1 = hypot(e1x, e1y);
    if (n1 == 0.0) { /* a circle */
        e1x = 1;
        e1y = 0;
        n1 = 1;
    }
    o->ec[0] = X0;
    o->ec[1] = Y0;
    o->axis[0][0] = e1x / n1;
    o->axis[0][1] = e1y / n1;
    o->axis[1][0] = -e1y / n1;
    o->axis[1][1] = e1x / n1;
    o->semi[0] = 1.0 / sqrt(l1);
    o->semi[1] = 1.0 / sqrt(l2);
}

void cj_sphere_oracle_init(cj_sphere_oracle *o, const cj_camera *cam, int w, int h, cj_vec3 c,
                           double r) {
    memset(o, 0, sizeof *o);
    o->cam = *cam;
    o->w = w;
    o->h = h;
    o->r = r;
    mpfr_t t[3], u[3], v[3], wv[3], d[3], tmp, tmp2;
    mpfr_inits2(PREC, t[0], t[1], t[2], u[0], u[1], u[2], v[0], v[1], v[2], wv[0], wv[1], wv[2],
                d[0], d[1], d[2], tmp, tmp2, (mpfr_ptr)0);
    mpfr_inits2(PREC, o->mC[0], o->mC[1], o->mC[2], o->mk, o->mtx, o->mty, o->mr2, o->s[0], o->s[1],
                o->s[2], o->s[3], o->s[4], o->s[5], (mpfr_ptr)0);
    const double gd[3] = {cam->gaze.x, cam->gaze.y, cam->gaze.z};
    const double td[3] = {cam->up.x, cam->up.y, cam->up.z};
    const double ed[3] = {c.x, c.y, c.z};
    const double eye[3] = {cam->eye.x, cam->eye.y, cam->eye.z};
    for (int i = 0; i < 3; i++) {
        mpfr_set_d(wv[i], -gd[i], MPFR_RNDN);
        mpfr_set_d(t[i], td[i], MPFR_RNDN);
        mpfr_set_d(d[i], ed[i], MPFR_RNDN);
        mpfr_sub_d(d[i], d[i], eye[i], MPFR_RNDN); /* exact at 256 bits */
    }
    m_normalize(wv, tmp, tmp2); /* w = -g/|g| */
    m_cross(u, t, wv, tmp);     /* u = t x w / |t x w| */
    m_normalize(u, tmp, tmp2);
    m_cross(v, wv, u, tmp); /* v = w x u */
    m_dot(o->mC[0], d, u, tmp);
    m_dot(o->mC[1], d, v, tmp);
    m_dot(o->mC[2], d, wv, tmp);
    m_dot(o->mk, d, d, tmp);
    mpfr_set_d(o->mr2, r, MPFR_RNDN);
    mpfr_sqr(o->mr2, o->mr2, MPFR_RNDN);
    mpfr_sub(o->mk, o->mk, o->mr2, MPFR_RNDN); /* |C|^2 - r^2 */
    if (cam->projection == CJ_PROJ_ORTHOGRAPHIC) {
        mpfr_set_d(o->mty, cam->ortho_height, MPFR_RNDN);
        mpfr_div_ui(o->mty, o->mty, 2, MPFR_RNDN);
    } else {
        mpfr_set_d(o->mty, cam->fov_y, MPFR_RNDN);
        mpfr_div_ui(o->mty, o->mty, 2, MPFR_RNDN);
        mpfr_tan(o->mty, o->mty, MPFR_RNDN);
    }
    mpfr_mul_ui(o->mtx, o->mty, (unsigned long)w, MPFR_RNDN);
    mpfr_div_ui(o->mtx, o->mtx, (unsigned long)h, MPFR_RNDN);
    for (int i = 0; i < 3; i++) o->C[i] = mpfr_get_d(o->mC[i], MPFR_RNDN);
    o->tx = mpfr_get_d(o->mtx, MPFR_RNDN);
    o->ty = mpfr_get_d(o->mty, MPFR_RNDN);
    if (cam->projection == CJ_PROJ_ORTHOGRAPHIC)
        o->px_per_unit = h / cam->ortho_height;
    else
        o->px_per_unit =
            (h / 2.0) / o->ty / sqrt(o->C[0] * o->C[0] + o->C[1] * o->C[1] + o->C[2] * o->C[2]);
    fit_ellipse(o);
    mpfr_clears(t[0], t[1], t[2], u[0], u[1], u[2], v[0], v[1], v[2], wv[0], wv[1], wv[2], d[0],
                d[1], d[2], tmp, tmp2, (mpfr_ptr)0);
}

void cj_sphere_oracle_clear(cj_sphere_oracle *o) {
    mpfr_clears(o->mC[0], o->mC[1], o->mC[2], o->mk, o->mtx, o->mty, o->mr2, o->s[0], o->s[1],
                o->s[2], o->s[3], o->s[4], o->s[5], (mpfr_ptr)0);
}

int cj_sphere_inside(cj_sphere_oracle *o, int x, int y) {
    mpfr_ptr xn = o->s[0], yn = o->s[1], a = o->s[2], b = o->s[3], acc = o->s[4], dd = o->s[5];
    /* NDC of the pixel centre, (2x + 1)/w - 1: exact */
    mpfr_set_si(xn, 2 * x + 1 - o->w, MPFR_RNDN);
    mpfr_div_si(xn, xn, o->w, MPFR_RNDN);
    mpfr_set_si(yn, 2 * y + 1 - o->h, MPFR_RNDN);
    mpfr_div_si(yn, yn, o->h, MPFR_RNDN);
    mpfr_mul(xn, xn, o->mtx, MPFR_RNDN); /* camera-plane coordinates */
    mpfr_mul(yn, yn, o->mty, MPFR_RNDN);
    if (o->cam.projection == CJ_PROJ_ORTHOGRAPHIC) {
        /* inside iff (ox - Cx)^2 + (oy - Cy)^2 < r^2 */
        mpfr_sub(a, xn, o->mC[0], MPFR_RNDN);
        mpfr_sqr(a, a, MPFR_RNDN);
        mpfr_sub(b, yn, o->mC[1], MPFR_RNDN);
        mpfr_sqr(b, b, MPFR_RNDN);
        mpfr_add(a, a, b, MPFR_RNDN);
        return mpfr_cmp(a, o->mr2) < 0;
    }
    /* D = (xn, yn, -1): inside iff D.C > 0 and (D.C)^2 - |D|^2 (|C|^2 - r^2) > 0 */
    mpfr_mul(acc, xn, o->mC[0], MPFR_RNDN);
    mpfr_mul(a, yn, o->mC[1], MPFR_RNDN);
    mpfr_add(acc, acc, a, MPFR_RNDN);
    mpfr_sub(acc, acc, o->mC[2], MPFR_RNDN);
    if (mpfr_sgn(acc) <= 0) return 0;
    mpfr_sqr(acc, acc, MPFR_RNDN);
    mpfr_sqr(dd, xn, MPFR_RNDN);
    mpfr_sqr(a, yn, MPFR_RNDN);
    mpfr_add(dd, dd, a, MPFR_RNDN);
    mpfr_add_ui(dd, dd, 1, MPFR_RNDN);
    mpfr_mul(dd, dd, o->mk, MPFR_RNDN);
    return mpfr_cmp(acc, dd) > 0;
}

double cj_sphere_conic_distance(const cj_sphere_oracle *o, int x, int y) {
    const double px = x + 0.5 - o->w / 2.0 - o->ec[0], py = y + 0.5 - o->h / 2.0 - o->ec[1];
    /* point in the ellipse's frame */
    const double p = px * o->axis[0][0] + py * o->axis[0][1];
    const double q = px * o->axis[1][0] + py * o->axis[1][1];
    const double A = o->semi[0], B = o->semi[1];
    enum { N = 4096 };
    double best = INFINITY, bt = 0.0;
    for (int k = 0; k < N; k++) {
        const double th = 2.0 * M_PI * k / N;
        const double d = hypot(p - A * cos(th), q - B * sin(th));
        if (d < best) {
            best = d;
            bt = th;
        }
    }
    double lo = bt - 2.0 * M_PI / N, hi = bt + 2.0 * M_PI / N;
    for (int it = 0; it < 60; it++) { /* ternary search: the distance is unimodal here */
        const double m1 = lo + (hi - lo) / 3, m2 = hi - (hi - lo) / 3;
        const double d1 = hypot(p - A * cos(m1), q - B * sin(m1));
        const double d2 = hypot(p - A * cos(m2), q - B * sin(m2));
        if (d1 < d2)
            hi = m2;
        else
            lo = m1;
    }
    const double th = 0.5 * (lo + hi);
    return fmin(best, hypot(p - A * cos(th), q - B * sin(th)));
}

void cj_silhouette_check(cj_sphere_oracle *o, const uint32_t *ids, cj_silhouette_stats *out) {
    memset(out, 0, sizeof *out);
    for (int y = 0; y < o->h; y++)
        for (int x = 0; x < o->w; x++) {
            const int got = ids[(size_t)y * o->w + x] != 0;
            if (got == cj_sphere_inside(o, x, y)) continue;
            const double d = cj_sphere_conic_distance(o, x, y);
            out->differ++;
            out->beyond += d > 1.0;
            if (d > out->max_dist) out->max_dist = d;
        }
}

static double pseudodepth(const cj_camera *cam, double z) {
    const double f = cam->near, F = cam->far;
    if (cam->projection == CJ_PROJ_ORTHOGRAPHIC) return (f + F - 2.0 * z) / (f - F);
    const double A = (f + F) / (f - F), B = -2.0 * f * F / (f - F);
    return -A - B / z;
}

int cj_sphere_hit(const cj_sphere_oracle *o, int x, int y, double rho, double hit[3]) {
    const double xn = (2.0 * x + 1.0 - o->w) / o->w, yn = (2.0 * y + 1.0 - o->h) / o->h;
    const double *C = o->C;
    if (o->cam.projection == CJ_PROJ_ORTHOGRAPHIC) {
        const double dx = xn * o->tx - C[0], dy = yn * o->ty - C[1];
        const double s = rho * rho - dx * dx - dy * dy;
        if (s <= 0.0) return 0;
        hit[0] = xn * o->tx;
        hit[1] = yn * o->ty;
        hit[2] = C[2] + sqrt(s);
        return 1;
    }
    const double D[3] = {xn * o->tx, yn * o->ty, -1.0};
    const double dc = D[0] * C[0] + D[1] * C[1] + D[2] * C[2];
    const double dd = D[0] * D[0] + D[1] * D[1] + 1.0;
    const double k = C[0] * C[0] + C[1] * C[1] + C[2] * C[2] - rho * rho;
    const double disc = dc * dc - dd * k;
    if (disc <= 0.0 || dc <= 0.0) return 0;
    const double s = k / (dc + sqrt(disc)); /* the nearer root, without cancellation */
    for (int i = 0; i < 3; i++) hit[i] = s * D[i];
    return 1;
}

void cj_sphere_depth_check(const cj_sphere_oracle *o, double inner, const uint32_t *ids,
                           const float *depth, cj_depth_interval_stats *out) {
    memset(out, 0, sizeof *out);
    for (int y = 0; y < o->h; y++)
        for (int x = 0; x < o->w; x++) {
            const size_t i = (size_t)y * o->w + x;
            if (!ids[i]) continue;
            double hi_pt[3], hs_pt[3];
            if (!cj_sphere_hit(o, x, y, inner, hi_pt) || !cj_sphere_hit(o, x, y, o->r, hs_pt))
                continue;
            const double lo = pseudodepth(&o->cam, hs_pt[2]);
            const double hi = pseudodepth(&o->cam, hi_pt[2]);
            const double got = depth[i];
            const double excess = got < lo ? lo - got : got > hi ? got - hi : 0.0;
            out->checked++;
            out->beyond += excess > CJ_DEPTH_TOL;
            if (excess > out->max_excess) out->max_excess = excess;
            if (hi - lo > out->max_width) out->max_width = hi - lo;
        }
}

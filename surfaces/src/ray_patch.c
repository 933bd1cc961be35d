/* Rays against Bézier patches, directly: the control net in "ray coordinates" (distances to
 * two planes through the ray, distance along it), subdivided until flat, then Newton. */
#include "casteljau/ray.h"
#include "error_internal.h"

#include <math.h>
#include <string.h>

#define MAXP      ((CJ_RAY_PATCH_MAX_DEGREE + 1) * (CJ_RAY_PATCH_MAX_DEGREE + 1))
#define MAX_DEPTH 40

cj_status cj_ray_patch_check(const cj_patch *patch, double tol) {
    cj_status st = cj_patch_check(patch);
    if (st != CJ_OK) return st;
    if (patch->deg_u > CJ_RAY_PATCH_MAX_DEGREE || patch->deg_v > CJ_RAY_PATCH_MAX_DEGREE)
        return cj_fail(CJ_ERR_DEGREE,
                       "patch of degree (%d, %d): direct ray intersection takes up to %d",
                       patch->deg_u, patch->deg_v, CJ_RAY_PATCH_MAX_DEGREE);
    if (!(tol > 0.0) || !isfinite(tol))
        return cj_fail(CJ_ERR_ARGUMENT, "ray-patch tolerance %g must be finite and > 0", tol);
    return CJ_OK;
}

typedef struct net {
    double u0, u1, v0, v1;
    double p[MAXP][4]; /* homogeneous (w x1, w x2, w x3, w) */
} net;

typedef struct ctx {
    int m, n, rational;
    double tol, tmin_s, tbest_s; /* along the ray in world units (|dir| = 1) */
    int found;
    double bu, bv, berr;
    cj_ray_patch_stats *stats;
} ctx;

static void split_u(const ctx *c, const net *in, net *l, net *r) {
    int m = c->m, n = c->n;
    double mid = 0.5 * (in->u0 + in->u1);
    l->u0 = in->u0;
    l->u1 = mid;
    r->u0 = mid;
    r->u1 = in->u1;
    l->v0 = r->v0 = in->v0;
    l->v1 = r->v1 = in->v1;
    double tmp[CJ_RAY_PATCH_MAX_DEGREE + 1][4];
    for (int j = 0; j <= n; j++) {
        for (int i = 0; i <= m; i++) memcpy(tmp[i], in->p[j * (m + 1) + i], sizeof tmp[i]);
        for (int k = 0; k < 4; k++) l->p[j * (m + 1)][k] = tmp[0][k];
        for (int k = 0; k < 4; k++) r->p[j * (m + 1) + m][k] = tmp[m][k];
        for (int lev = 1; lev <= m; lev++) {
            for (int i = 0; i <= m - lev; i++)
                for (int k = 0; k < 4; k++) tmp[i][k] = 0.5 * (tmp[i][k] + tmp[i + 1][k]);
            for (int k = 0; k < 4; k++) {
                l->p[j * (m + 1) + lev][k] = tmp[0][k];
                r->p[j * (m + 1) + m - lev][k] = tmp[m - lev][k];
            }
        }
    }
}

static void split_v(const ctx *c, const net *in, net *l, net *r) {
    int m = c->m, n = c->n;
    double mid = 0.5 * (in->v0 + in->v1);
    l->v0 = in->v0;
    l->v1 = mid;
    r->v0 = mid;
    r->v1 = in->v1;
    l->u0 = r->u0 = in->u0;
    l->u1 = r->u1 = in->u1;
    double tmp[CJ_RAY_PATCH_MAX_DEGREE + 1][4];
    for (int i = 0; i <= m; i++) {
        for (int j = 0; j <= n; j++) memcpy(tmp[j], in->p[j * (m + 1) + i], sizeof tmp[j]);
        for (int k = 0; k < 4; k++) l->p[i][k] = tmp[0][k];
        for (int k = 0; k < 4; k++) r->p[n * (m + 1) + i][k] = tmp[n][k];
        for (int lev = 1; lev <= n; lev++) {
            for (int j = 0; j <= n - lev; j++)
                for (int k = 0; k < 4; k++) tmp[j][k] = 0.5 * (tmp[j][k] + tmp[j + 1][k]);
            for (int k = 0; k < 4; k++) {
                l->p[lev * (m + 1) + i][k] = tmp[0][k];
                r->p[(n - lev) * (m + 1) + i][k] = tmp[n - lev][k];
            }
        }
    }
}

/* Box of the Euclidean net; 1 if it can hold a point within tol of the ray in [tmin, tbest].
 * (Locals, not the output arrays, carry the running bounds: the compiler cannot keep aliased
 * outputs in registers.) */
static int net_box(const ctx *c, const net *s, double lo[3], double hi[3]) {
    int cnt = (c->m + 1) * (c->n + 1);
    double l0 = INFINITY, l1 = INFINITY, l2 = INFINITY, h0 = -INFINITY, h1 = -INFINITY,
           h2 = -INFINITY;
    for (int i = 0; i < cnt; i++) {
        const double *p = s->p[i];
        double x = p[0], y = p[1], z = p[2];
        if (c->rational) {
            double iw = 1.0 / p[3];
            x *= iw;
            y *= iw;
            z *= iw;
        }
        l0 = x < l0 ? x : l0;
        h0 = x > h0 ? x : h0;
        l1 = y < l1 ? y : l1;
        h1 = y > h1 ? y : h1;
        l2 = z < l2 ? z : l2;
        h2 = z > h2 ? z : h2;
    }
    lo[0] = l0;
    lo[1] = l1;
    lo[2] = l2;
    hi[0] = h0;
    hi[1] = h1;
    hi[2] = h2;
    double slack = c->tol;
    if (c->stats) c->stats->boxes++;
    return l0 <= slack && h0 >= -slack && l1 <= slack && h1 >= -slack && h2 >= c->tmin_s - slack &&
           l2 <= c->tbest_s + slack;
}

/* The net deviates from the bilinear patch of its corners by at most `lim`. */
static int net_flat(const ctx *c, const net *s, double lim) {
    int m = c->m, n = c->n;
    if (m <= 1 && n <= 1) return 1;
    double q[4][3];
    const int idx[4] = {0, m, n * (m + 1), n * (m + 1) + m};
    for (int k = 0; k < 4; k++)
        for (int d = 0; d < 3; d++)
            q[k][d] = c->rational ? s->p[idx[k]][d] / s->p[idx[k]][3] : s->p[idx[k]][d];
    for (int j = 0; j <= n; j++) {
        double b = n ? (double)j / n : 0.0;
        for (int i = 0; i <= m; i++) {
            double a = m ? (double)i / m : 0.0;
            const double *pp = s->p[j * (m + 1) + i];
            double d2 = 0.0;
            for (int d = 0; d < 3; d++) {
                double L = (1 - a) * (1 - b) * q[0][d] + a * (1 - b) * q[1][d] +
                           (1 - a) * b * q[2][d] + a * b * q[3][d];
                double e = (c->rational ? pp[d] / pp[3] : pp[d]) - L;
                d2 += e * e;
            }
            if (d2 > lim * lim) return 0;
        }
    }
    return 1;
}

/* Bernstein values and derivatives of degree n at t. */
static void bern(int n, double t, double *b, double *db) {
    double lo[CJ_RAY_PATCH_MAX_DEGREE + 1];
    /* degree n-1 basis by the triangle, then the degree n basis and its derivative. */
    for (int i = 0; i <= n; i++) b[i] = 0.0;
    b[0] = 1.0;
    for (int k = 1; k <= n; k++) {
        if (k == n)
            for (int i = 0; i < n; i++) lo[i] = b[i];
        for (int i = k; i >= 1; i--) b[i] = (1.0 - t) * b[i] + t * b[i - 1];
        b[0] = (1.0 - t) * b[0];
    }
    if (n == 0) {
        db[0] = 0.0;
        return;
    }
    for (int i = 0; i <= n; i++) {
        double left = i >= 1 ? lo[i - 1] : 0.0, right = i < n ? lo[i] : 0.0;
        db[i] = n * (left - right);
    }
}

/* x1, x2 (Euclidean) and their partials on the sub-net at local (s, t). */
static void net_eval(const ctx *c, const net *s, double a, double b, double f[2], double fu[2],
                     double fv[2]) {
    int m = c->m, n = c->n;
    double Bu[CJ_RAY_PATCH_MAX_DEGREE + 1], dBu[CJ_RAY_PATCH_MAX_DEGREE + 1];
    double Bv[CJ_RAY_PATCH_MAX_DEGREE + 1], dBv[CJ_RAY_PATCH_MAX_DEGREE + 1];
    bern(m, a, Bu, dBu);
    bern(n, b, Bv, dBv);
    double P[4] = {0}, Pu[4] = {0}, Pv[4] = {0};
    for (int j = 0; j <= n; j++)
        for (int i = 0; i <= m; i++) {
            const double *pp = s->p[j * (m + 1) + i];
            double w0 = Bu[i] * Bv[j], wu = dBu[i] * Bv[j], wv = Bu[i] * dBv[j];
            for (int k = 0; k < 4; k++) {
                if (k == 2) continue; /* x3 (along the ray) is not needed by Newton */
                P[k] += w0 * pp[k];
                Pu[k] += wu * pp[k];
                Pv[k] += wv * pp[k];
            }
        }
    for (int k = 0; k < 2; k++) {
        f[k] = P[k] / P[3];
        fu[k] = (Pu[k] - Pu[3] * f[k]) / P[3];
        fv[k] = (Pv[k] - Pv[3] * f[k]) / P[3];
    }
}

/* Newton on the sub-net from its centre; 1 with local (a, b) in [0,1]² and |F| <= tol. */
static int newton(ctx *c, const net *s, double *ua, double *vb, double *res) {
    double a = 0.5, b = 0.5, f[2], fu[2], fv[2];
    double best = INFINITY;
    if (c->stats) c->stats->newton++;
    /* Run to full precision (until |F| stops shrinking): the root's t then decides reliably
     * whether it lies before tmin (the surface a secondary ray leaves) or after it. F is
     * evaluated at the returned point once more only if the loop ended after a step. */
    double r = INFINITY;
    int fresh = 0;
    for (int it = 0; it < 24; it++) {
        net_eval(c, s, a, b, f, fu, fv);
        fresh = 1;
        r = sqrt(f[0] * f[0] + f[1] * f[1]);
        if (r == 0.0) break;
        if (!(r < best * 0.999) && it > 3) break;
        if (r < best) best = r;
        double det = fu[0] * fv[1] - fu[1] * fv[0];
        if (det == 0.0 || !isfinite(det)) break;
        double da = (f[0] * fv[1] - f[1] * fv[0]) / det;
        double db = (fu[0] * f[1] - fu[1] * f[0]) / det;
        a -= da;
        b -= db;
        fresh = 0;
        if (!(a > -0.5 && a < 1.5 && b > -0.5 && b < 1.5)) return 0;
    }
    if (!fresh) {
        net_eval(c, s, a, b, f, fu, fv);
        r = sqrt(f[0] * f[0] + f[1] * f[1]);
    }
    const double eps = 1e-9;
    if (!(r <= c->tol) || a < -eps || a > 1 + eps || b < -eps || b > 1 + eps) return 0;
    *ua = fmin(1.0, fmax(0.0, a));
    *vb = fmin(1.0, fmax(0.0, b));
    *res = r;
    if (c->stats) c->stats->newton_ok++;
    return 1;
}

static double net_x3(const ctx *c, const net *s, double a, double b) {
    int m = c->m, n = c->n;
    double Bu[CJ_RAY_PATCH_MAX_DEGREE + 1], dBu[CJ_RAY_PATCH_MAX_DEGREE + 1];
    double Bv[CJ_RAY_PATCH_MAX_DEGREE + 1], dBv[CJ_RAY_PATCH_MAX_DEGREE + 1];
    bern(m, a, Bu, dBu);
    bern(n, b, Bv, dBv);
    double x = 0.0, w = 0.0;
    for (int j = 0; j <= n; j++)
        for (int i = 0; i <= m; i++) {
            x += Bu[i] * Bv[j] * s->p[j * (m + 1) + i][2];
            w += Bu[i] * Bv[j] * s->p[j * (m + 1) + i][3];
        }
    return x / w;
}

/* s's box (lo, hi) was computed and found to meet the ray by the caller. */
static void visit(ctx *c, const net *s, const double lo[3], const double hi[3], int depth) {
    double diag = sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                       (hi[2] - lo[2]) * (hi[2] - lo[2]));
    if (diag <= c->tol || depth >= MAX_DEPTH) {
        /* Within diag of the ray everywhere when the ray passes through the box (no slack):
         * the centre is a hit to tolerance. A candidate closer to the origin than its own
         * uncertainty is the surface the ray starts on, not a hit. */
        if (lo[0] > 0.0 || hi[0] < 0.0 || lo[1] > 0.0 || hi[1] < 0.0) return;
        double t = net_x3(c, s, 0.5, 0.5);
        if (t >= c->tmin_s + diag && t <= c->tbest_s) {
            c->found = 1;
            c->tbest_s = t;
            c->bu = 0.5 * (s->u0 + s->u1);
            c->bv = 0.5 * (s->v0 + s->v1);
            c->berr = diag;
        }
        return;
    }
    if (net_flat(c, s, diag / 8.0)) {
        double a, b, r;
        if (newton(c, s, &a, &b, &r)) {
            double t = net_x3(c, s, a, b);
            if (t >= c->tmin_s + r && t <= c->tbest_s) {
                c->found = 1;
                c->tbest_s = t;
                c->bu = s->u0 + a * (s->u1 - s->u0);
                c->bv = s->v0 + b * (s->v1 - s->v0);
                c->berr = r;
            }
            return;
        }
    }
    /* Split along the longer side of the net (corner to corner), nearer half first. */
    int m = c->m, n = c->n;
    double lu = 0.0, lv = 0.0;
    for (int k = 0; k < 3; k++) {
        double du = s->p[m][k] / s->p[m][3] - s->p[0][k] / s->p[0][3];
        double dv = s->p[n * (m + 1)][k] / s->p[n * (m + 1)][3] - s->p[0][k] / s->p[0][3];
        lu += du * du;
        lv += dv * dv;
    }
    net kids[2];
    if ((lu >= lv && m > 0) || n == 0)
        split_u(c, s, &kids[0], &kids[1]);
    else
        split_v(c, s, &kids[0], &kids[1]);
    double lo0[3], hi0[3], lo1[3], hi1[3];
    int h0 = net_box(c, &kids[0], lo0, hi0), h1 = net_box(c, &kids[1], lo1, hi1);
    if (h0 && h1 && lo1[2] < lo0[2]) {
        visit(c, &kids[1], lo1, hi1, depth + 1);
        if (lo0[2] <= c->tbest_s + c->tol) visit(c, &kids[0], lo0, hi0, depth + 1);
    } else {
        if (h0) visit(c, &kids[0], lo0, hi0, depth + 1);
        if (h1 && lo1[2] <= c->tbest_s + c->tol) visit(c, &kids[1], lo1, hi1, depth + 1);
    }
}

int cj_ray_patch(const cj_ray *ray, const cj_patch *patch, double tol, cj_hit *hit,
                 cj_ray_patch_stats *stats) {
    int m = patch->deg_u, n = patch->deg_v;
    if (m < 0 || n < 0 || m > CJ_RAY_PATCH_MAX_DEGREE || n > CJ_RAY_PATCH_MAX_DEGREE) return 0;
    if (!(tol > 0.0)) return 0;
    double len = cj_v3_norm(ray->dir);
    if (!(len > 0.0) || !isfinite(len)) return 0;
    cj_vec3 dn = cj_v3_scale(ray->dir, 1.0 / len);
    /* Two unit normals completing dn to an orthonormal frame. */
    cj_vec3 n1, n2;
    cj_frame_from_axis(dn, &n1, &n2);
    ctx c;
    c.m = m;
    c.n = n;
    c.rational = patch->weights != NULL;
    c.tol = tol;
    c.tmin_s = ray->tmin * len;
    c.tbest_s = ray->tmax * len;
    c.found = 0;
    c.stats = stats;
    net root;
    root.u0 = root.v0 = 0.0;
    root.u1 = root.v1 = 1.0;
    size_t cnt = cj_patch_point_count(patch);
    double mag[3] = {0, 0, 0};
    for (size_t i = 0; i < cnt; i++) {
        cj_vec3 b = cj_v3(patch->pts[3 * i], patch->pts[3 * i + 1], patch->pts[3 * i + 2]);
        mag[0] = fmax(mag[0], fabs(b.x));
        mag[1] = fmax(mag[1], fabs(b.y));
        mag[2] = fmax(mag[2], fabs(b.z));
        cj_vec3 w = cj_v3_sub(b, ray->org);
        double wt = patch->weights ? patch->weights[i] : 1.0;
        root.p[i][0] = wt * cj_v3_dot(n1, w);
        root.p[i][1] = wt * cj_v3_dot(n2, w);
        root.p[i][2] = wt * cj_v3_dot(dn, w);
        root.p[i][3] = wt;
    }
    double rlo[3], rhi[3];
    if (net_box(&c, &root, rlo, rhi)) visit(&c, &root, rlo, rhi, 0);
    if (!c.found) return 0;
    double S[3], nrm[3];
    if (cj_patch_eval(patch, CJ_EVAL_DECASTELJAU, c.bu, c.bv, S) != CJ_OK) return 0;
    cj_vec3 p = cj_v3(S[0], S[1], S[2]);
    cj_vec3 n3;
    if (cj_patch_normal(patch, c.bu, c.bv, nrm, NULL) == CJ_OK)
        n3 = cj_v3(nrm[0], nrm[1], nrm[2]);
    else
        n3 = cj_v3_normalize(cj_v3_scale(ray->dir, -1.0));
    cj_vec3 w = cj_v3_sub(p, ray->org);
    double along = cj_v3_dot(w, dn);
    cj_vec3 perp = cj_v3_sub(w, cj_v3_scale(dn, along));
    double g = cj_gamma(3 * (m + n) + 8);
    if (patch->weights) g *= 2.0;
    double t = along / len;
    if (!(t >= ray->tmin && t <= ray->tmax)) return 0;
    hit->t = t;
    hit->p = p;
    hit->p_err = cj_v3(g * mag[0], g * mag[1], g * mag[2]);
    hit->n = n3;
    hit->ng = n3;
    hit->u = c.bu;
    hit->v = c.bv;
    hit->err = fmax(cj_v3_norm(perp), 0.0);
    if (stats && hit->err > stats->max_err) stats->max_err = hit->err;
    return 1;
}

int cj_ray_bilinear(const cj_ray *ray, const cj_bilinear *bl, double tol, cj_hit *hit) {
    const double pts[12] = {bl->p00.x, bl->p00.y, bl->p00.z, bl->p10.x, bl->p10.y, bl->p10.z,
                            bl->p01.x, bl->p01.y, bl->p01.z, bl->p11.x, bl->p11.y, bl->p11.z};
    cj_patch p = cj_patch_view(1, 1, pts, NULL);
    return cj_ray_patch(ray, &p, tol, hit, NULL);
}

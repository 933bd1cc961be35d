/* Rays against quadrics: sphere, the six canonical quadrics, the right circular cylinder,
 * and the planar patch. Every quadric is written as the diagonal form
 *     f(x) = α x² + β y² + γ z² + λ z + κ
 * in its own frame and solved by one robust quadratic solver (see ray.h). */
#include "casteljau/ray.h"

#include <math.h>

static const double two_pi = 6.283185307179586476925286766559;

typedef struct diag_quadric {
    double al, be, ga, la, ka;
} diag_quadric;

static inline double fval(const diag_quadric *q, cj_vec3 p) {
    return (q->al * p.x * p.x + q->be * p.y * p.y) + (q->ga * p.z * p.z + (q->la * p.z + q->ka));
}

static inline double fmag(const diag_quadric *q, cj_vec3 p) {
    return fabs(q->al) * p.x * p.x + fabs(q->be) * p.y * p.y + fabs(q->ga) * p.z * p.z +
           fabs(q->la * p.z) + fabs(q->ka);
}

static inline cj_vec3 fgrad(const diag_quadric *q, cj_vec3 p) {
    return cj_v3(2.0 * q->al * p.x, 2.0 * q->be * p.y, 2.0 * q->ga * p.z + q->la);
}

/* Half the linear coefficient of f(o + t d): α ox dx + β oy dy + γ oz dz + λ dz / 2. */
static inline double half_b(const diag_quadric *q, cj_vec3 o, cj_vec3 d) {
    return q->al * o.x * d.x + q->be * o.y * d.y + q->ga * o.z * d.z + 0.5 * q->la * d.z;
}

typedef int (*domain_fn)(const void *ctx, cj_vec3 p);

/* Distance bound from the computed point p to the surface f = 0 (first order, doubled). */
static double surface_dist_bound(const diag_quadric *q, cj_vec3 p) {
    double g = cj_v3_norm(fgrad(q, p));
    double e = fabs(fval(q, p)) + cj_gamma(8) * fmag(q, p);
    if (!(g > 0.0)) return sqrt(e) + cj_gamma(4) * (fabs(p.x) + fabs(p.y) + fabs(p.z));
    return 2.0 * e / g;
}

/* The smallest t in [tmin, tmax] with f(o + t d) = 0 and dom(p); p in the local frame. */
static int solve_diag(const diag_quadric *q, cj_vec3 o, cj_vec3 d, double tmin, double tmax,
                      domain_fn dom, const void *ctx, double *t_out, cj_vec3 *p_out) {
    double A = q->al * d.x * d.x + q->be * d.y * d.y + q->ga * d.z * d.z;
    double Amag = fabs(q->al) * d.x * d.x + fabs(q->be) * d.y * d.y + fabs(q->ga) * d.z * d.z;
    double t0 = 0.0;
    /* Move the origin to where the quadratic is extremal: b' vanishes there and c = f(o') is
     * computed at a point of the scale of the surface, so b'² − ac does not cancel. */
    if (fabs(A) > 1e-8 * Amag) {
        t0 = -half_b(q, o, d) / A;
        if (!isfinite(t0)) t0 = 0.0;
    }
    cj_vec3 os = cj_v3_add(o, cj_v3_scale(d, t0));
    double B = half_b(q, os, d), C = fval(q, os);
    double disc = B * B - A * C;
    if (!(disc >= 0.0)) return 0;
    double sq = sqrt(disc);
    double qq = -(B + copysign(sq, B));
    double r[2];
    int nr = 0;
    if (A != 0.0) r[nr++] = qq / A;
    if (qq != 0.0)
        r[nr++] = C / qq;
    else if (A == 0.0)
        return 0;
    if (nr == 2 && r[1] < r[0]) {
        double s = r[0];
        r[0] = r[1];
        r[1] = s;
    }
    double gap = nr == 2 ? r[1] - r[0] : INFINITY;
    for (int i = 0; i < nr; i++) {
        double t = t0 + r[i];
        if (!isfinite(t)) continue;
        /* One Newton step on f(o + t d), kept well inside half the gap to the other root. */
        cj_vec3 p = cj_v3_add(o, cj_v3_scale(d, t));
        double F = fval(q, p), dF = 2.0 * half_b(q, p, d);
        if (dF != 0.0) {
            double step = F / dF;
            if (fabs(step) < 0.25 * gap) {
                t -= step;
                p = cj_v3_add(o, cj_v3_scale(d, t));
            }
        }
        if (!(t >= tmin && t <= tmax)) continue;
        if (dom && !dom(ctx, p)) continue;
        *t_out = t;
        *p_out = p;
        return 1;
    }
    return 0;
}

static double angle(double y, double x) {
    double u = atan2(y, x);
    return u < 0.0 ? u + two_pi : u;
}

/* ---- sphere ------------------------------------------------------------------------------- */

int cj_ray_sphere(const cj_ray *ray, cj_vec3 center, double radius, cj_hit *hit) {
    diag_quadric q = {1.0, 1.0, 1.0, 0.0, -radius * radius};
    cj_vec3 o = cj_v3_sub(ray->org, center);
    double t;
    cj_vec3 pl;
    if (!solve_diag(&q, o, ray->dir, ray->tmin, ray->tmax, NULL, NULL, &t, &pl)) return 0;
    /* Reproject onto the sphere (PBRT): the point is then within γ(5)|p| of it. */
    double len = cj_v3_norm(pl);
    if (len > 0.0) pl = cj_v3_scale(pl, radius / len);
    cj_vec3 p = cj_v3_add(center, pl);
    /* Reprojection leaves the point within γ(5)|p_l| <= γ(5) r of the sphere (in any
     * direction, so each coordinate gets the whole bound), plus the rounding of c + p_l. */
    double e5 = cj_gamma(5) * radius;
    hit->p_err = cj_v3(e5 + cj_gamma(1) * fabs(p.x), e5 + cj_gamma(1) * fabs(p.y),
                       e5 + cj_gamma(1) * fabs(p.z));
    cj_vec3 n = cj_v3_scale(pl, 1.0 / radius);
    hit->t = t;
    hit->p = p;
    hit->n = n;
    hit->ng = n;
    hit->u = angle(pl.y, pl.x);
    hit->v = asin(fmax(-1.0, fmin(1.0, pl.z / radius)));
    hit->err = 0.0;
    return 1;
}

/* ---- the canonical quadrics ------------------------------------------------------------------ */

static diag_quadric quadric_form(const cj_quadric *q) {
    double ia = 1.0 / (q->a * q->a), ib = 1.0 / (q->b * q->b), ic = 1.0 / (q->c * q->c);
    diag_quadric d = {ia, ib, ic, 0.0, -1.0};
    switch (q->kind) {
    case CJ_QUADRIC_ELLIPSOID:
        break;
    case CJ_QUADRIC_HYPERBOLOID1:
        d.ga = -ic;
        break;
    case CJ_QUADRIC_HYPERBOLOID2:
        d.ga = -ic;
        d.ka = 1.0;
        break;
    case CJ_QUADRIC_CONE:
        d.ga = -ic;
        d.ka = 0.0;
        break;
    case CJ_QUADRIC_PARABOLOID:
        d.ga = 0.0;
        d.la = -1.0;
        d.ka = 0.0;
        break;
    case CJ_QUADRIC_HYPERBOLIC_PARABOLOID:
        d.al = -ia;
        d.ga = 0.0;
        d.la = 1.0;
        d.ka = 0.0;
        break;
    }
    return d;
}

static int quadric_domain(const void *ctx, cj_vec3 p) {
    const cj_quadric *q = (const cj_quadric *)ctx;
    switch (q->kind) {
    case CJ_QUADRIC_ELLIPSOID:
        return 1;
    case CJ_QUADRIC_HYPERBOLOID1:
        return p.z >= q->c * sinh(q->v0) && p.z <= q->c * sinh(q->v1);
    case CJ_QUADRIC_HYPERBOLOID2:
        if (q->lower) return p.z < 0.0 && -p.z <= q->c * cosh(q->v1);
        return p.z > 0.0 && p.z <= q->c * cosh(q->v1);
    case CJ_QUADRIC_CONE:
        return p.z >= q->c * q->v0 && p.z <= q->c * q->v1;
    case CJ_QUADRIC_PARABOLOID:
        return p.z <= q->v1 * q->v1;
    case CJ_QUADRIC_HYPERBOLIC_PARABOLOID:
        return p.x >= q->a * q->u0 && p.x <= q->a * q->u1 && p.y >= q->b * q->v0 &&
               p.y <= q->b * q->v1;
    }
    return 0;
}

static void quadric_uv(const cj_quadric *q, cj_vec3 p, double *u, double *v) {
    double x = p.x / q->a, y = p.y / q->b, z = p.z / q->c;
    switch (q->kind) {
    case CJ_QUADRIC_ELLIPSOID:
        *u = angle(y, x);
        *v = asin(fmax(-1.0, fmin(1.0, z)));
        return;
    case CJ_QUADRIC_HYPERBOLOID1:
        *u = angle(y, x);
        *v = asinh(z);
        return;
    case CJ_QUADRIC_HYPERBOLOID2:
        if (q->lower) {
            *u = angle(-y, x);
            *v = acosh(fmax(1.0, -z));
        } else {
            *u = angle(y, x);
            *v = acosh(fmax(1.0, z));
        }
        return;
    case CJ_QUADRIC_CONE:
        *v = z;
        *u = z >= 0.0 ? angle(y, x) : angle(-y, -x);
        return;
    case CJ_QUADRIC_PARABOLOID:
        *u = angle(y, x);
        *v = sqrt(fmax(0.0, p.z));
        return;
    case CJ_QUADRIC_HYPERBOLIC_PARABOLOID:
        *u = x;
        *v = y;
        return;
    }
}

int cj_ray_quadric(const cj_ray *ray, const cj_quadric *q, cj_hit *hit) {
    diag_quadric f = quadric_form(q);
    double t;
    cj_vec3 p;
    if (!solve_diag(&f, ray->org, ray->dir, ray->tmin, ray->tmax, quadric_domain, q, &t, &p))
        return 0;
    double e = surface_dist_bound(&f, p);
    hit->p_err = cj_v3(e, e, e);
    cj_vec3 g = fgrad(&f, p);
    cj_vec3 n =
        cj_v3_norm(g) > 0.0 ? cj_v3_normalize(g) : cj_v3_normalize(cj_v3_scale(ray->dir, -1.0));
    hit->t = t;
    hit->p = p;
    hit->n = n;
    hit->ng = n;
    quadric_uv(q, p, &hit->u, &hit->v);
    hit->err = 0.0;
    return 1;
}

/* ---- right circular cylinder ----------------------------------------------------------------- */

typedef struct cyl_ctx {
    double h0, h1;
} cyl_ctx;

static int cyl_domain(const void *ctx, cj_vec3 p) {
    const cyl_ctx *c = (const cyl_ctx *)ctx;
    return p.z >= c->h0 && p.z <= c->h1;
}

static cj_vec3 to_frame(cj_vec3 w, cj_vec3 e1, cj_vec3 e2, cj_vec3 a) {
    return cj_v3(cj_v3_dot(w, e1), cj_v3_dot(w, e2), cj_v3_dot(w, a));
}

int cj_ray_cylinder(const cj_ray *ray, const cj_cylinder *cy, cj_hit *hit) {
    diag_quadric f = {1.0, 1.0, 0.0, 0.0, -cy->radius * cy->radius};
    cj_vec3 w = cj_v3_sub(ray->org, cy->base);
    cj_vec3 o = to_frame(w, cy->e1, cy->e2, cy->a);
    cj_vec3 d = to_frame(ray->dir, cy->e1, cy->e2, cy->a);
    cyl_ctx c = {cy->h0, cy->h1};
    double t;
    cj_vec3 pl;
    if (!solve_diag(&f, o, d, ray->tmin, ray->tmax, cyl_domain, &c, &t, &pl)) return 0;
    cj_vec3 p = cj_v3_add(ray->org, cj_v3_scale(ray->dir, t));
    /* The local point's distance bound is a distance (frame-independent); add the rounding
     * between the local and the world evaluation of the same t. */
    double e =
        surface_dist_bound(&f, pl) +
        cj_gamma(8) * (cj_v3_norm(w) + fabs(t) * cj_v3_norm(ray->dir) + cj_v3_norm(cy->base));
    hit->p_err = cj_v3(e, e, e);
    double rr = hypot(pl.x, pl.y);
    cj_vec3 n = rr > 0.0 ? cj_v3_add(cj_v3_scale(cy->e1, pl.x / rr), cj_v3_scale(cy->e2, pl.y / rr))
                         : cj_v3_normalize(cj_v3_scale(ray->dir, -1.0));
    hit->t = t;
    hit->p = p;
    hit->n = n;
    hit->ng = n;
    hit->u = angle(pl.y, pl.x);
    hit->v = pl.z;
    hit->err = 0.0;
    return 1;
}

/* ---- planar patch -------------------------------------------------------------------------- */

int cj_ray_planar(const cj_ray *ray, const cj_planar_patch *pp, cj_hit *hit) {
    cj_vec3 n = pp->plane.n;
    double dn = cj_v3_dot(n, ray->dir);
    if (dn == 0.0) return 0;
    double t = (pp->plane.d - cj_v3_dot(n, ray->org)) / dn;
    if (!(t >= ray->tmin && t <= ray->tmax)) return 0;
    cj_vec3 p = cj_v3_add(ray->org, cj_v3_scale(ray->dir, t));
    cj_vec3 w = cj_v3_sub(p, pp->p);
    cj_vec3 N = cj_v3_cross(pp->eu, pp->ev);
    double nn = cj_v3_dot(N, N);
    double u = cj_v3_dot(cj_v3_cross(w, pp->ev), N) / nn;
    double v = cj_v3_dot(cj_v3_cross(pp->eu, w), N) / nn;
    if (!(u >= 0.0 && u <= 1.0 && v >= 0.0 && v <= 1.0)) return 0;
    double dist = fabs(cj_v3_dot(n, p) - pp->plane.d);
    double e = 2.0 * dist + cj_gamma(6) * (fabs(n.x * p.x) + fabs(n.y * p.y) + fabs(n.z * p.z) +
                                           fabs(pp->plane.d));
    hit->p_err = cj_v3(e, e, e);
    hit->t = t;
    hit->p = p;
    hit->n = n;
    hit->ng = n;
    hit->u = u;
    hit->v = v;
    hit->err = 0.0;
    return 1;
}

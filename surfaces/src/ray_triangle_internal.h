/* Private: the watertight ray-triangle test (Woop, Benthin, Wald 2013) split into the test and
 * the hit record, inline for the BVH walk (bvh.c) and the public entry points
 * (ray_triangle.c), which run this one body. */
#ifndef CASTELJAU_RAY_TRIANGLE_INTERNAL_H
#define CASTELJAU_RAY_TRIANGLE_INTERNAL_H

#include "casteljau/ray.h"

#include <math.h>

/* The per-ray set-up of the watertight test (cj_ray_triangle_prepare), inline for the BVH walk:
 * z' is the direction's largest coordinate, the (x', y', z') frame kept right-handed so that
 * triangles keep their winding; the shear takes the direction to +z'. */
static inline void cj_tri_prepare(const cj_ray *ray, cj_ray_tri_pre *pre) {
    const double d[3] = {ray->dir.x, ray->dir.y, ray->dir.z};
    const double ax = fabs(d[0]), ay = fabs(d[1]), az = fabs(d[2]);
    const int kz = (ax > ay) ? (ax > az ? 0 : 2) : (ay > az ? 1 : 2);
    int kx = (kz + 1) % 3, ky = (kx + 1) % 3;
    if (d[kz] < 0.0) {
        const int tmp = kx;
        kx = ky;
        ky = tmp;
    }
    const double dz = d[kz];
    pre->kx = kx;
    pre->ky = ky;
    pre->kz = kz;
    pre->sx = d[kx] / dz;
    pre->sy = d[ky] / dz;
    pre->sz = 1.0 / dz;
}

/* px*qy − py*qx with the exact sign: the plain product difference when it exceeds its rounding
 * bound, else Kahan's fma form (w = py*qx, e = w − py*qx exactly, f = px*qy − w rounded once:
 * f + e has relative error <= 2u, so its sign is exact, and it is exactly 0 when px qy = py qx). */
static inline double cj_tri_edge_fn(double px, double py, double qx, double qy) {
    double a = px * qy, b = py * qx;
    double e = a - b;
    if (fabs(e) > 3.3306690738754716e-16 * (fabs(a) + fabs(b))) return e;
    double w = py * qx;
    double err = fma(-py, qx, w);
    double f = fma(px, qy, -w);
    return f + err;
}

/* Tie-break for an edge function that is exactly zero: the edge p -> q of a triangle taken
 * counter-clockwise (`flip` reverses it) owns the origin when the origin moved by (ε, −ε²)
 * falls inside, i.e. when dy < 0, or dy == 0 and dx < 0. The same edge in the neighbouring
 * triangle runs the other way, so exactly one of the two owns it. */
static inline int cj_tri_owns_zero(double px, double py, double qx, double qy, int flip) {
    double dx = qx - px, dy = qy - py;
    if (flip) {
        dx = -dx;
        dy = -dy;
    }
    return dy < 0.0 || (dy == 0.0 && dx < 0.0);
}

/* The test without the hit record: 1 when the ray meets the triangle v (its three vertices, 9
 * doubles, x y z each) at t in [tmin, tmax], with the (scaled) barycentric edge values e[3] and
 * their sum *det for cj_tri_fill. Inline, so the BVH walk can test a leaf's triangles straight
 * from its vertex array and fill the record once, for the closest. */
static inline int cj_tri_core_v(const cj_ray *ray, const cj_ray_tri_pre *pre, const double *v,
                                double *tout, double e[3], double *dout) {
    const int kx = pre->kx, ky = pre->ky, kz = pre->kz;
    const double o[3] = {ray->org.x, ray->org.y, ray->org.z};
    double a[3] = {v[kx] - o[kx], v[ky] - o[ky], v[kz] - o[kz]};
    double b[3] = {v[3 + kx] - o[kx], v[3 + ky] - o[ky], v[3 + kz] - o[kz]};
    double c[3] = {v[6 + kx] - o[kx], v[6 + ky] - o[ky], v[6 + kz] - o[kz]};
    double ax = a[0] - pre->sx * a[2], ay = a[1] - pre->sy * a[2];
    double bx = b[0] - pre->sx * b[2], by = b[1] - pre->sy * b[2];
    double cx = c[0] - pre->sx * c[2], cy = c[1] - pre->sy * c[2];
    /* e0 = orient(v1, v2, O), e1 = orient(v2, v0, O), e2 = orient(v0, v1, O). */
    double e0 = cj_tri_edge_fn(bx, by, cx, cy);
    double e1 = cj_tri_edge_fn(cx, cy, ax, ay);
    double e2 = cj_tri_edge_fn(ax, ay, bx, by);
    int pos = e0 > 0.0 || e1 > 0.0 || e2 > 0.0;
    int neg = e0 < 0.0 || e1 < 0.0 || e2 < 0.0;
    if (pos && neg) return 0;
    if (!pos && !neg) return 0; /* all zero: the triangle is seen edge-on */
    int flip = neg;             /* clockwise in the ray's view: reverse every edge */
    if (e0 == 0.0 && !cj_tri_owns_zero(bx, by, cx, cy, flip)) return 0;
    if (e1 == 0.0 && !cj_tri_owns_zero(cx, cy, ax, ay, flip)) return 0;
    if (e2 == 0.0 && !cj_tri_owns_zero(ax, ay, bx, by, flip)) return 0;
    double det = e0 + e1 + e2;
    if (det == 0.0) return 0;
    double az = pre->sz * a[2], bz = pre->sz * b[2], cz = pre->sz * c[2];
    double tsc = e0 * az + e1 * bz + e2 * cz;
    double t = tsc / det;
    if (!(t >= ray->tmin && t <= ray->tmax)) return 0;
    *tout = t;
    e[0] = e0, e[1] = e1, e[2] = e2;
    *dout = det;
    return 1;
}

/* The same test on three vertices. */
static inline int cj_tri_core(const cj_ray *ray, const cj_ray_tri_pre *pre, cj_vec3 v0, cj_vec3 v1,
                              cj_vec3 v2, double *tout, double e[3], double *dout) {
    const double v[9] = {v0.x, v0.y, v0.z, v1.x, v1.y, v1.z, v2.x, v2.y, v2.z};
    return cj_tri_core_v(ray, pre, v, tout, e, dout);
}

/* The hit record of a triangle the core test met: point, its rounding bound, normal,
 * barycentrics. */
static inline void cj_tri_fill(cj_vec3 v0, cj_vec3 v1, cj_vec3 v2, double t, const double e[3],
                               double det, cj_hit *hit) {
    const double e0 = e[0], e1 = e[1], e2 = e[2];
    double inv = 1.0 / det;
    double b0 = e0 * inv, b1 = e1 * inv, b2 = e2 * inv;
    cj_vec3 p = cj_v3(b0 * v0.x + b1 * v1.x + b2 * v2.x, b0 * v0.y + b1 * v1.y + b2 * v2.y,
                      b0 * v0.z + b1 * v1.z + b2 * v2.z);
    double g7 = cj_gamma(7);
    hit->p_err = cj_v3(g7 * (fabs(b0 * v0.x) + fabs(b1 * v1.x) + fabs(b2 * v2.x)),
                       g7 * (fabs(b0 * v0.y) + fabs(b1 * v1.y) + fabs(b2 * v2.y)),
                       g7 * (fabs(b0 * v0.z) + fabs(b1 * v1.z) + fabs(b2 * v2.z)));
    cj_vec3 ng = cj_v3_normalize(cj_v3_cross(cj_v3_sub(v1, v0), cj_v3_sub(v2, v0)));
    hit->t = t;
    hit->p = p;
    hit->n = ng;
    hit->ng = ng;
    hit->u = b1;
    hit->v = b2;
    hit->err = 0.0;
}

#endif

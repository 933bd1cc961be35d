/* Rays: validation, offsetting secondary origins, boxes, placed objects. */
#include "casteljau/ray.h"
#include "aabb_internal.h"
#include "error_internal.h"

#include <math.h>

cj_status cj_ray_check(const cj_ray *ray) {
    const double v[6] = {ray->org.x, ray->org.y, ray->org.z, ray->dir.x, ray->dir.y, ray->dir.z};
    for (int k = 0; k < 6; k++)
        if (!isfinite(v[k]))
            return cj_fail(CJ_ERR_NONFINITE, "ray %s coordinate %d is not finite",
                           k < 3 ? "origin" : "direction", k % 3);
    if (v[3] == 0.0 && v[4] == 0.0 && v[5] == 0.0)
        return cj_fail(CJ_ERR_DEGENERATE, "ray direction is zero");
    if (isnan(ray->tmin) || isnan(ray->tmax))
        return cj_fail(CJ_ERR_NONFINITE, "ray tmin/tmax is NaN");
    if (!(ray->tmin <= ray->tmax))
        return cj_fail(CJ_ERR_RANGE, "ray tmin %g > tmax %g", ray->tmin, ray->tmax);
    return CJ_OK;
}

cj_vec3 cj_ray_offset_origin(const cj_hit *hit, cj_vec3 w) {
    cj_vec3 n = hit->ng;
    double d = fabs(n.x) * hit->p_err.x + fabs(n.y) * hit->p_err.y + fabs(n.z) * hit->p_err.z;
    /* At least a few ulps of the point's largest coordinate, so a point computed exactly on a
     * surface through a zero coordinate does not leave it by a subnormal only; rounded up a
     * little so the offset's own rounding cannot shrink it. */
    double pm = fmax(fabs(hit->p.x), fmax(fabs(hit->p.y), fabs(hit->p.z)));
    if (d < 4.0 * cj_gamma(1) * pm) d = 4.0 * cj_gamma(1) * pm;
    d *= 1.0 + 4.0 * cj_gamma(1);
    double sg = cj_v3_dot(w, n) < 0.0 ? -1.0 : 1.0;
    cj_vec3 po = cj_v3_add(hit->p, cj_v3_scale(n, sg * d));
    /* One more ulp along each normal component (also when d == 0: a point computed exactly on
     * the surface must still leave it). */
    double sx = sg * n.x, sy = sg * n.y, sz = sg * n.z;
    if (sx != 0.0) po.x = nextafter(po.x, sx > 0.0 ? INFINITY : -INFINITY);
    if (sy != 0.0) po.y = nextafter(po.y, sy > 0.0 ? INFINITY : -INFINITY);
    if (sz != 0.0) po.z = nextafter(po.z, sz > 0.0 ? INFINITY : -INFINITY);
    return po;
}

/* ---- boxes ---------------------------------------------------------------------------- */

cj_aabb cj_aabb_empty(void) {
    cj_aabb b = {{INFINITY, INFINITY, INFINITY}, {-INFINITY, -INFINITY, -INFINITY}};
    return b;
}

void cj_aabb_grow(cj_aabb *b, cj_vec3 p) {
    const double c[3] = {p.x, p.y, p.z};
    for (int k = 0; k < 3; k++) {
        if (c[k] < b->lo[k]) b->lo[k] = c[k];
        if (c[k] > b->hi[k]) b->hi[k] = c[k];
    }
}

void cj_aabb_merge(cj_aabb *b, const cj_aabb *c) {
    for (int k = 0; k < 3; k++) {
        if (c->lo[k] < b->lo[k]) b->lo[k] = c->lo[k];
        if (c->hi[k] > b->hi[k]) b->hi[k] = c->hi[k];
    }
}

double cj_aabb_area(const cj_aabb *b) {
    double dx = b->hi[0] - b->lo[0], dy = b->hi[1] - b->lo[1], dz = b->hi[2] - b->lo[2];
    if (!(dx >= 0.0) || !(dy >= 0.0) || !(dz >= 0.0)) return 0.0;
    return 2.0 * (dx * dy + dy * dz + dz * dx);
}

int cj_aabb_ray(const cj_aabb *b, cj_vec3 org, cj_vec3 inv_dir, double tmin, double tmax,
                double *t0, double *t1) {
    const double o[3] = {org.x, org.y, org.z}, id[3] = {inv_dir.x, inv_dir.y, inv_dir.z};
    return cj_aabb_slab(b, o, id, tmin, tmax, t0, t1);
}

cj_aabb cj_aabb_triangle(cj_vec3 v0, cj_vec3 v1, cj_vec3 v2) {
    cj_aabb b = cj_aabb_empty();
    cj_aabb_grow(&b, v0);
    cj_aabb_grow(&b, v1);
    cj_aabb_grow(&b, v2);
    return b;
}

static cj_aabb box6(double x0, double x1, double y0, double y1, double z0, double z1) {
    cj_aabb b = {{x0, y0, z0}, {x1, y1, z1}};
    /* A relative margin covers the rounding of the hyperbolic functions above. */
    for (int k = 0; k < 3; k++) {
        double m = 1e-12 * (fabs(b.lo[k]) + fabs(b.hi[k])) + 1e-300;
        b.lo[k] -= m;
        b.hi[k] += m;
    }
    return b;
}

cj_aabb cj_aabb_quadric(const cj_quadric *q) {
    double a = q->a, b = q->b, c = q->c;
    double vm = fmax(fabs(q->v0), fabs(q->v1));
    switch (q->kind) {
    case CJ_QUADRIC_ELLIPSOID:
        return box6(-a, a, -b, b, -c, c);
    case CJ_QUADRIC_HYPERBOLOID1: {
        double r = cosh(vm);
        return box6(-a * r, a * r, -b * r, b * r, c * sinh(q->v0), c * sinh(q->v1));
    }
    case CJ_QUADRIC_HYPERBOLOID2: {
        double r = sinh(q->v1), h = c * cosh(q->v1);
        if (q->lower) return box6(-a * r, a * r, -b * r, b * r, -h, -c);
        return box6(-a * r, a * r, -b * r, b * r, c, h);
    }
    case CJ_QUADRIC_CONE:
        return box6(-a * vm, a * vm, -b * vm, b * vm, c * q->v0, c * q->v1);
    case CJ_QUADRIC_PARABOLOID:
        return box6(-a * q->v1, a * q->v1, -b * q->v1, b * q->v1, 0.0, q->v1 * q->v1);
    case CJ_QUADRIC_HYPERBOLIC_PARABOLOID: {
        double umax = fmax(q->u0 * q->u0, q->u1 * q->u1);
        double umin = (q->u0 <= 0.0 && q->u1 >= 0.0) ? 0.0 : fmin(q->u0 * q->u0, q->u1 * q->u1);
        double vmax = fmax(q->v0 * q->v0, q->v1 * q->v1);
        double vmin = (q->v0 <= 0.0 && q->v1 >= 0.0) ? 0.0 : fmin(q->v0 * q->v0, q->v1 * q->v1);
        return box6(a * q->u0, a * q->u1, b * q->v0, b * q->v1, umin - vmax, umax - vmin);
    }
    }
    return cj_aabb_empty();
}

cj_aabb cj_aabb_torus(const cj_torus *to) {
    /* Exact extent along each world axis: R |a_perp,k| + rho, with |a_perp,k| = sqrt(1 - a_k²). */
    const double a[3] = {to->a.x, to->a.y, to->a.z},
                 c[3] = {to->center.x, to->center.y, to->center.z};
    cj_aabb b;
    for (int k = 0; k < 3; k++) {
        double e = to->major * sqrt(fmax(0.0, 1.0 - a[k] * a[k])) + to->minor;
        e += 1e-12 * (fabs(c[k]) + e);
        b.lo[k] = c[k] - e;
        b.hi[k] = c[k] + e;
    }
    return b;
}

cj_aabb cj_aabb_cylinder(const cj_cylinder *cy) {
    const double a[3] = {cy->a.x, cy->a.y, cy->a.z};
    cj_vec3 p0 = cj_v3_add(cy->base, cj_v3_scale(cy->a, cy->h0));
    cj_vec3 p1 = cj_v3_add(cy->base, cj_v3_scale(cy->a, cy->h1));
    cj_aabb b = cj_aabb_triangle(p0, p1, p1);
    for (int k = 0; k < 3; k++) {
        double e = cy->radius * sqrt(fmax(0.0, 1.0 - a[k] * a[k]));
        e += 1e-12 * (fabs(b.lo[k]) + fabs(b.hi[k]) + e);
        b.lo[k] -= e;
        b.hi[k] += e;
    }
    return b;
}

cj_aabb cj_aabb_patch(const cj_patch *p) {
    cj_aabb b = cj_aabb_empty();
    size_t n = cj_patch_point_count(p);
    for (size_t i = 0; i < n; i++)
        cj_aabb_grow(&b, cj_v3(p->pts[3 * i], p->pts[3 * i + 1], p->pts[3 * i + 2]));
    return b;
}

/* ---- placed objects --------------------------------------------------------------------- */

cj_status cj_ray_xform_init(cj_ray_xform *x, const cj_xform3 *m) {
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++)
            if (!isfinite(m->m[i][j]))
                return cj_fail(CJ_ERR_NONFINITE, "object transform entry (%d, %d) is not finite", i,
                               j);
    if (!cj_xform3_is_affine(m))
        return cj_fail(CJ_ERR_UNSUPPORTED, "object transform is projective (last row not 0 0 0 1)");
    cj_xform3 inv;
    cj_status st = cj_xform3_inverse(m, &inv);
    if (st != CJ_OK) return st;
    x->m = *m;
    x->minv = inv;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) x->nrm[i][j] = inv.m[j][i];
    return CJ_OK;
}

static cj_vec3 lin(const double m[4][4], cj_vec3 v) {
    return cj_v3(m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z,
                 m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
                 m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z);
}

void cj_ray_to_object(const cj_ray_xform *x, const cj_ray *ray, cj_ray *out) {
    cj_vec3 o = lin(x->minv.m, ray->org);
    out->org = cj_v3(o.x + x->minv.m[0][3], o.y + x->minv.m[1][3], o.z + x->minv.m[2][3]);
    out->dir = lin(x->minv.m, ray->dir);
    out->tmin = ray->tmin;
    out->tmax = ray->tmax;
}

void cj_hit_to_world(const cj_ray_xform *x, cj_hit *hit) {
    const double(*m)[4] = x->m.m;
    cj_vec3 p = hit->p, e = hit->p_err;
    cj_vec3 q = lin(m, p);
    q = cj_v3(q.x + m[0][3], q.y + m[1][3], q.z + m[2][3]);
    double g = cj_gamma(3);
    double pe[3];
    const double pc[3] = {p.x, p.y, p.z}, ec[3] = {e.x, e.y, e.z};
    for (int i = 0; i < 3; i++) {
        double s = 0.0, r = fabs(m[i][3]);
        for (int j = 0; j < 3; j++) {
            s += fabs(m[i][j]) * ec[j];
            r += fabs(m[i][j] * pc[j]);
        }
        pe[i] = (1.0 + g) * s + g * r;
    }
    hit->p_err = cj_v3(pe[0], pe[1], pe[2]);
    hit->p = q;
    cj_vec3 n = hit->n, ng = hit->ng;
    hit->n = cj_v3_normalize(cj_v3(x->nrm[0][0] * n.x + x->nrm[0][1] * n.y + x->nrm[0][2] * n.z,
                                   x->nrm[1][0] * n.x + x->nrm[1][1] * n.y + x->nrm[1][2] * n.z,
                                   x->nrm[2][0] * n.x + x->nrm[2][1] * n.y + x->nrm[2][2] * n.z));
    hit->ng =
        cj_v3_normalize(cj_v3(x->nrm[0][0] * ng.x + x->nrm[0][1] * ng.y + x->nrm[0][2] * ng.z,
                              x->nrm[1][0] * ng.x + x->nrm[1][1] * ng.y + x->nrm[1][2] * ng.z,
                              x->nrm[2][0] * ng.x + x->nrm[2][1] * ng.y + x->nrm[2][2] * ng.z));
}

cj_aabb cj_aabb_transform(const cj_ray_xform *x, const cj_aabb *b) {
    cj_aabb r = cj_aabb_empty();
    if (!(b->lo[0] <= b->hi[0])) return r;
    for (int c = 0; c < 8; c++) {
        cj_vec3 p = cj_v3((c & 1) ? b->hi[0] : b->lo[0], (c & 2) ? b->hi[1] : b->lo[1],
                          (c & 4) ? b->hi[2] : b->lo[2]);
        cj_vec3 q = lin(x->m.m, p);
        cj_aabb_grow(&r, cj_v3(q.x + x->m.m[0][3], q.y + x->m.m[1][3], q.z + x->m.m[2][3]));
    }
    for (int k = 0; k < 3; k++) {
        double m = 4.0 * cj_gamma(3) * (fabs(r.lo[k]) + fabs(r.hi[k]));
        r.lo[k] -= m;
        r.hi[k] += m;
    }
    return r;
}

/* Taper and twist deformations (see deform.h). */
#include "casteljau/deform.h"
#include "error_internal.h"

#include <assert.h>
#include <math.h>

static cj_status setup_axis(cj_deform *d, const char *what, cj_vec3 origin, cj_vec3 axis) {
    if (!cj_v3_finite(origin))
        return cj_fail(CJ_ERR_NONFINITE, "%s: axis origin (%g, %g, %g) is not finite", what,
                       origin.x, origin.y, origin.z);
    if (!cj_v3_finite(axis))
        return cj_fail(CJ_ERR_NONFINITE, "%s: axis direction (%g, %g, %g) is not finite", what,
                       axis.x, axis.y, axis.z);
    /* Pre-scale by the largest component so that huge or tiny finite vectors normalise. */
    double big = fmax(fabs(axis.x), fmax(fabs(axis.y), fabs(axis.z)));
    if (big > 0.0) axis = cj_v3(axis.x / big, axis.y / big, axis.z / big);
    double len = cj_v3_norm(axis);
    if (!(len > 0.0) || !isfinite(len))
        return cj_fail(CJ_ERR_DEGENERATE, "%s: axis direction has zero length", what);
    d->origin = origin;
    d->a = cj_v3_scale(axis, 1.0 / len);
    cj_frame_from_axis(d->a, &d->e1, &d->e2);
    return CJ_OK;
}

cj_status cj_deform_taper(cj_deform *d, cj_vec3 origin, cj_vec3 axis, double k0, double k1,
                          double k2) {
    assert(d);
    const double k[3] = {k0, k1, k2};
    cj_status st = cj_check_finite(k, 3, "taper: coefficient k");
    if (st != CJ_OK) return st;
    if (k0 == 0.0 && k1 == 0.0 && k2 == 0.0)
        return cj_fail(CJ_ERR_DEGENERATE, "taper: r(s) = k0 + k1 s + k2 s^2 is identically zero");
    cj_deform t;
    st = setup_axis(&t, "taper", origin, axis);
    if (st != CJ_OK) return st;
    t.kind = CJ_DEFORM_TAPER;
    t.k0 = k0;
    t.k1 = k1;
    t.k2 = k2;
    t.rate = 0.0;
    *d = t;
    return CJ_OK;
}

cj_status cj_deform_twist(cj_deform *d, cj_vec3 origin, cj_vec3 axis, double rate) {
    assert(d);
    if (!isfinite(rate))
        return cj_fail(CJ_ERR_NONFINITE, "twist: rate is %s", isnan(rate) ? "NaN" : "infinite");
    cj_deform t;
    cj_status st = setup_axis(&t, "twist", origin, axis);
    if (st != CJ_OK) return st;
    t.kind = CJ_DEFORM_TWIST;
    t.k0 = 1.0;
    t.k1 = t.k2 = 0.0;
    t.rate = rate;
    *d = t;
    return CJ_OK;
}

static const char *kind_name(const cj_deform *d) {
    return d->kind == CJ_DEFORM_TAPER ? "taper" : "twist";
}

/* World -> local frame coordinates and back. */
static cj_vec3 to_local(const cj_deform *d, cj_vec3 w) {
    return cj_v3(cj_v3_dot(w, d->e1), cj_v3_dot(w, d->e2), cj_v3_dot(w, d->a));
}
static cj_vec3 to_world(const cj_deform *d, cj_vec3 l) {
    return cj_v3_add(cj_v3_add(cj_v3_scale(d->e1, l.x), cj_v3_scale(d->e2, l.y)),
                     cj_v3_scale(d->a, l.z));
}

/* Local Jacobian at local point q. */
static void local_jacobian(const cj_deform *d, cj_vec3 q, double J[3][3]) {
    double s = q.z;
    if (d->kind == CJ_DEFORM_TAPER) {
        double r = d->k0 + s * (d->k1 + s * d->k2), dr = d->k1 + 2.0 * d->k2 * s;
        double M[3][3] = {{r, 0, dr * q.x}, {0, r, dr * q.y}, {0, 0, 1}};
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) J[i][j] = M[i][j];
    } else {
        double t = d->rate * s, c = cos(t), sn = sin(t), k = d->rate;
        double M[3][3] = {
            {c, -sn, -k * (q.x * sn + q.y * c)}, {sn, c, k * (q.x * c - q.y * sn)}, {0, 0, 1}};
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) J[i][j] = M[i][j];
    }
}

static cj_vec3 mat_vec(double J[3][3], cj_vec3 v) {
    return cj_v3(J[0][0] * v.x + J[0][1] * v.y + J[0][2] * v.z,
                 J[1][0] * v.x + J[1][1] * v.y + J[1][2] * v.z,
                 J[2][0] * v.x + J[2][1] * v.y + J[2][2] * v.z);
}

static cj_status check_point(const cj_deform *d, cj_vec3 p, const char *what) {
    if (!cj_v3_finite(p))
        return cj_fail(CJ_ERR_NONFINITE, "%s: %s (%g, %g, %g) is not finite", kind_name(d), what,
                       p.x, p.y, p.z);
    return CJ_OK;
}

static cj_status check_result(const cj_deform *d, cj_vec3 p, const char *what) {
    if (!cj_v3_finite(p))
        return cj_fail(CJ_ERR_NONFINITE, "%s: deformed %s overflowed", kind_name(d), what);
    return CJ_OK;
}

/* Unchecked point map. */
static cj_vec3 deform_point(const cj_deform *d, cj_vec3 p) {
    cj_vec3 q = to_local(d, cj_v3_sub(p, d->origin));
    double s = q.z;
    cj_vec3 r;
    if (d->kind == CJ_DEFORM_TAPER) {
        double k = d->k0 + s * (d->k1 + s * d->k2);
        r = cj_v3(k * q.x, k * q.y, s);
    } else {
        double t = d->rate * s, c = cos(t), sn = sin(t);
        r = cj_v3(q.x * c - q.y * sn, q.x * sn + q.y * c, s);
    }
    return cj_v3_add(d->origin, to_world(d, r));
}

/* Unnormalised cof(J(p)) n; CJ_ERR_DEGENERATE if it vanishes. */
static cj_status deform_normal(const cj_deform *d, cj_vec3 p, cj_vec3 n, cj_vec3 *out) {
    cj_vec3 q = to_local(d, cj_v3_sub(p, d->origin));
    cj_vec3 m = to_local(d, n);
    double s = q.z;
    cj_vec3 r;
    if (d->kind == CJ_DEFORM_TAPER) {
        double k = d->k0 + s * (d->k1 + s * d->k2), dk = d->k1 + 2.0 * d->k2 * s;
        r = cj_v3_scale(cj_v3(m.x, m.y, k * m.z - dk * (q.x * m.x + q.y * m.y)), k);
    } else {
        double t = d->rate * s, c = cos(t), sn = sin(t);
        r = cj_v3(m.x * c - m.y * sn, m.x * sn + m.y * c, m.z - d->rate * (q.x * m.y - q.y * m.x));
    }
    cj_vec3 w = to_world(d, r);
    double len = cj_v3_norm(w);
    if (!isfinite(len))
        return cj_fail(CJ_ERR_NONFINITE, "%s: deformed normal overflowed", kind_name(d));
    if (!(len > 0.0))
        return cj_fail(CJ_ERR_DEGENERATE,
                       "%s: normal undefined at (%g, %g, %g): the deformation collapses the "
                       "cross-section there (r(s) = 0) or the normal is zero",
                       kind_name(d), p.x, p.y, p.z);
    *out = cj_v3_scale(w, 1.0 / len);
    return CJ_OK;
}

cj_status cj_deform_point(const cj_deform *d, cj_vec3 p, cj_vec3 *out) {
    assert(d && out);
    cj_status st = check_point(d, p, "point");
    if (st != CJ_OK) return st;
    cj_vec3 r = deform_point(d, p);
    st = check_result(d, r, "point");
    if (st != CJ_OK) return st;
    *out = r;
    return CJ_OK;
}

cj_status cj_deform_jacobian(const cj_deform *d, cj_vec3 p, double J[3][3]) {
    assert(d && J);
    cj_status st = check_point(d, p, "point");
    if (st != CJ_OK) return st;
    double L[3][3];
    local_jacobian(d, to_local(d, cj_v3_sub(p, d->origin)), L);
    /* J = F L F^T with F = [e1 e2 a] (columns): F[i][k] = component i of frame vector k. */
    const cj_vec3 fv[3] = {d->e1, d->e2, d->a};
    double F[3][3];
    for (int k = 0; k < 3; ++k) {
        F[0][k] = fv[k].x;
        F[1][k] = fv[k].y;
        F[2][k] = fv[k].z;
    }
    double out[3][3];
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) {
            double acc = 0.0;
            for (int k = 0; k < 3; ++k)
                for (int l = 0; l < 3; ++l) acc += F[i][k] * L[k][l] * F[j][l];
            if (!isfinite(acc))
                return cj_fail(CJ_ERR_NONFINITE, "%s: Jacobian overflowed", kind_name(d));
            out[i][j] = acc;
        }
    }
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) J[i][j] = out[i][j];
    return CJ_OK;
}

/* Unchecked tangent map J t. */
static cj_vec3 deform_tangent(const cj_deform *d, cj_vec3 p, cj_vec3 t) {
    double L[3][3];
    local_jacobian(d, to_local(d, cj_v3_sub(p, d->origin)), L);
    return to_world(d, mat_vec(L, to_local(d, t)));
}

cj_status cj_deform_tangent(const cj_deform *d, cj_vec3 p, cj_vec3 t, cj_vec3 *out) {
    assert(d && out);
    cj_status st = check_point(d, p, "point");
    if (st == CJ_OK) st = check_point(d, t, "tangent");
    if (st != CJ_OK) return st;
    cj_vec3 r = deform_tangent(d, p, t);
    st = check_result(d, r, "tangent");
    if (st != CJ_OK) return st;
    *out = r;
    return CJ_OK;
}

cj_status cj_deform_normal(const cj_deform *d, cj_vec3 p, cj_vec3 n, cj_vec3 *out) {
    assert(d && out);
    cj_status st = check_point(d, p, "point");
    if (st == CJ_OK) st = check_point(d, n, "normal");
    if (st != CJ_OK) return st;
    if (!(cj_v3_norm(n) > 0.0))
        return cj_fail(CJ_ERR_DEGENERATE, "%s: the normal to transform is zero", kind_name(d));
    return deform_normal(d, p, n, out);
}

cj_status cj_deform_vertices(const cj_deform *d, double *pos, double *nrm, size_t count) {
    assert(d && (pos || count == 0));
    /* Pass 1: validate and make sure every result is defined; nothing is written. */
    for (size_t i = 0; i < count; ++i) {
        cj_vec3 p = cj_v3(pos[3 * i], pos[3 * i + 1], pos[3 * i + 2]);
        if (!cj_v3_finite(p))
            return cj_fail(CJ_ERR_NONFINITE, "%s: vertex %zu position is not finite", kind_name(d),
                           i);
        if (!cj_v3_finite(deform_point(d, p)))
            return cj_fail(CJ_ERR_NONFINITE, "%s: vertex %zu overflowed", kind_name(d), i);
        if (nrm) {
            cj_vec3 n = cj_v3(nrm[3 * i], nrm[3 * i + 1], nrm[3 * i + 2]), m;
            if (!cj_v3_finite(n))
                return cj_fail(CJ_ERR_NONFINITE, "%s: vertex %zu normal is not finite",
                               kind_name(d), i);
            if (!(cj_v3_norm(n) > 0.0)) continue; /* unknown normal: stays zero */
            if (deform_normal(d, p, n, &m) != CJ_OK)
                return cj_fail(CJ_ERR_DEGENERATE,
                               "%s: vertex %zu: normal undefined after deformation (r(s) = 0 "
                               "collapses its cross-section)",
                               kind_name(d), i);
        }
    }
    /* Pass 2: write. */
    for (size_t i = 0; i < count; ++i) {
        cj_vec3 p = cj_v3(pos[3 * i], pos[3 * i + 1], pos[3 * i + 2]);
        if (nrm) {
            cj_vec3 n = cj_v3(nrm[3 * i], nrm[3 * i + 1], nrm[3 * i + 2]), m = n;
            cj_status st = cj_v3_norm(n) > 0.0 ? deform_normal(d, p, n, &m) : CJ_OK;
            assert(st == CJ_OK);
            (void)st;
            nrm[3 * i] = m.x;
            nrm[3 * i + 1] = m.y;
            nrm[3 * i + 2] = m.z;
        }
        cj_vec3 r = deform_point(d, p);
        pos[3 * i] = r.x;
        pos[3 * i + 1] = r.y;
        pos[3 * i + 2] = r.z;
    }
    return CJ_OK;
}

cj_status cj_deform_mesh(const cj_deform *d, cj_mesh *mesh) {
    assert(d && mesh);
    return cj_deform_vertices(d, mesh->positions, mesh->normals, mesh->vertex_count);
}

/* ---- deformed parametric surface ------------------------------------------------------ */

static cj_status deformed_cb(const void *data, double u, double v, cj_vec3 *p, cj_vec3 *su,
                             cj_vec3 *sv) {
    const cj_deformed_surface *ds = data;
    cj_vec3 P, Su, Sv;
    cj_status st = cj_surface_eval(&ds->base, u, v, &P, &Su, &Sv);
    if (st != CJ_OK) return st;
    *p = deform_point(&ds->def, P);
    *su = deform_tangent(&ds->def, P, Su);
    *sv = deform_tangent(&ds->def, P, Sv);
    return CJ_OK;
}

static cj_status deformed_normal_cb(const void *data, double u, double v, cj_vec3 *n) {
    const cj_deformed_surface *ds = data;
    cj_vec3 P, nb;
    cj_status st = cj_surface_eval(&ds->base, u, v, &P, NULL, NULL);
    if (st == CJ_OK) st = cj_surface_normal(&ds->base, u, v, &nb);
    if (st != CJ_OK) return st;
    return deform_normal(&ds->def, P, nb, n);
}

cj_status cj_deform_surface(const cj_deform *d, const cj_param_surface *base,
                            cj_deformed_surface *storage, cj_param_surface *out) {
    assert(d && base && storage && out);
    cj_status st = cj_param_surface_check(base);
    if (st != CJ_OK) return st;
    storage->def = *d;
    storage->base = *base;
    cj_param_surface s = {deformed_cb,
                          deformed_normal_cb,
                          storage,
                          base->u0,
                          base->u1,
                          base->v0,
                          base->v1,
                          base->flags,
                          d->kind == CJ_DEFORM_TAPER ? "tapered surface" : "twisted surface"};
    *out = s;
    return CJ_OK;
}

/* Affine placement of parametric and implicit surfaces (see surface.h). */
#include "casteljau/surface.h"
#include "error_internal.h"

#include <assert.h>
#include <math.h>

static cj_vec3 lin(const double m[3][4], cj_vec3 v) {
    return cj_v3(m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z,
                 m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
                 m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z);
}

static cj_vec3 aff(const double m[3][4], cj_vec3 v) {
    cj_vec3 r = lin(m, v);
    return cj_v3(r.x + m[0][3], r.y + m[1][3], r.z + m[2][3]);
}

static cj_vec3 mat3(const double c[3][3], cj_vec3 v) {
    return cj_v3(c[0][0] * v.x + c[0][1] * v.y + c[0][2] * v.z,
                 c[1][0] * v.x + c[1][1] * v.y + c[1][2] * v.z,
                 c[2][0] * v.x + c[2][1] * v.y + c[2][2] * v.z);
}

/* Validates m and fills the matrices of st. */
static cj_status setup(const cj_xform3 *m, cj_transformed_surface *st) {
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j)
            if (!isfinite(m->m[i][j]))
                return cj_fail(CJ_ERR_NONFINITE, "surface transform: matrix entry (%d,%d) is %s", i,
                               j, isnan(m->m[i][j]) ? "NaN" : "infinite");
    if (!cj_xform3_is_affine(m))
        return cj_fail(CJ_ERR_UNSUPPORTED, "surface transform: matrix is projective (last row "
                                           "is not 0 0 0 1); only affine maps are supported");
    cj_xform3 inv;
    cj_status s = cj_xform3_inverse(m, &inv);
    if (s != CJ_OK) return s;
    double C[3][3];
    /* cof(L)[i][j] = cofactor of L at (i,j) = det(L) (L^-T)[i][j]. */
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            int i1 = (i + 1) % 3, i2 = (i + 2) % 3, j1 = (j + 1) % 3, j2 = (j + 2) % 3;
            C[i][j] = m->m[i1][j1] * m->m[i2][j2] - m->m[i1][j2] * m->m[i2][j1];
        }
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 4; ++j) {
            st->m[i][j] = m->m[i][j];
            st->minv[i][j] = inv.m[i][j];
        }
        for (int j = 0; j < 3; ++j) st->cof[i][j] = C[i][j];
    }
    return CJ_OK;
}

static cj_status xf_eval(const void *data, double u, double v, cj_vec3 *p, cj_vec3 *su,
                         cj_vec3 *sv) {
    const cj_transformed_surface *t = data;
    cj_vec3 P, Su, Sv;
    cj_status st = cj_surface_eval(&t->base, u, v, &P, &Su, &Sv);
    if (st != CJ_OK) return st;
    *p = aff(t->m, P);
    *su = lin(t->m, Su);
    *sv = lin(t->m, Sv);
    return CJ_OK;
}

static cj_status xf_normal(const void *data, double u, double v, cj_vec3 *n) {
    const cj_transformed_surface *t = data;
    cj_vec3 nb;
    cj_status st = cj_surface_normal(&t->base, u, v, &nb);
    if (st != CJ_OK) return st;
    cj_vec3 r = mat3(t->cof, nb);
    double len = cj_v3_norm(r);
    if (!(len > 0.0) || !isfinite(len))
        return cj_fail(CJ_ERR_DEGENERATE, "transformed surface: normal undefined at (%g, %g)", u,
                       v);
    *n = cj_v3_scale(r, 1.0 / len);
    return CJ_OK;
}

cj_status cj_surface_transform(const cj_xform3 *m, const cj_param_surface *base,
                               cj_transformed_surface *storage, cj_param_surface *out) {
    assert(m && base && storage && out);
    cj_status st = cj_param_surface_check(base);
    if (st != CJ_OK) return st;
    cj_transformed_surface t;
    st = setup(m, &t);
    if (st != CJ_OK) return st;
    t.base = *base;
    t.ibase.eval = NULL;
    t.ibase.data = NULL;
    t.ibase.name = NULL;
    *storage = t;
    cj_param_surface s = {xf_eval,  xf_normal,   storage,
                          base->u0, base->u1,    base->v0,
                          base->v1, base->flags, base->name ? base->name : "transformed surface"};
    *out = s;
    return CJ_OK;
}

static cj_status xf_implicit(const void *data, cj_vec3 x, double *f, cj_vec3 *grad) {
    const cj_transformed_surface *t = data;
    cj_vec3 g;
    cj_status st = cj_implicit_eval(&t->ibase, aff(t->minv, x), f, &g);
    if (st != CJ_OK) return st;
    /* L^-T g: the transpose of the linear block of minv. */
    const double(*mi)[4] = t->minv;
    *grad = cj_v3(mi[0][0] * g.x + mi[1][0] * g.y + mi[2][0] * g.z,
                  mi[0][1] * g.x + mi[1][1] * g.y + mi[2][1] * g.z,
                  mi[0][2] * g.x + mi[1][2] * g.y + mi[2][2] * g.z);
    return CJ_OK;
}

cj_status cj_implicit_transform(const cj_xform3 *m, const cj_implicit_surface *base,
                                cj_transformed_surface *storage, cj_implicit_surface *out) {
    assert(m && base && storage && out);
    if (!base->eval)
        return cj_fail(CJ_ERR_ARGUMENT, "implicit transform: base has no evaluation callback");
    cj_transformed_surface t;
    cj_status st = setup(m, &t);
    if (st != CJ_OK) return st;
    t.ibase = *base;
    t.base.eval = NULL;
    t.base.normal = NULL;
    t.base.data = NULL;
    t.base.u0 = t.base.u1 = t.base.v0 = t.base.v1 = 0.0;
    t.base.flags = 0;
    t.base.name = NULL;
    *storage = t;
    out->eval = xf_implicit;
    out->data = storage;
    out->name = base->name ? base->name : "transformed implicit surface";
    return CJ_OK;
}

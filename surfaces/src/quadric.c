/* Quadrics in canonical position: implicit and parametric forms (see quadric.h). */
#include "casteljau/quadric.h"
#include "error_internal.h"

#include <assert.h>
#include <math.h>

static const double two_pi = 6.283185307179586476925286766559;
static const double half_pi = 1.5707963267948966192313216916398;

static const char *const kind_names[] = {
    "ellipsoid",     "hyperboloid of one sheet", "hyperboloid of two sheets",
    "elliptic cone", "elliptic paraboloid",      "hyperbolic paraboloid"};

static cj_status check_axis(const char *kind, const char *name, double v) {
    if (!isfinite(v))
        return cj_fail(CJ_ERR_NONFINITE, "%s: semi-axis %s is %s", kind, name,
                       isnan(v) ? "NaN" : "infinite");
    if (!(v > 0.0))
        return cj_fail(CJ_ERR_DEGENERATE, "%s: semi-axis %s = %g must be > 0", kind, name, v);
    return CJ_OK;
}

static cj_status check_range(const char *kind, const char *name, double lo, double hi) {
    if (!isfinite(lo) || !isfinite(hi))
        return cj_fail(CJ_ERR_NONFINITE, "%s: %s range bound is NaN or infinite", kind, name);
    if (!(lo < hi))
        return cj_fail(CJ_ERR_ARGUMENT, "%s: empty %s range [%g, %g]", kind, name, lo, hi);
    return CJ_OK;
}

static cj_status init(cj_quadric *q, cj_quadric_kind kind, double a, double b, double c,
                      int need_c) {
    assert(q);
    const char *k = kind_names[kind];
    cj_status st = check_axis(k, "a", a);
    if (st == CJ_OK) st = check_axis(k, "b", b);
    if (st == CJ_OK && need_c) st = check_axis(k, "c", c);
    if (st != CJ_OK) return st;
    q->kind = kind;
    q->a = a;
    q->b = b;
    q->c = need_c ? c : 1.0;
    q->u0 = 0.0;
    q->u1 = two_pi;
    q->v0 = 0.0;
    q->v1 = 1.0;
    q->lower = 0;
    return CJ_OK;
}

cj_status cj_quadric_ellipsoid(cj_quadric *q, double a, double b, double c) {
    cj_quadric t;
    cj_status st = init(&t, CJ_QUADRIC_ELLIPSOID, a, b, c, 1);
    if (st != CJ_OK) return st;
    t.v0 = -half_pi;
    t.v1 = half_pi;
    *q = t;
    return CJ_OK;
}

cj_status cj_quadric_hyperboloid1(cj_quadric *q, double a, double b, double c, double v0,
                                  double v1) {
    cj_quadric t;
    cj_status st = init(&t, CJ_QUADRIC_HYPERBOLOID1, a, b, c, 1);
    if (st == CJ_OK) st = check_range(kind_names[t.kind], "v", v0, v1);
    if (st != CJ_OK) return st;
    /* cosh overflows beyond ~710; keep the surface finite. */
    if (fabs(v0) > 700 || fabs(v1) > 700)
        return cj_fail(CJ_ERR_RANGE,
                       "hyperboloid of one sheet: |v| must be <= 700 (cosh overflow)");
    t.v0 = v0;
    t.v1 = v1;
    *q = t;
    return CJ_OK;
}

cj_status cj_quadric_hyperboloid2(cj_quadric *q, double a, double b, double c, int lower,
                                  double v1) {
    cj_quadric t;
    cj_status st = init(&t, CJ_QUADRIC_HYPERBOLOID2, a, b, c, 1);
    if (st == CJ_OK) st = check_range(kind_names[t.kind], "v", 0.0, v1);
    if (st != CJ_OK) return st;
    if (lower != 0 && lower != 1)
        return cj_fail(CJ_ERR_ARGUMENT,
                       "hyperboloid of two sheets: sheet %d, must be 0 (upper) "
                       "or 1 (lower)",
                       lower);
    if (v1 > 700)
        return cj_fail(CJ_ERR_RANGE,
                       "hyperboloid of two sheets: v1 must be <= 700 (cosh overflow)");
    t.v1 = v1;
    t.lower = lower;
    *q = t;
    return CJ_OK;
}

cj_status cj_quadric_cone(cj_quadric *q, double a, double b, double c, double v0, double v1) {
    cj_quadric t;
    cj_status st = init(&t, CJ_QUADRIC_CONE, a, b, c, 1);
    if (st == CJ_OK) st = check_range(kind_names[t.kind], "v", v0, v1);
    if (st != CJ_OK) return st;
    t.v0 = v0;
    t.v1 = v1;
    *q = t;
    return CJ_OK;
}

cj_status cj_quadric_paraboloid(cj_quadric *q, double a, double b, double v1) {
    cj_quadric t;
    cj_status st = init(&t, CJ_QUADRIC_PARABOLOID, a, b, 0.0, 0);
    if (st == CJ_OK) st = check_range(kind_names[t.kind], "v", 0.0, v1);
    if (st != CJ_OK) return st;
    t.v1 = v1;
    *q = t;
    return CJ_OK;
}

cj_status cj_quadric_hyperbolic_paraboloid(cj_quadric *q, double a, double b, double u0, double u1,
                                           double v0, double v1) {
    cj_quadric t;
    cj_status st = init(&t, CJ_QUADRIC_HYPERBOLIC_PARABOLOID, a, b, 0.0, 0);
    if (st == CJ_OK) st = check_range(kind_names[t.kind], "u", u0, u1);
    if (st == CJ_OK) st = check_range(kind_names[t.kind], "v", v0, v1);
    if (st != CJ_OK) return st;
    t.u0 = u0;
    t.u1 = u1;
    t.v0 = v0;
    t.v1 = v1;
    *q = t;
    return CJ_OK;
}

/* ---- implicit form ------------------------------------------------------------------ */

static cj_status implicit_cb(const void *data, cj_vec3 x, double *f, cj_vec3 *grad) {
    const cj_quadric *q = data;
    double ia2 = 1.0 / (q->a * q->a), ib2 = 1.0 / (q->b * q->b), ic2 = 1.0 / (q->c * q->c);
    double X = x.x * x.x * ia2, Y = x.y * x.y * ib2, Z = x.z * x.z * ic2;
    switch (q->kind) {
    case CJ_QUADRIC_ELLIPSOID:
        *f = X + Y + Z - 1.0;
        *grad = cj_v3(2 * x.x * ia2, 2 * x.y * ib2, 2 * x.z * ic2);
        break;
    case CJ_QUADRIC_HYPERBOLOID1:
    case CJ_QUADRIC_HYPERBOLOID2:
    case CJ_QUADRIC_CONE:
        *f = X + Y - Z +
             (q->kind == CJ_QUADRIC_HYPERBOLOID1   ? -1.0
              : q->kind == CJ_QUADRIC_HYPERBOLOID2 ? 1.0
                                                   : 0.0);
        *grad = cj_v3(2 * x.x * ia2, 2 * x.y * ib2, -2 * x.z * ic2);
        break;
    case CJ_QUADRIC_PARABOLOID:
        *f = X + Y - x.z;
        *grad = cj_v3(2 * x.x * ia2, 2 * x.y * ib2, -1.0);
        break;
    case CJ_QUADRIC_HYPERBOLIC_PARABOLOID:
        *f = x.z - X + Y;
        *grad = cj_v3(-2 * x.x * ia2, 2 * x.y * ib2, 1.0);
        break;
    }
    return CJ_OK;
}

cj_status cj_quadric_implicit_eval(const cj_quadric *q, cj_vec3 x, double *f, cj_vec3 *grad) {
    assert(q && f);
    cj_implicit_surface s;
    cj_quadric_implicit(q, &s);
    return cj_implicit_eval(&s, x, f, grad);
}

void cj_quadric_implicit(const cj_quadric *q, cj_implicit_surface *out) {
    assert(q && out);
    out->eval = implicit_cb;
    out->data = q;
    out->name = kind_names[q->kind];
}

/* ---- parametric form ---------------------------------------------------------------- */

static cj_status param_cb(const void *data, double u, double v, cj_vec3 *p, cj_vec3 *su,
                          cj_vec3 *sv) {
    const cj_quadric *q = data;
    double a = q->a, b = q->b, c = q->c;
    double cu = cos(u), sn = sin(u);
    switch (q->kind) {
    case CJ_QUADRIC_ELLIPSOID: {
        double cv = cos(v), sv_ = sin(v);
        *p = cj_v3(a * cv * cu, b * cv * sn, c * sv_);
        *su = cj_v3(-a * cv * sn, b * cv * cu, 0.0);
        *sv = cj_v3(-a * sv_ * cu, -b * sv_ * sn, c * cv);
        break;
    }
    case CJ_QUADRIC_HYPERBOLOID1: {
        double ch = cosh(v), sh = sinh(v);
        *p = cj_v3(a * ch * cu, b * ch * sn, c * sh);
        *su = cj_v3(-a * ch * sn, b * ch * cu, 0.0);
        *sv = cj_v3(a * sh * cu, b * sh * sn, c * ch);
        break;
    }
    case CJ_QUADRIC_HYPERBOLOID2: {
        double ch = cosh(v), sh = sinh(v);
        double s = q->lower ? -1.0 : 1.0; /* lower sheet: rotate by pi about x */
        *p = cj_v3(a * sh * cu, s * b * sh * sn, s * c * ch);
        *su = cj_v3(-a * sh * sn, s * b * sh * cu, 0.0);
        *sv = cj_v3(a * ch * cu, s * b * ch * sn, s * c * sh);
        break;
    }
    case CJ_QUADRIC_CONE:
        *p = cj_v3(a * v * cu, b * v * sn, c * v);
        *su = cj_v3(-a * v * sn, b * v * cu, 0.0);
        *sv = cj_v3(a * cu, b * sn, c);
        break;
    case CJ_QUADRIC_PARABOLOID:
        *p = cj_v3(a * v * cu, b * v * sn, v * v);
        *su = cj_v3(-a * v * sn, b * v * cu, 0.0);
        *sv = cj_v3(a * cu, b * sn, 2.0 * v);
        break;
    case CJ_QUADRIC_HYPERBOLIC_PARABOLOID:
        *p = cj_v3(a * u, b * v, u * u - v * v);
        *su = cj_v3(a, 0.0, 2.0 * u);
        *sv = cj_v3(0.0, b, -2.0 * v);
        break;
    }
    return CJ_OK;
}

/* S_u x S_v with the factor that vanishes at poles divided out (see quadric.h). */
static cj_status normal_cb(const void *data, double u, double v, cj_vec3 *n) {
    const cj_quadric *q = data;
    double a = q->a, b = q->b, c = q->c;
    double cu = cos(u), sn = sin(u);
    cj_vec3 m = {0, 0, 0};
    switch (q->kind) {
    case CJ_QUADRIC_ELLIPSOID: {
        double cv = cos(v);
        m = cj_v3(b * c * cv * cu, a * c * cv * sn, a * b * sin(v));
        break;
    }
    case CJ_QUADRIC_HYPERBOLOID1: {
        double ch = cosh(v);
        m = cj_v3(b * c * ch * cu, a * c * ch * sn, -a * b * sinh(v));
        break;
    }
    case CJ_QUADRIC_HYPERBOLOID2: {
        double sh = sinh(v), s = q->lower ? -1.0 : 1.0;
        m = cj_v3(b * c * sh * cu, s * a * c * sh * sn, -s * a * b * cosh(v));
        break;
    }
    case CJ_QUADRIC_CONE: {
        /* sign(v); at the apex the side the domain approaches it from. */
        double s = v > 0.0 ? 1.0 : v < 0.0 ? -1.0 : (q->v1 == 0.0 ? -1.0 : 1.0);
        m = cj_v3(s * b * c * cu, s * a * c * sn, -s * a * b);
        break;
    }
    case CJ_QUADRIC_PARABOLOID:
        m = cj_v3(2.0 * b * v * cu, 2.0 * a * v * sn, -a * b);
        break;
    case CJ_QUADRIC_HYPERBOLIC_PARABOLOID:
        m = cj_v3(-2.0 * b * u, 2.0 * a * v, a * b);
        break;
    }
    double len = cj_v3_norm(m);
    if (!(len > 0.0) || !isfinite(len))
        return cj_fail(CJ_ERR_DEGENERATE, "%s: normal undefined at (u,v) = (%g, %g)",
                       kind_names[q->kind], u, v);
    *n = cj_v3_scale(m, 1.0 / len);
    return CJ_OK;
}

void cj_quadric_surface(const cj_quadric *q, cj_param_surface *out) {
    assert(q && out);
    out->eval = param_cb;
    out->normal = normal_cb;
    out->data = q;
    out->u0 = q->u0;
    out->u1 = q->u1;
    out->v0 = q->v0;
    out->v1 = q->v1;
    out->name = kind_names[q->kind];
    unsigned fl = 0;
    switch (q->kind) {
    case CJ_QUADRIC_ELLIPSOID:
        fl = CJ_SURF_PERIODIC_U | CJ_SURF_COLLAPSED_V0 | CJ_SURF_COLLAPSED_V1;
        break;
    case CJ_QUADRIC_HYPERBOLOID1:
        fl = CJ_SURF_PERIODIC_U;
        break;
    case CJ_QUADRIC_HYPERBOLOID2:
    case CJ_QUADRIC_PARABOLOID:
        fl = CJ_SURF_PERIODIC_U | CJ_SURF_COLLAPSED_V0;
        break;
    case CJ_QUADRIC_CONE:
        fl = CJ_SURF_PERIODIC_U | (q->v0 == 0.0 ? CJ_SURF_COLLAPSED_V0 : 0u) |
             (q->v1 == 0.0 ? CJ_SURF_COLLAPSED_V1 : 0u);
        break;
    case CJ_QUADRIC_HYPERBOLIC_PARABOLOID:
        fl = 0;
        break;
    }
    out->flags = fl;
}

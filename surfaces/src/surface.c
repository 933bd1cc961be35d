/* Generic operations on parametric and implicit surfaces and planar curves. */
#include "casteljau/surface.h"
#include "casteljau/bezier.h"
#include "casteljau/rational.h"
#include "error_internal.h"

#include <assert.h>
#include <math.h>

static const char *surf_name(const cj_param_surface *s) {
    return s->name ? s->name : "surface";
}

cj_status cj_param_surface_check(const cj_param_surface *s) {
    assert(s);
    if (!s->eval) return cj_fail(CJ_ERR_ARGUMENT, "%s: no evaluation callback", surf_name(s));
    if (!isfinite(s->u0) || !isfinite(s->u1) || !isfinite(s->v0) || !isfinite(s->v1))
        return cj_fail(CJ_ERR_NONFINITE, "%s: domain bound is NaN or infinite", surf_name(s));
    if (!(s->u0 < s->u1))
        return cj_fail(CJ_ERR_ARGUMENT, "%s: empty u-domain [%g, %g]", surf_name(s), s->u0, s->u1);
    if (!(s->v0 < s->v1))
        return cj_fail(CJ_ERR_ARGUMENT, "%s: empty v-domain [%g, %g]", surf_name(s), s->v0, s->v1);
    return CJ_OK;
}

/* Clamps t into [a,b] if within the slack, else fails naming the parameter. */
static cj_status clamp_param(const cj_param_surface *s, const char *which, double a, double b,
                             double *t) {
    if (!isfinite(*t))
        return cj_fail(CJ_ERR_NONFINITE, "%s: parameter %s is %s", surf_name(s), which,
                       isnan(*t) ? "NaN" : "infinite");
    double slack = CJ_SURF_DOMAIN_SLACK * (b - a);
    if (*t < a) {
        if (*t < a - slack)
            return cj_fail(CJ_ERR_RANGE, "%s: %s = %.17g below the domain [%g, %g]", surf_name(s),
                           which, *t, a, b);
        *t = a;
    } else if (*t > b) {
        if (*t > b + slack)
            return cj_fail(CJ_ERR_RANGE, "%s: %s = %.17g above the domain [%g, %g]", surf_name(s),
                           which, *t, a, b);
        *t = b;
    }
    return CJ_OK;
}

static cj_status eval_checked(const cj_param_surface *s, double u, double v, cj_vec3 *p,
                              cj_vec3 *su, cj_vec3 *sv) {
    cj_status st = s->eval(s->data, u, v, p, su, sv);
    if (st != CJ_OK) return st;
    if (!cj_v3_finite(*p) || !cj_v3_finite(*su) || !cj_v3_finite(*sv))
        return cj_fail(CJ_ERR_NONFINITE, "%s: evaluation at (u,v) = (%g, %g) is not finite",
                       surf_name(s), u, v);
    return CJ_OK;
}

cj_status cj_surface_eval(const cj_param_surface *s, double u, double v, cj_vec3 *p, cj_vec3 *su,
                          cj_vec3 *sv) {
    assert(s && s->eval && p);
    cj_status st = clamp_param(s, "u", s->u0, s->u1, &u);
    if (st == CJ_OK) st = clamp_param(s, "v", s->v0, s->v1, &v);
    if (st != CJ_OK) return st;
    cj_vec3 P, Su, Sv;
    st = eval_checked(s, u, v, &P, &Su, &Sv);
    if (st != CJ_OK) return st;
    *p = P;
    if (su) *su = Su;
    if (sv) *sv = Sv;
    return CJ_OK;
}

/* Unit cross product of the partials if it is clearly non-zero. */
static int cross_normal(cj_vec3 su, cj_vec3 sv, cj_vec3 *n) {
    double a = cj_v3_norm(su), b = cj_v3_norm(sv);
    cj_vec3 c = cj_v3_cross(su, sv);
    double nc = cj_v3_norm(c);
    if (!(a > 0.0) || !(b > 0.0) || !(nc > 1e-12 * a * b)) return 0;
    *n = cj_v3_scale(c, 1.0 / nc);
    return 1;
}

cj_status cj_surface_normal(const cj_param_surface *s, double u, double v, cj_vec3 *n) {
    assert(s && s->eval && n);
    cj_status st = clamp_param(s, "u", s->u0, s->u1, &u);
    if (st == CJ_OK) st = clamp_param(s, "v", s->v0, s->v1, &v);
    if (st != CJ_OK) return st;
    if (s->normal) {
        cj_vec3 r;
        st = s->normal(s->data, u, v, &r);
        if (st != CJ_OK) return st;
        if (!cj_v3_finite(r))
            return cj_fail(CJ_ERR_NONFINITE, "%s: normal at (u,v) = (%g, %g) is not finite",
                           surf_name(s), u, v);
        *n = r;
        return CJ_OK;
    }
    cj_vec3 p, su, sv;
    st = eval_checked(s, u, v, &p, &su, &sv);
    if (st != CJ_OK) return st;
    if (cross_normal(su, sv, n)) return CJ_OK;
    /* Singular point: approach from the interior. Move the parameter(s) whose partial
     * vanishes (or both, if neither does alone) towards the middle of the domain. */
    double du = 1e-7 * (s->u1 - s->u0), dv = 1e-7 * (s->v1 - s->v0);
    double um = 0.5 * (s->u0 + s->u1), vm = 0.5 * (s->v0 + s->v1);
    double nu = u < um ? u + du : u - du, nv = v < vm ? v + dv : v - dv;
    double a = cj_v3_norm(su), b = cj_v3_norm(sv);
    const double tries[3][2] = {{a <= b ? u : nu, a <= b ? nv : v}, {nu, v}, {nu, nv}};
    for (int k = 0; k < 3; ++k) {
        st = eval_checked(s, tries[k][0], tries[k][1], &p, &su, &sv);
        if (st != CJ_OK) return st;
        if (cross_normal(su, sv, n)) return CJ_OK;
    }
    return cj_fail(CJ_ERR_DEGENERATE,
                   "%s: normal undefined at (u,v) = (%g, %g): partial derivatives are parallel "
                   "or zero there and nearby",
                   surf_name(s), u, v);
}

cj_status cj_implicit_eval(const cj_implicit_surface *s, cj_vec3 x, double *f, cj_vec3 *grad) {
    assert(s && s->eval && f);
    const char *name = s->name ? s->name : "implicit surface";
    if (!cj_v3_finite(x))
        return cj_fail(CJ_ERR_NONFINITE, "%s: point (%g, %g, %g) is not finite", name, x.x, x.y,
                       x.z);
    double F;
    cj_vec3 G;
    cj_status st = s->eval(s->data, x, &F, &G);
    if (st != CJ_OK) return st;
    if (!isfinite(F) || !cj_v3_finite(G))
        return cj_fail(CJ_ERR_NONFINITE, "%s: f or grad f at (%g, %g, %g) is not finite", name, x.x,
                       x.y, x.z);
    *f = F;
    if (grad) *grad = G;
    return CJ_OK;
}

cj_status cj_implicit_normal(const cj_implicit_surface *s, cj_vec3 x, cj_vec3 *n) {
    assert(n);
    double f;
    cj_vec3 g;
    cj_status st = cj_implicit_eval(s, x, &f, &g);
    if (st != CJ_OK) return st;
    double ng = cj_v3_norm(g);
    if (!(ng > 0.0))
        return cj_fail(CJ_ERR_DEGENERATE, "%s: gradient vanishes at (%g, %g, %g)",
                       s->name ? s->name : "implicit surface", x.x, x.y, x.z);
    *n = cj_v3_scale(g, 1.0 / ng);
    return CJ_OK;
}

/* ---- planar curves ------------------------------------------------------------------ */

static cj_status bezier_curve2(const void *data, double t, cj_vec2 d[3]) {
    const cj_bezier *b = data;
    double out[3 * 2];
    cj_status st = cj_bezier_eval_derivs(b, t, 2, out);
    if (st != CJ_OK) return st;
    for (int j = 0; j < 3; ++j) d[j] = cj_v2(out[2 * j], out[2 * j + 1]);
    return CJ_OK;
}

cj_status cj_curve2_from_bezier(const struct cj_bezier *b, cj_curve2 *out) {
    assert(b && out);
    cj_status st = cj_bezier_check(b, CJ_BEZIER_MAX_DEGREE);
    if (st != CJ_OK) return st;
    if (b->dim != 2)
        return cj_fail(CJ_ERR_DIMENSION, "planar curve: Bezier curve has dimension %d, need 2",
                       b->dim);
    const double *first = b->pts, *last = b->pts + 2 * b->degree;
    out->eval = bezier_curve2;
    out->data = b;
    out->t0 = 0.0;
    out->t1 = 1.0;
    out->closed = b->degree > 0 && first[0] == last[0] && first[1] == last[1];
    return CJ_OK;
}

static cj_status rbezier_curve2(const void *data, double t, cj_vec2 d[3]) {
    const cj_rbezier *b = data;
    double out[3 * 2];
    cj_status st = cj_rbezier_eval_derivs(b, t, 2, out);
    if (st != CJ_OK) return st;
    for (int j = 0; j < 3; ++j) d[j] = cj_v2(out[2 * j], out[2 * j + 1]);
    return CJ_OK;
}

cj_status cj_curve2_from_rbezier(const struct cj_rbezier *b, cj_curve2 *out) {
    assert(b && out);
    cj_status st = cj_rbezier_check(b);
    if (st != CJ_OK) return st;
    if (b->dim != 2)
        return cj_fail(CJ_ERR_DIMENSION,
                       "planar curve: rational Bezier curve has dimension %d, need 2", b->dim);
    const double *first = b->pts, *last = b->pts + 2 * b->degree;
    out->eval = rbezier_curve2;
    out->data = b;
    out->t0 = 0.0;
    out->t1 = 1.0;
    out->closed = b->degree > 0 && first[0] == last[0] && first[1] == last[1];
    return CJ_OK;
}

cj_status cj_curve2_check(const cj_curve2 *c) {
    assert(c);
    if (!c->eval) return cj_fail(CJ_ERR_ARGUMENT, "planar curve: no evaluation callback");
    if (!isfinite(c->t0) || !isfinite(c->t1))
        return cj_fail(CJ_ERR_NONFINITE, "planar curve: parameter bound is NaN or infinite");
    if (!(c->t0 < c->t1))
        return cj_fail(CJ_ERR_ARGUMENT, "planar curve: empty parameter range [%g, %g]", c->t0,
                       c->t1);
    return CJ_OK;
}

/* ---- frames ------------------------------------------------------------------------- */

void cj_frame_from_axis(cj_vec3 a, cj_vec3 *e1, cj_vec3 *e2) {
    assert(e1 && e2);
    /* Duff et al. 2017 "Building an orthonormal basis, revisited": branch on the sign of z. */
    double sign = copysign(1.0, a.z);
    double k = -1.0 / (sign + a.z);
    double m = a.x * a.y * k;
    *e1 = cj_v3(1.0 + sign * a.x * a.x * k, sign * m, -sign * a.x);
    *e2 = cj_v3(m, sign + a.y * a.y * k, -a.y);
}

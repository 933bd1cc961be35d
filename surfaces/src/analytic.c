/* Planes, planar and bilinear patches, cylinders, surfaces of revolution, the torus. */
#include "casteljau/analytic.h"
#include "error_internal.h"

#include <assert.h>
#include <math.h>

static const double two_pi = 6.283185307179586476925286766559;

static cj_status check_vec(const char *what, const char *name, cj_vec3 a) {
    if (!isfinite(a.x) || !isfinite(a.y) || !isfinite(a.z))
        return cj_fail(CJ_ERR_NONFINITE, "%s: %s (%g, %g, %g) is not finite", what, name, a.x, a.y,
                       a.z);
    return CJ_OK;
}

static cj_status check_num(const char *what, const char *name, double v) {
    if (!isfinite(v))
        return cj_fail(CJ_ERR_NONFINITE, "%s: %s is %s", what, name, isnan(v) ? "NaN" : "infinite");
    return CJ_OK;
}

static cj_status check_radius(const char *what, const char *name, double r) {
    cj_status st = check_num(what, name, r);
    if (st != CJ_OK) return st;
    if (!(r > 0.0)) return cj_fail(CJ_ERR_DEGENERATE, "%s: %s = %g must be > 0", what, name, r);
    return CJ_OK;
}

/* Normalises a non-zero finite axis and builds its frame. */
static cj_status make_axis(const char *what, cj_vec3 axis, cj_vec3 *a, cj_vec3 *e1, cj_vec3 *e2) {
    cj_status st = check_vec(what, "axis", axis);
    if (st != CJ_OK) return st;
    /* Pre-scale by the largest component so that huge or tiny finite vectors normalise. */
    double big = fmax(fabs(axis.x), fmax(fabs(axis.y), fabs(axis.z)));
    if (big > 0.0) axis = cj_v3(axis.x / big, axis.y / big, axis.z / big);
    double len = cj_v3_norm(axis);
    if (!(len > 0.0) || !isfinite(len))
        return cj_fail(CJ_ERR_DEGENERATE, "%s: axis has zero length", what);
    *a = cj_v3_scale(axis, 1.0 / len);
    cj_frame_from_axis(*a, e1, e2);
    return CJ_OK;
}

static cj_vec3 radial(cj_vec3 e1, cj_vec3 e2, double cu, double su) {
    return cj_v3_add(cj_v3_scale(e1, cu), cj_v3_scale(e2, su));
}

/* ---- plane ---------------------------------------------------------------------------- */

cj_status cj_plane_from_point_normal(cj_plane *pl, cj_vec3 p, cj_vec3 n) {
    assert(pl);
    cj_status st = check_vec("plane", "point", p);
    if (st == CJ_OK) st = check_vec("plane", "normal", n);
    if (st != CJ_OK) return st;
    /* Pre-scale by the largest component so that huge or tiny finite vectors normalise. */
    double big = fmax(fabs(n.x), fmax(fabs(n.y), fabs(n.z)));
    if (big > 0.0) n = cj_v3(n.x / big, n.y / big, n.z / big);
    double len = cj_v3_norm(n);
    if (!(len > 0.0) || !isfinite(len))
        return cj_fail(CJ_ERR_DEGENERATE, "plane: normal has zero length");
    pl->n = cj_v3_scale(n, 1.0 / len);
    pl->d = cj_v3_dot(pl->n, p);
    return CJ_OK;
}

cj_status cj_plane_from_points(cj_plane *pl, cj_vec3 a, cj_vec3 b, cj_vec3 c) {
    assert(pl);
    cj_status st = check_vec("plane", "point a", a);
    if (st == CJ_OK) st = check_vec("plane", "point b", b);
    if (st == CJ_OK) st = check_vec("plane", "point c", c);
    if (st != CJ_OK) return st;
    cj_vec3 ab = cj_v3_sub(b, a), ac = cj_v3_sub(c, a);
    cj_vec3 n = cj_v3_cross(ab, ac);
    if (!(cj_v3_norm(n) > 1e-14 * cj_v3_norm(ab) * cj_v3_norm(ac)))
        return cj_fail(CJ_ERR_DEGENERATE, "plane: the three points are collinear");
    return cj_plane_from_point_normal(pl, a, n);
}

static cj_status plane_cb(const void *data, cj_vec3 x, double *f, cj_vec3 *grad) {
    const cj_plane *pl = data;
    *f = cj_v3_dot(pl->n, x) - pl->d;
    *grad = pl->n;
    return CJ_OK;
}

void cj_plane_implicit(const cj_plane *pl, cj_implicit_surface *out) {
    assert(pl && out);
    out->eval = plane_cb;
    out->data = pl;
    out->name = "plane";
}

/* ---- planar patch --------------------------------------------------------------------- */

cj_status cj_planar_patch_init(cj_planar_patch *pp, cj_vec3 p, cj_vec3 eu, cj_vec3 ev) {
    assert(pp);
    cj_status st = check_vec("planar patch", "corner", p);
    if (st == CJ_OK) st = check_vec("planar patch", "edge vector e_u", eu);
    if (st == CJ_OK) st = check_vec("planar patch", "edge vector e_v", ev);
    if (st != CJ_OK) return st;
    cj_vec3 n = cj_v3_cross(eu, ev);
    if (!(cj_v3_norm(n) > 1e-14 * cj_v3_norm(eu) * cj_v3_norm(ev)) || !(cj_v3_norm(n) > 0.0))
        return cj_fail(CJ_ERR_DEGENERATE, "planar patch: edge vectors are parallel or zero");
    cj_planar_patch t = {p, eu, ev, {{0, 0, 0}, 0}};
    st = cj_plane_from_point_normal(&t.plane, p, n);
    if (st != CJ_OK) return st;
    *pp = t;
    return CJ_OK;
}

static cj_status planar_cb(const void *data, double u, double v, cj_vec3 *p, cj_vec3 *su,
                           cj_vec3 *sv) {
    const cj_planar_patch *pp = data;
    *p = cj_v3_add(pp->p, cj_v3_add(cj_v3_scale(pp->eu, u), cj_v3_scale(pp->ev, v)));
    *su = pp->eu;
    *sv = pp->ev;
    return CJ_OK;
}

static cj_status planar_normal_cb(const void *data, double u, double v, cj_vec3 *n) {
    (void)u;
    (void)v;
    *n = ((const cj_planar_patch *)data)->plane.n;
    return CJ_OK;
}

void cj_planar_patch_surface(const cj_planar_patch *pp, cj_param_surface *out) {
    assert(pp && out);
    cj_param_surface s = {planar_cb, planar_normal_cb, pp, 0.0, 1.0, 0.0, 1.0, 0u, "planar patch"};
    *out = s;
}

void cj_planar_patch_implicit(const cj_planar_patch *pp, cj_implicit_surface *out) {
    cj_plane_implicit(&pp->plane, out);
    out->name = "planar patch";
}

/* ---- bilinear patch ------------------------------------------------------------------- */

static int same(cj_vec3 a, cj_vec3 b) {
    return a.x == b.x && a.y == b.y && a.z == b.z;
}

cj_status cj_bilinear_init(cj_bilinear *bl, cj_vec3 p00, cj_vec3 p10, cj_vec3 p01, cj_vec3 p11) {
    assert(bl);
    const cj_vec3 c[4] = {p00, p10, p01, p11};
    static const char *const names[4] = {"corner p00", "corner p10", "corner p01", "corner p11"};
    for (int i = 0; i < 4; ++i) {
        cj_status st = check_vec("bilinear patch", names[i], c[i]);
        if (st != CJ_OK) return st;
    }
    /* Not all collinear: some triangle of corners has a non-negligible area. */
    double big = 0.0, scale = 0.0;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) {
            double d = cj_v3_norm(cj_v3_sub(c[i], c[j]));
            if (d > scale) scale = d;
            for (int k = 0; k < 4; ++k) {
                double ar = cj_v3_norm(cj_v3_cross(cj_v3_sub(c[j], c[i]), cj_v3_sub(c[k], c[i])));
                if (ar > big) big = ar;
            }
        }
    if (!(big > 1e-14 * scale * scale))
        return cj_fail(CJ_ERR_DEGENERATE, "bilinear patch: the four corners are collinear");
    bl->p00 = p00;
    bl->p10 = p10;
    bl->p01 = p01;
    bl->p11 = p11;
    bl->flags = (same(p00, p01) ? CJ_SURF_COLLAPSED_U0 : 0u) |
                (same(p10, p11) ? CJ_SURF_COLLAPSED_U1 : 0u) |
                (same(p00, p10) ? CJ_SURF_COLLAPSED_V0 : 0u) |
                (same(p01, p11) ? CJ_SURF_COLLAPSED_V1 : 0u);
    return CJ_OK;
}

static cj_status bilinear_cb(const void *data, double u, double v, cj_vec3 *p, cj_vec3 *su,
                             cj_vec3 *sv) {
    const cj_bilinear *b = data;
    cj_vec3 bot = cj_v3_lerp(b->p00, b->p10, u), top = cj_v3_lerp(b->p01, b->p11, u);
    *p = cj_v3_lerp(bot, top, v);
    *su = cj_v3_lerp(cj_v3_sub(b->p10, b->p00), cj_v3_sub(b->p11, b->p01), v);
    *sv = cj_v3_sub(top, bot);
    return CJ_OK;
}

void cj_bilinear_surface(const cj_bilinear *bl, cj_param_surface *out) {
    assert(bl && out);
    cj_param_surface s = {bilinear_cb, NULL, bl, 0.0, 1.0, 0.0, 1.0, bl->flags, "bilinear patch"};
    *out = s;
}

/* ---- right circular cylinder ---------------------------------------------------------- */

cj_status cj_cylinder_init(cj_cylinder *cy, cj_vec3 base, cj_vec3 axis, double radius, double h0,
                           double h1) {
    assert(cy);
    const char *w = "cylinder";
    cj_cylinder t;
    cj_status st = check_vec(w, "base point", base);
    if (st == CJ_OK) st = make_axis(w, axis, &t.a, &t.e1, &t.e2);
    if (st == CJ_OK) st = check_radius(w, "radius", radius);
    if (st == CJ_OK) st = check_num(w, "h0", h0);
    if (st == CJ_OK) st = check_num(w, "h1", h1);
    if (st != CJ_OK) return st;
    if (!(h0 < h1))
        return cj_fail(CJ_ERR_ARGUMENT, "cylinder: empty height range [%g, %g]", h0, h1);
    t.base = base;
    t.radius = radius;
    t.h0 = h0;
    t.h1 = h1;
    *cy = t;
    return CJ_OK;
}

static cj_status cylinder_cb(const void *data, double u, double v, cj_vec3 *p, cj_vec3 *su,
                             cj_vec3 *sv) {
    const cj_cylinder *c = data;
    double cu = cos(u), sn = sin(u);
    cj_vec3 er = radial(c->e1, c->e2, cu, sn), et = radial(c->e1, c->e2, -sn, cu);
    *p = cj_v3_add(c->base, cj_v3_add(cj_v3_scale(er, c->radius), cj_v3_scale(c->a, v)));
    *su = cj_v3_scale(et, c->radius);
    *sv = c->a;
    return CJ_OK;
}

static cj_status cylinder_normal_cb(const void *data, double u, double v, cj_vec3 *n) {
    const cj_cylinder *c = data;
    (void)v;
    *n = radial(c->e1, c->e2, cos(u), sin(u));
    return CJ_OK;
}

static cj_status cylinder_implicit_cb(const void *data, cj_vec3 x, double *f, cj_vec3 *grad) {
    const cj_cylinder *c = data;
    cj_vec3 w = cj_v3_sub(x, c->base);
    cj_vec3 wp = cj_v3_sub(w, cj_v3_scale(c->a, cj_v3_dot(w, c->a)));
    *f = (cj_v3_dot(wp, wp) - c->radius * c->radius) / (2.0 * c->radius);
    *grad = cj_v3_scale(wp, 1.0 / c->radius);
    return CJ_OK;
}

void cj_cylinder_surface(const cj_cylinder *cy, cj_param_surface *out) {
    assert(cy && out);
    cj_param_surface s = {cylinder_cb, cylinder_normal_cb, cy,        0.0, two_pi, cy->h0,
                          cy->h1,      CJ_SURF_PERIODIC_U, "cylinder"};
    *out = s;
}

void cj_cylinder_implicit(const cj_cylinder *cy, cj_implicit_surface *out) {
    assert(cy && out);
    out->eval = cylinder_implicit_cb;
    out->data = cy;
    out->name = "cylinder";
}

/* ---- general cylinder ----------------------------------------------------------------- */

cj_status cj_gen_cylinder_init(cj_gen_cylinder *gc, const cj_curve2 *curve, cj_vec3 origin,
                               cj_vec3 e1, cj_vec3 e2, cj_vec3 dir, double v0, double v1) {
    assert(gc && curve);
    const char *w = "general cylinder";
    cj_status st = cj_curve2_check(curve);
    if (st == CJ_OK) st = check_vec(w, "origin", origin);
    if (st == CJ_OK) st = check_vec(w, "plane vector e1", e1);
    if (st == CJ_OK) st = check_vec(w, "plane vector e2", e2);
    if (st == CJ_OK) st = check_vec(w, "direction", dir);
    if (st == CJ_OK) st = check_num(w, "v0", v0);
    if (st == CJ_OK) st = check_num(w, "v1", v1);
    if (st != CJ_OK) return st;
    if (!(v0 < v1)) return cj_fail(CJ_ERR_ARGUMENT, "%s: empty sweep range [%g, %g]", w, v0, v1);
    cj_vec3 pn = cj_v3_cross(e1, e2);
    double l1 = cj_v3_norm(e1), l2 = cj_v3_norm(e2), ld = cj_v3_norm(dir);
    if (!(ld > 0.0)) return cj_fail(CJ_ERR_DEGENERATE, "%s: direction has zero length", w);
    if (!(cj_v3_norm(pn) > 1e-12 * l1 * l2) || !(l1 > 0.0) || !(l2 > 0.0))
        return cj_fail(CJ_ERR_DEGENERATE, "%s: plane vectors e1, e2 are parallel or zero", w);
    if (!(fabs(cj_v3_dot(pn, dir)) > 1e-12 * cj_v3_norm(pn) * ld))
        return cj_fail(CJ_ERR_DEGENERATE, "%s: direction lies in the plane of the curve", w);
    gc->curve = *curve;
    gc->origin = origin;
    gc->e1 = e1;
    gc->e2 = e2;
    gc->dir = dir;
    gc->v0 = v0;
    gc->v1 = v1;
    return CJ_OK;
}

static cj_vec3 in_plane(const cj_gen_cylinder *g, cj_vec2 q) {
    return cj_v3_add(cj_v3_scale(g->e1, q.x), cj_v3_scale(g->e2, q.y));
}

static cj_status gen_cylinder_cb(const void *data, double u, double v, cj_vec3 *p, cj_vec3 *su,
                                 cj_vec3 *sv) {
    const cj_gen_cylinder *g = data;
    cj_vec2 d[3];
    cj_status st = g->curve.eval(g->curve.data, u, d);
    if (st != CJ_OK) return st;
    *p = cj_v3_add(g->origin, cj_v3_add(in_plane(g, d[0]), cj_v3_scale(g->dir, v)));
    *su = in_plane(g, d[1]);
    *sv = g->dir;
    return CJ_OK;
}

static cj_status gen_cylinder_normal_cb(const void *data, double u, double v, cj_vec3 *n) {
    const cj_gen_cylinder *g = data;
    cj_vec2 d[3];
    cj_status st = g->curve.eval(g->curve.data, u, d);
    if (st != CJ_OK) return st;
    for (int k = 1; k <= 2; ++k) {
        cj_vec3 c = cj_v3_cross(in_plane(g, d[k]), g->dir);
        double len = cj_v3_norm(c);
        if (len > 0.0 && isfinite(len)) {
            *n = cj_v3_scale(c, 1.0 / len);
            return CJ_OK;
        }
    }
    return cj_fail(CJ_ERR_DEGENERATE,
                   "general cylinder: normal undefined at (u,v) = (%g, %g): the curve's first and "
                   "second derivatives vanish",
                   u, v);
}

void cj_gen_cylinder_surface(const cj_gen_cylinder *gc, cj_param_surface *out) {
    assert(gc && out);
    cj_param_surface s = {gen_cylinder_cb,
                          gen_cylinder_normal_cb,
                          gc,
                          gc->curve.t0,
                          gc->curve.t1,
                          gc->v0,
                          gc->v1,
                          gc->curve.closed ? CJ_SURF_PERIODIC_U : 0u,
                          "general cylinder"};
    *out = s;
}

/* ---- surface of revolution ------------------------------------------------------------ */

cj_status cj_revolution_init(cj_revolution *rv, const cj_curve2 *profile, cj_vec3 origin,
                             cj_vec3 axis) {
    assert(rv && profile);
    const char *w = "surface of revolution";
    cj_revolution t;
    cj_status st = cj_curve2_check(profile);
    if (st == CJ_OK) st = check_vec(w, "origin", origin);
    if (st == CJ_OK) st = make_axis(w, axis, &t.a, &t.e1, &t.e2);
    if (st != CJ_OK) return st;
    cj_vec2 d0[3], d1[3];
    st = profile->eval(profile->data, profile->t0, d0);
    if (st == CJ_OK) st = profile->eval(profile->data, profile->t1, d1);
    if (st != CJ_OK) return st;
    double ends[4] = {d0[0].x, d0[0].y, d1[0].x, d1[0].y};
    st = cj_check_finite(ends, 4, "surface of revolution: profile end coordinate");
    if (st != CJ_OK) return st;
    double size = fmax(fmax(fabs(ends[0]), fabs(ends[1])), fmax(fabs(ends[2]), fabs(ends[3])));
    if (!(size > 0.0) && !(cj_v2_norm(d0[1]) > 0.0))
        return cj_fail(CJ_ERR_DEGENERATE, "surface of revolution: profile is a point on the axis");
    t.profile = *profile;
    t.origin = origin;
    t.flags = CJ_SURF_PERIODIC_U | (fabs(ends[0]) <= 1e-14 * size ? CJ_SURF_COLLAPSED_V0 : 0u) |
              (fabs(ends[2]) <= 1e-14 * size ? CJ_SURF_COLLAPSED_V1 : 0u) |
              (profile->closed ? CJ_SURF_PERIODIC_V : 0u);
    *rv = t;
    return CJ_OK;
}

static cj_status revolution_cb(const void *data, double u, double v, cj_vec3 *p, cj_vec3 *su,
                               cj_vec3 *sv) {
    const cj_revolution *r = data;
    cj_vec2 d[3];
    cj_status st = r->profile.eval(r->profile.data, v, d);
    if (st != CJ_OK) return st;
    double cu = cos(u), sn = sin(u);
    cj_vec3 er = radial(r->e1, r->e2, cu, sn), et = radial(r->e1, r->e2, -sn, cu);
    *p = cj_v3_add(r->origin, cj_v3_add(cj_v3_scale(er, d[0].x), cj_v3_scale(r->a, d[0].y)));
    *su = cj_v3_scale(et, d[0].x);
    *sv = cj_v3_add(cj_v3_scale(er, d[1].x), cj_v3_scale(r->a, d[1].y));
    return CJ_OK;
}

static cj_status revolution_normal_cb(const void *data, double u, double v, cj_vec3 *n) {
    const cj_revolution *r = data;
    cj_vec2 d[3];
    cj_status st = r->profile.eval(r->profile.data, v, d);
    if (st != CJ_OK) return st;
    cj_vec3 er = radial(r->e1, r->e2, cos(u), sin(u));
    for (int k = 1; k <= 2; ++k) {
        double len = cj_v2_norm(d[k]);
        if (len > 0.0 && isfinite(len)) {
            cj_vec3 m = cj_v3_sub(cj_v3_scale(er, d[k].y), cj_v3_scale(r->a, d[k].x));
            *n = cj_v3_scale(m, 1.0 / len);
            return CJ_OK;
        }
    }
    return cj_fail(CJ_ERR_DEGENERATE,
                   "surface of revolution: normal undefined at (u,v) = (%g, %g): the profile's "
                   "first and second derivatives vanish",
                   u, v);
}

void cj_revolution_surface(const cj_revolution *rv, cj_param_surface *out) {
    assert(rv && out);
    cj_param_surface s = {
        revolution_cb, revolution_normal_cb,   rv, 0.0, two_pi, rv->profile.t0, rv->profile.t1,
        rv->flags,     "surface of revolution"};
    *out = s;
}

/* ---- torus ---------------------------------------------------------------------------- */

cj_status cj_torus_init(cj_torus *to, cj_vec3 center, cj_vec3 axis, double major, double minor) {
    assert(to);
    const char *w = "torus";
    cj_torus t;
    cj_status st = check_vec(w, "center", center);
    if (st == CJ_OK) st = make_axis(w, axis, &t.a, &t.e1, &t.e2);
    if (st == CJ_OK) st = check_radius(w, "major radius", major);
    if (st == CJ_OK) st = check_radius(w, "minor radius", minor);
    if (st != CJ_OK) return st;
    if (!(minor < major))
        return cj_fail(CJ_ERR_ARGUMENT,
                       "torus: minor radius %g must be below major radius %g (ring torus)", minor,
                       major);
    t.center = center;
    t.major = major;
    t.minor = minor;
    *to = t;
    return CJ_OK;
}

static cj_status torus_cb(const void *data, double u, double v, cj_vec3 *p, cj_vec3 *su,
                          cj_vec3 *sv) {
    const cj_torus *t = data;
    double cu = cos(u), sn = sin(u), cv = cos(v), sv_ = sin(v);
    cj_vec3 er = radial(t->e1, t->e2, cu, sn), et = radial(t->e1, t->e2, -sn, cu);
    double rr = t->major + t->minor * cv;
    *p = cj_v3_add(t->center, cj_v3_add(cj_v3_scale(er, rr), cj_v3_scale(t->a, t->minor * sv_)));
    *su = cj_v3_scale(et, rr);
    *sv = cj_v3_add(cj_v3_scale(er, -t->minor * sv_), cj_v3_scale(t->a, t->minor * cv));
    return CJ_OK;
}

static cj_status torus_normal_cb(const void *data, double u, double v, cj_vec3 *n) {
    const cj_torus *t = data;
    cj_vec3 er = radial(t->e1, t->e2, cos(u), sin(u));
    *n = cj_v3_add(cj_v3_scale(er, cos(v)), cj_v3_scale(t->a, sin(v)));
    return CJ_OK;
}

static cj_status torus_implicit_cb(const void *data, cj_vec3 x, double *f, cj_vec3 *grad) {
    const cj_torus *t = data;
    cj_vec3 w = cj_v3_sub(x, t->center);
    double h = cj_v3_dot(w, t->a), q = cj_v3_dot(w, w);
    double R2 = t->major * t->major, s = q + R2 - t->minor * t->minor;
    *f = s * s - 4.0 * R2 * (q - h * h);
    *grad = cj_v3_sub(cj_v3_scale(w, 4.0 * s),
                      cj_v3_scale(cj_v3_sub(w, cj_v3_scale(t->a, h)), 8.0 * R2));
    return CJ_OK;
}

void cj_torus_surface(const cj_torus *to, cj_param_surface *out) {
    assert(to && out);
    cj_param_surface s = {torus_cb, torus_normal_cb,
                          to,       0.0,
                          two_pi,   0.0,
                          two_pi,   CJ_SURF_PERIODIC_U | CJ_SURF_PERIODIC_V,
                          "torus"};
    *out = s;
}

void cj_torus_implicit(const cj_torus *to, cj_implicit_surface *out) {
    assert(to && out);
    out->eval = torus_implicit_cb;
    out->data = to;
    out->name = "torus";
}

/* Validation of every part of a scene. Messages name the part by the path a reader of the
 * scene would use ("materials[2].alpha must be >= 0"); the JSON reader passes its own paths. */
#include "scene_internal.h"

#include "error_internal.h"

#include "casteljau/bezier.h"

#include <assert.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

/* Same bound as the framebuffer's CJ_FRAMEBUFFER_MAX_SIDE (raster/ is a higher layer). */
#define SCENE_MAX_SIDE 32768

static cj_status fin(const char *path, const char *field, double v) {
    if (!isfinite(v)) return cj_fail(CJ_ERR_NONFINITE, "%s.%s is not finite", path, field);
    return CJ_OK;
}

static cj_status ge(const char *path, const char *field, double v, double lo) {
    cj_status st = fin(path, field, v);
    if (st) return st;
    if (!(v >= lo)) return cj_fail(CJ_ERR_RANGE, "%s.%s must be >= %g", path, field, lo);
    return CJ_OK;
}

static cj_status gt(const char *path, const char *field, double v, double lo) {
    cj_status st = fin(path, field, v);
    if (st) return st;
    if (!(v > lo)) return cj_fail(CJ_ERR_RANGE, "%s.%s must be > %g", path, field, lo);
    return CJ_OK;
}

static cj_status in01(const char *path, const char *field, double v) {
    cj_status st = fin(path, field, v);
    if (st) return st;
    if (!(v >= 0.0 && v <= 1.0))
        return cj_fail(CJ_ERR_RANGE, "%s.%s must be in [0, 1]", path, field);
    return CJ_OK;
}

/* Coordinates, lengths and directions: finite and within CJ_SCENE_MAX_COORD, so that no
 * product a renderer forms (squares, clip coordinates, float radiance) overflows. */
static cj_status coord(const char *path, const char *field, int k, double v) {
    if (!isfinite(v)) {
        if (k < 0) return cj_fail(CJ_ERR_NONFINITE, "%s.%s is not finite", path, field);
        return cj_fail(CJ_ERR_NONFINITE, "%s.%s[%d] is not finite", path, field, k);
    }
    if (!(fabs(v) <= CJ_SCENE_MAX_COORD)) {
        if (k < 0)
            return cj_fail(CJ_ERR_RANGE, "%s.%s = %g is beyond the limit of +-%g", path, field, v,
                           CJ_SCENE_MAX_COORD);
        return cj_fail(CJ_ERR_RANGE, "%s.%s[%d] = %g is beyond the limit of +-%g", path, field, k,
                       v, CJ_SCENE_MAX_COORD);
    }
    return CJ_OK;
}

static cj_status vec(const char *path, const char *field, cj_vec3 v) {
    const double c[3] = {v.x, v.y, v.z};
    for (int k = 0; k < 3; ++k) {
        cj_status st = coord(path, field, k, c[k]);
        if (st) return st;
    }
    return CJ_OK;
}

static cj_status nonzero(const char *path, const char *field, cj_vec3 v) {
    cj_status st = vec(path, field, v);
    if (st) return st;
    if (!(cj_v3_norm(v) > 0.0))
        return cj_fail(CJ_ERR_DEGENERATE, "%s.%s must not be the zero vector", path, field);
    return CJ_OK;
}

/* Colour components in [0, max] (max < 0: no upper bound). */
static cj_status rgb(const char *path, const char *field, cj_rgb c, double max) {
    const double v[3] = {c.r, c.g, c.b};
    for (int k = 0; k < 3; ++k) {
        if (!isfinite(v[k]))
            return cj_fail(CJ_ERR_NONFINITE, "%s.%s[%d] is not finite", path, field, k);
        if (!(v[k] >= 0.0)) return cj_fail(CJ_ERR_RANGE, "%s.%s[%d] must be >= 0", path, field, k);
        if (max >= 0.0 && !(v[k] <= max))
            return cj_fail(CJ_ERR_RANGE, "%s.%s[%d] must be in [0, %g]", path, field, k, max);
    }
    return CJ_OK;
}

static cj_status flag(const char *path, const char *field, int v) {
    if (v != 0 && v != 1) return cj_fail(CJ_ERR_RANGE, "%s.%s must be 0 or 1", path, field);
    return CJ_OK;
}

/* Re-labels the message of a constructor of surfaces/ with the part's path. */
static cj_status relabel(cj_status st, const char *path) {
    if (st == CJ_OK) return st;
    char msg[512];
    snprintf(msg, sizeof msg, "%s", cj_last_error());
    return cj_fail(st, "%s: %s", path, msg);
}

#define TRY(x)                                                                                     \
    do {                                                                                           \
        cj_status st_ = (x);                                                                       \
        if (st_) return st_;                                                                       \
    } while (0)

cj_status cj_scene_check_camera_(const cj_camera *c, const char *p) {
    TRY(vec(p, "eye", c->eye));
    TRY(nonzero(p, "gaze", c->gaze));
    TRY(nonzero(p, "up", c->up));
    cj_vec3 g = cj_v3_normalize(c->gaze), t = cj_v3_normalize(c->up);
    if (!(cj_v3_norm(cj_v3_cross(g, t)) > 1e-9))
        return cj_fail(CJ_ERR_DEGENERATE, "%s.up must not be parallel to the gaze", p);
    TRY(fin(p, "near", c->near));
    TRY(fin(p, "far", c->far));
    if (!(c->near < 0.0)) return cj_fail(CJ_ERR_RANGE, "%s.near must be < 0", p);
    if (!(c->far < c->near)) return cj_fail(CJ_ERR_RANGE, "%s.far must be < near (%g)", p, c->near);
    if (c->projection == CJ_PROJ_PERSPECTIVE) {
        TRY(fin(p, "fov_y", c->fov_y));
        if (!(c->fov_y > 0.0 && c->fov_y < 3.14159265358979323846))
            return cj_fail(CJ_ERR_RANGE, "%s.fov_y must be in (0, pi)", p);
    } else if (c->projection == CJ_PROJ_ORTHOGRAPHIC) {
        TRY(gt(p, "ortho_height", c->ortho_height, 0.0));
    } else {
        return cj_fail(CJ_ERR_RANGE, "%s.projection %d is not a projection", p, (int)c->projection);
    }
    TRY(ge(p, "aperture", c->aperture, 0.0));
    if (c->aperture > 0.0) {
        TRY(gt(p, "focus_distance", c->focus_distance, 0.0));
        if (c->projection != CJ_PROJ_PERSPECTIVE)
            return cj_fail(CJ_ERR_RANGE, "%s.aperture needs a perspective camera", p);
    }
    /* Whatever else the camera model itself needs (its frame), in its own words. */
    return relabel(cj_camera_check(c), p);
}

cj_status cj_scene_check_settings_(const cj_scene_settings *s, const char *p) {
    if (s->width < 1 || s->width > SCENE_MAX_SIDE)
        return cj_fail(CJ_ERR_RANGE, "%s.width must be in [1, %d]", p, SCENE_MAX_SIDE);
    if (s->height < 1 || s->height > SCENE_MAX_SIDE)
        return cj_fail(CJ_ERR_RANGE, "%s.height must be in [1, %d]", p, SCENE_MAX_SIDE);
    if (s->spp < 1) return cj_fail(CJ_ERR_RANGE, "%s.spp must be >= 1", p);
    TRY(gt(p, "tol_px", s->tol_px, 0.0));
    TRY(rgb(p, "background", s->background, -1.0));
    if (s->max_depth < 0) return cj_fail(CJ_ERR_RANGE, "%s.max_depth must be >= 0", p);
    if ((int)s->light_model < 0 || s->light_model > CJ_LIGHT_RADIOMETRIC)
        return cj_fail(CJ_ERR_RANGE, "%s.light_model %d is not a light model", p,
                       (int)s->light_model);
    if ((int)s->filter < 0 || s->filter > CJ_FILTER_MITCHELL)
        return cj_fail(CJ_ERR_RANGE, "%s.filter %d is not a pixel filter", p, (int)s->filter);
    TRY(ge(p, "filter_radius", s->filter_radius, 0.0));
    return CJ_OK;
}

cj_status cj_scene_check_light_(const cj_light *l, const char *p) {
    if ((int)l->kind < 0 || l->kind > CJ_LIGHT_SPHERE)
        return cj_fail(CJ_ERR_RANGE, "%s.kind %d is not a light kind", p, (int)l->kind);
    TRY(rgb(p, "color", l->color, -1.0));
    TRY(ge(p, "intensity", l->intensity, 0.0));
    if (!(l->intensity * fmax(l->color.r, fmax(l->color.g, l->color.b)) <= CJ_SCENE_MAX_RADIANCE))
        return cj_fail(CJ_ERR_RANGE,
                       "%s.intensity %g (times its colour) is over the limit of %g: radiance "
                       "would overflow",
                       p, l->intensity, CJ_SCENE_MAX_RADIANCE);
    TRY(flag(p, "casts_shadows", l->casts_shadows));
    switch (l->kind) {
    case CJ_LIGHT_AMBIENT:
        break;
    case CJ_LIGHT_POINT:
        TRY(vec(p, "position", l->position));
        break;
    case CJ_LIGHT_DIRECTIONAL:
        TRY(nonzero(p, "direction", l->direction));
        break;
    case CJ_LIGHT_SPOT:
        TRY(vec(p, "position", l->position));
        TRY(nonzero(p, "direction", l->direction));
        TRY(fin(p, "spot_angle", l->spot_angle));
        if (!(l->spot_angle > 0.0 && l->spot_angle <= 1.5707963267948966))
            return cj_fail(CJ_ERR_RANGE, "%s.spot_angle must be in (0, pi/2]", p);
        TRY(ge(p, "spot_exponent", l->spot_exponent, 0.0));
        break;
    case CJ_LIGHT_AREA:
        TRY(vec(p, "position", l->position));
        TRY(nonzero(p, "edge_u", l->edge_u));
        TRY(nonzero(p, "edge_v", l->edge_v));
        if (!(cj_v3_norm(cj_v3_cross(l->edge_u, l->edge_v)) >
              1e-12 * cj_v3_norm(l->edge_u) * cj_v3_norm(l->edge_v)))
            return cj_fail(CJ_ERR_DEGENERATE, "%s.edge_v must not be parallel to edge_u", p);
        break;
    case CJ_LIGHT_DISC:
    case CJ_LIGHT_SPHERE:
        TRY(vec(p, "position", l->position));
        if (l->kind == CJ_LIGHT_DISC) TRY(nonzero(p, "direction", l->direction));
        TRY(fin(p, "radius", l->radius));
        if (!(l->radius > 0.0 && l->radius <= 1e9))
            return cj_fail(CJ_ERR_RANGE, "%s.radius %g must be in (0, 1e9]", p, l->radius);
        break;
    }
    return CJ_OK;
}

cj_status cj_scene_check_texture_(const cj_texture *t, const char *p) {
    if ((int)t->kind < 0 || t->kind > CJ_TEX_CHECKER)
        return cj_fail(CJ_ERR_RANGE, "%s.kind %d is not a texture kind", p, (int)t->kind);
    if ((int)t->filter < 0 || t->filter > CJ_TEX_TRILINEAR)
        return cj_fail(CJ_ERR_RANGE, "%s.filter %d is not a filter", p, (int)t->filter);
    if ((int)t->wrap < 0 || t->wrap > CJ_TEX_CLAMP)
        return cj_fail(CJ_ERR_RANGE, "%s.wrap %d is not a wrap mode", p, (int)t->wrap);
    TRY(fin(p, "scale[0]", t->scale_u));
    TRY(fin(p, "scale[1]", t->scale_v));
    if (t->scale_u == 0.0 || t->scale_v == 0.0)
        return cj_fail(CJ_ERR_RANGE, "%s.scale must not be 0", p);
    TRY(fin(p, "offset[0]", t->offset_u));
    TRY(fin(p, "offset[1]", t->offset_v));
    if (t->kind == CJ_TEX_IMAGE) {
        if (!t->path || !t->path[0])
            return cj_fail(CJ_ERR_ARGUMENT, "%s.path is missing (an image texture needs a file)",
                           p);
        if (t->texels) {
            if (t->width < 1 || t->height < 1 || t->width > 65535 || t->height > 65535)
                return cj_fail(CJ_ERR_RANGE, "%s: size %d x %d out of range 1..65535", p, t->width,
                               t->height);
        }
    } else {
        if (t->checks_u < 1) return cj_fail(CJ_ERR_RANGE, "%s.checks[0] must be >= 1", p);
        if (t->checks_v < 1) return cj_fail(CJ_ERR_RANGE, "%s.checks[1] must be >= 1", p);
        TRY(rgb(p, "colors[0]", t->checker_a, 1.0));
        TRY(rgb(p, "colors[1]", t->checker_b, 1.0));
    }
    return CJ_OK;
}

cj_status cj_scene_check_material_(const cj_material *m, size_t ntextures, const char *p) {
    TRY(rgb(p, "color", m->color, 1.0));
    TRY(rgb(p, "specular", m->specular, 1.0));
    TRY(ge(p, "ka", m->ka, 0.0));
    TRY(ge(p, "kd", m->kd, 0.0));
    TRY(ge(p, "ks", m->ks, 0.0));
    TRY(ge(p, "alpha", m->alpha, 0.0));
    if ((int)m->shading < 0 || m->shading > CJ_SHADE_PHONG)
        return cj_fail(CJ_ERR_RANGE, "%s.shading %d is not a shading model", p, (int)m->shading);
    TRY(flag(p, "two_sided", m->two_sided));
    if (m->texture < -1 || (m->texture >= 0 && (size_t)m->texture >= ntextures))
        return cj_fail(CJ_ERR_ARGUMENT, "%s.texture %d names no texture (%zu textures)", p,
                       m->texture, ntextures);
    TRY(in01(p, "opacity", m->opacity));
    TRY(in01(p, "mirror", m->mirror));
    TRY(in01(p, "transmission", m->transmission));
    TRY(ge(p, "ior", m->ior, 1.0));
    TRY(ge(p, "glossiness", m->glossiness, 0.0));
    TRY(rgb(p, "emission", m->emission, CJ_SCENE_MAX_RADIANCE));
    TRY(flag(p, "receives_shadows", m->receives_shadows));
    if ((int)m->specular_model < 0 || m->specular_model > CJ_SPEC_PHONG)
        return cj_fail(CJ_ERR_RANGE, "%s.specular_model %d is not a specular model", p,
                       (int)m->specular_model);
    return CJ_OK;
}

static cj_status check_points(const char *p, const char *field, const double *pts, size_t count,
                              int dim) {
    if (!pts) return cj_fail(CJ_ERR_ARGUMENT, "%s.%s is missing", p, field);
    for (size_t i = 0; i < count; ++i)
        for (int k = 0; k < dim; ++k)
            if (!(fabs(pts[i * (size_t)dim + (size_t)k]) <= CJ_SCENE_MAX_COORD)) {
                const double v = pts[i * (size_t)dim + (size_t)k];
                if (!isfinite(v))
                    return cj_fail(CJ_ERR_NONFINITE, "%s.%s[%zu][%d] is not finite", p, field, i,
                                   k);
                return cj_fail(CJ_ERR_RANGE, "%s.%s[%zu][%d] = %g is beyond the limit of +-%g", p,
                               field, i, k, v, CJ_SCENE_MAX_COORD);
            }
    return CJ_OK;
}

/* A control net whose points all lie on one line (or coincide) spans no area: the patch has
 * none either. The rasterizer's tessellator would find it; the tracer would not, so both are
 * told here. */
static cj_status check_net_area(const char *p, const cj_patch *q) {
    const size_t n = cj_patch_point_count(q);
    const double *a = q->pts;
    double far = 0.0, d[3] = {0, 0, 0};
    for (size_t i = 1; i < n; ++i) {
        const double e[3] = {q->pts[3 * i] - a[0], q->pts[3 * i + 1] - a[1],
                             q->pts[3 * i + 2] - a[2]};
        const double l = sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]);
        if (l > far) far = l, memcpy(d, e, sizeof d);
    }
    double best = 0.0;
    for (size_t i = 1; far > 0.0 && i < n; ++i) {
        const double e[3] = {q->pts[3 * i] - a[0], q->pts[3 * i + 1] - a[1],
                             q->pts[3 * i + 2] - a[2]};
        const double c[3] = {d[1] * e[2] - d[2] * e[1], d[2] * e[0] - d[0] * e[2],
                             d[0] * e[1] - d[1] * e[0]};
        best = fmax(best, sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]));
    }
    if (!(best > 1e-12 * far * far))
        return cj_fail(CJ_ERR_DEGENERATE,
                       "%s is degenerate: its control points %s, so the surface has no area", p,
                       far > 0.0 ? "lie on one line" : "all coincide");
    return CJ_OK;
}

static cj_status check_weights(const char *p, const double *w, size_t count) {
    if (!w) return CJ_OK;
    for (size_t i = 0; i < count; ++i) {
        if (!isfinite(w[i]))
            return cj_fail(CJ_ERR_NONFINITE, "%s.weights[%zu] is not finite", p, i);
        if (!(w[i] > 0.0)) return cj_fail(CJ_ERR_RANGE, "%s.weights[%zu] must be > 0", p, i);
    }
    return CJ_OK;
}

static cj_status check_quadric(const cj_quadric *q, const char *p) {
    cj_quadric t;
    cj_status st;
    switch (q->kind) {
    case CJ_QUADRIC_ELLIPSOID:
        st = cj_quadric_ellipsoid(&t, q->a, q->b, q->c);
        break;
    case CJ_QUADRIC_HYPERBOLOID1:
        st = cj_quadric_hyperboloid1(&t, q->a, q->b, q->c, q->v0, q->v1);
        break;
    case CJ_QUADRIC_HYPERBOLOID2:
        st = cj_quadric_hyperboloid2(&t, q->a, q->b, q->c, q->lower, q->v1);
        break;
    case CJ_QUADRIC_CONE:
        st = cj_quadric_cone(&t, q->a, q->b, q->c, q->v0, q->v1);
        break;
    case CJ_QUADRIC_PARABOLOID:
        st = cj_quadric_paraboloid(&t, q->a, q->b, q->v1);
        break;
    case CJ_QUADRIC_HYPERBOLIC_PARABOLOID:
        st = cj_quadric_hyperbolic_paraboloid(&t, q->a, q->b, q->u0, q->u1, q->v0, q->v1);
        break;
    default:
        return cj_fail(CJ_ERR_RANGE, "%s.kind %d is not a quadric", p, (int)q->kind);
    }
    return relabel(st, p);
}

static cj_status check_profile(const char *p, int degree, const double *pts, const double *w) {
    if (degree < 1 || degree > CJ_BEZIER_MAX_DEGREE)
        return cj_fail(CJ_ERR_RANGE, "%s.degree must be in [1, %d]", p, CJ_BEZIER_MAX_DEGREE);
    TRY(check_points(p, "points", pts, (size_t)degree + 1, 2));
    return check_weights(p, w, (size_t)degree + 1);
}

static cj_status check_curve(const cj_geometry *g, const char *p) {
    const size_t n = g->u.curve.count;
    switch (g->u.curve.kind) {
    case CJ_CURVE_BEZIER:
    case CJ_CURVE_RATIONAL:
        if (g->u.curve.degree < 1 || g->u.curve.degree > CJ_BEZIER_MAX_DEGREE)
            return cj_fail(CJ_ERR_RANGE, "%s.degree must be in [1, %d]", p, CJ_BEZIER_MAX_DEGREE);
        if (n != (size_t)g->u.curve.degree + 1)
            return cj_fail(CJ_ERR_RANGE, "%s.points: a degree %d curve needs %d points, not %zu", p,
                           g->u.curve.degree, g->u.curve.degree + 1, n);
        if (g->u.curve.kind == CJ_CURVE_RATIONAL && !g->u.curve.weights)
            return cj_fail(CJ_ERR_ARGUMENT, "%s.weights is missing (rational curve)", p);
        TRY(check_weights(p, g->u.curve.kind == CJ_CURVE_RATIONAL ? g->u.curve.weights : NULL, n));
        break;
    case CJ_CURVE_SPLINE:
        if ((int)g->u.curve.spline < 0 || g->u.curve.spline > CJ_SPLINE_KOCHANEK_BARTELS)
            return cj_fail(CJ_ERR_RANGE, "%s.spline %d is not a spline kind", p,
                           (int)g->u.curve.spline);
        if (n < (g->u.curve.closed ? 3u : 2u))
            return cj_fail(CJ_ERR_RANGE, "%s.points: a%s spline needs at least %d points", p,
                           g->u.curve.closed ? " closed" : "n open", g->u.curve.closed ? 3 : 2);
        TRY(fin(p, "tension", g->u.curve.tension));
        TRY(fin(p, "continuity", g->u.curve.continuity));
        TRY(fin(p, "bias", g->u.curve.bias));
        break;
    default:
        return cj_fail(CJ_ERR_RANGE, "%s.kind %d is not a curve kind", p, (int)g->u.curve.kind);
    }
    TRY(check_points(p, "points", g->u.curve.pts, n, 3));
    TRY(flag(p, "closed", g->u.curve.closed));
    TRY(ge(p, "width_px", g->u.curve.width_px, 1.0));
    return rgb(p, "color", g->u.curve.color, -1.0);
}

static cj_status check_mesh(const cj_mesh *m, const char *p) {
    if (!m) return cj_fail(CJ_ERR_ARGUMENT, "%s.mesh is missing", p);
    if (m->triangle_count == 0) return cj_fail(CJ_ERR_EMPTY, "%s: the mesh has no triangles", p);
    TRY(check_points(p, "positions", m->positions, m->vertex_count, 3));
    TRY(check_points(p, "normals", m->normals, m->vertex_count, 3));
    TRY(check_points(p, "uvs", m->uvs, m->vertex_count, 2));
    for (size_t t = 0; t < 3 * m->triangle_count; ++t)
        if (m->triangles[t] >= m->vertex_count)
            return cj_fail(CJ_ERR_RANGE, "%s.triangles[%zu][%zu] = %u names no vertex (%zu)", p,
                           t / 3, t % 3, m->triangles[t], m->vertex_count);
    return CJ_OK;
}

static cj_status check_gen_cylinder(const cj_geometry *g, const char *p) {
    TRY(check_profile(p, g->u.gen_cylinder.degree, g->u.gen_cylinder.pts,
                      g->u.gen_cylinder.weights));
    cj_vec3 e1 = g->u.gen_cylinder.e1, e2 = g->u.gen_cylinder.e2, dir = g->u.gen_cylinder.dir;
    double v0 = g->u.gen_cylinder.v0, v1 = g->u.gen_cylinder.v1;
    TRY(vec(p, "origin", g->u.gen_cylinder.origin));
    TRY(nonzero(p, "e1", e1));
    TRY(nonzero(p, "e2", e2));
    TRY(nonzero(p, "dir", dir));
    TRY(fin(p, "v0", v0));
    TRY(fin(p, "v1", v1));
    if (!(v0 < v1)) return cj_fail(CJ_ERR_RANGE, "%s.v1 must be > v0", p);
    cj_vec3 n = cj_v3_cross(e1, e2);
    if (!(cj_v3_norm(n) > 1e-12 * cj_v3_norm(e1) * cj_v3_norm(e2)))
        return cj_fail(CJ_ERR_DEGENERATE, "%s.e2 must not be parallel to e1", p);
    if (!(fabs(cj_v3_dot(n, dir)) > 1e-12 * cj_v3_norm(n) * cj_v3_norm(dir)))
        return cj_fail(CJ_ERR_DEGENERATE, "%s.dir must not lie in the plane of e1, e2", p);
    return CJ_OK;
}

cj_status cj_scene_check_geometry_(const cj_geometry *g, const char *p) {
    switch (g->kind) {
    case CJ_GEOM_PATCHES:
        if (g->u.patches.count == 0 || !g->u.patches.patches)
            return cj_fail(CJ_ERR_EMPTY, "%s.patches is empty", p);
        for (size_t i = 0; i < g->u.patches.count; ++i) {
            const cj_patch *q = &g->u.patches.patches[i];
            if (q->deg_u < 1 || q->deg_v < 1 || q->deg_u > CJ_PATCH_MAX_DEGREE ||
                q->deg_v > CJ_PATCH_MAX_DEGREE)
                return cj_fail(CJ_ERR_RANGE, "%s.patches[%zu].degree must be in [1, %d]", p, i,
                               CJ_PATCH_MAX_DEGREE);
            char sub[96];
            snprintf(sub, sizeof sub, "%s.patches[%zu]", p, i);
            TRY(check_points(sub, "points", q->pts, cj_patch_point_count(q), 3));
            TRY(check_weights(sub, q->weights, cj_patch_point_count(q)));
            TRY(check_net_area(sub, q));
        }
        return CJ_OK;
    case CJ_GEOM_QUADRIC:
        return check_quadric(&g->u.quadric, p);
    case CJ_GEOM_SPHERE:
        TRY(vec(p, "center", g->u.sphere.center));
        TRY(coord(p, "radius", -1, g->u.sphere.radius));
        return gt(p, "radius", g->u.sphere.radius, 0.0);
    case CJ_GEOM_TORUS: {
        cj_torus t;
        const cj_torus *s = &g->u.torus;
        return relabel(cj_torus_init(&t, s->center, s->a, s->major, s->minor), p);
    }
    case CJ_GEOM_CYLINDER: {
        cj_cylinder t;
        const cj_cylinder *s = &g->u.cylinder;
        return relabel(cj_cylinder_init(&t, s->base, s->a, s->radius, s->h0, s->h1), p);
    }
    case CJ_GEOM_PLANAR: {
        cj_planar_patch t;
        const cj_planar_patch *s = &g->u.planar;
        return relabel(cj_planar_patch_init(&t, s->p, s->eu, s->ev), p);
    }
    case CJ_GEOM_BILINEAR: {
        cj_bilinear t;
        const cj_bilinear *s = &g->u.bilinear;
        return relabel(cj_bilinear_init(&t, s->p00, s->p10, s->p01, s->p11), p);
    }
    case CJ_GEOM_REVOLUTION:
        TRY(check_profile(p, g->u.revolution.degree, g->u.revolution.pts, g->u.revolution.weights));
        TRY(vec(p, "origin", g->u.revolution.origin));
        return nonzero(p, "axis", g->u.revolution.axis);
    case CJ_GEOM_GEN_CYLINDER:
        return check_gen_cylinder(g, p);
    case CJ_GEOM_MESH:
        return check_mesh(g->u.mesh, p);
    case CJ_GEOM_CURVE:
        return check_curve(g, p);
    default:
        return cj_fail(CJ_ERR_RANGE, "%s.kind %d is not a geometry kind", p, (int)g->kind);
    }
}

cj_status cj_scene_check_transform_(const cj_transform *t, const char *p) {
    TRY(vec(p, "translate", t->translate));
    const double *q = t->rotation;
    for (int k = 0; k < 4; ++k)
        if (!isfinite(q[k]))
            return cj_fail(CJ_ERR_NONFINITE, "%s.quaternion[%d] is not finite", p, k);
    double n2 = q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3];
    if (!(fabs(n2 - 1.0) <= 1e-9))
        return cj_fail(CJ_ERR_RANGE, "%s.quaternion must have unit length (|q|^2 = %.17g)", p, n2);
    TRY(vec(p, "scale", t->scale));
    if (t->scale.x == 0.0 || t->scale.y == 0.0 || t->scale.z == 0.0)
        return cj_fail(CJ_ERR_RANGE, "%s.scale must have non-zero components", p);
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j)
            if (!isfinite(t->matrix.m[i][j]))
                return cj_fail(CJ_ERR_NONFINITE, "%s.matrix[%d][%d] is not finite", p, i, j);
    if (!cj_xform3_is_affine(&t->matrix))
        return cj_fail(CJ_ERR_RANGE, "%s.matrix must be affine (last row 0 0 0 1)", p);
    const double(*m)[4] = t->matrix.m;
    double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                 m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                 m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    if (!(det != 0.0) || !isfinite(det))
        return cj_fail(CJ_ERR_DEGENERATE, "%s.matrix must be invertible", p);
    return CJ_OK;
}

cj_status cj_scene_check_overlay_(const cj_overlay_style *o, const char *p) {
    if (o->flags & ~15u)
        return cj_fail(CJ_ERR_RANGE, "%s.flags 0x%x has unknown bits", p, o->flags);
    TRY(rgb(p, "color", o->color, -1.0));
    if ((o->flags & CJ_OVERLAY_ISO_LINES) && o->iso_count < 1)
        return cj_fail(CJ_ERR_RANGE, "%s.iso_lines must be >= 1", p);
    if (o->flags & CJ_OVERLAY_NORMALS) TRY(gt(p, "normals", o->normal_length, 0.0));
    return CJ_OK;
}

cj_status cj_scene_check_node_(const cj_scene *s, const cj_node *n, size_t index, const char *p) {
    if (n->parent != -1) {
        if (n->parent < -1 || (size_t)n->parent >= index || n->parent >= (int)s->nnodes ||
            s->nodes[n->parent].geometry != -1)
            return cj_fail(CJ_ERR_ARGUMENT, "%s.parent %d names no group added before it", p,
                           n->parent);
    }
    char sub[96];
    snprintf(sub, sizeof sub, "%s.transform", p);
    TRY(cj_scene_check_transform_(&n->local, sub));
    if (n->geometry < -1 || (n->geometry >= 0 && (size_t)n->geometry >= s->ngeoms))
        return cj_fail(CJ_ERR_ARGUMENT, "%s.geometry %d names no geometry (%zu geometries)", p,
                       n->geometry, s->ngeoms);
    if (n->geometry >= 0) {
        if (n->material < 0 || (size_t)n->material >= s->nmaterials)
            return cj_fail(CJ_ERR_ARGUMENT, "%s.material %d names no material (%zu materials)", p,
                           n->material, s->nmaterials);
    } else if (n->material != -1) {
        return cj_fail(CJ_ERR_ARGUMENT, "%s.material must be -1 for a group", p);
    }
    snprintf(sub, sizeof sub, "%s.overlay", p);
    TRY(cj_scene_check_overlay_(&n->overlay, sub));
    return flag(p, "visible", n->visible);
}

cj_status cj_scene_check(const cj_scene *s) {
    assert(s != NULL);
    char p[64];
    TRY(cj_scene_check_camera_(&s->camera, "camera"));
    TRY(cj_scene_check_settings_(&s->settings, "settings"));
    for (size_t i = 0; i < s->nlights; ++i) {
        snprintf(p, sizeof p, "lights[%zu]", i);
        TRY(cj_scene_check_light_(&s->lights[i], p));
    }
    for (size_t i = 0; i < s->ntextures; ++i) {
        snprintf(p, sizeof p, "textures[%zu]", i);
        TRY(cj_scene_check_texture_(&s->textures[i], p));
    }
    for (size_t i = 0; i < s->nmaterials; ++i) {
        snprintf(p, sizeof p, "materials[%zu]", i);
        TRY(cj_scene_check_material_(&s->materials[i], s->ntextures, p));
    }
    for (size_t i = 0; i < s->ngeoms; ++i) {
        snprintf(p, sizeof p, "geometries[%zu]", i);
        TRY(cj_scene_check_geometry_(&s->geoms[i], p));
    }
    for (size_t i = 0; i < s->nnodes; ++i) {
        snprintf(p, sizeof p, "nodes[%zu]", i);
        TRY(cj_scene_check_node_(s, &s->nodes[i], i, p));
    }
    return CJ_OK;
}

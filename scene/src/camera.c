/* The camera (seed 6): frame, viewing transform, perspective/orthographic projection to clip
 * space, and the primary ray through an image point, all from one model so that the
 * rasterizer and the ray tracer see the same picture. */
#include "casteljau/scene.h"

#include "error_internal.h"

#include <assert.h>
#include <math.h>
#include <string.h>

cj_camera cj_camera_defaults(void) {
    cj_camera c;
    memset(&c, 0, sizeof c);
    c.eye = cj_v3(0.0, 0.0, 5.0);
    c.gaze = cj_v3(0.0, 0.0, -1.0);
    c.up = cj_v3(0.0, 1.0, 0.0);
    c.near = -0.1;
    c.far = -100.0;
    c.projection = CJ_PROJ_PERSPECTIVE;
    c.fov_y = 45.0 * (3.14159265358979323846 / 180.0);
    c.ortho_height = 2.0;
    return c;
}

/* The frame without validation of the scalar fields; CJ_ERR_DEGENERATE for a zero gaze or an
 * up vector (numerically) parallel to it. */
static cj_status frame(const cj_camera *cam, cj_vec3 *u, cj_vec3 *v, cj_vec3 *w) {
    const double g = cj_v3_norm(cam->gaze);
    if (!(g > 0.0)) return cj_fail(CJ_ERR_DEGENERATE, "camera gaze is the zero vector");
    const cj_vec3 ww = cj_v3_scale(cam->gaze, -1.0 / g);
    const double t = cj_v3_norm(cam->up);
    const cj_vec3 c = cj_v3_cross(cam->up, ww);
    const double cn = cj_v3_norm(c);
    /* sin(angle(up, gaze)) below ~1e-12: the side vector is dominated by rounding. */
    if (!(t > 0.0) || !(cn > 1e-12 * t))
        return cj_fail(CJ_ERR_DEGENERATE, "camera up (%g, %g, %g) is zero or parallel to the gaze",
                       cam->up.x, cam->up.y, cam->up.z);
    const cj_vec3 uu = cj_v3_scale(c, 1.0 / cn);
    *u = uu;
    *v = cj_v3_cross(ww, uu);
    *w = ww;
    return CJ_OK;
}

cj_status cj_camera_check(const cj_camera *cam) {
    assert(cam);
    if (!cj_v3_finite(cam->eye)) return cj_fail(CJ_ERR_NONFINITE, "camera eye is not finite");
    if (!cj_v3_finite(cam->gaze)) return cj_fail(CJ_ERR_NONFINITE, "camera gaze is not finite");
    if (!cj_v3_finite(cam->up)) return cj_fail(CJ_ERR_NONFINITE, "camera up is not finite");
    if (!isfinite(cam->near)) return cj_fail(CJ_ERR_NONFINITE, "camera near is not finite");
    if (!isfinite(cam->far)) return cj_fail(CJ_ERR_NONFINITE, "camera far is not finite");
    if (!(cam->near < 0.0))
        return cj_fail(CJ_ERR_RANGE, "camera near f = %g must be < 0 (the camera looks down -w)",
                       cam->near);
    if (!(cam->far < cam->near))
        return cj_fail(CJ_ERR_RANGE, "camera far F = %g must be < near f = %g", cam->far,
                       cam->near);
    switch (cam->projection) {
    case CJ_PROJ_PERSPECTIVE:
        if (!isfinite(cam->fov_y)) return cj_fail(CJ_ERR_NONFINITE, "camera fov_y is not finite");
        if (!(cam->fov_y > 0.0 && cam->fov_y < 3.14159265358979323846))
            return cj_fail(CJ_ERR_RANGE, "camera fov_y = %g must be in (0, pi) radians",
                           cam->fov_y);
        break;
    case CJ_PROJ_ORTHOGRAPHIC:
        if (!isfinite(cam->ortho_height))
            return cj_fail(CJ_ERR_NONFINITE, "camera ortho_height is not finite");
        if (!(cam->ortho_height > 0.0))
            return cj_fail(CJ_ERR_RANGE, "camera ortho_height = %g must be > 0", cam->ortho_height);
        break;
    default:
        return cj_fail(CJ_ERR_ARGUMENT, "camera projection %d is not a cj_projection",
                       (int)cam->projection);
    }
    if (!isfinite(cam->aperture) || !isfinite(cam->focus_distance))
        return cj_fail(CJ_ERR_NONFINITE, "camera aperture or focus_distance is not finite");
    if (cam->aperture < 0.0)
        return cj_fail(CJ_ERR_RANGE, "camera aperture = %g must be >= 0", cam->aperture);
    if (cam->aperture > 0.0 && !(cam->focus_distance > 0.0))
        return cj_fail(CJ_ERR_RANGE, "camera focus_distance = %g must be > 0 with an aperture",
                       cam->focus_distance);
    if (cam->aperture > 0.0 && cam->projection != CJ_PROJ_PERSPECTIVE)
        return cj_fail(CJ_ERR_RANGE, "camera aperture %g needs a perspective camera",
                       cam->aperture);
    cj_vec3 u, v, w;
    return frame(cam, &u, &v, &w);
}

cj_status cj_camera_basis(const cj_camera *cam, cj_vec3 *u, cj_vec3 *v, cj_vec3 *w) {
    assert(cam && u && v && w);
    cj_status st = cj_camera_check(cam);
    if (st != CJ_OK) return st;
    return frame(cam, u, v, w);
}

cj_status cj_camera_view(const cj_camera *cam, cj_xform3 *out) {
    assert(cam && out);
    cj_vec3 u, v, w;
    cj_status st = cj_camera_basis(cam, &u, &v, &w);
    if (st != CJ_OK) return st;
    /* Rows u, v, w: the rotation to camera axes after translating the eye to the origin. */
    const cj_vec3 r[3] = {u, v, w};
    cj_xform3 m;
    memset(&m, 0, sizeof m);
    for (int i = 0; i < 3; ++i) {
        m.m[i][0] = r[i].x;
        m.m[i][1] = r[i].y;
        m.m[i][2] = r[i].z;
        m.m[i][3] = -cj_v3_dot(r[i], cam->eye);
    }
    m.m[3][3] = 1.0;
    *out = m;
    return CJ_OK;
}

static cj_status check_aspect(double aspect) {
    if (!isfinite(aspect)) return cj_fail(CJ_ERR_NONFINITE, "camera aspect is not finite");
    if (!(aspect > 0.0)) return cj_fail(CJ_ERR_RANGE, "camera aspect = %g must be > 0", aspect);
    return CJ_OK;
}

cj_status cj_camera_projection(const cj_camera *cam, double aspect, cj_xform3 *out) {
    assert(cam && out);
    cj_status st = cj_camera_check(cam);
    if (st == CJ_OK) st = check_aspect(aspect);
    if (st != CJ_OK) return st;
    const double f = cam->near, F = cam->far;
    cj_xform3 m;
    memset(&m, 0, sizeof m);
    if (cam->projection == CJ_PROJ_PERSPECTIVE) {
        const double c = 1.0 / tan(0.5 * cam->fov_y);
        /* z_ndc = (A z + B)/(−z) with −1 at z = f and +1 at z = F:
         *   A f + B = f,  A F + B = −F  =>  A = (f + F)/(f − F),  B = −2 f F/(f − F). */
        m.m[0][0] = c / aspect;
        m.m[1][1] = c;
        m.m[2][2] = (f + F) / (f - F);
        m.m[2][3] = -2.0 * f * F / (f - F);
        m.m[3][2] = -1.0;
    } else {
        const double h = cam->ortho_height;
        m.m[0][0] = 2.0 / (h * aspect);
        m.m[1][1] = 2.0 / h;
        /* z_ndc = (2z − f − F)/(F − f): −1 at f, +1 at F. */
        m.m[2][2] = 2.0 / (F - f);
        m.m[2][3] = -(f + F) / (F - f);
        m.m[3][3] = 1.0;
    }
    *out = m;
    return CJ_OK;
}

cj_status cj_camera_world_to_clip(const cj_camera *cam, double aspect, cj_xform3 *out) {
    assert(cam && out);
    cj_xform3 p, v;
    cj_status st = cj_camera_projection(cam, aspect, &p);
    if (st == CJ_OK) st = cj_camera_view(cam, &v);
    if (st != CJ_OK) return st;
    *out = cj_xform3_compose(&p, &v);
    return CJ_OK;
}

cj_status cj_camera_ray(const cj_camera *cam, int width, int height, double px, double py,
                        cj_vec3 *origin, cj_vec3 *dir) {
    assert(cam && origin && dir);
    if (width < 1 || height < 1)
        return cj_fail(CJ_ERR_RANGE, "camera ray: image size %d x %d must be positive", width,
                       height);
    if (!isfinite(px) || !isfinite(py))
        return cj_fail(CJ_ERR_NONFINITE, "camera ray: image point (%g, %g) is not finite", px, py);
    cj_vec3 u, v, w;
    cj_status st = cj_camera_basis(cam, &u, &v, &w);
    if (st != CJ_OK) return st;
    const double aspect = (double)width / (double)height;
    /* The inverse of the viewport map sx = (x_ndc + 1)·width/2 used by the rasterizer. */
    const double xn = 2.0 * px / (double)width - 1.0;
    const double yn = 2.0 * py / (double)height - 1.0;
    if (cam->projection == CJ_PROJ_PERSPECTIVE) {
        /* x_ndc = x cot(fov/2)/(aspect·(−z)): the camera-space direction (x, y, −1). */
        const double t = tan(0.5 * cam->fov_y);
        const double dx = xn * aspect * t, dy = yn * t;
        cj_vec3 d =
            cj_v3_add(cj_v3_add(cj_v3_scale(u, dx), cj_v3_scale(v, dy)), cj_v3_scale(w, -1.0));
        *origin = cam->eye;
        *dir = cj_v3_scale(d, 1.0 / cj_v3_norm(d));
    } else {
        const double h = cam->ortho_height;
        const cj_vec3 off =
            cj_v3_add(cj_v3_scale(u, 0.5 * xn * h * aspect), cj_v3_scale(v, 0.5 * yn * h));
        *origin = cj_v3_add(cam->eye, off);
        *dir = cj_v3_scale(w, -1.0);
    }
    return CJ_OK;
}

cj_status cj_camera_lens_ray(const cj_camera *cam, int width, int height, double px, double py,
                             double lu, double lv, cj_vec3 *origin, cj_vec3 *dir) {
    cj_status st = cj_camera_ray(cam, width, height, px, py, origin, dir);
    if (st != CJ_OK || !(cam->aperture > 0.0)) return st;
    cj_vec3 u, v, w;
    st = cj_camera_basis(cam, &u, &v, &w);
    if (st != CJ_OK) return st;
    /* the pinhole ray meets the plane in focus at distance F along −w */
    const double along = -cj_v3_dot(*dir, w);
    const cj_vec3 focus = cj_v3_add(cam->eye, cj_v3_scale(*dir, cam->focus_distance / along));
    const double r = 0.5 * cam->aperture * sqrt(lu), phi = 2.0 * 3.14159265358979323846 * lv;
    *origin =
        cj_v3_add(cam->eye, cj_v3_add(cj_v3_scale(u, r * cos(phi)), cj_v3_scale(v, r * sin(phi))));
    const cj_vec3 d = cj_v3_sub(focus, *origin);
    *dir = cj_v3_scale(d, 1.0 / cj_v3_norm(d));
    return CJ_OK;
}

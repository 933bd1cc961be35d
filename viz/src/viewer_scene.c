/* The 3D editor model (casteljau/viewer_scene.h): editable control points of a scene, exact
 * picking, drags on the camera-facing plane or along an axis, the undo log, the orbit camera. */
#include "casteljau/viewer_scene.h"

#include "casteljau/scene_bspline.h"

#include "error_internal.h"
#include "viewer_internal.h"

#include <assert.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct vpt {
    int node, geom;
    double *p; /* 3 coordinates inside the scene's geometry */
    double *w; /* its weight (a NURBS surface's net point), or NULL */
} vpt;

/* One moved point; the consecutive entries of one command share `cmd` (a linked move of a
 * shared corner is several entries, undone and redone together). */
typedef struct vmove {
    double *p; /* 3 coordinates, or one weight (dim 1) */
    int dim;
    int geom; /* the geometry the point belongs to (a B-spline surface re-derives its patches) */
    double from[3], to[3];
    unsigned long cmd;
} vmove;

struct cj_vscene {
    cj_scene *scene;
    vpt *pts;
    size_t npts;
    cj_xform3 *world, *inv; /* per node */
    vmove *log;
    size_t nlog, pos, cap;
    unsigned long ncmd;
    int linked;   /* coincident points of one geometry move together (default on) */
    double **grp; /* scratch: the points moved by one command (npts capacity) */
    int drag_open, drag_merge;
    cj_vec3 drag_start; /* world position of the dragged point when the drag began */
    /* orbit camera */
    cj_vec3 target, up, f0, r0;
    double dist, az, el;
};

static cj_vec3 lv(const double *p) {
    return cj_v3(p[0], p[1], p[2]);
}

static cj_status collect(cj_vscene *vs) {
    const size_t nn = cj_scene_node_count(vs->scene);
    size_t cap = 0;
    vs->world = calloc(nn ? nn : 1, sizeof *vs->world);
    vs->inv = calloc(nn ? nn : 1, sizeof *vs->inv);
    if (!vs->world || !vs->inv) return cj_fail(CJ_ERR_NOMEM, "viewer: out of memory (nodes)");
    for (size_t n = 0; n < nn; ++n) {
        const cj_node *node = cj_scene_node(vs->scene, (int)n);
        cj_status st = cj_scene_node_world(vs->scene, (int)n, &vs->world[n]);
        if (st) return st;
        if (node->geometry < 0 || !cj_scene_node_shown(vs->scene, (int)n)) continue;
        cj_geometry *g = cj_scene_geometry_mut(vs->scene, node->geometry);
        /* A B-spline / NURBS surface is edited through its own control net (scene_bspline.h):
         * its Bezier patches are re-derived from it after every move. */
        const cj_bspline_surface *bsp = cj_scene_geometry_bspline(vs->scene, node->geometry);
        size_t add = 0;
        if (bsp)
            add = (size_t)bsp->npts_u * (size_t)bsp->npts_v;
        else if (g->kind == CJ_GEOM_PATCHES)
            for (size_t k = 0; k < g->u.patches.count; ++k)
                add += cj_patch_point_count(&g->u.patches.patches[k]);
        else if (g->kind == CJ_GEOM_CURVE)
            add = g->u.curve.count;
        if (!add) continue;
        if (cj_xform3_inverse(&vs->world[n], &vs->inv[n]))
            return cj_fail(CJ_ERR_SINGULAR, "viewer: node %zu has a singular world transform", n);
        if (vs->npts + add > cap) {
            cap = 2 * (vs->npts + add);
            vpt *np = realloc(vs->pts, cap * sizeof *np);
            if (!np) return cj_fail(CJ_ERR_NOMEM, "viewer: out of memory for control points");
            vs->pts = np;
        }
        /* The scene owns these arrays (cj_scene_add_geometry copied them); the editor writes
         * through the mutable geometry it was handed. */
        if (bsp) {
            for (size_t i = 0; i < add; ++i)
                vs->pts[vs->npts++] = (vpt){(int)n, node->geometry, (double *)bsp->pts + 3 * i,
                                            bsp->weights ? (double *)bsp->weights + i : NULL};
        } else if (g->kind == CJ_GEOM_PATCHES) {
            for (size_t k = 0; k < g->u.patches.count; ++k) {
                const cj_patch *pa = &g->u.patches.patches[k];
                for (size_t i = 0; i < cj_patch_point_count(pa); ++i)
                    vs->pts[vs->npts++] =
                        (vpt){(int)n, node->geometry, (double *)pa->pts + 3 * i, NULL};
            }
        } else {
            for (size_t i = 0; i < g->u.curve.count; ++i)
                vs->pts[vs->npts++] =
                    (vpt){(int)n, node->geometry, (double *)g->u.curve.pts + 3 * i, NULL};
        }
    }
    return CJ_OK;
}

static cj_status camera_write(cj_vscene *vs) {
    cj_camera cam = *cj_scene_get_camera(vs->scene);
    const double ce = cos(vs->el), se = sin(vs->el);
    cj_vec3 g =
        cj_v3_add(cj_v3_scale(vs->f0, ce * cos(vs->az)), cj_v3_scale(vs->r0, ce * sin(vs->az)));
    g = cj_v3_sub(g, cj_v3_scale(vs->up, se));
    cam.gaze = g;
    cam.eye = cj_v3_sub(vs->target, cj_v3_scale(g, vs->dist));
    cam.up = vs->up;
    return cj_scene_set_camera(vs->scene, &cam);
}

static void camera_init(cj_vscene *vs) {
    const cj_camera *cam = cj_scene_get_camera(vs->scene);
    const cj_vec3 g = cj_v3_normalize(cam->gaze);
    vs->up = cj_v3_normalize(cam->up);
    /* Target: the centre of the control points along the gaze (else 5 units ahead). */
    double d = 5.0;
    if (vs->npts) {
        cj_vec3 lo = cj_v3(INFINITY, INFINITY, INFINITY),
                hi = cj_v3(-INFINITY, -INFINITY, -INFINITY);
        for (size_t k = 0; k < vs->npts; ++k) {
            cj_vec3 w;
            cj_vscene_point(vs, k, &w);
            lo = cj_v3(fmin(lo.x, w.x), fmin(lo.y, w.y), fmin(lo.z, w.z));
            hi = cj_v3(fmax(hi.x, w.x), fmax(hi.y, w.y), fmax(hi.z, w.z));
        }
        const double dd = cj_v3_dot(cj_v3_sub(cj_v3_lerp(lo, hi, 0.5), cam->eye), g);
        if (dd > 1e-9) d = dd;
    }
    vs->dist = d;
    vs->target = cj_v3_add(cam->eye, cj_v3_scale(g, d));
    const double gu = cj_v3_dot(g, vs->up);
    cj_vec3 f = cj_v3_sub(g, cj_v3_scale(vs->up, gu));
    if (cj_v3_norm(f) < 1e-12)
        f = cj_v3_cross(vs->up, fabs(vs->up.x) < 0.9 ? cj_v3(1, 0, 0) : cj_v3(0, 1, 0));
    vs->f0 = cj_v3_normalize(f);
    vs->r0 = cj_v3_cross(vs->f0, vs->up);
    vs->az = 0.0;
    vs->el = asin(fmax(-1.0, fmin(1.0, -gu)));
}

cj_status cj_vscene_create(cj_scene *scene, cj_vscene **out) {
    assert(scene && out);
    cj_vscene *vs = calloc(1, sizeof *vs);
    if (!vs) {
        cj_scene_destroy(scene);
        return cj_fail(CJ_ERR_NOMEM, "viewer: out of memory for the scene editor");
    }
    vs->scene = scene;
    cj_status st = cj_scene_check(scene);
    if (!st) st = collect(vs);
    if (!st && !(vs->grp = malloc((vs->npts ? vs->npts : 1) * sizeof *vs->grp)))
        st = cj_fail(CJ_ERR_NOMEM, "viewer: out of memory for control points");
    if (st) {
        cj_vscene_destroy(vs);
        return st;
    }
    camera_init(vs);
    vs->linked = 1;
    *out = vs;
    return CJ_OK;
}

void cj_vscene_destroy(cj_vscene *vs) {
    if (!vs) return;
    cj_scene_destroy(vs->scene);
    free(vs->pts);
    free(vs->world);
    free(vs->inv);
    free(vs->log);
    free(vs->grp);
    free(vs);
}

cj_scene *cj_vscene_scene(cj_vscene *vs) {
    return vs->scene;
}
size_t cj_vscene_point_count(const cj_vscene *vs) {
    return vs->npts;
}
size_t cj_vscene_undo_depth(const cj_vscene *vs) {
    size_t n = 0;
    for (size_t i = 0; i < vs->pos; ++i) n += i == 0 || vs->log[i].cmd != vs->log[i - 1].cmd;
    return n;
}

void cj_vscene_set_linked(cj_vscene *vs, int on) {
    vs->linked = on != 0;
    vs->drag_merge = 0;
}
int cj_vscene_linked(const cj_vscene *vs) {
    return vs->linked;
}

/* The distinct points moved with point k into vs->grp (k's own first): with linking on, every
 * point of the same geometry at bit-identically the same place. Returns their number. */
static size_t group_of(const cj_vscene *vs, size_t k) {
    double *const p = vs->pts[k].p;
    size_t n = 0;
    vs->grp[n++] = p;
    if (!vs->linked) return n;
    for (size_t i = 0; i < vs->npts; ++i) {
        double *q = vs->pts[i].p;
        if (vs->pts[i].geom != vs->pts[k].geom || memcmp(q, p, 3 * sizeof *p)) continue;
        int seen = 0; /* a geometry shared by several nodes lists its points once per node */
        for (size_t j = 0; j < n && !seen; ++j) seen = vs->grp[j] == q;
        if (!seen) vs->grp[n++] = q;
    }
    return n;
}

size_t cj_vscene_shared_count(const cj_vscene *vs, size_t k) {
    return k < vs->npts ? group_of(vs, k) : 0;
}

cj_status cj_vscene_point(const cj_vscene *vs, size_t k, cj_vec3 *world) {
    if (k >= vs->npts)
        return cj_fail(CJ_ERR_ARGUMENT, "viewer: control point %zu does not exist (%zu)", k,
                       vs->npts);
    return cj_xform3_apply_point(&vs->world[vs->pts[k].node], lv(vs->pts[k].p), world);
}

int cj_vscene_point_node(const cj_vscene *vs, size_t k) {
    return k < vs->npts ? vs->pts[k].node : -1;
}

static int project(const cj_xform3 *clip, cj_vec3 w, int width, int height, double out[3]) {
    double c[4];
    const double in[4] = {w.x, w.y, w.z, 1.0};
    for (int r = 0; r < 4; ++r)
        c[r] = clip->m[r][0] * in[0] + clip->m[r][1] * in[1] + clip->m[r][2] * in[2] +
               clip->m[r][3] * in[3];
    if (!(c[3] > 0.0)) return 0;
    out[0] = (c[0] / c[3] + 1.0) * 0.5 * width;
    out[1] = (c[1] / c[3] + 1.0) * 0.5 * height;
    out[2] = c[2] / c[3];
    return 1;
}

int cj_vscene_project(const cj_vscene *vs, size_t k, int width, int height, double out[3]) {
    cj_xform3 clip;
    cj_vec3 w;
    if (cj_camera_world_to_clip(cj_scene_get_camera(vs->scene), (double)width / height, &clip))
        return 0;
    if (cj_vscene_point(vs, k, &w)) return 0;
    return project(&clip, w, width, height, out);
}

int cj_vscene_pick(const cj_vscene *vs, int width, int height, const float *depth, double px,
                   double py, double radius, size_t *k) {
    cj_xform3 clip;
    if (cj_camera_world_to_clip(cj_scene_get_camera(vs->scene), (double)width / height, &clip))
        return 0;
    int found = 0;
    double b[2] = {0, 0};
    for (size_t i = 0; i < vs->npts; ++i) {
        cj_vec3 w;
        double q[3];
        if (cj_vscene_point(vs, i, &w) || !project(&clip, w, width, height, q)) continue;
        if (!(q[2] >= -1.0 && q[2] <= 1.0)) continue; /* outside near/far */
        if (depth && q[0] >= 0 && q[1] >= 0 && q[0] < width && q[1] < height &&
            q[2] > depth[(size_t)q[1] * (size_t)width + (size_t)q[0]] + CJ_VSCENE_DEPTH_TOL)
            continue; /* behind a surface */
        if (!cj_vpick_within(q[0], q[1], px, py, radius)) continue;
        if (!found || cj_vpick_closer(q[0], q[1], b[0], b[1], px, py) < 0) {
            found = 1;
            b[0] = q[0], b[1] = q[1];
            *k = i;
        }
    }
    return found;
}

/* After points of geometry `geom` moved: a B-spline surface re-derives the patches that
 * changed (the others keep their bits, so the tessellation cache rebuilds only those). */
static cj_status moved(cj_vscene *vs, int geom) {
    if (!cj_scene_geometry_bspline(vs->scene, geom)) return CJ_OK;
    return cj_scene_bspline_refresh(vs->scene, geom, NULL, 0, NULL);
}

/* Moves the n points of vs->grp (of geometry `geom`) to `to`: one command, or the
 * continuation of the drag's command when the same points moved last. */
static cj_status log_moves(cj_vscene *vs, int geom, int dim, size_t n, const double *to) {
    int merge = vs->drag_merge && vs->pos == vs->nlog && vs->pos >= n;
    for (size_t i = 0; merge && i < n; ++i) {
        const vmove *m = &vs->log[vs->pos - n + i];
        merge = m->p == vs->grp[i] && m->dim == dim && m->cmd == vs->log[vs->pos - 1].cmd &&
                (vs->pos == n || vs->log[vs->pos - n - 1].cmd != m->cmd);
    }
    if (merge) {
        for (size_t i = 0; i < n; ++i) {
            memcpy(vs->log[vs->pos - n + i].to, to, (size_t)dim * sizeof *to);
            memcpy(vs->grp[i], to, (size_t)dim * sizeof *to);
        }
        return moved(vs, geom);
    }
    vs->nlog = vs->pos;
    if (vs->nlog + n > vs->cap) {
        size_t cap = vs->cap ? 2 * vs->cap : 64;
        while (cap < vs->nlog + n) cap *= 2;
        vmove *nl = realloc(vs->log, cap * sizeof *nl);
        if (!nl) return cj_fail(CJ_ERR_NOMEM, "viewer: out of memory for the undo log");
        vs->log = nl;
        vs->cap = cap;
    }
    const unsigned long cmd = ++vs->ncmd;
    for (size_t i = 0; i < n; ++i) {
        vmove *m = &vs->log[vs->nlog++];
        m->p = vs->grp[i];
        m->geom = geom;
        m->dim = dim;
        m->cmd = cmd;
        memcpy(m->from, m->p, (size_t)dim * sizeof *to);
        memcpy(m->to, to, (size_t)dim * sizeof *to);
        memcpy(m->p, to, (size_t)dim * sizeof *to);
    }
    vs->pos = vs->nlog;
    vs->drag_merge = vs->drag_open;
    return moved(vs, geom);
}

cj_status cj_vscene_set_point(cj_vscene *vs, size_t k, cj_vec3 world) {
    if (k >= vs->npts)
        return cj_fail(CJ_ERR_ARGUMENT, "viewer: control point %zu does not exist (%zu)", k,
                       vs->npts);
    if (!isfinite(world.x) || !isfinite(world.y) || !isfinite(world.z))
        return cj_fail(CJ_ERR_NONFINITE, "viewer: control point %zu moved to a non-finite place",
                       k);
    cj_vec3 local;
    cj_status st = cj_xform3_apply_point(&vs->inv[vs->pts[k].node], world, &local);
    if (st) return st;
    const double to[3] = {local.x, local.y, local.z};
    return log_moves(vs, vs->pts[k].geom, 3, group_of(vs, k), to);
}

int cj_vscene_point_weight(const cj_vscene *vs, size_t k, double *w) {
    if (k >= vs->npts || !vs->pts[k].w) return 0;
    *w = *vs->pts[k].w;
    return 1;
}

cj_status cj_vscene_set_weight(cj_vscene *vs, size_t k, double w) {
    if (k >= vs->npts || !vs->pts[k].w)
        return cj_fail(CJ_ERR_ARGUMENT,
                       "viewer: control point %zu has no weight (not a NURBS "
                       "surface's net point)",
                       k);
    if (!isfinite(w) || !(w > 0.0))
        return cj_fail(CJ_ERR_ARGUMENT, "viewer: weight %g of control point %zu must be > 0", w, k);
    /* the weights of the points moved with k: group_of lists positions, each maps to its own
     * weight */
    const size_t n = group_of(vs, k);
    for (size_t g = 0; g < n; ++g)
        for (size_t i = 0; i < vs->npts; ++i)
            if (vs->pts[i].p == vs->grp[g]) {
                vs->grp[g] = vs->pts[i].w;
                break;
            }
    vs->drag_merge = 0;
    return log_moves(vs, vs->pts[k].geom, 1, n, &w);
}

void cj_vscene_begin_drag(cj_vscene *vs) {
    vs->drag_open = 1;
    vs->drag_merge = 0;
    vs->drag_start = cj_v3(NAN, NAN, NAN);
}
void cj_vscene_end_drag(cj_vscene *vs) {
    vs->drag_open = vs->drag_merge = 0;
}

/* The point of the plane through p with normal n hit by the ray through pixel (px, py). */
static cj_status plane_hit(const cj_camera *cam, int w, int h, double px, double py, cj_vec3 p,
                           cj_vec3 n, cj_vec3 *out) {
    cj_vec3 o, d;
    cj_status st = cj_camera_ray(cam, w, h, px, py, &o, &d);
    if (st) return st;
    const double dn = cj_v3_dot(d, n);
    if (fabs(dn) < 1e-12)
        return cj_fail(CJ_ERR_DEGENERATE, "viewer: the cursor ray runs along the drag plane");
    *out = cj_v3_add(o, cj_v3_scale(d, cj_v3_dot(cj_v3_sub(p, o), n) / dn));
    return CJ_OK;
}

/* Parameter s of the point p + s a nearest to the ray through pixel (px, py). */
static cj_status axis_param(const cj_camera *cam, int w, int h, double px, double py, cj_vec3 p,
                            cj_vec3 a, double *s) {
    cj_vec3 o, d;
    cj_status st = cj_camera_ray(cam, w, h, px, py, &o, &d);
    if (st) return st;
    const cj_vec3 r = cj_v3_sub(p, o);
    const double ad = cj_v3_dot(a, d), den = 1.0 - ad * ad; /* |a| = |d| = 1 */
    if (den < 1e-12)
        return cj_fail(CJ_ERR_DEGENERATE, "viewer: the cursor ray runs along the drag axis");
    *s = (ad * cj_v3_dot(r, d) - cj_v3_dot(r, a)) / den;
    return CJ_OK;
}

cj_status cj_vscene_drag(cj_vscene *vs, size_t k, int width, int height, double px0, double py0,
                         double px1, double py1, int axis) {
    if (k >= vs->npts)
        return cj_fail(CJ_ERR_ARGUMENT, "viewer: control point %zu does not exist (%zu)", k,
                       vs->npts);
    if (axis < -1 || axis > 2)
        return cj_fail(CJ_ERR_ARGUMENT, "viewer: drag axis %d is not -1, 0, 1 or 2", axis);
    cj_vec3 p;
    cj_status st = cj_vscene_point(vs, k, &p);
    if (st) return st;
    /* The start of a drag is remembered so that every move is measured from it (no drift). */
    if (!vs->drag_open || isnan(vs->drag_start.x)) vs->drag_start = p;
    const cj_vec3 p0 = vs->drag_start;
    const cj_camera *cam = cj_scene_get_camera(vs->scene);
    cj_vec3 np;
    if (axis < 0) {
        const cj_vec3 n = cj_v3_normalize(cam->gaze);
        cj_vec3 h0, h1;
        if ((st = plane_hit(cam, width, height, px0, py0, p0, n, &h0))) return st;
        if ((st = plane_hit(cam, width, height, px1, py1, p0, n, &h1))) return st;
        np = cj_v3_add(p0, cj_v3_sub(h1, h0));
    } else {
        const cj_vec3 a = cj_v3(axis == 0, axis == 1, axis == 2);
        double s0, s1;
        if ((st = axis_param(cam, width, height, px0, py0, p0, a, &s0))) return st;
        if ((st = axis_param(cam, width, height, px1, py1, p0, a, &s1))) return st;
        np = cj_v3_add(p0, cj_v3_scale(a, s1 - s0));
    }
    return cj_vscene_set_point(vs, k, np);
}

cj_status cj_vscene_update(cj_vscene *vs) {
    for (size_t n = 0; n < cj_scene_node_count(vs->scene); ++n) {
        cj_status st = cj_scene_node_world(vs->scene, (int)n, &vs->world[n]);
        if (st) return st;
        if (cj_xform3_inverse(&vs->world[n], &vs->inv[n])) vs->inv[n] = cj_xform3_identity();
    }
    return CJ_OK;
}

cj_status cj_vscene_undo(cj_vscene *vs) {
    if (!vs->pos) return cj_fail(CJ_ERR_EMPTY, "viewer: nothing to undo");
    const unsigned long cmd = vs->log[vs->pos - 1].cmd;
    cj_status st = CJ_OK;
    while (vs->pos && vs->log[vs->pos - 1].cmd == cmd) {
        const vmove *m = &vs->log[--vs->pos];
        memcpy(m->p, m->from, (size_t)m->dim * sizeof *m->from);
        if (!st) st = moved(vs, m->geom);
    }
    vs->drag_merge = 0;
    return st;
}

cj_status cj_vscene_redo(cj_vscene *vs) {
    if (vs->pos == vs->nlog) return cj_fail(CJ_ERR_EMPTY, "viewer: nothing to redo");
    const unsigned long cmd = vs->log[vs->pos].cmd;
    cj_status st = CJ_OK;
    while (vs->pos < vs->nlog && vs->log[vs->pos].cmd == cmd) {
        const vmove *m = &vs->log[vs->pos++];
        memcpy(m->p, m->to, (size_t)m->dim * sizeof *m->to);
        if (!st) st = moved(vs, m->geom);
    }
    vs->drag_merge = 0;
    return st;
}

/* ---- camera ---------------------------------------------------------------------------- */

cj_status cj_vscene_orbit(cj_vscene *vs, double dx, double dy) {
    const double lim = 89.0 * 3.14159265358979323846 / 180.0;
    vs->az -= 0.01 * dx;
    vs->el = fmax(-lim, fmin(lim, vs->el + 0.01 * dy));
    return camera_write(vs);
}

cj_status cj_vscene_pan(cj_vscene *vs, double dx, double dy, int height) {
    const cj_camera *cam = cj_scene_get_camera(vs->scene);
    cj_vec3 u, v, w;
    cj_status st = cj_camera_basis(cam, &u, &v, &w);
    if (st) return st;
    const double world_h = cam->projection == CJ_PROJ_PERSPECTIVE
                               ? 2.0 * vs->dist * tan(0.5 * cam->fov_y)
                               : cam->ortho_height;
    const double s = world_h / (height > 0 ? height : 1);
    vs->target = cj_v3_add(vs->target, cj_v3_add(cj_v3_scale(u, -dx * s), cj_v3_scale(v, -dy * s)));
    return camera_write(vs);
}

cj_status cj_vscene_zoom(cj_vscene *vs, double factor) {
    if (!(factor > 0.0) || !isfinite(factor))
        return cj_fail(CJ_ERR_RANGE, "viewer: zoom factor %g is not positive", factor);
    cj_camera cam = *cj_scene_get_camera(vs->scene);
    if (cam.projection == CJ_PROJ_ORTHOGRAPHIC) {
        cam.ortho_height *= factor;
        cj_status st = cj_scene_set_camera(vs->scene, &cam);
        if (st) return st;
    } else {
        vs->dist *= factor;
    }
    return camera_write(vs);
}

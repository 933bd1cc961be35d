/* Geometry -> object-space triangles for the view: the screen tolerance turned into an object
 * tolerance per geometry, patches (and the surfaces that are exactly rational patches) through
 * the watertight tessellator, the other analytic surfaces on a grid chosen by a proven
 * second-derivative bound. */
#include "render_internal.h"

#include "casteljau/tessellate.h"
#include "error_internal.h"

#include <math.h>
#include <string.h>

/* Largest grid per direction of an analytic surface (a patch: half of it per patch). */
#define CJ_RENDER_MAX_GRID 1024

/* ---- the view ------------------------------------------------------------------------------ */

cj_status cj_rview_init(const cj_camera *cam, int width, int height, cj_rview *out) {
    memset(out, 0, sizeof *out);
    out->cam = *cam;
    out->width = width;
    out->height = height;
    double aspect = (double)width / (double)height;
    cj_status st = cj_camera_world_to_clip(cam, aspect, &out->world_to_clip);
    if (st) return st;
    st = cj_camera_view(cam, &out->world_to_cam);
    if (st) return st;
    out->eye = cam->eye;
    out->gaze_unit = cj_v3_normalize(cam->gaze);
    if (cam->projection == CJ_PROJ_PERSPECTIVE) {
        double ty = tan(0.5 * cam->fov_y), tx = ty * aspect;
        out->f_px = (double)height / (2.0 * ty);
        out->k = sqrt(1.0 + tx * tx + ty * ty);
    } else {
        out->px_ortho = cam->ortho_height / (double)height;
        out->k = 1.0;
    }
    return CJ_OK;
}

/* Perspective: a point of depth D >= d displaced by Δ (|Δ| <= δ) moves on screen by
 *   f_px |(ΔX, ΔY) − (X/D, Y/D) ΔZ| / (D + ΔZ) <= f_px k δ / (d − δ),
 * k = sqrt(1 + tx² + ty²) the norm of [[1,0,−X/D],[0,1,−Y/D]] for points in the view
 * (|X/D| <= tx, |Y/D| <= ty). Orthographic: δ / pixel size. */
double cj_rview_pixels(const cj_rview *v, double depth, double dist) {
    if (v->cam.projection != CJ_PROJ_PERSPECTIVE) return dist / v->px_ortho;
    if (depth <= dist) return INFINITY;
    return v->f_px * v->k * dist / (depth - dist);
}

double cj_rview_world_tol(const cj_rview *v, double depth, double tol_px) {
    if (v->cam.projection != CJ_PROJ_PERSPECTIVE) return tol_px * v->px_ortho;
    /* the largest δ with f_px k δ / (d − δ) <= tol_px, shaved by 1e-12 for rounding */
    return tol_px * depth / (v->f_px * v->k + tol_px) * (1.0 - 1e-12);
}

double cj_rview_pixel_size(const cj_rview *v, double depth) {
    if (v->cam.projection != CJ_PROJ_PERSPECTIVE) return v->px_ortho;
    return depth / v->f_px;
}

int cj_rview_box_depth(const cj_rview *v, const cj_xform3 *world, const double lo[3],
                       const double hi[3], double *depth) {
    unsigned outside_all = 0x3f;
    double dmin = INFINITY;
    for (int c = 0; c < 8; ++c) {
        double p[4] = {(c & 1) ? hi[0] : lo[0], (c & 2) ? hi[1] : lo[1], (c & 4) ? hi[2] : lo[2],
                       1.0};
        double wp[4], cl[4];
        for (int r = 0; r < 4; ++r)
            wp[r] = world->m[r][0] * p[0] + world->m[r][1] * p[1] + world->m[r][2] * p[2] +
                    world->m[r][3];
        for (int r = 0; r < 4; ++r)
            cl[r] = v->world_to_clip.m[r][0] * wp[0] + v->world_to_clip.m[r][1] * wp[1] +
                    v->world_to_clip.m[r][2] * wp[2] + v->world_to_clip.m[r][3];
        double zc = v->world_to_cam.m[2][0] * wp[0] + v->world_to_cam.m[2][1] * wp[1] +
                    v->world_to_cam.m[2][2] * wp[2] + v->world_to_cam.m[2][3];
        if (-zc < dmin) dmin = -zc;
        unsigned out = 0;
        if (cl[0] > cl[3]) out |= 1;
        if (cl[0] < -cl[3]) out |= 2;
        if (cl[1] > cl[3]) out |= 4;
        if (cl[1] < -cl[3]) out |= 8;
        if (cl[2] > cl[3]) out |= 16;
        if (cl[2] < -cl[3]) out |= 32;
        outside_all &= out;
    }
    if (outside_all) return 0; /* every corner beyond one plane: the box is outside */
    double dn = -v->cam.near;
    *depth = dmin > dn ? dmin : dn;
    return 1;
}

/* ---- surfaces that are exactly rational Bézier patches --------------------------------------- */

cj_status cj_render_geometry_patches(const cj_geometry *g, const cj_allocator *alloc,
                                     cj_patch **patches, size_t *count, double **pts, double **w) {
    const double h = sqrt(0.5);
    if (g->kind == CJ_GEOM_REVOLUTION) {
        /* S = o + r(v) C(u) + z(v) a with the unit circle C as four rational quadratic quarter
         * arcs (corner weight sqrt(1/2)): Σ c_i ω_j (o + r_j C_i + z_j a) B_i B_j / Σ c_i ω_j B_i
         * B_j = o + C(u) r(v) + z(v) a exactly (the sums factor). Shared quarter ends are built
         * from the same axis vector, so the seams are bit-identical. */
        int d = g->u.revolution.degree, np = 3 * (d + 1);
        cj_vec3 a = cj_v3_normalize(g->u.revolution.axis), e1, e2;
        cj_frame_from_axis(a, &e1, &e2);
        cj_vec3 E[5] = {e1, e2, cj_v3_scale(e1, -1.0), cj_v3_scale(e2, -1.0), e1};
        *pts = cj_ralloc(alloc, sizeof(double) * 3 * (size_t)np * 4);
        *w = cj_ralloc(alloc, sizeof(double) * (size_t)np * 4);
        *patches = cj_ralloc(alloc, sizeof(cj_patch) * 4);
        if (!*pts || !*w || !*patches)
            return cj_fail(CJ_ERR_NOMEM, "surface of revolution patches");
        cj_vec3 o = g->u.revolution.origin;
        for (int q = 0; q < 4; ++q) {
            cj_vec3 C[3] = {E[q], cj_v3_add(E[q], E[q + 1]), E[q + 1]};
            double c[3] = {1.0, h, 1.0};
            double *P = *pts + 3 * (size_t)np * q, *W = *w + (size_t)np * q;
            for (int j = 0; j <= d; ++j) {
                double r = g->u.revolution.pts[2 * j], z = g->u.revolution.pts[2 * j + 1];
                double om = g->u.revolution.weights ? g->u.revolution.weights[j] : 1.0;
                for (int i = 0; i < 3; ++i) {
                    cj_vec3 b = cj_v3_add(o, cj_v3_add(cj_v3_scale(C[i], r), cj_v3_scale(a, z)));
                    P[3 * (j * 3 + i) + 0] = b.x;
                    P[3 * (j * 3 + i) + 1] = b.y;
                    P[3 * (j * 3 + i) + 2] = b.z;
                    W[j * 3 + i] = c[i] * om;
                }
            }
            (*patches)[q] = cj_patch_view(2, d, P, W);
        }
        *count = 4;
        return CJ_OK;
    }
    if (g->kind == CJ_GEOM_GEN_CYLINDER) {
        /* S = o + x(u) e1 + y(u) e2 + v dir, v in [v0, v1]: degree (d, 1), rows v0 and v1. */
        int d = g->u.gen_cylinder.degree;
        *pts = cj_ralloc(alloc, sizeof(double) * 3 * (size_t)(d + 1) * 2);
        *w = g->u.gen_cylinder.weights ? cj_ralloc(alloc, sizeof(double) * (size_t)(d + 1) * 2)
                                       : NULL;
        *patches = cj_ralloc(alloc, sizeof(cj_patch));
        if (!*pts || (g->u.gen_cylinder.weights && !*w) || !*patches)
            return cj_fail(CJ_ERR_NOMEM, "general cylinder patch");
        for (int j = 0; j < 2; ++j) {
            double v = j ? g->u.gen_cylinder.v1 : g->u.gen_cylinder.v0;
            for (int i = 0; i <= d; ++i) {
                cj_vec3 b =
                    cj_v3_add(g->u.gen_cylinder.origin,
                              cj_v3_add(cj_v3_add(cj_v3_scale(g->u.gen_cylinder.e1,
                                                              g->u.gen_cylinder.pts[2 * i]),
                                                  cj_v3_scale(g->u.gen_cylinder.e2,
                                                              g->u.gen_cylinder.pts[2 * i + 1])),
                                        cj_v3_scale(g->u.gen_cylinder.dir, v)));
                double *P = *pts + 3 * (size_t)(j * (d + 1) + i);
                P[0] = b.x;
                P[1] = b.y;
                P[2] = b.z;
                if (*w) (*w)[j * (d + 1) + i] = g->u.gen_cylinder.weights[i];
            }
        }
        (*patches)[0] = cj_patch_view(d, 1, *pts, *w);
        *count = 1;
        return CJ_OK;
    }
    return cj_fail(CJ_ERR_ARGUMENT, "geometry kind %d is not a patch surface", (int)g->kind);
}

/* ---- analytic surfaces: proven second-derivative bounds and bounding boxes ------------------- */

static void box_points(cj_rsurf *si, const cj_vec3 *p, int n) {
    for (int k = 0; k < 3; ++k) {
        si->lo[k] = INFINITY;
        si->hi[k] = -INFINITY;
    }
    for (int i = 0; i < n; ++i) {
        double c[3] = {p[i].x, p[i].y, p[i].z};
        for (int k = 0; k < 3; ++k) {
            if (c[k] < si->lo[k]) si->lo[k] = c[k];
            if (c[k] > si->hi[k]) si->hi[k] = c[k];
        }
    }
}

static void box_sym(cj_rsurf *si, double rx, double ry, double z0, double z1) {
    si->lo[0] = -rx;
    si->hi[0] = rx;
    si->lo[1] = -ry;
    si->hi[1] = ry;
    si->lo[2] = z0 < z1 ? z0 : z1;
    si->hi[2] = z0 < z1 ? z1 : z0;
}

/* |S_uu|, |S_uv|, |S_vv| bounds from the parametrisations of quadric.h / analytic.h. */
static cj_status quadric_info(const cj_quadric *q, cj_rsurf *si) {
    double ab = q->a > q->b ? q->a : q->b, c = q->c;
    double vm = fabs(q->v0) > fabs(q->v1) ? fabs(q->v0) : fabs(q->v1);
    cj_quadric_surface(q, &si->s);
    switch (q->kind) {
    case CJ_QUADRIC_ELLIPSOID: /* S_uu = −cos v (a cos u, b sin u, 0), S_vv = −S */
        si->muu = ab;
        si->muv = ab;
        si->mvv = ab > c ? ab : c;
        box_sym(si, q->a, q->b, -c, c);
        break;
    case CJ_QUADRIC_HYPERBOLOID1:
        si->muu = ab * cosh(vm);
        si->muv = ab * sinh(vm);
        si->mvv = hypot(ab * cosh(vm), c * sinh(vm));
        box_sym(si, q->a * cosh(vm), q->b * cosh(vm), c * sinh(q->v0), c * sinh(q->v1));
        break;
    case CJ_QUADRIC_HYPERBOLOID2:
        si->muu = ab * sinh(vm);
        si->muv = ab * cosh(vm);
        si->mvv = hypot(ab * sinh(vm), c * cosh(vm));
        if (q->lower)
            box_sym(si, q->a * sinh(vm), q->b * sinh(vm), -c, -c * cosh(vm));
        else
            box_sym(si, q->a * sinh(vm), q->b * sinh(vm), c, c * cosh(vm));
        break;
    case CJ_QUADRIC_CONE:
        si->muu = ab * vm;
        si->muv = ab;
        si->mvv = 0.0;
        box_sym(si, q->a * vm, q->b * vm, c * q->v0, c * q->v1);
        break;
    case CJ_QUADRIC_PARABOLOID:
        si->muu = ab * vm;
        si->muv = ab;
        si->mvv = 2.0;
        box_sym(si, q->a * vm, q->b * vm, 0.0, vm * vm);
        break;
    case CJ_QUADRIC_HYPERBOLIC_PARABOLOID: {
        si->muu = 2.0;
        si->muv = 0.0;
        si->mvv = 2.0;
        double um = fabs(q->u0) > fabs(q->u1) ? fabs(q->u0) : fabs(q->u1);
        si->lo[0] = q->a * q->u0;
        si->hi[0] = q->a * q->u1;
        si->lo[1] = q->b * q->v0;
        si->hi[1] = q->b * q->v1;
        si->lo[2] = -vm * vm;
        si->hi[2] = um * um;
        break;
    }
    default:
        return cj_fail(CJ_ERR_ARGUMENT, "unknown quadric kind %d", (int)q->kind);
    }
    return CJ_OK;
}

cj_status cj_rsurf_init(const cj_geometry *g, cj_rsurf *si) {
    memset(si, 0, sizeof *si);
    switch (g->kind) {
    case CJ_GEOM_QUADRIC:
        return quadric_info(&g->u.quadric, si);
    case CJ_GEOM_SPHERE: {
        double r = g->u.sphere.radius;
        cj_status st = cj_quadric_ellipsoid(&si->q, r, r, r);
        if (st) return st;
        st = quadric_info(&si->q, si);
        si->offset = g->u.sphere.center;
        for (int k = 0; k < 3; ++k) {
            double c = k == 0   ? g->u.sphere.center.x
                       : k == 1 ? g->u.sphere.center.y
                                : g->u.sphere.center.z;
            si->lo[k] += c;
            si->hi[k] += c;
        }
        return st; /* the centre is applied by the caller's transform */
    }
    case CJ_GEOM_TORUS: {
        const cj_torus *t = &g->u.torus;
        cj_torus_surface(t, &si->s);
        si->muu = t->major + t->minor; /* S_uu = −(R + ρ cos v) e_r */
        si->muv = t->minor;            /* S_uv = −ρ sin v e_θ */
        si->mvv = t->minor;            /* S_vv = −ρ (cos v e_r + sin v a) */
        double R = t->major + t->minor;
        cj_vec3 c = t->center;
        si->lo[0] = c.x - R;
        si->hi[0] = c.x + R;
        si->lo[1] = c.y - R;
        si->hi[1] = c.y + R;
        si->lo[2] = c.z - R;
        si->hi[2] = c.z + R;
        return CJ_OK;
    }
    case CJ_GEOM_CYLINDER: {
        const cj_cylinder *cy = &g->u.cylinder;
        cj_cylinder_surface(cy, &si->s);
        si->muu = cy->radius; /* S_uu = −radius e_r; S_uv = S_vv = 0 */
        cj_vec3 p[8];         /* the circles lie inside squares of side 2 radius */
        for (int i = 0; i < 8; ++i) {
            double sx = (i & 1) ? cy->radius : -cy->radius, sy = (i & 2) ? cy->radius : -cy->radius;
            cj_vec3 off = cj_v3_add(cj_v3_scale(cy->e1, sx), cj_v3_scale(cy->e2, sy));
            p[i] =
                cj_v3_add(cj_v3_add(cy->base, off), cj_v3_scale(cy->a, (i & 4) ? cy->h1 : cy->h0));
        }
        box_points(si, p, 8);
        return CJ_OK;
    }
    case CJ_GEOM_PLANAR: {
        const cj_planar_patch *pp = &g->u.planar;
        cj_planar_patch_surface(pp, &si->s);
        cj_vec3 p[4] = {pp->p, cj_v3_add(pp->p, pp->eu), cj_v3_add(pp->p, pp->ev),
                        cj_v3_add(cj_v3_add(pp->p, pp->eu), pp->ev)};
        box_points(si, p, 4);
        return CJ_OK;
    }
    case CJ_GEOM_BILINEAR: {
        const cj_bilinear *bl = &g->u.bilinear;
        cj_bilinear_surface(bl, &si->s);
        si->muv = cj_v3_norm(cj_v3_sub(cj_v3_add(bl->p11, bl->p00), cj_v3_add(bl->p10, bl->p01)));
        cj_vec3 p[4] = {bl->p00, bl->p10, bl->p01, bl->p11};
        box_points(si, p, 4);
        return CJ_OK;
    }
    default:
        return cj_fail(CJ_ERR_ARGUMENT, "geometry kind %d is not an analytic surface",
                       (int)g->kind);
    }
}

/* The smallest uniform grid (nu, nv) whose cells meet (Muu hu² + 2 Muv hu hv + Mvv hv²)/8 <= tol:
 * with hu <= sqrt(4 tol / (Muu + Muv)) and hv <= sqrt(4 tol / (Mvv + Muv)), the AM-GM step
 * 2 hu hv <= hu² + hv² gives bound <= tol; the exact bound of the grid taken is returned. */
static cj_status choose_grid(const cj_rsurf *si, double tol, int *nu, int *nv, double *bound) {
    double lu = si->s.u1 - si->s.u0, lv = si->s.v1 - si->s.v0;
    double cu = si->muu + si->muv, cv = si->mvv + si->muv;
    double nu_d = ceil(lu * sqrt(cu / (4.0 * tol))), nv_d = ceil(lv * sqrt(cv / (4.0 * tol)));
    int min_u = (si->s.flags & CJ_SURF_PERIODIC_U) ? 3 : 1;
    int min_v = (si->s.flags & CJ_SURF_PERIODIC_V) ? 3 : 1;
    if ((si->s.flags & CJ_SURF_COLLAPSED_V0) && (si->s.flags & CJ_SURF_COLLAPSED_V1)) min_v = 2;
    if ((si->s.flags & CJ_SURF_COLLAPSED_U0) && (si->s.flags & CJ_SURF_COLLAPSED_U1)) min_u = 2;
    /* geometry reaching the near plane can ask for absurd grids: cap them, and report the
     * bound of the grid used (then above tol; the stage report shows it) */
    if (!(nu_d <= CJ_RENDER_MAX_GRID)) nu_d = CJ_RENDER_MAX_GRID;
    if (!(nv_d <= CJ_RENDER_MAX_GRID)) nv_d = CJ_RENDER_MAX_GRID;
    *nu = nu_d < min_u ? min_u : (int)nu_d;
    *nv = nv_d < min_v ? min_v : (int)nv_d;
    double hu = lu / *nu, hv = lv / *nv;
    *bound = (si->muu * hu * hu + 2.0 * si->muv * hu * hv + si->mvv * hv * hv) / 8.0;
    return CJ_OK;
}

/* ---- one object ------------------------------------------------------------------------------ */

static cj_status patches_mesh(const cj_patch *pt, size_t n, const cj_robject *o,
                              const cj_rview *view, double tol_px, cj_render_cache *cache,
                              cj_mesh *mesh, double *tol_obj, double *bound, size_t *patches,
                              size_t *culled, int *skip, int *hit, cj_tess_cache_stats *cache_work,
                              const cj_allocator *alloc) {
    cj_patch *vis = cj_ralloc(alloc, sizeof(cj_patch) * (n ? n : 1));
    if (!vis) return cj_fail(CJ_ERR_NOMEM, "patch list of %zu", n);
    size_t nv = 0;
    double dmin = INFINITY;
    for (size_t i = 0; i < n; ++i) {
        double lo[3], hi[3], d;
        cj_status st = cj_patch_bbox(&pt[i], lo, hi);
        if (st) {
            cj_rfree(alloc, vis);
            return st;
        }
        if (!cj_rview_box_depth(view, &o->world, lo, hi, &d)) continue;
        vis[nv++] = pt[i];
        if (d < dmin) dmin = d;
    }
    *patches += n;
    *culled += n - nv;
    if (nv == 0) {
        cj_rfree(alloc, vis);
        *skip = 1;
        return CJ_OK;
    }
    cj_tess_options opt;
    memset(&opt, 0, sizeof opt);
    opt.tol = cj_rview_world_tol(view, dmin, tol_px) / o->sigma;
    cj_tess_report rep;
    /* a patch set reaching the near plane can need more than the per-patch cap: relax the
     * tolerance 4x at a time (the bound reported is the one reached, then above tol_px) */
    opt.max_segments = CJ_RENDER_MAX_GRID / 2;
    size_t v0 = mesh->vertex_count, t0 = mesh->triangle_count;
    cj_status st;
    for (int attempt = 0;; ++attempt) {
        if (cache) { /* incremental, within the tolerance band (render_cache.c) */
            cj_tess_cache_stats w;
            st = cj_rcache_tessellate(cache, o->node, vis, nv, &opt, mesh, &rep, &w);
            if (!st) {
                *hit = w.planned == 0 && w.built == 0;
                cache_work->planned += w.planned;
                cache_work->plans_reused += w.plans_reused;
                cache_work->built += w.built;
                cache_work->pieces_reused += w.pieces_reused;
            }
        } else {
            st = cj_tessellate_patches(vis, nv, &opt, mesh, &rep);
        }
        if (st != CJ_ERR_CAP || attempt == 12) break;
        cj_mesh_truncate(mesh, v0, t0);
        opt.tol *= 4.0;
    }
    cj_rfree(alloc, vis);
    if (st) return st;
    *tol_obj = opt.tol;
    /* the bound in pixels at the nearest depth (every patch was held to that tolerance) */
    *bound = cj_rview_pixels(view, dmin, rep.bound * o->sigma);
    return CJ_OK;
}

cj_status cj_render_geometry_mesh(const cj_geometry *g, const cj_robject *o, const cj_rview *view,
                                  double tol_px, cj_render_cache *cache, cj_mesh *mesh,
                                  double *tol_obj, double *bound, int *nu, int *nv, size_t *patches,
                                  size_t *culled, int *skip, int *cache_hit,
                                  cj_tess_cache_stats *cache_work) {
    *skip = 0;
    *cache_hit = 0;
    *bound = 0.0;
    *nu = *nv = 0;
    cj_allocator a = mesh->alloc_;
    switch (g->kind) {
    case CJ_GEOM_PATCHES:
        return patches_mesh(g->u.patches.patches, g->u.patches.count, o, view, tol_px, cache, mesh,
                            tol_obj, bound, patches, culled, skip, cache_hit, cache_work, &a);
    case CJ_GEOM_REVOLUTION:
    case CJ_GEOM_GEN_CYLINDER: {
        cj_patch *pt = NULL;
        double *pts = NULL, *w = NULL;
        size_t n = 0;
        cj_status st = cj_render_geometry_patches(g, &a, &pt, &n, &pts, &w);
        if (!st)
            st = patches_mesh(pt, n, o, view, tol_px, cache, mesh, tol_obj, bound, patches, culled,
                              skip, cache_hit, cache_work, &a);
        cj_rfree(&a, pt);
        cj_rfree(&a, pts);
        cj_rfree(&a, w);
        return st;
    }
    case CJ_GEOM_MESH:
    case CJ_GEOM_CURVE:
        return CJ_OK; /* handled by the caller */
    default: {
        cj_rsurf si;
        cj_status st = cj_rsurf_init(g, &si);
        if (st) return st;
        double d;
        if (!cj_rview_box_depth(view, &o->world, si.lo, si.hi, &d)) {
            *skip = 1;
            return CJ_OK;
        }
        double tol = cj_rview_world_tol(view, d, tol_px) / o->sigma, b = 0.0;
        st = choose_grid(&si, tol, nu, nv, &b);
        if (st) return st;
        *tol_obj = tol;
        *bound = cj_rview_pixels(view, d, b * o->sigma);
        if (g->kind == CJ_GEOM_SPHERE) {
            /* the ellipsoid is centred at the origin: move its vertices to the centre */
            size_t v0 = mesh->vertex_count;
            st = cj_tessellate_surface(&si.s, *nu, *nv, (int32_t)o->id, mesh, NULL);
            if (st) return st;
            for (size_t i = v0; i < mesh->vertex_count; ++i) {
                mesh->positions[3 * i] += g->u.sphere.center.x;
                mesh->positions[3 * i + 1] += g->u.sphere.center.y;
                mesh->positions[3 * i + 2] += g->u.sphere.center.z;
            }
            return CJ_OK;
        }
        return cj_tessellate_surface(&si.s, *nu, *nv, (int32_t)o->id, mesh, NULL);
    }
    }
}

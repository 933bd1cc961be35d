/* Scene -> world-space triangles: node hierarchy, per-object tessellation for the view
 * (render_geom.c), world transform of positions/normals/(u,v), back-face culling in world
 * space (seed 7.2). */
#include "render_internal.h"
#include "render_scene.h"

#include "casteljau/mesh.h"
#include "error_internal.h"

#include <math.h>
#include <string.h>

static cj_status grow(const cj_allocator *a, void **p, size_t *cap, size_t need, size_t elem,
                      int count_arrays, void **extra[], const size_t extra_elem[]) {
    if (need <= *cap) return CJ_OK;
    size_t nc = *cap ? *cap : 1024;
    while (nc < need) nc *= 2;
    void *np = cj_ralloc(a, nc * elem);
    if (!np) return cj_fail(CJ_ERR_NOMEM, "render buffers of %zu elements", nc);
    if (*p) memcpy(np, *p, *cap * elem);
    for (int k = 0; k < count_arrays; ++k) {
        if (!*extra[k]) continue;
        void *ne = cj_ralloc(a, nc * extra_elem[k]);
        if (!ne) {
            cj_rfree(a, np);
            return cj_fail(CJ_ERR_NOMEM, "render buffers of %zu elements", nc);
        }
        memcpy(ne, *extra[k], *cap * extra_elem[k]);
        cj_rfree(a, *extra[k]);
        *extra[k] = ne;
    }
    cj_rfree(a, *p);
    *p = np;
    *cap = nc;
    return CJ_OK;
}

cj_status cj_rbuild_add_vertex(cj_rbuild *b, const double p[3], const float n[3], const float uv[2],
                               uint32_t *index) {
    if (b->vertex_count == b->vertex_cap) {
        if (b->vertex_count >= 0xfffffff0u) return cj_fail(CJ_ERR_CAP, "more than 2^32 vertices");
        void **extra[2] = {(void **)&b->nrm, (void **)&b->uv};
        size_t ee[2] = {3 * sizeof(float), 2 * sizeof(float)};
        cj_status st = grow(&b->alloc, (void **)&b->pos, &b->vertex_cap, b->vertex_count + 1,
                            3 * sizeof(double), 2, extra, ee);
        if (st) return st;
    }
    size_t i = b->vertex_count++;
    memcpy(b->pos + 3 * i, p, 3 * sizeof(double));
    if (b->nrm) {
        if (n)
            memcpy(b->nrm + 3 * i, n, 3 * sizeof(float));
        else
            memset(b->nrm + 3 * i, 0, 3 * sizeof(float));
    }
    if (b->uv) {
        if (uv)
            memcpy(b->uv + 2 * i, uv, 2 * sizeof(float));
        else
            memset(b->uv + 2 * i, 0, 2 * sizeof(float));
    }
    if (index) *index = (uint32_t)i;
    return CJ_OK;
}

/* Room for `vertices` more vertices and `tris` more triangles in one step each (an object's
 * counts are known before it is appended: no doubling and copying per 1024 elements). */
static cj_status reserve(cj_rbuild *b, size_t vertices, size_t tris) {
    if (b->vertex_count + vertices > b->vertex_cap) {
        if (b->vertex_count + vertices >= 0xfffffff0u)
            return cj_fail(CJ_ERR_CAP, "more than 2^32 vertices");
        void **extra[2] = {(void **)&b->nrm, (void **)&b->uv};
        size_t ee[2] = {3 * sizeof(float), 2 * sizeof(float)};
        cj_status st = grow(&b->alloc, (void **)&b->pos, &b->vertex_cap, b->vertex_count + vertices,
                            3 * sizeof(double), 2, extra, ee);
        if (st) return st;
    }
    if (b->tri_count + tris > b->tri_cap) {
        void **extra[1] = {(void **)&b->tobj};
        size_t ee[1] = {sizeof(uint32_t)};
        cj_status st = grow(&b->alloc, (void **)&b->tris, &b->tri_cap, b->tri_count + tris,
                            3 * sizeof(uint32_t), 1, extra, ee);
        if (st) return st;
    }
    return CJ_OK;
}

cj_status cj_rbuild_add_tri(cj_rbuild *b, uint32_t a, uint32_t c, uint32_t d, uint32_t obj) {
    if (b->tri_count == b->tri_cap) {
        void **extra[1] = {(void **)&b->tobj};
        size_t ee[1] = {sizeof(uint32_t)};
        cj_status st = grow(&b->alloc, (void **)&b->tris, &b->tri_cap, b->tri_count + 1,
                            3 * sizeof(uint32_t), 1, extra, ee);
        if (st) return st;
    }
    size_t t = b->tri_count++;
    b->tris[3 * t] = a;
    b->tris[3 * t + 1] = c;
    b->tris[3 * t + 2] = d;
    b->tobj[t] = obj;
    return CJ_OK;
}

void cj_rbuild_free(cj_rbuild *b) {
    cj_rfree(&b->alloc, b->pos);
    cj_rfree(&b->alloc, b->nrm);
    cj_rfree(&b->alloc, b->uv);
    cj_rfree(&b->alloc, b->tris);
    cj_rfree(&b->alloc, b->tobj);
    cj_rfree(&b->alloc, b->objects);
    memset(b, 0, sizeof *b);
}

/* Largest singular value of the 3x3 linear part: sqrt of the largest eigenvalue of LᵀL (closed
 * form for symmetric 3x3), never above the Gershgorin bound, inflated for rounding. */
static double spectral_norm(const cj_xform3 *m) {
    double A[3][3];
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            A[i][j] = 0.0;
            for (int k = 0; k < 3; ++k) A[i][j] += m->m[k][i] * m->m[k][j];
        }
    double gersh = 0.0;
    for (int i = 0; i < 3; ++i) {
        double s = fabs(A[i][0]) + fabs(A[i][1]) + fabs(A[i][2]);
        if (s > gersh) gersh = s;
    }
    double p1 = A[0][1] * A[0][1] + A[0][2] * A[0][2] + A[1][2] * A[1][2];
    double q = (A[0][0] + A[1][1] + A[2][2]) / 3.0, lmax;
    double p2 = (A[0][0] - q) * (A[0][0] - q) + (A[1][1] - q) * (A[1][1] - q) +
                (A[2][2] - q) * (A[2][2] - q) + 2.0 * p1;
    if (p2 <= 0.0) {
        lmax = q;
    } else {
        double p = sqrt(p2 / 6.0), B[3][3];
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) B[i][j] = (A[i][j] - (i == j ? q : 0.0)) / p;
        double r = (B[0][0] * (B[1][1] * B[2][2] - B[1][2] * B[2][1]) -
                    B[0][1] * (B[1][0] * B[2][2] - B[1][2] * B[2][0]) +
                    B[0][2] * (B[1][0] * B[2][1] - B[1][1] * B[2][0])) /
                   2.0;
        r = r < -1.0 ? -1.0 : r > 1.0 ? 1.0 : r;
        lmax = q + 2.0 * p * cos(acos(r) / 3.0);
    }
    lmax *= 1.0 + 1e-9;
    if (lmax > gersh) lmax = gersh;
    return sqrt(lmax) * (1.0 + 1e-12);
}

static cj_status object_setup(const cj_rscene *rs, int node, cj_robject *o) {
    const cj_node *nd = cj_scene_node(rs->scene, node);
    memset(o, 0, sizeof *o);
    o->node = node;
    o->material = nd->material;
    o->id = nd->id;
    o->geometry = nd->geometry;
    o->world = rs->world[node];
    double(*m)[4] = o->world.m;
    o->det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
             m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
             m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    if (!(fabs(o->det) > 0.0) || !isfinite(o->det))
        return cj_fail(CJ_ERR_SINGULAR, "nodes[%d]: world transform is singular", node);
    cj_xform3 inv;
    cj_status st = cj_xform3_inverse(&o->world, &inv);
    if (st) return st;
    o->normal = cj_xform3_identity();
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) o->normal.m[i][j] = inv.m[j][i];
    o->sigma = spectral_norm(&o->world);
    return CJ_OK;
}

static cj_status append_object(cj_rbuild *b, const cj_scene *scene, const cj_mesh *mesh,
                               uint32_t oi, int want_n, int want_uv, int cull,
                               const cj_rview *view) {
    cj_robject *o = &b->objects[oi];
    const cj_material *mat = o->material >= 0 ? cj_scene_material(scene, o->material) : NULL;
    int one_sided = cull && !(mat && mat->two_sided);
    o->v0 = b->vertex_count;
    double t0 = cj_render_now();
    cj_status rs = reserve(b, mesh->vertex_count, mesh->triangle_count);
    if (rs) return rs;
    /* meshes without normals: accumulate area-weighted face normals */
    double *acc = NULL;
    int has_n = 0;
    for (size_t i = 0; i < mesh->vertex_count * 3 && !has_n; ++i)
        if (mesh->normals[i] != 0.0) has_n = 1;
    if (want_n && !has_n && mesh->vertex_count) {
        acc = cj_ralloc(&b->alloc, sizeof(double) * 3 * mesh->vertex_count);
        if (!acc) return cj_fail(CJ_ERR_NOMEM, "mesh normals");
        memset(acc, 0, sizeof(double) * 3 * mesh->vertex_count);
        for (size_t t = 0; t < mesh->triangle_count; ++t) {
            const uint32_t *tv = mesh->triangles + 3 * t;
            const double *p0 = mesh->positions + 3 * tv[0], *p1 = mesh->positions + 3 * tv[1],
                         *p2 = mesh->positions + 3 * tv[2];
            cj_vec3 n = cj_v3_cross(cj_v3(p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]),
                                    cj_v3(p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2]));
            for (int k = 0; k < 3; ++k) {
                acc[3 * tv[k]] += n.x;
                acc[3 * tv[k] + 1] += n.y;
                acc[3 * tv[k] + 2] += n.z;
            }
        }
    }
    /* written in place (room reserved above), one attribute at a time: the same products and
     * sums in the same order as cj_rbuild_add_vertex's callers made (-ffp-contract=off) */
    const cj_xform3 *Wx = &o->world;
    const cj_xform3 *Nx = &o->normal;
    const size_t nv = mesh->vertex_count, base = b->vertex_count;
    double *pos = b->pos + 3 * base;
    for (size_t i = 0; i < nv; ++i) {
        const double *p = mesh->positions + 3 * i;
        for (int r = 0; r < 3; ++r)
            pos[3 * i + r] =
                Wx->m[r][0] * p[0] + Wx->m[r][1] * p[1] + Wx->m[r][2] * p[2] + Wx->m[r][3];
    }
    if (b->nrm) {
        float *nrm = b->nrm + 3 * base;
        if (!want_n) memset(nrm, 0, sizeof(float) * 3 * nv);
        for (size_t i = 0; i < nv && want_n; ++i) {
            const double *n = acc ? acc + 3 * i : mesh->normals + 3 * i;
            double wn[3];
            for (int r = 0; r < 3; ++r)
                wn[r] = Nx->m[r][0] * n[0] + Nx->m[r][1] * n[1] + Nx->m[r][2] * n[2];
            double len = sqrt(wn[0] * wn[0] + wn[1] * wn[1] + wn[2] * wn[2]);
            for (int r = 0; r < 3; ++r) nrm[3 * i + r] = len > 0.0 ? (float)(wn[r] / len) : 0.0f;
        }
    }
    if (b->uv) {
        float *uv = b->uv + 2 * base;
        if (!want_uv) memset(uv, 0, sizeof(float) * 2 * nv);
        for (size_t i = 0; i < 2 * nv && want_uv; ++i) uv[i] = (float)mesh->uvs[i];
    }
    b->vertex_count += nv;
    cj_rfree(&b->alloc, acc);
    o->v1 = b->vertex_count;
    double t1 = cj_render_now();
    b->sec_transform += t1 - t0;
    o->t0 = b->tri_count;
    int flip = o->det < 0.0;
    int persp = view->cam.projection == CJ_PROJ_PERSPECTIVE;
    for (size_t t = 0; t < mesh->triangle_count; ++t) {
        uint32_t a = mesh->triangles[3 * t] + (uint32_t)o->v0;
        uint32_t c = mesh->triangles[3 * t + 1] + (uint32_t)o->v0;
        uint32_t d = mesh->triangles[3 * t + 2] + (uint32_t)o->v0;
        if (flip) {
            uint32_t s = c;
            c = d;
            d = s;
        }
        const double *p0 = b->pos + 3 * a, *p1 = b->pos + 3 * c, *p2 = b->pos + 3 * d;
        cj_vec3 n = cj_v3_cross(cj_v3(p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]),
                                cj_v3(p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2]));
        if (n.x == 0.0 && n.y == 0.0 && n.z == 0.0) continue; /* no area: draws nothing */
        if (one_sided) {
            cj_vec3 dir = persp
                              ? cj_v3(p0[0] - view->eye.x, p0[1] - view->eye.y, p0[2] - view->eye.z)
                              : view->gaze_unit;
            if (cj_v3_dot(dir, n) > 0.0) { /* (p̄ − ē)·n⃗ > 0: a back face */
                ++b->culled_back;
                continue;
            }
        }
        /* room reserved above */
        const size_t k = b->tri_count++;
        b->tris[3 * k] = a;
        b->tris[3 * k + 1] = c;
        b->tris[3 * k + 2] = d;
        b->tobj[k] = oi;
    }
    o->t1 = b->tri_count;
    b->sec_cull += cj_render_now() - t1;
    return CJ_OK;
}

cj_status cj_rbuild_scene(const cj_rscene *rs, const cj_rview *view, double tol_px, unsigned flags,
                          const unsigned *need, int cull, cj_render_cache *cache,
                          const cj_allocator *alloc, cj_rbuild *out) {
    const cj_scene *scene = rs->scene;
    memset(out, 0, sizeof *out);
    out->alloc = cj_render_alloc(alloc);
    out->flags = flags;
    out->tol_px = tol_px;
    size_t nn = cj_scene_node_count(scene);
    out->objects = cj_ralloc(&out->alloc, sizeof(cj_robject) * (nn ? nn : 1));
    if (!out->objects) return cj_fail(CJ_ERR_NOMEM, "object table of %zu nodes", nn);
    /* attribute arrays exist only when asked for; the growth helper follows their presence */
    out->vertex_cap = 1024;
    out->pos = cj_ralloc(&out->alloc, sizeof(double) * 3 * out->vertex_cap);
    if (flags & CJ_RB_NORMALS)
        out->nrm = cj_ralloc(&out->alloc, sizeof(float) * 3 * out->vertex_cap);
    if (flags & CJ_RB_UVS) out->uv = cj_ralloc(&out->alloc, sizeof(float) * 2 * out->vertex_cap);
    out->tri_cap = 1024;
    out->tris = cj_ralloc(&out->alloc, sizeof(uint32_t) * 3 * out->tri_cap);
    out->tobj = cj_ralloc(&out->alloc, sizeof(uint32_t) * out->tri_cap);
    if (!out->pos || !out->tris || !out->tobj || ((flags & CJ_RB_NORMALS) && !out->nrm) ||
        ((flags & CJ_RB_UVS) && !out->uv)) {
        cj_rbuild_free(out);
        return cj_fail(CJ_ERR_NOMEM, "render buffers");
    }
    cj_mesh *tmp = NULL;
    cj_status st = cj_mesh_create(&out->alloc, &tmp);
    if (st) {
        cj_rbuild_free(out);
        return st;
    }
    for (size_t i = 0; i < nn && !st; ++i) {
        const cj_node *nd = cj_scene_node(scene, (int)i);
        if (!rs->drawn[i]) continue;
        const cj_geometry *g = cj_scene_geometry(scene, nd->geometry);
        cj_robject *o = &out->objects[out->object_count];
        st = object_setup(rs, (int)i, o);
        if (st) break;
        uint32_t oi = (uint32_t)out->object_count++;
        o->v0 = o->v1 = out->vertex_count;
        o->t0 = o->t1 = out->tri_count;
        if (g->kind == CJ_GEOM_CURVE) continue; /* drawn by the line pass */
        unsigned nd_need = (need && nd->material >= 0) ? need[nd->material] : flags;
        int want_n = (flags & CJ_RB_NORMALS) && (nd_need & CJ_RB_NORMALS);
        int want_uv = (flags & CJ_RB_UVS) && (nd_need & CJ_RB_UVS);
        if (g->kind == CJ_GEOM_MESH) {
            double ts = cj_render_now();
            double lo[3] = {INFINITY, INFINITY, INFINITY},
                   hi[3] = {-INFINITY, -INFINITY, -INFINITY};
            const cj_mesh *m = g->u.mesh;
            for (size_t v = 0; v < m->vertex_count; ++v)
                for (int k = 0; k < 3; ++k) {
                    double c = m->positions[3 * v + k];
                    if (c < lo[k]) lo[k] = c;
                    if (c > hi[k]) hi[k] = c;
                }
            double d;
            if (m->vertex_count && cj_rview_box_depth(view, &o->world, lo, hi, &d))
                st = append_object(out, scene, m, oi, want_n, want_uv, cull, view);
            out->mesh_tris += o->t1 - o->t0;
            out->sec_meshes += cj_render_now() - ts;
            continue;
        }
        cj_mesh_clear(tmp);
        double ts = cj_render_now(), bound = 0.0;
        int skip = 0, hit = 0;
        cj_tess_cache_stats work = {0, 0, 0, 0};
        st = cj_render_geometry_mesh(g, o, view, tol_px, cache, tmp, &o->tol_obj, &bound,
                                     &o->grid_nu, &o->grid_nv, &out->patches_in,
                                     &out->patches_culled, &skip, &hit, &work);
        out->cache_hits += (size_t)hit;
        if (!skip && !hit &&
            (g->kind == CJ_GEOM_PATCHES || g->kind == CJ_GEOM_REVOLUTION ||
             g->kind == CJ_GEOM_GEN_CYLINDER))
            ++out->cache_misses;
        out->patches_planned += work.planned;
        out->patches_built += work.built;
        out->patches_reused += work.pieces_reused;
        double te = cj_render_now();
        int is_patch = g->kind == CJ_GEOM_PATCHES || g->kind == CJ_GEOM_REVOLUTION ||
                       g->kind == CJ_GEOM_GEN_CYLINDER;
        if (is_patch) {
            out->sec_patches += te - ts;
            if (bound > out->patch_bound_px) out->patch_bound_px = bound;
        } else {
            out->sec_surfaces += te - ts;
            if (bound > out->surface_bound_px) out->surface_bound_px = bound;
        }
        if (st || skip) continue;
        st = append_object(out, scene, tmp, oi, want_n, want_uv, cull, view);
        if (is_patch)
            out->patch_tris += o->t1 - o->t0;
        else
            out->surface_tris += o->t1 - o->t0;
    }
    cj_mesh_destroy(tmp);
    if (st) cj_rbuild_free(out);
    return st;
}

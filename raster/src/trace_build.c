/* The traced scene: one object per visible node with a surface, in object space under its
 * world transform, and a top-level SAH BVH over their world boxes. */
#include "trace_internal.h"

#include "error_internal.h"
#include "render_internal.h"
#include "render_scene.h"

#include <math.h>
#include <string.h>

static int traced_kind(int kind) {
    switch (kind) {
    case CJ_GEOM_PATCHES:
    case CJ_GEOM_QUADRIC:
    case CJ_GEOM_SPHERE:
    case CJ_GEOM_TORUS:
    case CJ_GEOM_CYLINDER:
    case CJ_GEOM_PLANAR:
    case CJ_GEOM_BILINEAR:
    case CJ_GEOM_REVOLUTION:
    case CJ_GEOM_GEN_CYLINDER:
    case CJ_GEOM_MESH:
        return 1;
    default:
        return 0;
    }
}

static int patch_cb(void *user, uint32_t prim, const cj_ray *ray, cj_hit *hit) {
    const tr_object *o = user;
    return cj_ray_patch(ray, &o->patches[prim], o->tol, hit, NULL);
}

/* Object-space box of the geometry. */
static cj_aabb object_box(const tr_object *o) {
    const cj_geometry *g = o->g;
    switch (g->kind) {
    case CJ_GEOM_QUADRIC:
        return cj_aabb_quadric(&g->u.quadric);
    case CJ_GEOM_SPHERE: {
        cj_vec3 c = g->u.sphere.center;
        double r = g->u.sphere.radius * (1.0 + 1e-12);
        cj_aabb b = {{c.x - r, c.y - r, c.z - r}, {c.x + r, c.y + r, c.z + r}};
        return b;
    }
    case CJ_GEOM_TORUS:
        return cj_aabb_torus(&g->u.torus);
    case CJ_GEOM_CYLINDER:
        return cj_aabb_cylinder(&g->u.cylinder);
    case CJ_GEOM_PLANAR: {
        const cj_planar_patch *p = &g->u.planar;
        cj_aabb b = cj_aabb_triangle(p->p, cj_v3_add(p->p, p->eu), cj_v3_add(p->p, p->ev));
        cj_aabb_grow(&b, cj_v3_add(p->p, cj_v3_add(p->eu, p->ev)));
        return b;
    }
    case CJ_GEOM_BILINEAR: {
        const cj_bilinear *p = &g->u.bilinear;
        cj_aabb b = cj_aabb_triangle(p->p00, p->p10, p->p01);
        cj_aabb_grow(&b, p->p11);
        return b;
    }
    case CJ_GEOM_MESH: {
        cj_aabb b = cj_aabb_empty();
        for (size_t i = 0; i < g->u.mesh->vertex_count; i++)
            cj_aabb_grow(&b, cj_v3(g->u.mesh->positions[3 * i], g->u.mesh->positions[3 * i + 1],
                                   g->u.mesh->positions[3 * i + 2]));
        return b;
    }
    default: {
        cj_aabb b = cj_aabb_empty();
        for (size_t i = 0; i < o->npatch; i++) {
            cj_aabb pb = cj_aabb_patch(&o->patches[i]);
            cj_aabb_merge(&b, &pb);
        }
        return b;
    }
    }
}

/* Planar boxes have zero thickness: widen every box a little so slab tests stay robust. */
static void pad(cj_aabb *b) {
    double d = 0.0;
    for (int k = 0; k < 3; k++) d = fmax(d, b->hi[k] - b->lo[k]);
    for (int k = 0; k < 3; k++) {
        double m = 1e-9 * d + 1e-12 * (fabs(b->lo[k]) + fabs(b->hi[k]));
        b->lo[k] -= m;
        b->hi[k] += m;
    }
}

/* The object BVH (patches or mesh triangles): from the cache when the data did not change. */
static cj_status object_bvh(tr_object *o, int node_index, tr_bvh_cache *cache,
                            const cj_allocator *a, size_t *reused, size_t *built) {
    if (cache) {
        o->bvh = tr_bvh_cache_find(cache, node_index, o->g, o->patches, o->npatch);
        if (o->bvh) {
            o->bvh_cached = 1;
            ++*reused;
            return CJ_OK;
        }
    }
    cj_status st;
    if (o->patches) {
        cj_aabb *boxes = cj_ralloc(a, o->npatch * sizeof *boxes);
        if (!boxes) return cj_fail(CJ_ERR_NOMEM, "ray tracer: out of memory");
        for (size_t i = 0; i < o->npatch; i++) {
            boxes[i] = cj_aabb_patch(&o->patches[i]);
            pad(&boxes[i]);
        }
        st = cj_bvh_build(boxes, o->npatch, a, &o->bvh);
        cj_rfree(a, boxes);
    } else {
        const cj_mesh *m = o->g->u.mesh;
        st = cj_bvh_mesh_build(m->positions, m->vertex_count, m->triangles, m->triangle_count, a,
                               &o->bvh);
    }
    if (st) return st;
    ++*built;
    if (cache && tr_bvh_cache_store(cache, node_index, o->bvh)) o->bvh_cached = 1;
    return CJ_OK;
}

/* The node's transforms over the shutter when they are not all equal. */
static void object_motion(tr_object *o, const tr_motion *mo, int node_index) {
    if (!mo || !mo->world) return;
    const cj_xform3 *x0 = &mo->world[node_index];
    for (int k = 1; k < mo->poses; ++k)
        if (memcmp(x0, &mo->world[(size_t)k * mo->node_count + (size_t)node_index], sizeof *x0)) {
            o->motion = x0;
            o->stride = mo->node_count;
            o->poses = mo->poses;
            return;
        }
}

/* The transform at shutter time τ: the poses around it interpolated entrywise (affine). */
static cj_xform3 motion_at(const tr_object *o, double time) {
    double u = time * (o->poses - 1);
    int k = (int)u;
    if (k < 0) k = 0;
    if (k > o->poses - 2) k = o->poses - 2;
    const double f = u - k;
    const cj_xform3 *a = &o->motion[(size_t)k * o->stride],
                    *b = &o->motion[(size_t)(k + 1) * o->stride];
    cj_xform3 m = *a;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 4; ++j) m.m[i][j] = (1.0 - f) * a->m[i][j] + f * b->m[i][j];
    return m;
}

static cj_status build_object(const cj_rscene *rs, int node_index, tr_bvh_cache *cache,
                              const tr_motion *mo, const cj_allocator *a, tr_object *o,
                              size_t *reused, size_t *built) {
    const cj_scene *scene = rs->scene;
    const cj_node *nd = cj_scene_node(scene, node_index);
    const cj_geometry *g = cj_scene_geometry(scene, nd->geometry);
    memset(o, 0, sizeof *o);
    o->g = g;
    o->kind = g->kind;
    o->id = nd->id;
    o->material = nd->material;
    cj_xform3 w = rs->world[node_index];
    cj_xform3 id = cj_xform3_identity();
    o->identity = memcmp(&w, &id, sizeof w) == 0;
    cj_status st = cj_ray_xform_init(&o->x, &w);
    if (st) return st;
    if (g->kind == CJ_GEOM_PATCHES) {
        o->patches = g->u.patches.patches;
        o->npatch = g->u.patches.count;
    } else if (g->kind == CJ_GEOM_REVOLUTION || g->kind == CJ_GEOM_GEN_CYLINDER) {
        st = cj_render_geometry_patches(g, a, &o->own_patches, &o->npatch, &o->own_pts, &o->own_w);
        if (st) return st;
        o->patches = o->own_patches;
    }
    if (o->patches) {
        if (o->npatch == 0) return cj_fail(CJ_ERR_EMPTY, "node %d: no patches", node_index);
        for (size_t i = 0; i < o->npatch; i++) {
            st = cj_ray_patch_check(&o->patches[i], 1.0);
            if (st) return st;
        }
        st = object_bvh(o, node_index, cache, a, reused, built);
        if (st) return st;
        cj_aabb b = object_box(o);
        double diag = sqrt((b.hi[0] - b.lo[0]) * (b.hi[0] - b.lo[0]) +
                           (b.hi[1] - b.lo[1]) * (b.hi[1] - b.lo[1]) +
                           (b.hi[2] - b.lo[2]) * (b.hi[2] - b.lo[2]));
        o->tol = 1e-7 * (diag > 0.0 ? diag : 1.0);
    } else if (g->kind == CJ_GEOM_MESH) {
        st = object_bvh(o, node_index, cache, a, reused, built);
        if (st) return st;
    }
    cj_aabb ob = object_box(o);
    pad(&ob);
    o->wbox = o->identity ? ob : cj_aabb_transform(&o->x, &ob);
    object_motion(o, mo, node_index);
    /* an interpolated transform maps each point between its images at the two poses, so the
     * boxes at the poses bound every time between them */
    for (int k = 0; o->motion && k < o->poses; ++k) {
        cj_ray_xform xk;
        st = cj_ray_xform_init(&xk, &o->motion[(size_t)k * o->stride]);
        if (st) return st;
        cj_aabb bk = cj_aabb_transform(&xk, &ob);
        cj_aabb_merge(&o->wbox, &bk);
    }
    if (o->motion) o->identity = 0;
    return CJ_OK;
}

void tr_scene_free(tr_scene *s) {
    for (size_t i = 0; i < s->nobj; i++) {
        if (!s->objs[i].bvh_cached) cj_bvh_destroy(s->objs[i].bvh);
        cj_rfree(&s->alloc, s->objs[i].own_patches);
        cj_rfree(&s->alloc, s->objs[i].own_pts);
        cj_rfree(&s->alloc, s->objs[i].own_w);
    }
    for (int i = 0; i < s->ntex; i++) cj_tex_sampler_free(&s->tex[i]);
    cj_rfree(&s->alloc, s->tex);
    cj_rfree(&s->alloc, s->objs);
    cj_rfree(&s->alloc, s->emit);
    cj_rfree(&s->alloc, s->emit_cdf);
    cj_rfree(&s->alloc, s->emit_obj);
    cj_bvh_destroy(s->top);
    memset(s, 0, sizeof *s);
}

cj_status tr_scene_build(const cj_rscene *rs, tr_bvh_cache *cache, const tr_motion *motion,
                         const cj_allocator *alloc, tr_scene *out, size_t *reused, size_t *built,
                         size_t *moving) {
    const cj_scene *scene = rs->scene;
    *reused = *built = *moving = 0;
    tr_scene s;
    memset(&s, 0, sizeof s);
    s.scene = scene;
    s.alloc = cj_render_alloc(alloc);
    size_t nn = cj_scene_node_count(scene);
    s.objs = cj_ralloc(&s.alloc, (nn ? nn : 1) * sizeof *s.objs);
    int nt = (int)cj_scene_texture_count(scene);
    s.tex = cj_ralloc(&s.alloc, (size_t)(nt ? nt : 1) * sizeof *s.tex);
    if (!s.objs || !s.tex) {
        tr_scene_free(&s);
        return cj_fail(CJ_ERR_NOMEM, "ray tracer: out of memory");
    }
    cj_status st = CJ_OK;
    for (int i = 0; i < nt && !st; i++) {
        st = cj_tex_sampler_init(cj_scene_texture(scene, i), i, &s.alloc, &s.tex[i]);
        if (!st) s.ntex = i + 1;
    }
    for (size_t i = 0; i < nn && !st; i++) {
        const cj_node *nd = cj_scene_node(scene, (int)i);
        if (!rs->drawn[i] || !traced_kind(cj_scene_geometry(scene, nd->geometry)->kind)) continue;
        st = build_object(rs, (int)i, cache, motion, &s.alloc, &s.objs[s.nobj], reused, built);
        if (s.objs[s.nobj].motion) ++*moving;
        s.nobj++;
    }
    if (!st && s.nobj) {
        cj_aabb *boxes = cj_ralloc(&s.alloc, s.nobj * sizeof *boxes);
        if (!boxes) st = cj_fail(CJ_ERR_NOMEM, "ray tracer: out of memory");
        for (size_t i = 0; !st && i < s.nobj; i++) boxes[i] = s.objs[i].wbox;
        if (!st) st = cj_bvh_build(boxes, s.nobj, &s.alloc, &s.top);
        cj_rfree(&s.alloc, boxes);
    }
    if (st) {
        tr_scene_free(&s);
        return st;
    }
    *out = s;
    return CJ_OK;
}

/* ---- intersection ------------------------------------------------------------------------ */

typedef struct cb_ctx {
    const tr_scene *s;
    tr_counts *c;
    double time;
} cb_ctx;

static int object_cb(void *user, uint32_t prim, const cj_ray *wray, cj_hit *hit) {
    const cb_ctx *cc = user;
    const tr_object *o = &cc->s->objs[prim];
    cj_ray r = *wray;
    cj_ray_xform xt; /* a moving object's transform at the ray's time */
    const cj_ray_xform *x = &o->x;
    if (o->motion) {
        const cj_xform3 m = motion_at(o, cc->time);
        if (cj_ray_xform_init(&xt, &m) != CJ_OK) return 0; /* singular in passing: not there */
        x = &xt;
    }
    if (!o->identity) cj_ray_to_object(x, wray, &r);
    const cj_geometry *g = o->g;
    int got = 0;
    switch (o->kind) {
    case CJ_GEOM_QUADRIC:
        got = cj_ray_quadric(&r, &g->u.quadric, hit);
        break;
    case CJ_GEOM_SPHERE:
        got = cj_ray_sphere(&r, g->u.sphere.center, g->u.sphere.radius, hit);
        break;
    case CJ_GEOM_TORUS:
        got = cj_ray_torus(&r, &g->u.torus, hit);
        break;
    case CJ_GEOM_CYLINDER:
        got = cj_ray_cylinder(&r, &g->u.cylinder, hit);
        break;
    case CJ_GEOM_PLANAR:
        got = cj_ray_planar(&r, &g->u.planar, hit);
        break;
    case CJ_GEOM_BILINEAR: {
        cj_aabb b = object_box(o);
        double diag = sqrt((b.hi[0] - b.lo[0]) * (b.hi[0] - b.lo[0]) +
                           (b.hi[1] - b.lo[1]) * (b.hi[1] - b.lo[1]) +
                           (b.hi[2] - b.lo[2]) * (b.hi[2] - b.lo[2]));
        got = cj_ray_bilinear(&r, &g->u.bilinear, 1e-7 * diag, hit);
        break;
    }
    case CJ_GEOM_MESH: {
        got = cj_bvh_mesh_closest(o->bvh, &r, hit, NULL);
        if (got) {
            const cj_mesh *m = g->u.mesh;
            const uint32_t *t = m->triangles + 3 * (size_t)hit->prim;
            double b1 = hit->u, b2 = hit->v, b0 = 1.0 - b1 - b2;
            const double *n0 = m->normals + 3 * (size_t)t[0], *n1 = m->normals + 3 * (size_t)t[1],
                         *n2 = m->normals + 3 * (size_t)t[2];
            cj_vec3 n =
                cj_v3(b0 * n0[0] + b1 * n1[0] + b2 * n2[0], b0 * n0[1] + b1 * n1[1] + b2 * n2[1],
                      b0 * n0[2] + b1 * n1[2] + b2 * n2[2]);
            if (cj_v3_norm(n) > 0.0) {
                n = cj_v3_normalize(n);
                /* keep the interpolated normal on the triangle's side */
                hit->n = cj_v3_dot(n, hit->ng) >= 0.0 ? n : cj_v3_scale(n, -1.0);
            }
            const double *u0 = m->uvs + 2 * (size_t)t[0], *u1 = m->uvs + 2 * (size_t)t[1],
                         *u2 = m->uvs + 2 * (size_t)t[2];
            hit->u = b0 * u0[0] + b1 * u1[0] + b2 * u2[0];
            hit->v = b0 * u0[1] + b1 * u1[1] + b2 * u2[1];
        }
        break;
    }
    default: {
        got = cj_bvh_closest(o->bvh, &r, patch_cb, (void *)o, hit, NULL);
        if (got && cc->c) {
            cc->c->patch_rays++;
            if (hit->err > cc->c->patch_max_err) cc->c->patch_max_err = hit->err;
        }
        break;
    }
    }
    if (!got) return 0;
    if (!o->identity) cj_hit_to_world(x, hit);
    hit->obj = prim;
    return 1;
}

int tr_closest(const tr_scene *s, const cj_ray *ray, double time, cj_hit *hit, tr_counts *c) {
    if (!s->top) return 0;
    cb_ctx cc = {s, c, time};
    if (!cj_bvh_closest(s->top, ray, object_cb, &cc, hit, NULL)) return 0;
    hit->obj = hit->prim; /* the top level's primitive is the object */
    return 1;
}

int tr_any(const tr_scene *s, const cj_ray *ray, double time, tr_counts *c) {
    if (!s->top) return 0;
    cb_ctx cc = {s, c, time};
    return cj_bvh_any(s->top, ray, object_cb, &cc, NULL);
}

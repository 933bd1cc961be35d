/* The tessellation cache of repeated renders (cj_render_cache, casteljau/render.h): per node,
 * the object-space mesh of its visible patches at the tolerance it was built for. A later
 * render reuses it when the same patches (same control data, bit for bit, same visible set)
 * need a tolerance between the cached one and twice it: the cached mesh's proven bound is then
 * within the new tolerance, at most 2x finer than needed. */
#include "render_internal.h"

#include "error_internal.h"

#include <string.h>

typedef struct cache_entry {
    int node;
    uint64_t key;
    double tol, bound;
    cj_mesh *mesh;
} cache_entry;

struct cj_render_cache {
    cj_allocator alloc;
    size_t count, cap;
    cache_entry *e;
    uint64_t hits, misses;
};

cj_status cj_render_cache_create(const cj_allocator *alloc, cj_render_cache **out) {
    cj_allocator a = cj_render_alloc(alloc);
    cj_render_cache *c = cj_ralloc(&a, sizeof *c);
    if (!c) return cj_fail(CJ_ERR_NOMEM, "render cache");
    memset(c, 0, sizeof *c);
    c->alloc = a;
    *out = c;
    return CJ_OK;
}

void cj_render_cache_destroy(cj_render_cache *c) {
    if (!c) return;
    for (size_t i = 0; i < c->count; ++i) cj_mesh_destroy(c->e[i].mesh);
    cj_allocator a = c->alloc;
    cj_rfree(&a, c->e);
    cj_rfree(&a, c);
}

/* FNV-1a over the bytes of the visible patches' degrees, points and weights. */
uint64_t cj_rcache_key(const cj_patch *p, size_t n) {
    uint64_t h = 1469598103934665603ull;
#define MIX(ptr, bytes)                                                                            \
    do {                                                                                           \
        const unsigned char *b_ = (const unsigned char *)(ptr);                                    \
        for (size_t k_ = 0; k_ < (bytes); ++k_) h = (h ^ b_[k_]) * 1099511628211ull;               \
    } while (0)
    MIX(&n, sizeof n);
    for (size_t i = 0; i < n; ++i) {
        size_t np = cj_patch_point_count(&p[i]);
        int deg[3] = {p[i].deg_u, p[i].deg_v, p[i].weights != NULL};
        MIX(deg, sizeof deg);
        MIX(p[i].pts, 3 * np * sizeof(double));
        if (p[i].weights) MIX(p[i].weights, np * sizeof(double));
    }
#undef MIX
    return h;
}

static cj_status append_mesh(cj_mesh *dst, const cj_mesh *src) {
    size_t v0 = dst->vertex_count;
    cj_status st =
        cj_mesh_reserve(dst, v0 + src->vertex_count, dst->triangle_count + src->triangle_count);
    for (size_t i = 0; i < src->vertex_count && !st; ++i)
        st = cj_mesh_add_vertex(dst, src->positions + 3 * i, src->normals + 3 * i, src->uvs + 2 * i,
                                NULL);
    for (size_t t = 0; t < src->triangle_count && !st; ++t)
        st = cj_mesh_add_triangle(dst, src->triangles[3 * t] + (uint32_t)v0,
                                  src->triangles[3 * t + 1] + (uint32_t)v0,
                                  src->triangles[3 * t + 2] + (uint32_t)v0, src->triangle_patch[t]);
    return st;
}

int cj_rcache_lookup(cj_render_cache *c, int node, uint64_t key, double tol, cj_mesh *mesh,
                     double *tol_used, double *bound) {
    for (size_t i = 0; i < c->count; ++i) {
        cache_entry *e = &c->e[i];
        if (e->node != node) continue;
        if (e->key != key || !(e->tol <= tol && tol <= 2.0 * e->tol)) break;
        if (append_mesh(mesh, e->mesh)) return 0; /* out of memory: tessellate instead */
        *tol_used = e->tol;
        *bound = e->bound;
        ++c->hits;
        return 1;
    }
    ++c->misses;
    return 0;
}

void cj_rcache_store(cj_render_cache *c, int node, uint64_t key, double tol, double bound,
                     const cj_mesh *mesh) {
    cache_entry *e = NULL;
    for (size_t i = 0; i < c->count && !e; ++i)
        if (c->e[i].node == node) e = &c->e[i];
    if (!e) {
        if (c->count == c->cap) {
            size_t nc = c->cap ? 2 * c->cap : 16;
            cache_entry *ne = cj_ralloc(&c->alloc, nc * sizeof *ne);
            if (!ne) return; /* a cache that cannot grow simply does not remember */
            if (c->e) memcpy(ne, c->e, c->count * sizeof *ne);
            cj_rfree(&c->alloc, c->e);
            c->e = ne;
            c->cap = nc;
        }
        e = &c->e[c->count++];
        memset(e, 0, sizeof *e);
        e->node = node;
    }
    cj_mesh *m = NULL;
    if (cj_mesh_create(&c->alloc, &m)) return;
    if (append_mesh(m, mesh)) {
        cj_mesh_destroy(m);
        return;
    }
    cj_mesh_destroy(e->mesh);
    e->mesh = m;
    e->key = key;
    e->tol = tol;
    e->bound = bound;
}

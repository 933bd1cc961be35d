/* The ray tracer's per-object BVH cache of a renderer (casteljau/renderer.h): per node, the BVH
 * of its patches or mesh triangles with a copy of the data it was built from. A frame reuses
 * it when the node's data is equal byte for byte (no hash: a collision could never give a
 * wrong picture); the BVH lives in object space, so the world transform may change freely.
 * Entries of nodes no frame asked for are dropped at the end of the frame. */
#include "trace_internal.h"

#include "error_internal.h"
#include "render_internal.h"

#include <string.h>

typedef struct bvh_entry {
    int node;
    int used; /* asked for in the current frame */
    unsigned char *key;
    size_t key_len;
    cj_bvh *bvh;
} bvh_entry;

struct tr_bvh_cache {
    cj_allocator alloc;
    bvh_entry *e;
    size_t count, cap;
    unsigned char *scratch; /* the key of the last lookup */
    size_t scratch_len, scratch_cap;
};

cj_status tr_bvh_cache_create(const cj_allocator *alloc, tr_bvh_cache **out) {
    cj_allocator a = cj_render_alloc(alloc);
    tr_bvh_cache *c = cj_ralloc(&a, sizeof *c);
    if (!c) return cj_fail(CJ_ERR_NOMEM, "BVH cache");
    memset(c, 0, sizeof *c);
    c->alloc = a;
    *out = c;
    return CJ_OK;
}

static void drop(tr_bvh_cache *c, bvh_entry *e) {
    cj_bvh_destroy(e->bvh);
    cj_rfree(&c->alloc, e->key);
    e->bvh = NULL;
    e->key = NULL;
}

void tr_bvh_cache_destroy(tr_bvh_cache *c) {
    if (!c) return;
    for (size_t i = 0; i < c->count; ++i) drop(c, &c->e[i]);
    cj_rfree(&c->alloc, c->e);
    cj_rfree(&c->alloc, c->scratch);
    cj_allocator a = c->alloc;
    cj_rfree(&a, c);
}

static int put(tr_bvh_cache *c, const void *bytes, size_t n) {
    if (c->scratch_len + n > c->scratch_cap) {
        size_t cap = c->scratch_cap ? c->scratch_cap : 4096;
        while (cap < c->scratch_len + n) cap *= 2;
        unsigned char *s = cj_ralloc(&c->alloc, cap);
        if (!s) return 0;
        if (c->scratch_len) memcpy(s, c->scratch, c->scratch_len);
        cj_rfree(&c->alloc, c->scratch);
        c->scratch = s;
        c->scratch_cap = cap;
    }
    memcpy(c->scratch + c->scratch_len, bytes, n);
    c->scratch_len += n;
    return 1;
}

/* The key: what the BVH is built from (patch degrees, points and weights, or the mesh's
 * positions and triangles). 0 when the scratch cannot grow (then nothing is cached). */
static int make_key(tr_bvh_cache *c, const cj_geometry *g, const cj_patch *p, size_t np) {
    c->scratch_len = 0;
    int kind = g->kind, ok = put(c, &kind, sizeof kind);
    if (g->kind == CJ_GEOM_MESH) {
        const cj_mesh *m = g->u.mesh;
        size_t counts[2] = {m->vertex_count, m->triangle_count};
        ok = ok && put(c, counts, sizeof counts);
        ok = ok && put(c, m->positions, 3 * sizeof(double) * m->vertex_count);
        ok = ok && put(c, m->triangles, 3 * sizeof(uint32_t) * m->triangle_count);
        return ok;
    }
    ok = ok && put(c, &np, sizeof np);
    for (size_t i = 0; i < np && ok; ++i) {
        size_t n = cj_patch_point_count(&p[i]);
        int deg[3] = {p[i].deg_u, p[i].deg_v, p[i].weights != NULL};
        ok = put(c, deg, sizeof deg) && put(c, p[i].pts, 3 * sizeof(double) * n);
        if (ok && p[i].weights) ok = put(c, p[i].weights, sizeof(double) * n);
    }
    return ok;
}

cj_bvh *tr_bvh_cache_find(tr_bvh_cache *c, int node, const cj_geometry *g, const cj_patch *p,
                          size_t np) {
    if (!make_key(c, g, p, np)) {
        c->scratch_len = 0;
        return NULL;
    }
    for (size_t i = 0; i < c->count; ++i) {
        bvh_entry *e = &c->e[i];
        if (e->node != node) continue;
        e->used = 1; /* found or about to be replaced: not swept */
        if (e->key_len == c->scratch_len && memcmp(e->key, c->scratch, e->key_len) == 0)
            return e->bvh;
        return NULL;
    }
    return NULL;
}

int tr_bvh_cache_store(tr_bvh_cache *c, int node, cj_bvh *bvh) {
    if (!c->scratch_len) return 0;
    bvh_entry *e = NULL;
    for (size_t i = 0; i < c->count && !e; ++i)
        if (c->e[i].node == node) e = &c->e[i];
    unsigned char *key = cj_ralloc(&c->alloc, c->scratch_len);
    if (!key) return 0;
    if (!e) {
        if (c->count == c->cap) {
            size_t nc = c->cap ? 2 * c->cap : 16;
            bvh_entry *ne = cj_ralloc(&c->alloc, nc * sizeof *ne);
            if (!ne) {
                cj_rfree(&c->alloc, key);
                return 0;
            }
            if (c->count) memcpy(ne, c->e, c->count * sizeof *ne);
            cj_rfree(&c->alloc, c->e);
            c->e = ne;
            c->cap = nc;
        }
        e = &c->e[c->count++];
        memset(e, 0, sizeof *e);
        e->node = node;
    }
    drop(c, e);
    memcpy(key, c->scratch, c->scratch_len);
    e->key = key;
    e->key_len = c->scratch_len;
    e->bvh = bvh;
    e->used = 1;
    return 1;
}

void tr_bvh_cache_sweep(tr_bvh_cache *c) {
    size_t k = 0;
    for (size_t i = 0; i < c->count; ++i) {
        if (!c->e[i].used) {
            drop(c, &c->e[i]);
            continue;
        }
        c->e[i].used = 0;
        c->e[k++] = c->e[i];
    }
    c->count = k;
}

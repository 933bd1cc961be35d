/* The tessellation cache of repeated renders (cj_render_cache, casteljau/render.h): per node, an
 * incremental tessellation cache (cj_tess_cache, casteljau/tess_cache.h) and the object
 * tolerance it tessellates at. TOLERANCE BAND: while the tolerance a frame needs stays within
 * [cached tol, 2 x cached tol], the node keeps its cached tolerance (its mesh's proven bound is
 * then within the needed tolerance, at most 2x finer than needed), so a moving camera does not
 * re-tessellate; outside the band the node re-tessellates at the needed tolerance, except on a
 * steady approach: when the needed tolerance falls below the band and the node's last departure
 * from its band was downwards too, it re-tessellates at needed/sqrt 2, so the frames of a camera
 * (or a dragged point) moving closer stay in the new band for a factor sqrt 2 in distance
 * instead of each redoing the whole node at a tolerance a hair finer than the last (the first
 * departure stays exact: a single edit or camera jump still gives the one-shot image). Within the
 * band an edit re-plans only the edited patches and rebuilds only them and the neighbours whose
 * shared side count changed; the mesh is bit-identical to a one-shot tessellation of the same
 * patches at the cached tolerance. */
#include "render_internal.h"

#include "casteljau/tess_cache.h"
#include "error_internal.h"

#include <string.h>

typedef struct cache_entry {
    int node;
    double tol;
    int approaching; /* the last departure from the band was below it (a finer tolerance) */
    cj_tess_cache *tess;
} cache_entry;

struct cj_render_cache {
    cj_allocator alloc;
    size_t count, cap;
    cache_entry *e;
    cj_render_progress_fn progress; /* the frame's callback while it prepares, else NULL */
    void *progress_user;
};

void cj_rcache_set_progress(cj_render_cache *c, cj_render_progress_fn fn, void *user) {
    c->progress = fn;
    c->progress_user = user;
}

/* The tessellation cache's per-patch hook, passed on as "preparing" (done = total = 0). */
static int tess_progress(void *user, size_t done, size_t total) {
    (void)done;
    (void)total;
    const cj_render_cache *c = user;
    return c->progress(c->progress_user, 0, 0);
}

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
    for (size_t i = 0; i < c->count; ++i) cj_tess_cache_destroy(c->e[i].tess);
    cj_allocator a = c->alloc;
    cj_rfree(&a, c->e);
    cj_rfree(&a, c);
}

/* The node's entry, created (with an empty tessellation cache) when missing; NULL when out of
 * memory. */
static cache_entry *entry_for(cj_render_cache *c, int node) {
    for (size_t i = 0; i < c->count; ++i)
        if (c->e[i].node == node) return &c->e[i];
    if (c->count == c->cap) {
        size_t nc = c->cap ? 2 * c->cap : 16;
        cache_entry *ne = cj_ralloc(&c->alloc, nc * sizeof *ne);
        if (!ne) return NULL;
        if (c->e) memcpy(ne, c->e, c->count * sizeof *ne);
        cj_rfree(&c->alloc, c->e);
        c->e = ne;
        c->cap = nc;
    }
    cache_entry *e = &c->e[c->count];
    memset(e, 0, sizeof *e);
    e->node = node;
    if (cj_tess_cache_create(&c->alloc, &e->tess)) return NULL;
    ++c->count;
    return e;
}

cj_status cj_rcache_tessellate(cj_render_cache *c, int node, const cj_patch *patches, size_t count,
                               cj_tess_options *opt, cj_mesh *mesh, cj_tess_report *rep,
                               cj_tess_cache_stats *stats) {
    cache_entry *e = entry_for(c, node);
    if (!e) return cj_fail(CJ_ERR_NOMEM, "render cache entry of node %d", node);
    const double need = opt->tol;
    const int in_band = e->tol > 0.0 && e->tol <= need && need <= 2.0 * e->tol;
    const int below = e->tol > 0.0 && need < e->tol;
    if (in_band)
        opt->tol = e->tol;
    else if (below && e->approaching)
        opt->tol = need * 0.70710678118654752; /* ≤ need (rounded 1/√2 < 1): the bound holds */
    cj_tess_cache_set_progress(e->tess, c->progress ? tess_progress : NULL, c);
    const cj_status st = cj_tess_cache_update(e->tess, patches, count, opt, mesh, rep, stats);
    cj_tess_cache_set_progress(e->tess, NULL, NULL);
    /* a cancelled update keeps its finished patches and the earlier ones (tess_cache.h): keep
     * the tolerance they were made at, so the next frame in the band resumes that work instead
     * of re-tessellating every patch at the exact needed tolerance */
    e->tol = st && st != CJ_ERR_CANCELLED ? 0.0 : opt->tol;
    if (!in_band) e->approaching = below && e->tol > 0.0;
    return st;
}

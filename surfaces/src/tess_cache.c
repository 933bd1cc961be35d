/* The incremental tessellation cache (casteljau/tess_cache.h): per patch, its plan and its mesh
 * piece, found again by the patch's content (hash, then a bit-for-bit comparison). An update
 * runs the same three steps as cj_tessellate_patches (tessellate.c: plan, share, build) and
 * skips the plans and builds whose inputs are unchanged; the pieces are then concatenated in
 * patch order, which is exactly what the one-shot function appends. */
#include "casteljau/tess_cache.h"
#include "alloc_internal.h"
#include "error_internal.h"
#include "patch_internal.h"
#include "tessellate_internal.h"

#include <assert.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct centry {
    uint64_t hash;
    int deg_u, deg_v, rational;
    double *pts, *w; /* copies of the control data (owned) */
    double tol;
    int cap;
    int have_plan;
    tess_plan plan;
    int have_piece;
    int k[4];       /* side counts of the piece */
    cj_mesh *piece; /* triangle_patch values are rewritten when appended */
    double bound;
    size_t dropped;
    grid used;
    int taken; /* matched by a patch of the current update */
} centry;

struct cj_tess_cache {
    cj_allocator alloc;
    centry *e;
    size_t count;
    cj_mesh *scratch; /* planning work space */
    ptess *P;
    cj_tess_cache_stats totals;
    cj_tess_progress_fn progress; /* NULL: not cancellable */
    void *progress_user;
};

cj_status cj_tess_cache_create(const cj_allocator *alloc, cj_tess_cache **out) {
    assert(out != NULL);
    const cj_allocator a = cj_allocator_resolve(alloc);
    cj_tess_cache *c = cj_allocator_alloc(&a, sizeof *c);
    if (!c) return cj_fail(CJ_ERR_NOMEM, "out of memory creating a tessellation cache");
    memset(c, 0, sizeof *c);
    c->alloc = a;
    c->P = cj_allocator_alloc(&a, sizeof *c->P);
    if (!c->P || cj_mesh_create(&c->alloc, &c->scratch)) {
        cj_allocator_free(&a, c->P);
        cj_allocator_free(&a, c);
        return cj_fail(CJ_ERR_NOMEM, "out of memory creating a tessellation cache");
    }
    *out = c;
    return CJ_OK;
}

static void entry_free(cj_tess_cache *c, centry *e) {
    cj_allocator_free(&c->alloc, e->pts);
    cj_allocator_free(&c->alloc, e->w);
    cj_mesh_destroy(e->piece);
    memset(e, 0, sizeof *e);
}

void cj_tess_cache_clear(cj_tess_cache *c) {
    assert(c != NULL);
    for (size_t i = 0; i < c->count; ++i) entry_free(c, &c->e[i]);
    cj_allocator_free(&c->alloc, c->e);
    c->e = NULL;
    c->count = 0;
}

void cj_tess_cache_destroy(cj_tess_cache *c) {
    if (!c) return;
    cj_tess_cache_clear(c);
    cj_mesh_destroy(c->scratch);
    const cj_allocator a = c->alloc;
    cj_allocator_free(&a, c->P);
    cj_allocator_free(&a, c);
}

void cj_tess_cache_set_progress(cj_tess_cache *c, cj_tess_progress_fn fn, void *user) {
    assert(c != NULL);
    c->progress = fn;
    c->progress_user = user;
}

/* CJ_ERR_CANCELLED when the progress callback asks to stop before step `done`. */
static cj_status check_cancel(const cj_tess_cache *c, size_t done, size_t total) {
    if (c->progress && c->progress(c->progress_user, done, total))
        return cj_fail(CJ_ERR_CANCELLED,
                       "tessellation cancelled by the progress callback before "
                       "step %zu of %zu",
                       done, total);
    return CJ_OK;
}

cj_tess_cache_stats cj_tess_cache_totals(const cj_tess_cache *c) {
    assert(c != NULL);
    return c->totals;
}

/* FNV-1a over the degrees, the rational flag, the points and the weights. */
static uint64_t patch_hash(const cj_patch *p) {
    uint64_t h = 1469598103934665603ull;
    const int hdr[3] = {p->deg_u, p->deg_v, p->weights != NULL};
    const size_t np = cj_patch_point_count(p);
#define MIX(ptr, bytes)                                                                            \
    do {                                                                                           \
        const unsigned char *b_ = (const unsigned char *)(ptr);                                    \
        for (size_t k_ = 0; k_ < (bytes); ++k_) h = (h ^ b_[k_]) * 1099511628211ull;               \
    } while (0)
    MIX(hdr, sizeof hdr);
    MIX(p->pts, 3 * np * sizeof(double));
    if (p->weights) MIX(p->weights, np * sizeof(double));
#undef MIX
    return h;
}

static int entry_matches(const centry *e, const cj_patch *p, uint64_t hash, double tol, int cap) {
    if (e->taken || !e->have_plan || e->hash != hash || e->tol != tol || e->cap != cap) return 0;
    if (e->deg_u != p->deg_u || e->deg_v != p->deg_v || e->rational != (p->weights != NULL))
        return 0;
    const size_t np = cj_patch_point_count(p);
    if (memcmp(e->pts, p->pts, 3 * np * sizeof(double)) != 0) return 0;
    return !p->weights || memcmp(e->w, p->weights, np * sizeof(double)) == 0;
}

/* A fresh entry for p (control data copied). */
static cj_status entry_init(cj_tess_cache *c, centry *e, const cj_patch *p, uint64_t hash,
                            double tol, int cap) {
    memset(e, 0, sizeof *e);
    const size_t np = cj_patch_point_count(p);
    e->hash = hash;
    e->deg_u = p->deg_u;
    e->deg_v = p->deg_v;
    e->rational = p->weights != NULL;
    e->tol = tol;
    e->cap = cap;
    e->pts = cj_allocator_alloc(&c->alloc, 3 * np * sizeof(double));
    e->w = e->rational ? cj_allocator_alloc(&c->alloc, np * sizeof(double)) : NULL;
    if (!e->pts || (e->rational && !e->w))
        return cj_fail(CJ_ERR_NOMEM, "out of memory caching a patch");
    memcpy(e->pts, p->pts, 3 * np * sizeof(double));
    if (e->rational) memcpy(e->w, p->weights, np * sizeof(double));
    return CJ_OK;
}

/* Appends piece (its triangles relabelled as patch q) to mesh; capacity was reserved. */
static void append_piece(cj_mesh *mesh, const cj_mesh *piece, int32_t q) {
    const size_t v0 = mesh->vertex_count, t0 = mesh->triangle_count;
    const size_t nv = piece->vertex_count, nt = piece->triangle_count;
    memcpy(mesh->positions + 3 * v0, piece->positions, 3 * nv * sizeof(double));
    memcpy(mesh->normals + 3 * v0, piece->normals, 3 * nv * sizeof(double));
    memcpy(mesh->uvs + 2 * v0, piece->uvs, 2 * nv * sizeof(double));
    for (size_t i = 0; i < 3 * nt; ++i)
        mesh->triangles[3 * t0 + i] = piece->triangles[i] + (uint32_t)v0;
    for (size_t t = 0; t < nt; ++t) mesh->triangle_patch[t0 + t] = q;
    mesh->vertex_count = v0 + nv;
    mesh->triangle_count = t0 + nt;
}

/* Index of old entries by hash (open addressing, slots hold index + 1). */
typedef struct hindex {
    size_t *slot, mask;
} hindex;

static cj_status index_build(cj_tess_cache *c, hindex *ix) {
    size_t n = 16;
    while (n < 2 * c->count) n *= 2;
    ix->slot = cj_allocator_alloc(&c->alloc, n * sizeof(size_t));
    if (!ix->slot) return cj_fail(CJ_ERR_NOMEM, "out of memory indexing the tessellation cache");
    memset(ix->slot, 0, n * sizeof(size_t));
    ix->mask = n - 1;
    for (size_t i = 0; i < c->count; ++i) {
        size_t s = (size_t)c->e[i].hash & ix->mask;
        while (ix->slot[s]) s = (s + 1) & ix->mask;
        ix->slot[s] = i + 1;
    }
    return CJ_OK;
}

static centry *index_find(cj_tess_cache *c, const hindex *ix, const cj_patch *p, uint64_t hash,
                          double tol, int cap) {
    for (size_t s = (size_t)hash & ix->mask; ix->slot[s]; s = (s + 1) & ix->mask) {
        centry *e = &c->e[ix->slot[s] - 1];
        if (entry_matches(e, p, hash, tol, cap)) return e;
    }
    return NULL;
}

cj_status cj_tess_cache_update(cj_tess_cache *c, const cj_patch *patches, size_t count,
                               const cj_tess_options *opt, cj_mesh *mesh, cj_tess_report *report,
                               cj_tess_cache_stats *stats) {
    assert(c != NULL && opt != NULL && mesh != NULL);
    assert(patches != NULL || count == 0);
    cj_tess_cache_stats w = {0, 0, 0, 0};
    cj_tess_report rep;
    memset(&rep, 0, sizeof rep);
    rep.measured = -1.0;
    if (opt->uniform != 0 || opt->measure != 0)
        return cj_fail(CJ_ERR_ARGUMENT,
                       "the tessellation cache is adaptive only (uniform %d, "
                       "measure %d must be 0)",
                       opt->uniform, opt->measure);
    if (opt->max_segments < 0)
        return cj_fail(CJ_ERR_ARGUMENT, "max_segments %d is negative", opt->max_segments);
    if (!isfinite(opt->tol)) return cj_fail(CJ_ERR_NONFINITE, "tolerance is not finite");
    if (!(opt->tol > 0.0)) return cj_fail(CJ_ERR_ARGUMENT, "tolerance %.17g must be > 0", opt->tol);
    const int cap = opt->max_segments ? opt->max_segments : CJ_TESS_DEFAULT_MAX_SEGMENTS;
    for (size_t q = 0; q < count; ++q) {
        const cj_status st = cj_patch_check(&patches[q]);
        if (st) return cj_fail(st, "patch %zu: %s", q, cj_last_error());
    }
    if (count > SIZE_MAX / (4 * sizeof(centry)))
        return cj_fail(CJ_ERR_NOMEM, "too many patches (%zu)", count);
    centry *ne = count ? cj_allocator_alloc(&c->alloc, count * sizeof *ne) : NULL;
    int *k = count ? cj_allocator_alloc(&c->alloc, 4 * count * sizeof(int)) : NULL;
    hindex ix = {NULL, 0};
    cj_status st = CJ_OK;
    if (count && (!ne || !k)) {
        st = cj_fail(CJ_ERR_NOMEM, "out of memory updating the tessellation cache");
    } else {
        if (count) memset(ne, 0, count * sizeof *ne);
        st = index_build(c, &ix);
    }
    size_t done = 0; /* ne[0..done) are initialised */
    /* 1. plans: kept when the patch (bit for bit), tol and cap are unchanged */
    for (size_t q = 0; q < count && !st; ++q, ++done) {
        const uint64_t h = patch_hash(&patches[q]);
        centry *old = index_find(c, &ix, &patches[q], h, opt->tol, cap);
        if (old) {
            ne[q] = *old;
            old->taken = 1;
            ne[q].taken = 0;
            ++w.plans_reused;
        } else {
            if ((st = check_cancel(c, q, 2 * count))) break; /* ne[q] not initialised */
            if ((st = entry_init(c, &ne[q], &patches[q], h, opt->tol, cap))) {
                ++done;
                break;
            }
            st = cj_tess_plan_patch(c->P, &patches[q], q, opt->tol, cap, c->scratch, &ne[q].plan,
                                    &rep.builds, &rep.trials);
            ne[q].have_plan = !st;
            ++w.planned;
        }
        if (!st) memcpy(k + 4 * q, ne[q].plan.k, sizeof ne[q].plan.k);
    }
    /* 2. shared sides: the largest count requested */
    if (!st) st = cj_tess_share_counts(patches, count, k, &c->alloc);
    /* 3. pieces: kept when the side counts are unchanged too */
    size_t nv = 0, nt = 0;
    for (size_t q = 0; q < count && !st; ++q) {
        centry *e = &ne[q];
        if (e->have_piece && memcmp(e->k, k + 4 * q, sizeof e->k) == 0) {
            ++w.pieces_reused;
        } else {
            if ((st = check_cancel(c, count + q, 2 * count))) break; /* e keeps its piece */
            e->have_piece = 0;
            if (!e->piece && (st = cj_mesh_create(&c->alloc, &e->piece))) break;
            cj_mesh_clear(e->piece);
            st = cj_tess_build_planned(c->P, &patches[q], q, opt->tol, cap, 0, k + 4 * q, &e->plan,
                                       e->piece, &e->used, &rep.builds, &rep.trials);
            ++w.built;
            if (st) break;
            e->have_piece = 1;
            memcpy(e->k, k + 4 * q, sizeof e->k);
            e->bound = c->P->bound;
            e->dropped = c->P->dropped;
        }
        nv += e->piece->vertex_count;
        nt += e->piece->triangle_count;
    }
    /* 4. the mesh: the pieces in patch order */
    if (!st) st = cj_mesh_reserve(mesh, mesh->vertex_count + nv, mesh->triangle_count + nt);
    if (!st)
        for (size_t q = 0; q < count; ++q) {
            const centry *e = &ne[q];
            append_piece(mesh, e->piece, (int32_t)q);
            rep.bound = fmax(rep.bound, e->bound);
            rep.dropped += e->dropped;
            if (e->used.nu > rep.max_nu) rep.max_nu = e->used.nu;
            if (e->used.nv > rep.max_nv) rep.max_nv = e->used.nv;
        }
    rep.vertices = nv;
    rep.triangles = nt;
    /* the cache now holds this update's patches (what was planned or built stays valid) */
    for (size_t q = done; q < count && ne; ++q) memset(&ne[q], 0, sizeof ne[q]);
    size_t kept = ne ? count : 0;
    if (st && ne) { /* a failed (cancelled) update keeps the old entries it has not reached */
        size_t untaken = 0;
        for (size_t i = 0; i < c->count; ++i) untaken += !c->e[i].taken;
        centry *merged =
            untaken ? cj_allocator_alloc(&c->alloc, (done + untaken) * sizeof *merged) : NULL;
        if (merged) {
            memcpy(merged, ne, done * sizeof *ne);
            kept = done;
            for (size_t i = 0; i < c->count; ++i)
                if (!c->e[i].taken) merged[kept++] = c->e[i];
            for (size_t q = 0; q < done; ++q) merged[q].taken = 0;
            cj_allocator_free(&c->alloc, ne);
            ne = merged;
            memset(c->e, 0, c->count * sizeof *c->e); /* moved, not freed */
        }
    }
    for (size_t i = 0; i < c->count; ++i)
        if (!c->e[i].taken) entry_free(c, &c->e[i]);
    cj_allocator_free(&c->alloc, c->e);
    c->e = ne;
    c->count = kept;
    cj_allocator_free(&c->alloc, k);
    cj_allocator_free(&c->alloc, ix.slot);
    c->totals.plans_reused += w.plans_reused;
    c->totals.planned += w.planned;
    c->totals.pieces_reused += w.pieces_reused;
    c->totals.built += w.built;
    if (stats) *stats = w;
    if (st) return st;
    if (report) *report = rep;
    return CJ_OK;
}

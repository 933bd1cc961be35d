/* casteljau: incremental adaptive tessellation of a patch list that changes a little between
 * calls (a designer dragging control points, a camera moving).
 *
 * Adaptive tessellation (tessellate.h, ADAPTIVE CHOICE) is three steps:
 *   plan(patch, tol)          -> the side counts the patch requests and its grid: a function
 *                                of the patch's control points (and weights) and tol alone;
 *   share(all requests)       -> every side shared by several patches gets the largest count
 *                                requested for it (watertight);
 *   build(patch, 4 counts, tol) -> the patch's mesh piece: a function of the patch, its four
 *                                side counts and tol alone.
 * The cache keeps, per patch, its plan keyed by (control points and weights bit for bit, tol,
 * segment cap) and its piece keyed by the same plus its four side counts. An update re-plans
 * only the patches it has not seen (edited ones), re-shares (cheap: a sort of the sides), and
 * rebuilds only the patches whose key or side counts changed: the edited ones and the
 * neighbours whose shared side count changed.
 * INVARIANT: the mesh of an update is bit-identical (same vertices, normals, (u,v), triangles,
 * triangle_patch, in the same order) to cj_tessellate_patches of the same patches and options
 * from scratch (tests/test_tess_cache.c checks it after long random edit sequences).
 * Patches are matched by content, not position: reordering, inserting or removing patches
 * reuses what is unchanged. Memory: entries, copies of the patches' control data and pieces
 * come from the allocator given at creation. Not thread-safe (one cache per thread).
 */
#ifndef CASTELJAU_TESS_CACHE_H
#define CASTELJAU_TESS_CACHE_H

#include "casteljau/alloc.h"
#include "casteljau/tessellate.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct cj_tess_cache cj_tess_cache;

/* Work of one update (or, summed, of all: cj_tess_cache_totals). */
typedef struct cj_tess_cache_stats {
    size_t plans_reused;  /* patches whose plan was kept */
    size_t planned;       /* patches planned */
    size_t pieces_reused; /* patches whose mesh piece was kept */
    size_t built;         /* patches built */
} cj_tess_cache_stats;

/* Creates an empty cache (alloc may be NULL: malloc/free). Status: CJ_ERR_NOMEM. */
cj_status cj_tess_cache_create(const cj_allocator *alloc, cj_tess_cache **out);
/* Releases the cache; NULL is a no-op. */
void cj_tess_cache_destroy(cj_tess_cache *cache);
/* Forgets every patch (the next update plans and builds everything). */
void cj_tess_cache_clear(cj_tess_cache *cache);

/* Appends the tessellation of `count` patches with `opt` to `mesh` (triangle_patch = patch
 * index), exactly as cj_tessellate_patches would (same mesh, same report), reusing the plans
 * and pieces of earlier updates as described above; then remembers these patches only.
 * Adaptive mode without measurement only: opt->uniform or opt->measure > 0 is
 * CJ_ERR_ARGUMENT. stats (may be NULL) receives this update's work.
 * Status: those of cj_tessellate_patches, CJ_ERR_CANCELLED (see CANCELLATION); on any failure
 * nothing is appended to the mesh (unlike cj_tessellate_patches, which keeps the patches before the
 * failing one) and the cache stays usable. */
cj_status cj_tess_cache_update(cj_tess_cache *cache, const cj_patch *patches, size_t count,
                               const cj_tess_options *opt, cj_mesh *mesh, cj_tess_report *report,
                               cj_tess_cache_stats *stats);

/* CANCELLATION. An update calls progress(user, done, total) before each patch it plans or builds
 * (not before patches whose plan and piece it reuses): done is the step about to start (q for
 * planning patch q, count + q for building it), total = 2 count. A nonzero return stops the
 * update at once: it returns CJ_ERR_CANCELLED, appends nothing to the mesh, and the cache keeps
 * every plan and piece finished so far and every entry of earlier updates not yet matched, so
 * the next update resumes the work (its mesh is still bit-identical to a one-shot tessellation;
 * tests/test_tess_cache.c cancels at every k-th step, then finishes). fn NULL: no calls. The
 * callback is called on the updating thread and must not use the cache. */
typedef int (*cj_tess_progress_fn)(void *user, size_t done, size_t total);
void cj_tess_cache_set_progress(cj_tess_cache *cache, cj_tess_progress_fn fn, void *user);

/* The work of all updates since creation. */
cj_tess_cache_stats cj_tess_cache_totals(const cj_tess_cache *cache);

#ifdef __cplusplus
}
#endif
#endif

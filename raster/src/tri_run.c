/* The rasterizer's tile pass on the shared scheduler (render_pool.h): tiles in row-major order,
 * one task each. Each worker owns its scratch planes and its tile's visibility samples, kept in
 * a cj_raster_workspace that a renderer holds across frames (a one-shot run makes its own). A
 * tile's result depends only on the tile, so the frame is the same for any thread count. */
#define _POSIX_C_SOURCE 200809L
#include "tri_internal.h"

#include "error_internal.h"
#include "render_internal.h"
#include "render_pool.h"
#include "render_progress.h"
#include "clock_internal.h"

#include <assert.h>
#include <string.h>

typedef struct worker_buf {
    cj_tri_scratch scratch;
    cj_vis_sample *samples;
} worker_buf;

struct cj_raster_workspace {
    cj_allocator alloc;
    int workers;
    size_t samples; /* per worker */
    worker_buf *w;
};

typedef struct run {
    const cj_raster_prep *prep;
    cj_tile_fn fn;
    void *user;
    worker_buf *w;
} run;

static void tile_task(void *user, int t, int worker) {
    run *r = user;
    const cj_raster_prep *p = r->prep;
    worker_buf *w = &r->w[worker];
    cj_tile tile;
    const int tx = t % p->tiles_x, ty = t / p->tiles_x;
    tile.x0 = tx * p->tile_size;
    tile.y0 = ty * p->tile_size;
    tile.x1 = tile.x0 + p->tile_size < p->width ? tile.x0 + p->tile_size : p->width;
    tile.y1 = tile.y0 + p->tile_size < p->height ? tile.y0 + p->tile_size : p->height;
    tile.spp = p->spp;
    tile.index = t;
    tile.thread = worker;
    tile.samples = w->samples;
    cj_tri_render_tile(p, &tile, &w->scratch, r->fn != NULL);
    if (r->fn) r->fn(r->user, &tile);
}

int cj_raster_thread_count(const cj_raster_prep *prep, int threads) {
    assert(prep);
    return cj_rpool_plan(threads, prep->tiles_x * prep->tiles_y);
}

cj_status cj_raster_workspace_create(const cj_allocator *alloc, cj_raster_workspace **out) {
    cj_allocator a = cj_render_alloc(alloc);
    cj_raster_workspace *ws = cj_ralloc(&a, sizeof *ws);
    if (!ws) return cj_fail(CJ_ERR_NOMEM, "raster workspace");
    memset(ws, 0, sizeof *ws);
    ws->alloc = a;
    *out = ws;
    return CJ_OK;
}

static void release(cj_raster_workspace *ws) {
    for (int i = 0; i < ws->workers; ++i) {
        cj_rfree(&ws->alloc, ws->w[i].scratch.depth);
        cj_rfree(&ws->alloc, ws->w[i].scratch.id);
        cj_rfree(&ws->alloc, ws->w[i].samples);
    }
    cj_rfree(&ws->alloc, ws->w);
    ws->w = NULL;
    ws->workers = 0;
    ws->samples = 0;
}

void cj_raster_workspace_destroy(cj_raster_workspace *ws) {
    if (!ws) return;
    release(ws);
    cj_allocator a = ws->alloc;
    cj_rfree(&a, ws);
}

/* Buffers for `workers` workers of n samples each: kept when large enough (*reused = 1). */
static cj_status reserve(cj_raster_workspace *ws, int workers, size_t n, int *reused) {
    *reused = workers <= ws->workers && n <= ws->samples;
    if (*reused) return CJ_OK;
    if (workers < ws->workers) workers = ws->workers;
    if (n < ws->samples) n = ws->samples;
    release(ws);
    ws->w = cj_ralloc(&ws->alloc, (size_t)workers * sizeof *ws->w);
    if (!ws->w) return cj_fail(CJ_ERR_NOMEM, "raster: no memory for %d workers", workers);
    memset(ws->w, 0, (size_t)workers * sizeof *ws->w);
    ws->workers = workers;
    ws->samples = n;
    for (int i = 0; i < workers; ++i) {
        /* +8: the span kernels touch up to seven samples past a span (unchanged). */
        ws->w[i].scratch.depth = cj_ralloc(&ws->alloc, (n + 8) * sizeof(float));
        ws->w[i].scratch.id = cj_ralloc(&ws->alloc, (n + 8) * sizeof(uint32_t));
        ws->w[i].samples = cj_ralloc(&ws->alloc, n * sizeof(cj_vis_sample));
        if (!ws->w[i].scratch.depth || !ws->w[i].scratch.id || !ws->w[i].samples) {
            release(ws);
            return cj_fail(CJ_ERR_NOMEM, "raster: no memory for the tile buffers of %d threads",
                           workers);
        }
    }
    return CJ_OK;
}

cj_status cj_raster_run_on(const cj_raster_prep *prep, struct cj_rpool *pool, int threads,
                           cj_raster_workspace *ws, cj_tile_fn fn, void *user,
                           struct cj_rprogress *progress, cj_raster_stats *stats,
                           int *buffers_reused) {
    assert(prep && pool && ws);
    const double t0 = cj_clock_seconds();
    if (threads < 0) return cj_fail(CJ_ERR_RANGE, "raster: thread count %d is negative", threads);
    threads = cj_raster_thread_count(prep, threads);
    if (threads > cj_rpool_threads(pool)) threads = cj_rpool_threads(pool);
    const int tw = prep->tile_size < prep->width ? prep->tile_size : prep->width;
    const int th = prep->tile_size < prep->height ? prep->tile_size : prep->height;
    const size_t n = (size_t)tw * (size_t)th * (size_t)prep->spp;
    int reused = 0;
    cj_status st = reserve(ws, threads, n, &reused);
    if (st) return st;
    if (buffers_reused) *buffers_reused = reused;
    for (int i = 0; i < threads; ++i) ws->w[i].scratch.tested = ws->w[i].scratch.written = 0;
    run r = {prep, fn, user, ws->w};
    const int cancelled =
        cj_rpool_run(pool, prep->tiles_x * prep->tiles_y, threads, tile_task, &r, progress);
    if (cancelled) return cj_fail(CJ_ERR_CANCELLED, "raster: cancelled by the progress callback");
    if (stats) {
        uint64_t tested = 0, written = 0;
        for (int i = 0; i < threads; ++i) {
            tested += ws->w[i].scratch.tested;
            written += ws->w[i].scratch.written;
        }
        stats->samples_tested = tested;
        stats->samples_written = written;
        stats->seconds_raster = cj_clock_seconds() - t0;
    }
    return CJ_OK;
}

cj_status cj_raster_run(const cj_raster_prep *prep, int threads, cj_tile_fn fn, void *user,
                        cj_rprogress *progress, cj_raster_stats *stats) {
    assert(prep);
    if (threads < 0) return cj_fail(CJ_ERR_RANGE, "raster: thread count %d is negative", threads);
    cj_rpool *pool = NULL;
    cj_raster_workspace *ws = NULL;
    cj_status st = cj_rpool_create(cj_raster_thread_count(prep, threads), &prep->alloc, &pool);
    if (!st) st = cj_raster_workspace_create(&prep->alloc, &ws);
    if (!st) st = cj_raster_run_on(prep, pool, threads, ws, fn, user, progress, stats, NULL);
    cj_raster_workspace_destroy(ws);
    cj_rpool_destroy(pool);
    return st;
}

/* The tile scheduler: `threads` workers (the calling thread is worker 0) take tiles in
 * row-major order from an atomic counter. Each worker owns its scratch planes and its tile's
 * visibility samples, allocated once per run. A tile's result depends only on the tile, so
 * the frame is the same for any thread count. */
#define _POSIX_C_SOURCE 200809L
#include "tri_internal.h"

#include "error_internal.h"
#include "render_progress.h"

#include <assert.h>
#include <pthread.h>
#include <stdatomic.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

typedef struct worker {
    struct run *run;
    int index;
    cj_tri_scratch scratch;
    cj_vis_sample *samples;
    pthread_t thread;
    int started;
} worker;

typedef struct run {
    const cj_raster_prep *prep;
    cj_tile_fn fn;
    void *user;
    cj_rprogress *progress;
    atomic_int next;
    int tiles;
} run;

static void *work(void *arg) {
    worker *w = arg;
    run *r = w->run;
    const cj_raster_prep *p = r->prep;
    for (;;) {
        if (cj_rprogress_stopped(r->progress)) break;
        const int t = atomic_fetch_add(&r->next, 1);
        if (t >= r->tiles) break;
        cj_tile tile;
        const int tx = t % p->tiles_x, ty = t / p->tiles_x;
        tile.x0 = tx * p->tile_size;
        tile.y0 = ty * p->tile_size;
        tile.x1 = tile.x0 + p->tile_size < p->width ? tile.x0 + p->tile_size : p->width;
        tile.y1 = tile.y0 + p->tile_size < p->height ? tile.y0 + p->tile_size : p->height;
        tile.spp = p->spp;
        tile.index = t;
        tile.thread = w->index;
        tile.samples = w->samples;
        cj_tri_render_tile(p, &tile, &w->scratch, r->fn != NULL);
        if (r->fn) r->fn(r->user, &tile);
        cj_rprogress_tile_done(r->progress);
    }
    return NULL;
}

static double wall(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

int cj_raster_thread_count(const cj_raster_prep *prep, int threads) {
    assert(prep);
    if (threads <= 0) {
        const long n = sysconf(_SC_NPROCESSORS_ONLN);
        threads = n > 0 ? (int)(n < 256 ? n : 256) : 1;
    }
    const int tiles = prep->tiles_x * prep->tiles_y;
    return threads < tiles ? threads : tiles;
}

cj_status cj_raster_run(const cj_raster_prep *prep, int threads, cj_tile_fn fn, void *user,
                        cj_rprogress *progress, cj_raster_stats *stats) {
    assert(prep);
    const double t0 = wall();
    if (threads < 0) return cj_fail(CJ_ERR_RANGE, "raster: thread count %d is negative", threads);
    threads = cj_raster_thread_count(prep, threads);
    run r;
    r.prep = prep;
    r.fn = fn;
    r.user = user;
    r.progress = progress;
    r.tiles = prep->tiles_x * prep->tiles_y;
    atomic_init(&r.next, 0);
    const cj_allocator *a = &prep->alloc;
    const int tw = prep->tile_size < prep->width ? prep->tile_size : prep->width;
    const int th = prep->tile_size < prep->height ? prep->tile_size : prep->height;
    const size_t n = (size_t)tw * (size_t)th * (size_t)prep->spp;
    worker *ws = a->alloc(a->user, (size_t)threads * sizeof *ws);
    if (!ws) return cj_fail(CJ_ERR_NOMEM, "raster: no memory for %d workers", threads);
    memset(ws, 0, (size_t)threads * sizeof *ws);
    cj_status st = CJ_OK;
    for (int i = 0; i < threads; ++i) {
        ws[i].run = &r;
        ws[i].index = i;
        /* +4: the span kernels touch up to three samples past a span (unchanged). */
        ws[i].scratch.depth = a->alloc(a->user, (n + 4) * sizeof(float));
        ws[i].scratch.id = a->alloc(a->user, (n + 4) * sizeof(uint32_t));
        ws[i].samples = a->alloc(a->user, n * sizeof(cj_vis_sample));
        if (!ws[i].scratch.depth || !ws[i].scratch.id || !ws[i].samples) {
            st = cj_fail(CJ_ERR_NOMEM, "raster: no memory for the tile buffers of %d threads",
                         threads);
            break;
        }
    }
    if (st == CJ_OK) {
        /* A thread that cannot be started is not an error: the others take its tiles. */
        for (int i = 1; i < threads; ++i)
            ws[i].started = pthread_create(&ws[i].thread, NULL, work, &ws[i]) == 0;
        work(&ws[0]);
        for (int i = 1; i < threads; ++i)
            if (ws[i].started) pthread_join(ws[i].thread, NULL);
    }
    uint64_t tested = 0, written = 0;
    for (int i = 0; i < threads; ++i) {
        tested += ws[i].scratch.tested;
        written += ws[i].scratch.written;
        a->free(a->user, ws[i].scratch.depth);
        a->free(a->user, ws[i].scratch.id);
        a->free(a->user, ws[i].samples);
    }
    a->free(a->user, ws);
    if (st == CJ_OK && cj_rprogress_stopped(progress))
        st = cj_fail(CJ_ERR_CANCELLED, "raster: cancelled by the progress callback");
    if (st == CJ_OK && stats) {
        stats->samples_tested = tested;
        stats->samples_written = written;
        stats->seconds_raster = wall() - t0;
    }
    return st;
}

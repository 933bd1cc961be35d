/* The progress gate of a render (cj_render_progress_fn, casteljau/render.h): tile schedulers
 * report each finished tile here; it serialises the caller's callback and turns a nonzero
 * answer into a stop flag that every worker reads before taking its next tile. */
#ifndef CJ_RENDER_PROGRESS_H
#define CJ_RENDER_PROGRESS_H

#include "casteljau/render.h"

#include <pthread.h>
#include <stdatomic.h>
#include <stdint.h>

typedef struct cj_rprogress {
    cj_render_progress_fn fn; /* NULL: tiles are only counted */
    void *user;
    pthread_mutex_t lock;
    uint64_t done, total;
    atomic_int stop;
} cj_rprogress;

/* total = the tiles the run will finish; fn/user from the options (opt may be NULL). */
void cj_rprogress_init(cj_rprogress *p, const cj_render_options *opt, uint64_t total);
void cj_rprogress_destroy(cj_rprogress *p);
/* A worker finished one tile: counts it and calls the callback. */
void cj_rprogress_tile_done(cj_rprogress *p);
/* Whether the run was cancelled (checked before taking a tile). p may be NULL. */
static inline int cj_rprogress_stopped(cj_rprogress *p) {
    return p && atomic_load_explicit(&p->stop, memory_order_relaxed);
}

#endif

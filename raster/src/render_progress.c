/* The progress gate: see render_progress.h. */
#include "render_progress.h"

#include <string.h>

void cj_rprogress_init(cj_rprogress *p, const cj_render_options *opt, uint64_t total) {
    memset(p, 0, sizeof *p);
    p->fn = opt ? opt->progress : NULL;
    p->user = opt ? opt->progress_user : NULL;
    p->total = total;
    pthread_mutex_init(&p->lock, NULL);
    atomic_init(&p->stop, 0);
}

void cj_rprogress_destroy(cj_rprogress *p) {
    pthread_mutex_destroy(&p->lock);
}

void cj_rprogress_tile_done(cj_rprogress *p) {
    if (!p) return;
    pthread_mutex_lock(&p->lock);
    uint64_t done = ++p->done;
    /* one call at a time, in order of `done`: the lock is held across the callback */
    if (p->fn && !atomic_load(&p->stop) && p->fn(p->user, done, p->total))
        atomic_store(&p->stop, 1);
    pthread_mutex_unlock(&p->lock);
}

/* The worker pool and its tile scheduler: see render_pool.h. Workers sleep on a condition
 * variable between jobs; a job is announced by bumping a generation counter, and the caller
 * waits until every pool thread has acknowledged it, so the job's data may live on the
 * caller's stack. */
#define _POSIX_C_SOURCE 200809L
#include "render_pool.h"

#include "error_internal.h"
#include "render_internal.h"

#include <pthread.h>
#include <stdatomic.h>
#include <string.h>
#include <unistd.h>

typedef struct pool_job {
    cj_rpool_fn fn;
    void *user;
    cj_rprogress *progress;
    int ntasks, use;
    atomic_int next;
} pool_job;

typedef struct pool_thread {
    struct cj_rpool *pool;
    int index;
    pthread_t thread;
} pool_thread;

struct cj_rpool {
    cj_allocator alloc;
    pthread_mutex_t lock;
    pthread_cond_t wake, idle;
    unsigned long generation; /* bumped per job */
    int quit;
    int busy;      /* pool threads still inside the current job */
    pool_job *job; /* the current job, valid while generation is new to a worker */
    int nthreads;  /* pool threads started (workers 1..nthreads) */
    pool_thread *threads;
};

static void run_tasks(pool_job *j, int worker) {
    for (;;) {
        if (cj_rprogress_stopped(j->progress)) break;
        const int t = atomic_fetch_add(&j->next, 1);
        if (t >= j->ntasks) break;
        j->fn(j->user, t, worker);
        cj_rprogress_tile_done(j->progress);
    }
}

static void *pool_main(void *arg) {
    pool_thread *self = arg;
    cj_rpool *p = self->pool;
    unsigned long seen = 0;
    pthread_mutex_lock(&p->lock);
    for (;;) {
        while (!p->quit && p->generation == seen) pthread_cond_wait(&p->wake, &p->lock);
        if (p->quit) break;
        seen = p->generation;
        pool_job *j = p->job;
        pthread_mutex_unlock(&p->lock);
        if (self->index < j->use) run_tasks(j, self->index);
        pthread_mutex_lock(&p->lock);
        if (--p->busy == 0) pthread_cond_signal(&p->idle);
    }
    pthread_mutex_unlock(&p->lock);
    return NULL;
}

int cj_rpool_plan(int threads, int ntasks) {
    if (threads <= 0) {
        const int n = cj_cpu_count();
        threads = n < 256 ? n : 256;
    }
    if (threads > 256) threads = 256;
    if (threads > ntasks) threads = ntasks;
    return threads < 1 ? 1 : threads;
}

cj_status cj_rpool_create(int threads, const cj_allocator *alloc, cj_rpool **out) {
    cj_allocator a = cj_render_alloc(alloc);
    if (threads < 1) threads = 1;
    cj_rpool *p = a.alloc(a.user, sizeof *p);
    if (!p) return cj_fail(CJ_ERR_NOMEM, "worker pool of %d threads", threads);
    memset(p, 0, sizeof *p);
    p->alloc = a;
    pthread_mutex_init(&p->lock, NULL);
    pthread_cond_init(&p->wake, NULL);
    pthread_cond_init(&p->idle, NULL);
    if (threads > 1) {
        p->threads = a.alloc(a.user, sizeof *p->threads * (size_t)(threads - 1));
        if (!p->threads) {
            cj_rpool_destroy(p);
            return cj_fail(CJ_ERR_NOMEM, "worker pool of %d threads", threads);
        }
        for (int i = 0; i < threads - 1; ++i) {
            pool_thread *t = &p->threads[p->nthreads];
            t->pool = p;
            t->index = p->nthreads + 1;
            if (pthread_create(&t->thread, NULL, pool_main, t) != 0) break;
            ++p->nthreads;
        }
    }
    *out = p;
    return CJ_OK;
}

void cj_rpool_destroy(cj_rpool *p) {
    if (!p) return;
    pthread_mutex_lock(&p->lock);
    p->quit = 1;
    pthread_cond_broadcast(&p->wake);
    pthread_mutex_unlock(&p->lock);
    for (int i = 0; i < p->nthreads; ++i) pthread_join(p->threads[i].thread, NULL);
    pthread_cond_destroy(&p->wake);
    pthread_cond_destroy(&p->idle);
    pthread_mutex_destroy(&p->lock);
    cj_allocator a = p->alloc;
    if (p->threads) a.free(a.user, p->threads);
    a.free(a.user, p);
}

int cj_rpool_threads(const cj_rpool *p) {
    return p->nthreads + 1;
}

int cj_rpool_run(cj_rpool *p, int ntasks, int use, cj_rpool_fn fn, void *user,
                 cj_rprogress *progress) {
    pool_job j;
    j.fn = fn;
    j.user = user;
    j.progress = progress;
    j.ntasks = ntasks;
    j.use = use < 1 ? 1 : (use > p->nthreads + 1 ? p->nthreads + 1 : use);
    atomic_init(&j.next, 0);
    const int helpers = j.use - 1;
    if (helpers > 0) {
        pthread_mutex_lock(&p->lock);
        p->job = &j;
        p->busy = p->nthreads; /* every pool thread acknowledges, helping or not */
        ++p->generation;
        pthread_cond_broadcast(&p->wake);
        pthread_mutex_unlock(&p->lock);
    }
    run_tasks(&j, 0);
    if (helpers > 0) {
        pthread_mutex_lock(&p->lock);
        while (p->busy > 0) pthread_cond_wait(&p->idle, &p->lock);
        p->job = NULL;
        pthread_mutex_unlock(&p->lock);
    }
    return cj_rprogress_stopped(progress);
}

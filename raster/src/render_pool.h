/* The one tile scheduler of both back ends (the rasterizer's cj_raster_run and the ray
 * tracer), on a pool of persistent worker threads that a cj_renderer creates once and keeps
 * across frames (a one-shot run makes a pool for itself).
 *
 * A run hands out tasks 0..ntasks-1 IN ORDER from one atomic counter to `use` workers: the
 * calling thread is worker 0, pool threads are workers 1..use-1. Before taking a task a worker
 * reads the progress gate (render_progress.h) and stops once it is cancelled; after each task
 * it reports it there. A task's result must depend only on the task, never on the worker, so
 * the picture is the same for any thread count. A pool runs one job at a time: a renderer, and
 * so its pool, is used by one thread at a time. */
#ifndef CJ_RENDER_POOL_H
#define CJ_RENDER_POOL_H

#include "casteljau/alloc.h"
#include "casteljau/status.h"
#include "render_progress.h"

typedef struct cj_rpool cj_rpool;

/* fn(user, task, worker): worker in 0..use-1 indexes per-worker scratch. */
typedef void (*cj_rpool_fn)(void *user, int task, int worker);

/* A pool of `threads` workers (>= 1; threads - 1 pthreads are started here and wait for
 * jobs). A thread that cannot be started is not an error: the pool simply has fewer workers
 * (cj_rpool_threads tells). CJ_ERR_NOMEM. */
cj_status cj_rpool_create(int threads, const cj_allocator *alloc, cj_rpool **out);
/* Stops and joins the threads. NULL is ignored. */
void cj_rpool_destroy(cj_rpool *pool);
/* The workers the pool has (the caller included). */
int cj_rpool_threads(const cj_rpool *pool);
/* The workers a run of `ntasks` tasks asked for with `threads` (0 = one per core this process
 * may use, cj_cpu_count) uses: never more than the tasks, never more than 256, at least 1. */
int cj_rpool_plan(int threads, int ntasks);
/* The cores this process may use (cpu_count.c): the online CPUs, cut to the affinity mask
 * (sched_getaffinity) and to the cgroup v2 quota (/sys/fs/cgroup/cpu.max); at least 1. */
int cj_cpu_count(void);
/* The CPUs a cgroup v2 cpu.max line allows, rounded up ("150000 100000" -> 2), or 0 for "max"
 * (no limit) and for text that is not a quota. */
int cj_cpu_quota_parse(const char *text);
/* Runs tasks 0..ntasks-1 on min(use, cj_rpool_threads(pool)) workers and returns when every
 * started task has finished. progress may be NULL. Returns 1 when the gate was cancelled. */
int cj_rpool_run(cj_rpool *pool, int ntasks, int use, cj_rpool_fn fn, void *user,
                 cj_rprogress *progress);

#endif

/* The render thread of `casteljau view` (viewer_render.h): jobs, cancellation, progressive
 * ray-traced passes, and the one function that calls the library's renderers. */
#define _POSIX_C_SOURCE 200809L
#include "viewer_render.h"

#include "casteljau/render.h"
#include "casteljau/renderer.h"
#include "casteljau/trace.h"
#include "error_internal.h"
#include "clock_internal.h"

#include <math.h>
#include <pthread.h>
#include <stdarg.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>

const int cj_vtrace_spp[VIEW_TRACE_PASSES] = {1, 1, 4, 16, 64};

int cj_vtrace_scale(int pass, int width, int height) {
    if (pass > 0) return 1;
    const int s = (int)ceil(sqrt((double)width * (double)height / 16384.0));
    return s < 1 ? 1 : s > 16 ? 16 : s;
}

struct cj_vrender {
    int width, height, threads;
    FILE *timeline;
    void (*wake)(void);
    pthread_t thread;
    int started;
    pthread_mutex_t lock, log_lock;
    pthread_cond_t changed;
    /* under `lock` */
    cj_vjob pending;
    int has_pending, running, running_cancellable, quit, frame_new;
    /* a drag frame may be dropped while it tessellates (running_droppable) when a newer drag
     * state arrives, unless the drag frame before it was dropped (last_dropped): so at least
     * every other drag frame is shown however fast the events come */
    int running_droppable, last_dropped;
    cj_vframe frames[3]; /* [work] drawn into by the thread, [done] newest finished, [shown] */
    int work, done, shown;
    /* set by the window's thread, read by the progress callback */
    atomic_int cancel;
    atomic_int drop; /* a newer drag state: drop the running drag frame if still preparing */
    atomic_uint_fast64_t tiles_done, tiles_total;
    /* the render thread's own: one renderer for the viewer's lifetime (its pool, tile buffers,
     * BVHs and image live across frames and passes), and the tessellation cache it is given */
    cj_renderer *ren;
    cj_render_image *img;
    cj_render_cache *cache;
    int cache_exact; /* every entry was made for the view `cache_view` at its tolerance */
    uint64_t cache_view;
};

void cj_vrender_log(cj_vrender *r, const char *fmt, ...) {
    if (!r || !r->timeline) return;
    pthread_mutex_lock(&r->log_lock);
    fprintf(r->timeline, "%.6f ", cj_clock_seconds());
    va_list ap;
    va_start(ap, fmt);
    vfprintf(r->timeline, fmt, ap);
    va_end(ap);
    fputc('\n', r->timeline);
    fflush(r->timeline);
    pthread_mutex_unlock(&r->log_lock);
}

/* ---- snapshot ------------------------------------------------------------------------------ */

cj_status cj_vscene_snapshot(const cj_scene *src, cj_scene **out) {
    cj_scene *s = NULL;
    cj_status st = cj_scene_create(NULL, &s);
    if (st) return st;
    int idx;
    st = cj_scene_set_camera(s, cj_scene_get_camera(src));
    if (!st) st = cj_scene_set_settings(s, cj_scene_get_settings(src));
    for (size_t i = 0; !st && i < cj_scene_light_count(src); ++i)
        st = cj_scene_add_light(s, cj_scene_light(src, (int)i), &idx);
    for (size_t i = 0; !st && i < cj_scene_texture_count(src); ++i) {
        st = cj_scene_add_texture(s, cj_scene_texture(src, (int)i), &idx);
        if (!st) st = cj_scene_set_texture_name(s, idx, cj_scene_texture_name(src, (int)i));
        if (!st) st = cj_scene_set_texture_source(s, idx, cj_scene_texture_source(src, (int)i));
    }
    for (size_t i = 0; !st && i < cj_scene_material_count(src); ++i) {
        st = cj_scene_add_material(s, cj_scene_material(src, (int)i), &idx);
        if (!st) st = cj_scene_set_material_name(s, idx, cj_scene_material_name(src, (int)i));
    }
    for (size_t i = 0; !st && i < cj_scene_geometry_count(src); ++i)
        st = cj_scene_add_geometry(s, cj_scene_geometry(src, (int)i), &idx);
    for (size_t i = 0; !st && i < cj_scene_node_count(src); ++i)
        st = cj_scene_add_node(s, cj_scene_node(src, (int)i), &idx);
    if (st) {
        cj_scene_destroy(s);
        return st;
    }
    *out = s;
    return CJ_OK;
}

/* ---- drawing ------------------------------------------------------------------------------- */

/* The renderer's progress: (0, 0) while it prepares the frame (the tessellation cache asks
 * before each patch it plans or builds), then tiles done of total. A drag frame is dropped only
 * while it prepares: the cache keeps every patch finished, so the next frame resumes the work;
 * once tiles are drawn it is cheaper to finish and show it. */
static int on_progress(void *user, uint64_t done, uint64_t total) {
    cj_vrender *r = user;
    atomic_store(&r->tiles_done, done);
    atomic_store(&r->tiles_total, total);
    if (total == 0 && atomic_load(&r->drop)) return 1;
    return atomic_load(&r->cancel);
}

/* FNV-1a over what decides the tessellation tolerance of every object: camera, settings and
 * the nodes' transforms and visibility. */
static uint64_t view_key(const cj_scene *s) {
    uint64_t h = 1469598103934665603ull;
#define MIX(ptr, bytes)                                                                            \
    do {                                                                                           \
        const unsigned char *b_ = (const unsigned char *)(ptr);                                    \
        for (size_t k_ = 0; k_ < (bytes); ++k_) h = (h ^ b_[k_]) * 1099511628211ull;               \
    } while (0)
    const cj_camera *cam = cj_scene_get_camera(s);
    const cj_scene_settings *set = cj_scene_get_settings(s);
    MIX(&cam->eye, sizeof cam->eye);
    MIX(&cam->gaze, sizeof cam->gaze);
    MIX(&cam->up, sizeof cam->up);
    MIX(&cam->near, sizeof cam->near);
    MIX(&cam->far, sizeof cam->far);
    MIX(&cam->fov_y, sizeof cam->fov_y);
    MIX(&cam->ortho_height, sizeof cam->ortho_height);
    MIX(&set->width, sizeof set->width);
    MIX(&set->height, sizeof set->height);
    MIX(&set->tol_px, sizeof set->tol_px);
    for (size_t i = 0; i < cj_scene_node_count(s); ++i) {
        const cj_node *n = cj_scene_node(s, (int)i);
        MIX(&n->local, sizeof n->local);
        MIX(&n->visible, sizeof n->visible);
    }
#undef MIX
    return h;
}

/* THE ONE PLACE where the viewer calls the library's renderer: pass `pass` of a job into
 * frame f, through the viewer's one cj_renderer (casteljau/renderer.h). The rasterizer keeps a
 * tessellation cache for the viewer's lifetime; a drag may reuse meshes within their tolerance
 * band, while a still view is drawn exactly as `casteljau render` draws it: from a cache whose
 * every entry was made for this very view, else from a fresh one. */
static cj_status draw(cj_vrender *r, const cj_vjob *job, int pass, cj_vframe *f) {
    cj_render_options ro = cj_render_options_defaults();
    ro.threads = r->threads;
    ro.progress = on_progress;
    ro.progress_user = r;
    cj_render_image *img = NULL;
    cj_renderer_options rop = cj_renderer_options_defaults();
    cj_stage_report rep;
    cj_status st;
    int scale = 1;
    const double t0 = cj_clock_seconds();
    if (job->trace) {
        scale = cj_vtrace_scale(pass, r->width, r->height);
        ro.spp = cj_vtrace_spp[pass];
        ro.width = (r->width + scale - 1) / scale;
        ro.height = (r->height + scale - 1) / scale;
        /* about the same work per tile at every spp, so a cancel lands within one tile's time;
         * any tile size gives the same image */
        ro.tile_size = ro.spp >= 16 ? 8 : ro.spp >= 4 ? 16 : 32;
        rop.render = ro;
        st = cj_renderer_set_options(r->ren, &rop);
        if (!st) st = cj_renderer_draw(r->ren, job->scene, CJ_BACKEND_TRACE, 0, &r->img, &rep);
    } else {
        const uint64_t key = view_key(job->scene);
        cj_render_cache *fresh = NULL;
        if (job->interactive) {
            /* a drag frame is a preview: 1 sample per pixel and at least 1 px of tessellation
             * tolerance; the still view after the drag has the scene's */
            const double tol = cj_scene_get_settings(job->scene)->tol_px;
            ro.spp = 1;
            ro.tol_px = tol > VIEW_DRAG_TOL_PX ? tol : VIEW_DRAG_TOL_PX;
        }
        if (job->interactive || (r->cache_exact && key == r->cache_view)) {
            ro.cache = r->cache;
        } else if (!cj_render_cache_create(NULL, &fresh)) {
            ro.cache = fresh;
        }
        rop.render = ro;
        st = cj_renderer_set_options(r->ren, &rop);
        if (!st)
            st = cj_renderer_draw(r->ren, job->scene, CJ_BACKEND_RASTER, CJ_IMAGE_DEPTH, &r->img,
                                  &rep);
        if (fresh && !st) {
            cj_render_cache_destroy(r->cache);
            r->cache = fresh;
            r->cache_exact = 1;
            r->cache_view = key;
        } else if (fresh) {
            cj_render_cache_destroy(fresh);
        } else if (job->interactive) {
            r->cache_exact = 0;
        }
    }
    if (st) return st;
    img = r->img;
    f->seconds = cj_clock_seconds() - t0;
    f->spp = ro.spp ? ro.spp : cj_scene_get_settings(job->scene)->spp;
    f->tol_px = ro.tol_px > 0 ? ro.tol_px : cj_scene_get_settings(job->scene)->tol_px;
    /* nearest upscaling of a low-resolution pass; alpha 255 (the window shows opaque pixels) */
    const size_t w = (size_t)r->width, h = (size_t)r->height, iw = (size_t)img->width;
    if (scale == 1) {
        st = cj_render_image_to_srgb8(img, f->rgba8, 0);
    } else {
        uint8_t *small = malloc(iw * (size_t)img->height * 4);
        st = small ? cj_render_image_to_srgb8(img, small, 0)
                   : cj_fail(CJ_ERR_NOMEM, "viewer: out of memory for a preview");
        for (size_t y = 0; !st && y < h; ++y)
            for (size_t x = 0; x < w; ++x)
                memcpy(f->rgba8 + 4 * (y * w + x), small + 4 * ((y / scale) * iw + x / scale), 4);
        free(small);
    }
    for (size_t i = 0; i < w * h; ++i) f->rgba8[4 * i + 3] = 255;
    if (img->depth && f->depth) memcpy(f->depth, img->depth, w * h * sizeof *f->depth);
    f->triangles = 0;
    f->planned = f->built = 0;
    f->bound_px = 0;
    for (int i = 0; i < rep.count; ++i) {
        const cj_stage *s = &rep.stages[i];
        if (!strncmp(s->name, "tessellate", 10) && s->ran) f->triangles += (size_t)s->out;
        for (int k = 0; k < s->extra_count; ++k)
            if (!strcmp(s->extra[k].key, "bound_px") && s->extra[k].value > f->bound_px)
                f->bound_px = s->extra[k].value;
            else if (!strcmp(s->extra[k].key, "patches_planned"))
                f->planned += (size_t)s->extra[k].value;
            else if (!strcmp(s->extra[k].key, "patches_built"))
                f->built += (size_t)s->extra[k].value;
    }
    return st;
}

/* ---- the thread ---------------------------------------------------------------------------- */

/* Hands the work frame over as the newest finished one (under the lock). */
static void publish(cj_vrender *r) {
    const int t = r->done;
    r->done = r->work;
    r->work = t;
    r->frame_new = 1;
}

static void *thread_main(void *arg) {
    cj_vrender *r = arg;
    pthread_mutex_lock(&r->lock);
    for (;;) {
        while (!r->has_pending && !r->quit) pthread_cond_wait(&r->changed, &r->lock);
        if (r->quit) break;
        const cj_vjob job = r->pending;
        r->has_pending = 0;
        r->running = 1;
        r->running_cancellable = job.trace || !job.interactive;
        r->running_droppable = !job.trace && job.interactive && !r->last_dropped;
        atomic_store(&r->cancel, 0);
        atomic_store(&r->drop, 0);
        pthread_mutex_unlock(&r->lock);
        for (int pass = job.first_pass; pass <= job.last_pass; ++pass) {
            cj_vframe *f = &r->frames[r->work]; /* only this thread touches [work] */
            atomic_store(&r->tiles_done, 0);
            atomic_store(&r->tiles_total, 0);
            cj_vrender_log(r, "start gen %lu %s pass %d", job.gen, job.trace ? "trace" : "raster",
                           job.trace ? pass : 0);
            const cj_status st = draw(r, &job, pass, f);
            const uint64_t done = atomic_load(&r->tiles_done), total = atomic_load(&r->tiles_total);
            if (st == CJ_ERR_CANCELLED) {
                const int dropped = !atomic_load(&r->cancel) && atomic_load(&r->drop);
                cj_vrender_log(r, "cancelled gen %lu pass %d tiles %llu/%llu%s", job.gen,
                               job.trace ? pass : 0, (unsigned long long)done,
                               (unsigned long long)total, dropped ? " preparing drag" : "");
                pthread_mutex_lock(&r->lock);
                r->last_dropped = dropped;
                pthread_mutex_unlock(&r->lock);
                break;
            }
            f->gen = job.gen;
            f->trace = job.trace;
            f->pass = job.trace ? pass : 0;
            f->status = st;
            f->tiles = done;
            snprintf(f->msg, sizeof f->msg, "%s", st ? cj_last_error() : "");
            cj_vrender_log(r, "done gen %lu pass %d tiles %llu/%llu in %.3f s patches %zu/%zu",
                           job.gen, f->pass, (unsigned long long)done, (unsigned long long)total,
                           f->seconds, f->planned, f->built);
            pthread_mutex_lock(&r->lock);
            publish(r);
            r->last_dropped = 0;
            const int stop = r->has_pending || r->quit || st;
            pthread_mutex_unlock(&r->lock);
            if (r->wake) r->wake();
            if (stop) break;
        }
        cj_scene_destroy(job.scene);
        pthread_mutex_lock(&r->lock);
        r->running = 0;
        pthread_cond_broadcast(&r->changed);
    }
    pthread_mutex_unlock(&r->lock);
    return NULL;
}

cj_status cj_vrender_create(int width, int height, int threads, FILE *timeline, void (*wake)(void),
                            cj_vrender **out) {
    cj_vrender *r = calloc(1, sizeof *r);
    if (!r) return cj_fail(CJ_ERR_NOMEM, "viewer: out of memory for the render thread");
    r->width = width, r->height = height, r->threads = threads;
    r->timeline = timeline;
    r->wake = wake;
    r->work = 0, r->done = 1, r->shown = 2;
    pthread_mutex_init(&r->lock, NULL);
    pthread_mutex_init(&r->log_lock, NULL);
    pthread_cond_init(&r->changed, NULL);
    atomic_init(&r->cancel, 0);
    atomic_init(&r->drop, 0);
    atomic_init(&r->tiles_done, 0);
    atomic_init(&r->tiles_total, 0);
    const size_t n = (size_t)width * (size_t)height;
    cj_status st = cj_render_cache_create(NULL, &r->cache);
    if (!st) st = cj_renderer_create(NULL, NULL, &r->ren);
    for (int i = 0; i < 3 && !st; ++i) {
        r->frames[i].rgba8 = malloc(4 * n);
        r->frames[i].depth = malloc(n * sizeof(float));
        if (!r->frames[i].rgba8 || !r->frames[i].depth)
            st = cj_fail(CJ_ERR_NOMEM, "viewer: out of memory for %d x %d pictures", width, height);
    }
    if (!st && pthread_create(&r->thread, NULL, thread_main, r))
        st = cj_fail(CJ_ERR_UNSUPPORTED, "viewer: cannot start the render thread");
    if (st) {
        cj_vrender_destroy(r);
        return st;
    }
    r->started = 1;
    *out = r;
    return CJ_OK;
}

void cj_vrender_destroy(cj_vrender *r) {
    if (!r) return;
    if (r->started) {
        pthread_mutex_lock(&r->lock);
        r->quit = 1;
        atomic_store(&r->cancel, 1);
        pthread_cond_broadcast(&r->changed);
        pthread_mutex_unlock(&r->lock);
        pthread_join(r->thread, NULL);
    }
    if (r->has_pending) cj_scene_destroy(r->pending.scene);
    for (int i = 0; i < 3; ++i) {
        free(r->frames[i].rgba8);
        free(r->frames[i].depth);
    }
    cj_render_image_destroy(r->img);
    cj_renderer_destroy(r->ren);
    cj_render_cache_destroy(r->cache);
    pthread_mutex_destroy(&r->lock);
    pthread_mutex_destroy(&r->log_lock);
    pthread_cond_destroy(&r->changed);
    free(r);
}

void cj_vrender_submit(cj_vrender *r, const cj_vjob *job) {
    cj_scene *dropped = NULL;
    pthread_mutex_lock(&r->lock);
    if (r->has_pending) dropped = r->pending.scene;
    r->pending = *job;
    r->has_pending = 1;
    /* a drag lets the drag frame in flight finish once it draws tiles (frames keep coming
     * while the mouse moves); anything else is stale the moment a new state exists */
    if (r->running && (r->running_cancellable || !job->interactive)) atomic_store(&r->cancel, 1);
    /* a newer drag state: the drag frame in flight gives way if it is still tessellating */
    if (r->running && job->interactive && r->running_droppable) atomic_store(&r->drop, 1);
    pthread_cond_broadcast(&r->changed);
    pthread_mutex_unlock(&r->lock);
    cj_scene_destroy(dropped);
}

const cj_vframe *cj_vrender_take(cj_vrender *r) {
    const cj_vframe *f = NULL;
    pthread_mutex_lock(&r->lock);
    if (r->frame_new) {
        const int t = r->shown;
        r->shown = r->done;
        r->done = t;
        r->frame_new = 0;
        f = &r->frames[r->shown];
    }
    pthread_mutex_unlock(&r->lock);
    return f;
}

void cj_vrender_wait(cj_vrender *r) {
    pthread_mutex_lock(&r->lock);
    while (r->has_pending || r->running) pthread_cond_wait(&r->changed, &r->lock);
    pthread_mutex_unlock(&r->lock);
}

int cj_vrender_busy(cj_vrender *r) {
    pthread_mutex_lock(&r->lock);
    const int busy = r->has_pending || r->running;
    pthread_mutex_unlock(&r->lock);
    return busy;
}

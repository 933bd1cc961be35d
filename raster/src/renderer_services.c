/* The renderer's services to its back ends (renderer_internal.h): the pool, the rasterizer's
 * shading buffers, the tessellation cache, the target image and the "frame" stage. Apart from
 * renderer.c so that the calls run one way: renderer.c hands a frame to a back end (render_main.c,
 * trace_main.c), and both call these. */
#include "renderer_internal.h"

#include "error_internal.h"
#include "render_pipe.h"

#include <string.h>

void cj_renderer_free_shade_buffers(cj_renderer *r) {
    for (int i = 0; i < r->shade_workers; ++i) {
        cj_rfree(&r->alloc, r->color[i]);
        cj_rfree(&r->alloc, r->order[i]);
    }
    cj_rfree(&r->alloc, r->color);
    cj_rfree(&r->alloc, r->order);
    cj_rfree(&r->alloc, r->count);
    r->color = NULL;
    r->order = NULL;
    r->count = NULL;
    r->shade_workers = 0;
    r->shade_samples = 0;
}

cj_status cj_renderer_pool(cj_renderer *r, int workers, int *reused) {
    *reused = r->pool && cj_rpool_threads(r->pool) >= workers;
    if (*reused) return CJ_OK;
    cj_rpool_destroy(r->pool);
    r->pool = NULL;
    return cj_rpool_create(workers, &r->alloc, &r->pool);
}

cj_status cj_renderer_shade_buffers(cj_renderer *r, int workers, size_t samples, int *reused) {
    *reused = workers <= r->shade_workers && samples <= r->shade_samples;
    if (*reused) {
        memset(r->count, 0, sizeof(cj_rcount) * (size_t)r->shade_workers);
        return CJ_OK;
    }
    if (workers < r->shade_workers) workers = r->shade_workers;
    if (samples < r->shade_samples) samples = r->shade_samples;
    cj_renderer_free_shade_buffers(r);
    r->color = cj_ralloc(&r->alloc, sizeof(float *) * (size_t)workers);
    r->order = cj_ralloc(&r->alloc, sizeof(uint32_t *) * (size_t)workers);
    r->count = cj_ralloc(&r->alloc, sizeof(cj_rcount) * (size_t)workers);
    if (!r->color || !r->order || !r->count) {
        cj_renderer_free_shade_buffers(r);
        return cj_fail(CJ_ERR_NOMEM, "per-thread tables");
    }
    memset(r->color, 0, sizeof(float *) * (size_t)workers);
    memset(r->order, 0, sizeof(uint32_t *) * (size_t)workers);
    memset(r->count, 0, sizeof(cj_rcount) * (size_t)workers);
    r->shade_workers = workers;
    r->shade_samples = samples;
    for (int i = 0; i < workers; ++i) {
        r->color[i] = cj_ralloc(&r->alloc, sizeof(float) * 4 * samples);
        r->order[i] = cj_ralloc(&r->alloc, sizeof(uint32_t) * samples);
        if (!r->color[i] || !r->order[i]) {
            cj_renderer_free_shade_buffers(r);
            return cj_fail(CJ_ERR_NOMEM, "tile buffers of %zu samples", samples);
        }
    }
    return CJ_OK;
}

cj_render_cache *cj_renderer_cache(const cj_renderer *r) {
    return r->opt.render.cache ? r->opt.render.cache : r->cache;
}

static cj_status acquire(cj_renderer *r, int width, int height, unsigned planes,
                         cj_render_image *const *image, cj_rtarget *t, int clear) {
    const cj_render_image *old = *image;
    if (old && old->width == width && old->height == height &&
        (old->ids != NULL) == ((planes & CJ_IMAGE_IDS) != 0) &&
        (old->depth != NULL) == ((planes & CJ_IMAGE_DEPTH) != 0)) {
        t->img = *image;
        t->fresh = 0;
        return CJ_OK;
    }
    t->fresh = 1;
    t->img = NULL;
    return cj_render_image_alloc(width, height, planes, &r->alloc, clear, &t->img);
}

cj_status cj_rtarget_acquire(cj_renderer *r, int width, int height, unsigned planes,
                             cj_render_image *const *image, cj_rtarget *t) {
    return acquire(r, width, height, planes, image, t, 1);
}

cj_status cj_rtarget_acquire_overwritten(cj_renderer *r, int width, int height, unsigned planes,
                                         cj_render_image *const *image, cj_rtarget *t) {
    return acquire(r, width, height, planes, image, t, 0);
}

void cj_rtarget_finish(cj_rtarget *t, cj_render_image **image, cj_status st) {
    if (!t->fresh) return;
    if (st) {
        cj_render_image_destroy(t->img);
        return;
    }
    if (*image != t->img) cj_render_image_destroy(*image);
    *image = t->img;
}

void cj_renderer_report_frame(const cj_renderer *r, cj_stage_report *R, int pool_workers,
                              int pool_reused, int buffers_reused, int image_reused) {
    cj_stage *s = cj_stage_report_set(R, "frame", 1, "frame %llu of this renderer",
                                      (unsigned long long)r->frame);
    cj_stage_add_value(s, "frame", (double)r->frame);
    cj_stage_add_value(s, "pool_workers", pool_workers);
    cj_stage_add_value(s, "pool_reused", pool_reused);
    if (buffers_reused >= 0) cj_stage_add_value(s, "buffers_reused", buffers_reused);
    cj_stage_add_value(s, "image_reused", image_reused);
}

/* Private to raster/: the renderer object (casteljau/renderer.h) as its two back ends see it
 * (render_main.c: the rasterizer, trace_main.c: the ray tracer). */
#ifndef CJ_RENDERER_INTERNAL_H
#define CJ_RENDERER_INTERNAL_H

#include "casteljau/renderer.h"
#include "raster3d_internal.h"
#include "render_pool.h"
#include "render_scene.h"
#include "render_scratch.h"

struct tr_bvh_cache;

struct cj_renderer {
    cj_allocator alloc;
    cj_renderer_options opt;
    int caching;            /* 0 for a renderer used once: no tessellation or BVH cache to fill */
    uint64_t frame;         /* frames drawn (the current one counts) */
    cj_stage_report report; /* the stage table of the last draw */
    cj_rpool *pool;         /* started at the first draw */
    cj_raster_workspace *ws;
    cj_rscratch *scratch;   /* the rasterizer frames' set-up arrays, recycled (render_scratch.h) */
    cj_render_cache *cache; /* own tessellation cache, or NULL */
    struct tr_bvh_cache *bvh;
    /* the rasterizer's per-worker shading buffers: 4 floats and one index per tile sample */
    int shade_workers;
    size_t shade_samples;
    float **color;
    uint32_t **order;
    struct cj_rcount *count;
    /* motion blur (cj_renderer_set_motion): motion_poses × motion_nodes transforms, or none */
    int motion_poses;
    size_t motion_nodes;
    cj_xform3 *motion;
};

/* A renderer for one call (the one-shot wrappers): no caches of its own. */
cj_status cj_renderer_create_once(const cj_renderer_options *opt, const cj_allocator *alloc,
                                  cj_renderer **out);

/* ---- the services the back ends call (renderer_services.c) ---- */

/* Frees the shading buffers below (the renderer keeps none afterwards). */
void cj_renderer_free_shade_buffers(cj_renderer *r);

/* The pool with at least `workers` workers (kept when it has them: *reused = 1). */
cj_status cj_renderer_pool(cj_renderer *r, int workers, int *reused);

/* The rasterizer's shading buffers for `workers` workers of `samples` samples (kept when large
 * enough: *reused = 1). */
cj_status cj_renderer_shade_buffers(cj_renderer *r, int workers, size_t samples, int *reused);

/* The tessellation cache a frame uses: the caller's (options.render.cache), the renderer's own,
 * or NULL. */
cj_render_cache *cj_renderer_cache(const cj_renderer *r);

/* The image a frame draws into: *image when it has the size and exactly the planes, else a new
 * one (t->fresh). cj_rtarget_finish hands a fresh image to *image on success (destroying the old
 * one) or destroys it on failure. */
typedef struct cj_rtarget {
    cj_render_image *img;
    int fresh;
} cj_rtarget;
cj_status cj_rtarget_acquire(cj_renderer *r, int width, int height, unsigned planes,
                             cj_render_image *const *image, cj_rtarget *t);
/* The same for a back end that writes every value of every plane of the image before it
 * succeeds (the rasterizer: every tile writes its colours, ids and depths): a fresh image is
 * not cleared first (a 1024² frame is 16 MB of floats). On failure the fresh image is
 * destroyed (cj_rtarget_finish), so its unwritten values are never seen. */
cj_status cj_rtarget_acquire_overwritten(cj_renderer *r, int width, int height, unsigned planes,
                                         cj_render_image *const *image, cj_rtarget *t);
void cj_rtarget_finish(cj_rtarget *t, cj_render_image **image, cj_status st);

/* Records the stage "frame": the frame number and what the renderer reused (buffers_reused < 0:
 * the back end keeps no tile buffers, left out). */
void cj_renderer_report_frame(const cj_renderer *r, cj_stage_report *R, int pool_workers,
                              int pool_reused, int buffers_reused, int image_reused);

/* ---- the back ends (render_main.c, trace_main.c), called by cj_renderer_draw ---- */

/* The back ends: one frame of a checked scene, after the scene pass. */
cj_status cj_rraster_frame(cj_renderer *r, const cj_rscene *rs, unsigned planes,
                           cj_render_image **image, cj_stage_report *R);
cj_status cj_rtrace_frame(cj_renderer *r, const cj_rscene *rs, unsigned planes,
                          cj_render_image **image, cj_stage_report *R);

#endif

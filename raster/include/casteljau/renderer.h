/* casteljau: the RENDERER, an object that lives across frames (a viewer, an animation, a
 * bench) and draws scenes with either back end: the z-buffered rasterizer (casteljau/render.h)
 * or the ray tracer (casteljau/trace.h). The one-shot calls cj_render_raster, cj_render_trace,
 * cj_render_trace_with_options and cj_render_scene_mesh are thin wrappers around a renderer used
 * once.
 *
 *     cj_renderer *r;
 *     cj_renderer_options o = cj_renderer_options_defaults();
 *     o.render.threads = 2;
 *     cj_renderer_create(&o, NULL, &r);
 *     cj_render_image *img = NULL;                  // created by the first draw, then reused
 *     for (each frame) {
 *         edit the scene (control points, camera, materials...);
 *         cj_renderer_draw(r, scene, CJ_BACKEND_RASTER, 0, &img, &report);
 *     }
 *     cj_render_image_destroy(img);
 *     cj_renderer_destroy(r);
 *
 * WHAT IT OWNS, created once and kept between frames:
 *   - its options (cj_renderer_options, settable between frames with cj_renderer_set_options);
 *     each frame resolves them against the scene's settings (0 = the scene decides);
 *   - a TESSELLATION CACHE (cj_render_cache, see render.h): a patch object whose control points
 *     and weights did not change (bit for bit) and whose needed object tolerance stays within
 *     [cached, 2 x cached] is not tessellated again. Unless options.render.cache names a cache
 *     of the caller's, which is then used instead;
 *   - the ray tracer's PER-OBJECT BVHs, kept per node and reused while the geometry's data
 *     (patch degrees, control points and weights, or mesh positions and triangles) is equal
 *     bit for bit to what the BVH was built from; the world transform may change freely (rays
 *     are intersected in object space). The top-level BVH over the objects is rebuilt per frame;
 *   - ONE POOL of worker threads (persistent pthreads; the calling thread is worker 0) and ONE
 *     tile scheduler shared by both back ends: tiles are taken in row-major order from one
 *     counter; the progress callback (cj_render_options.progress) sees every tile of both back
 *     ends and can cancel a frame (CJ_ERR_CANCELLED). The pool is started at the first draw
 *     with min(threads, tiles) workers (threads 0 = one per core) and restarted only when a
 *     later frame asks for more workers;
 *   - the per-worker tile buffers (the rasterizer's visibility planes and shading buffers),
 *     grown when a frame needs larger tiles or more workers, never reallocated otherwise;
 *   - the STAGE TABLE of the last frame (cj_renderer_report);
 *   - nothing of the scene: the scene is read during cj_renderer_draw only and may be edited
 *     or destroyed freely between draws.
 *
 * WHAT A FRAME REUSES AND WHAT IT REDOES. Reused: the pool, the tile buffers, unchanged
 * tessellations, unchanged BVHs, the output image when it fits. Redone every frame: the scene
 * pass (visibility, world transforms, lights, materials, the feature mask), transforming the
 * object-space meshes to the world, culling, projection, set-up, rasterization and shading (or
 * the top-level BVH and all rays). The stage report says what was reused: the stage "frame"
 * (frame number, pool workers, pool_reused, buffers_reused (rasterizer), image_reused),
 * tessellate_patches (cache_hits, cache_misses: patch objects taken from the cache / tessellated),
 * build_bvh (bvh_reused, bvh_built).
 *
 * IMAGES. A draw gives exactly the one-shot call's image (bit for bit, any thread count)
 * whenever no cached tessellation is reused at another tolerance than the frame needs: an
 * empty cache, a still camera, edits of control points, materials, lights or other objects
 * all keep that. When the camera or an object's transform moves, a cached mesh up to 2x finer
 * than needed may be drawn instead of a fresh one, and a node whose needed tolerance falls
 * below its band twice in a row (a steady approach) is re-tessellated sqrt 2 finer than needed
 * (render.h, TESSELLATION CACHE): the proven bound still holds (bound_px <= tol_px), but the
 * triangles, and so the pixels along silhouettes, can differ from a one-shot render. The ray
 * tracer's images never depend on its caches.
 *
 * THREADING. A renderer is used by one thread at a time (its draws must not overlap); distinct
 * renderers are independent. The progress callback runs on worker threads, one call at a time.
 *
 * ALLOCATION. Every buffer comes from the allocator given at creation (NULL: malloc/free).
 */
#ifndef CASTELJAU_RENDERER_H
#define CASTELJAU_RENDERER_H

#include "casteljau/render.h"
#include "casteljau/trace.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct cj_renderer cj_renderer;

/* The back end of a draw. */
typedef enum cj_backend {
    CJ_BACKEND_RASTER = 0, /* the rasterizer (cj_render_raster's picture) */
    CJ_BACKEND_TRACE = 1   /* the ray tracer (cj_render_trace_with_options's picture) */
} cj_backend;

typedef struct cj_renderer_options {
    cj_render_options render; /* size, spp, tolerance, threads, tile size, depth, seed, progress;
                                 render.cache: NULL = the renderer's own cache */
    cj_trace_options trace;   /* the ray tracer's sampling choices */
} cj_renderer_options;

/* All zero: the scene decides, one thread per core. */
cj_renderer_options cj_renderer_options_defaults(void);

/* Creates a renderer (no thread is started before the first draw). opt may be NULL (the
 * defaults), alloc may be NULL. CJ_ERR_RANGE for options out of range everywhere (threads < 0,
 * tile_size not 0 and < 8, tol_px negative or not finite, spp < 0, a trace option out of
 * range, see cj_renderer_set_options), CJ_ERR_NOMEM. */
cj_status cj_renderer_create(const cj_renderer_options *opt, const cj_allocator *alloc,
                             cj_renderer **out);
/* Joins the threads and frees every cache and buffer. NULL is ignored. */
void cj_renderer_destroy(cj_renderer *r);

/* Replaces the options for the next frames (caches are kept: they are keyed by what they
 * depend on). Same CJ_ERR_RANGE checks as cj_renderer_create; on error the old options stay. */
cj_status cj_renderer_set_options(cj_renderer *r, const cj_renderer_options *opt);
/* The options in use. */
const cj_renderer_options *cj_renderer_get_options(const cj_renderer *r);

/* Draws the scene with `backend` into *image with the planes `planes` (CJ_IMAGE_*). *image
 * NULL: a new image is created (free with cj_render_image_destroy). *image an image of the
 * frame's size with exactly those planes: drawn into in place (no allocation); of another
 * size or planes: destroyed and replaced. report may be NULL. Status: as cj_render_raster
 * (CJ_BACKEND_RASTER) or cj_render_trace_with_options (CJ_BACKEND_TRACE), including
 * CJ_ERR_CANCELLED from the progress callback. On error a new image is not created; a reused one
 * keeps unspecified pixels but stays valid. */
cj_status cj_renderer_draw(cj_renderer *r, const cj_scene *scene, cj_backend backend,
                           unsigned planes, cj_render_image **image, cj_stage_report *report);

/* MOTION BLUR (the ray tracer; docs/light.md). The world transforms of every node of the scene
 * at `poses` times evenly spaced over the shutter interval, pose k at shutter fraction
 * k/(poses − 1), pose-major: world[k * node_count + node] (cj_anim_sample_motion writes exactly
 * this). Each camera sample of the tracer carries a time τ in [0, 1) over the shutter
 * (stratified over the pixel's samples, uniform otherwise), and every ray of that sample sees a
 * node whose transforms differ between poses under the transform linearly interpolated between
 * the two poses around τ (exact for motion linear between poses; a rotation by Δθ between poses
 * is drawn with a chord error of at most Δθ²/8 of its radius). Nodes whose poses are all equal
 * bit for bit are static; the camera, lights, materials and geometry are the scene's as drawn.
 * The rasterizer IGNORES the motion: it draws the scene as posed (the frame's time).
 *
 * The motion is copied and applies to every later draw until cleared (m NULL); a draw whose scene
 * has another node count fails with CJ_ERR_DIMENSION. poses outside 2..1024, node_count 0:
 * CJ_ERR_RANGE; a non-finite or projective transform: CJ_ERR_NONFINITE / CJ_ERR_UNSUPPORTED;
 * CJ_ERR_NOMEM. On error the previous motion is cleared. */
typedef struct cj_motion {
    int poses;
    size_t node_count;
    const cj_xform3 *world; /* poses × node_count transforms */
} cj_motion;
cj_status cj_renderer_set_motion(cj_renderer *r, const cj_motion *m);

/* The stage table of the last draw (what ran, why, what was reused: see above), kept by the
 * renderer until the next draw; after a failed draw it holds what that draw recorded. */
const cj_stage_report *cj_renderer_report(const cj_renderer *r);

/* The world-space triangles the rasterizer would draw for this scene now (see
 * cj_render_scene_mesh), through the renderer's tessellation cache. Free with
 * cj_mesh_destroy. Status as cj_render_scene_mesh. */
cj_status cj_renderer_scene_mesh(cj_renderer *r, const cj_scene *scene, cj_mesh **out);

#ifdef __cplusplus
}
#endif
#endif

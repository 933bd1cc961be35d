/* casteljau: rendering a scene (casteljau/scene.h) into an image: the z-buffered triangle
 * rasterizer (seed 6-10). The ray tracer (casteljau/trace.h) writes the same image type.
 *
 * OUTPUT: a cj_render_image holds LINEAR float RGBA radiance (straight alpha; alpha 1 where an
 * object covers the pixel fully, 0 on the background), rows BOTTOM-UP as the framebuffer
 * (origin at the lower-left pixel). Optional planes: per pixel the id of the object seen at the
 * pixel centre (cj_node.id, 0 = background) and its pseudodepth in [−1, 1] (+1 = background).
 * Conversion to 8-bit sRGB happens once, at output (cj_render_image_to_srgb8).
 *
 * PIPELINE: the renderer assembles its stages from what the scene uses (no lights: no normals
 * and no shading; no textures: no (u, v) and no sampling; no transparent material: no
 * sorting; flat shading: no per-pixel normals; 1 sample per pixel: no resolve; no overlays: no
 * line pass) and records every stage, run or left out, in a cj_stage_report
 * (casteljau/stage_report.h).
 *
 * DETERMINISM: the image is bit-identical for any thread count and tile size.
 *
 * THE RASTERIZER (cj_render_raster) in detail:
 *   - colour: the picture composited over the scene's background colour (background samples
 *     hold the background colour with alpha 0; transparent fragments blend over what is
 *     behind them, alpha += a (1 − alpha)); with supersampling, the box-filtered mean of the
 *     samples, so alpha is the pixel's coverage. The id and depth planes hold the pixel's
 *     sample 0 (its centre at 1 spp), before overlay lines.
 *   - the camera is a pinhole: cj_camera.aperture (the thin lens, depth of field) is read by
 *     the ray tracer only;
 *   - tessellation for the view: patches (and surfaces of revolution / general cylinders,
 *     converted exactly to rational patches) are tessellated at the object tolerance whose
 *     projection is at most tol_px pixels at the nearest depth of the visible patches (one
 *     cj_tessellate_patches call per object: watertight); other analytic surfaces on a grid
 *     meeting the same second-order bound; the stage report gives the triangles and the
 *     bound in pixels. Geometry reaching the near plane can ask for absurd counts: grids are
 *     capped at 1024 cells per direction and a patch set needing more than 512 segments per
 *     patch is retessellated at 4x the tolerance (repeatedly); bound_px then exceeds tol_px.
 *   - shading: Phong reflectance (casteljau/scene.h, cj_material) with point, directional and
 *     spot lights (area lights as a point at their centre), flat / Gouraud / Phong per
 *     material; no light at all shows each object's diffuse colour (times its texture); only
 *     ambient light shows c_r r_a I_a. Lights of zero intensity are left out.
 *   - transparency: back to front after the opaque surfaces, ordered by a BSP tree whose leaves
 *     are lists for which the painter's order is proven exact (Newell's plane tests on every
 *     pair overlapping on screen); interpenetrating surfaces are cut.
 *   - overlays and curves: depth-tested exact lines, overlays moved two pixel sizes towards
 *     the eye along their view ray so they sit on their surface.
 *   - the stage report names every stage: tessellate_patches, tessellate_surfaces, meshes,
 *     transform, vertex_normals, texture_coords, cull_backfaces, sort_transparent, project,
 *     shade_setup, mipmaps, raster_setup, rasterize, shade_unlit, shade_flat, shade_gouraud,
 *     shade_phong, texture, overlay_lines, transparency, resolve, output. Per-tile stages'
 *     seconds are summed over the worker threads.
 */
#ifndef CASTELJAU_RENDER_H
#define CASTELJAU_RENDER_H

#include "casteljau/alloc.h"
#include "casteljau/scene.h"
#include "casteljau/stage_report.h"
#include "casteljau/status.h"
#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Planes of a cj_render_image beyond the colour. */
enum { CJ_IMAGE_IDS = 1u, CJ_IMAGE_DEPTH = 2u };

typedef struct cj_render_image {
    int width, height;
    float *rgba;   /* 4 floats per pixel, linear, bottom row first */
    uint32_t *ids; /* object id at the pixel centre (0 = background), or NULL */
    float *depth;  /* pseudodepth at the pixel centre (+1 = background), or NULL */
    /* private */
    cj_allocator alloc_;
} cj_render_image;

/* Creates a width × height image (1..CJ_FRAMEBUFFER_MAX_SIDE each) cleared to 0, ids 0,
 * depth +1, with the planes `flags` asks for. alloc may be NULL. */
cj_status cj_render_image_create(int width, int height, unsigned flags, const cj_allocator *alloc,
                                 cj_render_image **out);
void cj_render_image_destroy(cj_render_image *img);

/* Converts to 8-bit sRGB (IEC 61966-2-1 transfer curve, each channel clamped to [0, 1] and
 * rounded to nearest; alpha linear), rows bottom-up, `stride` bytes between rows (0 = 4·width).
 * NaN is never produced by the renderer; a NaN here is CJ_ERR_NONFINITE naming the pixel. */
cj_status cj_render_image_to_srgb8(const cj_render_image *img, uint8_t *rgba8, size_t stride);

/* PROGRESS AND CANCELLATION of a long render. The tile scheduler calls progress(user, done,
 * total) after each finished tile (done of total tiles, 1 <= done <= total), from whichever
 * worker thread finished it, one call at a time (calls never overlap; done increases). A
 * nonzero return cancels: no worker starts another tile, the render returns CJ_ERR_CANCELLED
 * and writes no image. NULL: no calls. The callback must not call the renderer.
 * While a renderer with a tessellation cache (renderer.h) prepares a frame, the callback is
 * also called with done = total = 0 ("preparing") before each patch the cache plans or builds,
 * on the drawing thread; a nonzero answer cancels the frame there (CJ_ERR_CANCELLED) and the
 * cache keeps the patches finished so far (casteljau/tess_cache.h, CANCELLATION). */
typedef int (*cj_render_progress_fn)(void *user, uint64_t done, uint64_t total);

typedef struct cj_render_options {
    int width, height; /* 0: the scene's settings */
    int spp;           /* 0: the scene's; the rasterizer takes 1, 4 or 16 */
    double tol_px;     /* 0: the scene's screen-space tessellation tolerance (pixels) */
    int threads;       /* 0: one per core */
    int tile_size;     /* 0: 64 pixels; any >= 8 gives the same image */
    int max_depth;     /* ray tracer: 0 = the scene's */
    int use_seed;      /* ray tracer: 1 = use `seed` instead of the scene's */
    uint64_t seed;
    struct cj_render_cache *cache;  /* rasterizer: NULL, or a tessellation cache (below) */
    cj_render_progress_fn progress; /* NULL, or called per finished tile (see above) */
    void *progress_user;
} cj_render_options;

/* All zero: the scene decides. */
cj_render_options cj_render_options_defaults(void);

/* Renders the scene with the rasterizer into *out, created here with the planes `planes`
 * (CJ_IMAGE_*) at the size the scene/options ask for (free with cj_render_image_destroy): a
 * renderer used once (casteljau/renderer.h keeps one across frames, with its caches).
 * report may be NULL. Status: whatever cj_scene_check reports; CJ_ERR_RANGE (spp not 1, 4 or
 * 16, a size out of range), CJ_ERR_ARGUMENT (an image texture without pixels), CJ_ERR_NOMEM,
 * CJ_ERR_CAP (tessellation asked for more than the triangle cap). *out is set only on
 * success. */
cj_status cj_render_raster(const cj_scene *scene, const cj_render_options *opt, unsigned planes,
                           const cj_allocator *alloc, cj_render_image **out,
                           cj_stage_report *report);

/* A TESSELLATION CACHE for repeated renders (animation, a viewer, the bench): per object node,
 * an incremental per-patch tessellation (casteljau/tess_cache.h) and the object tolerance it
 * was made at. A render given the cache (cj_render_options.cache) keeps a node's tolerance while
 * the tolerance the frame needs stays between the cached one and twice it, so the proven bound
 * still holds (the mesh is at most 2x finer than needed) and a moving camera does not
 * re-tessellate; otherwise the node re-tessellates at the needed tolerance, or, on a steady
 * approach (the needed tolerance falls below the band and the node's last departure from its
 * band was downwards too), at needed/sqrt 2, so that a camera or an edit moving the object
 * closer does not redo the whole node every frame. Either way only the patches whose control
 * points (and weights) changed are re-planned, and only they and the neighbours whose shared
 * side changed are rebuilt; the rest is reused. Transforms may change
 * freely (the mesh is in object space). The image is the same as without a cache whenever the
 * cached tolerance equals the needed one (e.g. a still camera, after any edits). Not
 * thread-safe: one cache per renderer thread. The stage report's tessellate_patches gives
 * patches_planned, patches_built, patches_reused and cache_hits (patch objects with nothing
 * re-planned or rebuilt). */
typedef struct cj_render_cache cj_render_cache;
cj_status cj_render_cache_create(const cj_allocator *alloc, cj_render_cache **out);
void cj_render_cache_destroy(cj_render_cache *cache);

/* The world-space triangles the rasterizer draws for this scene and view (what cj_render_raster
 * rasterizes before clipping: tessellated for the view at the options' screen tolerance, back
 * faces of one-sided materials removed), as a new mesh: positions and unit normals in world
 * space, the geometry's (u, v), triangle_patch = the object's id (cj_node.id). For
 * cross-checks (VTK) and exports. Free with cj_mesh_destroy. Status as cj_render_raster. */
cj_status cj_render_scene_mesh(const cj_scene *scene, const cj_render_options *opt,
                               const cj_allocator *alloc, cj_mesh **out);

/* The built-in demo scene of `casteljau render --demo`: the Utah teapot read from teapot_bpt
 * (data/teapot.bpt), lit by an ambient, a point and a directional light, with a procedural
 * checker and its control net, on a checkered floor; 800 x 600, 4 samples per pixel. The
 * scene is scenes/demo_render.json, embedded in the library at build time and read by
 * cj_scene_parse_json_with_options (casteljau/scene_json.h) with teapot_bpt as the teapot's path.
 * Status: those of cj_scene_parse_json_with_options (CJ_ERR_IO naming the .bpt file when it cannot
 * be read), CJ_ERR_NOMEM. */
cj_status cj_render_demo_scene(const char *teapot_bpt, const cj_allocator *alloc, cj_scene **out);

#ifdef __cplusplus
}
#endif
#endif

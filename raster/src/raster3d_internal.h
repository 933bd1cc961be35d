/* Private to raster/: the contract between the exact triangle rasterizer (tri_*.c: clipping,
 * fixed-point set-up, top-left rule, tiles and threads) and the rendering pipeline
 * (render_*.c: scene to triangles, shading, textures, transparency, overlays, stage report).
 *
 * The rasterizer knows nothing of materials or lights. It turns clip-space triangles into a
 * VISIBILITY BUFFER per tile: for each sample the nearest triangle, its pseudodepth and its
 * perspective-correct barycentric coordinates with respect to the SOURCE triangle (so a
 * triangle cut by the near plane still interpolates its own vertex attributes). The pipeline
 * then shades each tile from that buffer (deferred: every visible sample is shaded once), in
 * a loop specialised on the scene's feature mask.
 *
 * Screen space: pixel (x, y) covers [x, x+1) × [y, y+1), origin lower-left, centre
 * (x + 0.5, y + 0.5). Clip -> screen: sx = (x_c/w_c + 1)·width/2, sy = (y_c/w_c + 1)·height/2.
 * Sample s of pixel (x, y) lies at (x + ox[s], y + oy[s]) with the fixed pattern of
 * cj_raster_sample_pattern (spp 1: the centre).
 *
 * Coverage is exact: positions snap to a fixed-point grid of 1/256 pixel, edge functions are
 * evaluated in 64-bit integers, and the top-left rule decides samples on an edge, so triangles
 * sharing an edge cover every sample exactly once (checked against a rational reference in
 * tests/test_raster_exact.c). Depth test: a sample is written when its depth is strictly
 * less than the stored one; triangles are processed in input order within every tile, so
 * ties keep the earlier triangle and the result does not depend on tiling or threads.
 */
#ifndef CASTELJAU_RASTER3D_INTERNAL_H
#define CASTELJAU_RASTER3D_INTERNAL_H

#include "casteljau/alloc.h"
#include "casteljau/status.h"
#include <stddef.h>
#include <stdint.h>

#define CJ_RASTER_SUBPIXEL_BITS 8
#define CJ_RASTER_NO_TRI        UINT32_MAX

/* One sample of the visibility buffer. */
typedef struct cj_vis_sample {
    float depth;  /* pseudodepth in [-1, 1]; +1 (far) where nothing was drawn */
    uint32_t tri; /* index of the source triangle in cj_raster_input, or CJ_RASTER_NO_TRI */
    float b1, b2; /* perspective-correct barycentrics of source vertices 1 and 2 (b0 = 1-b1-b2) */
} cj_vis_sample;

/* A rectangle of pixels [x0, x1) × [y0, y1) with its samples: sample s of pixel (x, y) is
 * samples[((y - y0) * (x1 - x0) + (x - x0)) * spp + s]. */
typedef struct cj_tile {
    int x0, y0, x1, y1;
    int spp;
    int index;  /* tile number in row-major order over the image */
    int thread; /* worker that runs it, 0..threads-1 (for per-thread scratch) */
    cj_vis_sample *samples;
} cj_tile;

/* The triangles to draw: clip-space vertices (x_c, y_c, z_c, w_c) and index triples. The
 * pipeline has already culled back faces (in world space, seed 7.2); the rasterizer draws both
 * windings. */
typedef struct cj_raster_input {
    size_t vertex_count;
    const double *clip; /* 4 per vertex */
    size_t tri_count;
    const uint32_t *tris; /* 3 per triangle */
    int width, height;    /* the image */
    int spp;              /* 1, 4 or 16 */
} cj_raster_input;

/* Counters of one preparation / run (for the stage report). */
typedef struct cj_raster_stats {
    uint64_t tris_in;       /* triangles given */
    uint64_t tris_clipped;  /* triangles cut by the near/far planes or the guard band */
    uint64_t tris_rejected; /* entirely outside the view volume, or zero area after snapping */
    uint64_t tris_setup;    /* screen triangles set up (after clipping: a cut one may give 2+) */
    uint64_t samples_tested;
    uint64_t samples_written; /* depth test passed */
    double seconds_setup, seconds_raster;
} cj_raster_stats;

/* Clipped, snapped, set-up and binned triangles, ready to rasterize any tile. Opaque. */
typedef struct cj_raster_prep cj_raster_prep;

/* The fixed sample pattern: offsets within the pixel for spp = 1 (centre), 4 (rotated grid)
 * or 16 (4 × 4 jittered, fixed); each offset a multiple of 1/256. Returns NULL for other spp. */
const double (*cj_raster_sample_pattern(int spp))[2];

/* Clips every triangle against the near and far planes and the guard band in homogeneous
 * coordinates, snaps to the fixed-point grid, sets up the edge functions and bins the result
 * into tiles of `tile_size` pixels. The input arrays are not kept. */
cj_status cj_raster_prepare(const cj_raster_input *in, int tile_size, const cj_allocator *alloc,
                            cj_raster_prep **out, cj_raster_stats *stats);
void cj_raster_prep_destroy(cj_raster_prep *prep);

/* cj_raster_prepare into a prep made by an earlier call (its allocator is kept): the set-up
 * records, bins and scratch are written into the previous frame's memory, grown only when the
 * new frame needs more, so a renderer preparing every frame writes to warm, mapped pages and
 * allocates nothing in the steady state. The result is the same as a fresh cj_raster_prepare
 * (barycentrics switched on again). Same status codes; on an error the prep holds no
 * triangles (a run draws nothing) and may be prepared again or destroyed. */
cj_status cj_raster_prepare_again(cj_raster_prep *prep, const cj_raster_input *in, int tile_size,
                                  cj_raster_stats *stats);

/* Called once per tile, on a worker thread, after the tile's visibility buffer is complete.
 * It may call cj_raster_tile_forward. It must write only pixels of its own tile. */
typedef void (*cj_tile_fn)(void *user, const cj_tile *tile);

/* Renders every tile: clears its samples (depth +1, no triangle), rasterizes the prepared
 * triangles into it in input order, then calls fn. `threads` workers (0 = one per core)
 * take tiles in order. The same prep may be run many times. fn may be NULL (a pass that only
 * counts, e.g. the fill-rate bench: the tile samples are then not written). stats may be
 * NULL; otherwise its samples_tested, samples_written and seconds_raster are set (the
 * preparation's counters are left as they are). progress may be NULL; otherwise every finished
 * tile is reported to it and a cancelled gate stops the run: CJ_ERR_CANCELLED (the tiles not
 * yet taken are left unrendered). */
struct cj_rprogress;
cj_status cj_raster_run(const cj_raster_prep *prep, int threads, cj_tile_fn fn, void *user,
                        struct cj_rprogress *progress, cj_raster_stats *stats);

/* PER-WORKER TILE BUFFERS (scratch planes and visibility samples) kept across runs: a renderer
 * holds one workspace for its lifetime, so frames after the first allocate nothing here. Grows
 * when a run needs more workers or larger tiles; never shrinks. */
typedef struct cj_raster_workspace cj_raster_workspace;
cj_status cj_raster_workspace_create(const cj_allocator *alloc, cj_raster_workspace **out);
void cj_raster_workspace_destroy(cj_raster_workspace *ws);

/* cj_raster_run on a persistent worker pool (render_pool.h) with the workspace's buffers:
 * min(cj_raster_thread_count(prep, threads), the pool's workers) workers. *buffers_reused (may
 * be NULL) is set to 1 when the workspace's buffers served without a new allocation. */
struct cj_rpool;
cj_status cj_raster_run_on(const cj_raster_prep *prep, struct cj_rpool *pool, int threads,
                           cj_raster_workspace *ws, cj_tile_fn fn, void *user,
                           struct cj_rprogress *progress, cj_raster_stats *stats,
                           int *buffers_reused);

/* Forward mode (transparent surfaces, coverage tests): for every triangle of `prep` in input
 * order and every sample of `tile` it covers whose depth is strictly less than the depth stored
 * in tile->samples (which is NOT updated), calls frag(user, x, y, s, tri, depth, b1, b2). */
typedef void (*cj_frag_fn)(void *user, int x, int y, int s, uint32_t tri, float depth, float b1,
                           float b2);
void cj_raster_tile_forward(const cj_raster_prep *prep, const cj_tile *tile, cj_frag_fn frag,
                            void *user);

/* The number of workers cj_raster_run(prep, threads, ...) will use (0 = one per core, never
 * more than the tiles): tile->thread is below it, so per-thread scratch can be sized ahead. */
int cj_raster_thread_count(const cj_raster_prep *prep, int threads);

/* Whether cj_raster_run resolves the barycentrics of the visible triangle into the tile
 * samples (on by default). Off, b1 = b2 = 0 there: a depth/id-only pass (flat shading without
 * attributes, the depth bench) skips two divisions per sample. The forward mode always
 * computes them. */
void cj_raster_prep_set_barycentrics(cj_raster_prep *prep, int on);

/* The tile size and image size a prep was built for. */
void cj_raster_prep_layout(const cj_raster_prep *prep, int *width, int *height, int *spp,
                           int *tile_size);

#endif

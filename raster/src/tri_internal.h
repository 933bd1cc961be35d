/* Private to the triangle rasterizer (tri_*.c): the clipped vertex, the set-up triangle and
 * the prepared scene shared by clipping/set-up (tri_clip.c, tri_setup.c), per-tile
 * rasterization (tri_raster.c) and the tile scheduler (tri_run.c). The contract with the
 * pipeline is raster3d_internal.h.
 *
 * FIXED POINT. A screen position (sx, sy) in pixels becomes the integer pair
 *     X = rint(256 · fl(fl(fl(x_c / w_c) + 1) · (width / 2))),   Y likewise with y_c, height,
 * (round to nearest, ties to even; every product by a power of two is exact), i.e. 1/256 pixel
 * units. Sample s of pixel (x, y) sits at (256 x + ox[s], 256 y + oy[s]). The guard band keeps
 * |X|, |Y| <= 256 (2^19 + 2^14) < 2^28 (sides <= 2^15), so edge-function coefficients stay
 * below 2^29 and values below 2^60: 64-bit arithmetic is exact. (The snap adds and removes
 * 1.5·2^52, which is rint for such values.)
 *
 * EDGE FUNCTIONS. After orienting the snapped triangle counter-clockwise (y up), edge k from
 * v_k to v_{k+1} has E_k(X, Y) = dx (Y − Y_k) − dy (X − X_k), positive inside. A sample on an
 * edge (E_k = 0) belongs to the triangle iff the edge is a top or left edge of it:
 * dy < 0 (left) or dy = 0 and dx < 0 (top) — equivalently, the sample is moved by
 * (+ε, −ε²) before an open inside test, which makes every partition of the plane into
 * triangles cover every sample exactly once, vertices included. The rule is folded into
 * the constant: inside iff E_k − (owned ? 0 : 1) >= 0 for k = 0, 1, 2.
 */
#ifndef CASTELJAU_TRI_INTERNAL_H
#define CASTELJAU_TRI_INTERNAL_H

#include "raster3d_internal.h"

#include <stdint.h>

/* Guard band: clip space |x_c| <= gx·w_c with gx = 2^20/width keeps sx within 2^19 pixels of
 * the image centre (y likewise). */
#define CJ_TRI_GUARD_PX 524288.0

/* A vertex during clipping: clip coordinates and the barycentrics (b1, b2) of the point in
 * its SOURCE triangle (linear in clip space, hence perspective-correct after division). */
typedef struct cj_tri_vert {
    double x, y, z, w;
    double b1, b2;
} cj_tri_vert;

/* Clipping against 2 (near, far) + 4 (guard band) planes adds at most 6 vertices. */
#define CJ_TRI_CLIP_MAX 9

/* Clips the triangle in[0..2] against z + w >= 0 (near), w − z >= 0 (far) and the guard band
 * gx·w ± x >= 0, gy·w ± y >= 0. Returns the number of vertices of the convex polygon written
 * to out (0 when nothing is left). *cut is set to 1 when a plane actually cut the triangle.
 * An intersection on an edge is computed from its inside end towards its outside end, so two
 * triangles sharing an edge get bit-identical cut points. */
int cj_tri_clip(const cj_tri_vert in[3], double gx, double gy, cj_tri_vert *out, int *cut);

/* A plane v(X, Y) = v0 + va (X − X_ref) + vb (Y − Y_ref) over the fixed-point screen, with
 * (X_ref, Y_ref) the triangle's snapped vertex 0. Evaluated in double in that order at any
 * sample: the value depends only on the sample, never on the tile. */
typedef struct cj_tri_plane {
    double v0, va, vb;
} cj_tri_plane;

/* One set-up screen triangle (a source triangle, or one piece of a clipped one): what the
 * visibility pass reads, 112 bytes... The coefficients ea = −dy, eb = dx are differences of
 * snapped coordinates (|X|, |Y| < 2^28), so they fit in 32 bits; products with positions are
 * formed in 64 bits. (A 96-byte record, xr, yr in int32 and bounds in int16, read 10 % faster
 * from a kept prep, but with one-shot preps its smaller arrays let malloc trim and re-fault
 * the heap every frame in bench_raster: set-up twice as slow. Kept at 112 bytes.) */
typedef struct cj_tri_setup {
    int32_t ea[3], eb[3];       /* E_k = ea X + eb Y + ec, fill rule folded in ec */
    int64_t ec[3];              /* (products widened to 64 bits) */
    int64_t xr, yr;             /* reference point: snapped vertex 0 */
    int minx, miny, maxx, maxy; /* inclusive pixel bounds, clamped to the image */
    cj_tri_plane z;             /* pseudodepth */
    int32_t small; /* every |ea_k|, |eb_k| <= 2^14: 32-bit edge values near it (tri_raster.c) */
} cj_tri_setup;

/* ... and what only the resolve and the forward mode read, kept apart (same index). */
typedef struct cj_tri_attr {
    cj_tri_plane r, q1, q2; /* 1/w, b1/w, b2/w of the source triangle */
    uint32_t src;           /* source triangle index */
} cj_tri_attr;

struct cj_raster_prep {
    cj_allocator alloc;
    int width, height, spp, tile_size;
    int tiles_x, tiles_y;
    int ox[16], oy[16]; /* sample offsets in 1/256 pixel */
    int oxmin, oxmax, oymin, oymax;
    int barycentrics; /* resolve b1, b2 into the tile samples (cj_raster_prep_set_barycentrics) */
    size_t setup_count;
    cj_tri_setup *setups;
    cj_tri_attr *attrs;
    uint32_t *src;     /* attrs[i].src again, compact: the resolve reads it for every sample */
    size_t *bin_start; /* tiles_x·tiles_y + 1 offsets into bin_items */
    uint32_t *bin_items;
    /* Capacities and set-up scratch kept for cj_raster_prepare_again, which writes the next
     * frame into the same (warm, already mapped) memory. */
    size_t setup_cap, bin_start_cap, bin_items_cap;
    uint16_t (*range)[4]; /* tile range of each set-up, while binning */
    void *vcache;         /* the vertex cache of tri_setup.c */
    int huge;             /* kept across frames: large arrays in transparent huge pages */
};

/* The fixed sample offsets of spp 1, 4 or 16 in 1/256 pixel (tri_prep.c). */
void cj_tri_pattern_fixed(int spp, int *ox, int *oy);

/* The refusals of cj_raster_prepare that need no memory: image size, spp, tile size, triangle
 * count and vertex indices (tri_prep.c). NaN and infinite coordinates are found by the set-up. */
cj_status cj_tri_check_input(const cj_raster_input *in, int tile_size);

/* Per-thread scratch of one run: the tile's depth and set-up index planes, sample-major
 * (plane q holds sample q of every pixel of the tile, row by row), padded by 8 entries. */
typedef struct cj_tri_scratch {
    float *depth;
    uint32_t *id;
    uint64_t tested, written;
} cj_tri_scratch;

/* Rasterizes every binned triangle of tile `t` into scratch (cleared first), then, when
 * `resolve`, writes the visibility samples (source index, depth, perspective-correct
 * barycentrics) to t->samples (a run without a tile callback has no reader for them). */
void cj_tri_render_tile(const cj_raster_prep *prep, const cj_tile *t, cj_tri_scratch *scratch,
                        int resolve);

/* The depth and barycentrics of set-up triangle `s` at sample position (X, Y). */
float cj_tri_depth_at(const cj_tri_setup *s, int64_t X, int64_t Y);
void cj_tri_bary_at(const cj_tri_setup *s, const cj_tri_attr *a, int64_t X, int64_t Y, float *b1,
                    float *b2);

#endif

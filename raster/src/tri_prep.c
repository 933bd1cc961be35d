/* The prepared frame's fixed parts: the sample patterns, the refusals that need no memory,
 * and the accessors and destructor of cj_raster_prep (its set-up is tri_setup.c). */
#include "tri_internal.h"

#include "casteljau/framebuffer.h"
#include "error_internal.h"

#include <assert.h>
#include <stddef.h>

#if defined(__AVX2__)
#include <immintrin.h>
#endif

/* ---- sample patterns --------------------------------------------------------------------- */

/* spp 4: rotated grid; spp 16: 4 × 4 cells, one sample per cell, every x and every y distinct
 * (multi-jittered: x = (4i + p[j] + 1/2)/16, y = (4j + q[i] + 1/2)/16 for cell (i, j)). */
static const int k_pat4[4][2] = {{96, 32}, {224, 96}, {32, 160}, {160, 224}};
static const int k_p16[4] = {2, 0, 3, 1};
static const int k_q16[4] = {1, 3, 0, 2};

static const double k_dpat1[1][2] = {{0.5, 0.5}};
static const double k_dpat4[4][2] = {{96 / 256.0, 32 / 256.0},
                                     {224 / 256.0, 96 / 256.0},
                                     {32 / 256.0, 160 / 256.0},
                                     {160 / 256.0, 224 / 256.0}};
/* pattern_fixed(16) / 256, written out so that the table is constant (no lazy init). */
static const double k_dpat16[16][2] = {
    {40 / 256.0, 24 / 256.0},   {104 / 256.0, 56 / 256.0},  {168 / 256.0, 8 / 256.0},
    {232 / 256.0, 40 / 256.0},  {8 / 256.0, 88 / 256.0},    {72 / 256.0, 120 / 256.0},
    {136 / 256.0, 72 / 256.0},  {200 / 256.0, 104 / 256.0}, {56 / 256.0, 152 / 256.0},
    {120 / 256.0, 184 / 256.0}, {184 / 256.0, 136 / 256.0}, {248 / 256.0, 168 / 256.0},
    {24 / 256.0, 216 / 256.0},  {88 / 256.0, 248 / 256.0},  {152 / 256.0, 200 / 256.0},
    {216 / 256.0, 232 / 256.0}};

void cj_tri_pattern_fixed(int spp, int *ox, int *oy) {
    if (spp == 1) {
        ox[0] = oy[0] = 128;
    } else if (spp == 4) {
        for (int s = 0; s < 4; ++s) {
            ox[s] = k_pat4[s][0];
            oy[s] = k_pat4[s][1];
        }
    } else {
        for (int j = 0; j < 4; ++j)
            for (int i = 0; i < 4; ++i) {
                ox[4 * j + i] = 16 * (4 * i + k_p16[j]) + 8;
                oy[4 * j + i] = 16 * (4 * j + k_q16[i]) + 8;
            }
    }
}

const double (*cj_raster_sample_pattern(int spp))[2] {
    if (spp == 1) return k_dpat1;
    if (spp == 4) return k_dpat4;
    if (spp == 16) return k_dpat16;
    return NULL;
}

/* The refusals of cj_raster_prepare that need no memory: sizes, spp, tile size, counts and
 * indices. */
cj_status cj_tri_check_input(const cj_raster_input *in, int tile_size) {
    assert(in->vertex_count == 0 || in->clip);
    assert(in->tri_count == 0 || in->tris);
    if (in->width < 1 || in->height < 1 || in->width > CJ_FRAMEBUFFER_MAX_SIDE ||
        in->height > CJ_FRAMEBUFFER_MAX_SIDE)
        return cj_fail(CJ_ERR_RANGE, "raster: image size %d x %d outside 1..%d", in->width,
                       in->height, CJ_FRAMEBUFFER_MAX_SIDE);
    if (in->spp != 1 && in->spp != 4 && in->spp != 16)
        return cj_fail(CJ_ERR_RANGE, "raster: spp = %d must be 1, 4 or 16", in->spp);
    if (tile_size < 1 || tile_size > CJ_FRAMEBUFFER_MAX_SIDE)
        return cj_fail(CJ_ERR_RANGE, "raster: tile size %d outside 1..%d", tile_size,
                       CJ_FRAMEBUFFER_MAX_SIDE);
    if (in->tri_count > (size_t)1 << 28)
        return cj_fail(CJ_ERR_RANGE, "raster: %zu triangles exceed the limit 2^28", in->tri_count);
    /* The largest index first (a loop without exits, which vectorizes), the culprit after. */
    uint32_t top = 0;
    size_t i0 = 0;
#if defined(__AVX2__)
    __m256i vtop = _mm256_setzero_si256();
    for (; i0 + 8 <= 3 * in->tri_count; i0 += 8)
        vtop = _mm256_max_epu32(vtop, _mm256_loadu_si256((const __m256i *)(in->tris + i0)));
    uint32_t lanes[8];
    _mm256_storeu_si256((__m256i *)lanes, vtop);
    for (int k = 0; k < 8; ++k) top = lanes[k] > top ? lanes[k] : top;
#endif
    for (size_t i = i0; i < 3 * in->tri_count; ++i) top = in->tris[i] > top ? in->tris[i] : top;
    if (in->tri_count && (size_t)top >= in->vertex_count)
        for (size_t i = 0; i < 3 * in->tri_count; ++i)
            if (in->tris[i] >= in->vertex_count)
                return cj_fail(CJ_ERR_ARGUMENT, "raster: triangle %zu names vertex %u of %zu",
                               i / 3, (unsigned)in->tris[i], in->vertex_count);
    return CJ_OK;
}

/* ---- the prep ----------------------------------------------------------------------------- */

void cj_raster_prep_destroy(cj_raster_prep *p) {
    if (!p) return;
    cj_allocator a = p->alloc;
    a.free(a.user, p->setups);
    a.free(a.user, p->attrs);
    a.free(a.user, p->src);
    a.free(a.user, p->bin_start);
    a.free(a.user, p->bin_items);
    a.free(a.user, p->range);
    a.free(a.user, p->vcache);
    a.free(a.user, p);
}

void cj_raster_prep_set_barycentrics(cj_raster_prep *p, int on) {
    assert(p);
    p->barycentrics = on != 0;
}

void cj_raster_prep_layout(const cj_raster_prep *p, int *width, int *height, int *spp,
                           int *tile_size) {
    assert(p);
    if (width) *width = p->width;
    if (height) *height = p->height;
    if (spp) *spp = p->spp;
    if (tile_size) *tile_size = p->tile_size;
}

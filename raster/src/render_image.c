/* The render image (linear float RGBA + optional id and depth planes), its conversion to 8-bit
 * sRGB, and the small helpers every render_*.c file shares. */
#define _POSIX_C_SOURCE 200809L
#include "render_internal.h"

#include "casteljau/framebuffer.h"
#include "error_internal.h"
#include "clock_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static void *sys_alloc(void *user, size_t bytes) {
    (void)user;
    return malloc(bytes);
}
static void sys_free(void *user, void *p) {
    (void)user;
    free(p);
}

cj_allocator cj_render_alloc(const cj_allocator *alloc) {
    if (alloc) return *alloc;
    cj_allocator a = {sys_alloc, sys_free, NULL};
    return a;
}

void *cj_ralloc(const cj_allocator *a, size_t bytes) {
    return a->alloc(a->user, bytes ? bytes : 1);
}

void cj_rfree(const cj_allocator *a, void *p) {
    if (p) a->free(a->user, p);
}

double cj_render_now(void) {
    return cj_clock_seconds();
}

double cj_render_thread_cpu(void) {
    struct timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

cj_render_options cj_render_options_defaults(void) {
    cj_render_options o;
    memset(&o, 0, sizeof o);
    return o;
}

cj_status cj_render_image_create(int width, int height, unsigned flags, const cj_allocator *alloc,
                                 cj_render_image **out) {
    return cj_render_image_alloc(width, height, flags, alloc, 1, out);
}

cj_status cj_render_image_alloc(int width, int height, unsigned flags, const cj_allocator *alloc,
                                int clear, cj_render_image **out) {
    if (width < 1 || height < 1 || width > CJ_FRAMEBUFFER_MAX_SIDE ||
        height > CJ_FRAMEBUFFER_MAX_SIDE)
        return cj_fail(CJ_ERR_RANGE, "image size %d x %d outside 1..%d", width, height,
                       CJ_FRAMEBUFFER_MAX_SIDE);
    if (flags & ~(unsigned)(CJ_IMAGE_IDS | CJ_IMAGE_DEPTH))
        return cj_fail(CJ_ERR_ARGUMENT, "unknown image plane flags 0x%x", flags);
    cj_allocator a = cj_render_alloc(alloc);
    size_t n = (size_t)width * (size_t)height;
    cj_render_image *img = cj_ralloc(&a, sizeof *img);
    if (!img) return cj_fail(CJ_ERR_NOMEM, "render image of %d x %d", width, height);
    memset(img, 0, sizeof *img);
    img->width = width;
    img->height = height;
    img->alloc_ = a;
    img->rgba = cj_ralloc(&a, n * 4 * sizeof(float));
    if (flags & CJ_IMAGE_IDS) img->ids = cj_ralloc(&a, n * sizeof(uint32_t));
    if (flags & CJ_IMAGE_DEPTH) img->depth = cj_ralloc(&a, n * sizeof(float));
    if (!img->rgba || ((flags & CJ_IMAGE_IDS) && !img->ids) ||
        ((flags & CJ_IMAGE_DEPTH) && !img->depth)) {
        cj_render_image_destroy(img);
        return cj_fail(CJ_ERR_NOMEM, "render image of %d x %d", width, height);
    }
    if (clear) {
        memset(img->rgba, 0, n * 4 * sizeof(float));
        if (img->ids) memset(img->ids, 0, n * sizeof(uint32_t));
        if (img->depth)
            for (size_t i = 0; i < n; ++i) img->depth[i] = 1.0f;
    }
    *out = img;
    return CJ_OK;
}

void cj_render_image_destroy(cj_render_image *img) {
    if (!img) return;
    cj_allocator a = img->alloc_;
    cj_rfree(&a, img->rgba);
    cj_rfree(&a, img->ids);
    cj_rfree(&a, img->depth);
    cj_rfree(&a, img);
}

/* The sRGB transfer curve (IEC 61966-2-1), inverse direction. */
static double srgb_decode(double y) {
    return y <= 0.04045 ? y / 12.92 : pow((y + 0.055) / 1.055, 2.4);
}

/* Rounding to the nearest code is a threshold count: code k is the number of the 255
 * thresholds decode((j + 1/2)/255) (rounded to float) that are <= x. That is exact up to the
 * rounding of those thresholds and avoids a pow per channel. The count is found by table: for a
 * positive float the bit pattern orders like the value, so the top 16 bits of x (sign, exponent
 * and 7 mantissa bits) name a bucket whose first code is tabulated, and the few thresholds
 * inside the bucket (at most two) are stepped over by comparing bit patterns; a sentinel of +Inf
 * ends the step. Both tables are built per call (about 16 k steps: no shared state). */
enum { SRGB_BUCKETS = (0x3F800000u >> 16) }; /* buckets of the floats in [0, 1) */

typedef struct srgb_table {
    uint32_t threshold[256];          /* bit patterns, ascending; [255] = +Inf sentinel */
    uint8_t first_code[SRGB_BUCKETS]; /* thresholds below the bucket's first float */
} srgb_table;

static void srgb_table_build(srgb_table *t) {
    for (int k = 0; k < 255; ++k) {
        float th = (float)srgb_decode((k + 0.5) / 255.0);
        memcpy(&t->threshold[k], &th, sizeof th);
    }
    t->threshold[255] = 0x7F800000u;
    unsigned k = 0;
    for (uint32_t b = 0; b < SRGB_BUCKETS; ++b) {
        while (k < 255 && t->threshold[k] < (b << 16)) ++k;
        t->first_code[b] = (uint8_t)k;
    }
}

/* A NaN takes the first branch and sets *nan. */
static inline uint8_t srgb_code(const srgb_table *t, float x, int *nan) {
    if (!(x > 0.0f)) {
        *nan |= x != x;
        return 0;
    }
    if (x >= 1.0f) return 255;
    uint32_t bits;
    memcpy(&bits, &x, sizeof bits);
    unsigned k = t->first_code[bits >> 16];
    while (t->threshold[k] <= bits) ++k;
    return (uint8_t)k;
}

cj_status cj_render_image_to_srgb8(const cj_render_image *img, uint8_t *rgba8, size_t stride) {
    srgb_table th;
    srgb_table_build(&th);
    if (stride == 0) stride = (size_t)img->width * 4;
    const size_t row = (size_t)img->width * 4;
    for (int y = 0; y < img->height; ++y) {
        const float *src = img->rgba + (size_t)y * row;
        uint8_t *dst = rgba8 + (size_t)y * stride;
        for (int x = 0; x < img->width; ++x) {
            int nan = 0;
            dst[4 * x + 0] = srgb_code(&th, src[4 * x + 0], &nan);
            dst[4 * x + 1] = srgb_code(&th, src[4 * x + 1], &nan);
            dst[4 * x + 2] = srgb_code(&th, src[4 * x + 2], &nan);
            const float a_in = src[4 * x + 3];
            nan |= a_in != a_in;
            const float a = a_in > 0.0f ? (a_in < 1.0f ? a_in : 1.0f) : 0.0f; /* NaN: 0 */
            /* round to nearest, ties to even (what lrintf does in the default rounding mode):
             * adding 2^23 leaves no fraction bits for a value in [0, 255] */
            dst[4 * x + 3] = (uint8_t)(int)((a * 255.0f + 0x1p23f) - 0x1p23f);
            if (nan) /* the NaN pixel's bytes are left unspecified */
                for (int c = 0; c < 4; ++c)
                    if (src[4 * x + c] != src[4 * x + c])
                        return cj_fail(CJ_ERR_NONFINITE, "pixel (%d, %d) channel %d is NaN", x, y,
                                       c);
        }
    }
    return CJ_OK;
}

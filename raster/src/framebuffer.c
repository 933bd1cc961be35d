/* The RGBA8 framebuffer: creation, clearing, pixel access and exact source-over blending. */
#include "casteljau/framebuffer.h"
#include "alloc_internal.h"
#include "error_internal.h"
#include "raster_internal.h"

#include <assert.h>
#include <math.h>
#include <string.h>

cj_status cj_framebuffer_create(int width, int height, unsigned flags, const cj_allocator *alloc,
                                cj_framebuffer **out) {
    assert(out);
    if (width < 1 || width > CJ_FRAMEBUFFER_MAX_SIDE)
        return cj_fail(CJ_ERR_RANGE, "framebuffer width %d is outside [1, %d]", width,
                       CJ_FRAMEBUFFER_MAX_SIDE);
    if (height < 1 || height > CJ_FRAMEBUFFER_MAX_SIDE)
        return cj_fail(CJ_ERR_RANGE, "framebuffer height %d is outside [1, %d]", height,
                       CJ_FRAMEBUFFER_MAX_SIDE);
    if (flags & ~(unsigned)(CJ_FB_DEPTH | CJ_FB_PADDED))
        return cj_fail(CJ_ERR_ARGUMENT, "framebuffer flags 0x%x contain unknown bits", flags);
    const cj_allocator a = cj_allocator_resolve(alloc);
    ptrdiff_t stride = width;
    if (flags & CJ_FB_PADDED) {
        stride = (width + 15) / 16 * 16; /* 16 pixels = one 64-byte line */
        if ((stride / 16) % 2 == 0) stride += 16;
    }
    size_t n = (size_t)stride * (size_t)height;
    cj_framebuffer *fb = cj_allocator_alloc(&a, sizeof *fb);
    if (!fb) return cj_fail(CJ_ERR_NOMEM, "no memory for a framebuffer header");
    memset(fb, 0, sizeof *fb);
    fb->alloc_ = a;
    fb->width = width;
    fb->height = height;
    fb->stride = stride;
    fb->pixels = cj_allocator_alloc(&a, n * sizeof *fb->pixels);
    if (!fb->pixels) {
        cj_framebuffer_destroy(fb);
        return cj_fail(CJ_ERR_NOMEM, "no memory for %dx%d RGBA pixels", width, height);
    }
    memset(fb->pixels, 0, n * sizeof *fb->pixels);
    if (flags & CJ_FB_DEPTH) {
        fb->depth = cj_allocator_alloc(&a, n * sizeof *fb->depth);
        if (!fb->depth) {
            cj_framebuffer_destroy(fb);
            return cj_fail(CJ_ERR_NOMEM, "no memory for a %dx%d depth plane", width, height);
        }
        cj_framebuffer_clear_depth(fb, 1.0f);
    }
    *out = fb;
    return CJ_OK;
}

void cj_framebuffer_destroy(cj_framebuffer *fb) {
    if (!fb) return;
    const cj_allocator a = fb->alloc_;
    cj_allocator_free(&a, fb->pixels);
    cj_allocator_free(&a, fb->depth);
    cj_allocator_free(&a, fb->cover_);
    cj_allocator_free(&a, fb->span_lo_);
    cj_allocator_free(&a, fb->span_hi_);
    cj_allocator_free(&a, fb);
}

void cj_framebuffer_clear(cj_framebuffer *fb, cj_rgba c) {
    assert(fb);
    size_t n = (size_t)fb->stride * (size_t)fb->height; /* padding included: harmless */
    cj_rgba *p = fb->pixels;
    for (size_t i = 0; i < n; ++i) p[i] = c;
}

void cj_framebuffer_clear_depth(cj_framebuffer *fb, float z) {
    assert(fb);
    if (!fb->depth) return;
    size_t n = (size_t)fb->stride * (size_t)fb->height;
    for (size_t i = 0; i < n; ++i) fb->depth[i] = z;
}

int cj_framebuffer_setpixel(cj_framebuffer *fb, long long x, long long y, cj_rgba c) {
    assert(fb);
    if (!cj_framebuffer_inside(fb, x, y)) return 0;
    fb->pixels[(ptrdiff_t)y * fb->stride + (ptrdiff_t)x] = c;
    return 1;
}

cj_status cj_framebuffer_getpixel(const cj_framebuffer *fb, long long x, long long y,
                                  cj_rgba *out) {
    assert(fb && out);
    if (!cj_framebuffer_inside(fb, x, y))
        return cj_fail(CJ_ERR_RANGE, "pixel (%lld, %lld) is outside the %dx%d framebuffer", x, y,
                       fb->width, fb->height);
    *out = fb->pixels[(ptrdiff_t)y * fb->stride + (ptrdiff_t)x];
    return CJ_OK;
}

cj_rgba cj_rgba_over(cj_rgba s, cj_rgba d) {
    return cj_rgba_over_inl_(s, d);
}

int cj_framebuffer_blend(cj_framebuffer *fb, long long x, long long y, cj_rgba c) {
    assert(fb);
    if (!cj_framebuffer_inside(fb, x, y)) return 0;
    cj_rgba *p = &fb->pixels[(ptrdiff_t)y * fb->stride + (ptrdiff_t)x];
    *p = cj_rgba_over_inl_(c, *p);
    return 1;
}

int cj_framebuffer_blend_coverage(cj_framebuffer *fb, long long x, long long y, cj_rgba c,
                                  float coverage) {
    assert(fb);
    if (!cj_framebuffer_inside(fb, x, y)) return 0;
    c.a = cj_raster_scale_alpha_(c.a, coverage);
    cj_rgba *p = &fb->pixels[(ptrdiff_t)y * fb->stride + (ptrdiff_t)x];
    *p = cj_rgba_over_inl_(c, *p);
    return 1;
}

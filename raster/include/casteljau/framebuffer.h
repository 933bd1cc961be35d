/* casteljau: an RGBA8 framebuffer with an optional float depth plane.
 *
 * Coordinates: pixel (x, y) covers the square [x, x+1) x [y, y+1) of the plane and its centre is
 * (x + 0.5, y + 0.5). The origin is the LOWER-LEFT pixel, as in OpenGL: row 0 is the bottom row
 * and y grows upwards. Pixel (x, y) lives at pixels[y * stride + x]; stride == width unless the
 * framebuffer was created with CJ_FB_PADDED (always index with stride).
 *
 * Image files are the other way round: they store the TOP row first. Whoever writes a
 * framebuffer to a file (the viz/ image writer) flips the rows, and whoever reads one flips back;
 * cj_framebuffer_row_top() gives the row to write in file order.
 *
 * Colour: 8-bit straight (non-premultiplied) RGBA, one cj_rgba (4 bytes, r g b a in memory
 * order) per pixel. Blending is Porter-Duff source-over on the stored 8-bit values (no gamma
 * conversion), with exact rational arithmetic rounded to nearest (see cj_rgba_over).
 *
 * Ownership: cj_framebuffer_create() allocates the planes through the given allocator (or
 * malloc/free when it is NULL) and cj_framebuffer_destroy() releases them. The public fields are
 * read-only for users; write pixels through the functions here or directly into `pixels`.
 * A framebuffer is not thread-safe (drawing uses scratch planes inside it).
 */
#ifndef CASTELJAU_FRAMEBUFFER_H
#define CASTELJAU_FRAMEBUFFER_H

#include "casteljau/alloc.h"
#include "casteljau/status.h"
#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Largest width or height of a framebuffer. */
#define CJ_FRAMEBUFFER_MAX_SIDE 32768

/* Objects of raster/ that own memory take an optional cj_allocator (casteljau/alloc.h). */

/* One pixel, straight (non-premultiplied) alpha; 255 = opaque. */
typedef struct cj_rgba {
    uint8_t r, g, b, a;
} cj_rgba;

static inline cj_rgba cj_rgba_make(uint8_t r, uint8_t g, uint8_t b, uint8_t a) {
    cj_rgba c;
    c.r = r;
    c.g = g;
    c.b = b;
    c.a = a;
    return c;
}

/* Flags for cj_framebuffer_create(). */
enum {
    CJ_FB_DEPTH = 1u, /* also allocate a float depth plane (for the 3D renderer) */
    /* Pad rows so that the row pitch is an odd number of 64-byte cache lines. With power-of-two
     * widths (512, 1024, 2048) every pixel of a column maps to the same cache set and steep
     * lines run ~10x slower (bench_lines shows both); padding removes that. Rows are then not
     * contiguous: stride > width. */
    CJ_FB_PADDED = 2u
};

typedef struct cj_framebuffer {
    int width;        /* 1..CJ_FRAMEBUFFER_MAX_SIDE */
    int height;       /* 1..CJ_FRAMEBUFFER_MAX_SIDE */
    ptrdiff_t stride; /* pixels from one row to the next (== width unless CJ_FB_PADDED) */
    cj_rgba *pixels;  /* stride*height pixels, row 0 = bottom row */
    float *depth;     /* depths laid out like pixels (same stride), or NULL without CJ_FB_DEPTH */
    /* private: allocator and the scratch planes of the anti-aliased stroker */
    cj_allocator alloc_;
    float *cover_;
    int *span_lo_, *span_hi_;
} cj_framebuffer;

/* Creates a width x height framebuffer cleared to transparent black (0,0,0,0), with a depth plane
 * cleared to +1 (the far end of pseudodepth [-1, 1]) when flags has CJ_FB_DEPTH, and padded rows
 * with CJ_FB_PADDED.
 * `alloc` may be NULL (malloc/free); it is copied.
 * Returns CJ_ERR_RANGE if width or height is outside [1, CJ_FRAMEBUFFER_MAX_SIDE],
 * CJ_ERR_ARGUMENT for unknown flags, CJ_ERR_NOMEM if an allocation fails; *out is set only on
 * success. */
cj_status cj_framebuffer_create(int width, int height, unsigned flags, const cj_allocator *alloc,
                                cj_framebuffer **out);

/* Releases everything; fb may be NULL. */
void cj_framebuffer_destroy(cj_framebuffer *fb);

/* Sets every pixel to c. */
void cj_framebuffer_clear(cj_framebuffer *fb, cj_rgba c);

/* Sets every depth to z; does nothing without a depth plane. */
void cj_framebuffer_clear_depth(cj_framebuffer *fb, float z);

/* 1 if (x, y) is a pixel of fb, else 0. */
static inline int cj_framebuffer_inside(const cj_framebuffer *fb, long long x, long long y) {
    return x >= 0 && y >= 0 && x < fb->width && y < fb->height;
}

/* Stores c at (x, y) (no blending). Out-of-range pixels are ignored (clipping is not an error):
 * returns 1 if the pixel was written, 0 if it lies outside. */
int cj_framebuffer_setpixel(cj_framebuffer *fb, long long x, long long y, cj_rgba c);

/* Reads the pixel at (x, y) into *out. CJ_ERR_RANGE (naming the coordinate) if it lies outside;
 * *out untouched then. */
cj_status cj_framebuffer_getpixel(const cj_framebuffer *fb, long long x, long long y, cj_rgba *out);

/* Porter-Duff source-over of straight-alpha colours, exactly rounded: with α_s = s.a/255 and
 * α_d = d.a/255,
 *     α_o = α_s + α_d (1 - α_s),   c_o = (c_s α_s + c_d α_d (1 - α_s)) / α_o,
 * each result channel is the nearest 8-bit value to the exact rational result (halves round up).
 * An opaque source returns s unchanged; a transparent one (s.a == 0) returns d unchanged. */
cj_rgba cj_rgba_over(cj_rgba s, cj_rgba d);

/* Blends c over the pixel at (x, y) (source-over, see cj_rgba_over). Out-of-range pixels are
 * ignored: returns 1 if the pixel was touched, else 0. */
int cj_framebuffer_blend(cj_framebuffer *fb, long long x, long long y, cj_rgba c);

/* Blends c with its alpha scaled by coverage (clamped to [0, 1]; NaN counts as 0): the source
 * alpha is round(c.a * coverage). Used by the anti-aliased drawing functions. Returns 1 if the
 * pixel is inside, else 0. */
int cj_framebuffer_blend_coverage(cj_framebuffer *fb, long long x, long long y, cj_rgba c,
                                  float coverage);

/* The row that comes `file_row`-th in an image file (top row first): row height-1-file_row.
 * file_row must be in [0, height). */
static inline const cj_rgba *cj_framebuffer_row_top(const cj_framebuffer *fb, int file_row) {
    return fb->pixels + (ptrdiff_t)(fb->height - 1 - file_row) * fb->stride;
}

#ifdef __cplusplus
}
#endif
#endif

/* Private to the stroker: the coverage plane and its exact signed-area accumulation
 * (stroke_cover.c), shared with the stroke geometry (stroke.c). */
#ifndef CASTELJAU_STROKE_INTERNAL_H
#define CASTELJAU_STROKE_INTERNAL_H

#include "casteljau/line.h"
#include <math.h>
#include <stddef.h>

typedef struct cover_target {
    float *cover;     /* w*h, zero outside touched spans */
    int *lo, *hi;     /* per row, relative x; empty when lo > hi */
    int ox, oy, w, h; /* pixel (x, y) is cover[(y-oy)*cs + (x-ox)] */
    ptrdiff_t cs;     /* row pitch of the plane (padded: see CJ_FB_PADDED) */
    int ymin, ymax;   /* touched rows, relative; empty when ymin > ymax */
    /* Sheared plane (steep single segments, see narrow_plane): row ry holds the cells of
     * columns base(ry) .. base(ry) + cs - 1, base(ry) = floor(bx0 + bk ry); 0 when !sheared. */
    int sheared;
    double bx0, bk;
} cover_target;

/* Offset of cell (ry, x = 0) in the plane. */
static inline ptrdiff_t row_offset(const cover_target *t, int ry) {
    ptrdiff_t o = (ptrdiff_t)ry * t->cs;
    if (t->sheared) o -= (ptrdiff_t)floor(t->bx0 + t->bk * ry);
    return o;
}

#define POLY_MAX 16
typedef struct poly {
    cj_vec2 v[POLY_MAX];
    int n;
} poly;

/* Accumulates sign * area(pixel ∩ p) into t for every pixel of the target (see stroke_cover.c). */
void cj_stroke_cover_poly(cover_target *t, const poly *p, float sign);

/* Hands every covered pixel to fn (or blends colour c into fb; both NULL: just clears) and
 * clears the plane behind. */
void cj_stroke_compose(cover_target *t, cj_framebuffer *fb, cj_rgba c, cj_line_cover_fn fn,
                       void *user);

/* Switches t to the narrow sheared plane where the stroke allows it (see stroke_cover.c);
 * returns 1 if it did. */
int cj_stroke_narrow_plane(cover_target *t, const cj_vec2 *pts, size_t n, int closed,
                           const cj_line_stroke *style);

#endif

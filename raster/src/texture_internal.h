/* Private to raster/: texture sampling (seed 10) for the rasterizer pipeline and the ray tracer.
 *
 * A sampler is prepared once per scene texture (cj_tex_sampler_init) and then read by any number
 * of threads. Texture coordinates: (u, v) of the geometry mapped by the texture's scale and
 * offset, u' = u·scale_u + offset_u; u' in [0, 1] spans the image once (texel i covers
 * [i/w, (i+1)/w), centres at (i + 1/2)/w; v' = 0 is the bottom row). REPEAT wraps, CLAMP clamps.
 *   NEAREST    the texel containing (u', v').
 *   BILINEAR   the 4 nearest texel centres, lerped (a + f (b − a), so a constant texture is
 *              returned exactly).
 *   TRILINEAR  a mip pyramid (each level the 2x2 box average of the one below, odd sizes
 *              averaging the texels that exist), level λ = log2 ρ with ρ the longer of the
 *              footprints |∂(u',v')/∂x|, |∂(u',v')/∂y| in level-0 texels; bilinear in levels
 *              floor(λ) and floor(λ)+1, lerped by the fraction; λ <= 0 is bilinear level 0.
 *   CHECKER    squares of 1/checks in (u', v'), colour a where floor(u' cu) + floor(v' cv) is
 *              even. NEAREST point-samples; the other filters box-filter the pattern over the
 *              pixel footprint analytically (the integral of the square wave), which removes
 *              the checker's aliasing in the distance.
 * The derivatives are in texture units per pixel of the image. */
#ifndef CASTELJAU_TEXTURE_INTERNAL_H
#define CASTELJAU_TEXTURE_INTERNAL_H

#include "casteljau/alloc.h"
#include "casteljau/scene.h"
#include "casteljau/status.h"

#define CJ_TEX_MAX_LEVELS 24

typedef struct cj_tex_level {
    int w, h;
    const float *rgba; /* 4 floats per texel, bottom row first */
} cj_tex_level;

typedef struct cj_tex_sampler {
    cj_texture_kind kind;
    cj_tex_filter filter;
    cj_tex_wrap wrap;
    double su, sv, ou, ov;
    int levels;
    cj_tex_level level[CJ_TEX_MAX_LEVELS];
    float *owned; /* the mip levels above 0, one block */
    int checks_u, checks_v;
    float a[3], b[3];
    int needs_deriv; /* 1 when the sample depends on the footprint */
    cj_allocator alloc;
} cj_tex_sampler;

/* Prepares a sampler for texture `index` of a scene (image textures need their pixels:
 * CJ_ERR_ARGUMENT naming the texture otherwise). Builds the mip pyramid for TRILINEAR. */
cj_status cj_tex_sampler_init(const cj_texture *tex, int index, const cj_allocator *alloc,
                              cj_tex_sampler *out);
void cj_tex_sampler_free(cj_tex_sampler *s);

/* The filtered RGB at (u, v) (the geometry's coordinates) with the screen derivatives of u and
 * v (ignored unless needs_deriv). */
void cj_tex_sample(const cj_tex_sampler *s, double u, double v, double dudx, double dvdx,
                   double dudy, double dvdy, float out[3]);

#endif

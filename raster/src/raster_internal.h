/* Private helpers shared by the raster/ sources. */
#ifndef CASTELJAU_RASTER_INTERNAL_H
#define CASTELJAU_RASTER_INTERNAL_H

#include "alloc_internal.h"
#include "casteljau/framebuffer.h"
#include <stddef.h>

/* round(a * coverage) with coverage clamped to [0, 1] (NaN -> 0). */
static inline uint8_t cj_raster_scale_alpha_(uint8_t a, float coverage) {
    if (!(coverage > 0.0f)) return 0;
    if (coverage >= 1.0f) return a;
    return (uint8_t)((float)a * coverage + 0.5f);
}

/* Exact source-over (see cj_rgba_over), inlined into the drawing loops. */
static inline cj_rgba cj_rgba_over_inl_(cj_rgba s, cj_rgba d) {
    uint32_t sa = s.a, da = d.a;
    if (sa == 255) return s;
    if (sa == 0) return d;
    if (da == 255) { /* opaque destination: A = 255^2, divide by the constant 2*255 */
        uint32_t ws = sa, wd = 255u - sa;
        cj_rgba o;
        o.r = (uint8_t)((2u * (s.r * ws + d.r * wd) + 255u) / 510u);
        o.g = (uint8_t)((2u * (s.g * ws + d.g * wd) + 255u) / 510u);
        o.b = (uint8_t)((2u * (s.b * ws + d.b * wd) + 255u) / 510u);
        o.a = 255;
        return o;
    }
    /* Everything scaled by 255^2: A = α_o 255², channel numerator = c_o α_o 255². */
    uint32_t wd = da * (255u - sa);
    uint32_t A = sa * 255u + wd;
    cj_rgba o; /* A >= 255 since sa >= 1 */
    o.a = (uint8_t)((2u * A + 255u) / 510u);
    uint32_t ws = sa * 255u, A2 = 2u * A;
    o.r = (uint8_t)((2u * (s.r * ws + d.r * wd) + A) / A2);
    o.g = (uint8_t)((2u * (s.g * ws + d.g * wd) + A) / A2);
    o.b = (uint8_t)((2u * (s.b * ws + d.b * wd) + A) / A2);
    return o;
}

#endif

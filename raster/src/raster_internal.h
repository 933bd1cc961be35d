/* Private helpers shared by the raster/ sources. */
#ifndef CASTELJAU_RASTER_INTERNAL_H
#define CASTELJAU_RASTER_INTERNAL_H

#include "casteljau/framebuffer.h"
#include <stddef.h>

void *cj_raster_alloc_(const cj_raster_allocator *a, size_t bytes);
void cj_raster_free_(const cj_raster_allocator *a, void *ptr);

/* round(a * coverage) with coverage clamped to [0, 1] (NaN -> 0). */
static inline uint8_t cj_raster_scale_alpha_(uint8_t a, float coverage) {
    if (!(coverage > 0.0f)) return 0;
    if (coverage >= 1.0f) return a;
    return (uint8_t)((float)a * coverage + 0.5f);
}

#endif

/* The ray tracer's pixel reconstruction filters (cj_pixel_filter in casteljau/scene.h). */
#ifndef CASTELJAU_PIXEL_FILTER_H
#define CASTELJAU_PIXEL_FILTER_H

#include "casteljau/scene.h"

#include <math.h>

/* The support radius in pixels: r, or the filter's default when r is 0. */
static inline double cj_pixel_filter_radius(cj_pixel_filter f, double r) {
    if (r > 0.0) return r;
    switch (f) {
    case CJ_FILTER_TENT:
        return 1.0;
    case CJ_FILTER_GAUSSIAN:
        return 1.5;
    case CJ_FILTER_MITCHELL:
        return 2.0;
    default:
        return 0.5;
    }
}

/* f(x) for |x| < r (0 outside); the formulas of cj_pixel_filter. */
static inline double cj_pixel_filter_eval(cj_pixel_filter f, double r, double x) {
    const double ax = fabs(x);
    if (!(ax < r)) return 0.0;
    switch (f) {
    case CJ_FILTER_TENT:
        return 1.0 - ax / r;
    case CJ_FILTER_GAUSSIAN: {
        const double s2 = 2.0 * (r / 3.0) * (r / 3.0);
        return exp(-ax * ax / s2) - exp(-r * r / s2);
    }
    case CJ_FILTER_MITCHELL: {
        const double B = 1.0 / 3.0, C = 1.0 / 3.0, t = 2.0 * ax / r;
        if (t < 1.0)
            return ((12 - 9 * B - 6 * C) * t * t * t + (-18 + 12 * B + 6 * C) * t * t +
                    (6 - 2 * B)) /
                   6.0;
        return ((-B - 6 * C) * t * t * t + (6 * B + 30 * C) * t * t + (-12 * B - 48 * C) * t +
                (8 * B + 24 * C)) /
               6.0;
    }
    default:
        return 1.0;
    }
}

#endif

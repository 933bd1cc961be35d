/* The local reflection model of both renderers, written once (docs/light.md, DESIGN.md "Light
 * is radiometric"). The rasterizer's float kernels (render_shade.c) and the ray tracer's double
 * shading (trace_shade.c) both call the functions below; one macro body defines the float and
 * the double instance, so the two renderers cannot drift apart.
 *
 * For one light of intensity I (already multiplied by its spot / distance factor f), unit
 * normal n on the side being lit, unit direction l towards the light and unit direction v
 * towards the viewer:
 *   diffuse   d = max(0, n·l)
 *   specular  s = 0                                  where n·l <= 0 (the light is behind the
 *                                                    surface: no highlight beyond the terminator)
 *             s = max(0, n·h)^α, h = (l+v)/|l+v|     CJ_SPEC_BLINN
 *             s = max(0, m·v)^α, m = 2(n·l)n − l     CJ_SPEC_PHONG (the seed's mirror form)
 * and the material adds c_r r_d I d + c_p r_s I s. With α = 0 the lobe is 1 wherever n·l > 0
 * (0^0 = 1: a constant lobe over the lit side).
 *
 * WHY n·l <= 0 GIVES NO HIGHLIGHT: a point whose normal faces away from the light receives no
 * light (its irradiance n·l E is zero); any reflected radiance there would be created from
 * nothing. The half-vector lobe alone is positive up to 90° past the terminator, which is what
 * the rasterizer drew before (issue 21). */
#ifndef CASTELJAU_REFLECT_MODEL_H
#define CASTELJAU_REFLECT_MODEL_H

#include "casteljau/scene.h"

#include <math.h>

#define CJ_REFLECT_DEFINE(SUF, T, SQRT, POW)                                                       \
    /* d and s of one light (see above); n, l, v unit vectors. */                                  \
    static inline void cj_reflect_terms_##SUF(const T n[3], const T l[3], const T v[3], T alpha,   \
                                              int model, T *d, T *s) {                             \
        const T nl = n[0] * l[0] + n[1] * l[1] + n[2] * l[2];                                      \
        if (!(nl > (T)0)) {                                                                        \
            *d = (T)0;                                                                             \
            *s = (T)0;                                                                             \
            return;                                                                                \
        }                                                                                          \
        *d = nl;                                                                                   \
        T c;                                                                                       \
        if (model == CJ_SPEC_PHONG) {                                                              \
            c = (T)0;                                                                              \
            for (int k = 0; k < 3; ++k) c += ((T)2 * nl * n[k] - l[k]) * v[k];                     \
        } else {                                                                                   \
            T h[3] = {l[0] + v[0], l[1] + v[1], l[2] + v[2]};                                      \
            T hl = SQRT(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);                                  \
            /* l = −v: every half vector is as good as none; the lobe is at its rim */           \
            c = hl > (T)0 ? (n[0] * h[0] + n[1] * h[1] + n[2] * h[2]) / hl : (T)0;                 \
        }                                                                                          \
        if (c > (T)0)                                                                              \
            *s = POW(c, alpha);                                                                    \
        else                                                                                       \
            *s = alpha == (T)0 ? (T)1 : (T)0; /* max(0, c)^0 = 1 */                                \
    }

CJ_REFLECT_DEFINE(f, float, sqrtf, powf)
CJ_REFLECT_DEFINE(d, double, sqrt, pow)

#undef CJ_REFLECT_DEFINE

#endif

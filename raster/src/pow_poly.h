/* c^a in float without a libm call, for the rasterizer's specular lobes and spot cones
 * (render_shade.c, render_shade8.c). Straight-line arithmetic (no branch, no table), so a loop
 * of 8 calls over arrays vectorises; every lane does the same IEEE operations as a scalar
 * call, so a sample's value never depends on the lane, tile or thread that computed it.
 *
 * METHOD. c = 2^e m with m in [√½, √2) (exponent and mantissa from the bits), then
 *   log2 c = e + (2/ln 2) atanh(t),  t = (m − 1)/(m + 1),  |t| <= 3 − 2√2 < 0.1716,
 * with atanh t = t + t³/3 + t⁵/5 + t⁷/7 + t⁹/9 (truncation <= t¹⁰/(11(1 − t²)) < 2.1e-9
 * relative); y = a log2 c (0 below −126, clamped at 126); y = k + f with k = rint(y), |f| <= 1/2;
 *   2^f = Σ_{i<=7} (f ln 2)^i / i!  (truncation <= (ln2/2)^8/8! · √2 < 7.4e-9 relative),
 * and 2^k from the exponent bits. m − 1 is exact (Sterbenz), so log2 c keeps a small relative
 * error even where c is near 1.
 *
 * DOMAIN. c > 0 normal (c >= FLT_MIN) and finite, a >= 0 finite. A result below 2^-126 is
 * returned as 0 (absolute error < 1.2e-38, as powf's underflow). a = 0 or c = 1 gives exactly 1.
 *
 * ERROR BOUND (stated with a margin of 2 over what we measured, and checked against MPFR at
 * 140 bits by test_pow_poly over 1.2·10⁶ random and grid points of the domain, the worst case
 * printed: 1.85e-7 relative, 9.4e-8 absolute). With y = a log2 c:
 *   |pow_poly(c, a) − c^a| <= 4e-7 · c^a · (1 + |y|)       (every c, a in the domain)
 *   |pow_poly(c, a) − c^a| <= 5e-7                          (where c <= 1)
 * The second follows from the first: for y <= 0, 2^y (1 + |y|) peaks at y = 1 − 1/ln 2 with
 * value 1.0615. Where the error comes from: about 8 float roundings in log2 c, amplified by a
 * (an error δ in y is a relative error ln 2 · δ in 2^y), and about 9 in the exp2 polynomial.
 * In the shading (colour values of order 1, written in 8-bit sRGB steps of 1/255 or as float
 * EXR), 5e-7 is about 1/8000 of an 8-bit step. */
#ifndef CASTELJAU_POW_POLY_H
#define CASTELJAU_POW_POLY_H

#include <stdint.h>
#include <string.h>

#if defined(__GNUC__)
#define CJ_POW_INLINE static inline __attribute__((always_inline))
#else
#define CJ_POW_INLINE static inline
#endif

CJ_POW_INLINE float cj_pow_poly(float c, float a) {
    uint32_t bits;
    memcpy(&bits, &c, sizeof bits);
    /* m in [1, 2) from the mantissa; halved (and e raised) when above √2 (mantissa bits of
     * √2 = 1.41421354 are 0x3504f3) */
    const uint32_t frac = bits & 0x7fffffu;
    const uint32_t big = frac > 0x3504f3u ? 1u : 0u;
    const uint32_t mbits = (frac | 0x3f800000u) - (big << 23);
    const int32_t e = (int32_t)(bits >> 23) - 127 + (int32_t)big;
    float m;
    memcpy(&m, &mbits, sizeof m);
    const float t = (m - 1.0f) / (m + 1.0f), t2 = t * t;
    /* 2/ln 2 and 1/(2i+1) */
    const float series =
        1.0f + t2 * (0.333333333f + t2 * (0.2f + t2 * (0.142857143f + t2 * 0.111111111f)));
    const float log2c = (float)e + t * 2.88539008f * series;
    const float y0 = a * log2c;
    float y = y0 < -126.0f ? -126.0f : y0;
    y = y > 126.0f ? 126.0f : y;
    /* rint by the 1.5·2^23 shift: exact for |y| < 2^22; f = y − k is exact */
    const float k = (y + 12582912.0f) - 12582912.0f, f = y - k;
    /* (ln 2)^i / i!, i = 1..7 */
    const float p =
        1.0f +
        f * (0.693147181f +
             f * (0.240226507f +
                  f * (0.0555041087f +
                       f * (0.00961812911f +
                            f * (0.00133335581f + f * (0.000154035304f + f * 1.52527338e-05f))))));
    const uint32_t sbits = (uint32_t)((int32_t)k + 127) << 23;
    float scale;
    memcpy(&scale, &sbits, sizeof scale);
    return y0 < -126.0f ? 0.0f : p * scale;
}

#endif

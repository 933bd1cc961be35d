/* Private to the casteljau tool: rational weights scaled so that the largest is in [1, 2).
 * A rational curve or patch does not change when every weight is multiplied by one constant,
 * and multiplying by a power of two is exact, so this changes nothing but keeps products of
 * weights and coordinates (and error bounds) inside the double range: weights all equal to
 * 1e308 describe the plain polynomial, and are treated as such. */
#ifndef CASTELJAU_APP_WEIGHTS_H
#define CASTELJAU_APP_WEIGHTS_H

#include <math.h>
#include <stddef.h>

/* Scales w[0..n) (all > 0 and finite) by 2^-e, e the exponent of the largest. Returns 0, or -1
 * when the smallest weight would underflow (weights spanning more than the double range). */
static inline int weights_normalize(double *w, size_t n) {
    double mx = 0.0;
    for (size_t i = 0; i < n; ++i) mx = w[i] > mx ? w[i] : mx;
    if (!(mx > 0.0)) return -1;
    const int e = ilogb(mx);
    for (size_t i = 0; i < n; ++i) {
        const double s = ldexp(w[i], -e);
        if (!(s >= 0x1p-1022)) return -1; /* subnormal or zero: precision lost */
        w[i] = s;
    }
    return 0;
}

#endif

/* Private: error-free transformations (Knuth's TwoSum, TwoProd by fma). The compensated
 * de Casteljau kernel built on them is declared in eval_internal.h. */
#ifndef CASTELJAU_EFT_INTERNAL_H
#define CASTELJAU_EFT_INTERNAL_H

#include "casteljau/bezier.h"
#include <math.h>

/* a + b = *s + *e exactly, *s = fl(a + b). Knuth's branch-free version: 6 flops. */
static inline void cj_two_sum(double a, double b, double *s, double *e) {
    const double x = a + b;
    const double z = x - a;
    *e = (a - (x - z)) + (b - z);
    *s = x;
}

/* a * b = *p + *e exactly (barring underflow), *p = fl(a * b). With a hardware fma this is
 * two instructions; otherwise Dekker's splitting (17 flops) keeps it exact without fma. */
static inline void cj_two_prod(double a, double b, double *p, double *e) {
    const double x = a * b;
#if defined(FP_FAST_FMA) || defined(__FMA__)
    *e = fma(a, b, -x);
#else
    const double f = 134217729.0; /* 2^27 + 1 */
    double c = f * a, ah = c - (c - a), al = a - ah;
    c = f * b;
    double bh = c - (c - b), bl = b - bh;
    *e = al * bl - (((x - ah * bh) - al * bh) - ah * bl);
#endif
    *p = x;
}

#endif

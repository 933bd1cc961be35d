/* Private: unchecked evaluation kernels shared by the Bézier sources. The caller has validated
 * the curve (degree within the method's limit, dimension, finite points) and the parameter. */
#ifndef CASTELJAU_EVAL_INTERNAL_H
#define CASTELJAU_EVAL_INTERNAL_H

#include "casteljau/bezier.h"
#include <stddef.h>

#if defined(__GNUC__)
#define CJ_ALWAYS_INLINE static inline __attribute__((always_inline))
#else
#define CJ_ALWAYS_INLINE static inline
#endif

/* The smallest positive subnormal, 2^-1074: every rounding that underflows (a product, or an
 * fma, landing below 2^-1022) may add an absolute error of half of it on top of the relative
 * error u the published bounds account for. */
#define CJ_ETA 0x1p-1074

/* 1 if all count values are finite: x - x is +0 for finite x and NaN for NaN or ±inf, and a
 * NaN survives any sum. Four independent accumulators and no branch per value: this runs on
 * every evaluation call, so it must cost little next to a cubic's evaluation. */
static inline int cj_all_finite(const double *v, size_t count) {
    double a0 = 0.0, a1 = 0.0, a2 = 0.0, a3 = 0.0;
    size_t i = 0;
    for (; i + 4 <= count; i += 4) {
        a0 += v[i] - v[i];
        a1 += v[i + 1] - v[i + 1];
        a2 += v[i + 2] - v[i + 2];
        a3 += v[i + 3] - v[i + 3];
    }
    for (; i < count; ++i) a0 += v[i] - v[i];
    return (a0 + a1) + (a2 + a3) == 0.0;
}

/* CJ_OK if the dim values are finite, else CJ_ERR_RANGE naming t: a finite curve evaluated at a
 * finite t can still overflow when extrapolating far outside [0,1], and the methods would then
 * return NaN or infinity; that is reported instead. */
cj_status cj_check_value(const double *v, int dim, double t);

/* out[0..dim-1] = v[0..dim-1], unrolled for the common dimensions (a plain loop becomes a
 * memcpy call, which costs more than the copy for a point). */
static inline void cj_copy_point(double *out, const double *v, int dim) {
    switch (dim) {
    case 4:
        out[3] = v[3];
        /* fallthrough */
    case 3:
        out[2] = v[2];
        /* fallthrough */
    case 2:
        out[1] = v[1];
        /* fallthrough */
    case 1:
        out[0] = v[0];
        break;
    default:
        for (int k = 0; k < dim; ++k) out[k] = v[k];
        break;
    }
}

/* Plain de Casteljau: out[0..dim-1] = c(t). */
void cj_decasteljau_kernel(const cj_bezier *c, double t, double *out);

/* Compensated de Casteljau: out[k] = c_k(t) as if computed in twice the working precision and
 * rounded once. If bound is not NULL, bound[k] is a rigorous a-posteriori bound of
 * |out[k] - c_k(t)| (see bezier_compensated.c). */
void cj_compensated_kernel(const cj_bezier *c, double t, double *out, double *bound);

/* Allowance for underflow in an evaluation of degree n with `ops` possibly underflowing
 * roundings per triangle entry and level: ops (n+1) eta A^n with A = |1-t| + |t| (1 on [0,1]),
 * the factor by which an absolute error can grow through the remaining levels. Rounded up;
 * +INFINITY when A^n overflows; 0 for n = 0 (a constant is returned without arithmetic). */
double cj_underflow_allowance(int n, double t, double ops);

#endif

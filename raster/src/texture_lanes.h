/* Private to the rasterizer's Phong kernels (render_shade8.c): the procedural checker of
 * texture_internal.h on CJ_LANES samples at once, with the screen derivatives of (u, v) from
 * each triangle's (u, v) plane (render_shade.c's uv_plane). The same double operations as
 * cj_tex_sample and uv_derivs, written without branches per sample so that the loops
 * vectorise (4 doubles per AVX register): the values are bit-identical to the scalar sampler
 * (test_render_lanes checks it on random inputs). Image textures stay on cj_tex_sample. */
#ifndef CASTELJAU_TEXTURE_LANES_H
#define CASTELJAU_TEXTURE_LANES_H

#include "texture_internal.h"

#include <math.h>

#define CJ_TEX_LANES 8

#if defined(__GNUC__)
#define CJ_TEX_LANE_INLINE static inline __attribute__((always_inline))
#else
#define CJ_TEX_LANE_INLINE static inline
#endif

/* One block of checker lookups: per lane the geometry's (u, v), the pixel point (sx, sy), the
 * (u,v) plane U, V, Q (9 doubles; all 0 where the sample needs no footprint) and the
 * sampler's parameters. */
typedef struct cj_checker_lanes {
    double u[CJ_TEX_LANES], v[CJ_TEX_LANES], sx[CJ_TEX_LANES], sy[CJ_TEX_LANES];
    double plane[9][CJ_TEX_LANES];
    double su[CJ_TEX_LANES], sv[CJ_TEX_LANES], ou[CJ_TEX_LANES], ov[CJ_TEX_LANES];
    double cu[CJ_TEX_LANES], cv[CJ_TEX_LANES]; /* checks_u, checks_v */
    int32_t deriv[CJ_TEX_LANES];               /* the sampler's needs_deriv */
    float a[3][CJ_TEX_LANES], b[3][CJ_TEX_LANES];
} cj_checker_lanes;

/* Lane j unused (defined inputs, result ignored). */
CJ_TEX_LANE_INLINE void cj_checker_lanes_clear(cj_checker_lanes *L, int j) {
    L->u[j] = L->v[j] = L->sx[j] = L->sy[j] = 0.0;
    for (int k = 0; k < 9; ++k) L->plane[k][j] = 0.0;
    L->su[j] = L->sv[j] = L->ou[j] = L->ov[j] = L->cu[j] = L->cv[j] = 0.0;
    L->deriv[j] = 0;
    for (int k = 0; k < 3; ++k) L->a[k][j] = L->b[k][j] = 0.0f;
}

/* Every lane takes the parameters of the one sampler smp (a block whose lanes share a
 * material): broadcast stores, a few per lane instead of a gather of 17 values per lane. */
CJ_TEX_LANE_INLINE void cj_checker_lanes_set_params(cj_checker_lanes *L,
                                                    const cj_tex_sampler *smp) {
    const double su = smp->su, sv = smp->sv, ou = smp->ou, ov = smp->ov;
    const double cu = smp->checks_u, cv = smp->checks_v;
    const int32_t deriv = smp->needs_deriv;
    for (int j = 0; j < CJ_TEX_LANES; ++j) {
        L->su[j] = su;
        L->sv[j] = sv;
        L->ou[j] = ou;
        L->ov[j] = ov;
        L->cu[j] = cu;
        L->cv[j] = cv;
        L->deriv[j] = deriv;
    }
    for (int k = 0; k < 3; ++k) {
        const float a = smp->a[k], b = smp->b[k];
        for (int j = 0; j < CJ_TEX_LANES; ++j) {
            L->a[k][j] = a;
            L->b[k][j] = b;
        }
    }
}

/* floor(x/2) + max(0, x − 2 floor(x/2) − 1): the measure of the odd cells in [0, x). */
CJ_TEX_LANE_INLINE double cj_lane_odd_measure(double x) {
    const double h = floor(x / 2.0), r = x - 2.0 * h;
    return h + (r > 1.0 ? r - 1.0 : 0.0);
}

/* The fraction of [x − w/2, x + w/2] in odd cells (texture.c's odd_fraction). */
CJ_TEX_LANE_INLINE double cj_lane_odd_fraction(double x, double w) {
    const double fl = floor(x), parity = fl - 2.0 * floor(fl / 2.0);
    const double box = (cj_lane_odd_measure(x + 0.5 * w) - cj_lane_odd_measure(x - 0.5 * w)) / w;
    return !(w > 1e-9) ? parity : (w > 1e6 ? 0.5 : box);
}

/* The RGB of lanes j < n into out[3][lanes]. */
CJ_TEX_LANE_INLINE void cj_checker_lanes_sample(int n, const cj_checker_lanes *L,
                                                float out[3][CJ_TEX_LANES]) {
    double dudx[CJ_TEX_LANES], dvdx[CJ_TEX_LANES], dudy[CJ_TEX_LANES], dvdy[CJ_TEX_LANES];
    float f[CJ_TEX_LANES];
    for (int j = 0; j < n; ++j) {
        const double U0 = L->plane[0][j], U1 = L->plane[1][j], U2 = L->plane[2][j];
        const double V0 = L->plane[3][j], V1 = L->plane[4][j], V2 = L->plane[5][j];
        const double Q0 = L->plane[6][j], Q1 = L->plane[7][j], Q2 = L->plane[8][j];
        const double s = Q0 * L->sx[j] + Q1 * L->sy[j] + Q2, q = s == 0.0 ? 1.0 : s;
        const double u = (U0 * L->sx[j] + U1 * L->sy[j] + U2) / q;
        const double v = (V0 * L->sx[j] + V1 * L->sy[j] + V2) / q;
        dudx[j] = s == 0.0 ? 0.0 : (U0 - u * Q0) / q;
        dudy[j] = s == 0.0 ? 0.0 : (U1 - u * Q1) / q;
        dvdx[j] = s == 0.0 ? 0.0 : (V0 - v * Q0) / q;
        dvdy[j] = s == 0.0 ? 0.0 : (V1 - v * Q1) / q;
    }
    for (int j = 0; j < n; ++j) {
        const double tu = L->u[j] * L->su[j] + L->ou[j], tv = L->v[j] * L->sv[j] + L->ov[j];
        double cu = tu * L->cu[j], cv = tv * L->cv[j];
        cu -= 2.0 * floor(cu / 2.0);
        cv -= 2.0 * floor(cv / 2.0);
        const double wu = (fabs(dudx[j]) + fabs(dudy[j])) * fabs(L->su[j]) * L->cu[j];
        const double wv = (fabs(dvdx[j]) + fabs(dvdy[j])) * fabs(L->sv[j]) * L->cv[j];
        /* both computed, then chosen: a call under a condition would keep the loop scalar */
        const double bu = cj_lane_odd_fraction(cu, wu), bv = cj_lane_odd_fraction(cv, wv);
        const double fu = L->deriv[j] ? bu : (cu >= 1.0 ? 1.0 : 0.0);
        const double fv = L->deriv[j] ? bv : (cv >= 1.0 ? 1.0 : 0.0);
        f[j] = (float)(fu * (1.0 - fv) + fv * (1.0 - fu));
    }
    for (int k = 0; k < 3; ++k)
        for (int j = 0; j < n; ++j) out[k][j] = L->a[k][j] + f[j] * (L->b[k][j] - L->a[k][j]);
}

#endif

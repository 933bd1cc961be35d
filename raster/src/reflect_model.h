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

/* Always inlined: the rasterizer calls the float instance once per light per sample, and
 * inlined into its kernel the model and light-model branches are decided once per frame. The
 * arithmetic is the same either way (no contraction: -ffp-contract=off). */
#if defined(__GNUC__)
#define CJ_REFLECT_INLINE static inline __attribute__((always_inline))
#else
#define CJ_REFLECT_INLINE static inline
#endif

#define CJ_REFLECT_DEFINE(SUF, T, SQRT, POW)                                                       \
    /* d and s of one light (see above); n, l, v unit vectors; radiometric: the BRDF terms         \
     * times n·l (below). */                                                                      \
    CJ_REFLECT_INLINE void cj_reflect_terms_##SUF(const T n[3], const T l[3], const T v[3],        \
                                                  T alpha, int model, int radiometric, T *d,       \
                                                  T *s) {                                          \
        const T nl = n[0] * l[0] + n[1] * l[1] + n[2] * l[2];                                      \
        if (!(nl > (T)0)) {                                                                        \
            *d = (T)0;                                                                             \
            *s = (T)0;                                                                             \
            return;                                                                                \
        }                                                                                          \
        *d = nl;                                                                                   \
        T c, hl = (T)0;                                                                            \
        if (model == CJ_SPEC_PHONG) {                                                              \
            c = (T)0;                                                                              \
            for (int k = 0; k < 3; ++k) c += ((T)2 * nl * n[k] - l[k]) * v[k];                     \
        } else {                                                                                   \
            T h[3] = {l[0] + v[0], l[1] + v[1], l[2] + v[2]};                                      \
            hl = SQRT(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);                                    \
            /* l = −v: every half vector is as good as none; the lobe is at its rim */           \
            c = hl > (T)0 ? (n[0] * h[0] + n[1] * h[1] + n[2] * h[2]) / hl : (T)0;                 \
        }                                                                                          \
        if (c > (T)0)                                                                              \
            *s = POW(c, alpha);                                                                    \
        else                                                                                       \
            /* legacy: max(0, c)^0 = 1; radiometric: the lobe is the half space c > 0 */           \
            *s = alpha == (T)0 && !radiometric ? (T)1 : (T)0;                                      \
        if (radiometric) {                                                                         \
            const T pi = (T)3.14159265358979323846;                                                \
            *d = nl / pi;                                                                          \
            if (model == CJ_SPEC_PHONG) {                                                          \
                *s *= (alpha + (T)2) / ((T)2 * pi) * nl;                                           \
            } else {                                                                               \
                const T nv = n[0] * v[0] + n[1] * v[1] + n[2] * v[2];                              \
                const T lh = hl / (T)2, mx = nv > nl ? nv : nl;                                    \
                *s = lh > (T)0 ? *s * (alpha + (T)1) / ((T)8 * pi * lh * mx) * nl : (T)0;          \
            }                                                                                      \
        }                                                                                          \
    }

CJ_REFLECT_DEFINE(f, float, sqrtf, powf)
CJ_REFLECT_DEFINE(d, double, sqrt, pow)

#undef CJ_REFLECT_DEFINE

/* RADIOMETRIC LIGHT (cj_light_model CJ_LIGHT_RADIOMETRIC): the material is the BRDF
 *   f_r = r_d c_r / π + r_s c_p f_s,
 * and a light of irradiance E = I cos θ (/ r²) adds f_r E; the terms above then return
 * d = cos θ / π and s = f_s cos θ (cos θ = n·l), so the caller's formula c_r r_d I d + c_p r_s I s
 * is the same in both models. The specular lobes are energy-conserving BRDFs:
 *   CJ_SPEC_PHONG  f_s = (α + 2)/(2π) max(0, m·v)^α: its directional albedo ∫ f_s cos θ dω is
 *                  exactly 1 at normal incidence (∫ cos^(α+1) θ dω = 2π/(α+2)) and less at any
 *                  other (the lobe is cut by the horizon and weighted by a smaller cos);
 *   CJ_SPEC_BLINN  f_s = (α + 1)/(8π) max(0, n·h)^α / ((l·h) max(n·l, n·v)) (the half-vector
 *                  lobe with Ashikhmin and Shirley's denominator): sampling h with density
 *                  (α + 1)/(2π) (n·h)^α and reflecting v about it gives wi with pdf
 *                  (α+1)/(2π) (n·h)^α / (4 v·h), so f_s cos θ / pdf = n·l / max(n·l, n·v) <= 1
 *                  and the albedo is at most 1 for every α and every view.
 * The same lobes are the BRDFs of brdf.h (the path tracer's materials). */
/* The irradiance at point p with unit normal n from a Lambertian polygon of radiance 1 (the
 * integral of cos θ cos θ′ / r² over its area), by Lambert's formula
 *   E = 1/2 |Σ_i Θ_i (γ_i · n)|,  Θ_i the angle edge i subtends at p, γ_i the unit normal of
 *   the plane through p and edge i,
 * after clipping the polygon to the half space in front of the surface (n·(x − p) > 0), the
 * part the point can see. One-sided emitter: 0 when p lies behind it (on the side opposite
 * to the unit normal nl). nv <= CJ_REFLECT_POLY_MAX vertices in order (convex). Multiply by
 * the radiance L_e. */
#define CJ_REFLECT_POLY_MAX 32
static inline double cj_reflect_polygon_irradiance(const double p[3], const double n[3],
                                                   const double (*v)[3], int nv,
                                                   const double nl[3]) {
    double side = 0.0;
    for (int k = 0; k < 3; ++k) side += (p[k] - v[0][k]) * nl[k];
    if (!(side > 0.0)) return 0.0;
    /* clip against the surface's tangent plane (Sutherland-Hodgman: one plane, at most one
     * more vertex than the input) */
    double c[CJ_REFLECT_POLY_MAX + 1][3];
    int nc = 0;
    for (int i = 0; i < nv; ++i) {
        const double *a = v[i], *b = v[(i + 1) % nv];
        double da = 0.0, db = 0.0;
        for (int k = 0; k < 3; ++k) {
            da += (a[k] - p[k]) * n[k];
            db += (b[k] - p[k]) * n[k];
        }
        if (da > 0.0)
            for (int k = 0; k < 3; ++k) c[nc][k] = a[k] - p[k];
        if (da > 0.0) ++nc;
        if ((da > 0.0) != (db > 0.0)) {
            double t = da / (da - db);
            for (int k = 0; k < 3; ++k) c[nc][k] = a[k] + t * (b[k] - a[k]) - p[k];
            ++nc;
        }
    }
    if (nc < 3) return 0.0;
    double sum = 0.0;
    for (int i = 0; i < nc; ++i) {
        const double *a = c[i], *b = c[(i + 1) % nc];
        double la = sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
        double lb = sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2]);
        if (!(la > 0.0) || !(lb > 0.0)) continue;
        double x[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
                       a[0] * b[1] - a[1] * b[0]};
        double lx = sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
        if (!(lx > 0.0)) continue;
        double ab = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
        double theta = atan2(lx, ab); /* accurate for small angles, unlike acos */
        sum += theta * (x[0] * n[0] + x[1] * n[1] + x[2] * n[2]) / lx;
    }
    return 0.5 * fabs(sum);
}

/* A disc of radius R (centre o, unit normal n) as the regular CJ_REFLECT_DISC_SIDES-gon of the
 * same area, for cj_reflect_polygon_irradiance: vertex radius R √(2π / (N sin(2π/N))), between
 * the inscribed polygon (vertex radius R) and the circumscribed one (R / cos(π/N)), so where
 * the whole disc is in front of the receiver its irradiance lies between theirs, as the disc's
 * does. Measured against the closed form on planes parallel to the disc (docs/light.md): within
 * 2e-5 of the on-axis irradiance wherever the receiver is at least R/4 from the disc's plane,
 * 1.7e-3 at R/10 (the polygon's sagitta, R (π/N)²/2, is then no longer small beside the
 * distance). The horizon clip of the polygon formula applies unchanged. */
#define CJ_REFLECT_DISC_SIDES 32
static inline void cj_reflect_disc_polygon(const double o[3], const double n[3], double R,
                                           double (*v)[3]) {
    const double pi = 3.14159265358979323846, N = CJ_REFLECT_DISC_SIDES;
    const double rv = R * sqrt(2.0 * pi / (N * sin(2.0 * pi / N)));
    /* an orthonormal pair (e1, e2) spanning the disc's plane */
    const double pick[3] = {fabs(n[0]) < 0.6 ? 1.0 : 0.0, fabs(n[0]) < 0.6 ? 0.0 : 1.0, 0.0};
    double e1[3] = {pick[1] * n[2] - pick[2] * n[1], pick[2] * n[0] - pick[0] * n[2],
                    pick[0] * n[1] - pick[1] * n[0]};
    const double l1 = sqrt(e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]);
    for (int k = 0; k < 3; ++k) e1[k] /= l1;
    const double e2[3] = {n[1] * e1[2] - n[2] * e1[1], n[2] * e1[0] - n[0] * e1[2],
                          n[0] * e1[1] - n[1] * e1[0]};
    for (int i = 0; i < CJ_REFLECT_DISC_SIDES; ++i) {
        const double a = 2.0 * pi * i / N, ca = rv * cos(a), sa = rv * sin(a);
        for (int k = 0; k < 3; ++k) v[i][k] = o[k] + ca * e1[k] + sa * e2[k];
    }
}

#endif

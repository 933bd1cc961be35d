/* Private to the rasterizer's shading (render_shade.c, render_shade8.c): the lighting of up to
 * CJ_LANES samples at once, structure of arrays, in float.
 *
 * It is the reflection model of reflect_model.h (cj_reflect_terms_f) written without branches
 * per sample, so that with n = CJ_LANES (a compile-time constant once inlined) every loop below
 * vectorises (8 floats per AVX register); with n = 1 it is the scalar path of the flat,
 * Gouraud and transparent shading. Both run the same source, so a sample's colour never
 * depends on the path, lane, tile or thread that shaded it. Only two things differ from the
 * tracer's double instance, both documented errors:
 *   - positions are float, relative to the eye (c->pe, cj_rlight.pe): the view and light
 *     directions carry float rounding (relative ~1e-7 of the distances involved);
 *   - x^α is cj_pow_poly (pow_poly.h: |error| <= 5e-7 for x <= 1), not powf.
 * test_render_lanes checks the terms against cj_reflect_terms_f over random geometry (the same
 * values up to the pow bound) and the lane loop against n = 1 (bit-identical). */
#ifndef CASTELJAU_RENDER_LIGHT8_H
#define CASTELJAU_RENDER_LIGHT8_H

#include "pow_poly.h"
#include "reflect_model.h"
#include "render_pipe.h"

#include <float.h>
#include <math.h>

#define CJ_LANES 8

#if defined(__GNUC__)
#define CJ_LANE_INLINE static inline __attribute__((always_inline))
#else
#define CJ_LANE_INLINE static inline
#endif

/* The inputs and sums of a block of samples (lanes j < n are used). */
typedef struct cj_lanes {
    float nx[CJ_LANES], ny[CJ_LANES], nz[CJ_LANES]; /* unit normal of the side being lit */
    float px[CJ_LANES], py[CJ_LANES], pz[CJ_LANES]; /* position − eye */
    float alpha[CJ_LANES];
    int32_t mirror[CJ_LANES]; /* 1: CJ_SPEC_PHONG lobe, 0: CJ_SPEC_BLINN */
    float sd[3][CJ_LANES];    /* Σ f I d (or, for an area light, its irradiance · I) */
    float ss[3][CJ_LANES];    /* Σ f I s */
} cj_lanes;

/* x^α where x > 0 (cj_pow_poly; subnormal x, outside its domain, by powf). */
CJ_LANE_INLINE float cj_lane_pow_fix(float x, float a, float p) {
    return x > 0.0f && x < FLT_MIN ? powf(x, a) : p;
}

/* 1 if some lane holds a positive subnormal (a vectorised test, so the scalar fix-up of
 * cj_lane_pow_fix runs only for the rare block that needs it). */
CJ_LANE_INLINE int cj_lanes_any_subnormal(int n, const float *x) {
    int any = 0;
    for (int j = 0; j < n; ++j) any |= x[j] > 0.0f && x[j] < FLT_MIN;
    return any;
}

/* d and s (reflect_model.h) of one light direction l per lane, v the view direction. */
CJ_LANE_INLINE void cj_lanes_terms(int n, int radiometric, int any_mirror, int any_half,
                                   const cj_lanes *b, const float *lx, const float *ly,
                                   const float *lz, const float *vx, const float *vy,
                                   const float *vz, float *d, float *s) {
    float nl[CJ_LANES], cm[CJ_LANES], ch[CJ_LANES], hl[CJ_LANES], cc[CJ_LANES], pw[CJ_LANES];
    for (int j = 0; j < n; ++j) nl[j] = b->nx[j] * lx[j] + b->ny[j] * ly[j] + b->nz[j] * lz[j];
    if (any_mirror)
        for (int j = 0; j < n; ++j) {
            float c = 0.0f;
            c += (2.0f * nl[j] * b->nx[j] - lx[j]) * vx[j];
            c += (2.0f * nl[j] * b->ny[j] - ly[j]) * vy[j];
            c += (2.0f * nl[j] * b->nz[j] - lz[j]) * vz[j];
            cm[j] = c;
        }
    for (int j = 0; j < n; ++j) hl[j] = 0.0f;
    if (any_half)
        for (int j = 0; j < n; ++j) {
            const float h0 = lx[j] + vx[j], h1 = ly[j] + vy[j], h2 = lz[j] + vz[j];
            const float len = sqrtf(h0 * h0 + h1 * h1 + h2 * h2);
            const float q =
                (b->nx[j] * h0 + b->ny[j] * h1 + b->nz[j] * h2) / (len > 0.0f ? len : 1.0f);
            hl[j] = len;
            ch[j] = len > 0.0f ? q : 0.0f;
        }
    for (int j = 0; j < n; ++j) {
        cc[j] = any_mirror && (!any_half || b->mirror[j]) ? cm[j] : ch[j];
        pw[j] = cj_pow_poly(cc[j] > FLT_MIN ? cc[j] : FLT_MIN, b->alpha[j]);
    }
    if (cj_lanes_any_subnormal(n, cc))
        for (int j = 0; j < n; ++j) pw[j] = cj_lane_pow_fix(cc[j], b->alpha[j], pw[j]);
    /* two loops, not one with the light model tested inside: the test kept the loop scalar */
    if (!radiometric) {
        for (int j = 0; j < n; ++j) {
            const float zero_lobe = b->alpha[j] == 0.0f ? 1.0f : 0.0f;
            const float sj = cc[j] > 0.0f ? pw[j] : zero_lobe;
            const int lit = nl[j] > 0.0f;
            d[j] = lit ? nl[j] : 0.0f;
            s[j] = lit ? sj : 0.0f;
        }
        return;
    }
    for (int j = 0; j < n; ++j) {
        const float pi = 3.14159265358979323846f;
        const float sj = cc[j] > 0.0f ? pw[j] : 0.0f, dj = nl[j] / pi;
        const float sm = sj * ((b->alpha[j] + 2.0f) / (2.0f * pi) * nl[j]);
        const float nv = b->nx[j] * vx[j] + b->ny[j] * vy[j] + b->nz[j] * vz[j];
        const float lh = hl[j] / 2.0f, mx = nv > nl[j] ? nv : nl[j];
        const float den = 8.0f * pi * lh * mx;
        const float sh = sj * (b->alpha[j] + 1.0f) / (den > 0.0f ? den : 1.0f) * nl[j];
        const float sr = any_mirror && (!any_half || b->mirror[j]) ? sm : (lh > 0.0f ? sh : 0.0f);
        const int lit = nl[j] > 0.0f;
        d[j] = lit ? dj : 0.0f;
        s[j] = lit ? sr : 0.0f;
    }
}

/* v = −p/|p| (perspective) or −gaze (orthographic) per lane. */
CJ_LANE_INLINE void cj_lanes_view(const cj_rctx *c, int n, const cj_lanes *b, float *vx, float *vy,
                                  float *vz) {
    if (c->view->cam.projection == CJ_PROJ_PERSPECTIVE) {
        for (int j = 0; j < n; ++j) {
            const float x = -b->px[j], y = -b->py[j], z = -b->pz[j];
            const float len = sqrtf(x * x + y * y + z * z);
            const float r = 1.0f / (len > 0.0f ? len : 1.0f);
            vx[j] = len > 0.0f ? x * r : x;
            vy[j] = len > 0.0f ? y * r : y;
            vz[j] = len > 0.0f ? z * r : z;
        }
    } else {
        for (int j = 0; j < n; ++j) {
            vx[j] = (float)-c->view->gaze_unit.x;
            vy[j] = (float)-c->view->gaze_unit.y;
            vz[j] = (float)-c->view->gaze_unit.z;
        }
    }
}

/* Normalises (nx, ny, nz) per lane where its length is > 0 (else leaves it). */
CJ_LANE_INLINE void cj_lanes_normalize(int n, float *x, float *y, float *z) {
    for (int j = 0; j < n; ++j) {
        const float len = sqrtf(x[j] * x[j] + y[j] * y[j] + z[j] * z[j]);
        /* r = 1 where len is not > 0, and x·1 = x: a plain multiply, not a select, so the
         * stores are unconditional (GCC made the select a masked store, which AMD cores run
         * slowly and which stalls the loads that follow it) */
        const float r = 1.0f / (len > 0.0f ? len : 1.0f);
        x[j] *= r;
        y[j] *= r;
        z[j] *= r;
    }
}

/* A radiometric sphere light L (render_pipe.h) on lanes whose horizon cuts its cone (|cos θ| <
 * sin θ_max, θ the angle of its centre above the horizon, sin θ_max = R/dist): the point
 * path's cos θ / π is replaced by the exact clipped irradiance, by the polygon path, of the
 * disc that fills the same cone (the sphere's tangent circle: centre at (dist² − R²)/dist from
 * p towards the centre, radius R √(dist² − R²)/dist, facing p), over the point's f = 1/dist² and
 * I = π R² L_e. l: unit directions to the centre; f: 1/dist²; d: the point path's terms. A point
 * inside the sphere is left to the point path. */
CJ_LANE_INLINE void cj_lanes_sphere_horizon(const cj_rctx *c, int n, const cj_lanes *b,
                                            const cj_rlight *L, const float *lx, const float *ly,
                                            const float *lz, const float *f, float *d) {
    int any = 0;
    const float r2 = (float)(L->radius * L->radius);
    for (int j = 0; j < n; ++j) {
        const float ct = b->nx[j] * lx[j] + b->ny[j] * ly[j] + b->nz[j] * lz[j];
        any |= ct * ct < r2 * f[j];
    }
    if (!any) return;
    for (int j = 0; j < n; ++j) {
        const double p[3] = {c->view->eye.x + (double)b->px[j], c->view->eye.y + (double)b->py[j],
                             c->view->eye.z + (double)b->pz[j]};
        const double nd[3] = {b->nx[j], b->ny[j], b->nz[j]};
        const double u[3] = {L->pos[0] - p[0], L->pos[1] - p[1], L->pos[2] - p[2]};
        const double dist2 = u[0] * u[0] + u[1] * u[1] + u[2] * u[2], R2 = L->radius * L->radius;
        if (!(dist2 > R2)) continue;
        const double dist = sqrt(dist2), ct = (u[0] * nd[0] + u[1] * nd[1] + u[2] * nd[2]) / dist;
        if (!(ct * ct * dist2 < R2)) continue;
        const double t = 1.0 - R2 / dist2,
                     o[3] = {p[0] + t * u[0], p[1] + t * u[1], p[2] + t * u[2]};
        const double facing[3] = {-u[0] / dist, -u[1] / dist, -u[2] / dist};
        double poly[CJ_REFLECT_DISC_SIDES][3];
        cj_reflect_disc_polygon(o, facing, L->radius * sqrt(t), poly);
        const double e = cj_reflect_polygon_irradiance(p, nd, (const double(*)[3])poly,
                                                       CJ_REFLECT_DISC_SIDES, facing);
        /* f I d = L_e E / π with I = π R² L_e, f = 1/dist² */
        d[j] = (float)(e * dist2 / (3.14159265358979323846 * 3.14159265358979323846 * R2));
    }
}

/* The lights of the frame on lanes j < n: fills b->sd and b->ss. any_mirror / any_half: some
 * lane uses the mirror (Phong) / the half-vector (Blinn) lobe. */
CJ_LANE_INLINE void cj_lanes_light(const cj_rctx *c, int n, int any_mirror, int any_half,
                                   cj_lanes *b) {
    float vx[CJ_LANES], vy[CJ_LANES], vz[CJ_LANES], lx[CJ_LANES], ly[CJ_LANES], lz[CJ_LANES];
    float f[CJ_LANES], d[CJ_LANES], s[CJ_LANES];
    cj_lanes_view(c, n, b, vx, vy, vz);
    for (int k = 0; k < 3; ++k)
        for (int j = 0; j < n; ++j) b->sd[k][j] = b->ss[k][j] = 0.0f;
    for (int i = 0; i < c->nlights; ++i) {
        const cj_rlight *L = &c->lights[i];
        if (L->area) {
            /* diffuse: the polygon's exact irradiance (double); specular: its centre */
            for (int j = 0; j < n; ++j) {
                const double p[3] = {c->view->eye.x + (double)b->px[j],
                                     c->view->eye.y + (double)b->py[j],
                                     c->view->eye.z + (double)b->pz[j]};
                const double nd[3] = {b->nx[j], b->ny[j], b->nz[j]};
                const float e =
                    (float)(cj_reflect_polygon_irradiance(p, nd, L->corner, L->ncorner, L->normal) /
                            3.14159265358979323846);
                double to[3] = {L->pos[0] - p[0], L->pos[1] - p[1], L->pos[2] - p[2]};
                double r2 = to[0] * to[0] + to[1] * to[1] + to[2] * to[2];
                double ct = -(to[0] * L->normal[0] + to[1] * L->normal[1] + to[2] * L->normal[2]);
                f[j] = ct > 0.0 && r2 > 0.0 ? (float)(L->size * ct / (sqrt(r2) * r2)) : 0.0f;
                lx[j] = (float)to[0];
                ly[j] = (float)to[1];
                lz[j] = (float)to[2];
                for (int k = 0; k < 3; ++k) b->sd[k][j] += e * L->I[k];
            }
            cj_lanes_normalize(n, lx, ly, lz);
            cj_lanes_terms(n, c->radiometric, any_mirror, any_half, b, lx, ly, lz, vx, vy, vz, d,
                           s);
            for (int k = 0; k < 3; ++k)
                for (int j = 0; j < n; ++j) b->ss[k][j] += f[j] * L->I[k] * s[j];
            continue;
        }
        if (L->directional) {
            for (int j = 0; j < n; ++j) {
                lx[j] = L->l[0];
                ly[j] = L->l[1];
                lz[j] = L->l[2];
                f[j] = 1.0f;
            }
        } else {
            for (int j = 0; j < n; ++j) {
                lx[j] = L->pe[0] - b->px[j];
                ly[j] = L->pe[1] - b->py[j];
                lz[j] = L->pe[2] - b->pz[j];
                f[j] = 1.0f;
            }
            if (L->falloff)
                for (int j = 0; j < n; ++j)
                    f[j] = 1.0f / (lx[j] * lx[j] + ly[j] * ly[j] + lz[j] * lz[j]);
            cj_lanes_normalize(n, lx, ly, lz);
            if (L->spot) {
                float ct[CJ_LANES], pw[CJ_LANES];
                for (int j = 0; j < n; ++j) {
                    ct[j] = -(L->axis[0] * lx[j] + L->axis[1] * ly[j] + L->axis[2] * lz[j]);
                    pw[j] = cj_pow_poly(ct[j] > FLT_MIN ? ct[j] : FLT_MIN, L->spot_exp);
                }
                if (cj_lanes_any_subnormal(n, ct))
                    for (int j = 0; j < n; ++j) pw[j] = cj_lane_pow_fix(ct[j], L->spot_exp, pw[j]);
                for (int j = 0; j < n; ++j) f[j] = ct[j] >= L->cos_cut ? f[j] * pw[j] : 0.0f;
            }
        }
        cj_lanes_terms(n, c->radiometric, any_mirror, any_half, b, lx, ly, lz, vx, vy, vz, d, s);
        if (L->sphere) cj_lanes_sphere_horizon(c, n, b, L, lx, ly, lz, f, d);
        for (int k = 0; k < 3; ++k)
            for (int j = 0; j < n; ++j) {
                b->sd[k][j] += f[j] * L->I[k] * d[j];
                b->ss[k][j] += f[j] * L->I[k] * s[j];
            }
    }
}

#endif

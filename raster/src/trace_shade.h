/* Private to the ray tracer: per-thread shading state and the recursive trace. */
#ifndef CASTELJAU_TRACE_SHADE_H
#define CASTELJAU_TRACE_SHADE_H

#include "trace_internal.h"

#define TR_MAX_MEDIA  16
#define TR_MAX_LIGHTS 64

typedef struct tr_rng {
    uint64_t key;
    uint64_t n;
} tr_rng;

uint64_t cj_trace_mix(uint64_t z);
double tr_rand(tr_rng *r);
/* A pseudo-random permutation of [0, n) chosen by key: i -> its image, for i < n, n >= 1. */
uint32_t cj_trace_permute(uint32_t i, uint32_t n, uint64_t key);

typedef struct tr_lights {
    int unlit;       /* the scene has no light at all: colour shown flat, as the rasterizer does */
    cj_rgb ia;       /* Σ ambient colour × intensity */
    int radiometric; /* cj_light_model CJ_LIGHT_RADIOMETRIC: 1/r², area lights of radiance,
                        BRDFs (reflect_model.h) */
    int count;
    const cj_light *light[TR_MAX_LIGHTS];
} tr_lights;

/* The stack of indices of refraction of the media the ray is inside (ior[0] = 1, air). */
typedef struct tr_medium {
    double ior[TR_MAX_MEDIA];
    int top;
} tr_medium;

typedef struct tr_shade {
    const tr_scene *s;
    const tr_lights *lights;
    tr_counts *c;
    cj_rgb background;
    int max_depth, spp, strata, random;
    int integrator;        /* cj_trace_integrator */
    int emit_nee;          /* path tracer: emissive triangles sampled as lights */
    int indirect;          /* diffuse interreflection rays per diffuse hit (0: off) */
    int in_indirect;       /* 1 while tracing an indirect ray: one bounce only */
    uint32_t sample, perm; /* the pixel sample; a random offset of the light strata */
    uint64_t perm_key;     /* chooses the pixel's permutation of the light strata */
    tr_rng rng;
    double time; /* the camera sample's shutter time in [0, 1) (motion blur), else 0.5 */
} tr_shade;

/* trace_lights.c: the extended emitters (area, disc, sphere lights; scene.h) read
 * radiometrically. tr_is_emitter: the light is one of them. tr_emitter_point: the point (u1,
 * u2) in [0, 1)² of a parallelogram or disc, uniform by area (a sphere: its centre).
 * tr_emitter_sample: a point *target of the emitter seen from p and *weight, the factor that
 * turns its radiance L_e into the irradiance estimate along the direction to it
 * (E ≈ L_e · weight · cos θ at p): parallelogram and disc sampled by area, weight
 * A cos θ′ / r²; a sphere by the solid angle of its cone, weight 2π (1 − cos θ_max); *pdf is
 * the sample's solid-angle density (1 / weight). centre: the deterministic one-sample estimate
 * (caller passes u = 0.5 for a parallelogram or disc: the centre; a sphere: its axis with weight
 * π sin² θ_max, *pdf 0). 0: the emitter sends nothing to p (its back, or p inside a sphere).
 * tr_emitter_hit: the ray meets the emitter's emitting side at *t in (tmin, t_max); *pdf the
 * solid-angle density with which tr_emitter_sample from the ray's origin draws that direction. */
int tr_is_emitter(const cj_light *lt);
cj_vec3 tr_emitter_point(const cj_light *lt, double u1, double u2);
int tr_emitter_sample(const cj_light *lt, cj_vec3 p, double u1, double u2, int centre,
                      cj_vec3 *target, double *weight, double *pdf);
int tr_emitter_hit(const cj_light *lt, const cj_ray *ray, double t_max, double *t_out, double *pdf);

/* trace_emit.c: a point *target of the scene's emissive triangles (picked by area with u0, uniform
 * on the triangle with u1, u2) seen from p, its emission, *pdf the solid-angle density
 * r² / (A_total |cos θ′|) and *weight = 1 / *pdf; 0 when there are none or the sample is
 * edge-on. The density of a direction that meets an emissive triangle at distance r with cosine
 * cos θ′ is the same r² / (A_total |cos θ′|). */
int tr_emit_sample(const tr_scene *s, cj_vec3 p, double u0, double u1, double u2, cj_vec3 *target,
                   cj_rgb *emission, double *weight, double *pdf);

int tr_cast(tr_shade *sh, int kind, const cj_ray *ray, cj_hit *hit);
/* A shadow ray: 1 when anything is hit in [tmin, tmax] (counted as a shadow ray). */
int tr_occluded(tr_shade *sh, const cj_ray *ray);
/* trace_path.c: the path tracer's radiance along a camera ray (CJ_INTEGRATOR_PATH). */
cj_rgb tr_path(tr_shade *sh, const cj_ray *camera_ray, int *hit_any);
cj_rgb tr_trace(tr_shade *sh, const cj_ray *ray, int kind, int depth, tr_medium med, int *hit_any);

#endif

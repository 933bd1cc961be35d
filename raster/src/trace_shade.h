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
    int indirect;          /* diffuse interreflection rays per diffuse hit (0: off) */
    int in_indirect;       /* 1 while tracing an indirect ray: one bounce only */
    uint32_t sample, perm; /* the pixel sample; a random offset of the light strata */
    uint64_t perm_key;     /* chooses the pixel's permutation of the light strata */
    tr_rng rng;
} tr_shade;

int tr_cast(tr_shade *sh, int kind, const cj_ray *ray, cj_hit *hit);
/* A shadow ray: 1 when anything is hit in [tmin, tmax] (counted as a shadow ray). */
int tr_occluded(tr_shade *sh, const cj_ray *ray);
/* trace_path.c: the path tracer's radiance along a camera ray (CJ_INTEGRATOR_PATH). */
cj_rgb tr_path(tr_shade *sh, const cj_ray *camera_ray, int *hit_any);
cj_rgb tr_trace(tr_shade *sh, const cj_ray *ray, int kind, int depth, tr_medium med, int *hit_any);

#endif

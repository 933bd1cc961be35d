/* Private: the particle system's layout, shared by its files. */
#ifndef CASTELJAU_PARTICLE_INTERNAL_H
#define CASTELJAU_PARTICLE_INTERNAL_H

#include "casteljau/particles.h"

struct cj_particles {
    cj_allocator alloc;
    int has_alloc;
    cj_particles_desc d; /* pointers below point into this object's own copies */
    cj_emitter *emitters;
    cj_sphere_collider *spheres;
    cj_plane_collider *planes;
    size_t count;
    double *x, *v, *acc; /* capacity × 3 */
    double *age, *life;  /* capacity */
    double *emit_acc;    /* per emitter: accumulated fractional particles */
    uint64_t rng[4];
    double t;
    uint64_t steps;
};

/* particle_patches.c: moves a particle that crossed the collider on its step a -> x back to the
 * surface and reflects v; returns 1 on a hit. */
int cj_patch_collider_resolve_(const cj_patch_collider *c, const double a[3], double x[3],
                               double v[3], double restitution);

/* particle_patches.c: a particle of a solid collider's inside (cj_patch_collider_inside) moved
 * out through the nearest surface point (certified, cj_patch_nearest) by the collider's offset,
 * its velocity into the surface removed (the tangential part scaled by 1 - friction); returns 1
 * when it was moved. */
int cj_patch_collider_push_out_(const cj_patch_collider *c, double x[3], double v[3]);

#endif

/* Private: the spring system's layout, shared by its files. */
#ifndef CASTELJAU_SPRING_INTERNAL_H
#define CASTELJAU_SPRING_INTERNAL_H

#include "casteljau/springs.h"

struct cj_springs {
    cj_allocator alloc;
    int has_alloc;
    int dim;
    size_t count, nsprings, nspheres, nplanes;
    double *x, *v;    /* count × dim */
    double *mass;     /* 0 for fixed particles */
    double *inv_mass; /* 0 for fixed particles */
    unsigned char *fixed;
    cj_spring *springs;
    cj_sphere_collider *spheres;
    cj_plane_collider *planes;
    double gravity[3];
    double drag;
    double t;
    double *ode_work; /* RK4 work space */
    double *cg;       /* 7 × count × dim: dv, r, p, q, z, diag, rhs */
    double *cache;    /* 6 per spring: n (3), alpha, beta, gamma */
    double *xold;     /* count × dim: positions before the step (patch colliders) */
    size_t npatch;
    const cj_patch_collider **patch_colliders;
};

/* Forces at (x, v) into f (count × dim). */
void cj_springs_forces_at(const cj_springs *s, const double *x, const double *v, double *f);
/* The linearised backward Euler step (x, v updated). CJ_ERR_CAP if CG hit its cap. */
cj_status cj_springs_implicit_step(cj_springs *s, double h, cj_springs_stats *stats);
/* Pushes particles out of the colliders; returns how many were moved. */
size_t cj_springs_collide(cj_springs *s);

#endif

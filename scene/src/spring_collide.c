/* The spring system's colliders (spheres, planes, patches): particles pushed out, velocities
 * resolved. Called by the step (spring_system.c); calls nothing of the system back. */
#include "casteljau/springs.h"

#include "error_internal.h"
#include "particle_internal.h"
#include "spring_internal.h"

#include <assert.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Moves x to the surface point along the unit normal nrm, removes the inward normal velocity,
 * scales the tangential one. */
static void resolve(double *x, double *v, size_t dim, const double *nrm, double depth,
                    double friction) {
    double vn = 0.0;
    for (size_t k = 0; k < dim; ++k) {
        x[k] += depth * nrm[k];
        vn += v[k] * nrm[k];
    }
    for (size_t k = 0; k < dim; ++k) {
        const double vnk = vn * nrm[k];
        double vt = v[k] - vnk;
        vt *= 1.0 - friction;
        v[k] = (vn < 0.0 ? 0.0 : vnk) + vt;
    }
}

size_t cj_springs_collide(cj_springs *s) {
    const size_t dim = (size_t)s->dim;
    size_t hits = 0;
    if (s->npatch && dim == 3)
        for (size_t i = 0; i < s->count; ++i)
            if (!s->fixed[i])
                for (size_t j = 0; j < s->npatch; ++j) {
                    hits += (size_t)cj_patch_collider_resolve_(
                        s->patch_colliders[j], s->xold + 3 * i, s->x + 3 * i, s->v + 3 * i, 0.0);
                    /* a solid's inside: entered through a gap or a seam the segment missed */
                    hits += (size_t)cj_patch_collider_push_out_(s->patch_colliders[j], s->x + 3 * i,
                                                                s->v + 3 * i);
                }
    if (s->nspheres == 0 && s->nplanes == 0) return hits;
    for (size_t i = 0; i < s->count; ++i) {
        if (s->fixed[i]) continue;
        double *x = s->x + i * dim, *v = s->v + i * dim;
        int hit = 0;
        for (size_t j = 0; j < s->nspheres; ++j) {
            const cj_sphere_collider *c = &s->spheres[j];
            double d[3] = {0, 0, 0}, l2 = 0.0;
            for (size_t k = 0; k < dim; ++k) {
                d[k] = x[k] - c->center[k];
                l2 += d[k] * d[k];
            }
            const double l = sqrt(l2);
            if (l >= c->radius) continue;
            double nrm[3] = {0, 0, 0};
            if (l > 0.0)
                for (size_t k = 0; k < dim; ++k) nrm[k] = d[k] / l;
            else
                nrm[dim - 1] = 1.0; /* at the centre: push out along the last axis */
            /* land exactly on the sphere: recompute the point rather than add a depth */
            for (size_t k = 0; k < dim; ++k) x[k] = c->center[k] + c->radius * nrm[k];
            resolve(x, v, dim, nrm, 0.0, c->friction);
            hit = 1;
        }
        for (size_t j = 0; j < s->nplanes; ++j) {
            const cj_plane_collider *c = &s->planes[j];
            double nl = 0.0, nrm[3] = {0, 0, 0}, side = 0.0;
            for (size_t k = 0; k < dim; ++k) nl += c->normal[k] * c->normal[k];
            nl = sqrt(nl);
            if (!(nl > 0.0)) continue;
            for (size_t k = 0; k < dim; ++k) {
                nrm[k] = c->normal[k] / nl;
                side += nrm[k] * x[k];
            }
            if (side >= c->offset) continue;
            resolve(x, v, dim, nrm, c->offset - side, c->friction);
            hit = 1;
        }
        hits += (size_t)hit;
    }
    return hits;
}

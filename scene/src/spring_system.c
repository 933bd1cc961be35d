/* Spring-mass systems: forces, the explicit integrators through cj_ode2, the linearised
 * backward Euler by matrix-free preconditioned conjugate gradients, colliders. */
#include "casteljau/springs.h"

#include "error_internal.h"
#include "spring_internal.h"
#include "clock_internal.h"

#include <assert.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static cj_status check_desc(const cj_springs_desc *d) {
    if (d->dim < 1 || d->dim > 3)
        return cj_fail(CJ_ERR_DIMENSION, "spring system dimension %d outside 1..3", d->dim);
    if (d->count == 0) return cj_fail(CJ_ERR_EMPTY, "spring system has no particles");
    const size_t dim = (size_t)d->dim;
    for (size_t i = 0; i < d->count; ++i) {
        for (size_t k = 0; k < dim; ++k)
            if (!isfinite(d->x[i * dim + k]) || (d->v && !isfinite(d->v[i * dim + k])))
                return cj_fail(CJ_ERR_NONFINITE, "particle %zu: position or velocity not finite",
                               i);
        const int fixed = d->fixed && d->fixed[i];
        if (!fixed && !(d->mass[i] > 0.0 && isfinite(d->mass[i])))
            return cj_fail(CJ_ERR_RANGE, "particle %zu: mass %g must be finite and > 0", i,
                           d->mass[i]);
    }
    for (size_t j = 0; j < d->spring_count; ++j) {
        const cj_spring *s = &d->springs[j];
        if (s->a < 0 || s->b < 0 || (size_t)s->a >= d->count || (size_t)s->b >= d->count ||
            s->a == s->b)
            return cj_fail(CJ_ERR_ARGUMENT, "spring %zu joins particles %d and %d (of %zu)", j,
                           s->a, s->b, d->count);
        if (!isfinite(s->rest) || !isfinite(s->stiffness) || !isfinite(s->damping))
            return cj_fail(CJ_ERR_NONFINITE, "spring %zu: rest, stiffness or damping not finite",
                           j);
        if (s->rest < 0.0 || s->stiffness < 0.0 || s->damping < 0.0)
            return cj_fail(CJ_ERR_RANGE, "spring %zu: rest, stiffness and damping must be >= 0", j);
    }
    for (size_t k = 0; k < 3; ++k)
        if (!isfinite(d->gravity[k])) return cj_fail(CJ_ERR_NONFINITE, "gravity not finite");
    if (!(d->drag >= 0.0 && isfinite(d->drag)))
        return cj_fail(CJ_ERR_RANGE, "drag %g must be finite and >= 0", d->drag);
    for (size_t j = 0; j < d->patch_collider_count; ++j)
        if (!d->patch_colliders || !d->patch_colliders[j])
            return cj_fail(CJ_ERR_ARGUMENT, "patch collider %zu is NULL", j);
    if (d->patch_collider_count && d->dim != 3)
        return cj_fail(CJ_ERR_DIMENSION, "patch colliders need a 3D spring system (dim %d)",
                       d->dim);
    for (size_t j = 0; j < d->sphere_count; ++j) {
        const cj_sphere_collider *c = &d->spheres[j];
        if (!isfinite(c->center[0]) || !isfinite(c->center[1]) || !isfinite(c->center[2]) ||
            !isfinite(c->radius) || !isfinite(c->friction))
            return cj_fail(CJ_ERR_NONFINITE, "sphere collider %zu not finite", j);
        if (!(c->radius > 0.0) || c->friction < 0.0 || c->friction > 1.0)
            return cj_fail(CJ_ERR_RANGE, "sphere collider %zu: radius > 0, friction in [0,1]", j);
    }
    for (size_t j = 0; j < d->plane_count; ++j) {
        const cj_plane_collider *c = &d->planes[j];
        const double n2 =
            c->normal[0] * c->normal[0] + c->normal[1] * c->normal[1] + c->normal[2] * c->normal[2];
        if (!isfinite(n2) || !isfinite(c->offset) || !isfinite(c->friction))
            return cj_fail(CJ_ERR_NONFINITE, "plane collider %zu not finite", j);
        if (!(n2 > 0.0) || c->friction < 0.0 || c->friction > 1.0)
            return cj_fail(CJ_ERR_RANGE,
                           "plane collider %zu: zero normal or friction outside "
                           "[0,1]",
                           j);
    }
    return CJ_OK;
}

static void *sp_alloc(const cj_springs *s, size_t bytes) {
    return s->has_alloc ? s->alloc.alloc(s->alloc.user, bytes) : malloc(bytes);
}

cj_status cj_springs_create(const cj_springs_desc *d, const cj_allocator *alloc, cj_springs **out) {
    assert(d && out && d->x && d->mass && (d->springs || d->spring_count == 0));
    cj_status st = check_desc(d);
    if (st != CJ_OK) return st;
    cj_springs tmp;
    memset(&tmp, 0, sizeof tmp);
    if (alloc) {
        tmp.alloc = *alloc;
        tmp.has_alloc = 1;
    }
    const size_t n = d->count * (size_t)d->dim;
    /* one block: the struct, then the arrays (doubles first for alignment) */
    const size_t ndoubles = 2 * n + d->count /* inv mass */ + d->count /* mass */ +
                            cj_ode2_work_size(n, CJ_INTEGRATE_RK4) + 7 * n + d->spring_count * 6 +
                            n;
    const size_t bytes =
        sizeof(cj_springs) + sizeof(double) * ndoubles + sizeof(cj_spring) * d->spring_count +
        sizeof(cj_sphere_collider) * d->sphere_count + sizeof(cj_plane_collider) * d->plane_count +
        sizeof(cj_patch_collider *) * d->patch_collider_count + d->count;
    cj_springs *s = sp_alloc(&tmp, bytes);
    if (!s) return cj_fail(CJ_ERR_NOMEM, "spring system: no memory for %zu particles", d->count);
    *s = tmp;
    s->dim = d->dim;
    s->count = d->count;
    s->nsprings = d->spring_count;
    s->nspheres = d->sphere_count;
    s->nplanes = d->plane_count;
    s->drag = d->drag;
    for (int k = 0; k < 3; ++k) s->gravity[k] = k < d->dim ? d->gravity[k] : 0.0;
    double *p = (double *)(s + 1);
    s->x = p;
    p += n;
    s->v = p;
    p += n;
    s->mass = p;
    p += d->count;
    s->inv_mass = p;
    p += d->count;
    s->ode_work = p;
    p += cj_ode2_work_size(n, CJ_INTEGRATE_RK4);
    s->cg = p;
    p += 7 * n;
    s->cache = p;
    p += d->spring_count * 6;
    s->xold = p;
    p += n;
    s->springs = (cj_spring *)p;
    s->spheres = (cj_sphere_collider *)(s->springs + d->spring_count);
    s->planes = (cj_plane_collider *)(s->spheres + d->sphere_count);
    s->patch_colliders = (const cj_patch_collider **)(s->planes + d->plane_count);
    s->npatch = d->patch_collider_count;
    for (size_t i = 0; i < d->patch_collider_count; ++i)
        s->patch_colliders[i] = d->patch_colliders[i];
    s->fixed = (unsigned char *)(s->patch_colliders + d->patch_collider_count);
    memcpy(s->x, d->x, sizeof(double) * n);
    if (d->v)
        memcpy(s->v, d->v, sizeof(double) * n);
    else
        memset(s->v, 0, sizeof(double) * n);
    for (size_t i = 0; i < d->count; ++i) {
        s->fixed[i] = d->fixed ? (d->fixed[i] != 0) : 0;
        s->mass[i] = s->fixed[i] ? 0.0 : d->mass[i];
        s->inv_mass[i] = s->fixed[i] ? 0.0 : 1.0 / d->mass[i];
        if (s->fixed[i])
            for (int k = 0; k < d->dim; ++k) s->v[i * (size_t)d->dim + (size_t)k] = 0.0;
    }
    if (d->spring_count) memcpy(s->springs, d->springs, sizeof(cj_spring) * d->spring_count);
    if (d->sphere_count)
        memcpy(s->spheres, d->spheres, sizeof(cj_sphere_collider) * d->sphere_count);
    if (d->plane_count) memcpy(s->planes, d->planes, sizeof(cj_plane_collider) * d->plane_count);
    s->t = 0.0;
    *out = s;
    return CJ_OK;
}

void cj_springs_destroy(cj_springs *s) {
    if (!s) return;
    if (s->has_alloc)
        s->alloc.free(s->alloc.user, s);
    else
        free(s);
}

int cj_springs_dim(const cj_springs *s) {
    return s->dim;
}
size_t cj_springs_count(const cj_springs *s) {
    return s->count;
}
size_t cj_springs_spring_count(const cj_springs *s) {
    return s->nsprings;
}
const double *cj_springs_positions(const cj_springs *s) {
    return s->x;
}
const double *cj_springs_velocities(const cj_springs *s) {
    return s->v;
}
double cj_springs_time(const cj_springs *s) {
    return s->t;
}

cj_status cj_springs_set_state(cj_springs *s, const double *x, const double *v) {
    const size_t n = s->count * (size_t)s->dim;
    for (size_t i = 0; i < n; ++i)
        if (!isfinite(x[i]) || (v && !isfinite(v[i])))
            return cj_fail(CJ_ERR_NONFINITE, "particle %zu: state not finite", i / (size_t)s->dim);
    memcpy(s->x, x, sizeof(double) * n);
    for (size_t i = 0; i < n; ++i) s->v[i] = (v && !s->fixed[i / (size_t)s->dim]) ? v[i] : 0.0;
    return CJ_OK;
}

static void accel_cb(void *user, double t, const double *x, const double *v, double *a) {
    (void)t;
    const cj_springs *s = user;
    const size_t dim = (size_t)s->dim;
    cj_springs_forces_at(s, x, v, a);
    for (size_t i = 0; i < s->count; ++i)
        for (size_t k = 0; k < dim; ++k) a[i * dim + k] *= s->inv_mass[i];
}

void cj_springs_accel(const cj_springs *s, double *a) {
    accel_cb((void *)s, s->t, s->x, s->v, a);
}

void cj_springs_energy(const cj_springs *s, double *kinetic, double *potential) {
    const size_t dim = (size_t)s->dim;
    double ke = 0.0, pe = 0.0;
    for (size_t i = 0; i < s->count; ++i)
        for (size_t k = 0; k < dim; ++k) {
            ke += 0.5 * s->mass[i] * s->v[i * dim + k] * s->v[i * dim + k];
            pe -= s->mass[i] * s->gravity[k] * s->x[i * dim + k];
        }
    for (size_t j = 0; j < s->nsprings; ++j) {
        const cj_spring *sp = &s->springs[j];
        double l2 = 0.0;
        for (size_t k = 0; k < dim; ++k) {
            const double d = s->x[(size_t)sp->a * dim + k] - s->x[(size_t)sp->b * dim + k];
            l2 += d * d;
        }
        const double e = sqrt(l2) - sp->rest;
        pe += 0.5 * sp->stiffness * e * e;
    }
    if (kinetic) *kinetic = ke;
    if (potential) *potential = pe;
}

cj_status cj_springs_step(cj_springs *s, cj_integrator m, double h, cj_springs_stats *stats) {
    assert(s);
    if (!(h > 0.0) || !isfinite(h)) return cj_fail(CJ_ERR_RANGE, "time step %g must be > 0", h);
    cj_springs_stats local;
    memset(&local, 0, sizeof local);
    cj_status st = CJ_OK;
    const double t0 = cj_clock_seconds();
    if (s->npatch) memcpy(s->xold, s->x, sizeof(double) * s->count * (size_t)s->dim);
    if (m == CJ_INTEGRATE_IMPLICIT_EULER) {
        st = cj_springs_implicit_step(s, h, &local);
    } else {
        cj_ode2 sys;
        sys.n = s->count * (size_t)s->dim;
        sys.user = s;
        sys.accel = accel_cb;
        sys.jacobian = NULL;
        st = cj_ode2_step(&sys, m, s->t, h, s->x, s->v, s->ode_work, NULL, NULL);
        local.seconds_forces = cj_clock_seconds() - t0;
    }
    if (st != CJ_OK && st != CJ_ERR_CAP) {
        if (stats) *stats = local;
        if (st == CJ_ERR_NONFINITE) {
            for (size_t i = 0; i < s->count * (size_t)s->dim; ++i)
                if (!isfinite(s->x[i]) || !isfinite(s->v[i]))
                    return cj_fail(CJ_ERR_NONFINITE,
                                   "particle %zu blew up (unstable step h = %g with %s)",
                                   i / (size_t)s->dim, h, cj_integrator_name(m));
        }
        return st;
    }
    s->t += h;
    const double t1 = cj_clock_seconds();
    local.collisions = cj_springs_collide(s);
    local.seconds_collide = cj_clock_seconds() - t1;
    if (stats) *stats = local;
    if (st == CJ_ERR_CAP)
        return cj_fail(CJ_ERR_CAP,
                       "conjugate gradients stopped after %d iterations at relative "
                       "residual %.3g",
                       local.cg_iterations, local.cg_residual);
    return CJ_OK;
}

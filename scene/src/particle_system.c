/* Particle systems: seeded emission, forces, flocking, symplectic Euler, colliders, ageing. */
#include "casteljau/particles.h"

#include "error_internal.h"
#include "particle_internal.h"
#include "clock_internal.h"

#include <assert.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define CJ_PI 3.14159265358979323846

/* xoshiro256** seeded by splitmix64 (Blackman and Vigna). */
static uint64_t rotl(uint64_t x, int k) {
    return (x << k) | (x >> (64 - k));
}
static uint64_t rng_next(uint64_t *s) {
    const uint64_t r = rotl(s[1] * 5, 7) * 9, t = s[1] << 17;
    s[2] ^= s[0];
    s[3] ^= s[1];
    s[1] ^= s[2];
    s[0] ^= s[3];
    s[2] ^= t;
    s[3] = rotl(s[3], 45);
    return r;
}
static double rng_unit(uint64_t *s) {
    return (double)(rng_next(s) >> 11) * 0x1p-53;
}
static double rng_sym(uint64_t *s) {
    return 2.0 * rng_unit(s) - 1.0;
}

cj_emitter cj_emitter_defaults(void) {
    cj_emitter e;
    memset(&e, 0, sizeof e);
    e.direction[2] = 1.0;
    e.spread = 0.3;
    e.speed = 1.0;
    e.rate = 10.0;
    e.lifetime = 2.0;
    return e;
}

static int fin3(const double *v) {
    return isfinite(v[0]) && isfinite(v[1]) && isfinite(v[2]);
}
static double norm3(const double *v) {
    return sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}
static int in01(double x) {
    return x >= 0.0 && x <= 1.0;
}

static cj_status check_desc(const cj_particles_desc *d) {
    if (d->capacity == 0) return cj_fail(CJ_ERR_EMPTY, "particle system capacity is 0");
    for (size_t i = 0; i < d->emitter_count; ++i) {
        const cj_emitter *e = &d->emitters[i];
        if (!fin3(e->position) || !fin3(e->direction) || !isfinite(e->spread) ||
            !isfinite(e->speed) || !isfinite(e->rate) || !isfinite(e->lifetime) ||
            !isfinite(e->start) || !isfinite(e->stop) || !isfinite(e->jitter_radius) ||
            !isfinite(e->speed_jitter) || !isfinite(e->lifetime_jitter))
            return cj_fail(CJ_ERR_NONFINITE, "emitter %zu: a field is not finite", i);
        if (!(norm3(e->direction) > 0.0))
            return cj_fail(CJ_ERR_RANGE, "emitter %zu: zero direction", i);
        if (e->spread < 0.0 || e->spread > CJ_PI || e->speed < 0.0 || e->rate < 0.0 ||
            !(e->lifetime > 0.0) || e->jitter_radius < 0.0 || !in01(e->speed_jitter) ||
            !in01(e->lifetime_jitter))
            return cj_fail(CJ_ERR_RANGE,
                           "emitter %zu: spread in [0, pi], speed, rate, radius >= 0, lifetime "
                           "> 0, jitters in [0, 1]",
                           i);
    }
    if (!fin3(d->gravity) || !fin3(d->wind) || !isfinite(d->drag) || !isfinite(d->restitution))
        return cj_fail(CJ_ERR_NONFINITE, "particle system: gravity, wind, drag or restitution");
    if (d->drag < 0.0 || !in01(d->restitution))
        return cj_fail(CJ_ERR_RANGE, "particle system: drag >= 0, restitution in [0, 1]");
    const cj_flocking *f = &d->flocking;
    if (!isfinite(f->radius) || !isfinite(f->separation) || !isfinite(f->alignment) ||
        !isfinite(f->cohesion) || !isfinite(f->max_speed))
        return cj_fail(CJ_ERR_NONFINITE, "flocking: a weight is not finite");
    if (f->radius < 0.0 || f->max_speed < 0.0)
        return cj_fail(CJ_ERR_RANGE, "flocking: radius and max_speed must be >= 0");
    for (size_t i = 0; i < d->patch_collider_count; ++i)
        if (!d->patch_colliders || !d->patch_colliders[i])
            return cj_fail(CJ_ERR_ARGUMENT, "patch collider %zu is NULL", i);
    for (size_t i = 0; i < d->sphere_count; ++i) {
        const cj_sphere_collider *c = &d->spheres[i];
        if (!fin3(c->center) || !isfinite(c->radius) || !isfinite(c->friction))
            return cj_fail(CJ_ERR_NONFINITE, "sphere collider %zu not finite", i);
        if (!(c->radius > 0.0) || !in01(c->friction))
            return cj_fail(CJ_ERR_RANGE, "sphere collider %zu: radius > 0, friction in [0,1]", i);
    }
    for (size_t i = 0; i < d->plane_count; ++i) {
        const cj_plane_collider *c = &d->planes[i];
        if (!fin3(c->normal) || !isfinite(c->offset) || !isfinite(c->friction))
            return cj_fail(CJ_ERR_NONFINITE, "plane collider %zu not finite", i);
        if (!(norm3(c->normal) > 0.0) || !in01(c->friction))
            return cj_fail(CJ_ERR_RANGE,
                           "plane collider %zu: zero normal or friction outside "
                           "[0,1]",
                           i);
    }
    return CJ_OK;
}

cj_status cj_particles_create(const cj_particles_desc *d, const cj_allocator *alloc,
                              cj_particles **out) {
    assert(d && out);
    cj_status st = check_desc(d);
    if (st != CJ_OK) return st;
    const size_t cap = d->capacity;
    const size_t bytes = sizeof(cj_particles) + sizeof(double) * (cap * 11 + d->emitter_count) +
                         sizeof(cj_patch_collider *) * d->patch_collider_count +
                         sizeof(cj_emitter) * d->emitter_count +
                         sizeof(cj_sphere_collider) * d->sphere_count +
                         sizeof(cj_plane_collider) * d->plane_count;
    cj_particles *p = alloc ? alloc->alloc(alloc->user, bytes) : malloc(bytes);
    if (!p) return cj_fail(CJ_ERR_NOMEM, "particle system: no memory for %zu particles", cap);
    memset(p, 0, sizeof *p);
    if (alloc) {
        p->alloc = *alloc;
        p->has_alloc = 1;
    }
    p->d = *d;
    double *q = (double *)(p + 1);
    p->x = q;
    q += 3 * cap;
    p->v = q;
    q += 3 * cap;
    p->acc = q;
    q += 3 * cap;
    p->age = q;
    q += cap;
    p->life = q;
    q += cap;
    p->emit_acc = q;
    q += d->emitter_count;
    p->emitters = (cj_emitter *)q;
    p->spheres = (cj_sphere_collider *)(p->emitters + d->emitter_count);
    p->planes = (cj_plane_collider *)(p->spheres + d->sphere_count);
    if (d->emitter_count) memcpy(p->emitters, d->emitters, sizeof(cj_emitter) * d->emitter_count);
    if (d->sphere_count)
        memcpy(p->spheres, d->spheres, sizeof(cj_sphere_collider) * d->sphere_count);
    if (d->plane_count) memcpy(p->planes, d->planes, sizeof(cj_plane_collider) * d->plane_count);
    const cj_patch_collider **pcs = (const cj_patch_collider **)(p->planes + d->plane_count);
    for (size_t i = 0; i < d->patch_collider_count; ++i) pcs[i] = d->patch_colliders[i];
    p->d.patch_colliders = pcs;
    p->d.emitters = p->emitters;
    p->d.spheres = p->spheres;
    p->d.planes = p->planes;
    memset(p->emit_acc, 0, sizeof(double) * d->emitter_count);
    uint64_t z = d->seed;
    for (int k = 0; k < 4; ++k) { /* splitmix64 */
        z += 0x9e3779b97f4a7c15ULL;
        uint64_t w = z;
        w = (w ^ (w >> 30)) * 0xbf58476d1ce4e5b9ULL;
        w = (w ^ (w >> 27)) * 0x94d049bb133111ebULL;
        p->rng[k] = w ^ (w >> 31);
    }
    *out = p;
    return CJ_OK;
}

void cj_particles_destroy(cj_particles *p) {
    if (!p) return;
    if (p->has_alloc)
        p->alloc.free(p->alloc.user, p);
    else
        free(p);
}

size_t cj_particles_count(const cj_particles *p) {
    return p->count;
}
const double *cj_particles_positions(const cj_particles *p) {
    return p->x;
}
const double *cj_particles_velocities(const cj_particles *p) {
    return p->v;
}
const double *cj_particles_ages(const cj_particles *p) {
    return p->age;
}
const double *cj_particles_lifetimes(const cj_particles *p) {
    return p->life;
}
double cj_particles_time(const cj_particles *p) {
    return p->t;
}
uint64_t cj_particles_steps(const cj_particles *p) {
    return p->steps;
}

cj_status cj_particles_add(cj_particles *p, const double x[3], const double v[3], double lifetime) {
    if (!fin3(x) || !fin3(v) || !isfinite(lifetime))
        return cj_fail(CJ_ERR_NONFINITE, "added particle: position, velocity or lifetime");
    if (!(lifetime > 0.0)) return cj_fail(CJ_ERR_RANGE, "added particle: lifetime %g", lifetime);
    if (p->count >= p->d.capacity)
        return cj_fail(CJ_ERR_BUFFER, "particle pool full (%zu)", p->d.capacity);
    const size_t i = p->count++;
    memcpy(p->x + 3 * i, x, sizeof(double) * 3);
    memcpy(p->v + 3 * i, v, sizeof(double) * 3);
    p->age[i] = 0.0;
    p->life[i] = lifetime;
    return CJ_OK;
}

static void spawn(cj_particles *p, const cj_emitter *e, cj_particles_stats *st) {
    uint64_t *s = p->rng;
    /* draw every number even when the pool is full, so the stream does not depend on it */
    double off[3];
    do {
        for (int k = 0; k < 3; ++k) off[k] = rng_sym(s);
    } while (off[0] * off[0] + off[1] * off[1] + off[2] * off[2] > 1.0);
    const double cz = 1.0 - rng_unit(s) * (1.0 - cos(e->spread)), phi = 2.0 * CJ_PI * rng_unit(s);
    const double sp = e->speed * (1.0 + e->speed_jitter * rng_sym(s));
    const double life = e->lifetime * (1.0 + e->lifetime_jitter * rng_sym(s));
    if (p->count >= p->d.capacity || !(life > 0.0)) {
        ++st->dropped;
        return;
    }
    /* orthonormal frame (a, b, n) around the direction */
    double n[3], a[3], b[3];
    const double nn = norm3(e->direction);
    for (int k = 0; k < 3; ++k) n[k] = e->direction[k] / nn;
    const double helper[3] = {fabs(n[0]) < 0.9 ? 1.0 : 0.0, fabs(n[0]) < 0.9 ? 0.0 : 1.0, 0.0};
    a[0] = helper[1] * n[2] - helper[2] * n[1];
    a[1] = helper[2] * n[0] - helper[0] * n[2];
    a[2] = helper[0] * n[1] - helper[1] * n[0];
    const double an = norm3(a);
    for (int k = 0; k < 3; ++k) a[k] /= an;
    b[0] = n[1] * a[2] - n[2] * a[1];
    b[1] = n[2] * a[0] - n[0] * a[2];
    b[2] = n[0] * a[1] - n[1] * a[0];
    const double sz = sqrt(fmax(0.0, 1.0 - cz * cz));
    const size_t i = p->count++;
    for (int k = 0; k < 3; ++k) {
        const double dir = cz * n[k] + sz * (cos(phi) * a[k] + sin(phi) * b[k]);
        p->x[3 * i + k] = e->position[k] + e->jitter_radius * off[k];
        p->v[3 * i + k] = sp * dir;
    }
    p->age[i] = 0.0;
    p->life[i] = life;
    ++st->emitted;
}

static void flock(cj_particles *p, cj_particles_stats *st) {
    const cj_flocking *f = &p->d.flocking;
    const double r2 = f->radius * f->radius;
    for (size_t i = 0; i < p->count; ++i) {
        double sep[3] = {0, 0, 0}, vs[3] = {0, 0, 0}, xs[3] = {0, 0, 0};
        size_t nb = 0;
        for (size_t j = 0; j < p->count; ++j) {
            if (j == i) continue;
            double d[3], d2 = 0.0;
            for (int k = 0; k < 3; ++k) {
                d[k] = p->x[3 * i + k] - p->x[3 * j + k];
                d2 += d[k] * d[k];
            }
            if (d2 > r2) continue;
            ++nb;
            for (int k = 0; k < 3; ++k) {
                if (d2 > 0.0) sep[k] += d[k] / d2;
                vs[k] += p->v[3 * j + k];
                xs[k] += p->x[3 * j + k];
            }
        }
        st->neighbour_pairs += nb;
        if (!nb) continue;
        for (int k = 0; k < 3; ++k)
            p->acc[3 * i + k] += f->separation * sep[k] +
                                 f->alignment * (vs[k] / (double)nb - p->v[3 * i + k]) +
                                 f->cohesion * (xs[k] / (double)nb - p->x[3 * i + k]);
    }
}

static int bounce(double *x, double *v, const double *nrm, double depth, double e, double fr) {
    double vn = 0.0;
    for (int k = 0; k < 3; ++k) {
        x[k] += 2.0 * depth * nrm[k]; /* mirror the penetration */
        vn += v[k] * nrm[k];
    }
    if (vn < 0.0)
        for (int k = 0; k < 3; ++k) {
            const double vt = v[k] - vn * nrm[k];
            v[k] = -e * vn * nrm[k] + (1.0 - fr) * vt;
        }
    return 1;
}

static size_t collide(cj_particles *p) {
    size_t hits = 0;
    const double e = p->d.restitution;
    for (size_t i = 0; i < p->count; ++i) {
        double *x = p->x + 3 * i, *v = p->v + 3 * i;
        for (size_t j = 0; j < p->d.plane_count; ++j) {
            const cj_plane_collider *c = &p->planes[j];
            const double nl = norm3(c->normal);
            const double nrm[3] = {c->normal[0] / nl, c->normal[1] / nl, c->normal[2] / nl};
            const double side = nrm[0] * x[0] + nrm[1] * x[1] + nrm[2] * x[2];
            if (side < c->offset)
                hits += (size_t)bounce(x, v, nrm, c->offset - side, e, c->friction);
        }
        for (size_t j = 0; j < p->d.sphere_count; ++j) {
            const cj_sphere_collider *c = &p->spheres[j];
            double d[3] = {x[0] - c->center[0], x[1] - c->center[1], x[2] - c->center[2]};
            const double l = norm3(d);
            if (l >= c->radius) continue;
            double nrm[3] = {0, 0, 1};
            if (l > 0.0)
                for (int k = 0; k < 3; ++k) nrm[k] = d[k] / l;
            hits += (size_t)bounce(x, v, nrm, c->radius - l, e, c->friction);
        }
    }
    return hits;
}

cj_status cj_particles_step(cj_particles *p, double h, cj_particles_stats *stats) {
    assert(p);
    if (!(h > 0.0) || !isfinite(h)) return cj_fail(CJ_ERR_RANGE, "time step %g must be > 0", h);
    cj_particles_stats st;
    memset(&st, 0, sizeof st);
    double t0 = cj_clock_seconds();
    /* Bounded work whatever the rate, step or restored state: a step in which one emitter
     * would emit more than CJ_PARTICLES_MAX_EMIT_PER_STEP particles is refused, not looped over,
     * and refused before any emitter has changed anything. */
    for (size_t j = 0; j < p->d.emitter_count; ++j) {
        const cj_emitter *e = &p->emitters[j];
        const int active = p->t >= e->start && (e->stop <= e->start || p->t < e->stop);
        const double acc = p->emit_acc[j] + (active ? e->rate * h : 0.0);
        if (!(acc < CJ_PARTICLES_MAX_EMIT_PER_STEP + 1.0))
            return cj_fail(CJ_ERR_RANGE,
                           "emitter %zu would emit %g particles in one step of %g s (at most "
                           "%g: lower its rate or shorten the step)",
                           j, acc, h, CJ_PARTICLES_MAX_EMIT_PER_STEP);
    }
    for (size_t j = 0; j < p->d.emitter_count; ++j) {
        const cj_emitter *e = &p->emitters[j];
        const int active = p->t >= e->start && (e->stop <= e->start || p->t < e->stop);
        if (!active) continue;
        const double acc = p->emit_acc[j] + e->rate * h;
        const long n = (long)floor(acc);
        p->emit_acc[j] = acc - (double)n;
        for (long k = 0; k < n; ++k) spawn(p, e, &st);
    }
    double t1 = cj_clock_seconds();
    st.seconds_emit = t1 - t0;
    const double *g = p->d.gravity, *w = p->d.wind, dr = p->d.drag;
    for (size_t i = 0; i < p->count; ++i)
        for (int k = 0; k < 3; ++k) p->acc[3 * i + k] = g[k] + dr * (w[k] - p->v[3 * i + k]);
    const cj_flocking *f = &p->d.flocking;
    if (f->radius > 0.0 && (f->separation != 0.0 || f->alignment != 0.0 || f->cohesion != 0.0))
        flock(p, &st);
    for (size_t i = 0; i < p->count; ++i) {
        double *v = p->v + 3 * i;
        for (int k = 0; k < 3; ++k) v[k] += h * p->acc[3 * i + k];
        if (f->max_speed > 0.0) {
            const double s = norm3(v);
            if (s > f->max_speed)
                for (int k = 0; k < 3; ++k) v[k] *= f->max_speed / s;
        }
        for (int k = 0; k < 3; ++k) {
            p->acc[3 * i + k] = p->x[3 * i + k]; /* the acceleration is used: keep x_old */
            p->x[3 * i + k] += h * v[k];
        }
    }
    double t2 = cj_clock_seconds();
    st.seconds_forces = t2 - t1;
    if (p->d.patch_collider_count)
        for (size_t i = 0; i < p->count; ++i)
            for (size_t j = 0; j < p->d.patch_collider_count; ++j)
                st.collisions += (size_t)cj_patch_collider_resolve_(p->d.patch_colliders[j],
                                                                    p->acc + 3 * i, p->x + 3 * i,
                                                                    p->v + 3 * i, p->d.restitution);
    if (p->d.plane_count || p->d.sphere_count) st.collisions += collide(p);
    st.seconds_collide = cj_clock_seconds() - t2;
    for (size_t i = 0; i < p->count;) {
        p->age[i] += h;
        if (p->age[i] >= p->life[i]) {
            const size_t last = --p->count;
            memcpy(p->x + 3 * i, p->x + 3 * last, sizeof(double) * 3);
            memcpy(p->v + 3 * i, p->v + 3 * last, sizeof(double) * 3);
            p->age[i] = p->age[last];
            p->life[i] = p->life[last];
            ++st.died;
            continue; /* slot i now holds the last particle, not aged yet */
        }
        ++i;
    }
    p->t += h;
    ++p->steps;
    for (size_t i = 0; i < 3 * p->count; ++i)
        if (!isfinite(p->x[i]) || !isfinite(p->v[i])) {
            if (stats) *stats = st;
            return cj_fail(CJ_ERR_NONFINITE, "particle %zu: state became non-finite", i / 3);
        }
    if (stats) *stats = st;
    return CJ_OK;
}

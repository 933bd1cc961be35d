/* casteljau: particle systems — emitters, lifetimes, forces (gravity, drag, wind), collisions
 * with planes and spheres, flocking (separation, alignment, cohesion); seeded and reproducible,
 * with checkpoints that resume bit-identically.
 *
 * Each step of size h runs, in this order:
 *   1. EMIT: emitter e accumulates rate·h (while its time window [start, stop) covers the step's
 *      start) and spawns one particle per whole unit accumulated, at `position` plus a uniform
 *      offset in a ball of radius `jitter_radius`, with a direction uniform on the spherical cap
 *      of half-angle `spread` around `direction`, speed speed·(1 + speed_jitter·U(−1,1)) and
 *      lifetime lifetime·(1 + lifetime_jitter·U(−1,1)). A full pool drops the particle (counted).
 *   2. FORCES: a = g + drag·(wind − v) + flocking (below).
 *   3. INTEGRATE: semi-implicit (symplectic) Euler, v += h a, x += h v.
 *   4. COLLIDE: a particle behind a plane or inside a sphere is reflected back to the free side
 *      (its penetration mirrored), its normal velocity reversed and scaled by `restitution`, its
 *      tangential velocity scaled by (1 − friction).
 *   5. AGE: age += h; a particle whose age reaches its lifetime dies (swap-removed: the order of
 *      the pool is part of the deterministic state).
 * FLOCKING (Reynolds; weights 0 turn a rule off, and all zero skip the O(n²) neighbour pass):
 * for the neighbours j within `radius` of particle i,
 *   separation  Σ (x_i − x_j)/|x_i − x_j|²,   alignment  mean(v_j) − v_i,
 *   cohesion    mean(x_j) − x_i,
 * weighted and added to a; then |v| is capped at max_speed (if > 0).
 *
 * RANDOMNESS: one xoshiro256** stream seeded from `seed` (splitmix64), drawn in a fixed order:
 * the same description and steps give bit-identical particles on every machine with IEEE
 * doubles (no threads, no time).
 *
 * CHECKPOINTS: cj_particles_save() writes the whole state (time, step count, generator state,
 * emitter accumulators, every particle) as a little binary file (magic "CJPARTS1", doubles
 * stored as their IEEE bit patterns, little-endian); cj_particles_load() restores it into a
 * system created from the same description. Running N steps after a load gives exactly the
 * particles the uninterrupted run has, bit for bit — so a long animation can be split at any
 * frame over many processes. A file from another description (capacity or emitter count
 * differ), truncated or corrupt, is CJ_ERR_PARSE with nothing changed; I/O failures CJ_ERR_IO.
 *
 * OWNERSHIP: create copies the description and allocates the pool (capacity particles) once;
 * steps allocate nothing.
 *
 * Errors (nothing created / state unchanged): capacity 0: CJ_ERR_EMPTY; a non-finite field:
 * CJ_ERR_NONFINITE naming it ("emitter 1: direction"); a negative rate, lifetime, drag,
 * radius or max_speed, a spread outside [0, pi], jitters outside [0, 1], restitution or friction
 * outside [0, 1], a zero emitter direction or plane normal, a sphere radius <= 0:
 * CJ_ERR_RANGE naming it; a time step that is NaN or <= 0: CJ_ERR_RANGE ("time step").
 */
#ifndef CASTELJAU_PARTICLES_H
#define CASTELJAU_PARTICLES_H

#include "casteljau/alloc.h"
#include "casteljau/patch.h"
#include "casteljau/springs.h"
#include "casteljau/transform.h"
#include "casteljau/status.h"
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct cj_emitter {
    double position[3];
    double jitter_radius;   /* >= 0 */
    double direction[3];    /* non-zero */
    double spread;          /* half-angle of the cone, [0, pi] */
    double speed;           /* >= 0 */
    double speed_jitter;    /* [0, 1] */
    double rate;            /* particles per second, >= 0 */
    double lifetime;        /* seconds, > 0 */
    double lifetime_jitter; /* [0, 1] */
    double start, stop;     /* emission window; stop <= start means "forever from start" */
} cj_emitter;

cj_emitter
cj_emitter_defaults(void); /* at the origin, up +z, spread 0.3, speed 1, rate 10, life 2 */

typedef struct cj_flocking {
    double radius; /* neighbourhood radius, >= 0 */
    double separation, alignment, cohesion;
    double max_speed; /* 0: no cap */
} cj_flocking;

/* A collider made of Bézier patches (the teapot): the patches, mapped to world space by an
 * affine matrix, in a BVH over their control-point boxes. A particle that moves from a to b in a
 * step is tested along the SEGMENT a→b with the ray tracer's patch intersection
 * (casteljau/ray.h: cj_ray_patch by subdivision + Newton to `tol` world units), so fast
 * particles cannot tunnel through. On a hit the particle is put back at the hit point, moved
 * off the surface by 1e-6 of the collider's size (plus 100 tol) on the side it came from, and its
 * velocity reflected (restitution, friction) as for spheres; the rest of that step's motion is
 * dropped. Degrees above CJ_RAY_PATCH_MAX_DEGREE: CJ_ERR_DEGREE. The collider is read-only
 * once built and may be shared by several particle systems (which must not outlive it). */
typedef struct cj_patch_collider cj_patch_collider;

cj_status cj_patch_collider_create(const cj_patch *patches, size_t count, const cj_xform3 *to_world,
                                   double tol, double friction, const cj_allocator *alloc,
                                   cj_patch_collider **out);
void cj_patch_collider_destroy(cj_patch_collider *c);
/* First hit of the segment a→b (parameter t in [0, 1]): 1 with t, the point and the unit normal
 * facing a; 0 when the segment misses. */
int cj_patch_collider_segment(const cj_patch_collider *c, const double a[3], const double b[3],
                              double *t, double point[3], double normal[3]);
/* SOLID colliders. A segment test misses a particle that enters through a gap between patches
 * (the teapot's lid sits 0.1 inside its rim, leaving an open ring) or slips through a seam; it
 * then stays inside, since every later crossing is pushed back in. After set_solid(up) (up: a
 * nonzero direction, NULL or zero: not solid) the patches are taken to bound a solid closed
 * along `up` (every ray from the inside along up leaves through a patch: the teapot with up =
 * its lid's direction, whatever its open bottom), and a spring system (springs.h) moves a
 * particle found inside out through the nearest surface point after its segment tests. Inside
 * means an odd number of crossings of the ray from the point along up (a crossing found on two
 * patches at a seam counts once); points outside the patches' box are outside. The nearest
 * point is certified (casteljau/patch_nearest.h, to the collider's tol). Call before the
 * collider is shared. */
void cj_patch_collider_set_solid(cj_patch_collider *c, const double up[3]);
int cj_patch_collider_inside(const cj_patch_collider *c, const double x[3]);
/* SEALS of a solid: a model's surface can leave narrow gaps (the Utah teapot's lid rests 0.1
 * inside its rim, an open ring through which a cloth sinks and which hides the inside from the
 * vertical ray). set_solid pairs every open patch side (shared by no other side, not collapsed)
 * with the nearest open side of another patch of the same degree whose control points all lie
 * within 2% of the collider's size of its own, and closes the pair with a ruled patch (degree
 * (d, 1), rows the two sides), which the segment test, the inside test and the nearest point
 * then include. The teapot gets four (lid to rim). The number of seals: */
size_t cj_patch_collider_seals(const cj_patch_collider *c);

typedef struct cj_particles_desc {
    size_t capacity;
    uint64_t seed;
    size_t emitter_count;
    const cj_emitter *emitters;
    double gravity[3];
    double drag;    /* >= 0, 1/s */
    double wind[3]; /* the air's velocity that drag pulls towards */
    size_t sphere_count;
    const cj_sphere_collider *spheres;
    size_t plane_count;
    const cj_plane_collider *planes;
    size_t patch_collider_count;
    const cj_patch_collider *const *patch_colliders; /* not owned; must outlive the system */
    double restitution;                              /* [0, 1] */
    cj_flocking flocking;
} cj_particles_desc;

typedef struct cj_particles cj_particles;

typedef struct cj_particles_stats {
    size_t emitted, dropped, died, collisions, neighbour_pairs;
    double seconds_emit, seconds_forces, seconds_collide;
} cj_particles_stats;

cj_status cj_particles_create(const cj_particles_desc *desc, const cj_allocator *alloc,
                              cj_particles **out);
void cj_particles_destroy(cj_particles *p);

/* Advances by h seconds (> 0, finite). An emitter that would emit more than
 * CJ_PARTICLES_MAX_EMIT_PER_STEP particles in this step (rate * h plus the fraction carried
 * over) makes the step fail with CJ_ERR_RANGE naming it, before anything changes: the work of
 * a step is bounded whatever the rate and step. */
#define CJ_PARTICLES_MAX_EMIT_PER_STEP 1e6
cj_status cj_particles_step(cj_particles *p, double h, cj_particles_stats *stats);

/* Live particles and their arrays (count × 3 positions, velocities; count ages and lifetimes),
 * valid until the next step. */
size_t cj_particles_count(const cj_particles *p);
const double *cj_particles_positions(const cj_particles *p);
const double *cj_particles_velocities(const cj_particles *p);
const double *cj_particles_ages(const cj_particles *p);
const double *cj_particles_lifetimes(const cj_particles *p);
double cj_particles_time(const cj_particles *p);
uint64_t cj_particles_steps(const cj_particles *p);

/* Adds one particle by hand (for tests and scripted effects): CJ_ERR_BUFFER when full. */
cj_status cj_particles_add(cj_particles *p, const double x[3], const double v[3], double lifetime);

cj_status cj_particles_save(const cj_particles *p, FILE *f);
/* Restores a state saved by cj_particles_save. Every value is checked before anything changes:
 * time finite and >= 0, each emitter's carried fraction in [0, 1), positions and velocities
 * finite, ages >= 0 and lifetimes > 0 (finite), a random state that is not all zero; a
 * violation is CJ_ERR_PARSE naming the value
 * ("particle 3: velocity is NaN"). Truncated or foreign checkpoints are CJ_ERR_PARSE too. */
cj_status cj_particles_load(cj_particles *p, FILE *f);

#ifdef __cplusplus
}
#endif
#endif

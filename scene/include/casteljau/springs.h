/* casteljau: physically-based animation (seed 16.5) — time integrators for second-order systems
 * and spring-mass systems in 1D, 2D and 3D (springs, fixed points, gravity, drag, sphere and
 * plane colliders, cloth).
 *
 * INTEGRATORS for x'' = a(t, x, v), step h > 0 (x, v of n numbers each):
 *   EXPLICIT_EULER     x⁺ = x + h v,  v⁺ = v + h a(x, v)                 (order 1, unstable on
 *                      undamped oscillators for EVERY h: energy grows by (1 + h²ω²) per step)
 *   SYMPLECTIC_EULER   v⁺ = v + h a(x, v),  x⁺ = x + h v⁺                (order 1, symplectic:
 *                      stable for hω < 2; on x'' = −ω²x it conserves I = v² + ω²x² − hω² x v
 *                      exactly, so the energy E = (v² + ω²x²)/2 never drifts: with θ = hω,
 *                      |E_n/E_0 − 1| <= θ/(1 − θ/2) for all n)
 *   RK4                classical fourth-order Runge–Kutta on (x, v)      (order 4, stable for
 *                      hω < 2.78 on oscillators)
 *   IMPLICIT_EULER     backward Euler v⁺ = v + h a(x⁺, v⁺), x⁺ = x + h v⁺ (order 1, L-stable:
 *                      bounded for every h, damps |amplitude| by 1/√(1 + h²ω²) per step).
 *
 * The generic stepper cj_ode2_step() solves the implicit equations by Newton's method with the
 * caller's dense Jacobians and LAPACKE dgesv (n <= CJ_ODE2_DENSE_MAX unknowns: the dense solve
 * is O(n³) per Newton iteration; larger systems should use the spring system's sparse path).
 *
 * SPRING SYSTEMS: particles with positions x_i ∈ R^dim (dim 1..3), masses m_i > 0 (ignored for
 * fixed particles, which never move), springs (a, b, rest length L, stiffness k >= 0, damping
 * c >= 0) pulling with
 *     f_a = −(k (l − L) + c (v_a − v_b)·n) n = −f_b,   d = x_a − x_b, l = |d|, n = d/l
 * (a spring of zero current length exerts no force: its direction is undefined), gravity g
 * (force m_i g) and linear drag (force −m_i·drag·v_i). Energy: kinetic Σ m v²/2, potential
 * Σ k (l − L)²/2 − Σ m g·x.
 * The spring system's IMPLICIT_EULER is the linearised backward Euler of Baraff and Witkin
 * (one Newton step, exact for linear forces):
 *     (M − h ∂f/∂v − h² ∂f/∂x) Δv = h (f + h ∂f/∂x v),   v⁺ = v + Δv,  x⁺ = x + h v⁺,
 * solved matrix-free by Jacobi-preconditioned conjugate gradients (any size, O(springs) per
 * iteration), with the compressive part of ∂f/∂x dropped (the factor 1 − L/l clamped at 0,
 * Choi and Ko) so the matrix stays symmetric positive definite. CG starts from Δv = 0 (no warm
 * start, so a step depends on (x, v) alone and checkpoints resume bit-identically) and stops at
 * relative residual 1e-9 (far below the O(h) error of the method) or after CJ_SPRING_CG_MAX
 * iterations; hitting the cap still advances the state and returns CJ_ERR_CAP.
 * Collisions (after each step): a particle whose step segment crosses a patch collider is put
 * back on the side it came from (as particles.h describes, restitution 0); then a particle
 * inside a sphere (|x − c| < r) or behind a plane (n·x < offset) is moved to the surface along
 * the normal, its inward normal velocity removed and its tangential velocity scaled by
 * (1 − friction).
 *
 * OWNERSHIP: cj_springs_create() copies everything and allocates all its work space; a step
 * allocates nothing. Deterministic: the same inputs give bit-identical states.
 *
 * Errors (nothing created / state unchanged): non-finite input: CJ_ERR_NONFINITE naming the
 * particle, spring or collider; a spring naming a particle that does not exist or itself, a
 * negative stiffness, damping or rest length, a non-positive mass of a free particle, a sphere
 * of radius <= 0, a plane with a zero normal: CJ_ERR_ARGUMENT / CJ_ERR_RANGE naming it; dim
 * outside 1..3: CJ_ERR_DIMENSION; a time step that is NaN or <= 0: CJ_ERR_RANGE ("time step").
 * A state that becomes non-finite (an unstable explicit step): CJ_ERR_NONFINITE, naming the
 * particle; the state is left as computed so the caller can see the blow-up.
 */
#ifndef CASTELJAU_SPRINGS_H
#define CASTELJAU_SPRINGS_H

#include "casteljau/alloc.h"
#include "casteljau/status.h"
#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef enum cj_integrator {
    CJ_INTEGRATE_EXPLICIT_EULER = 0,
    CJ_INTEGRATE_SYMPLECTIC_EULER,
    CJ_INTEGRATE_RK4,
    CJ_INTEGRATE_IMPLICIT_EULER,
    CJ_INTEGRATOR_COUNT_
} cj_integrator;

/* "explicit_euler", "symplectic_euler", "rk4", "implicit_euler". */
const char *cj_integrator_name(cj_integrator m);

/* ---- generic second-order systems ------------------------------------------------------ */

#define CJ_ODE2_DENSE_MAX 512

typedef struct cj_ode2 {
    size_t n; /* unknowns */
    void *user;
    /* a[n] = x'' at (t, x, v). */
    void (*accel)(void *user, double t, const double *x, const double *v, double *a);
    /* IMPLICIT_EULER only: dadx, dadv (n × n, row-major) = ∂a/∂x, ∂a/∂v at (t, x, v). */
    void (*jacobian)(void *user, double t, const double *x, const double *v, double *dadx,
                     double *dadv);
} cj_ode2;

/* Doubles of work space cj_ode2_step() needs for n unknowns and a method. */
size_t cj_ode2_work_size(size_t n, cj_integrator m);

/* One step of size h from time t, x and v updated in place. work: cj_ode2_work_size() doubles,
 * ipiv: n ints (IMPLICIT_EULER only, else may be NULL). Implicit Euler runs Newton until the
 * update is below 1e-14 of the state's size (at most 20 iterations, else CJ_ERR_CAP with the last
 * iterate written); a singular Newton matrix is CJ_ERR_SINGULAR (state unchanged); n above
 * CJ_ODE2_DENSE_MAX or a missing jacobian is CJ_ERR_ARGUMENT. *newton_iters (may be NULL)
 * receives the iterations used (0 for explicit methods). */
cj_status cj_ode2_step(const cj_ode2 *sys, cj_integrator m, double t, double h, double *x,
                       double *v, double *work, int *ipiv, int *newton_iters);

/* ---- spring-mass systems ----------------------------------------------------------------- */

#define CJ_SPRING_CG_MAX 1000

typedef struct cj_spring {
    int a, b;         /* particle indices, a != b */
    double rest;      /* L >= 0 */
    double stiffness; /* k >= 0 */
    double damping;   /* c >= 0 */
} cj_spring;

typedef struct cj_sphere_collider {
    double center[3];
    double radius;   /* > 0 */
    double friction; /* in [0, 1] */
} cj_sphere_collider;

typedef struct cj_plane_collider {
    double normal[3]; /* non-zero; the free side is normal·x >= offset·|normal| */
    double offset;
    double friction;
} cj_plane_collider;

/* Bézier-patch colliders (casteljau/particles.h, cj_patch_collider_create): each free particle's
 * step segment is tested against them, so cloth can drape over the teapot. */
typedef struct cj_patch_collider cj_patch_collider;

typedef struct cj_springs_desc {
    int dim;                    /* 1, 2 or 3 */
    size_t count;               /* particles */
    const double *x;            /* count × dim */
    const double *v;            /* count × dim, or NULL for rest */
    const double *mass;         /* count */
    const unsigned char *fixed; /* count flags, or NULL: none fixed */
    size_t spring_count;
    const cj_spring *springs;
    double gravity[3]; /* only the first dim components are used */
    double drag;       /* >= 0 */
    size_t sphere_count;
    const cj_sphere_collider *spheres;
    size_t plane_count;
    const cj_plane_collider *planes;
    size_t patch_collider_count;
    const cj_patch_collider *const *patch_colliders; /* not owned; must outlive the system */
} cj_springs_desc;

typedef struct cj_springs cj_springs;

typedef struct cj_springs_stats {
    int cg_iterations;  /* implicit Euler: CG iterations of the last step */
    double cg_residual; /* relative residual reached */
    size_t collisions;  /* particles pushed out of colliders in the last step */
    double seconds_forces, seconds_solve, seconds_collide; /* wall time of the last step */
} cj_springs_stats;

cj_status cj_springs_create(const cj_springs_desc *desc, const cj_allocator *alloc,
                            cj_springs **out);
void cj_springs_destroy(cj_springs *s);

int cj_springs_dim(const cj_springs *s);
size_t cj_springs_count(const cj_springs *s);
size_t cj_springs_spring_count(const cj_springs *s);
/* The current state, count × dim each (valid until destroy). */
const double *cj_springs_positions(const cj_springs *s);
const double *cj_springs_velocities(const cj_springs *s);
/* Replaces the state (count × dim each; v NULL for rest). Non-finite: CJ_ERR_NONFINITE. */
cj_status cj_springs_set_state(cj_springs *s, const double *x, const double *v);
/* Simulated time (the sum of the steps taken). */
double cj_springs_time(const cj_springs *s);

/* Advances by h with the chosen integrator; stats may be NULL. */
cj_status cj_springs_step(cj_springs *s, cj_integrator m, double h, cj_springs_stats *stats);

/* Kinetic and potential energy (see above); either pointer may be NULL. */
void cj_springs_energy(const cj_springs *s, double *kinetic, double *potential);

/* The forces' accelerations at the current state into a[count × dim] (fixed particles: 0). */
void cj_springs_accel(const cj_springs *s, double *a);

/* A CLOTH: a grid of nu × nv particles (nu, nv >= 2) at corner + i/(nu−1) eu + j/(nv−1) ev
 * (3D), total mass `mass`, with structural springs (grid neighbours, stiffness k_struct),
 * shear springs (diagonals, k_shear) and bend springs (two apart, k_bend; 0 leaves them out),
 * all with damping c and rest lengths from the initial grid. Particle (i, j) has index
 * j·nu + i. `pinned` (may be NULL) lists pinned_count particle indices that are fixed.
 * Gravity, drag and colliders come from `extra` (its dim must be 3; its particle and spring
 * fields are ignored; may be NULL: no gravity, drag or colliders). */
cj_status cj_springs_create_cloth(int nu, int nv, const double corner[3], const double eu[3],
                                  const double ev[3], double mass, double k_struct, double k_shear,
                                  double k_bend, double c, const int *pinned, size_t pinned_count,
                                  const cj_springs_desc *extra, const cj_allocator *alloc,
                                  cj_springs **out);

#ifdef __cplusplus
}
#endif
#endif

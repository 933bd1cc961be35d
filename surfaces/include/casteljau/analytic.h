/* casteljau: the elementary surfaces of seed chapter 5 — planes, planar and bilinear patches,
 * right circular and general cylinders, surfaces of revolution (any profile) and the torus.
 *
 * Each is a small value struct filled and validated by its *_init function (which never
 * allocates) and viewed as a cj_param_surface / cj_implicit_surface whose `data` points at the
 * struct: keep the struct alive and unchanged while a view is in use. The views cannot fail
 * once the struct was initialised successfully, so they return void.
 *
 * Placement: several surfaces take an axis. An axis vector is normalised; the frame (e1, e2, a)
 * completing it is built by cj_frame_from_axis and stored, so e1, e2, a is right-handed and
 * orthonormal. "Angle u" below means the direction e_r(u) = cos u e1 + sin u e2.
 *
 * Status codes of the *_init functions:
 *   CJ_ERR_NONFINITE   a NaN or infinite coordinate, radius or range bound (named);
 *   CJ_ERR_DEGENERATE  a zero-length axis or normal, a radius <= 0, a parallelogram or
 *                      bilinear patch whose corners are collinear, a sweep direction parallel
 *                      to the curve's plane (named);
 *   CJ_ERR_ARGUMENT    an empty range (h0 >= h1), minor radius >= major radius, a curve
 *                      struct without callback;
 *   anything the profile/directrix callback returns.
 */
#ifndef CASTELJAU_ANALYTIC_H
#define CASTELJAU_ANALYTIC_H

#include "casteljau/surface.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- plane: f(x) = n.x - d with |n| = 1 (signed distance; grad f = n) ------------------ */

typedef struct cj_plane {
    cj_vec3 n; /* unit normal */
    double d;  /* offset: the plane is n.x = d */
} cj_plane;

/* The plane through p with normal n (any non-zero length). */
cj_status cj_plane_from_point_normal(cj_plane *pl, cj_vec3 p, cj_vec3 n);
/* The plane through a, b, c with normal (b-a) x (c-a) (a, b, c counter-clockwise seen from
 * the side n points to). Collinear points: CJ_ERR_DEGENERATE. */
cj_status cj_plane_from_points(cj_plane *pl, cj_vec3 a, cj_vec3 b, cj_vec3 c);
void cj_plane_implicit(const cj_plane *pl, cj_implicit_surface *out);

/* ---- planar patch (parallelogram): S(u,v) = p + u e_u + v e_v, (u,v) in [0,1]^2 ---------- */
/* S_u = e_u, S_v = e_v, normal e_u x e_v / |e_u x e_v| (constant); implicit form: its plane. */

typedef struct cj_planar_patch {
    cj_vec3 p, eu, ev;
    cj_plane plane;
} cj_planar_patch;

cj_status cj_planar_patch_init(cj_planar_patch *pp, cj_vec3 p, cj_vec3 eu, cj_vec3 ev);
void cj_planar_patch_surface(const cj_planar_patch *pp, cj_param_surface *out);
void cj_planar_patch_implicit(const cj_planar_patch *pp, cj_implicit_surface *out);

/* ---- bilinear patch ---------------------------------------------------------------------
 *   S(u,v) = (1-u)(1-v) p00 + u(1-v) p10 + (1-u)v p01 + uv p11,   (u,v) in [0,1]^2
 *   S_u = (1-v)(p10 - p00) + v(p11 - p01),   S_v = (1-u)(p01 - p00) + u(p11 - p10).
 * A non-planar one is a piece of a hyperbolic paraboloid (no implicit form is offered). If two
 * corners coincide (a triangle as a collapsed bilinear patch) the normal at the collapsed edge
 * is the limit from the interior (cj_surface_normal's generic rule). All four corners
 * collinear (or coincident): CJ_ERR_DEGENERATE. */

typedef struct cj_bilinear {
    cj_vec3 p00, p10, p01, p11;
    unsigned flags; /* CJ_SURF_COLLAPSED_* for edges whose two corners coincide */
} cj_bilinear;

cj_status cj_bilinear_init(cj_bilinear *bl, cj_vec3 p00, cj_vec3 p10, cj_vec3 p01, cj_vec3 p11);
void cj_bilinear_surface(const cj_bilinear *bl, cj_param_surface *out);

/* ---- right circular cylinder ------------------------------------------------------------
 *   S(u,v) = base + radius e_r(u) + v a,   u in [0, 2pi] (periodic), v in [h0, h1]
 *   normal e_r(u) (outward); implicit f = (|w_perp|^2 - radius^2) / (2 radius),
 *   w = x - base, w_perp = w - (w.a) a, grad f = w_perp / radius (unit on the surface).
 *   The implicit form is the infinite cylinder. */

typedef struct cj_cylinder {
    cj_vec3 base, a, e1, e2;
    double radius, h0, h1;
} cj_cylinder;

cj_status cj_cylinder_init(cj_cylinder *cy, cj_vec3 base, cj_vec3 axis, double radius, double h0,
                           double h1);
void cj_cylinder_surface(const cj_cylinder *cy, cj_param_surface *out);
void cj_cylinder_implicit(const cj_cylinder *cy, cj_implicit_surface *out);

/* ---- general cylinder: a planar curve swept along a direction ----------------------------
 *   S(u,v) = origin + x(u) e1 + y(u) e2 + v dir,   u in [t0,t1] of the curve, v in [v0,v1]
 *   S_u = x'(u) e1 + y'(u) e2,  S_v = dir,  normal S_u x dir normalised; where the curve's
 *   speed vanishes, the second derivative's direction is used (the one-sided limit of the
 *   tangent at a cusp). e1, e2 (the plane of the curve) need not be orthonormal but must be
 *   independent; dir must not lie in their plane. A curve counter-clockwise in the (e1, e2)
 *   plane swept along a dir with positive component on e1 x e2 gets outward normals.
 *   Periodic in u when the curve is `closed`. */

typedef struct cj_gen_cylinder {
    cj_curve2 curve; /* copied; curve.data must stay alive */
    cj_vec3 origin, e1, e2, dir;
    double v0, v1;
} cj_gen_cylinder;

cj_status cj_gen_cylinder_init(cj_gen_cylinder *gc, const cj_curve2 *curve, cj_vec3 origin,
                               cj_vec3 e1, cj_vec3 e2, cj_vec3 dir, double v0, double v1);
void cj_gen_cylinder_surface(const cj_gen_cylinder *gc, cj_param_surface *out);

/* ---- surface of revolution of a profile (r(t), z(t)) about an axis ------------------------
 *   S(u,v) = origin + r(v) e_r(u) + z(v) a,   u in [0, 2pi] (periodic), v in [t0, t1]
 *   S_u = r e_theta(u),  S_v = r' e_r(u) + z' a,  S_u x S_v = r (z' e_r(u) - r' a).
 * The normal is N = (z' e_r(u) - r' a) / |(r', z')| — S_u x S_v with the factor r divided
 * out, so it is defined and continuous where the profile meets the axis (r = 0, a pole) and
 * equals the normalised S_u x S_v wherever r > 0. Where the profile's speed vanishes,
 * (r'', z'') replaces (r', z'). The profile should lie in r >= 0. A profile running
 * counter-clockwise in the (r, z) half-plane (e.g. from the south pole up to the north pole,
 * or a closed loop around a region) gets outward normals.
 * Flags: PERIODIC_U; COLLAPSED_V0 / _V1 where |r(t0)| / |r(t1)| <= 1e-14 times the profile's
 * size at its ends; PERIODIC_V if the profile is `closed`. */

typedef struct cj_revolution {
    cj_curve2 profile; /* copied; profile.data must stay alive */
    cj_vec3 origin, a, e1, e2;
    unsigned flags;
} cj_revolution;

cj_status cj_revolution_init(cj_revolution *rv, const cj_curve2 *profile, cj_vec3 origin,
                             cj_vec3 axis);
void cj_revolution_surface(const cj_revolution *rv, cj_param_surface *out);

/* ---- torus (ring torus, 0 < minor < major) ----------------------------------------------
 *   S(u,v) = center + (R + rho cos v) e_r(u) + rho sin v a,   u, v in [0, 2pi], both periodic
 *   normal cos v e_r(u) + sin v a (outward, exact, no singular points);
 *   implicit f = (|w|^2 + R^2 - rho^2)^2 - 4 R^2 (|w|^2 - (w.a)^2),  w = x - center,
 *   grad f = 4 (|w|^2 + R^2 - rho^2) w - 8 R^2 (w - (w.a) a). f < 0 inside the tube. */

typedef struct cj_torus {
    cj_vec3 center, a, e1, e2;
    double major, minor;
} cj_torus;

cj_status cj_torus_init(cj_torus *to, cj_vec3 center, cj_vec3 axis, double major, double minor);
void cj_torus_surface(const cj_torus *to, cj_param_surface *out);
void cj_torus_implicit(const cj_torus *to, cj_implicit_surface *out);

#ifdef __cplusplus
}
#endif
#endif

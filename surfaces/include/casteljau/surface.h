/* casteljau: the common representation of surfaces (seed chapter 5).
 *
 * Two forms, each a small non-owning value struct: a callback plus a `data` pointer to the
 * definition it reads (a cj_quadric, a cj_torus, a Bézier patch, a deformation wrapper...).
 * The caller owns `data` and must keep it alive, unchanged, while the struct is used.
 * Nothing here allocates.
 *
 * PARAMETRIC  S : [u0,u1] x [v0,v1] -> R^3, with its first partial derivatives
 *             S_u = dS/du, S_v = dS/dv. Any code (tessellator, renderer, deformer) can treat
 *             every parametric surface the same way through cj_param_surface.
 *
 *   Orientation: the surface normal is n = S_u x S_v / |S_u x S_v|. Every closed surface of
 *   this library (sphere, ellipsoid, torus, closed profiles of revolution) is parametrised so
 *   that n points OUTWARD; a triangle whose (u,v) corners run counter-clockwise in the
 *   parameter plane is then counter-clockwise seen from outside. For open surfaces each
 *   constructor documents which side n points to (always the side where the implicit
 *   function, if any, is positive: n agrees in direction with the implicit gradient).
 *
 *   Closure flags tell a tessellator how the domain's edges are glued:
 *     CJ_SURF_PERIODIC_U   S(u0,v) == S(u1,v) for every v (e.g. the angle of revolution);
 *     CJ_SURF_PERIODIC_V   S(u,v0) == S(u,v1) for every u (e.g. a torus's tube angle);
 *     CJ_SURF_COLLAPSED_U0 the whole edge u = u0 maps to one point (a pole, a cone apex);
 *     CJ_SURF_COLLAPSED_U1, _V0, _V1 likewise for the other edges.
 *   On a collapsed edge S_u x S_v vanishes; the normal there is DEFINED as the limit of n as
 *   the point approaches the edge from the interior along the other parameter held fixed
 *   (for a smooth pole this limit is the same for every value of the other parameter; for a
 *   cone apex it is the normal of the generator line through that parameter value).
 *
 * IMPLICIT    f : R^3 -> R with gradient grad f. The surface is f = 0; by the library's
 *             convention f < 0 "inside" (the solid bounded by a closed surface, the region
 *             containing the axis for a hyperboloid of one sheet...), so grad f points outward.
 *
 * Status codes of the generic functions below:
 *   CJ_ERR_NONFINITE   u, v or a coordinate of x is NaN or infinite, or the callback produced
 *                      a non-finite value;
 *   CJ_ERR_RANGE       (u,v) outside the domain by more than the rounding slack (see below);
 *   CJ_ERR_DEGENERATE  the normal is undefined: S_u x S_v vanishes at (u,v) and no limit was
 *                      found, or grad f == 0 (a cone apex, a point off the surface where the
 *                      gradient vanishes);
 *   CJ_ERR_ARGUMENT    a malformed struct (cj_param_surface_check: empty or reversed domain,
 *                      missing callback);
 *   anything a callback returns is passed through unchanged.
 */
#ifndef CASTELJAU_SURFACE_H
#define CASTELJAU_SURFACE_H

#include "casteljau/status.h"
#include "casteljau/transform.h"
#include "casteljau/vec.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- parametric surfaces --------------------------------------------------------------- */

#define CJ_SURF_PERIODIC_U   0x01u
#define CJ_SURF_PERIODIC_V   0x02u
#define CJ_SURF_COLLAPSED_U0 0x04u
#define CJ_SURF_COLLAPSED_U1 0x08u
#define CJ_SURF_COLLAPSED_V0 0x10u
#define CJ_SURF_COLLAPSED_V1 0x20u

/* Writes S(u,v) to *p and the partials to *su, *sv (all three non-NULL). Called only with
 * finite (u,v) inside the domain; must not allocate. Returns CJ_OK or a status (through
 * cj_fail) if the definition cannot be evaluated there. */
typedef cj_status (*cj_surface_eval_fn)(const void *data, double u, double v, cj_vec3 *p,
                                        cj_vec3 *su, cj_vec3 *sv);

/* Optional: writes the UNIT normal at (u,v) including its limit on collapsed edges and other
 * singular points (see the orientation rules above). Called only with valid (u,v). */
typedef cj_status (*cj_surface_normal_fn)(const void *data, double u, double v, cj_vec3 *n);

typedef struct cj_param_surface {
    cj_surface_eval_fn eval;     /* required */
    cj_surface_normal_fn normal; /* may be NULL: cj_surface_normal then uses S_u x S_v and,
                                    where it vanishes, the limit rule by a one-sided nudge */
    const void *data;            /* the definition, owned by the caller */
    double u0, u1, v0, v1;       /* the domain; u0 < u1, v0 < v1 */
    unsigned flags;              /* CJ_SURF_* closure flags */
    const char *name;            /* static description for messages ("ellipsoid"), or NULL */
} cj_param_surface;

/* Validates the struct itself: eval non-NULL, finite domain with u0 < u1 and v0 < v1. */
cj_status cj_param_surface_check(const cj_param_surface *s);

/* Relative slack accepted on the domain: a parameter up to CJ_SURF_DOMAIN_SLACK*(u1-u0)
 * outside [u0,u1] (rounding in u0 + i*(u1-u0)/n) is clamped to the edge; beyond that
 * CJ_ERR_RANGE. */
#define CJ_SURF_DOMAIN_SLACK 1e-12

/* S(u,v) and its partials. su and sv may be NULL when not wanted. */
cj_status cj_surface_eval(const cj_param_surface *s, double u, double v, cj_vec3 *p, cj_vec3 *su,
                          cj_vec3 *sv);

/* The unit normal at (u,v): s->normal if provided; else S_u x S_v normalised when
 *   |S_u x S_v| > 1e-12 |S_u| |S_v|   (and both partials are non-zero);
 * else (a collapsed edge or another singular point) the limit rule above approximated by
 * the cross product at a point moved into the interior by 1e-7 of the domain width along the
 * parameter that reaches the singular edge (approximation error O(1e-7) in direction).
 * CJ_ERR_DEGENERATE if that also vanishes. */
cj_status cj_surface_normal(const cj_param_surface *s, double u, double v, cj_vec3 *n);

/* ---- implicit surfaces ----------------------------------------------------------------- */

/* Writes f(x) to *f and grad f(x) to *grad (both non-NULL). Must not allocate. */
typedef cj_status (*cj_implicit_fn)(const void *data, cj_vec3 x, double *f, cj_vec3 *grad);

typedef struct cj_implicit_surface {
    cj_implicit_fn eval; /* required */
    const void *data;    /* the definition, owned by the caller */
    const char *name;    /* static description for messages, or NULL */
} cj_implicit_surface;

/* f(x) and grad f(x) (grad may be NULL). CJ_ERR_NONFINITE for a non-finite x. */
cj_status cj_implicit_eval(const cj_implicit_surface *s, cj_vec3 x, double *f, cj_vec3 *grad);

/* grad f(x) / |grad f(x)|; CJ_ERR_DEGENERATE where the gradient is zero. */
cj_status cj_implicit_normal(const cj_implicit_surface *s, cj_vec3 x, cj_vec3 *n);

/* ---- planar curves (profiles and cylinder directrices) ---------------------------------- */

/* Writes c(t), c'(t), c''(t) to d[0], d[1], d[2]. Called only with t in [t0,t1]. */
typedef cj_status (*cj_curve2_fn)(const void *data, double t, cj_vec2 d[3]);

/* A planar curve c : [t0,t1] -> R^2 given by a callback (or a Bézier curve, below). */
typedef struct cj_curve2 {
    cj_curve2_fn eval;
    const void *data; /* owned by the caller */
    double t0, t1;    /* t0 < t1 */
    int closed;       /* non-zero if c(t0) == c(t1) and the curve should be treated as a loop */
} cj_curve2;

/* Views a 2D Bézier curve (dim must be 2) as a cj_curve2 on [0,1]. `closed` is set when the
 * first and last control points are identical. The cj_bezier struct and its points must
 * outlive *out. CJ_ERR_DIMENSION, CJ_ERR_DEGREE, CJ_ERR_NONFINITE as cj_bezier_check. */
struct cj_bezier;
cj_status cj_curve2_from_bezier(const struct cj_bezier *b, cj_curve2 *out);

/* Views a 2D rational Bézier curve (dim 2, weights > 0) as a cj_curve2 on [0,1]: exact conic
 * profiles (cj_rbezier_ellipse_arc) give exact spheres, tori and cones of revolution. Same
 * ownership and `closed` rule as cj_curve2_from_bezier; errors of cj_rbezier_check, and
 * CJ_ERR_DIMENSION for dim != 2. */
struct cj_rbezier;
cj_status cj_curve2_from_rbezier(const struct cj_rbezier *b, cj_curve2 *out);

/* Validates the struct: eval non-NULL, finite t0 < t1. */
cj_status cj_curve2_check(const cj_curve2 *c);

/* ---- placing a surface: affine transforms ----------------------------------------------- */

/* A surface moved by an affine map x -> M x = L x + t (cj_xform3 of transform.h with last row
 * 0 0 0 1). Parametric: S'(u,v) = M S(u,v), S'_u = L S_u, S'_v = L S_v, normal
 * cof(L) n_S / |.| (cof(L) = det(L) L^-T, so the normal is exactly the direction of
 * S'_u x S'_v, pole limits included, and CCW-in-(u,v) triangles stay CCW seen from the
 * normal's side). Implicit: f'(x) = f(M^-1 x), grad f'(x) = L^-T grad f(M^-1 x), so "inside"
 * stays inside. A mirroring map (det L < 0) therefore turns the parametric normal of a closed
 * surface INWARD while the implicit gradient stays outward: compose with a reflection of the
 * parameter (or avoid mirrors) where outward parametric normals matter.
 * Both structs hold copies of the map, its inverse and the base view (the base's own `data`
 * must stay alive); `out->data` points at the storage struct. Domain and flags are the base's.
 * Status: CJ_ERR_NONFINITE (a NaN/Inf matrix entry), CJ_ERR_UNSUPPORTED (a projective matrix:
 * last row not 0 0 0 1), CJ_ERR_SINGULAR (L not invertible to working precision), and the
 * base's cj_param_surface_check errors. */
typedef struct cj_transformed_surface {
    double m[3][4];    /* L | t */
    double minv[3][4]; /* L^-1 | -L^-1 t */
    double cof[3][3];  /* det(L) L^-T */
    cj_param_surface base;
    cj_implicit_surface ibase;
} cj_transformed_surface;

cj_status cj_surface_transform(const cj_xform3 *m, const cj_param_surface *base,
                               cj_transformed_surface *storage, cj_param_surface *out);
cj_status cj_implicit_transform(const cj_xform3 *m, const cj_implicit_surface *base,
                                cj_transformed_surface *storage, cj_implicit_surface *out);

/* ---- frames ---------------------------------------------------------------------------- */

/* A right-handed orthonormal frame (e1, e2, a) around the unit vector a, continuous in a
 * except where a == -z. a must be unit length (not checked). */
void cj_frame_from_axis(cj_vec3 a, cj_vec3 *e1, cj_vec3 *e2);

#ifdef __cplusplus
}
#endif
#endif

/* casteljau: ray–surface intersection (seed 11.3, 11.6): watertight triangles, planar
 * polygons, spheres, cylinders, every quadric of casteljau/quadric.h, the torus, planar,
 * bilinear and Bézier patches (directly, without tessellating), and affinely placed objects.
 *
 * A RAY is  r(t) = org + t dir,  t in [tmin, tmax]  (dir need not be unit length; t is measured
 * in units of |dir|). A HIT records the parameter t, the point, the normal of the SURFACE at
 * the point (exact surface normal, not a mesh's), the surface parameters (u, v), the index of
 * the primitive hit, and a per-coordinate bound p_err on the distance from the computed point
 * to the true surface (so a secondary ray can be started on the correct side without a fixed
 * epsilon: cj_ray_offset_origin).
 *
 * CONVENTIONS. Intersection functions are hot paths: they return 1 and fill *hit when the
 * surface is hit at some t in [tmin, tmax] (the smallest such t), 0 otherwise; they never fail
 * and never allocate. A ray or a primitive with NaN/Inf components simply never hits (every
 * comparison with NaN is false); validate inputs once with cj_ray_check and the surfaces'
 * own constructors. `hit->n` is the surface's oriented normal (outward for closed surfaces,
 * S_u × S_v for patches, (b−a)×(c−a) for triangles): it is NOT flipped towards the ray;
 * `hit->ng` is the normal of the primitive actually hit (the triangle's plane, or the same as
 * n for exact surfaces), with the same orientation.
 */
#ifndef CASTELJAU_RAY_H
#define CASTELJAU_RAY_H

#include "casteljau/analytic.h"
#include "casteljau/patch.h"
#include "casteljau/quadric.h"
#include "casteljau/status.h"
#include "casteljau/transform.h"
#include "casteljau/vec.h"
#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct cj_ray {
    cj_vec3 org, dir; /* dir != 0 */
    double tmin, tmax;
} cj_ray;

typedef struct cj_hit {
    double t;      /* ray parameter of the hit */
    cj_vec3 p;     /* the hit point (on the surface to within p_err) */
    cj_vec3 n;     /* unit surface normal at p (oriented as the surface, not towards the ray) */
    cj_vec3 ng;    /* unit normal of the primitive hit (triangle plane; = n for exact ones) */
    double u, v;   /* surface parameters (triangles: barycentrics of vertices 1 and 2) */
    cj_vec3 p_err; /* |p_k − (true surface point)_k| <= p_err_k, k = x, y, z */
    uint32_t prim; /* primitive index (triangle, patch) within its object; set by callers */
    uint32_t obj;  /* object index; set by callers (BVH over objects, the tracer) */
    double err;    /* patches: distance from p to the ray line reached by Newton (<= tol);
                      other primitives: 0 */
} cj_hit;

/* Validates a ray: finite org and dir, dir != 0, tmin <= tmax, tmin not NaN (tmax may be
 * +inf). CJ_ERR_NONFINITE / CJ_ERR_DEGENERATE / CJ_ERR_RANGE naming the field. */
cj_status cj_ray_check(const cj_ray *ray);

/* ---- secondary rays without a fixed epsilon (Wächter and Binder 2019 style) ------------- */

/* The origin for a ray leaving the hit point p towards direction w: p moved along the normal
 * ng by d = max(|ng_x| p_err_x + |ng_y| p_err_y + |ng_z| p_err_z, 4u max_k |p_k|) to the side w
 * points to, each coordinate then rounded one ulp further (in the direction of ng's component). The
 * true surface lies within p_err of p, so the new origin is strictly on w's side of the surface (up
 * to the surface's curvature over the distance d, which is of the order of the rounding error) and
 * a ray started there with tmin = 0 cannot hit the surface it leaves at t ≈ 0. The offset scales
 * with the magnitude of the coordinates and the accuracy of the intersection: it is neither too
 * small at 1e6 scale (acne) nor too large at 1e-6 scale (light leaking). */
cj_vec3 cj_ray_offset_origin(const cj_hit *hit, cj_vec3 w);

/* ---- triangles (watertight) -------------------------------------------------------------- */

/* Watertight ray–triangle intersection (Woop, Benthin and Wald 2013): the vertices are
 * translated to the ray origin, sheared and scaled so the ray runs along +z' through the
 * origin of the (x', y') plane (the coordinate kz with the largest |dir| becomes z'), and the
 * three 2D edge functions of the origin against the transformed vertices decide. Each edge
 * function depends only on the edge's two transformed vertices, and each transformed vertex
 * only on the vertex, so triangles sharing an edge compute exactly opposite values on it.
 * Edge function signs are exact: when the product difference is within its rounding bound
 * it is recomputed with fma (Kahan's 2×2 determinant, whose sign is always right). A zero edge
 * function (the ray exactly through an edge or vertex in the transformed plane) is resolved by
 * a tie-break rule equivalent to moving the ray by (ε, −ε²) in the (x', y') plane (a
 * "top-left" rule on the triangle oriented counter-clockwise in that plane), so a ray through
 * a shared edge or vertex of a mesh hits EXACTLY ONE of the triangles around it (no miss, no
 * double hit) wherever the mesh does not fold over itself in the ray's view. Triangles seen
 * edge-on (zero transformed area) are missed. Both faces are hit.
 * hit: t, p (barycentric combination, error bound γ(7) Σ|b_i v_i|), n = ng = the unit
 * (v1−v0)×(v2−v0), (u, v) = barycentrics (b1, b2), err = 0; prim untouched. */
int cj_ray_triangle(const cj_ray *ray, cj_vec3 v0, cj_vec3 v1, cj_vec3 v2, cj_hit *hit);

/* The same test with a precomputed ray transform (one per ray, reused for every triangle). */
typedef struct cj_ray_tri_pre {
    int kx, ky, kz;
    double sx, sy, sz;
} cj_ray_tri_pre;
void cj_ray_triangle_prepare(const cj_ray *ray, cj_ray_tri_pre *pre);
int cj_ray_triangle_pre(const cj_ray *ray, const cj_ray_tri_pre *pre, cj_vec3 v0, cj_vec3 v1,
                        cj_vec3 v2, cj_hit *hit);

/* ---- planar polygons ----------------------------------------------------------------------- */

/* A planar polygon of `count` >= 3 vertices (xyz per vertex, any winding, convex or not) with
 * its plane normal (the Newell normal of the vertices) and the crossing-number rule (even–odd)
 * in the projection that drops the normal's largest coordinate; half-open crossing tests make
 * polygons sharing an edge hit exactly once through their shared edge's interior.
 * n = ng = unit Newell normal (counter-clockwise vertices seen from the side it points to),
 * (u, v) = the hit's coordinates along the first edge and its perpendicular in the plane.
 * Degenerate polygons (zero area) are missed. */
int cj_ray_polygon(const cj_ray *ray, const double *pts, size_t count, cj_hit *hit);

/* ---- exact surfaces in canonical or placed form ----------------------------------------------
 * Quadratics are solved with the stable formula q = −(b' + sign(b') sqrt(b'² − ac)), roots
 * q/a and c/q, after moving the ray origin to the point of the ray where the quadratic is
 * extremal (t0 = −b'/a), which removes the cancellation of b'² − ac for grazing rays and
 * far-away origins; each root is then polished by one Newton step on f(org + t dir).
 * p = org + t dir, p_err = 2 (|f(p)| + e_f) / |grad f(p)| per coordinate plus the rounding of
 * p, where e_f is the rounding bound of evaluating f at p (a first-order bound on the distance
 * from p to the surface, doubled for the second-order term). */

/* Sphere |x − c| = r: n outward, (u, v) the ellipsoid angles of quadric.h about the z axis. */
int cj_ray_sphere(const cj_ray *ray, cj_vec3 center, double radius, cj_hit *hit);

/* A quadric of quadric.h (canonical position), its parameter domain respected (v0..v1, the
 * sheet of a hyperboloid of two sheets, u0..u1 of the hyperbolic paraboloid). n = grad f
 * normalised (the parametric normal's direction, see quadric.h); at the cone's apex (zero
 * gradient) n = −dir normalised. (u, v) the parameters of quadric.h. */
int cj_ray_quadric(const cj_ray *ray, const cj_quadric *q, cj_hit *hit);

/* The right circular cylinder of analytic.h (no caps), v in [h0, h1]. */
int cj_ray_cylinder(const cj_ray *ray, const cj_cylinder *cy, cj_hit *hit);

/* The torus of analytic.h: the quartic g(s) = (|w|² + R² − ρ²)² − 4R²(|w|² − (w·a)²) in the
 * torus frame with the origin moved to the ray's point nearest the centre and dir normalised
 * (so the cubic coefficient vanishes and the coefficients are of the torus's scale), on the
 * part of the ray inside the bounding sphere |w| <= R + ρ. Roots are ISOLATED, not guessed:
 * the quadratic g'' splits the interval into pieces where g' is monotone, their sign changes
 * give g's critical points (safeguarded Newton–bisection), which split it into pieces where g
 * is monotone; each sign change of g (evaluated in the geometric form above, not from the
 * coefficients) is a root found by safeguarded Newton–bisection to full precision. A critical
 * point where |g| is within the rounding bound of its evaluation is a tangent (grazing) hit.
 * n outward, (u, v) the torus angles in [0, 2pi). */
int cj_ray_torus(const cj_ray *ray, const cj_torus *to, cj_hit *hit);

/* Planar patch (parallelogram) p + u eu + v ev, (u, v) in [0, 1]²: n = the plane's normal. */
int cj_ray_planar(const cj_ray *ray, const cj_planar_patch *pp, cj_hit *hit);

/* ---- patches, directly ----------------------------------------------------------------------- */

/* Largest degree per direction intersected directly (subdivision work space on the stack). */
#define CJ_RAY_PATCH_MAX_DEGREE 8

typedef struct cj_ray_patch_stats {
    uint64_t boxes;     /* sub-patch bounding boxes tested */
    uint64_t newton;    /* Newton solves started */
    uint64_t newton_ok; /* converged to tol inside their sub-patch */
    double max_err;     /* largest distance to the ray line accepted */
} cj_ray_patch_stats;

/* A Bézier patch (polynomial or rational, degrees <= CJ_RAY_PATCH_MAX_DEGREE) intersected
 * directly by subdivision plus Newton: the ray is written as the intersection of two planes
 * (n1·x = d1, n2·x = d2 with n1, n2, dir orthonormal up to |dir|), sub-patches whose control
 * net's box misses the ray (in those plane distances and in t) are discarded, the others are
 * halved along their longer side until the net is flat (every control point within 1/8 of its
 * box's diagonal of the bilinear patch of its corners) and Newton's method on
 * F(u, v) = (n1·S(u,v) − d1, n2·S(u,v) − d2) is started at the sub-patch centre. A solve is
 * accepted when |F| <= tol (the distance from S(u, v) to the ray line: `tol` is in world
 * units, > 0) and (u, v) lies in the sub-patch (up to 1e-9): otherwise the sub-patch is split
 * further, down to a box diagonal below tol or 40 splits (a grazing ray at a silhouette or a
 * degenerate corner, where Newton's Jacobian is singular), and a box the ray passes through is
 * then accepted as a hit at its centre. A candidate nearer the ray's tmin than its own error
 * is rejected (it is the surface a secondary ray starts from). p = S(u, v), which lies on the
 * patch (p_err = the evaluation bound γ(3(m+n)+8) max|b_ij|), and hit->err = the distance from
 * p to the ray line actually reached: <= tol after Newton, the box size after the split cap
 * (reported, e.g. as max_err in the tracer's stage report). n = cj_patch_normal (pole limits
 * included). stats (may be NULL) accumulates counters. Degree above the cap,
 * tol <= 0: no hit (validate with cj_ray_patch_check). */
int cj_ray_patch(const cj_ray *ray, const cj_patch *patch, double tol, cj_hit *hit,
                 cj_ray_patch_stats *stats);

/* CJ_ERR_DEGREE for a degree above CJ_RAY_PATCH_MAX_DEGREE, CJ_ERR_ARGUMENT for tol <= 0 or
 * NaN, and cj_patch_check's errors. */
cj_status cj_ray_patch_check(const cj_patch *patch, double tol);

/* The bilinear patch of analytic.h as a degree (1, 1) Bézier patch through cj_ray_patch. */
int cj_ray_bilinear(const cj_ray *ray, const cj_bilinear *bl, double tol, cj_hit *hit);

/* ---- affinely placed objects (seed 11.3.4, 11.6.1) ---------------------------------------- */

/* An object placed by the affine map x -> M x: rays are carried into object space by M^-1
 * (the parameter t is unchanged, since the map is affine and dir is not renormalised), the
 * object intersected there, and the hit carried back: p by M, the normals by M^-T
 * (renormalised), p_err by |L| p_err + the rounding of M p. */
typedef struct cj_ray_xform {
    cj_xform3 m, minv;
    double nrm[3][3]; /* L^-T */
} cj_ray_xform;

/* CJ_ERR_UNSUPPORTED (projective matrix), CJ_ERR_SINGULAR, CJ_ERR_NONFINITE. */
cj_status cj_ray_xform_init(cj_ray_xform *x, const cj_xform3 *m);
/* The ray in object space (same tmin, tmax). */
void cj_ray_to_object(const cj_ray_xform *x, const cj_ray *ray, cj_ray *out);
/* An object-space hit to world space (t, u, v, prim, obj, err kept). */
void cj_hit_to_world(const cj_ray_xform *x, cj_hit *hit);

/* ---- axis-aligned boxes ------------------------------------------------------------------ */

typedef struct cj_aabb {
    double lo[3], hi[3];
} cj_aabb;

/* The empty box (lo = +inf, hi = −inf), growing and merging. */
cj_aabb cj_aabb_empty(void);
void cj_aabb_grow(cj_aabb *b, cj_vec3 p);
void cj_aabb_merge(cj_aabb *b, const cj_aabb *c);
/* Surface area (0 for an empty box). */
double cj_aabb_area(const cj_aabb *b);

/* Slab test against [tmin, tmax] given 1/dir per coordinate (inf allowed); the far distance is
 * enlarged by 1 + 2γ(3) so rounding never loses a box the ray touches (PBRT's robust test).
 * Returns 1 and the entry/exit parameters when the ray meets the box. */
int cj_aabb_ray(const cj_aabb *b, cj_vec3 org, cj_vec3 inv_dir, double tmin, double tmax,
                double *t0, double *t1);

/* Boxes of the primitives above (conservative). */
cj_aabb cj_aabb_triangle(cj_vec3 v0, cj_vec3 v1, cj_vec3 v2);
cj_aabb cj_aabb_quadric(const cj_quadric *q);
cj_aabb cj_aabb_torus(const cj_torus *to);
cj_aabb cj_aabb_cylinder(const cj_cylinder *cy);
/* The box of the control net (contains the patch); rational: of the Euclidean points. */
cj_aabb cj_aabb_patch(const cj_patch *p);
/* The box of an object-space box mapped by x (its 8 corners), enlarged for rounding. */
cj_aabb cj_aabb_transform(const cj_ray_xform *x, const cj_aabb *b);

#ifdef __cplusplus
}
#endif
#endif

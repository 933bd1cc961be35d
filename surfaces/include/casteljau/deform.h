/* casteljau: nonlinear global deformations of seed 5.7 (after Barr 1984) — taper and twist
 * about an axis — applied to points, normals, parametric surfaces and meshes.
 *
 * The axis is a point `origin` and a direction `a` (normalised on construction), completed to
 * a right-handed orthonormal frame (e1, e2, a) by cj_frame_from_axis. In local coordinates
 *     x = (p - origin).e1,   y = (p - origin).e2,   s = (p - origin).a
 * the deformations are
 *     TAPER   (x, y, s) -> (r(s) x, r(s) y, s),      r(s) = k0 + k1 s + k2 s^2
 *             (linear taper: k2 = 0; the classical one has k0 = 1)
 *     TWIST   (x, y, s) -> (x cos t - y sin t, x sin t + y cos t, s),   t(s) = rate * s
 *             (rate in radians per unit length along the axis)
 * and the result is mapped back with the same frame.
 *
 * Normals. A surface with tangents T transforms as T -> J T (J the Jacobian at the undeformed
 * point), so its normal transforms by the inverse transpose: n -> J^{-T} n. This library uses
 * the cofactor matrix cof(J) = det(J) J^{-T}, which gives EXACTLY the direction of
 * (J S_u) x (J S_v) = cof(J) (S_u x S_v) — so the deformed normal keeps the orientation of the
 * parametrisation even where det J < 0. In local coordinates, analytically:
 *     TAPER   cof(J) n = r * (n_x, n_y, r n_z - r'(s) (x n_x + y n_y)),   det J = r^2
 *     TWIST   cof(J) n = (R(t) (n_x, n_y), n_z - rate (x n_y - y n_x)),    det J = 1
 * (R(t) the rotation by t in the (e1, e2) plane). Where a taper has r(s) = 0 the map
 * collapses a whole cross-section to a point and the normal is undefined (CJ_ERR_DEGENERATE).
 *
 * Status codes:
 *   CJ_ERR_NONFINITE   a NaN/Inf in an origin, axis, coefficient, point or normal (named), or
 *                      a result that overflowed;
 *   CJ_ERR_DEGENERATE  a zero-length axis or normal; taper coefficients all zero; r(s) = 0 at
 *                      a point whose normal is asked for (the vertex index is named).
 */
#ifndef CASTELJAU_DEFORM_H
#define CASTELJAU_DEFORM_H

#include "casteljau/mesh.h"
#include "casteljau/surface.h"
#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef enum cj_deform_kind { CJ_DEFORM_TAPER = 0, CJ_DEFORM_TWIST } cj_deform_kind;

/* Filled by the constructors, which validate; read-only afterwards. */
typedef struct cj_deform {
    cj_deform_kind kind;
    cj_vec3 origin, a, e1, e2; /* axis point and right-handed orthonormal frame (e1, e2, a) */
    double k0, k1, k2;         /* taper profile r(s) = k0 + k1 s + k2 s^2 */
    double rate;               /* twist rate, radians per unit length */
} cj_deform;

/* Taper with r(s) = k0 + k1 s + k2 s^2 (linear: k2 = 0). */
cj_status cj_deform_taper(cj_deform *d, cj_vec3 origin, cj_vec3 axis, double k0, double k1,
                          double k2);
/* Twist by `rate` radians per unit length (rate = 0 is the identity, allowed). */
cj_status cj_deform_twist(cj_deform *d, cj_vec3 origin, cj_vec3 axis, double rate);

/* The deformed point D(p). */
cj_status cj_deform_point(const cj_deform *d, cj_vec3 p, cj_vec3 *out);

/* The Jacobian J = dD/dp at p in world coordinates, row-major: J[i][j] = dD_i/dp_j. */
cj_status cj_deform_jacobian(const cj_deform *d, cj_vec3 p, double J[3][3]);

/* The tangent vector t at p mapped to J t (exact chain rule). */
cj_status cj_deform_tangent(const cj_deform *d, cj_vec3 p, cj_vec3 t, cj_vec3 *out);

/* The UNIT normal after deformation of a surface with normal n (any non-zero length) at the
 * UNDEFORMED point p: cof(J(p)) n normalised (see above). */
cj_status cj_deform_normal(const cj_deform *d, cj_vec3 p, cj_vec3 n, cj_vec3 *out);

/* Deforms `count` vertices in place: positions pos[3i..3i+2] and, if nrm != NULL, unit
 * normals nrm[3i..3i+2] (each normal uses its vertex's undeformed position; a zero normal
 * means "unknown", as in cj_mesh, and stays zero). This is the layout of cj_mesh (mesh.h):
 * cj_deform_vertices(d, mesh->positions, mesh->normals, mesh->vertex_count). Validates and
 * computes everything before writing anything: on failure both arrays are untouched and the
 * message names the vertex. count == 0 is CJ_OK. Allocation-free. */
cj_status cj_deform_vertices(const cj_deform *d, double *pos, double *nrm, size_t count);

/* Deforms a whole cj_mesh in place (positions and normals; uvs, triangles and patch ids are
 * unchanged): cj_deform_vertices on its arrays, with the same all-or-nothing rule. Both
 * deformations have det J > 0 wherever the normal is defined (twist: 1; taper: r(s)^2, a
 * negative r turns the cross-section by pi, it does not mirror it), so counter-clockwise
 * triangles stay counter-clockwise seen from the side the normals point to. */
cj_status cj_deform_mesh(const cj_deform *d, cj_mesh *mesh);

/* A deformed parametric surface D(S(u,v)): partials J S_u, J S_v; normal cof(J) n_S where n_S
 * is cj_surface_normal of the base (so pole limits carry over). Same domain and closure flags
 * as the base. The struct holds copies of the deformation and of the base view (the base's
 * own `data` must stay alive). */
typedef struct cj_deformed_surface {
    cj_deform def;
    cj_param_surface base;
} cj_deformed_surface;

/* Fills *storage and makes *out a view of it (out->data = storage: keep storage alive).
 * Validates the base view (cj_param_surface_check). */
cj_status cj_deform_surface(const cj_deform *d, const cj_param_surface *base,
                            cj_deformed_surface *storage, cj_param_surface *out);

#ifdef __cplusplus
}
#endif
#endif

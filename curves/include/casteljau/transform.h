/* casteljau: affine and projective transforms in homogeneous coordinates.
 *
 * cj_xform2 is a 3x3 matrix acting on 2D points (x, y, 1) and vectors (x, y, 0); cj_xform3 is a
 * 4x4 matrix acting on (x, y, z, 1) and (x, y, z, 0). Matrices are row-major, m[row][col], and
 * act on column vectors: p' = M p. Composition cj_xform*_compose(A, B) = A B means "B first,
 * then A".
 *
 *   point  (w = 1):  (x', y', w') = M (x, y, 1), result (x'/w', y'/w'); w' = 0 (a point mapped
 *                    to infinity by a projective matrix) is CJ_ERR_DEGENERATE.
 *   vector (w = 0):  L v, L the upper-left linear block (the translation does not act).
 *   normal:          L^-T n (inverse transpose), so that a normal stays perpendicular to the
 *                    transformed tangent line/plane; not renormalised (the caller normalises);
 *                    singular L is CJ_ERR_SINGULAR.
 *
 * Affine invariance of Bézier curves: for an affine matrix (last row 0..0 1) transforming the
 * control points transforms the curve. A projective matrix maps a polynomial curve to a
 * rational one; cj_xform*_apply_points then gives only the divided control points, which is
 * NOT the image of the curve.
 *
 * Constructors return by value and do not validate (a NaN angle gives a NaN matrix); every
 * function that returns a cj_status validates its matrix and inputs (CJ_ERR_NONFINITE naming
 * the entry). Angles are in radians, counter-clockwise (right-handed in 3D: rotation about an
 * axis is counter-clockwise seen from the axis tip looking to the origin).
 */
#ifndef CASTELJAU_TRANSFORM_H
#define CASTELJAU_TRANSFORM_H

#include "casteljau/status.h"
#include "casteljau/vec.h"
#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct cj_xform2 {
    double m[3][3];
} cj_xform2;

typedef struct cj_xform3 {
    double m[4][4];
} cj_xform3;

/* ---- 2D ------------------------------------------------------------------------------ */

cj_xform2 cj_xform2_identity(void);
/* p' = p + (tx, ty). */
cj_xform2 cj_xform2_translate(double tx, double ty);
/* Rotation about the origin by `angle` radians, counter-clockwise. */
cj_xform2 cj_xform2_rotate(double angle);
/* x' = sx x, y' = sy y (sx = sy: uniform scale; a negative factor mirrors). */
cj_xform2 cj_xform2_scale(double sx, double sy);
/* x' = x + shx y, y' = shy x + y. */
cj_xform2 cj_xform2_shear(double shx, double shy);
/* Reflection about the line through the origin with direction `dir`: I - 2 n n^T, n the unit
 * normal of the line. Zero direction: CJ_ERR_DEGENERATE; non-finite: CJ_ERR_NONFINITE. */
cj_status cj_xform2_reflect(cj_vec2 dir, cj_xform2 *out);
/* A B: apply b first, then a. */
cj_xform2 cj_xform2_compose(const cj_xform2 *a, const cj_xform2 *b);
/* Inverse by Gauss–Jordan elimination with partial pivoting. CJ_ERR_SINGULAR when a pivot
 * falls to 16 u max|m_ij| or below (the matrix is singular to working precision, estimated
 * condition number above ~ 2.8e14); CJ_ERR_NONFINITE for a NaN/Inf entry. */
cj_status cj_xform2_inverse(const cj_xform2 *m, cj_xform2 *inv);
/* 1 if the last row is exactly (0, 0, 1). */
int cj_xform2_is_affine(const cj_xform2 *m);
cj_status cj_xform2_apply_point(const cj_xform2 *m, cj_vec2 p, cj_vec2 *out);
cj_status cj_xform2_apply_vector(const cj_xform2 *m, cj_vec2 v, cj_vec2 *out);
cj_status cj_xform2_apply_normal(const cj_xform2 *m, cj_vec2 n, cj_vec2 *out);
/* Transforms `count` 2D points stored x,y,x,y,... (a control-point array of dimension 2) as
 * points (w = 1). out may equal in. Everything is validated (and every w' checked) before
 * anything is written, so on failure out is untouched. */
cj_status cj_xform2_apply_points(const cj_xform2 *m, const double *in, size_t count, double *out);

/* ---- 3D ------------------------------------------------------------------------------ */

cj_xform3 cj_xform3_identity(void);
cj_xform3 cj_xform3_translate(double tx, double ty, double tz);
cj_xform3 cj_xform3_rotate_x(double angle);
cj_xform3 cj_xform3_rotate_y(double angle);
cj_xform3 cj_xform3_rotate_z(double angle);
/* Rotation by `angle` about the axis through the origin with direction `axis` (Rodrigues:
 * R = I + sin(a) K + (1 - cos(a)) K^2, K the cross-product matrix of the unit axis).
 * Zero axis: CJ_ERR_DEGENERATE; non-finite axis or angle: CJ_ERR_NONFINITE. */
cj_status cj_xform3_rotate_axis(cj_vec3 axis, double angle, cj_xform3 *out);
cj_xform3 cj_xform3_scale(double sx, double sy, double sz);
/* x' = x + xy y + xz z,  y' = yx x + y + yz z,  z' = zx x + zy y + z. */
cj_xform3 cj_xform3_shear(double xy, double xz, double yx, double yz, double zx, double zy);
/* Reflection about the plane through the origin with normal `normal`: I - 2 n n^T / |n|^2.
 * Zero normal: CJ_ERR_DEGENERATE; non-finite: CJ_ERR_NONFINITE. */
cj_status cj_xform3_reflect(cj_vec3 normal, cj_xform3 *out);
cj_xform3 cj_xform3_compose(const cj_xform3 *a, const cj_xform3 *b);
/* As cj_xform2_inverse, 4x4. */
cj_status cj_xform3_inverse(const cj_xform3 *m, cj_xform3 *inv);
int cj_xform3_is_affine(const cj_xform3 *m);
cj_status cj_xform3_apply_point(const cj_xform3 *m, cj_vec3 p, cj_vec3 *out);
cj_status cj_xform3_apply_vector(const cj_xform3 *m, cj_vec3 v, cj_vec3 *out);
cj_status cj_xform3_apply_normal(const cj_xform3 *m, cj_vec3 n, cj_vec3 *out);
/* As cj_xform2_apply_points, for x,y,z,x,y,z,... */
cj_status cj_xform3_apply_points(const cj_xform3 *m, const double *in, size_t count, double *out);

#ifdef __cplusplus
}
#endif
#endif

/* casteljau: the quadrics of seed chapter 5 in canonical position (centre or vertex at the
 * origin, axes along x, y, z), each in implicit form f(x,y,z) with its gradient and in
 * parametric form. Semi-axes a, b, c must be finite and > 0.
 *
 *  ELLIPSOID              f = x²/a² + y²/b² + z²/c² - 1
 *      S = (a cos v cos u, b cos v sin u, c sin v),   v in [-pi/2, pi/2]; poles at v = ±pi/2
 *  HYPERBOLOID1 (one sheet)   f = x²/a² + y²/b² - z²/c² - 1
 *      S = (a cosh v cos u, b cosh v sin u, c sinh v),   v in [v0, v1]; no singular point
 *  HYPERBOLOID2 (two sheets)  f = x²/a² + y²/b² - z²/c² + 1
 *      upper sheet (z > 0): S = (a sinh v cos u, b sinh v sin u, c cosh v); lower sheet: the
 *      upper one turned by pi about x, (x, -y, -z);   v in [0, v1]; pole (vertex) at v = 0
 *  CONE (elliptic)        f = x²/a² + y²/b² - z²/c²
 *      S = (a v cos u, b v sin u, c v),   v in [v0, v1]; apex at v = 0
 *  PARABOLOID (elliptic)  f = x²/a² + y²/b² - z
 *      S = (a v cos u, b v sin u, v²),   v in [0, v1]; pole (vertex) at v = 0
 *  HYPERBOLIC_PARABOLOID  f = z - x²/a² + y²/b²
 *      S = (a u, b v, u² - v²),   u in [u0, u1], v in [v0, v1]; no singular point
 * In all but the last, u in [0, 2pi] is the angle about the z axis. f < 0 is "inside".
 *
 * (c is unused by the two paraboloids.) The parametric normal S_u x S_v / |S_u x S_v| points
 * the same way as grad f everywhere (outward for the ellipsoid; away from the axis for the
 * hyperboloid of one sheet and the cone; away from the solid bowl for the hyperboloid of two
 * sheets and the elliptic paraboloid (down at the vertex); up (+z side of the saddle) for the
 * hyperbolic paraboloid). It is computed from the partials with the vanishing factor divided
 * out analytically, so it is exact and continuous up to and including the poles:
 *   ellipsoid        S_u x S_v = cos v   (bc cos v cos u, ac cos v sin u, ab sin v)
 *   hyperboloid 1    S_u x S_v = cosh v  (bc cosh v cos u, ac cosh v sin u, -ab sinh v)
 *   hyperboloid 2    S_u x S_v = sinh v  (bc sinh v cos u, ac sinh v sin u, -ab cosh v)
 *   cone             S_u x S_v = v       (bc cos u, ac sin u, -ab)
 *   paraboloid       S_u x S_v = v       (2bv cos u, 2av sin u, -ab)
 * At the cone's apex (v = 0) the limit along the generator at angle u is returned, taking
 * the side of the domain the apex is approached from (v0 = 0: v > 0; v1 = 0: v < 0; apex
 * inside the domain: v > 0); the implicit gradient there is zero (CJ_ERR_DEGENERATE).
 *
 * u is periodic (CJ_SURF_PERIODIC_U) for all but the hyperbolic paraboloid. Collapsed edges:
 * ellipsoid V0 and V1; hyperboloid 2 and paraboloid V0; cone V0 if v0 == 0 and V1 if v1 == 0.
 */
#ifndef CASTELJAU_QUADRIC_H
#define CASTELJAU_QUADRIC_H

#include "casteljau/surface.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum cj_quadric_kind {
    CJ_QUADRIC_ELLIPSOID = 0,
    CJ_QUADRIC_HYPERBOLOID1,
    CJ_QUADRIC_HYPERBOLOID2,
    CJ_QUADRIC_CONE,
    CJ_QUADRIC_PARABOLOID,
    CJ_QUADRIC_HYPERBOLIC_PARABOLOID
} cj_quadric_kind;

/* Filled by the constructors below, which validate; read-only afterwards. */
typedef struct cj_quadric {
    cj_quadric_kind kind;
    double a, b, c;        /* semi-axes (c unused by the paraboloids) */
    double u0, u1, v0, v1; /* parameter domain (u0,u1 = 0, 2pi except hyperbolic paraboloid) */
    int lower;             /* hyperboloid of two sheets: 1 for the lower sheet (z < 0) */
} cj_quadric;

/* Constructors. Status codes: CJ_ERR_NONFINITE (a NaN/Inf argument), CJ_ERR_DEGENERATE (a
 * semi-axis <= 0, named), CJ_ERR_ARGUMENT (an empty or invalid parameter range, named). */
cj_status cj_quadric_ellipsoid(cj_quadric *q, double a, double b, double c);
/* v0 < v1, any sign. */
cj_status cj_quadric_hyperboloid1(cj_quadric *q, double a, double b, double c, double v0,
                                  double v1);
/* lower = 0: upper sheet, 1: lower sheet; v1 > 0 (the sheet up to |z| = c cosh v1). */
cj_status cj_quadric_hyperboloid2(cj_quadric *q, double a, double b, double c, int lower,
                                  double v1);
/* v0 < v1, any sign (v < 0 is the lower nappe). */
cj_status cj_quadric_cone(cj_quadric *q, double a, double b, double c, double v0, double v1);
/* v1 > 0 (the bowl up to z = v1²). */
cj_status cj_quadric_paraboloid(cj_quadric *q, double a, double b, double v1);
/* u0 < u1, v0 < v1. */
cj_status cj_quadric_hyperbolic_paraboloid(cj_quadric *q, double a, double b, double u0, double u1,
                                           double v0, double v1);

/* f(x) and grad f(x) (grad may be NULL); CJ_ERR_NONFINITE for a non-finite x. */
cj_status cj_quadric_implicit_eval(const cj_quadric *q, cj_vec3 x, double *f, cj_vec3 *grad);

/* Views q as an implicit / parametric surface (data = q: keep q alive). No failure once q was
 * built by a constructor; the return is void. */
void cj_quadric_implicit(const cj_quadric *q, cj_implicit_surface *out);
void cj_quadric_surface(const cj_quadric *q, cj_param_surface *out);

#ifdef __cplusplus
}
#endif
#endif

/* casteljau: the certified nearest point of a Bézier patch (polynomial or rational) to a point.
 *
 * cj_patch_nearest finds min over (u,v) in [0,1]^2 of |S(u,v) - q| by branch and bound over
 * sub-patches obtained by exact halvings (in u or v, the longer side first), whose homogeneous
 * control points carry a tracked bound on their rounding. A sub-patch is discarded only when a
 * PROVEN lower bound of its distance to q (the larger of the distance to the box of its
 * enclosed control points and the gap along the direction from q to the mean of its corners,
 * in outward-rounded interval arithmetic) is at least the best distance found minus tol. Upper
 * bounds are enclosed evaluations (interval de Casteljau) at sub-patch centres, polished by
 * Gauss-Newton steps. At the root and every fourth level a second lower bound is taken from the
 * Bernstein form of the squared distance, N/D with N = sum_k (P_k - q_k W)^2 and D = W^2 of
 * degree (2m, 2n): N/D >= min_IJ N_IJ / D_IJ. It is exact for a patch whose points are all
 * equally far from q (a sphere patch seen from its centre: every ratio is r^2 to rounding), so
 * such a patch, where no box bound can ever prune, is certified at once: any point is nearest
 * within tol. The result carries lower <= min |S - q| <= distance, distance - lower <=
 * tol, and distance bounds |S(u,v) - q| at the reported (u,v).
 *
 * Degrees up to CJ_PATCH_NEAREST_MAX_DEGREE in each direction (CJ_ERR_DEGREE above); tol
 * finite, > 0 and >= 2^-36 times the scale (max |coordinate| of the net and of q), else
 * CJ_ERR_ARGUMENT naming tol; a NaN q is CJ_ERR_NONFINITE; the patch is validated as
 * cj_patch_check does, and one whose control points all coincide is CJ_ERR_DEGENERATE. Work
 * space: one allocation of about 1 MiB per call (CJ_ERR_NOMEM). Work is capped at
 * CJ_PATCH_NEAREST_MAX_PIECES sub-patches (CJ_ERR_CAP; the bounds written are still valid).
 */
#ifndef CASTELJAU_PATCH_NEAREST_H
#define CASTELJAU_PATCH_NEAREST_H

#include "casteljau/patch.h"
#include "casteljau/status.h"

#ifdef __cplusplus
extern "C" {
#endif

#define CJ_PATCH_NEAREST_MAX_DEGREE 15
#define CJ_PATCH_NEAREST_MAX_PIECES 2000000L

typedef struct cj_patch_nearest_result {
    double u, v;     /* parameters of the nearest point found */
    double point[3]; /* S(u,v), rounded */
    double distance; /* proven upper bound of |S(u,v) - q| */
    double lower;    /* proven lower bound of the minimum distance over [0,1]^2 */
    long pieces;     /* sub-patches examined */
} cj_patch_nearest_result;

cj_status cj_patch_nearest(const cj_patch *p, const double q[3], double tol,
                           cj_patch_nearest_result *out);

#ifdef __cplusplus
}
#endif
#endif

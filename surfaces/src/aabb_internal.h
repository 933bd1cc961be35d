/* The ray-box slab test, inline: the public cj_aabb_ray (ray_common.c) and the BVH traversal
 * loop (bvh.c) run this one body, so the two can never disagree on which boxes a ray meets. */
#ifndef CASTELJAU_AABB_INTERNAL_H
#define CASTELJAU_AABB_INTERNAL_H

#include "casteljau/ray.h"

#include <stddef.h>

/* Slab test of the ray o + t d (id = 1/d per coordinate, inf allowed) against b over
 * [tmin, tmax]; the far distance is widened by 1 + 2γ(3) so rounding never loses a box the ray
 * touches. Returns 1 with the entry parameter in *t0 and the exit one in *t1 (t1 may be NULL)
 * when the ray meets the box, else 0. */
static inline int cj_aabb_slab(const cj_aabb *b, const double o[3], const double id[3], double tmin,
                               double tmax, double *t0, double *t1) {
    const double widen = 1.0 + 2.0 * 3.3306690738754716e-16; /* 1 + 2γ(3) */
    for (int k = 0; k < 3; k++) {
        double tn = (b->lo[k] - o[k]) * id[k];
        double tf = (b->hi[k] - o[k]) * id[k];
        if (tn > tf) {
            double s = tn;
            tn = tf;
            tf = s;
        }
        tf *= widen;
        /* NaN (0 * inf: origin on a slab plane of a ray parallel to it) leaves the bound. */
        if (tn > tmin) tmin = tn;
        if (tf < tmax) tmax = tf;
        if (tmin > tmax) return 0;
    }
    *t0 = tmin;
    if (t1) *t1 = tmax;
    return 1;
}

#endif

/* Private: the 4-wide form of a BVH that traversal walks (bvh_wide.c). */
#ifndef CASTELJAU_BVH_INTERNAL_H
#define CASTELJAU_BVH_INTERNAL_H

#include "casteljau/bvh.h"

/* Up to 4 children, their boxes stored per coordinate (structure of arrays) so that one ray
 * meets all four in one pass. child[i] >= 0: a wide node; < 0: the binary leaf ~child[i]
 * (bvh->nodes). Unused slots have the box lo = +inf, hi = -inf, which the slab test never
 * hits. The boxes are the binary tree's double boxes, unchanged. */
typedef struct cj_bvh4_node {
    double lo[3][4], hi[3][4];
    int32_t child[4];
    int32_t count; /* used slots */
    int32_t pad_;
} cj_bvh4_node;

typedef struct cj_bvh4 {
    size_t count;
    cj_bvh4_node *nodes; /* nodes[0] is the root */
} cj_bvh4;

/* Collapses the binary tree of bvh into bvh->wide_ (each wide node takes a binary node's
 * children, then repeatedly the children of its largest inner child, up to 4). */
cj_status cj_bvh4_build(cj_bvh *bvh);
void cj_bvh4_destroy(cj_bvh *bvh);

/* The ray data of the wide slab test. */
typedef struct cj_bvh4_ray {
    double o[3], id[3];
    int neg[3]; /* id[k] has its sign bit set: the near plane is hi */
} cj_bvh4_ray;

/* Slab test of the ray against the 4 child boxes of n over [tmin, tmax]: bit i of the result is
 * set when child i is met, with its entry parameter in t0[i]. Exactly cj_aabb_slab's arithmetic
 * per box (same products, the far distance widened by 1 + 2γ(3), NaN from 0 * inf ignored), the
 * near plane chosen by the direction's sign instead of a swap. */
int cj_bvh4_slab(const cj_bvh4_node *n, const cj_bvh4_ray *r, double tmin, double tmax,
                 double t0[4]);

#endif

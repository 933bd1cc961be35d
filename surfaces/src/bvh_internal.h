/* Private: the 4-wide form of a BVH that traversal walks (bvh_wide.c). */
#ifndef CASTELJAU_BVH_INTERNAL_H
#define CASTELJAU_BVH_INTERNAL_H

#include "casteljau/bvh.h"

#ifdef __AVX__
#include <immintrin.h>
#endif

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

/* The ray data of the wide slab test, each coordinate repeated in 4 lanes. */
typedef struct cj_bvh4_ray {
    double o[3][4], id[3][4];
    int neg[3]; /* id[k] has its sign bit set: the near plane is hi */
} cj_bvh4_ray;

/* Slab test of the ray against the 4 child boxes of n over [tmin, tmax]: bit i of the result is
 * set when child i is met, with its entry parameter in t0[i]. Exactly cj_aabb_slab's arithmetic
 * per box (same products, the far distance widened by 1 + 2γ(3), NaN from 0 * inf ignored), the
 * near plane chosen by the direction's sign instead of a swap. Inline: it is the walk's inner
 * step. */
static inline int cj_bvh4_slab(const cj_bvh4_node *n, const cj_bvh4_ray *r, double tmin,
                               double tmax, double t0[4]) {
    const double widen = 1.0 + 2.0 * 3.3306690738754716e-16; /* 1 + 2γ(3), as cj_aabb_slab */
#ifdef __AVX__
    __m256d vmin = _mm256_set1_pd(tmin), vmax = _mm256_set1_pd(tmax);
    const __m256d vw = _mm256_set1_pd(widen);
    for (int k = 0; k < 3; ++k) {
        const double *nearp = r->neg[k] ? n->hi[k] : n->lo[k];
        const double *farp = r->neg[k] ? n->lo[k] : n->hi[k];
        const __m256d o = _mm256_loadu_pd(r->o[k]), id = _mm256_loadu_pd(r->id[k]);
        const __m256d tn = _mm256_mul_pd(_mm256_sub_pd(_mm256_loadu_pd(nearp), o), id);
        const __m256d tf =
            _mm256_mul_pd(_mm256_mul_pd(_mm256_sub_pd(_mm256_loadu_pd(farp), o), id), vw);
        /* max/min return their second operand when the first is NaN: NaN leaves the bound */
        vmin = _mm256_max_pd(tn, vmin);
        vmax = _mm256_min_pd(tf, vmax);
    }
    _mm256_storeu_pd(t0, vmin);
    return _mm256_movemask_pd(_mm256_cmp_pd(vmin, vmax, _CMP_LE_OQ));
#else
    int mask = 0;
    for (int i = 0; i < 4; ++i) {
        double lo = tmin, hi = tmax;
        for (int k = 0; k < 3; ++k) {
            const double tn = ((r->neg[k] ? n->hi[k][i] : n->lo[k][i]) - r->o[k][0]) * r->id[k][0];
            const double tf =
                ((r->neg[k] ? n->lo[k][i] : n->hi[k][i]) - r->o[k][0]) * r->id[k][0] * widen;
            if (tn > lo) lo = tn;
            if (tf < hi) hi = tf;
        }
        t0[i] = lo;
        if (lo <= hi) mask |= 1 << i;
    }
    return mask;
#endif
}

#endif

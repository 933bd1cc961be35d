/* Private helpers shared by the patch, tessellation and patch-set sources. */
#ifndef CASTELJAU_PATCH_INTERNAL_H
#define CASTELJAU_PATCH_INTERNAL_H

#include "casteljau/patch.h"
#include <stddef.h>

/* Work space for one homogeneous control net of the largest patch. */
#define CJ_PATCH_NET_MAX ((CJ_PATCH_MAX_DEGREE + 1) * (CJ_PATCH_MAX_DEGREE + 1) * 4)

/* Loads the (validated) patch's net into h in homogeneous form: dimension 3 (polynomial,
 * plain copy) or 4 ((w x, w y, w z, w)); returns that dimension. */
int cj_patch_load_h(const cj_patch *p, double *h);
/* Inverse of cj_patch_load_h: count points of h (dimension hd) to pts (and w if hd == 4). */
void cj_patch_store_h(const double *h, int hd, size_t count, double *pts, double *w);
/* Tensor de Casteljau of a homogeneous net: out[hd]. */
void cj_patch_eval_h(const double *h, int hd, int m, int n, double u, double v, double *out);
/* Euclidean partials (see cj_patch_eval_derivs) of a validated patch with net h loaded. */
void cj_patch_derivs_unchecked(const cj_patch *p, const double *h, int hd, double u, double v,
                               int ku, int kv, double *out);
/* Unit normal (see cj_patch_normal) of a validated patch with net h loaded. */
cj_status cj_patch_normal_unchecked(const cj_patch *p, const double *h, int hd, double u, double v,
                                    double n[3], int *order);
/* Homogeneous sub-net over [u0,u1]x[v0,v1] (valid, ordered parameters in [0,1]). */
void cj_patch_sub_h(const double *h, int hd, int m, int n, double u0, double u1, double v0,
                    double v1, double *out);
/* Index of the first control point, the index step and the point count along an edge. */
void cj_patch_edge_indices(int m, int n, int edge, int *first, int *step, int *count);

#endif

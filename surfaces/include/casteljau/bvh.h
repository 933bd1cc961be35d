/* casteljau: bounding volume hierarchies (surface-area heuristic) over anything with a box:
 * the triangles of a mesh, the patches of a patch set, the objects of a scene.
 *
 * BUILD. Top-down, binned SAH (Wald 2007): at each node the primitives' centroids are binned
 * along each axis (16 bins, or one per primitive below 16) and the split minimising
 *     C = C_trav + C_isect (A_left B_left + A_right B_right) / A_node
 * is taken if it beats a leaf (cost C_isect B, B = blocks of primitives); a node with more than
 * 8 primitives that SAH would keep as a leaf, or whose centroids coincide, is split at the
 * median. cj_bvh_build counts one block per primitive with C_isect = C_trav = 1;
 * cj_bvh_mesh_build counts blocks of 4 triangles (its leaves are tested 4 at a time) with
 * C_isect = 2 (a 4-triangle test costs about two node visits). Primitive references are
 * partitioned in place; the tree is stored flat (children of an inner node adjacent); the
 * primitive order is the permutation `prims` (leaf k holds prims[first .. first+count-1]).
 * Build is O(n log n).
 *
 * TRAVERSAL. The binary tree is collapsed into an 8-wide one (each wide node takes a node's
 * children, then the children of its largest inner child, up to 8). The 8 child boxes are
 * stored in float, rounded OUTWARD from the double boxes, and one visit tests the ray against
 * all 8 at once (AVX) with a float slab test whose origin rounding is directed and whose
 * entry/exit are padded so that it provably reports every box the ray meets in exact
 * arithmetic (the proof is in surfaces/src/bvh_internal.h; test_bvh_float checks it against
 * rational arithmetic). A box is entered at worst slightly early, never missed, so the hits
 * found are exactly those of an exact walk. Closest hit descends into the nearest met child and
 * pushes the others farthest first (prefetching them), skipping boxes beyond the best hit so
 * far, so a ray costs O(log n) box tests on well-distributed scenes; any hit (shadow rays) stops
 * at the first hit. Statistics count the boxes tested (the used slots of each visited wide node)
 * and the triangles (or primitives) of the leaves tested.
 *
 * Primitives are intersected by a callback, or by the built-in watertight triangle test of
 * cj_bvh_mesh_* : the triangles of each leaf are stored in packets of 4 (double coordinates,
 * one lane per triangle) and tested together in AVX lanes with exactly the scalar test's
 * arithmetic, so each answer, and the hit record filled once for the closest, is bit-identical
 * to cj_ray_triangle on that triangle. A mesh BVH stores its wide nodes and packets in one
 * array, depth first, each node followed by its leaves' packets. The vertex positions are also
 * kept in `tri` in tree order. Nothing in traversal allocates; a BVH is read-only after build
 * and may be shared by threads. Of triangles hit at exactly the same t (coincident
 * triangles), which one is reported depends on the walk's order.
 *
 * Status codes: CJ_ERR_EMPTY (no primitives), CJ_ERR_NONFINITE (a box with a NaN, named),
 * CJ_ERR_CAP (more than 2^31 primitives), CJ_ERR_NOMEM, CJ_ERR_RANGE (a triangle index out of
 * range).
 */
#ifndef CASTELJAU_BVH_H
#define CASTELJAU_BVH_H

#include "casteljau/alloc.h"
#include "casteljau/ray.h"
#include "casteljau/status.h"
#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct cj_bvh_node {
    cj_aabb box;
    uint32_t first; /* inner: index of the left child (right = first + 1); leaf: first prim */
    uint32_t count; /* 0 for an inner node, else the number of primitives */
} cj_bvh_node;

typedef struct cj_bvh {
    size_t node_count, prim_count;
    cj_bvh_node *nodes; /* nodes[0] is the root */
    uint32_t *prims;    /* permutation of 0..prim_count-1 in leaf order */
    int depth;          /* longest root-to-leaf path (root = 1) */
    double sah_cost;    /* SAH cost of the tree (expected tests per ray, relative) */
    /* built-in triangles (cj_bvh_mesh_build): 9 doubles per triangle in `prims` order */
    double *tri;
    /* private */
    cj_allocator alloc_;
    void *wide_; /* the 8-wide form traversal walks (bvh_wide.c) */
} cj_bvh;

/* Builds a BVH over `count` boxes (empty boxes are allowed and never hit). alloc may be NULL. */
cj_status cj_bvh_build(const cj_aabb *boxes, size_t count, const cj_allocator *alloc, cj_bvh **out);
void cj_bvh_destroy(cj_bvh *bvh);

/* Per-ray counters (may be NULL where taken). */
typedef struct cj_bvh_trav_stats {
    uint64_t nodes; /* boxes tested */
    uint64_t prims; /* primitive tests */
} cj_bvh_trav_stats;

/* Intersects primitive `prim` with `ray` (whose tmax is the best hit so far): returns 1 and
 * fills *hit when it is hit at t in [tmin, tmax], else 0. */
typedef int (*cj_bvh_prim_fn)(void *user, uint32_t prim, const cj_ray *ray, cj_hit *hit);

/* Closest hit along the ray: 1 and *hit (hit->prim = the primitive index) if any. For a BVH of
 * cj_bvh_build only (a mesh BVH's leaves hold its triangles: cj_bvh_mesh_closest). */
int cj_bvh_closest(const cj_bvh *bvh, const cj_ray *ray, cj_bvh_prim_fn fn, void *user, cj_hit *hit,
                   cj_bvh_trav_stats *stats);
/* Any hit in [tmin, tmax] (occlusion): 1 as soon as one is found. */
int cj_bvh_any(const cj_bvh *bvh, const cj_ray *ray, cj_bvh_prim_fn fn, void *user,
               cj_bvh_trav_stats *stats);

/* A BVH over the triangles of an indexed mesh (positions 3 per vertex, 3 indices per
 * triangle), intersected with cj_ray_triangle (watertight). */
cj_status cj_bvh_mesh_build(const double *positions, size_t vertex_count, const uint32_t *tris,
                            size_t tri_count, const cj_allocator *alloc, cj_bvh **out);
/* Closest hit / any hit against the built-in triangles; hit->prim = the triangle index. */
int cj_bvh_mesh_closest(const cj_bvh *bvh, const cj_ray *ray, cj_hit *hit,
                        cj_bvh_trav_stats *stats);
int cj_bvh_mesh_any(const cj_bvh *bvh, const cj_ray *ray, cj_bvh_trav_stats *stats);

#ifdef __cplusplus
}
#endif
#endif

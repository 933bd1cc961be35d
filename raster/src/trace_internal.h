/* Private to the ray tracer (trace_*.c): the traced scene (objects under a top-level BVH) and
 * the intersection entry points the shading code uses. */
#ifndef CASTELJAU_TRACE_INTERNAL_H
#define CASTELJAU_TRACE_INTERNAL_H

#include "casteljau/bvh.h"
#include "casteljau/ray.h"
#include "casteljau/scene.h"
#include "casteljau/trace.h"
#include "texture_internal.h"

typedef struct tr_object {
    const cj_geometry *g;
    int kind;
    int identity; /* world transform is the identity: no ray transform */
    cj_ray_xform x;
    uint32_t id;
    int material;
    double tol; /* patches: world-unit tolerance of cj_ray_patch (object space) */
    const cj_patch *patches;
    size_t npatch;
    cj_patch *own_patches; /* revolution / general cylinder as rational patches */
    double *own_pts, *own_w;
    cj_bvh *bvh;    /* patches or mesh triangles */
    int bvh_cached; /* bvh belongs to the renderer's BVH cache, not to this object */
    cj_aabb wbox;   /* over the whole shutter for a moving object */
    /* motion blur: the object's transforms at `poses` evenly spaced shutter times, every
     * `stride`-th entry of the renderer's motion array from `motion`; NULL when static */
    const cj_xform3 *motion;
    size_t stride;
    int poses;
} tr_object;

/* Per-thread counters of ray kinds. */
enum { TR_PRIMARY = 0, TR_SHADOW, TR_REFLECT, TR_REFRACT, TR_THROUGH, TR_INDIRECT, TR_KINDS };

typedef struct tr_counts {
    uint64_t cast[TR_KINDS], hit[TR_KINDS];
    double seconds[TR_KINDS];
    uint64_t patch_rays;
    double patch_max_err;
} tr_counts;

/* An emissive triangle in world space (a mesh triangle, or half of a planar patch), sampled by
 * area for next-event estimation in the path tracer; it emits on both sides, as a path meets
 * an emissive surface from either side. */
typedef struct tr_emit_tri {
    cj_vec3 p0, e1, e2; /* p0 + s e1 + t e2, s, t >= 0, s + t <= 1 */
    cj_vec3 n;          /* unit normal */
    double area;
    cj_rgb emission;
} tr_emit_tri;

typedef struct tr_scene {
    const cj_scene *scene;
    /* emissive triangles (static emissive mesh and planar objects), their area CDF, the total
     * area and, per object, 1 if its triangles are in the table */
    tr_emit_tri *emit;
    double *emit_cdf;
    size_t nemit;
    double emit_area;
    uint8_t *emit_obj;
    tr_object *objs;
    size_t nobj;
    cj_bvh *top;
    cj_tex_sampler *tex;
    int ntex;
    cj_allocator alloc;
} tr_scene;

/* The renderer's per-object BVH cache (trace_cache.c; see casteljau/renderer.h). find: the
 * cached BVH of `node` when its data (the patches p[0..np) or, for a mesh, g's positions and
 * triangles) equals what it was built from, else NULL; it remembers the key for store, which
 * takes ownership of a BVH built from that data (returns 0 when it cannot: the caller keeps
 * it). sweep, after a frame: drops the entries of nodes the frame did not ask for. */
typedef struct tr_bvh_cache tr_bvh_cache;
cj_status tr_bvh_cache_create(const cj_allocator *alloc, tr_bvh_cache **out);
void tr_bvh_cache_destroy(tr_bvh_cache *c);
cj_bvh *tr_bvh_cache_find(tr_bvh_cache *c, int node, const cj_geometry *g, const cj_patch *p,
                          size_t np);
int tr_bvh_cache_store(tr_bvh_cache *c, int node, cj_bvh *bvh);
void tr_bvh_cache_sweep(tr_bvh_cache *c);

/* The traced scene of the frame's scene pass (render_scene.h: drawn nodes, world transforms).
 * cache may be NULL; *reused / *built count the object BVHs taken from it / built. */
struct cj_rscene;
/* motion (may be NULL): poses × node_count world transforms (cj_renderer_set_motion), node_count
 * equal to the scene's; *moving counts the objects that move over the shutter. */
typedef struct tr_motion {
    const cj_xform3 *world;
    int poses;
    size_t node_count;
} tr_motion;
cj_status tr_scene_build(const struct cj_rscene *rs, tr_bvh_cache *cache, const tr_motion *motion,
                         const cj_allocator *alloc, tr_scene *out, size_t *reused, size_t *built,
                         size_t *moving);
void tr_scene_free(tr_scene *s);
/* The emissive triangle table of a built scene (trace_emit.c). CJ_ERR_NOMEM. */
cj_status tr_scene_emitters(tr_scene *s);

/* Closest hit (hit->obj = object index) / any hit in [tmin, tmax], with moving objects placed
 * at shutter time `time` in [0, 1] (ignored by static ones). */
int tr_closest(const tr_scene *s, const cj_ray *ray, double time, cj_hit *hit, tr_counts *c);
int tr_any(const tr_scene *s, const cj_ray *ray, double time, tr_counts *c);

#endif

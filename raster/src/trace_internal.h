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
    cj_bvh *bvh; /* patches or mesh triangles */
    cj_aabb wbox;
} tr_object;

/* Per-thread counters of ray kinds. */
enum { TR_PRIMARY = 0, TR_SHADOW, TR_REFLECT, TR_REFRACT, TR_THROUGH, TR_INDIRECT, TR_KINDS };

typedef struct tr_counts {
    uint64_t cast[TR_KINDS], hit[TR_KINDS];
    double seconds[TR_KINDS];
    uint64_t patch_rays;
    double patch_max_err;
} tr_counts;

typedef struct tr_scene {
    const cj_scene *scene;
    tr_object *objs;
    size_t nobj;
    cj_bvh *top;
    cj_tex_sampler *tex;
    int ntex;
    cj_allocator alloc;
} tr_scene;

cj_status tr_scene_build(const cj_scene *scene, const cj_allocator *alloc, tr_scene *out);
void tr_scene_free(tr_scene *s);

/* Closest hit (hit->obj = object index) / any hit in [tmin, tmax]. */
int tr_closest(const tr_scene *s, const cj_ray *ray, cj_hit *hit, tr_counts *c);
int tr_any(const tr_scene *s, const cj_ray *ray, tr_counts *c);

#endif

/* Embree 3, the peer of our BVH in the ray benches (bench_trace, bench_trace_peer): a triangle
 * mesh as an Embree scene on one thread, and closest hits of a batch of rays. Built only when
 * CJ_HAVE_EMBREE (bench/areas/ray.cmake finds the library). */
#ifndef CJ_BENCH_EMBREE_MESH_H
#define CJ_BENCH_EMBREE_MESH_H

#include "casteljau/mesh.h"
#include "casteljau/ray.h"

#include <embree3/rtcore.h>

typedef struct cj_bench_embree {
    RTCDevice dev;
    RTCScene scene;
} cj_bench_embree;

/* The mesh's triangles (positions rounded to float) in a committed scene of a one-thread
 * device. Free with cj_bench_embree_free. */
cj_bench_embree cj_bench_embree_build(const cj_mesh *m);
void cj_bench_embree_free(cj_bench_embree e);

/* How many of rays[0..n-1] hit the scene (rtcIntersect1, rays rounded to float, t from 0). */
int cj_bench_embree_rays(RTCScene scene, const cj_ray *rays, int n);

#endif

/* The Embree peer of the ray benches (embree_mesh.h). */
#include "embree_mesh.h"

#include <math.h>
#include <string.h>

cj_bench_embree cj_bench_embree_build(const cj_mesh *m) {
    cj_bench_embree e;
    e.dev = rtcNewDevice("threads=1");
    e.scene = rtcNewScene(e.dev);
    RTCGeometry g = rtcNewGeometry(e.dev, RTC_GEOMETRY_TYPE_TRIANGLE);
    float *v = rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                       3 * sizeof(float), m->vertex_count);
    unsigned *ix = rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                           3 * sizeof(unsigned), m->triangle_count);
    for (size_t i = 0; i < 3 * m->vertex_count; i++) v[i] = (float)m->positions[i];
    for (size_t i = 0; i < 3 * m->triangle_count; i++) ix[i] = m->triangles[i];
    rtcCommitGeometry(g);
    rtcAttachGeometry(e.scene, g);
    rtcReleaseGeometry(g);
    rtcCommitScene(e.scene);
    return e;
}

void cj_bench_embree_free(cj_bench_embree e) {
    rtcReleaseScene(e.scene);
    rtcReleaseDevice(e.dev);
}

int cj_bench_embree_rays(RTCScene scene, const cj_ray *rays, int n) {
    int hits = 0;
    struct RTCIntersectContext ctx;
    for (int i = 0; i < n; i++) {
        rtcInitIntersectContext(&ctx);
        struct RTCRayHit rh;
        memset(&rh, 0, sizeof rh);
        rh.ray.org_x = (float)rays[i].org.x;
        rh.ray.org_y = (float)rays[i].org.y;
        rh.ray.org_z = (float)rays[i].org.z;
        rh.ray.dir_x = (float)rays[i].dir.x;
        rh.ray.dir_y = (float)rays[i].dir.y;
        rh.ray.dir_z = (float)rays[i].dir.z;
        rh.ray.tnear = 0.0f;
        rh.ray.tfar = INFINITY;
        rh.ray.mask = 0xffffffffu;
        rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(scene, &ctx, &rh);
        hits += rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
    }
    return hits;
}

/* Watertight ray–triangle intersection (Woop, Benthin, Wald 2013) with exact edge-function
 * signs and a consistent tie-break for rays exactly through edges and vertices. */
#include "casteljau/ray.h"
#include "ray_triangle_internal.h"

#include <math.h>

static inline double comp(cj_vec3 a, int k) {
    return k == 0 ? a.x : (k == 1 ? a.y : a.z);
}

void cj_ray_triangle_prepare(const cj_ray *ray, cj_ray_tri_pre *pre) {
    double ax = fabs(ray->dir.x), ay = fabs(ray->dir.y), az = fabs(ray->dir.z);
    int kz = (ax > ay) ? (ax > az ? 0 : 2) : (ay > az ? 1 : 2);
    int kx = (kz + 1) % 3, ky = (kx + 1) % 3;
    /* Keep the (x', y', z') frame right-handed so triangles keep their winding. */
    if (comp(ray->dir, kz) < 0.0) {
        int tmp = kx;
        kx = ky;
        ky = tmp;
    }
    double dz = comp(ray->dir, kz);
    pre->kx = kx;
    pre->ky = ky;
    pre->kz = kz;
    pre->sx = comp(ray->dir, kx) / dz;
    pre->sy = comp(ray->dir, ky) / dz;
    pre->sz = 1.0 / dz;
}

int cj_ray_triangle_pre(const cj_ray *ray, const cj_ray_tri_pre *pre, cj_vec3 v0, cj_vec3 v1,
                        cj_vec3 v2, cj_hit *hit) {
    double t, e[3], det;
    if (!cj_tri_core(ray, pre, v0, v1, v2, &t, e, &det)) return 0;
    cj_tri_fill(v0, v1, v2, t, e, det, hit);
    return 1;
}

int cj_ray_triangle(const cj_ray *ray, cj_vec3 v0, cj_vec3 v1, cj_vec3 v2, cj_hit *hit) {
    cj_ray_tri_pre pre;
    cj_ray_triangle_prepare(ray, &pre);
    return cj_ray_triangle_pre(ray, &pre, v0, v1, v2, hit);
}

/* Watertight ray–triangle intersection (Woop, Benthin, Wald 2013) with exact edge-function
 * signs and a consistent tie-break for rays exactly through edges and vertices. */
#include "casteljau/ray.h"
#include "ray_triangle_internal.h"

#include <math.h>

void cj_ray_triangle_prepare(const cj_ray *ray, cj_ray_tri_pre *pre) {
    cj_tri_prepare(ray, pre);
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

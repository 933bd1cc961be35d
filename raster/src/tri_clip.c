/* Homogeneous clipping (Sutherland–Hodgman) of one triangle against the near and far planes
 * and the guard band, before the division by w: a triangle crossing the eye plane is cut where
 * it crosses z = f and never wraps around through infinity. */
#include "tri_internal.h"

/* Signed distance of v to plane p (inside when >= 0). */
static double plane_dist(const cj_tri_vert *v, int p, double gx, double gy) {
    switch (p) {
    case 0:
        return v->z + v->w; /* near: z_ndc >= −1 */
    case 1:
        return v->w - v->z; /* far: z_ndc <= 1 */
    case 2:
        return gx * v->w - v->x; /* right guard */
    case 3:
        return gx * v->w + v->x; /* left guard */
    case 4:
        return gy * v->w - v->y; /* top guard */
    default:
        return gy * v->w + v->y; /* bottom guard */
    }
}

/* The point of segment (a inside, b outside) on the plane, always interpolated from the inside
 * end so that the result does not depend on the direction a triangle walks the edge. */
static cj_tri_vert cut_point(const cj_tri_vert *a, double da, const cj_tri_vert *b, double db) {
    const double t = da / (da - db);
    cj_tri_vert r;
    r.x = a->x + t * (b->x - a->x);
    r.y = a->y + t * (b->y - a->y);
    r.z = a->z + t * (b->z - a->z);
    r.w = a->w + t * (b->w - a->w);
    r.b1 = a->b1 + t * (b->b1 - a->b1);
    r.b2 = a->b2 + t * (b->b2 - a->b2);
    return r;
}

int cj_tri_clip(const cj_tri_vert in[3], double gx, double gy, cj_tri_vert *out, int *cut) {
    cj_tri_vert buf[2][CJ_TRI_CLIP_MAX + 1];
    double d[CJ_TRI_CLIP_MAX + 1];
    int n = 3, cur = 0;
    *cut = 0;
    for (int i = 0; i < 3; ++i) buf[0][i] = in[i];
    for (int p = 0; p < 6; ++p) {
        const cj_tri_vert *src = buf[cur];
        int outside = 0;
        for (int i = 0; i < n; ++i) {
            d[i] = plane_dist(&src[i], p, gx, gy);
            outside += !(d[i] >= 0.0);
        }
        if (outside == 0) continue;
        if (outside == n) return 0;
        *cut = 1;
        cj_tri_vert *dst = buf[cur ^ 1];
        int m = 0;
        for (int i = 0; i < n; ++i) {
            const int j = i + 1 == n ? 0 : i + 1;
            const int in_i = d[i] >= 0.0, in_j = d[j] >= 0.0;
            if (in_i) dst[m++] = src[i];
            if (in_i && !in_j)
                dst[m++] = cut_point(&src[i], d[i], &src[j], d[j]);
            else if (!in_i && in_j)
                dst[m++] = cut_point(&src[j], d[j], &src[i], d[i]);
        }
        n = m;
        cur ^= 1;
        if (n < 3) return 0;
    }
    for (int i = 0; i < n; ++i) out[i] = buf[cur][i];
    return n;
}

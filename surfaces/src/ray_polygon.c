/* Rays against general planar polygons: the plane, then the crossing number in 2D. */
#include "casteljau/ray.h"

#include <math.h>

int cj_ray_polygon(const cj_ray *ray, const double *pts, size_t count, cj_hit *hit) {
    if (count < 3) return 0;
    /* Newell's normal: robust for non-convex and slightly non-planar polygons. */
    cj_vec3 nn = cj_v3(0.0, 0.0, 0.0), c = cj_v3(0.0, 0.0, 0.0);
    for (size_t i = 0; i < count; i++) {
        const double *a = pts + 3 * i, *b = pts + 3 * ((i + 1) % count);
        nn.x += (a[1] - b[1]) * (a[2] + b[2]);
        nn.y += (a[2] - b[2]) * (a[0] + b[0]);
        nn.z += (a[0] - b[0]) * (a[1] + b[1]);
        c = cj_v3_add(c, cj_v3(a[0], a[1], a[2]));
    }
    double len = cj_v3_norm(nn);
    if (!(len > 0.0)) return 0;
    cj_vec3 n = cj_v3_scale(nn, 1.0 / len);
    c = cj_v3_scale(c, 1.0 / (double)count);
    double dn = cj_v3_dot(n, ray->dir);
    if (dn == 0.0) return 0;
    double t = cj_v3_dot(n, cj_v3_sub(c, ray->org)) / dn;
    if (!(t >= ray->tmin && t <= ray->tmax)) return 0;
    cj_vec3 p = cj_v3_add(ray->org, cj_v3_scale(ray->dir, t));
    /* Drop the normal's largest coordinate. */
    int k =
        fabs(n.x) > fabs(n.y) ? (fabs(n.x) > fabs(n.z) ? 0 : 2) : (fabs(n.y) > fabs(n.z) ? 1 : 2);
    int ix = (k + 1) % 3, iy = (k + 2) % 3;
    const double pc[3] = {p.x, p.y, p.z};
    double px = pc[ix], py = pc[iy];
    int inside = 0;
    for (size_t i = 0, j = count - 1; i < count; j = i++) {
        double xi = pts[3 * i + ix], yi = pts[3 * i + iy];
        double xj = pts[3 * j + ix], yj = pts[3 * j + iy];
        /* Half-open in y: an edge counts when it straddles py with one end at or above it. */
        if ((yi > py) != (yj > py)) {
            double xc = xj + (py - yj) * (xi - xj) / (yi - yj);
            if (px < xc) inside = !inside;
        }
    }
    if (!inside) return 0;
    double dist = fabs(cj_v3_dot(n, cj_v3_sub(p, c)));
    double e = 2.0 * dist + cj_gamma(8) * (fabs(p.x) + fabs(p.y) + fabs(p.z) + fabs(c.x) +
                                           fabs(c.y) + fabs(c.z));
    cj_vec3 e0 =
        cj_v3_normalize(cj_v3_sub(cj_v3(pts[3], pts[4], pts[5]), cj_v3(pts[0], pts[1], pts[2])));
    cj_vec3 e1 = cj_v3_cross(n, e0);
    cj_vec3 w = cj_v3_sub(p, cj_v3(pts[0], pts[1], pts[2]));
    hit->t = t;
    hit->p = p;
    hit->p_err = cj_v3(e, e, e);
    hit->n = n;
    hit->ng = n;
    hit->u = cj_v3_dot(w, e0);
    hit->v = cj_v3_dot(w, e1);
    hit->err = 0.0;
    return 1;
}

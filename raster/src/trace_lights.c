/* The ray tracer's extended emitters (scene.h: area, disc, sphere lights read radiometrically):
 * a sample of the radiance they send to a point, and a ray meeting them (trace_shade.h). */
#include "trace_shade.h"

#include <math.h>

static const double PI = 3.14159265358979323846;

/* 1 − cos θ_max of the cone a sphere of radius R subtends at distance d > R, without the
 * cancellation of 1 − √(1 − x) for small x = R²/d². */
static double cone_one_minus_cos(double R, double d) {
    const double x = (R * R) / (d * d);
    return x / (1.0 + sqrt(1.0 - x));
}

/* A point of the unit disc from (u1, u2) in [0, 1)², uniform by area, strata kept (Shirley and
 * Chiu's concentric map: squares to rings). */
static void concentric(double u1, double u2, double *x, double *y) {
    const double a = 2.0 * u1 - 1.0, b = 2.0 * u2 - 1.0;
    if (a == 0.0 && b == 0.0) {
        *x = *y = 0.0;
        return;
    }
    double r, phi;
    if (fabs(a) > fabs(b)) {
        r = a;
        phi = (PI / 4.0) * (b / a);
    } else {
        r = b;
        phi = PI / 2.0 - (PI / 4.0) * (a / b);
    }
    *x = r * cos(phi);
    *y = r * sin(phi);
}

int tr_is_emitter(const cj_light *lt) {
    return lt->kind == CJ_LIGHT_AREA || lt->kind == CJ_LIGHT_DISC || lt->kind == CJ_LIGHT_SPHERE;
}

cj_vec3 tr_emitter_point(const cj_light *lt, double u1, double u2) {
    if (lt->kind == CJ_LIGHT_AREA)
        return cj_v3_add(lt->position,
                         cj_v3_add(cj_v3_scale(lt->edge_u, u1), cj_v3_scale(lt->edge_v, u2)));
    if (lt->kind == CJ_LIGHT_DISC) {
        cj_vec3 a, b;
        cj_frame_from_axis(cj_v3_normalize(lt->direction), &a, &b);
        double x, y;
        concentric(u1, u2, &x, &y);
        return cj_v3_add(lt->position,
                         cj_v3_add(cj_v3_scale(a, lt->radius * x), cj_v3_scale(b, lt->radius * y)));
    }
    return lt->position;
}

int tr_emitter_sample(const cj_light *lt, cj_vec3 p, double u1, double u2, int centre,
                      cj_vec3 *target, double *weight, double *pdf) {
    if (lt->kind == CJ_LIGHT_SPHERE) {
        const cj_vec3 to = cj_v3_sub(lt->position, p);
        const double d = cj_v3_norm(to), R = lt->radius;
        if (!(d > R)) return 0; /* inside the emitter: it shines outwards only */
        const double omc = cone_one_minus_cos(R, d);
        const cj_vec3 axis = cj_v3_scale(to, 1.0 / d);
        cj_vec3 dir = axis;
        if (centre) {
            /* the axis, weighted by the cone's projected solid angle π sin² θ_max: the exact
             * irradiance per unit radiance when the whole sphere is above the horizon */
            *weight = PI * (R / d) * (R / d);
        } else {
            const double om = u1 * omc, ct = 1.0 - om, st = sqrt(fmax(0.0, om * (2.0 - om))),
                         ph = 2.0 * PI * u2;
            cj_vec3 a, b;
            cj_frame_from_axis(axis, &a, &b);
            dir = cj_v3_normalize(
                cj_v3_add(cj_v3_scale(axis, ct),
                          cj_v3_add(cj_v3_scale(a, st * cos(ph)), cj_v3_scale(b, st * sin(ph)))));
            *weight = 2.0 * PI * omc;
        }
        /* where the direction meets the sphere (the nearer root; inside the cone it exists) */
        const double b = cj_v3_dot(dir, to), disc = R * R - (d * d - b * b);
        const double t = b - sqrt(fmax(0.0, disc));
        *target = cj_v3_add(p, cj_v3_scale(dir, t));
        *pdf = centre ? 0.0 : 1.0 / *weight;
        return 1;
    }
    /* parallelogram and disc: by area (pdf 1/A), L_e A cos θ′ / r² per unit radiance */
    cj_vec3 n;
    double A;
    if (lt->kind == CJ_LIGHT_AREA) {
        n = cj_v3_cross(lt->edge_u, lt->edge_v);
        A = cj_v3_norm(n);
        n = cj_v3_scale(n, 1.0 / A);
    } else {
        n = cj_v3_normalize(lt->direction);
        A = PI * lt->radius * lt->radius;
    }
    const cj_vec3 q = tr_emitter_point(lt, u1, u2);
    const cj_vec3 to = cj_v3_sub(q, p);
    const double r2 = cj_v3_dot(to, to);
    if (!(r2 > 0.0)) return 0;
    const double ct = -cj_v3_dot(n, to) / sqrt(r2);
    if (!(ct > 0.0)) return 0; /* the back of a one-sided emitter */
    *target = q;
    *weight = A * ct / r2;
    *pdf = r2 / (A * ct);
    return 1;
}

int tr_emitter_hit(const cj_light *lt, const cj_ray *ray, double t_max, double *t_out,
                   double *pdf) {
    const double dd = cj_v3_dot(ray->dir, ray->dir);
    if (lt->kind == CJ_LIGHT_SPHERE) {
        const cj_vec3 to = cj_v3_sub(lt->position, ray->org);
        const double d2 = cj_v3_dot(to, to), R = lt->radius;
        if (!(d2 > R * R)) return 0;
        const double b = cj_v3_dot(ray->dir, to), disc = b * b - dd * (d2 - R * R);
        if (!(disc >= 0.0) || !(b > 0.0)) return 0;
        const double t = (b - sqrt(disc)) / dd;
        if (!(t > ray->tmin) || !(t < t_max)) return 0;
        *t_out = t;
        *pdf = 1.0 / (2.0 * PI * cone_one_minus_cos(R, sqrt(d2)));
        return 1;
    }
    cj_vec3 n;
    double A;
    if (lt->kind == CJ_LIGHT_AREA) {
        n = cj_v3_cross(lt->edge_u, lt->edge_v);
        A = cj_v3_norm(n);
        n = cj_v3_scale(n, 1.0 / A);
    } else {
        n = cj_v3_normalize(lt->direction);
        A = PI * lt->radius * lt->radius;
    }
    const double dn = cj_v3_dot(ray->dir, n);
    if (!(dn < 0.0)) return 0; /* the back of the emitter, or edge-on */
    const double t = cj_v3_dot(cj_v3_sub(lt->position, ray->org), n) / dn;
    if (!(t > ray->tmin) || !(t < t_max)) return 0;
    const cj_vec3 q = cj_v3_sub(cj_v3_add(ray->org, cj_v3_scale(ray->dir, t)), lt->position);
    if (lt->kind == CJ_LIGHT_AREA) { /* coordinates in (edge_u, edge_v) by the dual basis */
        const double uu = cj_v3_dot(lt->edge_u, lt->edge_u), uv = cj_v3_dot(lt->edge_u, lt->edge_v),
                     vv = cj_v3_dot(lt->edge_v, lt->edge_v), qu = cj_v3_dot(q, lt->edge_u),
                     qv = cj_v3_dot(q, lt->edge_v), det = uu * vv - uv * uv;
        const double s = (qu * vv - qv * uv) / det, r = (qv * uu - qu * uv) / det;
        if (s < 0.0 || s > 1.0 || r < 0.0 || r > 1.0) return 0;
    } else if (!(cj_v3_dot(q, q) <= lt->radius * lt->radius)) {
        return 0;
    }
    *t_out = t;
    const double cl = -dn / sqrt(dd);
    *pdf = t * t * dd / (A * cl);
    return 1;
}

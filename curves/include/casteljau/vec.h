/* casteljau: small value vectors for the 2D and 3D APIs (points p̄ and vectors τ⃗ alike).
 * All functions are static inline and pure; none validates its input. */
#ifndef CASTELJAU_VEC_H
#define CASTELJAU_VEC_H

#include <math.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct cj_vec2 {
    double x, y;
} cj_vec2;

typedef struct cj_vec3 {
    double x, y, z;
} cj_vec3;

static inline cj_vec2 cj_v2(double x, double y) {
    cj_vec2 r = {x, y};
    return r;
}
static inline cj_vec2 cj_v2_add(cj_vec2 a, cj_vec2 b) {
    return cj_v2(a.x + b.x, a.y + b.y);
}
static inline cj_vec2 cj_v2_sub(cj_vec2 a, cj_vec2 b) {
    return cj_v2(a.x - b.x, a.y - b.y);
}
static inline cj_vec2 cj_v2_scale(cj_vec2 a, double s) {
    return cj_v2(a.x * s, a.y * s);
}
static inline double cj_v2_dot(cj_vec2 a, cj_vec2 b) {
    return a.x * b.x + a.y * b.y;
}
/* z-component of the 3D cross product: positive when b is counter-clockwise from a. */
static inline double cj_v2_cross(cj_vec2 a, cj_vec2 b) {
    return a.x * b.y - a.y * b.x;
}
static inline double cj_v2_norm(cj_vec2 a) {
    return hypot(a.x, a.y);
}
/* a turned +90 degrees (counter-clockwise). */
static inline cj_vec2 cj_v2_perp(cj_vec2 a) {
    return cj_v2(-a.y, a.x);
}
static inline cj_vec2 cj_v2_lerp(cj_vec2 a, cj_vec2 b, double t) {
    return cj_v2((1.0 - t) * a.x + t * b.x, (1.0 - t) * a.y + t * b.y);
}

static inline cj_vec3 cj_v3(double x, double y, double z) {
    cj_vec3 r = {x, y, z};
    return r;
}
/* 1 when the three coordinates are finite (no NaN, no infinity): the check every reader of
 * points, directions and positions makes before using them. */
static inline int cj_v3_finite(cj_vec3 a) {
    return isfinite(a.x) && isfinite(a.y) && isfinite(a.z);
}
static inline cj_vec3 cj_v3_add(cj_vec3 a, cj_vec3 b) {
    return cj_v3(a.x + b.x, a.y + b.y, a.z + b.z);
}
static inline cj_vec3 cj_v3_sub(cj_vec3 a, cj_vec3 b) {
    return cj_v3(a.x - b.x, a.y - b.y, a.z - b.z);
}
static inline cj_vec3 cj_v3_scale(cj_vec3 a, double s) {
    return cj_v3(a.x * s, a.y * s, a.z * s);
}
static inline double cj_v3_dot(cj_vec3 a, cj_vec3 b) {
    return a.x * b.x + a.y * b.y + a.z * b.z;
}
static inline cj_vec3 cj_v3_cross(cj_vec3 a, cj_vec3 b) {
    return cj_v3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}
static inline double cj_v3_norm(cj_vec3 a) {
    return sqrt(cj_v3_dot(a, a));
}
static inline cj_vec3 cj_v3_lerp(cj_vec3 a, cj_vec3 b, double t) {
    return cj_v3((1.0 - t) * a.x + t * b.x, (1.0 - t) * a.y + t * b.y, (1.0 - t) * a.z + t * b.z);
}
/* a / |a|, or the zero vector when |a| == 0 (callers that care check the norm first). */
static inline cj_vec3 cj_v3_normalize(cj_vec3 a) {
    double n = cj_v3_norm(a);
    return n > 0.0 ? cj_v3_scale(a, 1.0 / n) : cj_v3(0.0, 0.0, 0.0);
}

#ifdef __cplusplus
}
#endif
#endif

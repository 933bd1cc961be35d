/* Private: the built-in triangles of a mesh BVH in packets of 4, tested together in AVX lanes
 * with exactly the arithmetic of the scalar watertight test (ray_triangle_internal.h), so every
 * lane's answer is bit-identical to cj_tri_core_v on the same triangle. */
#ifndef CASTELJAU_BVH_LEAF_INTERNAL_H
#define CASTELJAU_BVH_LEAF_INTERNAL_H

#include "bvh_internal.h"
#include "ray_triangle_internal.h"

#include <stdint.h>

/* 4 triangles, coordinates per lane: v[3 j + k][lane] is coordinate k of vertex j. idx[lane] is
 * the triangle's index in the mesh (hit->prim); unused lanes hold NaN vertices
 * (never hit: every comparison of a NaN edge value is false) and idx UINT32_MAX. */
typedef struct cj_bvhw_tris {
    double v[9][4];
    uint32_t idx[4];
    uint32_t pad_[4]; /* 320 bytes: 5 whole cache lines when aligned */
} cj_bvhw_tris;

/* The 9 coordinates of lane l. */
static inline void cj_bvhw_tris_lane(const cj_bvhw_tris *p, int l, double v[9]) {
    v[0] = p->v[0][l], v[1] = p->v[1][l], v[2] = p->v[2][l];
    v[3] = p->v[3][l], v[4] = p->v[4][l], v[5] = p->v[5][l];
    v[6] = p->v[6][l], v[7] = p->v[7][l], v[8] = p->v[8][l];
}

/* The outcome of one packet: lane bits that hit at t in [tmin, tmax], their t, edge values and
 * sums. */
typedef struct cj_bvhw_tri_hits {
    int mask;
    double t[4], e0[4], e1[4], e2[4], det[4];
} cj_bvhw_tri_hits;

#if defined(__AVX__) && defined(__FMA__)
/* cj_tri_edge_fn in 4 lanes: the plain difference where it clears its rounding bound, else
 * Kahan's fma form, chosen per lane by the same comparison. */
static inline __m256d cj_tri_edge_fn4(__m256d px, __m256d py, __m256d qx, __m256d qy) {
    const __m256d absmask = _mm256_castsi256_pd(_mm256_set1_epi64x(0x7fffffffffffffffLL));
    const __m256d a = _mm256_mul_pd(px, qy), b = _mm256_mul_pd(py, qx);
    const __m256d e = _mm256_sub_pd(a, b);
    const __m256d bound =
        _mm256_mul_pd(_mm256_set1_pd(3.3306690738754716e-16),
                      _mm256_add_pd(_mm256_and_pd(a, absmask), _mm256_and_pd(b, absmask)));
    const __m256d fast = _mm256_cmp_pd(_mm256_and_pd(e, absmask), bound, _CMP_GT_OQ);
    if (_mm256_movemask_pd(fast) == 0xf) return e;
    const __m256d sign = _mm256_castsi256_pd(_mm256_set1_epi64x((long long)0x8000000000000000ULL));
    const __m256d w = b; /* py * qx, as the scalar form recomputes it; negation flips the sign */
    const __m256d err = _mm256_fmadd_pd(_mm256_xor_pd(py, sign), qx, w);
    const __m256d f = _mm256_fmadd_pd(px, qy, _mm256_xor_pd(w, sign));
    return _mm256_blendv_pd(_mm256_add_pd(f, err), e, fast);
}
#endif

/* What the packet test needs of the ray, set up once per ray rather than once per packet: the
 * rows of the packet holding the sheared frame's x', y', z' (kx, ky, kz), and the origin, shear
 * and interval broadcast to the lanes. */
typedef struct cj_bvhw_tri_ray {
    const cj_ray *ray;
    const cj_ray_tri_pre *pre;
#if defined(__AVX__) && defined(__FMA__)
    int kx, ky, kz;
    __m256d ox, oy, oz, sx, sy, sz, tmin, tmax;
#endif
} cj_bvhw_tri_ray;

static inline void cj_bvhw_tri_ray_setup(const cj_ray *ray, const cj_ray_tri_pre *pre,
                                         cj_bvhw_tri_ray *r) {
    r->ray = ray;
    r->pre = pre;
#if defined(__AVX__) && defined(__FMA__)
    const double o[3] = {ray->org.x, ray->org.y, ray->org.z};
    r->kx = pre->kx, r->ky = pre->ky, r->kz = pre->kz;
    r->ox = _mm256_set1_pd(o[pre->kx]);
    r->oy = _mm256_set1_pd(o[pre->ky]);
    r->oz = _mm256_set1_pd(o[pre->kz]);
    r->sx = _mm256_set1_pd(pre->sx);
    r->sy = _mm256_set1_pd(pre->sy);
    r->sz = _mm256_set1_pd(pre->sz);
    r->tmin = _mm256_set1_pd(ray->tmin);
    r->tmax = _mm256_set1_pd(ray->tmax);
#endif
}

/* Tests the 4 triangles of p against the ray of r (set up by cj_bvhw_tri_ray_setup; r->tmax
 * must follow ray->tmax when the caller shrinks it). */
static inline __attribute__((always_inline)) void
cj_bvhw_tris_test_r(const cj_bvhw_tris *p, const cj_bvhw_tri_ray *r, cj_bvhw_tri_hits *out) {
    int mask = 0;
    const cj_ray *ray = r->ray;
    const cj_ray_tri_pre *pre = r->pre;
#if defined(__AVX__) && defined(__FMA__)
    const __m256d ox = r->ox, oy = r->oy, oz = r->oz, sx = r->sx, sy = r->sy, sz = r->sz;
    __m256d X[3], Y[3], Z[3];
#define CJ_BVHW_VERTEX(j)                                                                          \
    do {                                                                                           \
        const __m256d a0 = _mm256_sub_pd(_mm256_loadu_pd(p->v[3 * (j) + r->kx]), ox);              \
        const __m256d a1 = _mm256_sub_pd(_mm256_loadu_pd(p->v[3 * (j) + r->ky]), oy);              \
        const __m256d a2 = _mm256_sub_pd(_mm256_loadu_pd(p->v[3 * (j) + r->kz]), oz);              \
        X[j] = _mm256_sub_pd(a0, _mm256_mul_pd(sx, a2));                                           \
        Y[j] = _mm256_sub_pd(a1, _mm256_mul_pd(sy, a2));                                           \
        Z[j] = a2;                                                                                 \
    } while (0)
    CJ_BVHW_VERTEX(0);
    CJ_BVHW_VERTEX(1);
    CJ_BVHW_VERTEX(2);
#undef CJ_BVHW_VERTEX
    const __m256d e0 = cj_tri_edge_fn4(X[1], Y[1], X[2], Y[2]);
    const __m256d e1 = cj_tri_edge_fn4(X[2], Y[2], X[0], Y[0]);
    const __m256d e2 = cj_tri_edge_fn4(X[0], Y[0], X[1], Y[1]);
    const __m256d zero = _mm256_setzero_pd();
    const __m256d pos = _mm256_or_pd(
        _mm256_or_pd(_mm256_cmp_pd(e0, zero, _CMP_GT_OQ), _mm256_cmp_pd(e1, zero, _CMP_GT_OQ)),
        _mm256_cmp_pd(e2, zero, _CMP_GT_OQ));
    const __m256d neg = _mm256_or_pd(
        _mm256_or_pd(_mm256_cmp_pd(e0, zero, _CMP_LT_OQ), _mm256_cmp_pd(e1, zero, _CMP_LT_OQ)),
        _mm256_cmp_pd(e2, zero, _CMP_LT_OQ));
    const __m256d anyzero = _mm256_or_pd(
        _mm256_or_pd(_mm256_cmp_pd(e0, zero, _CMP_EQ_OQ), _mm256_cmp_pd(e1, zero, _CMP_EQ_OQ)),
        _mm256_cmp_pd(e2, zero, _CMP_EQ_OQ));
    /* one-signed without a zero edge value: the scalar test's path without the tie-break */
    const __m256d ok = _mm256_andnot_pd(anyzero, _mm256_xor_pd(pos, neg));
    const int zmask = _mm256_movemask_pd(anyzero);
    int cand = _mm256_movemask_pd(ok);
    if (cand) {
        const __m256d det = _mm256_add_pd(_mm256_add_pd(e0, e1), e2);
        const __m256d tsc = _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(e0, _mm256_mul_pd(sz, Z[0])),
                                                        _mm256_mul_pd(e1, _mm256_mul_pd(sz, Z[1]))),
                                          _mm256_mul_pd(e2, _mm256_mul_pd(sz, Z[2])));
        const __m256d t = _mm256_div_pd(tsc, det);
        const __m256d in = _mm256_and_pd(_mm256_and_pd(_mm256_cmp_pd(det, zero, _CMP_NEQ_OQ),
                                                       _mm256_cmp_pd(t, r->tmin, _CMP_GE_OQ)),
                                         _mm256_cmp_pd(t, r->tmax, _CMP_LE_OQ));
        mask = cand & _mm256_movemask_pd(in);
        if (mask) {
            _mm256_storeu_pd(out->t, t);
            _mm256_storeu_pd(out->e0, e0);
            _mm256_storeu_pd(out->e1, e1);
            _mm256_storeu_pd(out->e2, e2);
            _mm256_storeu_pd(out->det, det);
        }
    }
    /* lanes with an edge value of exactly zero take the scalar test and its tie-break */
    for (int z = zmask; z; z &= z - 1) {
        const int l = __builtin_ctz((unsigned)z);
        if (p->idx[l] == UINT32_MAX) continue;
        double t, e[3], det, v[9];
        cj_bvhw_tris_lane(p, l, v);
        if (!cj_tri_core_v(ray, pre, v, &t, e, &det)) continue;
        mask |= 1 << l;
        out->t[l] = t, out->e0[l] = e[0], out->e1[l] = e[1], out->e2[l] = e[2];
        out->det[l] = det;
    }
#else
    for (int l = 0; l < 4; ++l) {
        if (p->idx[l] == UINT32_MAX) continue;
        double t, e[3], det, v[9];
        cj_bvhw_tris_lane(p, l, v);
        if (!cj_tri_core_v(ray, pre, v, &t, e, &det)) continue;
        mask |= 1 << l;
        out->t[l] = t, out->e0[l] = e[0], out->e1[l] = e[1], out->e2[l] = e[2];
        out->det[l] = det;
    }
#endif
    out->mask = mask;
}

/* The same for one packet on its own (the tests compare it with the scalar test). */
static inline void cj_bvhw_tris_test(const cj_bvhw_tris *p, const cj_ray *ray,
                                     const cj_ray_tri_pre *pre, cj_bvhw_tri_hits *out) {
    cj_bvhw_tri_ray r;
    cj_bvhw_tri_ray_setup(ray, pre, &r);
    cj_bvhw_tris_test_r(p, &r, out);
}

#endif

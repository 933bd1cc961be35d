/* Private: the 8-wide form of a BVH that traversal walks (bvh_wide.c), with float child boxes
 * rounded outward and a float slab test that provably never loses a box the ray meets. */
#ifndef CASTELJAU_BVH_INTERNAL_H
#define CASTELJAU_BVH_INTERNAL_H

#include "casteljau/bvh.h"

#include <float.h>
#include <math.h>
#include <string.h>

#ifdef __SSE2__
#include <immintrin.h>
#endif

/* The deepest wide tree the walks' fixed stacks hold (cj_bvhw_build refuses a deeper one, which
 * the builder never makes: its depth stays below 82). */
#define CJ_BVHW_MAX_DEPTH 128

/* Children per wide node. 8: one AVX pass tests them all, and the tree is about 1.5 times
 * shallower than a 4-wide one, which matters because the walk waits on one cache miss per level
 * (measured: the first load of a node or a leaf packet takes most of the walk's time). */
#define CJ_BVHW_W 8

/* Up to 8 children, their boxes stored per plane (structure of arrays) so that one ray meets all
 * eight in one pass: b[2k][i] is the low bound of coordinate k of child i, b[2k+1][i] the high
 * one, each the binary tree's double bound rounded OUTWARD to float (low bounds down, high bounds
 * up), so the float box contains the double box. child[i] >= 0: a wide node; < 0: a leaf whose
 * primitives are prims[~child[i] .. ~child[i] + nprim[i] - 1]. Unused slots (i >= count) have
 * lo = +inf, hi = -inf and are masked out by `valid`. 256 bytes: four cache lines, 64-byte
 * aligned, so a node never straddles more lines than it must. */
typedef struct cj_bvhw_node {
    float b[6][CJ_BVHW_W];
    int32_t child[CJ_BVHW_W];
    uint8_t nprim[CJ_BVHW_W];
    int32_t count; /* used slots */
    int32_t valid; /* (1 << count) - 1 */
    int32_t pad_[4];
} cj_bvhw_node;
_Static_assert(sizeof(cj_bvhw_node) == 256, "a wide node is four whole cache lines");

typedef struct cj_bvhw_tris cj_bvhw_tris; /* bvh_leaf_internal.h */

typedef struct cj_bvhw {
    size_t count;        /* wide nodes */
    cj_bvhw_node *nodes; /* callback BVH: nodes[0] is the root; 64-byte aligned. NULL in a mesh
                          * BVH once its triangles are packed into `lines` */
    /* Mesh BVH only: the nodes and the triangles (in packets of 4 per leaf) interleaved in one
     * array of 64-byte lines, depth first, each node followed by the packets of its leaf
     * children, so the line after a node is often the leaf the ray tests next (the processor's
     * stream prefetch fetches it with the node). There a child reference is a line index: a
     * node at line child[i] >= 0, or a leaf whose nprim[i] triangles fill ceil(nprim[i] / 4)
     * packets from line ~child[i]. The root is at line 0. */
    unsigned char *lines; /* 64-byte aligned */
    size_t line_count, tris_count;
    void *nodes_mem_, *lines_mem_; /* the allocations the aligned arrays live in */
} cj_bvhw;

/* cj_bvh_build with the leaf cost counted in blocks of `block` primitives, a power of two (1:
 * cj_bvh_build; 4: the mesh BVH, whose leaves are tested 4 triangles at a time). */
cj_status cj_bvh_build_blocks(const cj_aabb *boxes, size_t count, const cj_allocator *alloc,
                              int block, cj_bvh **out);

/* Collapses the binary tree of bvh into bvh->wide_ (each wide node takes a binary node's
 * children, then repeatedly the children of its largest inner child, up to CJ_BVHW_W). */
cj_status cj_bvhw_build(cj_bvh *bvh);
void cj_bvhw_destroy(cj_bvh *bvh);
/* Packs bvh->tri (set) and the wide nodes into bvh->wide_->lines (see cj_bvhw), and frees the
 * wide nodes' own array. */
cj_status cj_bvhw_pack_triangles(cj_bvh *bvh);

/* Rounds a double to float downward / upward (to the nearest float on that side; ±inf beyond the
 * float range on the far side, ±FLT_MAX on the near side): the conversion rounds to nearest, and
 * when that landed on the wrong side one step of the float's bit pattern moves it back. */
static inline float cj_f32_step(float f, int up) {
    if (f == 0.0f) return up ? FLT_TRUE_MIN : -FLT_TRUE_MIN;
    uint32_t u;
    memcpy(&u, &f, sizeof u);
    u += ((f > 0.0f) == (up != 0)) ? 1u : (uint32_t)-1;
    memcpy(&f, &u, sizeof f);
    return f;
}
static inline float cj_f32_down(double x) {
    const float f = (float)x;
    return (double)f > x ? cj_f32_step(f, 0) : f;
}
static inline float cj_f32_up(double x) {
    const float f = (float)x;
    return (double)f < x ? cj_f32_step(f, 1) : f;
}

/* THE FLOAT SLAB TEST AND WHY IT IS CONSERVATIVE.
 *
 * Let the ray be o + t d (double), the box [lo, hi] (double) and lo' <= lo, hi' >= hi its float
 * bounds. Per coordinate the ray setup stores a float ou >= o and a float od <= o (f = float(o)
 * rounded to nearest is within half a float spacing of o, and f ± (|f| 2^-23 + 2^-149) rounded to
 * nearest is at least one spacing away from f, on its side: a branch-free directed rounding, at
 * most two spacings loose), and inv = float(1/d) (|relative error| <= u + 2^-53, u = 2^-24). Every
 * LOW plane is measured from ou and every HIGH plane from od, whatever the direction's sign: s_lo =
 * lo' - ou <= lo - o,    s_hi = hi' - od >= hi - o      (as real numbers). So for d > 0 the near
 * parameter's numerator s_lo / d is <= the true (lo - o) / d and the far one s_hi / d is >= the
 * true (hi - o) / d; for d < 0 the planes swap roles and the same holds (dividing by d < 0 reverses
 * the inequalities the right way). The computed tn' = fl(fl(s) * inv) = (s / d)(1 + θ),   |θ|
 * <= 3.1 u (the float subtraction rounds once, the product once, inv carries its error; a result in
 * the subnormal range adds an absolute error below 2^-149). The box's entry and exit are near =
 * P(max(tmin', tn'_x, tn'_y, tn'_z)),   far = Q(min(tmax', tf'_x, tf'_y, tf'_z)) with tmin' = tmin
 * rounded down, tmax' = tmax rounded up, and the paddings P(x) = min(x (1 - c), x (1 + c)) -
 * 2^-125,   Q(x) = max(x (1 - c), x (1 + c)) + 2^-125, c = 2^-20 = 16 u. P and Q are nondecreasing
 * (and stay so when rounded), so P(max(...)) = max(P(...)) and Q(min(...)) = min(Q(...)); P(tn') <=
 * s/d <= tn (the shrink by 16 u and the absolute 2^-125 exceed the 3.1 u relative error, the
 * rounding of the padding itself, and any subnormal error), likewise Q(tf') >= tf. Hence when the
 * ray truly meets the double box (max(tmin, tn_k) <= min(tmax, tf_k)) the float test has near <=
 * max(tmin, tn_k) <= min(tmax, tf_k) <= far: it reports the box. NaN (a zero numerator times an
 * infinite inverse: d = 0 with the origin on the plane in float) is skipped by max/min, which drops
 * that slab's constraint, again only more conservative; for d = 0 otherwise the slab gives ±inf
 * with the exact sign of the numerator, which is inside/outside the slab conservatively by the two
 * inequalities above. Overflow to ±inf keeps the order (rounding is monotone).
 *
 * When tmin >= 0 (nearly every ray) the paddings are one-sided: near >= tmin' >= 0, so P(x) =
 * x (1 - c) - 2^-125 there; and whenever the ray truly meets the box every true exit is >= tmin >=
 * 0, and then so is every computed one (the directed numerators keep their sign, and rounding keeps
 * the sign of a product), so Q(x) = x (1 + c) + 2^-125 on the values that matter, while a
 * negative far value only rejects a box the ray does not meet. One fused multiply-add each.
 *
 * The argument needs inv finite and nonzero and the origin in float range, so a ray with a
 * direction coordinate 0 < |d_k| < 2^-64 or > 2^64, or an origin coordinate beyond 2^64, is
 * walked EXHAUSTIVELY (inv = NaN: every box of the tree is entered); such rays are never
 * produced by the camera or the tracer's secondary rays in practice, and they stay exact, only
 * slow. */
typedef struct cj_bvhw_ray {
    size_t near[3], far[3]; /* byte offsets of the near / far plane rows of coordinate k */
#if defined(__AVX__)
    __m256 onear[3], ofar[3], inv[3]; /* each repeated in 8 lanes */
#elif defined(__SSE2__)
    __m128 onear[3], ofar[3], inv[3]; /* each repeated in 4 lanes */
#else
    float onear[3], ofar[3], inv[3];
#endif
    int nonneg; /* tmin >= 0: the one-sided paddings suffice */
} cj_bvhw_ray;

#define CJ_BVHW_PAD 0x1p-20f
#define CJ_BVHW_ABS 0x1p-125f

/* The exhaustive walk is inv = NaN in every coordinate: every slab is then skipped and each used
 * slot is entered. */
static inline void cj_bvhw_ray_setup(const cj_ray *ray, cj_bvhw_ray *r) {
#if defined(__AVX2__)
    /* the scalar form below, 3 coordinates in 4 lanes (lane 3 is ignored: it reads dir.x and
     * tmin, the next members of the ray) */
    const __m256d o = _mm256_loadu_pd(&ray->org.x), d = _mm256_loadu_pd(&ray->dir.x);
    const __m256i abs = _mm256_set1_epi64x(0x7fffffffffffffffLL);
    const __m256i bd = _mm256_and_si256(_mm256_castpd_si256(d), abs);
    const __m256i bo = _mm256_and_si256(_mm256_castpd_si256(o), abs);
    const __m256i lo_bits = _mm256_set1_epi64x(0x3bf0000000000000LL); /* 2^-64 */
    const __m256i hi_bits = _mm256_set1_epi64x(0x43f0000000000000LL); /* 2^64 */
    const __m256i tiny = _mm256_andnot_si256(_mm256_cmpeq_epi64(bd, _mm256_setzero_si256()),
                                             _mm256_cmpgt_epi64(lo_bits, bd));
    const __m256i bad = _mm256_or_si256(
        tiny, _mm256_or_si256(_mm256_cmpgt_epi64(bd, hi_bits), _mm256_cmpgt_epi64(bo, hi_bits)));
    const int all = _mm256_movemask_pd(_mm256_castsi256_pd(bad)) & 7;
    const __m128 f = _mm256_cvtpd_ps(o);
    const __m128 step =
        _mm_add_ps(_mm_mul_ps(_mm_andnot_ps(_mm_set1_ps(-0.0f), f), _mm_set1_ps(0x1p-23f)),
                   _mm_set1_ps(0x1p-149f));
    const __m128 ou = _mm_add_ps(f, step), od = _mm_sub_ps(f, step);
    const __m128 inv =
        all ? _mm_set1_ps(NAN) : _mm256_cvtpd_ps(_mm256_div_pd(_mm256_set1_pd(1.0), d));
    const __m128 negv = _mm256_cvtpd_ps(d); /* the sign survives the conversion, -0 too */
    const int neg = _mm256_movemask_pd(d);
    float on[4], of[4], iv[4];
    _mm_storeu_ps(on, _mm_blendv_ps(ou, od, negv));
    _mm_storeu_ps(of, _mm_blendv_ps(od, ou, negv));
    _mm_storeu_ps(iv, inv);
    for (int k = 0; k < 3; ++k) {
        const int nk = (neg >> k) & 1;
        r->near[k] = (size_t)(2 * k + nk) * CJ_BVHW_W * sizeof(float);
        r->far[k] = (size_t)(2 * k + !nk) * CJ_BVHW_W * sizeof(float);
        r->onear[k] = _mm256_set1_ps(on[k]);
        r->ofar[k] = _mm256_set1_ps(of[k]);
        r->inv[k] = _mm256_set1_ps(iv[k]);
    }
#else
    const double o[3] = {ray->org.x, ray->org.y, ray->org.z};
    const double d[3] = {ray->dir.x, ray->dir.y, ray->dir.z};
    /* on the bit patterns of |d| and |o| (ordered as the values are, NaN above infinity): a
     * direction in (0, 2^-64) is 0 < bits < B(2^-64), i.e. bits - 1 < B(2^-64) - 1 unsigned */
    const uint64_t lo_bits = 0x3bf0000000000000u, hi_bits = 0x43f0000000000000u; /* 2^-64, 2^64 */
    int all = 0;
    for (int k = 0; k < 3; ++k) {
        uint64_t bd, bo;
        memcpy(&bd, &d[k], sizeof bd);
        memcpy(&bo, &o[k], sizeof bo);
        bd &= 0x7fffffffffffffffu;
        bo &= 0x7fffffffffffffffu;
        all |= (bd - 1u < lo_bits - 1u) | (bd > hi_bits) | (bo > hi_bits);
    }
    for (int k = 0; k < 3; ++k) {
        const int neg = signbit(d[k]) != 0;
        const float f = (float)o[k], step = fabsf(f) * 0x1p-23f + 0x1p-149f;
        const float ou = f + step, od = f - step;
        const float inv = all ? NAN : (float)(1.0 / d[k]);
        /* d >= 0: the near plane is the low one (row 2k), measured from ou; the far plane the
         * high one, from od; d < 0 swaps them */
        r->near[k] = (size_t)(2 * k + neg) * CJ_BVHW_W * sizeof(float);
        r->far[k] = (size_t)(2 * k + !neg) * CJ_BVHW_W * sizeof(float);
#if defined(__AVX__)
        r->onear[k] = _mm256_set1_ps(neg ? od : ou);
        r->ofar[k] = _mm256_set1_ps(neg ? ou : od);
        r->inv[k] = _mm256_set1_ps(inv);
#elif defined(__SSE2__)
        r->onear[k] = _mm_set1_ps(neg ? od : ou);
        r->ofar[k] = _mm_set1_ps(neg ? ou : od);
        r->inv[k] = _mm_set1_ps(inv);
#else
        r->onear[k] = neg ? od : ou;
        r->ofar[k] = neg ? ou : od;
        r->inv[k] = inv;
#endif
    }
#endif
    r->nonneg = ray->tmin >= 0.0;
}

/* Slab test of the ray against the CJ_BVHW_W child boxes of n over [tmin', tmax'] (floats,
 * rounded outward by the caller): bit i of the result is set when child i may be met, with a
 * lower bound of its entry parameter in t0[i]. */
static inline int cj_bvhw_slab(const cj_bvhw_node *n, const cj_bvhw_ray *r, float tmin, float tmax,
                               float t0[CJ_BVHW_W]) {
    const char *base = (const char *)n->b;
#if defined(__AVX__)
    __m256 vn = _mm256_set1_ps(tmin), vf = _mm256_set1_ps(tmax);
    /* max/min return their second operand when the first is NaN: NaN leaves the bound */
#define CJ_BVHW_AXIS(k)                                                                            \
    vn = _mm256_max_ps(                                                                            \
        _mm256_mul_ps(                                                                             \
            _mm256_sub_ps(_mm256_loadu_ps((const float *)(base + r->near[k])), r->onear[k]),       \
            r->inv[k]),                                                                            \
        vn);                                                                                       \
    vf = _mm256_min_ps(                                                                            \
        _mm256_mul_ps(                                                                             \
            _mm256_sub_ps(_mm256_loadu_ps((const float *)(base + r->far[k])), r->ofar[k]),         \
            r->inv[k]),                                                                            \
        vf)
    CJ_BVHW_AXIS(0);
    CJ_BVHW_AXIS(1);
    CJ_BVHW_AXIS(2);
#undef CJ_BVHW_AXIS
    const __m256 lo = _mm256_set1_ps(1.0f - CJ_BVHW_PAD), hi = _mm256_set1_ps(1.0f + CJ_BVHW_PAD);
    const __m256 ab = _mm256_set1_ps(CJ_BVHW_ABS);
    if (r->nonneg) { /* near >= tmin' >= 0; far matters only when >= 0 (see above) */
#ifdef __FMA__
        vn = _mm256_fmsub_ps(vn, lo, ab);
        vf = _mm256_fmadd_ps(vf, hi, ab);
#else
        vn = _mm256_sub_ps(_mm256_mul_ps(vn, lo), ab);
        vf = _mm256_add_ps(_mm256_mul_ps(vf, hi), ab);
#endif
    } else {
        vn = _mm256_sub_ps(_mm256_min_ps(_mm256_mul_ps(vn, lo), _mm256_mul_ps(vn, hi)), ab);
        vf = _mm256_add_ps(_mm256_max_ps(_mm256_mul_ps(vf, lo), _mm256_mul_ps(vf, hi)), ab);
    }
    _mm256_storeu_ps(t0, vn);
    return _mm256_movemask_ps(_mm256_cmp_ps(vn, vf, _CMP_LE_OQ)) & n->valid;
#elif defined(__SSE2__)
    int mask = 0;
    for (int h = 0; h < CJ_BVHW_W; h += 4) { /* the same arithmetic, 4 lanes at a time */
        __m128 vn = _mm_set1_ps(tmin), vf = _mm_set1_ps(tmax);
        for (int k = 0; k < 3; ++k) {
            const float *pn = (const float *)(base + r->near[k]) + h;
            const float *pf = (const float *)(base + r->far[k]) + h;
            vn = _mm_max_ps(_mm_mul_ps(_mm_sub_ps(_mm_loadu_ps(pn), r->onear[k]), r->inv[k]), vn);
            vf = _mm_min_ps(_mm_mul_ps(_mm_sub_ps(_mm_loadu_ps(pf), r->ofar[k]), r->inv[k]), vf);
        }
        const __m128 lo = _mm_set1_ps(1.0f - CJ_BVHW_PAD), hi = _mm_set1_ps(1.0f + CJ_BVHW_PAD);
        const __m128 ab = _mm_set1_ps(CJ_BVHW_ABS);
        vn = _mm_sub_ps(_mm_min_ps(_mm_mul_ps(vn, lo), _mm_mul_ps(vn, hi)), ab);
        vf = _mm_add_ps(_mm_max_ps(_mm_mul_ps(vf, lo), _mm_mul_ps(vf, hi)), ab);
        _mm_storeu_ps(t0 + h, vn);
        mask |= _mm_movemask_ps(_mm_cmple_ps(vn, vf)) << h;
    }
    return mask & n->valid;
#else
    int mask = 0;
    for (int i = 0; i < CJ_BVHW_W; ++i) {
        float vn = tmin, vf = tmax;
        for (int k = 0; k < 3; ++k) {
            const float tn = (((const float *)(base + r->near[k]))[i] - r->onear[k]) * r->inv[k];
            const float tf = (((const float *)(base + r->far[k]))[i] - r->ofar[k]) * r->inv[k];
            if (tn > vn) vn = tn;
            if (tf < vf) vf = tf;
        }
        const float a = vn * (1.0f - CJ_BVHW_PAD), b = vn * (1.0f + CJ_BVHW_PAD);
        const float c = vf * (1.0f - CJ_BVHW_PAD), e = vf * (1.0f + CJ_BVHW_PAD);
        vn = (a < b ? a : b) - CJ_BVHW_ABS;
        vf = (c > e ? c : e) + CJ_BVHW_ABS;
        t0[i] = vn;
        if (vn <= vf) mask |= 1 << i;
    }
    return mask & n->valid;
#endif
}

#endif

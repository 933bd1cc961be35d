/* Per-tile rasterization: the binned triangles of one tile, in input order, into the tile's
 * depth/id planes (the visibility pass), the conversion of the winners into visibility samples
 * with perspective-correct barycentrics, and the forward (every fragment) mode.
 *
 * Every value computed at a sample — edge functions, depth, barycentrics — is a fixed function
 * of the set-up triangle and the sample's absolute position (integers, or doubles evaluated in
 * one order from exact integer offsets), never of the tile's origin: the same frame comes out
 * for any tile size and thread count. The AVX2 kernels compute the same IEEE operations as
 * the scalar ones, lane by lane.
 *
 * Scratch planes are sample-major (plane q holds sample q of every pixel, row by row), so a
 * row of one sample is contiguous for the span kernels. Wide spans are cut exactly by integer
 * division of the edge functions (no per-sample edge test); narrow ones test the three edge
 * functions per sample. */
#include "tri_internal.h"

#include <math.h>
#include <string.h>

#if defined(__AVX2__)
#include <immintrin.h>
#endif

/* Below this many pixels a row is scanned with per-sample edge tests; above, its exact span
 * is found by three integer divisions per sample row. */
#define NARROW_SPAN 24

static inline double plane_at(const cj_tri_plane *p, double dx, double dy) {
    return (p->v0 + p->vb * dy) + p->va * dx;
}

static inline float clamp_depth(double z) {
    z = z < -1.0 ? -1.0 : z;
    z = z > 1.0 ? 1.0 : z;
    return (float)z;
}

float cj_tri_depth_at(const cj_tri_setup *s, int64_t X, int64_t Y) {
    return clamp_depth(plane_at(&s->z, (double)(X - s->xr), (double)(Y - s->yr)));
}

void cj_tri_bary_at(const cj_tri_setup *s, const cj_tri_attr *a, int64_t X, int64_t Y, float *b1,
                    float *b2) {
    const double dx = (double)(X - s->xr), dy = (double)(Y - s->yr);
    const double r = plane_at(&a->r, dx, dy);
    *b1 = (float)(plane_at(&a->q1, dx, dy) / r);
    *b2 = (float)(plane_at(&a->q2, dx, dy) / r);
}

/* floor(n / d) and ceil(n / d) for d > 0. */
static inline int64_t floor_div(int64_t n, int64_t d) {
    int64_t q = n / d;
    return (n % d != 0 && n < 0) ? q - 1 : q;
}
static inline int64_t ceil_div(int64_t n, int64_t d) {
    int64_t q = n / d;
    return (n % d != 0 && n > 0) ? q + 1 : q;
}

/* The exact columns [*lo, *hi) of the sample row at Yq (sample x offset ox) inside all three
 * edges: E_k = 256 a_k x + g_k >= 0 with g_k = a_k ox + b_k Yq + c_k. Returns 0 if empty. */
static inline int exact_span(const cj_tri_setup *s, int64_t ox, int64_t Yq, int *lo, int *hi) {
    int64_t l = *lo, h = *hi;
    for (int k = 0; k < 3; ++k) {
        const int64_t a = s->ea[k], g = a * ox + s->eb[k] * Yq + s->ec[k];
        if (a > 0) {
            const int64_t x = ceil_div(-g, 256 * a);
            if (x > l) l = x;
        } else if (a < 0) {
            const int64_t x = floor_div(g, -256 * a) + 1;
            if (x < h) h = x;
        } else if (g < 0) {
            return 0;
        }
    }
    if (l >= h) return 0;
    *lo = (int)l;
    *hi = (int)h;
    return 1;
}

#if defined(__AVX2__)
/* Lane masks for the 4-bit "all edges inside" patterns. */
static const int32_t k_lane_mask[16][4] = {
    {0, 0, 0, 0},   {-1, 0, 0, 0},   {0, -1, 0, 0},   {-1, -1, 0, 0},
    {0, 0, -1, 0},  {-1, 0, -1, 0},  {0, -1, -1, 0},  {-1, -1, -1, 0},
    {0, 0, 0, -1},  {-1, 0, 0, -1},  {0, -1, 0, -1},  {-1, -1, 0, -1},
    {0, 0, -1, -1}, {-1, 0, -1, -1}, {0, -1, -1, -1}, {-1, -1, -1, -1}};
#endif

/* Depth test of n consecutive samples of one sample row: z = (rowz + za·dx) with dx = dx0 +
 * 256 i, clamped to [−1, 1], written with id where strictly nearer. With edges (e != NULL):
 * only where e_k + i·st_k >= 0 for k = 0, 1, 2. Returns the samples written. */
static inline uint64_t span_kernel(float *dp, uint32_t *ip, int n, double rowz, double za,
                                   double dx0, uint32_t id, const int64_t *e, const int64_t *st) {
    uint64_t wr = 0;
    int i = 0;
    int64_t e0 = 0, e1 = 0, e2 = 0;
    if (e) {
        e0 = e[0];
        e1 = e[1];
        e2 = e[2];
    }
#if defined(__AVX2__)
    const __m256d vz = _mm256_set1_pd(rowz), va = _mm256_set1_pd(za);
    const __m256d lo = _mm256_set1_pd(-1.0), hi = _mm256_set1_pd(1.0);
    const __m256d step = _mm256_set1_pd(1024.0);
    __m256d dx = _mm256_setr_pd(dx0, dx0 + 256.0, dx0 + 512.0, dx0 + 768.0);
    const __m128i vid = _mm_set1_epi32((int)id);
    __m256i ve0 = _mm256_setzero_si256(), ve1 = ve0, ve2 = ve0, vs0 = ve0, vs1 = ve0, vs2 = ve0;
    if (e) {
        ve0 = _mm256_setr_epi64x(e0, e0 + st[0], e0 + 2 * st[0], e0 + 3 * st[0]);
        ve1 = _mm256_setr_epi64x(e1, e1 + st[1], e1 + 2 * st[1], e1 + 3 * st[1]);
        ve2 = _mm256_setr_epi64x(e2, e2 + st[2], e2 + 2 * st[2], e2 + 3 * st[2]);
        vs0 = _mm256_set1_epi64x(4 * st[0]);
        vs1 = _mm256_set1_epi64x(4 * st[1]);
        vs2 = _mm256_set1_epi64x(4 * st[2]);
    }
    /* Whole groups of four, the last one masked to the span: the lanes past the end read and
     * write back their own values (the scratch planes are padded by 8). */
    for (; i < n; i += 4) {
        __m256d z = _mm256_add_pd(vz, _mm256_mul_pd(va, dx));
        z = _mm256_min_pd(_mm256_max_pd(z, lo), hi);
        const __m128 zf = _mm256_cvtpd_ps(z);
        const __m128 old = _mm_loadu_ps(dp + i);
        __m128 m = _mm_cmplt_ps(zf, old);
        if (n - i < 4)
            m = _mm_and_ps(m, _mm_loadu_ps((const float *)k_lane_mask[(1 << (n - i)) - 1]));
        if (e) {
            const __m256i o = _mm256_or_si256(_mm256_or_si256(ve0, ve1), ve2);
            const int outside = _mm256_movemask_pd(_mm256_castsi256_pd(o));
            m = _mm_and_ps(m, _mm_loadu_ps((const float *)k_lane_mask[outside ^ 15]));
            ve0 = _mm256_add_epi64(ve0, vs0);
            ve1 = _mm256_add_epi64(ve1, vs1);
            ve2 = _mm256_add_epi64(ve2, vs2);
        }
        _mm_storeu_ps(dp + i, _mm_blendv_ps(old, zf, m));
        const __m128i oid = _mm_loadu_si128((const __m128i *)(ip + i));
        _mm_storeu_si128((__m128i *)(ip + i), _mm_blendv_epi8(oid, vid, _mm_castps_si128(m)));
        wr += (uint64_t)__builtin_popcount((unsigned)_mm_movemask_ps(m));
        dx = _mm256_add_pd(dx, step);
    }
#endif
    for (; i < n; ++i) {
        const float z = clamp_depth(rowz + za * (dx0 + 256.0 * i));
        const float old = dp[i];
        int pass = z < old;
        if (e) {
            pass &= (e0 | e1 | e2) >= 0;
            e0 += st[0];
            e1 += st[1];
            e2 += st[2];
        }
        dp[i] = pass ? z : old;
        ip[i] = pass ? id : ip[i];
        wr += (uint64_t)pass;
    }
    return wr;
}

#if defined(__AVX2__)
/* Columns up to which a small triangle's rows are scanned in groups of 8 lanes (beyond, the
 * exact spans of the general path test fewer samples). */
#define SMALL_SPAN 32

/* The visibility pass of a SMALL triangle: every edge coefficient satisfies |ea_k|, |eb_k| <=
 * 2^14 (the snapped triangle spans at most 64 pixels each way; set-up marks it in s->small),
 * its columns in the tile scanned in groups of 8 lanes.
 *
 * 32-BIT EDGE FUNCTIONS. Every value the kernel forms is E_k at a sample P = (256 x + ox,
 * 256 y + oy) with x in [xa, xb + 7) and y in [ya, yb), i.e. within the triangle's pixel
 * bounding box widened by 7 pixels to the right (the last group's lanes past xb). Writing
 * E_k(P) = ea (PX − X_k) + eb (PY − Y_k) − bias with (X_k, Y_k) a vertex: the vertices lie in
 * the snapped box [minX, maxX] × [minY, maxY], whose sides are at most 2^14 (each side is the
 * largest |dx| or |dy| of an edge), and the pixel box reaches at most 255 below the box and
 * 255 + 7·256 above it, so |PX − X_k| <= 2^14 + 2^11 and |PY − Y_k| <= 2^14 + 2^8. Hence
 *     |E_k(P)| <= 2^14 (2^14 + 2^11) + 2^14 (2^14 + 2^8) + 1 < 2^29 + 2^26 < 2^31:
 * the int32 lanes hold the same integers as the 64-bit evaluation, and the coverage is the
 * same. Depth is the double plane of span_kernel, (v0 + vb·dy) + va·dx from exact offsets,
 * lane by lane: the same IEEE operations, the same floats. Lanes past xb load and store back
 * their own values (the scratch planes are padded by 8). */
/* Depth test of one group of 8 samples of sample row Yq starting at offset dx (exact, from the
 * triangle's reference point) where `cover` is set; returns the samples written. */
static inline uint64_t small_group(const cj_tri_setup *s, int64_t Yq, double dx, __m256i cover,
                                   float *dp, uint32_t *ip, __m256 vid) {
    const __m256d lo = _mm256_set1_pd(-1.0), hi = _mm256_set1_pd(1.0);
    const __m256d va = _mm256_set1_pd(s->z.va);
    const __m256d vz = _mm256_set1_pd(s->z.v0 + s->z.vb * (double)(Yq - s->yr));
    const __m256d gdx = _mm256_set1_pd(dx);
    __m256d z0 = _mm256_add_pd(
        vz, _mm256_mul_pd(va, _mm256_add_pd(gdx, _mm256_setr_pd(0.0, 256.0, 512.0, 768.0))));
    __m256d z1 = _mm256_add_pd(
        vz, _mm256_mul_pd(va, _mm256_add_pd(gdx, _mm256_setr_pd(1024.0, 1280.0, 1536.0, 1792.0))));
    z0 = _mm256_min_pd(_mm256_max_pd(z0, lo), hi);
    z1 = _mm256_min_pd(_mm256_max_pd(z1, lo), hi);
    const __m256 zf = _mm256_set_m128(_mm256_cvtpd_ps(z1), _mm256_cvtpd_ps(z0));
    const __m256 old = _mm256_loadu_ps(dp);
    const __m256 m = _mm256_and_ps(_mm256_cmp_ps(zf, old, _CMP_LT_OQ), _mm256_castsi256_ps(cover));
    _mm256_storeu_ps(dp, _mm256_blendv_ps(old, zf, m));
    const __m256 oid = _mm256_loadu_ps((const float *)ip);
    _mm256_storeu_ps((float *)ip, _mm256_blendv_ps(oid, vid, m));
    return (uint64_t)__builtin_popcount((unsigned)_mm256_movemask_ps(m));
}

static void raster_small(const cj_raster_prep *p, const cj_tri_setup *s, uint32_t id,
                         const cj_tile *t, cj_tri_scratch *sc, int xa, int xb, int ya, int yb) {
    const int tw = t->x1 - t->x0, spp = p->spp;
    const size_t plane = (size_t)tw * (size_t)(t->y1 - t->y0);
    const __m256i lane = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
    const __m256 vid = _mm256_castsi256_ps(_mm256_set1_epi32((int)id));
    /* Per-row step of each edge (256 eb; the per-lane step 256 ea is formed per sample, which
     * keeps the kernel's vectors within the 16 registers). */
    const __m256i ry0 = _mm256_set1_epi32((int32_t)(256 * (int64_t)s->eb[0]));
    const __m256i ry1 = _mm256_set1_epi32((int32_t)(256 * (int64_t)s->eb[1]));
    const __m256i ry2 = _mm256_set1_epi32((int32_t)(256 * (int64_t)s->eb[2]));
    const __m256i lane256 = _mm256_slli_epi32(lane, 8);
    uint64_t written = 0;
    for (int q = 0; q < spp; ++q) {
        const int64_t X = (int64_t)xa * 256 + p->ox[q], Y = (int64_t)ya * 256 + p->oy[q];
        __m256i e0 =
            _mm256_add_epi32(_mm256_set1_epi32((int32_t)(s->ea[0] * X + s->eb[0] * Y + s->ec[0])),
                             _mm256_mullo_epi32(lane256, _mm256_set1_epi32(s->ea[0])));
        __m256i e1 =
            _mm256_add_epi32(_mm256_set1_epi32((int32_t)(s->ea[1] * X + s->eb[1] * Y + s->ec[1])),
                             _mm256_mullo_epi32(lane256, _mm256_set1_epi32(s->ea[1])));
        __m256i e2 =
            _mm256_add_epi32(_mm256_set1_epi32((int32_t)(s->ea[2] * X + s->eb[2] * Y + s->ec[2])),
                             _mm256_mullo_epi32(lane256, _mm256_set1_epi32(s->ea[2])));
        const double dx0 = (double)(X - s->xr);
        size_t at = (size_t)q * plane + (size_t)(ya - t->y0) * tw + (size_t)(xa - t->x0);
        if (xb - xa <= 8) { /* one group per row */
            const __m256i in_x = _mm256_cmpgt_epi32(_mm256_set1_epi32(xb - xa), lane);
            for (int y = ya; y < yb; ++y, at += (size_t)tw) {
                const __m256i out = _mm256_or_si256(_mm256_or_si256(e0, e1), e2);
                const __m256i cover = _mm256_andnot_si256(_mm256_srai_epi32(out, 31), in_x);
                e0 = _mm256_add_epi32(e0, ry0);
                e1 = _mm256_add_epi32(e1, ry1);
                e2 = _mm256_add_epi32(e2, ry2);
                if (_mm256_testz_si256(cover, cover)) continue;
                written += small_group(s, y * 256 + p->oy[q], dx0, cover, sc->depth + at,
                                       sc->id + at, vid);
            }
            continue;
        }
        for (int y = ya; y < yb; ++y, at += (size_t)tw) {
            __m256i g0 = e0, g1 = e1, g2 = e2;
            e0 = _mm256_add_epi32(e0, ry0);
            e1 = _mm256_add_epi32(e1, ry1);
            e2 = _mm256_add_epi32(e2, ry2);
            for (int xg = xa; xg < xb; xg += 8) {
                const __m256i in_x = _mm256_cmpgt_epi32(_mm256_set1_epi32(xb - xg), lane);
                const __m256i out = _mm256_or_si256(_mm256_or_si256(g0, g1), g2);
                const __m256i cover = _mm256_andnot_si256(_mm256_srai_epi32(out, 31), in_x);
                if (xg + 8 < xb) { /* the next group: 8 pixels to the right */
                    g0 = _mm256_add_epi32(g0, _mm256_set1_epi32(2048 * s->ea[0]));
                    g1 = _mm256_add_epi32(g1, _mm256_set1_epi32(2048 * s->ea[1]));
                    g2 = _mm256_add_epi32(g2, _mm256_set1_epi32(2048 * s->ea[2]));
                }
                if (_mm256_testz_si256(cover, cover)) continue;
                written +=
                    small_group(s, y * 256 + p->oy[q], dx0 + 256.0 * (double)(xg - xa), cover,
                                sc->depth + at + (xg - xa), sc->id + at + (xg - xa), vid);
            }
        }
    }
    sc->tested += (uint64_t)(xb - xa) * (uint64_t)(yb - ya) * (uint64_t)spp;
    sc->written += written;
}
#endif

/* The visibility pass of one triangle over the tile. */
static void raster_one(const cj_raster_prep *p, const cj_tri_setup *s, uint32_t id,
                       const cj_tile *t, cj_tri_scratch *sc) {
    const int xa = s->minx > t->x0 ? s->minx : t->x0;
    const int xb = s->maxx + 1 < t->x1 ? s->maxx + 1 : t->x1;
    const int ya = s->miny > t->y0 ? s->miny : t->y0;
    const int yb = s->maxy + 1 < t->y1 ? s->maxy + 1 : t->y1;
    if (xa >= xb || ya >= yb) return;
#if defined(__AVX2__)
    if (s->small && xb - xa <= SMALL_SPAN) {
        raster_small(p, s, id, t, sc, xa, xb, ya, yb);
        return;
    }
#endif
    const int tw = t->x1 - t->x0, spp = p->spp;
    const size_t plane = (size_t)tw * (size_t)(t->y1 - t->y0);
    const int narrow = xb - xa <= NARROW_SPAN;
    const int64_t st[3] = {(int64_t)s->ea[0] * 256, (int64_t)s->ea[1] * 256,
                           (int64_t)s->ea[2] * 256};
    const double za = s->z.va;
    uint64_t tested = 0, written = 0;
    for (int y = ya; y < yb; ++y) {
        const size_t row = (size_t)(y - t->y0) * tw;
        for (int q = 0; q < spp; ++q) {
            const int64_t ox = p->ox[q], Yq = (int64_t)y * 256 + p->oy[q];
            int lo = xa, hi = xb;
            int64_t e[3];
            if (narrow) {
                const int64_t X = (int64_t)xa * 256 + ox;
                for (int k = 0; k < 3; ++k) e[k] = s->ea[k] * X + s->eb[k] * Yq + s->ec[k];
            } else if (!exact_span(s, ox, Yq, &lo, &hi)) {
                continue;
            }
            const double rowz = s->z.v0 + s->z.vb * (double)(Yq - s->yr);
            const double dx0 = (double)((int64_t)lo * 256 + ox - s->xr);
            const size_t at = (size_t)q * plane + row + (size_t)(lo - t->x0);
            tested += (uint64_t)(hi - lo);
            written += span_kernel(sc->depth + at, sc->id + at, hi - lo, rowz, za, dx0, id,
                                   narrow ? e : NULL, st);
        }
    }
    sc->tested += tested;
    sc->written += written;
}

void cj_tri_render_tile(const cj_raster_prep *p, const cj_tile *t, cj_tri_scratch *sc,
                        int resolve) {
    const int spp = p->spp, tw = t->x1 - t->x0;
    const size_t plane = (size_t)tw * (size_t)(t->y1 - t->y0), n = plane * (size_t)spp;
    size_t c = 0;
#if defined(__AVX2__)
    /* 8 samples a store (the compiler leaves this loop scalar at -O2: 4 instructions a sample,
     * a tenth of a small triangle's visibility cost). */
    const __m256 far = _mm256_set1_ps(1.0f);
    for (; c + 8 <= n; c += 8) _mm256_storeu_ps(sc->depth + c, far);
#endif
    for (; c < n; ++c) sc->depth[c] = 1.0f;
    memset(sc->id, 0xff, n * sizeof *sc->id); /* CJ_RASTER_NO_TRI */
    const size_t b0 = p->bin_start[t->index], b1 = p->bin_start[t->index + 1];
    for (size_t b = b0; b < b1; ++b) {
        /* Binned triangles are scattered over the set-up array: fetch ahead. */
        if (b + 12 < b1) { /* every line of the record: its first, second and last byte */
            const char *ahead = (const char *)&p->setups[p->bin_items[b + 12]];
            __builtin_prefetch(ahead);
            __builtin_prefetch(ahead + 64);
            __builtin_prefetch(ahead + sizeof(cj_tri_setup) - 1);
        }
        const uint32_t id = p->bin_items[b];
        raster_one(p, &p->setups[id], id, t, sc);
    }
    if (!resolve) return;
    /* Resolve the winners into the tile's samples (pixel-major): source index and, unless
     * switched off, barycentrics, once per visible sample. Sample row by sample row, so the
     * planes are read in order. Along a row the winner changes rarely: its planes' row parts
     * v0 + vb·dy (the first operation of plane_at, the same doubles) are kept while it lasts,
     * leaving + va·dx and the two divisions per sample. */
    const int bary = p->barycentrics;
    const uint32_t *src = p->src;
    const float *dpl = sc->depth;
    const uint32_t *ipl = sc->id;
    cj_vis_sample *out = t->samples;
    for (int y = t->y0; y < t->y1; ++y) {
        const size_t row = (size_t)(y - t->y0) * tw;
        for (int q = 0; q < spp; ++q) {
            const float *dr = dpl + (size_t)q * plane + row;
            const uint32_t *ir = ipl + (size_t)q * plane + row;
            cj_vis_sample *o = out + row * spp + q;
            if (!bary) { /* depth and source only: a loop without branches */
                for (int i = 0; i < tw; ++i, o += spp) {
                    const uint32_t id = ir[i];
                    o->depth = dr[i];
                    o->tri = id == CJ_RASTER_NO_TRI ? CJ_RASTER_NO_TRI : src[id];
                    o->b1 = o->b2 = 0.0f;
                }
                continue;
            }
            const int64_t Y = (int64_t)y * 256 + p->oy[q];
            const int64_t X0 = (int64_t)t->x0 * 256 + p->ox[q];
            uint32_t last = CJ_RASTER_NO_TRI, last_src = CJ_RASTER_NO_TRI;
            int64_t xr = 0;
            double rr = 0, r1 = 0, r2 = 0, ra = 0, a1 = 0, a2 = 0;
            for (int i = 0; i < tw; ++i, o += spp) {
                const uint32_t id = ir[i];
                o->depth = dr[i];
                if (id == CJ_RASTER_NO_TRI) {
                    o->tri = CJ_RASTER_NO_TRI;
                    o->b1 = o->b2 = 0.0f;
                    continue;
                }
                if (id != last) {
                    last = id;
                    last_src = src[id];
                    const cj_tri_setup *st = &p->setups[id];
                    const cj_tri_attr *at = &p->attrs[id];
                    const double dy = (double)(Y - st->yr);
                    xr = st->xr;
                    rr = at->r.v0 + at->r.vb * dy;
                    r1 = at->q1.v0 + at->q1.vb * dy;
                    r2 = at->q2.v0 + at->q2.vb * dy;
                    ra = at->r.va;
                    a1 = at->q1.va;
                    a2 = at->q2.va;
                }
                o->tri = last_src;
                const double dx = (double)(X0 + 256 * (int64_t)i - xr);
                const double r = rr + ra * dx;
                o->b1 = (float)((r1 + a1 * dx) / r);
                o->b2 = (float)((r2 + a2 * dx) / r);
            }
        }
    }
}

void cj_raster_tile_forward(const cj_raster_prep *p, const cj_tile *t, cj_frag_fn frag,
                            void *user) {
    const int spp = p->spp;
    const int tw = t->x1 - t->x0;
    const size_t b0 = p->bin_start[t->index], b1 = p->bin_start[t->index + 1];
    for (size_t b = b0; b < b1; ++b) {
        const cj_tri_setup *s = &p->setups[p->bin_items[b]];
        const cj_tri_attr *at = &p->attrs[p->bin_items[b]];
        const int xa = s->minx > t->x0 ? s->minx : t->x0;
        const int xb = s->maxx + 1 < t->x1 ? s->maxx + 1 : t->x1;
        const int ya = s->miny > t->y0 ? s->miny : t->y0;
        const int yb = s->maxy + 1 < t->y1 ? s->maxy + 1 : t->y1;
        for (int y = ya; y < yb; ++y)
            for (int q = 0; q < spp; ++q) {
                const int64_t Y = (int64_t)y * 256 + p->oy[q];
                int lo = xa, hi = xb;
                if (!exact_span(s, p->ox[q], Y, &lo, &hi)) continue;
                for (int x = lo; x < hi; ++x) {
                    const int64_t X = (int64_t)x * 256 + p->ox[q];
                    const float z = cj_tri_depth_at(s, X, Y);
                    const size_t idx = ((size_t)(y - t->y0) * tw + (size_t)(x - t->x0)) * spp + q;
                    if (!(z < t->samples[idx].depth)) continue;
                    float bb1, bb2;
                    cj_tri_bary_at(s, at, X, Y, &bb1, &bb2);
                    frag(user, x, y, q, at->src, z, bb1, bb2);
                }
            }
    }
}

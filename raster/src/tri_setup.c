/* Preparation of a frame's triangles: validation, clipping, snapping to the 1/256 pixel grid,
 * 64-bit edge functions with the top-left rule, attribute planes, and binning into tiles
 * (count, then fill, so the bins are one array in input order). */
#define _DEFAULT_SOURCE /* madvise */
#include "tri_internal.h"

#include "casteljau/framebuffer.h"
#include "error_internal.h"
#include "clock_internal.h"

#include <assert.h>
#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#if defined(__AVX2__)
#include <immintrin.h>
#endif
#if defined(__linux__)
#include <sys/mman.h>
#include <unistd.h>
#endif

/* The per-triangle steps are inlined into the loop over the triangles (a call per triangle,
 * with its saved registers, was a tenth of the set-up). */
#if defined(__GNUC__)
#define ALWAYS_INLINE inline __attribute__((always_inline))
#else
#define ALWAYS_INLINE inline
#endif

/* ---- memory ------------------------------------------------------------------------------- */

static void *std_alloc(void *u, size_t n) {
    (void)u;
    return malloc(n);
}
static void std_free(void *u, void *p) {
    (void)u;
    free(p);
}

static void *xalloc(const cj_allocator *a, size_t n) {
    return a->alloc(a->user, n ? n : 1);
}

/* The set-up records are read in bin order, scattered over arrays of tens of megabytes: with
 * 4 KiB pages nearly every record costs a TLB miss besides its cache miss. Large arrays of a
 * prep that is kept across frames (`huge`: cj_raster_prepare_again) ask for transparent huge
 * pages (a hint: the pages of the whole 2 MiB-aligned extents inside the array, faulted in
 * later, may be huge; nothing changes where the kernel declines). Not for a prep used once:
 * faulting fresh huge pages every frame cost more set-up time than they saved. */
static void *xalloc_big(const cj_allocator *a, size_t n, int huge_pages) {
    void *m = xalloc(a, n);
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    const uintptr_t huge = (uintptr_t)1 << 21;
    if (m && huge_pages && n >= 2 * huge) {
        const uintptr_t lo = ((uintptr_t)m + huge - 1) & ~(huge - 1);
        const uintptr_t hi = ((uintptr_t)m + n) & ~(huge - 1);
        if (hi > lo) (void)madvise((void *)lo, hi - lo, MADV_HUGEPAGE);
    }
#else
    (void)huge_pages;
#endif
    return m;
}

/* ---- set-up ------------------------------------------------------------------------------ */

/* A polygon vertex after projection: exact screen position (pixels, double), snapped
 * position (1/256 pixel), pseudodepth and the interpolants. */
typedef struct pvert {
    double sx, sy;
    int64_t X, Y;
    double z, r, q1, q2;
} pvert;
/* The lane code stores (sx, sy) and (z, r) as pairs and loads (z, r, q1, q2) as one vector. */
_Static_assert(offsetof(pvert, sy) == offsetof(pvert, sx) + sizeof(double), "pvert: sx, sy");
_Static_assert(offsetof(pvert, q2) == offsetof(pvert, z) + 3 * sizeof(double),
               "pvert: z, r, q1, q2");

/* rint(256·((ndc + 1)·half)): adding and removing 1.5·2^52 rounds to the nearest integer,
 * ties to even (the default rounding mode), exactly like rint for |v| < 2^51 (the guard band
 * keeps |v| < 2^30), without a libm call. */
static int64_t snap(double ndc, double half) {
    const double v = 256.0 * ((ndc + 1.0) * half);
    volatile double magic = 0x1.8p52; /* volatile: the sum must not be folded away */
    return (int64_t)((v + magic) - magic);
}

#if !defined(__AVX2__)
/* The plane through (px_k, py_k, val_k); inv_det = 1/((p1 − p0) × (p2 − p0)). */
static cj_tri_plane plane_of(const pvert *v[3], const double px[3], const double py[3],
                             double inv_det, double val0, double val1, double val2) {
    const double d1x = px[1] - px[0], d1y = py[1] - py[0];
    const double d2x = px[2] - px[0], d2y = py[2] - py[0];
    const double e1 = val1 - val0, e2 = val2 - val0;
    cj_tri_plane p;
    p.va = (e1 * d2y - e2 * d1y) * inv_det;
    p.vb = (e2 * d1x - e1 * d2x) * inv_det;
    /* Re-anchor at the snapped vertex 0, the reference point of every plane. */
    p.v0 = val0 + p.va * ((double)v[0]->X - px[0]) + p.vb * ((double)v[0]->Y - py[0]);
    return p;
}
#endif

/* Sets up the screen triangle (a, b, c) of source triangle `src`. Returns 0 when it has zero
 * area after snapping, or its orientation disagrees with `want` (+1/−1, 0 = any: a piece of
 * a clipped polygon that snapping folded over is dropped rather than drawn twice). */
static ALWAYS_INLINE int setup_tri(const cj_raster_prep *p, const pvert *a, const pvert *b,
                                   const pvert *c, uint32_t src, int want, cj_tri_setup *s,
                                   cj_tri_attr *at) {
    const int64_t area = (b->X - a->X) * (c->Y - a->Y) - (b->Y - a->Y) * (c->X - a->X);
    if (area == 0) return 0;
    if (want != 0 && (area > 0 ? 1 : -1) != want) return 0;
    const pvert *v[3] = {a, b, c};
    if (area < 0) { /* orient counter-clockwise; the attributes travel with their vertex */
        v[1] = c;
        v[2] = b;
    }
    int64_t minX = v[0]->X, maxX = v[0]->X, minY = v[0]->Y, maxY = v[0]->Y;
#if defined(__AVX2__)
    /* The three edges in three 64-bit lanes. Snapped coordinates and their differences are
     * below 2^29 in magnitude (the guard band), so _mm256_mul_epi32, a product of the low 32
     * bits as signed integers, forms dy·X and dx·Y exactly. */
    const __m256i X = _mm256_setr_epi64x(v[0]->X, v[1]->X, v[2]->X, 0);
    const __m256i Y = _mm256_setr_epi64x(v[0]->Y, v[1]->Y, v[2]->Y, 0);
    const __m256i dx = _mm256_sub_epi64(_mm256_permute4x64_epi64(X, 0xC9), X); /* 1,2,0,3 */
    const __m256i dy = _mm256_sub_epi64(_mm256_permute4x64_epi64(Y, 0xC9), Y);
    const __m256i zero = _mm256_setzero_si256();
    const __m256i owned = _mm256_or_si256(
        _mm256_cmpgt_epi64(zero, dy),
        _mm256_and_si256(_mm256_cmpeq_epi64(dy, zero), _mm256_cmpgt_epi64(zero, dx)));
    /* ec = dy·X − dx·Y − (owned ? 0 : 1), with owned = −1 or 0 */
    const __m256i ec = _mm256_sub_epi64(
        _mm256_sub_epi64(_mm256_sub_epi64(_mm256_mul_epi32(dy, X), _mm256_mul_epi32(dx, Y)),
                         _mm256_set1_epi64x(1)),
        owned);
    int64_t ldx[4], ldy[4], lec[4];
    _mm256_storeu_si256((__m256i *)ldx, dx);
    _mm256_storeu_si256((__m256i *)ldy, dy);
    _mm256_storeu_si256((__m256i *)lec, ec);
    for (int k = 0; k < 3; ++k) {
        s->ea[k] = (int32_t)-ldy[k];
        s->eb[k] = (int32_t)ldx[k];
        s->ec[k] = lec[k];
        if (v[k]->X < minX) minX = v[k]->X;
        if (v[k]->X > maxX) maxX = v[k]->X;
        if (v[k]->Y < minY) minY = v[k]->Y;
        if (v[k]->Y > maxY) maxY = v[k]->Y;
    }
#else
    for (int k = 0; k < 3; ++k) {
        const pvert *p0 = v[k], *p1 = v[k == 2 ? 0 : k + 1];
        const int64_t dx = p1->X - p0->X, dy = p1->Y - p0->Y;
        const int owned = dy < 0 || (dy == 0 && dx < 0);
        s->ea[k] = (int32_t)-dy;
        s->eb[k] = (int32_t)dx;
        s->ec[k] = dy * p0->X - dx * p0->Y - (owned ? 0 : 1);
        if (p1->X < minX) minX = p1->X;
        if (p1->X > maxX) maxX = p1->X;
        if (p1->Y < minY) minY = p1->Y;
        if (p1->Y > maxY) maxY = p1->Y;
    }
#endif
    /* Pixels whose samples can lie in the bounding box (floor division by 256). */
    int64_t x0 = minX >> 8, x1 = maxX >> 8, y0 = minY >> 8, y1 = maxY >> 8;
    if (x0 < 0) x0 = 0;
    if (y0 < 0) y0 = 0;
    if (x1 > p->width - 1) x1 = p->width - 1;
    if (y1 > p->height - 1) y1 = p->height - 1;
    if (x0 > x1 || y0 > y1) return 0;
    const int64_t lim = (int64_t)1 << 14;
    s->small = maxX - minX <= lim && maxY - minY <= lim; /* each |ea_k| <= H, |eb_k| <= W */
    s->minx = (int)x0;
    s->maxx = (int)x1;
    s->miny = (int)y0;
    s->maxy = (int)y1;
    s->xr = v[0]->X;
    s->yr = v[0]->Y;
    at->src = src;
    /* Attribute planes through the exact (unsnapped) positions, in 1/256 pixel units; when
     * snapping made a sliver out of a (nearly) degenerate triangle, through the snapped ones. */
    double px[3], py[3];
    for (int k = 0; k < 3; ++k) {
        px[k] = 256.0 * v[k]->sx;
        py[k] = 256.0 * v[k]->sy;
    }
    double det = (px[1] - px[0]) * (py[2] - py[0]) - (py[1] - py[0]) * (px[2] - px[0]);
    if (!(fabs(det) >= 0.25 * fabs((double)area))) {
        for (int k = 0; k < 3; ++k) {
            px[k] = (double)v[k]->X;
            py[k] = (double)v[k]->Y;
        }
        det = (double)area;
    }
    const double inv = 1.0 / det;
#if defined(__AVX2__)
    /* The four planes (z, r, q1, q2 lie side by side in pvert) in the four lanes: lane by lane
     * the operations of plane_of, in its order, so the same doubles. */
    const __m256d d1x = _mm256_set1_pd(px[1] - px[0]), d1y = _mm256_set1_pd(py[1] - py[0]);
    const __m256d d2x = _mm256_set1_pd(px[2] - px[0]), d2y = _mm256_set1_pd(py[2] - py[0]);
    const __m256d vinv = _mm256_set1_pd(inv);
    const __m256d val0 = _mm256_loadu_pd(&v[0]->z);
    const __m256d e1 = _mm256_sub_pd(_mm256_loadu_pd(&v[1]->z), val0);
    const __m256d e2 = _mm256_sub_pd(_mm256_loadu_pd(&v[2]->z), val0);
    const __m256d va =
        _mm256_mul_pd(_mm256_sub_pd(_mm256_mul_pd(e1, d2y), _mm256_mul_pd(e2, d1y)), vinv);
    const __m256d vb =
        _mm256_mul_pd(_mm256_sub_pd(_mm256_mul_pd(e2, d1x), _mm256_mul_pd(e1, d2x)), vinv);
    const __m256d v0 = _mm256_add_pd(
        _mm256_add_pd(val0, _mm256_mul_pd(va, _mm256_set1_pd((double)v[0]->X - px[0]))),
        _mm256_mul_pd(vb, _mm256_set1_pd((double)v[0]->Y - py[0])));
    double l0[4], la[4], lb[4];
    _mm256_storeu_pd(l0, v0);
    _mm256_storeu_pd(la, va);
    _mm256_storeu_pd(lb, vb);
    s->z = (cj_tri_plane){l0[0], la[0], lb[0]};
    at->r = (cj_tri_plane){l0[1], la[1], lb[1]};
    at->q1 = (cj_tri_plane){l0[2], la[2], lb[2]};
    at->q2 = (cj_tri_plane){l0[3], la[3], lb[3]};
#else
    s->z = plane_of(v, px, py, inv, v[0]->z, v[1]->z, v[2]->z);
    at->r = plane_of(v, px, py, inv, v[0]->r, v[1]->r, v[2]->r);
    at->q1 = plane_of(v, px, py, inv, v[0]->q1, v[1]->q1, v[2]->q1);
    at->q2 = plane_of(v, px, py, inv, v[0]->q2, v[1]->q2, v[2]->q2);
#endif
    return 1;
}

/* The set-up arrays, grown by doubling (most triangles give one set-up, so the first
 * capacity is the triangle count). */
/* One vertex of the cache: outcode (bit p: outside plane p of cj_tri_clip; bit 6: w <= 0,
 * left to the general path) and, for code 0, the projection. */
#define VCACHE_SIZE 1024
typedef struct vcache {
    uint64_t tag; /* vertex index, UINT64_MAX = empty */
    unsigned code;
    pvert v;
} vcache;

static const vcache *vertex(vcache *cache, const double *clip, uint32_t i, double hw, double hh,
                            double gx, double gy) {
    vcache *e = &cache[i & (VCACHE_SIZE - 1)];
    if (e->tag == i) return e;
    const double *c = clip + 4 * (size_t)i;
    const double x = c[0], y = c[1], z = c[2], w = c[3];
    e->tag = i;
#if defined(__AVX2__)
    /* The six plane values of the scalar outcode below in two vectors (a − b is a + (−b) and
     * products commute: the same doubles), their signs read by two compares. */
    const __m256d xxyy = _mm256_setr_pd(-x, x, -y, y);
    const __m256d guard =
        _mm256_add_pd(_mm256_mul_pd(_mm256_set1_pd(w), _mm256_setr_pd(gx, gx, gy, gy)), xxyy);
    const __m128d nearfar = _mm_add_pd(_mm_setr_pd(z, -z), _mm_set1_pd(w));
    e->code = (unsigned)_mm_movemask_pd(_mm_cmp_pd(nearfar, _mm_setzero_pd(), _CMP_NGE_UQ)) |
              (unsigned)_mm256_movemask_pd(_mm256_cmp_pd(guard, _mm256_setzero_pd(), _CMP_NGE_UQ))
                  << 2 |
              (unsigned)!(w > 0.0) << 6;
#else
    e->code = (unsigned)!(z + w >= 0.0) | (unsigned)!(w - z >= 0.0) << 1 |
              (unsigned)!(gx * w - x >= 0.0) << 2 | (unsigned)!(gx * w + x >= 0.0) << 3 |
              (unsigned)!(gy * w - y >= 0.0) << 4 | (unsigned)!(gy * w + y >= 0.0) << 5 |
              (unsigned)!(w > 0.0) << 6;
#endif
    if (e->code) return e;
#if defined(__AVX2__)
    /* The same IEEE operations as the scalar path, four divisions at once; the snap reads the
     * integer out of the bit pattern of v + 1.5·2^52 (the sum is exact in the binade
     * [2^52, 2^53), whose unit is 1, so its bits minus those of 1.5·2^52 are rint(v)). */
    const __m256d num = _mm256_blend_pd(_mm256_loadu_pd(c), _mm256_set1_pd(1.0), 8);
    const __m256d q = _mm256_div_pd(num, _mm256_set1_pd(w)); /* x/w, y/w, z/w, 1/w */
    const __m128d sxy =
        _mm_mul_pd(_mm_add_pd(_mm256_castpd256_pd128(q), _mm_set1_pd(1.0)), _mm_setr_pd(hw, hh));
    const __m128d big = _mm_add_pd(_mm_mul_pd(_mm_set1_pd(256.0), sxy), _mm_set1_pd(0x1.8p52));
    const __m128i XY = _mm_sub_epi64(_mm_castpd_si128(big), _mm_set1_epi64x(0x4338000000000000));
    _mm_storeu_pd(&e->v.sx, sxy);
    e->v.X = _mm_cvtsi128_si64(XY);
    e->v.Y = _mm_extract_epi64(XY, 1);
    _mm_storeu_pd(&e->v.z, _mm256_extractf128_pd(q, 1));
#else
    const double xn = x / w, yn = y / w;
    e->v.sx = (xn + 1.0) * hw;
    e->v.sy = (yn + 1.0) * hh;
    e->v.X = snap(xn, hw);
    e->v.Y = snap(yn, hh);
    e->v.z = z / w;
    e->v.r = 1.0 / w;
#endif
    e->v.q1 = e->v.q2 = 0.0;
    return e;
}

typedef struct setup_list {
    const cj_allocator *alloc;
    int huge; /* xalloc_big's huge_pages */
    cj_tri_setup *v;
    cj_tri_attr *a;
    uint32_t *src;        /* a[i].src again, compact (what the resolve reads) */
    uint16_t (*range)[4]; /* tile range tx0, tx1, ty0, ty1 of each set-up */
    size_t n, cap;
} setup_list;

static int grow(const cj_allocator *al, void **arr, size_t n, size_t cap, size_t size, int huge) {
    void *na = xalloc_big(al, cap * size, huge);
    if (!na) return 0;
    if (n) memcpy(na, *arr, n * size);
    al->free(al->user, *arr);
    *arr = na;
    return 1;
}

static int list_reserve(setup_list *l, size_t need) {
    if (need <= l->cap) return 1;
    size_t cap = l->cap ? 2 * l->cap : 1024;
    if (cap < need) cap = need;
    if (!grow(l->alloc, (void **)&l->v, l->n, cap, sizeof *l->v, l->huge) ||
        !grow(l->alloc, (void **)&l->a, l->n, cap, sizeof *l->a, l->huge) ||
        !grow(l->alloc, (void **)&l->src, l->n, cap, sizeof *l->src, l->huge) ||
        !grow(l->alloc, (void **)&l->range, l->n, cap, sizeof *l->range, l->huge))
        return 0;
    l->cap = cap;
    return 1;
}

/* Tile t of the prep intersects triangle s: its bounding box does, and no edge function is
 * negative over the whole tile (tested at the tile corner where it is largest). */
static int tile_hit(const cj_raster_prep *p, const cj_tri_setup *s, int tx, int ty) {
    const int64_t X0 = (int64_t)tx * p->tile_size * 256, Y0 = (int64_t)ty * p->tile_size * 256;
    int64_t X1 = ((int64_t)tx + 1) * p->tile_size * 256 - 1;
    int64_t Y1 = ((int64_t)ty + 1) * p->tile_size * 256 - 1;
    for (int k = 0; k < 3; ++k) {
        const int64_t X = s->ea[k] > 0 ? X1 : X0, Y = s->eb[k] > 0 ? Y1 : Y0;
        if (s->ea[k] * X + s->eb[k] * Y + s->ec[k] < 0) return 0;
    }
    return 1;
}

/* Counts set-up i into the bins of the tiles it touches (bin_start[t + 1]) and keeps its tile
 * range, right after the set-up, while its record is still in the cache: the fill pass then
 * rereads only the records of triangles over several tiles. */
static ALWAYS_INLINE void count_bins(const cj_raster_prep *p, setup_list *l, size_t i, int shift) {
    const cj_tri_setup *s = &l->v[i];
    int tx0, tx1, ty0, ty1;
    if (shift >= 0) {
        tx0 = s->minx >> shift;
        tx1 = s->maxx >> shift;
        ty0 = s->miny >> shift;
        ty1 = s->maxy >> shift;
    } else {
        tx0 = s->minx / p->tile_size;
        tx1 = s->maxx / p->tile_size;
        ty0 = s->miny / p->tile_size;
        ty1 = s->maxy / p->tile_size;
    }
    l->range[i][0] = (uint16_t)tx0;
    l->range[i][1] = (uint16_t)tx1;
    l->range[i][2] = (uint16_t)ty0;
    l->range[i][3] = (uint16_t)ty1;
    if (tx0 == tx1 && ty0 == ty1) {
        p->bin_start[(size_t)ty0 * p->tiles_x + tx0 + 1]++;
        return;
    }
    for (int ty = ty0; ty <= ty1; ++ty)
        for (int tx = tx0; tx <= tx1; ++tx)
            if (tile_hit(p, s, tx, ty)) p->bin_start[(size_t)ty * p->tiles_x + tx + 1]++;
}

/* The bins from the counts of count_bins: offsets, then the set-ups in input order. */
static cj_status bin(cj_raster_prep *p, uint16_t (*range)[4]) {
    const size_t tiles = (size_t)p->tiles_x * (size_t)p->tiles_y;
    for (size_t t = 0; t < tiles; ++t) p->bin_start[t + 1] += p->bin_start[t];
    if (p->bin_start[tiles] + 1 > p->bin_items_cap) {
        p->alloc.free(p->alloc.user, p->bin_items);
        p->bin_items_cap = 0;
        p->bin_items =
            xalloc_big(&p->alloc, (p->bin_start[tiles] + 1) * sizeof *p->bin_items, p->huge);
        if (!p->bin_items)
            return cj_fail(CJ_ERR_NOMEM, "raster: no memory for %zu binned triangles",
                           p->bin_start[tiles]);
        p->bin_items_cap = p->bin_start[tiles] + 1;
    }
    for (size_t i = 0; i < p->setup_count; ++i) {
        const int tx0 = range[i][0], tx1 = range[i][1], ty0 = range[i][2], ty1 = range[i][3];
        if (tx0 == tx1 && ty0 == ty1) {
            p->bin_items[p->bin_start[(size_t)ty0 * p->tiles_x + tx0]++] = (uint32_t)i;
            continue;
        }
        for (int ty = ty0; ty <= ty1; ++ty)
            for (int tx = tx0; tx <= tx1; ++tx)
                if (tile_hit(p, &p->setups[i], tx, ty))
                    p->bin_items[p->bin_start[(size_t)ty * p->tiles_x + tx]++] = (uint32_t)i;
    }
    /* The fill advanced each start to the next bin's start: shift back. */
    for (size_t t = tiles; t > 0; --t) p->bin_start[t] = p->bin_start[t - 1];
    p->bin_start[0] = 0;
    return CJ_OK;
}

/* After a failed preparation: no triangles, every bin empty (a run draws nothing). */
static void make_empty(cj_raster_prep *p) {
    p->setup_count = 0;
    const size_t tiles = (size_t)p->tiles_x * (size_t)p->tiles_y;
    if (p->bin_start && p->bin_start_cap >= tiles + 1)
        memset(p->bin_start, 0, (tiles + 1) * sizeof *p->bin_start);
    else
        p->tiles_x = p->tiles_y = 0;
}

/* Prepares the frame `in` into p, whose arrays (set-ups, attributes, bins, vertex cache) are
 * reused where large enough and replaced where not. */
static cj_status prepare_into(cj_raster_prep *p, const cj_raster_input *in, int tile_size,
                              cj_raster_stats *stats, double t_start) {
    p->setup_count = 0;
    p->width = in->width;
    p->height = in->height;
    p->spp = in->spp;
    p->tile_size = tile_size;
    p->barycentrics = 1;
    p->tiles_x = (in->width + tile_size - 1) / tile_size;
    p->tiles_y = (in->height + tile_size - 1) / tile_size;
    cj_tri_pattern_fixed(in->spp, p->ox, p->oy);
    p->oxmin = p->oymin = 256;
    p->oxmax = p->oymax = -1;
    for (int s = 0; s < in->spp; ++s) {
        if (p->ox[s] < p->oxmin) p->oxmin = p->ox[s];
        if (p->ox[s] > p->oxmax) p->oxmax = p->ox[s];
        if (p->oy[s] < p->oymin) p->oymin = p->oy[s];
        if (p->oy[s] > p->oymax) p->oymax = p->oy[s];
    }

    cj_raster_stats st;
    memset(&st, 0, sizeof st);
    st.tris_in = in->tri_count;
    const double hw = 0.5 * in->width, hh = 0.5 * in->height;
    const double gx = 2.0 * CJ_TRI_GUARD_PX / in->width, gy = 2.0 * CJ_TRI_GUARD_PX / in->height;
    setup_list list = {&p->alloc, p->huge, p->setups, p->attrs, p->src, p->range, 0, p->setup_cap};
    cj_status status = CJ_OK;
    const size_t tiles = (size_t)p->tiles_x * (size_t)p->tiles_y;
    if (tiles + 1 > p->bin_start_cap) {
        p->alloc.free(p->alloc.user, p->bin_start);
        p->bin_start_cap = 0;
        p->bin_start = xalloc(&p->alloc, (tiles + 1) * sizeof *p->bin_start);
        if (p->bin_start) p->bin_start_cap = tiles + 1;
    }
    if (!p->bin_start)
        status = cj_fail(CJ_ERR_NOMEM, "raster: no memory for %zu tile bins", tiles);
    else
        memset(p->bin_start, 0, (tiles + 1) * sizeof *p->bin_start);
    int shift = -1; /* tile sizes that are powers of two divide by a shift */
    for (int k = 0; k < 16; ++k)
        if (p->tile_size == 1 << k) shift = k;
    /* Whether any coordinate is NaN or infinite (all exponent bits set), in a loop without
     * exits; the culprit is looked for only then. */
    uint64_t nonfinite = 0;
    size_t c0 = 0;
#if defined(__AVX2__)
    const __m256i expo = _mm256_set1_epi64x(0x7ff0000000000000ll);
    __m256i vbad = _mm256_setzero_si256();
    for (; c0 < 4 * in->vertex_count; c0 += 4) {
        const __m256i bits =
            _mm256_and_si256(_mm256_castpd_si256(_mm256_loadu_pd(in->clip + c0)), expo);
        vbad = _mm256_or_si256(vbad, _mm256_cmpeq_epi64(bits, expo));
    }
    nonfinite = !_mm256_testz_si256(vbad, vbad);
#endif
    for (size_t i = c0; i < 4 * in->vertex_count; ++i) {
        uint64_t bits;
        memcpy(&bits, &in->clip[i], sizeof bits);
        nonfinite |= (uint64_t)((bits & 0x7ff0000000000000ull) == 0x7ff0000000000000ull);
    }
    for (size_t i = 0; nonfinite && i < 4 * in->vertex_count && status == CJ_OK; ++i)
        if (!isfinite(in->clip[i]))
            status = cj_fail(CJ_ERR_NONFINITE, "raster: clip coordinate %zu of vertex %zu is %g",
                             i % 4, i / 4, in->clip[i]);
    /* Mesh vertices are shared by several triangles, mostly close together in the input: a
     * small direct-mapped cache keeps each vertex's outcode and projection (the same values as
     * computing them again). */
    if (!p->vcache) p->vcache = xalloc(&p->alloc, VCACHE_SIZE * sizeof(vcache));
    vcache *cache = p->vcache;
    if (!cache)
        status = cj_fail(CJ_ERR_NOMEM, "raster: no memory for the vertex cache");
    else
        for (int i = 0; i < VCACHE_SIZE; ++i) cache[i].tag = UINT64_MAX;
    if (status == CJ_OK && !list_reserve(&list, in->tri_count + 16))
        status = cj_fail(CJ_ERR_NOMEM, "raster: no memory for %zu set-up triangles", in->tri_count);
    for (size_t t = 0; t < in->tri_count && status == CJ_OK; ++t) {
        const uint32_t *ix = in->tris + 3 * t;
        const vcache *e[3];
        for (int k = 0; k < 3; ++k) e[k] = vertex(cache, in->clip, ix[k], hw, hh, gx, gy);
        const unsigned o0 = e[0]->code, o1 = e[1]->code, o2 = e[2]->code;
        if (o0 & o1 & o2 & 63u) { /* all three outside one plane */
            st.tris_rejected++;
            continue;
        }
        if ((o0 | o1 | o2) == 0) { /* inside every plane: the projected vertices as they are */
            pvert pv[3] = {e[0]->v, e[1]->v, e[2]->v};
            pv[1].q1 = pv[1].r; /* b/w with the source barycentrics (0,0), (1,0), (0,1) */
            pv[2].q2 = pv[2].r;
            if (setup_tri(p, &pv[0], &pv[1], &pv[2], (uint32_t)t, 0, &list.v[list.n],
                          &list.a[list.n])) {
                list.src[list.n] = (uint32_t)t;
                count_bins(p, &list, list.n++, shift);
                st.tris_setup++;
            } else {
                st.tris_rejected++;
            }
            continue;
        }
        cj_tri_vert tv[3];
        static const double bary[3][2] = {{0, 0}, {1, 0}, {0, 1}};
        for (int k = 0; k < 3; ++k) {
            const double *c = in->clip + 4 * (size_t)in->tris[3 * t + k];
            tv[k].x = c[0];
            tv[k].y = c[1];
            tv[k].z = c[2];
            tv[k].w = c[3];
            tv[k].b1 = bary[k][0];
            tv[k].b2 = bary[k][1];
        }
        cj_tri_vert poly[CJ_TRI_CLIP_MAX];
        int cut = 0;
        const int n = cj_tri_clip(tv, gx, gy, poly, &cut);
        st.tris_clipped += cut;
        pvert pv[CJ_TRI_CLIP_MAX];
        int ok = n >= 3;
        for (int k = 0; k < n && ok; ++k) {
            const cj_tri_vert *c = &poly[k];
            if (!(c->w > 0.0)) { /* only a degenerate input reaches w = 0 inside the volume */
                ok = 0;
                break;
            }
            const double xn = c->x / c->w, yn = c->y / c->w;
            pv[k].sx = (xn + 1.0) * hw;
            pv[k].sy = (yn + 1.0) * hh;
            pv[k].X = snap(xn, hw);
            pv[k].Y = snap(yn, hh);
            pv[k].z = c->z / c->w;
            pv[k].r = 1.0 / c->w;
            pv[k].q1 = c->b1 * pv[k].r;
            pv[k].q2 = c->b2 * pv[k].r;
        }
        size_t made = 0;
        if (ok) {
            int want = 0;
            if (n > 3) { /* orientation of the whole snapped polygon (shoelace, exact) */
                int64_t a2 = 0;
                for (int k = 0; k < n; ++k) {
                    const pvert *u = &pv[k], *w = &pv[k + 1 == n ? 0 : k + 1];
                    a2 += u->X * w->Y - u->Y * w->X;
                }
                want = a2 > 0 ? 1 : a2 < 0 ? -1 : 2;
            }
            for (int k = 1; k + 1 < n && want != 2; ++k) {
                if (!list_reserve(&list, list.n + 1)) {
                    status = cj_fail(CJ_ERR_NOMEM, "raster: no memory for set-up triangles");
                    break;
                }
                if (setup_tri(p, &pv[0], &pv[k], &pv[k + 1], (uint32_t)t, want, &list.v[list.n],
                              &list.a[list.n])) {
                    list.src[list.n] = (uint32_t)t;
                    count_bins(p, &list, list.n++, shift);
                    made++;
                }
            }
        }
        if (made == 0) st.tris_rejected++;
        st.tris_setup += made;
    }
    p->setups = list.v;
    p->attrs = list.a;
    p->src = list.src;
    p->range = list.range;
    p->setup_cap = list.cap;
    p->setup_count = list.n;
    /* A prep used once gives its scratch back as soon as it is done with it, in the order it
     * always did: the heap then stays mapped between frames (freed later, after the bins, the
     * cache let malloc trim the whole heap every frame: a third more page faults). */
    if (!p->huge) {
        p->alloc.free(p->alloc.user, p->vcache);
        p->vcache = NULL;
    }
    if (status == CJ_OK) status = bin(p, list.range);
    if (!p->huge) {
        p->alloc.free(p->alloc.user, p->range);
        p->range = NULL;
    }
    if (status != CJ_OK) {
        make_empty(p);
        return status;
    }
    st.seconds_setup = cj_clock_seconds() - t_start;
    if (stats) *stats = st;
    return CJ_OK;
}

cj_status cj_raster_prepare(const cj_raster_input *in, int tile_size, const cj_allocator *alloc,
                            cj_raster_prep **out, cj_raster_stats *stats) {
    assert(in && out);
    const double t_start = cj_clock_seconds();
    cj_status status = cj_tri_check_input(in, tile_size);
    if (status) return status;
    cj_allocator a;
    if (alloc)
        a = *alloc;
    else {
        a.alloc = std_alloc;
        a.free = std_free;
        a.user = NULL;
    }
    cj_raster_prep *p = xalloc(&a, sizeof *p);
    if (!p) return cj_fail(CJ_ERR_NOMEM, "raster: no memory for the prepared frame");
    memset(p, 0, sizeof *p);
    p->alloc = a;
    status = prepare_into(p, in, tile_size, stats, t_start);
    if (status != CJ_OK) {
        cj_raster_prep_destroy(p);
        return status;
    }
    *out = p;
    return CJ_OK;
}

cj_status cj_raster_prepare_again(cj_raster_prep *prep, const cj_raster_input *in, int tile_size,
                                  cj_raster_stats *stats) {
    assert(prep && in);
    const double t_start = cj_clock_seconds();
    prep->setup_count = 0;
    prep->barycentrics = 1;
    if (!prep->huge) { /* kept across frames from now on: its arrays again, in huge pages */
        cj_allocator *a = &prep->alloc;
        a->free(a->user, prep->setups);
        a->free(a->user, prep->attrs);
        a->free(a->user, prep->src);
        a->free(a->user, prep->range);
        a->free(a->user, prep->bin_items);
        prep->setups = NULL;
        prep->attrs = NULL;
        prep->src = NULL;
        prep->range = NULL;
        prep->bin_items = NULL;
        prep->setup_cap = prep->bin_items_cap = 0;
        prep->huge = 1;
    }
    cj_status status = cj_tri_check_input(in, tile_size);
    if (status) {
        make_empty(prep);
        return status;
    }
    return prepare_into(prep, in, tile_size, stats, t_start);
}

/* Per-tile rasterization: the binned triangles of one tile, in input order, into the tile's
 * depth/id planes (the visibility pass), the conversion of the winners into visibility samples
 * with perspective-correct barycentrics, and the forward (every fragment) mode.
 *
 * Every value computed at a sample — edge functions, depth, barycentrics — is a fixed function
 * of the set-up triangle and the sample's absolute position (integers, or doubles evaluated in
 * one order from exact integer offsets), never of the tile's origin: the same frame comes out
 * for any tile size and thread count. */
#include "tri_internal.h"

#include <math.h>
#include <string.h>

#if defined(__GNUC__)
#define CJ_INLINE static inline __attribute__((always_inline))
#else
#define CJ_INLINE static inline
#endif

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

void cj_tri_bary_at(const cj_tri_setup *s, int64_t X, int64_t Y, float *b1, float *b2) {
    const double dx = (double)(X - s->xr), dy = (double)(Y - s->yr);
    const double r = plane_at(&s->r, dx, dy);
    *b1 = (float)(plane_at(&s->q1, dx, dy) / r);
    *b2 = (float)(plane_at(&s->q2, dx, dy) / r);
}

/* The pixel columns [*lo, *hi) of row y that may hold covered samples: each edge bounds the
 * span from one side, computed in double and widened by two pixels (the exact test inside the
 * span decides). Returns 0 when an edge excludes the whole row. */
static int row_span(const cj_raster_prep *p, const cj_tri_setup *s, int y, int *lo, int *hi) {
    const int64_t Ypix = (int64_t)y * 256;
    double l = *lo, h = *hi;
    for (int k = 0; k < 3; ++k) {
        const int64_t a = s->ea[k], b = s->eb[k];
        const int64_t Yb = Ypix + (b > 0 ? p->oymax : p->oymin);
        const int64_t cy = b * Yb + s->ec[k];
        if (a > 0) { /* a X + cy >= 0  <=>  X >= −cy/a, X = 256 x + oxmax at best */
            const double x = ((double)(-cy) / (double)a - p->oxmax) / 256.0 - 2.0;
            if (x > l) l = x;
        } else if (a < 0) {
            const double x = ((double)cy / (double)(-a) - p->oxmin) / 256.0 + 2.0;
            if (x < h) h = x;
        } else if (cy < 0) {
            return 0;
        }
    }
    if (!(l < h)) return 0;
    const int il = (int)ceil(l), ih = (int)floor(h) + 1;
    if (il > *lo) *lo = il;
    if (ih < *hi) *hi = ih;
    return *lo < *hi;
}

/* The visibility pass of one triangle over the tile, specialised on the sample count. */
CJ_INLINE void raster_one(const cj_raster_prep *p, const cj_tri_setup *s, uint32_t id,
                          const cj_tile *t, float *depth, uint32_t *ids, const int SPP,
                          uint64_t *tested, uint64_t *written) {
    const int xa = s->minx > t->x0 ? s->minx : t->x0;
    const int xb = s->maxx + 1 < t->x1 ? s->maxx + 1 : t->x1;
    const int ya = s->miny > t->y0 ? s->miny : t->y0;
    const int yb = s->maxy + 1 < t->y1 ? s->maxy + 1 : t->y1;
    if (xa >= xb || ya >= yb) return;
    const int tw = t->x1 - t->x0;
    int64_t eoff[3][16];
    for (int k = 0; k < 3; ++k)
        for (int q = 0; q < SPP; ++q) eoff[k][q] = s->ea[k] * p->ox[q] + s->eb[k] * p->oy[q];
    const int64_t st0 = s->ea[0] * 256, st1 = s->ea[1] * 256, st2 = s->ea[2] * 256;
    const double za = s->z.va;
    uint64_t tst = 0, wr = 0;
    for (int y = ya; y < yb; ++y) {
        int lo = xa, hi = xb;
        if (!row_span(p, s, y, &lo, &hi)) continue;
        const int64_t X = (int64_t)lo * 256, Y = (int64_t)y * 256;
        int64_t e0 = s->ea[0] * X + s->eb[0] * Y + s->ec[0];
        int64_t e1 = s->ea[1] * X + s->eb[1] * Y + s->ec[1];
        int64_t e2 = s->ea[2] * X + s->eb[2] * Y + s->ec[2];
        double rowz[16], dxs[16];
        for (int q = 0; q < SPP; ++q) {
            rowz[q] = s->z.v0 + s->z.vb * (double)(Y + p->oy[q] - s->yr);
            dxs[q] = (double)p->ox[q];
        }
        double dxp = (double)(X - s->xr);
        const size_t base = ((size_t)(y - t->y0) * tw + (size_t)(lo - t->x0)) * SPP;
        float *dp = depth + base;
        uint32_t *ip = ids + base;
        const int n = hi - lo;
        tst += (uint64_t)n * SPP;
        for (int i = 0; i < n; ++i) {
            for (int q = 0; q < SPP; ++q) {
                const int64_t f0 = e0 + eoff[0][q], f1 = e1 + eoff[1][q], f2 = e2 + eoff[2][q];
                const int inside = (f0 | f1 | f2) >= 0;
                const float z = clamp_depth(rowz[q] + za * (dxp + dxs[q]));
                const float old = dp[q];
                const int pass = inside & (z < old);
                dp[q] = pass ? z : old;
                ip[q] = pass ? id : ip[q];
                wr += (uint64_t)pass;
            }
            e0 += st0;
            e1 += st1;
            e2 += st2;
            dxp += 256.0;
            dp += SPP;
            ip += SPP;
        }
    }
    *tested += tst;
    *written += wr;
}

static void raster_bin(const cj_raster_prep *p, const cj_tile *t, cj_tri_scratch *sc,
                       const int SPP) {
    const size_t tile_index = (size_t)t->index;
    const size_t b0 = p->bin_start[tile_index], b1 = p->bin_start[tile_index + 1];
    for (size_t b = b0; b < b1; ++b) {
        const uint32_t id = p->bin_items[b];
        if (SPP == 1)
            raster_one(p, &p->setups[id], id, t, sc->depth, sc->id, 1, &sc->tested, &sc->written);
        else if (SPP == 4)
            raster_one(p, &p->setups[id], id, t, sc->depth, sc->id, 4, &sc->tested, &sc->written);
        else
            raster_one(p, &p->setups[id], id, t, sc->depth, sc->id, 16, &sc->tested, &sc->written);
    }
}

void cj_tri_render_tile(const cj_raster_prep *p, const cj_tile *t, cj_tri_scratch *sc) {
    const int spp = p->spp;
    const size_t n = (size_t)(t->x1 - t->x0) * (size_t)(t->y1 - t->y0) * (size_t)spp;
    for (size_t i = 0; i < n; ++i) {
        sc->depth[i] = 1.0f;
        sc->id[i] = CJ_RASTER_NO_TRI;
    }
    if (spp == 1)
        raster_bin(p, t, sc, 1);
    else if (spp == 4)
        raster_bin(p, t, sc, 4);
    else
        raster_bin(p, t, sc, 16);
    /* Resolve the winners: source index and barycentrics, once per visible sample. */
    size_t i = 0;
    for (int y = t->y0; y < t->y1; ++y)
        for (int x = t->x0; x < t->x1; ++x)
            for (int q = 0; q < spp; ++q, ++i) {
                cj_vis_sample *o = &t->samples[i];
                o->depth = sc->depth[i];
                const uint32_t id = sc->id[i];
                if (id == CJ_RASTER_NO_TRI) {
                    o->tri = CJ_RASTER_NO_TRI;
                    o->b1 = o->b2 = 0.0f;
                    continue;
                }
                const cj_tri_setup *s = &p->setups[id];
                o->tri = s->src;
                cj_tri_bary_at(s, (int64_t)x * 256 + p->ox[q], (int64_t)y * 256 + p->oy[q], &o->b1,
                               &o->b2);
            }
}

void cj_raster_tile_forward(const cj_raster_prep *p, const cj_tile *t, cj_frag_fn frag,
                            void *user) {
    const int spp = p->spp;
    const int tw = t->x1 - t->x0;
    const size_t b0 = p->bin_start[t->index], b1 = p->bin_start[t->index + 1];
    for (size_t b = b0; b < b1; ++b) {
        const cj_tri_setup *s = &p->setups[p->bin_items[b]];
        const int xa = s->minx > t->x0 ? s->minx : t->x0;
        const int xb = s->maxx + 1 < t->x1 ? s->maxx + 1 : t->x1;
        const int ya = s->miny > t->y0 ? s->miny : t->y0;
        const int yb = s->maxy + 1 < t->y1 ? s->maxy + 1 : t->y1;
        for (int y = ya; y < yb; ++y) {
            int lo = xa, hi = xb;
            if (!row_span(p, s, y, &lo, &hi)) continue;
            for (int x = lo; x < hi; ++x)
                for (int q = 0; q < spp; ++q) {
                    const int64_t X = (int64_t)x * 256 + p->ox[q], Y = (int64_t)y * 256 + p->oy[q];
                    const int64_t f0 = s->ea[0] * X + s->eb[0] * Y + s->ec[0];
                    const int64_t f1 = s->ea[1] * X + s->eb[1] * Y + s->ec[1];
                    const int64_t f2 = s->ea[2] * X + s->eb[2] * Y + s->ec[2];
                    if ((f0 | f1 | f2) < 0) continue;
                    const float z = cj_tri_depth_at(s, X, Y);
                    const size_t idx = ((size_t)(y - t->y0) * tw + (size_t)(x - t->x0)) * spp + q;
                    if (!(z < t->samples[idx].depth)) continue;
                    float bb1, bb2;
                    cj_tri_bary_at(s, X, Y, &bb1, &bb2);
                    frag(user, x, y, q, s->src, z, bb1, bb2);
                }
        }
    }
}

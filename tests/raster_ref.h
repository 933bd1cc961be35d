/* Test-side helpers shared by the triangle rasterizer tests (test_raster_exact.c,
 * test_raster_clip.c): the snapping rule as specified in raster/src/tri_internal.h, an exact
 * sample-coverage predicate (double filter, GMP rationals whenever the sign is in doubt), and a
 * harness that runs the rasterizer and collects its visibility buffer and forward fragments.
 * None of it calls the rasterizer's own set-up or coverage code. */
#ifndef CJ_TEST_RASTER_REF_H
#define CJ_TEST_RASTER_REF_H

#include "raster3d_internal.h"

#include <gmp.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/* The specified snapping: X = rint(256 · fl(fl(fl(c/w) + 1) · size/2)). */
static inline int64_t ref_snap(double c, double w, int size) {
    return (int64_t)llrint(256.0 * ((c / w + 1.0) * (0.5 * size)));
}

/* Sign of the exact rational (bx−ax)(sy−ay) − (by−ay)(sx−ax), all coordinates k/256 given by
 * their numerators k. The double evaluation decides when it is far from zero (each of the two
 * products has relative error <= 2^-53, the difference adds one more rounding), otherwise the
 * value is computed in GMP rationals. */
static inline int ref_orient(int64_t ax, int64_t ay, int64_t bx, int64_t by, int64_t sx,
                             int64_t sy) {
    const double d1 = (double)(bx - ax), d2 = (double)(sy - ay);
    const double d3 = (double)(by - ay), d4 = (double)(sx - ax);
    const double p = d1 * d2, q = d3 * d4, e = p - q;
    const double bound = 0x1p-50 * (fabs(p) + fabs(q));
    if (e > bound) return 1;
    if (e < -bound) return -1;
    mpq_t A[6], t1, t2;
    const int64_t v[6] = {ax, ay, bx, by, sx, sy};
    for (int i = 0; i < 6; ++i) {
        mpq_init(A[i]);
        mpz_set_si(mpq_numref(A[i]), (long)v[i]);
        mpz_set_si(mpq_denref(A[i]), 256);
        mpq_canonicalize(A[i]);
    }
    mpq_inits(t1, t2, NULL);
    mpq_t u;
    mpq_init(u);
    mpq_sub(t1, A[2], A[0]); /* bx − ax */
    mpq_sub(u, A[5], A[1]);  /* sy − ay */
    mpq_mul(t1, t1, u);
    mpq_sub(t2, A[3], A[1]); /* by − ay */
    mpq_sub(u, A[4], A[0]);  /* sx − ax */
    mpq_mul(t2, t2, u);
    mpq_sub(t1, t1, t2);
    const int s = mpq_sgn(t1);
    for (int i = 0; i < 6; ++i) mpq_clear(A[i]);
    mpq_clears(t1, t2, u, NULL);
    return s;
}

/* Coverage by the top-left rule, from its definition: the sample s is moved by (+ε, −ε²) and
 * tested for being strictly inside. For an edge a→b with E(s) = 0 the perturbed value is
 * −ε·dy − ε²·dx. Triangles are taken in either winding. Returns 1 if covered. */
static inline int ref_edge_side(int64_t ax, int64_t ay, int64_t bx, int64_t by, int64_t sx,
                                int64_t sy) {
    const int e = ref_orient(ax, ay, bx, by, sx, sy);
    if (e) return e;
    const int64_t dx = bx - ax, dy = by - ay;
    if (dy) return dy < 0 ? 1 : -1;
    return dx < 0 ? 1 : (dx > 0 ? -1 : 0);
}

static inline int64_t ref_area2(const int64_t X[3], const int64_t Y[3]) {
    return (X[1] - X[0]) * (Y[2] - Y[0]) - (Y[1] - Y[0]) * (X[2] - X[0]);
}

static inline int ref_covers(const int64_t X[3], const int64_t Y[3], int64_t sx, int64_t sy) {
    const int64_t a = ref_area2(X, Y);
    if (a == 0) return 0;
    const int want = a > 0 ? 1 : -1; /* the inside is on this side of every edge */
    for (int k = 0; k < 3; ++k) {
        const int j = k == 2 ? 0 : k + 1;
        if (ref_edge_side(X[k], Y[k], X[j], Y[j], sx, sy) != want) return 0;
    }
    return 1;
}

/* Sample offsets in 1/256 pixel from the public double pattern (checked to be exact). */
static inline int ref_pattern(int spp, int64_t ox[16], int64_t oy[16]) {
    const double(*pat)[2] = cj_raster_sample_pattern(spp);
    if (!pat) return 0;
    for (int s = 0; s < spp; ++s) {
        const double x = pat[s][0] * 256.0, y = pat[s][1] * 256.0;
        if (x != floor(x) || y != floor(y) || x < 0 || x >= 256 || y < 0 || y >= 256) return 0;
        ox[s] = (int64_t)x;
        oy[s] = (int64_t)y;
    }
    return 1;
}

/* ---- harness ---------------------------------------------------------------------------- */

#define RH_MAX_THREADS 8

typedef struct rh_frag_ctx rh_frag_ctx;
typedef void (*rh_frag)(void *ctx, int x, int y, int s, uint32_t tri, float depth, float b1,
                        float b2);

typedef struct rh {
    const cj_raster_prep *prep;
    int W, H, spp;
    cj_vis_sample *vis;                 /* whole image, or NULL */
    cj_vis_sample *fwd[RH_MAX_THREADS]; /* per thread: a tile of depth 2 (every fragment) */
    float fwd_depth;                    /* depth the forward tile holds (2: all fragments) */
    int forward_on_vis;                 /* 1: forward against the real visibility samples */
    rh_frag frag;
    void *ctx;
} rh;

static void rh_on_tile(void *u, const cj_tile *t) {
    rh *h = u;
    const int tw = t->x1 - t->x0;
    if (h->vis)
        for (int y = t->y0; y < t->y1; ++y)
            memcpy(&h->vis[((size_t)y * h->W + t->x0) * h->spp],
                   &t->samples[(size_t)(y - t->y0) * tw * h->spp],
                   (size_t)tw * h->spp * sizeof(cj_vis_sample));
    if (h->frag) {
        if (h->forward_on_vis) {
            cj_raster_tile_forward(h->prep, t, h->frag, h->ctx);
        } else {
            cj_tile c = *t;
            c.samples = h->fwd[t->thread];
            const size_t n = (size_t)tw * (t->y1 - t->y0) * h->spp;
            for (size_t i = 0; i < n; ++i) c.samples[i].depth = h->fwd_depth;
            cj_raster_tile_forward(h->prep, &c, h->frag, h->ctx);
        }
    }
}

/* Prepares and runs; every fragment goes to frag(ctx, ...) when frag is set, the visibility
 * buffer to vis when it is not NULL. Returns the status of prepare or run. */
static inline cj_status rh_render(const cj_raster_input *in, int tile, int threads,
                                  cj_vis_sample *vis, rh_frag frag, void *ctx,
                                  cj_raster_stats *stats) {
    /* Every other call re-prepares one kept prep (cj_raster_prepare_again, buffers of earlier
     * frames of other sizes reused), so both paths meet the reference. */
    static cj_raster_prep *kept;
    static unsigned calls;
    const int again = (calls++ & 1) != 0;
    cj_raster_prep *prep = NULL;
    cj_status st;
    if (again && kept) {
        prep = kept;
        st = cj_raster_prepare_again(prep, in, tile, stats);
    } else {
        st = cj_raster_prepare(in, tile, NULL, &prep, stats);
    }
    if (st != CJ_OK) return st;
    rh h;
    memset(&h, 0, sizeof h);
    h.prep = prep;
    h.W = in->width;
    h.H = in->height;
    h.spp = in->spp;
    h.vis = vis;
    h.frag = frag;
    h.ctx = ctx;
    h.fwd_depth = 2.0f;
    const int nt = cj_raster_thread_count(prep, threads);
    const size_t tn = (size_t)tile * tile * in->spp;
    for (int i = 0; i < nt && i < RH_MAX_THREADS; ++i)
        h.fwd[i] = frag ? malloc(tn * sizeof(cj_vis_sample)) : NULL;
    cj_raster_stats rs;
    st = cj_raster_run(prep, threads, rh_on_tile, &h, NULL, &rs);
    if (stats) {
        stats->samples_tested = rs.samples_tested;
        stats->samples_written = rs.samples_written;
        stats->seconds_raster = rs.seconds_raster;
    }
    for (int i = 0; i < RH_MAX_THREADS; ++i) free(h.fwd[i]);
    if (prep != kept) {
        cj_raster_prep_destroy(kept);
        kept = prep; /* freed with the process (its buffers serve the next frames) */
    }
    return st;
}

#endif

/* The Phong kernels, CJ_LANES samples at a time (issue 20): the tile's Phong samples are
 * gathered in blocks of 8 into a structure of arrays (normal, position − eye, material), lit
 * by the lane lighting of render_light8.h (vectorised: one AVX register per quantity), then
 * written out. A short last block repeats its last sample in the unused lanes, so every
 * sample goes through the same 8-lane code whatever the tile or thread; the values equal the
 * scalar k_phong_one of render_shade.c (the same source at n = 1).
 *
 * The gather is most of a block's work, so it is arranged to cost little per lane:
 *   - each vertex is one record of 8 floats (normal, position − eye, (u, v): c->vrec, made
 *     once per frame), so a lane interpolates its three records with 8-wide arithmetic and
 *     the block is transposed once, instead of 24 scalar loads and products per lane;
 *   - a block whose lanes share one material (all but the blocks on an object's border) takes
 *     the material and the checker's parameters once, not per lane, and writes its colours
 *     from a structure of arrays;
 * Every lane value is computed by the same float and double operations, in the same order, as
 * the per-lane gather it replaces, so the pixels are unchanged (bench_live's image hash). */
#include "render_light8.h"
#include "texture_lanes.h"

#include <string.h>

#if defined(__AVX__)
#include <immintrin.h>
#endif

/* plane[k][j] = P[9 tri[j] + k] for the 8 lanes (the (u,v) planes of render_shade.c): with
 * AVX, 4 × 4 blocks of lanes × components loaded as rows and transposed in registers (AVX2
 * gathers took fewer instructions but no less time on the AMD cores measured), the ninth
 * component by plain loads. */
static inline __attribute__((always_inline)) void
gather_planes(const double *P, const uint32_t *tri, double plane[9][CJ_LANES]) {
#if defined(__AVX__)
    for (int g = 0; g < CJ_LANES; g += 4) {
        const double *r[4];
        for (int i = 0; i < 4; ++i) r[i] = P + 9 * (size_t)tri[g + i];
        for (int k = 0; k < 8; k += 4) {
            const __m256d r0 = _mm256_loadu_pd(r[0] + k), r1 = _mm256_loadu_pd(r[1] + k);
            const __m256d r2 = _mm256_loadu_pd(r[2] + k), r3 = _mm256_loadu_pd(r[3] + k);
            const __m256d t0 = _mm256_unpacklo_pd(r0, r1), t1 = _mm256_unpackhi_pd(r0, r1);
            const __m256d t2 = _mm256_unpacklo_pd(r2, r3), t3 = _mm256_unpackhi_pd(r2, r3);
            _mm256_storeu_pd(plane[k] + g, _mm256_permute2f128_pd(t0, t2, 0x20));
            _mm256_storeu_pd(plane[k + 1] + g, _mm256_permute2f128_pd(t1, t3, 0x20));
            _mm256_storeu_pd(plane[k + 2] + g, _mm256_permute2f128_pd(t0, t2, 0x31));
            _mm256_storeu_pd(plane[k + 3] + g, _mm256_permute2f128_pd(t1, t3, 0x31));
        }
        for (int i = 0; i < 4; ++i) plane[8][g + i] = r[i][8];
    }
#else
    for (int j = 0; j < CJ_LANES; ++j) {
        const double *pl = P + 9 * (size_t)tri[j];
        for (int k = 0; k < 9; ++k) plane[k][j] = pl[k];
    }
#endif
}

/* soa[k][j] = rec[j][k] (8 × 8 floats). */
static inline __attribute__((always_inline)) void transpose8(const float rec[CJ_LANES][8],
                                                             float soa[8][CJ_LANES]) {
#if defined(__AVX__)
    __m256 r[8], s[8];
    for (int j = 0; j < 8; ++j) r[j] = _mm256_loadu_ps(rec[j]);
    for (int j = 0; j < 8; j += 2) {
        s[j] = _mm256_unpacklo_ps(r[j], r[j + 1]);
        s[j + 1] = _mm256_unpackhi_ps(r[j], r[j + 1]);
    }
    /* s[0] = a0 b0 a1 b1 | a4 b4 a5 b5, s[1] = a2 b2 a3 b3 | a6 b6 a7 b7, s[2], s[3]: c, d ... */
    __m256 u[8];
    for (int q = 0; q < 8; q += 4) {
        u[q] = _mm256_shuffle_ps(s[q], s[q + 2], 0x44);     /* a0 b0 c0 d0 | a4 b4 c4 d4 */
        u[q + 1] = _mm256_shuffle_ps(s[q], s[q + 2], 0xEE); /* a1 b1 c1 d1 | a5 ... */
        u[q + 2] = _mm256_shuffle_ps(s[q + 1], s[q + 3], 0x44);
        u[q + 3] = _mm256_shuffle_ps(s[q + 1], s[q + 3], 0xEE);
    }
    for (int k = 0; k < 4; ++k) {
        _mm256_storeu_ps(soa[k], _mm256_permute2f128_ps(u[k], u[k + 4], 0x20));
        _mm256_storeu_ps(soa[k + 4], _mm256_permute2f128_ps(u[k], u[k + 4], 0x31));
    }
#else
    for (int k = 0; k < 8; ++k)
        for (int j = 0; j < CJ_LANES; ++j) soa[k][j] = rec[j][k];
#endif
}

/* One block: lanes j < n hold the samples idx[0..n) of the tile (n <= CJ_LANES). */
static inline __attribute__((always_inline)) void phong_block(const cj_rctx *c, const cj_tile *t,
                                                              const uint32_t *idx, int n,
                                                              const int tex, float *col) {
    const cj_rlist *L = &c->opaque;
    uint32_t si[CJ_LANES], tri[CJ_LANES];
    float b0[CJ_LANES], b1[CJ_LANES], b2[CJ_LANES];
    int32_t mi[CJ_LANES], flip[CJ_LANES];
    for (int j = 0; j < CJ_LANES; ++j) {
        const uint32_t i = idx[j < n ? j : n - 1];
        const cj_vis_sample *s = &t->samples[i];
        si[j] = i;
        tri[j] = s->tri;
        b1[j] = s->b1;
        b2[j] = s->b2;
    }
    for (int j = 0; j < CJ_LANES; ++j) b0[j] = 1.0f - b1[j] - b2[j];
    int uniform = 1;
    for (int j = 0; j < CJ_LANES; ++j) {
        mi[j] = c->obj_mat[L->obj[tri[j]]];
        uniform &= mi[j] == mi[0];
        flip[j] = L->back ? L->back[tri[j]] : 0;
    }

    /* normal, position − eye and (u, v), interpolated: b0 r0 + b1 r1 + b2 r2 per component */
    float rec[CJ_LANES][8], soa[8][CJ_LANES];
    for (int j = 0; j < CJ_LANES; ++j) {
        const uint32_t *tv = L->tris + 3 * (size_t)tri[j];
        const float *r0 = c->vrec + 8 * (size_t)tv[0], *r1 = c->vrec + 8 * (size_t)tv[1],
                    *r2 = c->vrec + 8 * (size_t)tv[2];
        for (int k = 0; k < 8; ++k) rec[j][k] = b0[j] * r0[k] + b1[j] * r1[k] + b2[j] * r2[k];
    }
    transpose8((const float(*)[8])rec, soa);
    cj_lanes b;
    memcpy(b.nx, soa[0], sizeof b.nx);
    memcpy(b.ny, soa[1], sizeof b.ny);
    memcpy(b.nz, soa[2], sizeof b.nz);
    memcpy(b.px, soa[3], sizeof b.px);
    memcpy(b.py, soa[4], sizeof b.py);
    memcpy(b.pz, soa[5], sizeof b.pz);

    /* the material: once for a uniform block, else per lane */
    const cj_rmat *m0 = &c->mats[mi[0]];
    float cr[3][CJ_LANES];
    int any_mirror = 0, any_half = 0;
    if (uniform) {
        const int mirror = m0->spec_model == CJ_SPEC_PHONG;
        any_mirror = mirror;
        any_half = !mirror;
        for (int j = 0; j < CJ_LANES; ++j) {
            b.alpha[j] = m0->alpha;
            b.mirror[j] = mirror;
        }
        for (int k = 0; k < 3; ++k)
            for (int j = 0; j < CJ_LANES; ++j) cr[k][j] = m0->cr[k];
    } else {
        for (int j = 0; j < CJ_LANES; ++j) {
            const cj_rmat *m = &c->mats[mi[j]];
            b.alpha[j] = m->alpha;
            b.mirror[j] = m->spec_model == CJ_SPEC_PHONG;
            any_mirror |= b.mirror[j];
            any_half |= !b.mirror[j];
            for (int k = 0; k < 3; ++k) cr[k][j] = m->cr[k];
        }
    }

    if (tex) {
        /* pixel and sample of index i without an integer division: spp is 1, 4 or 16;
         * (px + ½)/tw is at least 1/(2 tw) from an integer and its product by the rounded
         * 1/tw errs by under 2^-52 · px/tw < 2^-22, so the truncation is exact */
        const int tw = t->x1 - t->x0, spp = t->spp;
        const int spp_shift = spp == 16 ? 4 : spp == 4 ? 2 : 0;
        const double inv_tw = 1.0 / tw;
        cj_checker_lanes ck;
        for (int j = 0; j < CJ_LANES; ++j) {
            const uint32_t px = si[j] >> spp_shift, s = si[j] & (uint32_t)(spp - 1);
            const int row = (int)(((double)px + 0.5) * inv_tw), column = (int)px - row * tw;
            ck.sx[j] = t->x0 + column + c->pattern[s][0];
            ck.sy[j] = t->y0 + row + c->pattern[s][1];
            ck.u[j] = (double)soa[6][j];
            ck.v[j] = (double)soa[7][j];
        }
        /* no footprint: the zero plane, whose derivatives are 0 (texture_lanes.h) */
        static const double zero_plane[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
        float tx[3][CJ_LANES];
        const cj_tex_sampler *s0 = &c->samplers[m0->tex];
        if (uniform && s0->kind == CJ_TEX_CHECKER) {
            if (s0->needs_deriv && L->uvplane) {
                for (int j = 0; j < CJ_LANES; ++j) (void)cj_rshade_plane(c, L, tri[j]);
                gather_planes(L->uvplane, tri, ck.plane);
            } else
                for (int k = 0; k < 9; ++k)
                    for (int j = 0; j < CJ_LANES; ++j) ck.plane[k][j] = 0.0;
            cj_checker_lanes_set_params(&ck, s0);
            cj_checker_lanes_sample(CJ_LANES, &ck, tx);
        } else {
            int any_checker = 0, checker[CJ_LANES];
            for (int j = 0; j < CJ_LANES; ++j) {
                const cj_tex_sampler *smp = &c->samplers[c->mats[mi[j]].tex];
                checker[j] = smp->kind == CJ_TEX_CHECKER;
                if (!checker[j]) { /* image textures: the scalar sampler */
                    float rgb[3];
                    cj_rshade_tex(c, L, tri[j], b1[j], b2[j], ck.sx[j], ck.sy[j], rgb);
                    for (int k = 0; k < 3; ++k) tx[k][j] = rgb[k];
                    cj_checker_lanes_clear(&ck, j);
                    continue;
                }
                any_checker = 1;
                const double *pl =
                    smp->needs_deriv && L->uvplane ? cj_rshade_plane(c, L, tri[j]) : zero_plane;
                for (int k = 0; k < 9; ++k) ck.plane[k][j] = pl[k];
                ck.su[j] = smp->su;
                ck.sv[j] = smp->sv;
                ck.ou[j] = smp->ou;
                ck.ov[j] = smp->ov;
                ck.cu[j] = smp->checks_u;
                ck.cv[j] = smp->checks_v;
                ck.deriv[j] = smp->needs_deriv;
                for (int k = 0; k < 3; ++k) {
                    ck.a[k][j] = smp->a[k];
                    ck.b[k][j] = smp->b[k];
                }
            }
            if (any_checker) {
                float ct[3][CJ_LANES];
                cj_checker_lanes_sample(CJ_LANES, &ck, ct);
                for (int k = 0; k < 3; ++k)
                    for (int j = 0; j < CJ_LANES; ++j) tx[k][j] = checker[j] ? ct[k][j] : tx[k][j];
            }
        }
        for (int k = 0; k < 3; ++k)
            for (int j = 0; j < CJ_LANES; ++j) cr[k][j] *= tx[k][j];
    }
    cj_lanes_normalize(CJ_LANES, b.nx, b.ny, b.nz);
    for (int j = 0; j < CJ_LANES; ++j) {
        b.nx[j] = flip[j] ? -b.nx[j] : b.nx[j];
        b.ny[j] = flip[j] ? -b.ny[j] : b.ny[j];
        b.nz[j] = flip[j] ? -b.nz[j] : b.nz[j];
    }
    cj_lanes_light(c, CJ_LANES, any_mirror, any_half, &b);
    if (uniform) {
        float o[3][CJ_LANES];
        for (int k = 0; k < 3; ++k)
            for (int j = 0; j < CJ_LANES; ++j) {
                /* emission is added, not reflected (as light_eval does for the scalar paths) */
                const float A = m0->amb[k] + m0->kd * b.sd[k][j],
                            S = m0->spec[k] * b.ss[k][j] + m0->emit[k];
                o[k][j] = cr[k][j] * A + S;
            }
        for (int j = 0; j < n; ++j) {
            float *out = col + 4 * (size_t)idx[j];
            out[0] = o[0][j];
            out[1] = o[1][j];
            out[2] = o[2][j];
            out[3] = m0->opacity;
        }
        return;
    }
    for (int j = 0; j < n; ++j) {
        const cj_rmat *m = &c->mats[mi[j]];
        float *out = col + 4 * (size_t)idx[j];
        for (int k = 0; k < 3; ++k) {
            const float A = m->amb[k] + m->kd * b.sd[k][j],
                        S = m->spec[k] * b.ss[k][j] + m->emit[k];
            out[k] = cr[k][j] * A + S;
        }
        out[3] = m->opacity;
    }
}

void cj_rshade_phong8(const cj_rctx *c, const cj_tile *t, const uint32_t *idx, size_t n,
                      float *col) {
    for (size_t j = 0; j < n; j += CJ_LANES)
        phong_block(c, t, idx + j, n - j < CJ_LANES ? (int)(n - j) : CJ_LANES, 0, col);
}

void cj_rshade_phong8_tex(const cj_rctx *c, const cj_tile *t, const uint32_t *idx, size_t n,
                          float *col) {
    for (size_t j = 0; j < n; j += CJ_LANES)
        phong_block(c, t, idx + j, n - j < CJ_LANES ? (int)(n - j) : CJ_LANES, 1, col);
}

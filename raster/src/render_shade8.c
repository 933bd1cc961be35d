/* The Phong kernels, CJ_LANES samples at a time (issue 20): the tile's Phong samples are
 * gathered in blocks of 8 into a structure of arrays (normal, position − eye, material), lit
 * by the lane lighting of render_light8.h (vectorised: one AVX register per quantity), then
 * written out. A short last block repeats its last sample in the unused lanes, so every
 * sample goes through the same 8-lane code whatever the tile or thread; the values equal the
 * scalar k_phong_one of render_shade.c (the same source at n = 1). */
#include "render_light8.h"
#include "texture_lanes.h"

/* One block: lanes j < n hold the samples idx[0..n) of the tile (n <= CJ_LANES). */
static inline __attribute__((always_inline)) void phong_block(const cj_rctx *c, const cj_tile *t,
                                                              const uint32_t *idx, int n,
                                                              const int tex, float *col) {
    const cj_rlist *L = &c->opaque;
    const int tw = t->x1 - t->x0, spp = t->spp;
    const int spp_shift = spp == 16 ? 4 : spp == 4 ? 2 : 0;
    const double inv_tw = 1.0 / tw;
    cj_lanes b;
    const cj_rmat *mat[CJ_LANES];
    float cr[3][CJ_LANES], tx[3][CJ_LANES];
    cj_checker_lanes ck;
    int any_mirror = 0, any_half = 0, any_checker = 0, checker[CJ_LANES];
    for (int j = 0; j < CJ_LANES; ++j) {
        const uint32_t i = idx[j < n ? j : n - 1];
        const cj_vis_sample *s = &t->samples[i];
        const uint32_t tri = s->tri, *tv = L->tris + 3 * (size_t)tri;
        const float b1 = s->b1, b2 = s->b2, b0 = 1.0f - b1 - b2;
        const cj_rmat *m = &c->mats[c->obj_mat[L->obj[tri]]];
        mat[j] = m;
        const float *n0 = c->b->nrm + 3 * (size_t)tv[0], *n1 = c->b->nrm + 3 * (size_t)tv[1],
                    *n2 = c->b->nrm + 3 * (size_t)tv[2];
        const float *p0 = c->pe + 3 * (size_t)tv[0], *p1 = c->pe + 3 * (size_t)tv[1],
                    *p2 = c->pe + 3 * (size_t)tv[2];
        b.nx[j] = b0 * n0[0] + b1 * n1[0] + b2 * n2[0];
        b.ny[j] = b0 * n0[1] + b1 * n1[1] + b2 * n2[1];
        b.nz[j] = b0 * n0[2] + b1 * n1[2] + b2 * n2[2];
        b.px[j] = b0 * p0[0] + b1 * p1[0] + b2 * p2[0];
        b.py[j] = b0 * p0[1] + b1 * p1[1] + b2 * p2[1];
        b.pz[j] = b0 * p0[2] + b1 * p1[2] + b2 * p2[2];
        b.alpha[j] = m->alpha;
        b.mirror[j] = m->spec_model == CJ_SPEC_PHONG;
        any_mirror |= b.mirror[j];
        any_half |= !b.mirror[j];
        cr[0][j] = m->cr[0];
        cr[1][j] = m->cr[1];
        cr[2][j] = m->cr[2];
        if (tex) {
            /* pixel and sample of index i without an integer division: spp is 1, 4 or 16;
             * (px + ½)/tw is at least 1/(2 tw) from an integer and its product by the rounded
             * 1/tw errs by under 2^-52 · px/tw < 2^-22, so the truncation is exact */
            const uint32_t px = i >> spp_shift, si = i & (uint32_t)(spp - 1);
            const int row = (int)(((double)px + 0.5) * inv_tw), column = (int)px - row * tw;
            const double sx = t->x0 + column + c->pattern[si][0];
            const double sy = t->y0 + row + c->pattern[si][1];
            const cj_tex_sampler *smp = &c->samplers[m->tex];
            checker[j] = smp->kind == CJ_TEX_CHECKER;
            if (!checker[j]) { /* image textures: the scalar sampler */
                float rgb[3];
                cj_rshade_tex(c, L, tri, b1, b2, sx, sy, rgb);
                for (int k = 0; k < 3; ++k) tx[k][j] = rgb[k];
                cj_checker_lanes_clear(&ck, j);
                continue;
            }
            any_checker = 1;
            const float *t0 = c->b->uv + 2 * (size_t)tv[0], *t1 = c->b->uv + 2 * (size_t)tv[1],
                        *t2 = c->b->uv + 2 * (size_t)tv[2];
            ck.u[j] = (double)(b0 * t0[0] + b1 * t1[0] + b2 * t2[0]);
            ck.v[j] = (double)(b0 * t0[1] + b1 * t1[1] + b2 * t2[1]);
            ck.sx[j] = sx;
            ck.sy[j] = sy;
            /* no footprint: the zero plane, whose derivatives are 0 (texture_lanes.h) */
            static const double zero_plane[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
            const double *pl =
                smp->needs_deriv && L->uvplane ? L->uvplane + 9 * (size_t)tri : zero_plane;
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
    }
    if (tex) {
        if (any_checker) {
            float ct[3][CJ_LANES];
            cj_checker_lanes_sample(CJ_LANES, &ck, ct);
            for (int k = 0; k < 3; ++k)
                for (int j = 0; j < CJ_LANES; ++j) tx[k][j] = checker[j] ? ct[k][j] : tx[k][j];
        }
        for (int k = 0; k < 3; ++k)
            for (int j = 0; j < CJ_LANES; ++j) cr[k][j] *= tx[k][j];
    }
    cj_lanes_normalize(CJ_LANES, b.nx, b.ny, b.nz);
    for (int j = 0; j < CJ_LANES; ++j) {
        const uint32_t tri = t->samples[idx[j < n ? j : n - 1]].tri;
        if (L->back && L->back[tri]) {
            b.nx[j] = -b.nx[j];
            b.ny[j] = -b.ny[j];
            b.nz[j] = -b.nz[j];
        }
    }
    cj_lanes_light(c, CJ_LANES, any_mirror, any_half, &b);
    for (int j = 0; j < n; ++j) {
        const cj_rmat *m = mat[j];
        float *out = col + 4 * (size_t)idx[j];
        for (int k = 0; k < 3; ++k) {
            /* emission is added, not reflected (as light_eval does for the scalar paths) */
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

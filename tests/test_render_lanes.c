/* test_render_lanes: the rasterizer's 8-lane reflection terms (raster/src/render_light8.h)
 * against the one shared model (reflect_model.h, cj_reflect_terms_f with powf), over random
 * unit normals, light and view directions, exponents 0..200, both lobes and both light
 * models (seed printed; CJ_SEED replays):
 *   - d is bit-identical (the same float operations);
 *   - s differs only by the polynomial pow: |Δs| <= 6e-7 (1 + |α log2 c|) |s| (pow_poly.h's
 *     4e-7 bound plus powf's own rounding), c the lobe cosine, or both below 1e-30 (the
 *     pow underflows to 0 below 2^-126, where powf may give a subnormal);
 *   - lit/unlit and the zero lobe (α = 0) agree exactly;
 *   - an 8-lane call equals 8 one-lane calls bit for bit (this file is compiled with the
 *     kernels' flags, so the 8-lane loops are vectorised as in the library).
 * And the 8-lane checker (texture_lanes.h) against cj_tex_sample, bit for bit, over random
 * (u, v), scales, offsets, checks, filters (NEAREST point-samples, BILINEAR box-filters) and
 * footprints from tiny to huge (the derivatives from a random (u,v) plane by the formula of
 * render_shade.c's uv_derivs, restated here); half of the blocks with one sampler in every lane
 * through cj_checker_lanes_set_params. Prints the worst relative difference of s. */
#include "render_light8.h"
#include "texture_lanes.h"

#include "support/check.h"
#include "support/rng.h"

#include <math.h>
#include <stdio.h>

static void unit(cj_rng *r, float out[3]) {
    double v[3], l;
    do {
        for (int k = 0; k < 3; ++k) v[k] = cj_rng_range(r, -1.0, 1.0);
        l = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    } while (l < 0.1 || l > 1.0);
    for (int k = 0; k < 3; ++k) out[k] = (float)(v[k] / l);
}

/* The (u,v) plane's screen derivatives at (sx, sy) (render_shade.c's uv_derivs). */
static void plane_derivs(const double *pl, double sx, double sy, double d[4]) {
    const double *U = pl, *V = pl + 3, *Q = pl + 6;
    const double s = Q[0] * sx + Q[1] * sy + Q[2];
    if (s == 0.0) {
        d[0] = d[1] = d[2] = d[3] = 0.0;
        return;
    }
    const double u = (U[0] * sx + U[1] * sy + U[2]) / s, v = (V[0] * sx + V[1] * sy + V[2]) / s;
    d[0] = (U[0] - u * Q[0]) / s; /* du/dx */
    d[1] = (V[0] - v * Q[0]) / s; /* dv/dx */
    d[2] = (U[1] - u * Q[1]) / s; /* du/dy */
    d[3] = (V[1] - v * Q[1]) / s; /* dv/dy */
}

/* Returns the number of lanes that differ from cj_tex_sample. */
static long checker_cases(cj_rng *rng, long *count) {
    long differ = 0;
    for (int it = 0; it < 20000; ++it) {
        cj_tex_sampler smp[CJ_TEX_LANES];
        cj_checker_lanes ck;
        for (int j = 0; j < CJ_TEX_LANES; ++j) {
            cj_texture tx = cj_texture_defaults(CJ_TEX_CHECKER);
            tx.filter = cj_rng_unit(rng) < 0.25 ? CJ_TEX_NEAREST : CJ_TEX_BILINEAR;
            tx.scale_u = cj_rng_range(rng, -4.0, 4.0);
            tx.scale_v = cj_rng_range(rng, -4.0, 4.0);
            tx.offset_u = cj_rng_range(rng, -2.0, 2.0);
            tx.offset_v = cj_rng_range(rng, -2.0, 2.0);
            tx.checks_u = cj_rng_int(rng, 1, 64);
            tx.checks_v = cj_rng_int(rng, 1, 64);
            tx.checker_a = cj_rgb_make(cj_rng_unit(rng), cj_rng_unit(rng), cj_rng_unit(rng));
            tx.checker_b = cj_rgb_make(cj_rng_unit(rng), cj_rng_unit(rng), cj_rng_unit(rng));
            CHECK(!cj_tex_sampler_init(&tx, 0, NULL, &smp[j]), "sampler");
            ck.u[j] = cj_rng_range(rng, -3.0, 3.0);
            ck.v[j] = cj_rng_range(rng, -3.0, 3.0);
            /* on cell edges now and then */
            if (cj_rng_unit(rng) < 0.1) {
                ck.u[j] = (double)cj_rng_int(rng, -8, 8) / tx.checks_u;
                smp[j].su = 1.0;
                smp[j].ou = 0.0;
            }
            ck.sx[j] = cj_rng_range(rng, 0.0, 1024.0);
            ck.sy[j] = cj_rng_range(rng, 0.0, 1024.0);
            const double scale = pow(10.0, cj_rng_range(rng, -9.0, 7.0));
            const int zero = cj_rng_unit(rng) < 0.1;
            for (int k = 0; k < 9; ++k)
                ck.plane[k][j] = zero ? 0.0 : cj_rng_range(rng, -1.0, 1.0) * (k < 6 ? scale : 1.0);
            ck.su[j] = smp[j].su;
            ck.sv[j] = smp[j].sv;
            ck.ou[j] = smp[j].ou;
            ck.ov[j] = smp[j].ov;
            ck.cu[j] = smp[j].checks_u;
            ck.cv[j] = smp[j].checks_v;
            ck.deriv[j] = smp[j].needs_deriv;
            for (int k = 0; k < 3; ++k) {
                ck.a[k][j] = smp[j].a[k];
                ck.b[k][j] = smp[j].b[k];
            }
        }
        /* every other block: one sampler for all lanes, its parameters broadcast by
         * cj_checker_lanes_set_params (the Phong kernel's blocks on one material) */
        const int uniform = it % 2 == 1;
        if (uniform) cj_checker_lanes_set_params(&ck, &smp[0]);
        float out[3][CJ_TEX_LANES];
        cj_checker_lanes_sample(CJ_TEX_LANES, &ck, out);
        for (int j = 0; j < CJ_TEX_LANES; ++j) {
            double pl[9], d[4];
            for (int k = 0; k < 9; ++k) pl[k] = ck.plane[k][j];
            plane_derivs(pl, ck.sx[j], ck.sy[j], d);
            float ref[3];
            cj_tex_sample(&smp[uniform ? 0 : j], ck.u[j], ck.v[j], d[0], d[1], d[2], d[3], ref);
            ++*count;
            if (ref[0] != out[0][j] || ref[1] != out[1][j] || ref[2] != out[2][j]) {
                if (++differ <= 5)
                    fprintf(stderr,
                            "checker lane %d: (%.9g %.9g %.9g) vs cj_tex_sample (%.9g %.9g %.9g)\n",
                            j, out[0][j], out[1][j], out[2][j], ref[0], ref[1], ref[2]);
            }
            cj_tex_sampler_free(&smp[j]);
        }
    }
    return differ;
}

int main(void) {
    const uint64_t seed = cj_test_seed("test_render_lanes", 1126);
    cj_rng rng;
    cj_rng_init(&rng, seed);
    long cases = 0, lit = 0, lane_mismatch = 0;
    double worst = 0.0;
    for (int it = 0; it < 40000; ++it) {
        const int radiometric = it & 1;
        cj_lanes b;
        float lx[CJ_LANES], ly[CJ_LANES], lz[CJ_LANES], vx[CJ_LANES], vy[CJ_LANES], vz[CJ_LANES];
        int any_mirror = 0, any_half = 0;
        for (int j = 0; j < CJ_LANES; ++j) {
            float n[3], l[3], v[3];
            unit(&rng, n);
            unit(&rng, l);
            unit(&rng, v);
            /* bias the view towards the mirror direction so that highlights are common */
            if (cj_rng_unit(&rng) < 0.5) {
                const float nl = n[0] * l[0] + n[1] * l[1] + n[2] * l[2];
                for (int k = 0; k < 3; ++k)
                    v[k] = 2.0f * nl * n[k] - l[k] + (float)cj_rng_range(&rng, -0.1, 0.1);
                const float len = sqrtf(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
                for (int k = 0; k < 3; ++k) v[k] /= len;
            }
            b.nx[j] = n[0], b.ny[j] = n[1], b.nz[j] = n[2];
            lx[j] = l[0], ly[j] = l[1], lz[j] = l[2];
            vx[j] = v[0], vy[j] = v[1], vz[j] = v[2];
            const int zero = cj_rng_unit(&rng) < 0.05;
            b.alpha[j] = zero ? 0.0f : (float)cj_rng_range(&rng, 0.0, 200.0);
            b.mirror[j] = cj_rng_unit(&rng) < 0.5;
            any_mirror |= b.mirror[j];
            any_half |= !b.mirror[j];
        }
        float d8[CJ_LANES], s8[CJ_LANES];
        cj_lanes_terms(CJ_LANES, radiometric, any_mirror, any_half, &b, lx, ly, lz, vx, vy, vz, d8,
                       s8);
        for (int j = 0; j < CJ_LANES; ++j) {
            /* one lane alone */
            cj_lanes one;
            one.nx[0] = b.nx[j], one.ny[0] = b.ny[j], one.nz[0] = b.nz[j];
            one.alpha[0] = b.alpha[j];
            one.mirror[0] = b.mirror[j];
            float d1, s1;
            cj_lanes_terms(1, radiometric, one.mirror[0], !one.mirror[0], &one, &lx[j], &ly[j],
                           &lz[j], &vx[j], &vy[j], &vz[j], &d1, &s1);
            if (d1 != d8[j] || s1 != s8[j]) ++lane_mismatch;
            /* the shared model */
            const float n[3] = {b.nx[j], b.ny[j], b.nz[j]}, l[3] = {lx[j], ly[j], lz[j]},
                        v[3] = {vx[j], vy[j], vz[j]};
            float dr, sr;
            cj_reflect_terms_f(n, l, v, b.alpha[j], b.mirror[j] ? CJ_SPEC_PHONG : CJ_SPEC_BLINN,
                               radiometric, &dr, &sr);
            ++cases;
            CHECK(dr == d8[j], "case %ld lane %d: d %.9g vs model %.9g", cases, j, d8[j], dr);
            /* below 2^-126 the pow underflows to 0 (pow_poly.h), where powf may still give a
             * subnormal: values below 1e-30 (after the BRDF's factor) count as 0 */
            const double tiny = 1e-30;
            CHECK((sr > 0.0f) == (s8[j] > 0.0f) || fabs((double)s8[j] - sr) <= tiny,
                  "case %ld: s %.9g vs %.9g (lit state)", cases, s8[j], sr);
            if (!(sr > 0.0f) || fabs((double)s8[j] - sr) <= tiny) continue;
            ++lit;
            /* the lobe cosine, for the bound */
            double c;
            if (b.mirror[j]) {
                const double nl = (double)n[0] * l[0] + (double)n[1] * l[1] + (double)n[2] * l[2];
                c = 0.0;
                for (int k = 0; k < 3; ++k) c += (2.0 * nl * n[k] - l[k]) * v[k];
            } else {
                double h[3] = {(double)l[0] + v[0], (double)l[1] + v[1], (double)l[2] + v[2]};
                const double hl = sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
                c = (n[0] * h[0] + n[1] * h[1] + n[2] * h[2]) / hl;
            }
            const double y = c > 0.0 ? b.alpha[j] * fabs(log2(c)) : 0.0;
            const double rel = fabs((double)s8[j] - sr) / ((1.0 + y) * sr);
            if (rel > worst) worst = rel;
            CHECK(rel <= 6e-7, "case %ld lane %d: s %.9g vs model %.9g (α %.4g, y %.3g): %.3g",
                  cases, j, s8[j], sr, b.alpha[j], y, rel);
        }
    }
    CHECK(lane_mismatch == 0, "%ld lanes differ between the 8-lane and 1-lane calls",
          lane_mismatch);
    long checker_count = 0;
    const long checker_differ = checker_cases(&rng, &checker_count);
    CHECK(checker_differ == 0, "%ld of %ld checker lanes differ from cj_tex_sample", checker_differ,
          checker_count);
    printf("test_render_lanes: seed %llu, %ld cases (%ld lit with a lobe): d bit-identical to "
           "reflect_model.h, worst relative s difference %.3g of (1 + |α log2 c|) (bound 6e-7), "
           "8 lanes = 1 lane (%ld mismatches); checker: %ld of %ld lanes differ from "
           "cj_tex_sample\n",
           (unsigned long long)seed, cases, lit, worst, lane_mismatch, checker_differ,
           checker_count);
    return cj_check_exit();
}

/* Texture sampling of the rasterizer (raster/src/texture_internal.h, seed 10): nearest texels
 * and wrap modes, bilinear against a double-precision reference at seeded random points, the
 * mip pyramid and trilinear level choice from the screen footprint, the procedural checker
 * point-sampled and box-filtered, and the refusal of an image texture without pixels. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "rng.h"
#include "texture_internal.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

static cj_texture image(int w, int h, const float *texels, cj_tex_filter f, cj_tex_wrap wrap) {
    cj_texture t = cj_texture_defaults(CJ_TEX_IMAGE);
    t.filter = f;
    t.wrap = wrap;
    t.width = w;
    t.height = h;
    t.texels = texels;
    t.path = "test";
    t.scale_u = t.scale_v = 1.0;
    t.offset_u = t.offset_v = 0.0;
    return t;
}

static void test_nearest_and_wrap(void **state) {
    (void)state;
    /* 2 x 2: red, green (bottom row), blue, white (top row) */
    const float px[16] = {1, 0, 0, 1, 0, 1, 0, 1, 0, 0, 1, 1, 1, 1, 1, 1};
    cj_tex_sampler s;
    cj_texture t = image(2, 2, px, CJ_TEX_NEAREST, CJ_TEX_REPEAT);
    assert_int_equal(cj_tex_sampler_init(&t, 0, NULL, &s), CJ_OK);
    float o[3];
    cj_tex_sample(&s, 0.25, 0.25, 0, 0, 0, 0, o);
    assert_true(o[0] == 1 && o[1] == 0 && o[2] == 0);
    cj_tex_sample(&s, 0.75, 0.25, 0, 0, 0, 0, o);
    assert_true(o[0] == 0 && o[1] == 1 && o[2] == 0);
    cj_tex_sample(&s, 0.25, 0.75, 0, 0, 0, 0, o);
    assert_true(o[0] == 0 && o[1] == 0 && o[2] == 1);
    cj_tex_sample(&s, 1.25 + 7.0, -0.25, 0, 0, 0, 0, o); /* repeat: (0.25, 0.75) */
    assert_true(o[0] == 0 && o[1] == 0 && o[2] == 1);
    cj_tex_sampler_free(&s);
    t.wrap = CJ_TEX_CLAMP;
    assert_int_equal(cj_tex_sampler_init(&t, 0, NULL, &s), CJ_OK);
    cj_tex_sample(&s, 3.0, -2.0, 0, 0, 0, 0, o); /* clamp: (1, 0) -> green */
    assert_true(o[0] == 0 && o[1] == 1 && o[2] == 0);
    cj_tex_sampler_free(&s);
    /* no pixels: refused, naming the texture */
    t.texels = NULL;
    assert_int_equal(cj_tex_sampler_init(&t, 3, NULL, &s), CJ_ERR_ARGUMENT);
    assert_non_null(strstr(cj_last_error(), "textures[3]"));
    printf("test_nearest_and_wrap: texels, repeat, clamp, missing pixels refused\n");
}

static void test_bilinear_reference(void **state) {
    (void)state;
    uint64_t seed = cj_test_seed("test_bilinear_reference", 8);
    cj_rng r;
    cj_rng_init(&r, seed);
    enum { W = 5, H = 3 };
    float px[W * H * 4];
    for (int i = 0; i < W * H * 4; ++i) px[i] = (float)cj_rng_unit(&r);
    cj_tex_sampler s;
    cj_texture t = image(W, H, px, CJ_TEX_BILINEAR, CJ_TEX_REPEAT);
    assert_int_equal(cj_tex_sampler_init(&t, 0, NULL, &s), CJ_OK);
    double worst = 0.0;
    for (int k = 0; k < 2000; ++k) {
        double u = cj_rng_range(&r, -2, 3), v = cj_rng_range(&r, -2, 3);
        float o[3];
        cj_tex_sample(&s, u, v, 0, 0, 0, 0, o);
        double x = (u - floor(u)) * W - 0.5, y = (v - floor(v)) * H - 0.5;
        int x0 = (int)floor(x), y0 = (int)floor(y);
        double fx = x - x0, fy = y - y0;
        for (int c = 0; c < 3; ++c) {
            double acc = 0.0;
            for (int dy = 0; dy < 2; ++dy)
                for (int dx = 0; dx < 2; ++dx) {
                    int xi = ((x0 + dx) % W + W) % W, yi = ((y0 + dy) % H + H) % H;
                    acc += (dx ? fx : 1 - fx) * (dy ? fy : 1 - fy) * px[(yi * W + xi) * 4 + c];
                }
            double e = fabs(o[c] - acc);
            if (e > worst) worst = e;
        }
    }
    assert_true(worst < 2e-6);
    cj_tex_sampler_free(&s);
    printf("test_bilinear_reference: 2000 random points on a 5 x 3 texture, max |error| %.2e vs "
           "the double formula\n",
           worst);
}

static void test_trilinear_levels(void **state) {
    (void)state;
    /* 4 x 4 black/white checker: every 2 x 2 box averages to 0.5 */
    float px[64];
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x)
            for (int c = 0; c < 4; ++c) px[(y * 4 + x) * 4 + c] = (float)((x + y) & 1);
    cj_tex_sampler s;
    cj_texture t = image(4, 4, px, CJ_TEX_TRILINEAR, CJ_TEX_REPEAT);
    assert_int_equal(cj_tex_sampler_init(&t, 0, NULL, &s), CJ_OK);
    assert_int_equal(s.levels, 3);
    assert_true(s.level[1].w == 2 && s.level[2].w == 1);
    for (int i = 0; i < 4; ++i) assert_true(s.level[1].rgba[4 * i] == 0.5f);
    float o[3];
    /* footprint below a texel: level 0, the texel itself at its centre */
    cj_tex_sample(&s, 0.125, 0.125, 0.01, 0, 0, 0.01, o);
    assert_true(o[0] == 0.0f);
    cj_tex_sample(&s, 0.375, 0.125, 0.01, 0, 0, 0.01, o);
    assert_true(o[0] == 1.0f);
    /* footprint of 2 texels: level 1, uniformly 0.5; larger: the last level */
    cj_tex_sample(&s, 0.375, 0.125, 0.5, 0, 0, 0.5, o);
    assert_true(o[0] == 0.5f);
    cj_tex_sample(&s, 0.1, 0.9, 30.0, 0, 0, 30.0, o);
    assert_true(o[0] == 0.5f);
    /* between level 0 and 1 (footprint sqrt 2 texels): halfway between texel and 0.5 */
    cj_tex_sample(&s, 0.375, 0.125, sqrt(2.0) / 4.0, 0, 0, 0, o);
    assert_float_equal(o[0], 0.75, 1e-6);
    cj_tex_sampler_free(&s);
    printf("test_trilinear_levels: pyramid 4-2-1, level from the footprint, lerp between levels\n");
}

static void test_checker(void **state) {
    (void)state;
    cj_texture t = cj_texture_defaults(CJ_TEX_CHECKER);
    t.checks_u = t.checks_v = 4;
    t.scale_u = t.scale_v = 1.0;
    t.offset_u = t.offset_v = 0.0;
    t.checker_a = cj_rgb_make(1, 1, 1);
    t.checker_b = cj_rgb_make(0, 0, 0);
    t.filter = CJ_TEX_NEAREST;
    cj_tex_sampler s;
    assert_int_equal(cj_tex_sampler_init(&t, 0, NULL, &s), CJ_OK);
    float o[3];
    cj_tex_sample(&s, 0.1, 0.1, 0, 0, 0, 0, o);
    assert_true(o[0] == 1.0f);
    cj_tex_sample(&s, 0.3, 0.1, 0, 0, 0, 0, o);
    assert_true(o[0] == 0.0f);
    cj_tex_sample(&s, 0.3, 0.3, 0, 0, 0, 0, o);
    assert_true(o[0] == 1.0f);
    cj_tex_sample(&s, -0.1, 0.1, 0, 0, 0, 0, o); /* cell -1: odd */
    assert_true(o[0] == 0.0f);
    t.filter = CJ_TEX_BILINEAR;
    assert_int_equal(cj_tex_sampler_init(&t, 0, NULL, &s), CJ_OK);
    /* a footprint of 2 checks in u and v: exactly half of each colour */
    cj_tex_sample(&s, 0.37, 0.61, 0.5, 0.0, 0.0, 0.5, o);
    assert_float_equal(o[0], 0.5, 1e-12);
    /* a tiny footprint inside a cell: the cell's colour */
    cj_tex_sample(&s, 0.1, 0.1, 1e-4, 0, 0, 1e-4, o);
    assert_float_equal(o[0], 1.0, 1e-12);
    /* a footprint of half a check centred on an edge: half and half */
    cj_tex_sample(&s, 0.25, 0.1, 0.125, 0, 0, 1e-4, o);
    assert_float_equal(o[0], 0.5, 1e-6);
    printf("test_checker: point-sampled cells and the box-filtered pattern (0.5 over two "
           "checks, half on an edge)\n");
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_nearest_and_wrap),
        cmocka_unit_test(test_bilinear_reference),
        cmocka_unit_test(test_trilinear_levels),
        cmocka_unit_test(test_checker),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

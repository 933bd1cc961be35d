/* The ray tracer's stratified sampling of area lights (raster/src/trace_shade.c):
 *  - cj_trace_permute is a permutation of [0, n) for every n up to 1100 and for 4096 and 65536,
 *    under many keys, and its pairings are not one fixed shift;
 *  - stratified soft shadows converge: the RMSE between two renders with different seeds
 *    falls at least like 1/sqrt(spp) from 16 to 256 spp (a fixed pairing of pixel and light
 *    strata kept a floor that more samples did not lower);
 *  - at a sample count that is not a square (8), the stratified estimate is unbiased: its mean
 *    over many seeds agrees with plain random sampling's to within their noise. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "casteljau/render.h"
#include "casteljau/scene.h"
#include "casteljau/trace.h"
#include "trace_shade.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define W 32

static void test_permute_is_bijective(void **state) {
    (void)state;
    static unsigned char seen[65536];
    const uint32_t big[2] = {4096, 65536};
    int shifts = 0, tried = 0;
    for (uint32_t n = 1; n <= 1100 + 2; n++) {
        uint32_t m = n <= 1100 ? n : big[n - 1101];
        for (int k = 0; k < 8; k++) {
            uint64_t key = cj_trace_mix(0x1234u + 977u * m + (uint64_t)k);
            memset(seen, 0, m);
            for (uint32_t i = 0; i < m; i++) {
                uint32_t p = cj_trace_permute(i, m, key);
                assert_true(p < m);
                assert_int_equal(seen[p], 0);
                seen[p] = 1;
            }
            if (m >= 4) { /* a cyclic shift maps i + 1 to p(i) + 1 for every i */
                int shift = 1;
                for (uint32_t i = 0; i + 1 < m && shift; i++)
                    shift =
                        cj_trace_permute(i + 1, m, key) == (cj_trace_permute(i, m, key) + 1) % m;
                shifts += shift;
                tried++;
            }
        }
    }
    printf("  cj_trace_permute: a permutation for n = 1..1100, 4096, 65536 under 8 keys each; "
           "%d of %d are cyclic shifts\n",
           shifts, tried);
    assert_true(shifts * 100 < tried);
}

/* A floor, a unit sphere at height 2 and a 4 x 4 area light at height 6: the camera looks down
 * on the sphere's soft shadow, so most pixels are in the penumbra. */
static cj_scene *penumbra_scene(int spp) {
    cj_scene *sc;
    assert_int_equal(cj_scene_create(NULL, &sc), CJ_OK);
    cj_camera cam = cj_camera_defaults();
    cam.eye = cj_v3(0, 9, 0.01);
    cam.gaze = cj_v3(0, -1, 0);
    cam.up = cj_v3(0, 0, -1);
    cam.near = -0.1;
    cam.far = -100;
    assert_int_equal(cj_scene_set_camera(sc, &cam), CJ_OK);
    cj_scene_settings set = cj_scene_settings_defaults();
    set.width = W;
    set.height = W;
    set.spp = spp;
    assert_int_equal(cj_scene_set_settings(sc, &set), CJ_OK);
    cj_light area = cj_light_defaults(CJ_LIGHT_AREA);
    area.position = cj_v3(-2, 6, -2);
    area.edge_u = cj_v3(4, 0, 0);
    area.edge_v = cj_v3(0, 0, 4);
    area.intensity = 1.0;
    assert_int_equal(cj_scene_add_light(sc, &area, NULL), CJ_OK);
    cj_material fm = cj_material_defaults();
    fm.ka = 0.0;
    fm.kd = 1.0;
    fm.ks = 0.0;
    int ifm, ig1, ig2;
    assert_int_equal(cj_scene_add_material(sc, &fm, &ifm), CJ_OK);
    cj_geometry g;
    memset(&g, 0, sizeof g);
    g.kind = CJ_GEOM_PLANAR;
    assert_int_equal(
        cj_planar_patch_init(&g.u.planar, cj_v3(-20, 0, 20), cj_v3(40, 0, 0), cj_v3(0, 0, -40)),
        CJ_OK);
    assert_int_equal(cj_scene_add_geometry(sc, &g, &ig1), CJ_OK);
    memset(&g, 0, sizeof g);
    g.kind = CJ_GEOM_SPHERE;
    g.u.sphere.center = cj_v3(0, 2, 0);
    g.u.sphere.radius = 1;
    assert_int_equal(cj_scene_add_geometry(sc, &g, &ig2), CJ_OK);
    cj_node n1 = cj_node_defaults(ig1, ifm), n2 = cj_node_defaults(ig2, ifm);
    assert_int_equal(cj_scene_add_node(sc, &n1, NULL), CJ_OK);
    assert_int_equal(cj_scene_add_node(sc, &n2, NULL), CJ_OK);
    return sc;
}

/* The red channel of a render with this seed and sampling, accumulated into acc (W*W). */
static void render_into(const cj_scene *sc, uint64_t seed, int random, double *acc) {
    cj_render_options o = cj_render_options_defaults();
    o.use_seed = 1;
    o.seed = seed;
    o.threads = 2;
    cj_trace_options to = {random, 0, 0, 0, 0};
    cj_render_image *img = NULL;
    assert_int_equal(cj_render_trace_with_options(sc, &o, &to, 0, NULL, &img, NULL), CJ_OK);
    for (int i = 0; i < W * W; i++) acc[i] += img->rgba[4 * i];
    cj_render_image_destroy(img);
}

static double rmse(const double *a, const double *b, double scale) {
    double s = 0;
    for (int i = 0; i < W * W; i++) s += (a[i] - b[i]) * (a[i] - b[i]);
    return sqrt(s / (W * W)) * scale;
}

static void test_stratified_converges(void **state) {
    (void)state;
    const int spp[2] = {16, 256};
    double r[2];
    for (int k = 0; k < 2; k++) {
        cj_scene *sc = penumbra_scene(spp[k]);
        double a[W * W] = {0}, b[W * W] = {0};
        render_into(sc, 101, 0, a);
        render_into(sc, 202, 0, b);
        r[k] = rmse(a, b, 1.0);
        cj_scene_destroy(sc);
    }
    printf("  stratified, RMSE between two seeds: %.5f at 16 spp, %.5f at 256 spp (%.2fx; "
           "1/sqrt(spp) predicts 4x)\n",
           r[0], r[1], r[0] / r[1]);
    assert_true(r[0] > 0 && r[1] > 0);
    assert_true(r[0] / r[1] >= 3.5);
}

static void test_non_square_unbiased(void **state) {
    (void)state;
    enum { SEEDS = 32 };
    cj_scene *sc = penumbra_scene(8);
    static double strat[W * W], rnd[W * W], rnd2[W * W];
    memset(strat, 0, sizeof strat);
    memset(rnd, 0, sizeof rnd);
    memset(rnd2, 0, sizeof rnd2);
    for (int s = 0; s < SEEDS; s++) {
        render_into(sc, 1000 + (uint64_t)s, 0, strat);
        render_into(sc, 5000 + (uint64_t)s, 1, rnd);
        render_into(sc, 9000 + (uint64_t)s, 1, rnd2);
    }
    cj_scene_destroy(sc);
    /* Random against random shows the noise of a 256-sample mean; stratified has less noise,
     * so an unbiased stratified mean is no farther from a random one than that. */
    double d_sr = rmse(strat, rnd, 1.0 / SEEDS), d_rr = rmse(rnd2, rnd, 1.0 / SEEDS);
    printf("  8 spp x %d seeds: RMSE stratified - random %.5f, random - random %.5f\n", SEEDS, d_sr,
           d_rr);
    assert_true(d_sr <= 1.1 * d_rr);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_permute_is_bijective),
        cmocka_unit_test(test_stratified_converges),
        cmocka_unit_test(test_non_square_unbiased),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

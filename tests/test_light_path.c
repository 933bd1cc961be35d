/* The path tracer (cj_trace_options.integrator = CJ_INTEGRATOR_PATH, docs/light.md) against
 * closed forms:
 *  - the furnace: inside a closed sphere whose diffuse wall has albedo ρ and emits L_e, the
 *    radiance is L_e / (1 − ρ) everywhere (the Neumann series L_e Σ ρ^k); the image mean is
 *    within 4 standard errors of it (ρ = 0.5, 0.8, 0.9 per channel, Russian roulette and
 *    max_depth 64, whose truncation L_e ρ^65 / (1 − ρ) is added to the bound);
 *  - next-event estimation + MIS are unbiased: a Lambertian floor under a rectangular emitter
 *    (radiance L_e) shows ρ/π · E, E by the form factor's closed form (as in
 *    test_light_radiometric), within 4 standard errors on the floor's mean, the RMS pixel
 *    error under 3 % and the worst of the 2304 pixels under 12 % of the peak (256 spp), with
 *    the emitter also reachable by BRDF samples;
 *  - the emitter is seen by camera rays: pixels looking at it show L_e;
 *  - RMSE against a 4096-spp reference falls as 1/√spp with plain random sampling: the log-log
 *    slope over 4 … 256 spp is in [−0.6, −0.4]; with the first hit's light and BRDF samples
 *    stratified (the default) the error is lower at every spp;
 *  - the image is bit-identical for 1, 2 and 3 threads; every kind of ray is counted. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "casteljau/render.h"
#include "casteljau/scene.h"
#include "casteljau/stage_report.h"
#include "casteljau/trace.h"
#include "light_floor.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const double PI = 3.14159265358979323846;

static int g_random; /* cj_trace_options.random_sampling of path_render */

static cj_render_image *path_render(const cj_scene *s, int spp, int threads, uint64_t seed,
                                    cj_stage_report *rep) {
    cj_render_options o = cj_render_options_defaults();
    o.spp = spp;
    o.threads = threads;
    o.use_seed = 1;
    o.seed = seed;
    cj_trace_options to;
    memset(&to, 0, sizeof to);
    to.integrator = CJ_INTEGRATOR_PATH;
    to.random_sampling = g_random;
    cj_render_image *img = NULL;
    cj_status st = cj_render_trace_with_options(s, &o, &to, 0, NULL, &img, rep);
    if (st) printf("trace failed: %s\n", cj_last_error());
    assert_int_equal(st, CJ_OK);
    return img;
}

static void test_furnace(void **state) {
    (void)state;
    cj_scene *s;
    assert_int_equal(cj_scene_create(NULL, &s), CJ_OK);
    cj_camera cam = cj_camera_defaults();
    cam.eye = cj_v3(0.1, -0.2, 0.05);
    cam.gaze = cj_v3(0.3, 1, 0.2);
    cam.fov_y = 1.2;
    cam.near = -0.01;
    assert_int_equal(cj_scene_set_camera(s, &cam), CJ_OK);
    cj_scene_settings st = cj_scene_settings_defaults();
    st.width = 32;
    st.height = 32;
    st.max_depth = 64;
    st.light_model = CJ_LIGHT_RADIOMETRIC;
    assert_int_equal(cj_scene_set_settings(s, &st), CJ_OK);
    const double rho[3] = {0.5, 0.8, 0.9}, le = 0.3;
    cj_material m = cj_material_defaults();
    m.color = cj_rgb_make(rho[0], rho[1], rho[2]);
    m.kd = 1.0;
    m.ks = 0.0;
    m.ka = 0.0;
    m.two_sided = 1;
    m.emission = cj_rgb_make(le, le, le);
    int mi, gi;
    assert_int_equal(cj_scene_add_material(s, &m, &mi), CJ_OK);
    cj_geometry g;
    memset(&g, 0, sizeof g);
    g.kind = CJ_GEOM_SPHERE;
    g.u.sphere.radius = 1.0;
    assert_int_equal(cj_scene_add_geometry(s, &g, &gi), CJ_OK);
    cj_node n = cj_node_defaults(gi, mi);
    assert_int_equal(cj_scene_add_node(s, &n, NULL), CJ_OK);
    cj_stage_report rep;
    cj_render_image *img = path_render(s, 16, 0, 5, &rep);
    const int N = 32 * 32;
    for (int k = 0; k < 3; ++k) {
        double sum = 0, sum2 = 0;
        for (int i = 0; i < N; ++i) {
            double v = img->rgba[4 * i + k];
            sum += v;
            sum2 += v * v;
        }
        double mean = sum / N, se = sqrt(fmax(sum2 / N - mean * mean, 0.0) / N);
        double expect = le / (1 - rho[k]), trunc = expect * pow(rho[k], 65);
        printf("furnace rho %.2f: mean radiance %.5f +- %.5f (4 se), closed form L_e/(1-rho) = "
               "%.5f (max_depth truncation <= %.1e)\n",
               rho[k], mean, 4 * se, expect, trunc);
        assert_true(fabs(mean - expect) <= 4 * se + trunc);
    }
    const cj_stage *ind = cj_stage_report_find(&rep, "indirect_rays");
    const cj_stage *pri = cj_stage_report_find(&rep, "primary_rays");
    assert_non_null(ind);
    assert_non_null(pri);
    printf("rays: %llu primary, %llu bounces (%.2f per path)\n", (unsigned long long)pri->in,
           (unsigned long long)ind->in, (double)ind->in / (double)pri->in);
    assert_true(pri->in == (uint64_t)N * 16);
    assert_true(ind->in > pri->in);
    cj_render_image_destroy(img);
    cj_scene_destroy(s);
}

/* Floor [-2, 2]² at z = 0 of albedo 0.6 seen from above; emitter 1.2 × 1.2 at height 0.8. */
static const double RECT[4] = {-0.7, 0.5, -0.4, 0.8}, RH = 0.8, LE = 3.0, RHO = 0.6;
#define FW 48

static cj_scene *emitter_scene(double cam_z) {
    cj_scene *s = cj_test_light_floor(FW, FW, 2.0, 0.0, cam_z, RHO, CJ_LIGHT_RADIOMETRIC);
    assert_non_null(s);
    cj_scene_settings st = *cj_scene_get_settings(s);
    st.max_depth = 8;
    assert_int_equal(cj_scene_set_settings(s, &st), CJ_OK);
    cj_light a = cj_light_defaults(CJ_LIGHT_AREA);
    a.intensity = LE;
    a.position = cj_v3(RECT[0], RECT[2], RH);
    a.edge_u = cj_v3(0, RECT[3] - RECT[2], 0); /* edge_u × edge_v = −z: facing the floor */
    a.edge_v = cj_v3(RECT[1] - RECT[0], 0, 0);
    assert_int_equal(cj_scene_add_light(s, &a, NULL), CJ_OK);
    return s;
}

static double ff_corner(double a, double b, double h) {
    double X = a / h, Y = b / h, sx = sqrt(1 + X * X), sy = sqrt(1 + Y * Y);
    return (X / sx * atan(Y / sx) + Y / sy * atan(X / sy)) / (2 * PI);
}

static double rect_ff(double px, double py) {
    double xs[2] = {RECT[0] - px, RECT[1] - px}, ys[2] = {RECT[2] - py, RECT[3] - py}, f = 0;
    for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 2; ++j) {
            double sgn = ((i == 1) == (j == 1)) ? 1.0 : -1.0;
            f += sgn * (xs[i] < 0 ? -1 : 1) * (ys[j] < 0 ? -1 : 1) *
                 ff_corner(fabs(xs[i]), fabs(ys[j]), RH);
        }
    return f;
}

static void test_emitter_mis(void **state) {
    (void)state;
    /* the camera below the emitter: every floor pixel is the floor */
    cj_scene *s = emitter_scene(0.5);
    cj_render_image *img = path_render(s, 256, 0, 11, NULL);
    double worst = 0, peak = 0, sum = 0, sum_ref = 0, sum_d2 = 0;
    const int N = FW * FW;
    for (int y = 0; y < FW; ++y)
        for (int x = 0; x < FW; ++x) {
            double px = -2 + (x + 0.5) * 4.0 / FW, py = -2 + (y + 0.5) * 4.0 / FW;
            double ref = RHO * LE * rect_ff(px, py), v = img->rgba[4 * (y * FW + x)];
            if (ref > peak) peak = ref;
            double d = v - ref;
            sum += v;
            sum_ref += ref;
            sum_d2 += d * d;
            if (fabs(d) > worst) worst = fabs(d);
        }
    /* the error of the mean: per-pixel errors are independent */
    double se = sqrt(sum_d2 / N / N), bias = (sum - sum_ref) / N;
    double rms = sqrt(sum_d2 / N);
    printf("emitter + floor, 256 spp: worst pixel %.2e of the peak %.4f (tol 0.12), RMS %.2e of "
           "it (tol 0.03), mean off by %.2e (4 se = %.2e)\n",
           worst / peak, peak, rms / peak, bias, 4 * se);
    assert_true(worst <= 0.12 * peak);
    assert_true(rms <= 0.03 * peak);
    assert_true(fabs(bias) <= 4 * se);
    cj_render_image_destroy(img);
    cj_scene_destroy(s);

    /* the camera above the emitter: its back is dark (one-sided), so look from below it */
    s = emitter_scene(0.5);
    cj_camera cam = *cj_scene_get_camera(s);
    cam.eye = cj_v3(-0.1, 0.2, 0.3);
    cam.gaze = cj_v3(0, 0, 1);
    cam.ortho_height = 0.5;
    assert_int_equal(cj_scene_set_camera(s, &cam), CJ_OK);
    img = path_render(s, 1, 1, 3, NULL);
    double lo = 1e9, hi = 0;
    for (int i = 0; i < N; ++i) {
        double v = img->rgba[4 * i];
        if (v < lo) lo = v;
        if (v > hi) hi = v;
    }
    printf("camera rays at the emitter: radiance in [%g, %g], L_e = %g\n", lo, hi, LE);
    assert_true(lo == LE && hi == LE);
    cj_render_image_destroy(img);
    cj_scene_destroy(s);
}

static void test_convergence_and_threads(void **state) {
    (void)state;
    cj_scene *s = emitter_scene(2.0);
    cj_scene_settings st = *cj_scene_get_settings(s);
    st.width = st.height = 24;
    assert_int_equal(cj_scene_set_settings(s, &st), CJ_OK);
    g_random = 1; /* the reference: plain random sampling, unlike the stratified rows */
    cj_render_image *ref = path_render(s, 4096, 0, 99, NULL);
    const int spps[4] = {4, 16, 64, 256};
    double slope[2], rmse[2][4];
    for (int m = 0; m < 2; ++m) {
        g_random = m == 0;
        double lx[4], ly[4];
        for (int k = 0; k < 4; ++k) {
            cj_render_image *img = path_render(s, spps[k], 0, 1000 + k, NULL);
            double e2 = 0;
            for (int i = 0; i < 24 * 24; ++i) {
                double d = img->rgba[4 * i] - ref->rgba[4 * i];
                e2 += d * d;
            }
            rmse[m][k] = sqrt(e2 / (24 * 24));
            lx[k] = log((double)spps[k]);
            ly[k] = log(rmse[m][k]);
            cj_render_image_destroy(img);
        }
        double mx = 0, my = 0, sxy = 0, sxx = 0;
        for (int k = 0; k < 4; ++k) mx += lx[k] / 4, my += ly[k] / 4;
        for (int k = 0; k < 4; ++k)
            sxy += (lx[k] - mx) * (ly[k] - my), sxx += (lx[k] - mx) * (lx[k] - mx);
        slope[m] = sxy / sxx;
    }
    g_random = 0;
    for (int k = 0; k < 4; ++k)
        printf("spp %4d: RMSE random %.5f, stratified first hit %.5f (%.2fx lower)\n", spps[k],
               rmse[0][k], rmse[1][k], rmse[0][k] / rmse[1][k]);
    printf("log-log slope of RMSE against spp: random %.3f (1/sqrt(spp): -0.5), stratified %.3f\n",
           slope[0], slope[1]);
    /* plain Monte Carlo converges as 1/sqrt(spp); stratifying the first hit's light and BRDF
     * samples only lowers the error (the reference's own noise, 1/64 of the 1-spp variance,
     * flattens the stratified curve at 256 spp) */
    assert_true(slope[0] >= -0.6 && slope[0] <= -0.4);
    for (int k = 0; k < 4; ++k) assert_true(rmse[1][k] < rmse[0][k]);
    cj_render_image_destroy(ref);

    cj_render_image *one = path_render(s, 8, 1, 7, NULL);
    for (int th = 2; th <= 3; ++th) {
        cj_render_image *img = path_render(s, 8, th, 7, NULL);
        assert_memory_equal(one->rgba, img->rgba, sizeof(float) * 4 * 24 * 24);
        cj_render_image_destroy(img);
    }
    printf("8 spp: bit-identical for 1, 2, 3 threads\n");
    cj_render_image_destroy(one);
    cj_scene_destroy(s);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_furnace),
        cmocka_unit_test(test_emitter_mis),
        cmocka_unit_test(test_convergence_and_threads),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

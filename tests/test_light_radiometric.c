/* Radiometric light (settings.light_model "radiometric", docs/light.md) against closed forms,
 * on a Lambertian floor z = 0 (albedo ρ, BRDF ρ/π) seen straight from above:
 *  - a point light of intensity I at height h and a directional light of irradiance E_d: the
 *    floor's radiance is ρ/π (I h / r³ + E_d cos θ_d) (inverse square, cosine at the floor)
 *    at every pixel, in the tracer (exact plane; a float image) within 1e-6 relative and in the
 *    rasterizer (float shading) within 1e-5 relative; moving the light twice as high divides
 *    the radiance under it by 4 exactly;
 *  - a rectangular Lambertian emitter of radiance L_e parallel to the floor: the irradiance at a
 *    floor point is π L_e times the form factor, summed with signs over the four rectangles
 *    with a corner above the point (the classical closed form for a differential area under a
 *    parallel rectangle: F = (1/2π)[X/√(1+X²) atan(Y/√(1+X²)) + Y/√(1+Y²) atan(X/√(1+Y²))],
 *    X = a/h, Y = b/h, not the code's Lambert polygon sum). The rasterizer (exact polygon
 *    irradiance) matches ρ/π E within 1e-5 of the peak; the tracer (area samples, stratified,
 *    SPP per pixel) within NOISE_TOL of the peak at every pixel, and its mean over the floor
 *    within BIAS_TOL of the oracle's mean (no bias);
 *  - the emitter is one-sided: a floor above it (the emitter facing away) gets nothing, and
 *    camera rays see its emitting side with radiance L_e in both renderers;
 *  - the legacy model is unchanged: the same scene with "legacy" has no falloff (the radiance
 *    of the point-lit floor is ρ I cos θ, no π, no r²). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "casteljau/render.h"
#include "casteljau/scene.h"
#include "casteljau/trace.h"
#include "light_floor.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define W         64
#define H         64
#define SPP       256
#define NOISE_TOL 0.02 /* tracer, one pixel, fraction of the peak radiance */
#define BIAS_TOL  2e-3 /* tracer, mean over the floor, fraction of the oracle's mean */

static const double PI = 3.14159265358979323846;
static const double RHO = 0.6, HALF = 2.0; /* floor albedo; floor [-HALF, HALF]² */

/* The floor seen from above by an orthographic camera covering it exactly. */
static cj_scene *floor_scene(cj_light_model model, double floor_z) {
    cj_scene *s = cj_test_light_floor(W, H, HALF, floor_z, 10.0, RHO, model);
    assert_non_null(s);
    return s;
}

/* The floor point seen at the centre of pixel (x, y). */
static void floor_point(int x, int y, double *px, double *py) {
    *px = -HALF + (x + 0.5) * (2 * HALF / W);
    *py = -HALF + (y + 0.5) * (2 * HALF / H);
}

static cj_render_image *draw(const cj_scene *s, int trace, int spp) {
    cj_render_options o = cj_render_options_defaults();
    o.spp = spp;
    cj_render_image *img = NULL;
    cj_status st = trace ? cj_render_trace(s, &o, 0, NULL, &img, NULL)
                         : cj_render_raster(s, &o, 0, NULL, &img, NULL);
    if (st) printf("render failed: %s\n", cj_last_error());
    assert_int_equal(st, CJ_OK);
    return img;
}

static const double LP[3] = {0.4, -0.3, 1.5}, LI = 2.0; /* point light: position, intensity */
static const double ED = 0.5, TD = 0.6;                 /* directional: irradiance, angle */

static void add_lamps(cj_scene *s, double height) {
    cj_light p = cj_light_defaults(CJ_LIGHT_POINT);
    p.position = cj_v3(LP[0], LP[1], height);
    p.intensity = LI;
    p.casts_shadows = 0;
    assert_int_equal(cj_scene_add_light(s, &p, NULL), CJ_OK);
    cj_light d = cj_light_defaults(CJ_LIGHT_DIRECTIONAL);
    d.direction = cj_v3(sin(TD), 0, -cos(TD));
    d.intensity = ED;
    d.casts_shadows = 0;
    assert_int_equal(cj_scene_add_light(s, &d, NULL), CJ_OK);
}

static double lamps_oracle(double x, double y, double height) {
    double dx = LP[0] - x, dy = LP[1] - y, r = sqrt(dx * dx + dy * dy + height * height);
    return RHO / PI * (LI * height / (r * r * r) + ED * cos(TD));
}

static void test_point_and_directional(void **state) {
    (void)state;
    double worst[2] = {0, 0};
    for (int trace = 0; trace < 2; ++trace) {
        cj_scene *s = floor_scene(CJ_LIGHT_RADIOMETRIC, 0.0);
        add_lamps(s, LP[2]);
        cj_render_image *img = draw(s, trace, 1);
        for (int y = 0; y < H; ++y)
            for (int x = 0; x < W; ++x) {
                double fx, fy;
                floor_point(x, y, &fx, &fy);
                double ref = lamps_oracle(fx, fy, LP[2]);
                for (int k = 0; k < 3; ++k) {
                    double e = fabs(img->rgba[4 * ((size_t)y * W + x) + k] - ref) / ref;
                    if (e > worst[trace]) worst[trace] = e;
                }
            }
        cj_render_image_destroy(img);
        cj_scene_destroy(s);
    }
    printf("point (I %g at height %g) + directional (E %g at %g rad): worst relative error "
           "render %.2e (tol 1e-5), trace %.2e (tol 1e-6: the image is float)\n",
           LI, LP[2], ED, TD, worst[0], worst[1]);
    assert_true(worst[0] <= 1e-5);
    assert_true(worst[1] <= 1e-6);

    /* twice as high: the point light's part under it falls to a quarter */
    for (int trace = 0; trace < 2; ++trace) {
        double v[2];
        for (int k = 0; k < 2; ++k) {
            cj_scene *s = floor_scene(CJ_LIGHT_RADIOMETRIC, 0.0);
            cj_light p = cj_light_defaults(CJ_LIGHT_POINT);
            p.position = cj_v3(0, 0, k ? 2.0 : 1.0);
            p.intensity = LI;
            assert_int_equal(cj_scene_add_light(s, &p, NULL), CJ_OK);
            cj_render_image *img = draw(s, trace, 1);
            /* the four pixels around the centre, at (±δ, ±δ), δ = half a pixel */
            double sum = 0.0;
            for (int y = H / 2 - 1; y <= H / 2; ++y)
                for (int x = W / 2 - 1; x <= W / 2; ++x) sum += img->rgba[4 * (y * W + x)];
            v[k] = sum / 4;
            cj_render_image_destroy(img);
            cj_scene_destroy(s);
        }
        double d = 0.5 * 2 * HALF / W, r1 = sqrt(1 + 2 * d * d), r2 = sqrt(4 + 2 * d * d);
        double expect = (2.0 / (r2 * r2 * r2)) / (1.0 / (r1 * r1 * r1));
        printf("%s: radiance at height 2 / at height 1 = %.6f (closed form %.6f, ~1/4)\n",
               trace ? "trace" : "render", v[1] / v[0], expect);
        assert_true(fabs(v[1] / v[0] - expect) < 1e-5);
    }
}

/* Form factor from a differential area to a parallel rectangle a × b at height h with one
 * corner straight above it. */
static double ff_corner(double a, double b, double h) {
    double X = a / h, Y = b / h, sx = sqrt(1 + X * X), sy = sqrt(1 + Y * Y);
    return (X / sx * atan(Y / sx) + Y / sy * atan(X / sy)) / (2 * PI);
}

static double rect_ff(double px, double py, const double R[4], double h) {
    /* F(rect) = Σ over the corners with signs: F(x1,y1) − F(x0,y1) − F(x1,y0) + F(x0,y0) with
     * F(x, y) the form factor of the rectangle spanned by the point's foot and corner (x, y),
     * signed by the quadrant */
    double xs[2] = {R[0] - px, R[1] - px}, ys[2] = {R[2] - py, R[3] - py}, f = 0.0;
    for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 2; ++j) {
            double sgn = ((i == 1) == (j == 1)) ? 1.0 : -1.0;
            double sx = xs[i] < 0 ? -1.0 : 1.0, sy = ys[j] < 0 ? -1.0 : 1.0;
            f += sgn * sx * sy * ff_corner(fabs(xs[i]), fabs(ys[j]), h);
        }
    return f;
}

static const double RECT[4] = {-0.7, 0.5, -0.4, 0.8}; /* x0, x1, y0, y1 */
static const double RH = 0.8, LE = 3.0;               /* height, radiance */

static void add_emitter(cj_scene *s, int facing_down) {
    cj_light a = cj_light_defaults(CJ_LIGHT_AREA);
    a.intensity = LE;
    a.casts_shadows = 0;
    a.position = cj_v3(RECT[0], RECT[2], RH);
    cj_vec3 eu = cj_v3(RECT[1] - RECT[0], 0, 0), ev = cj_v3(0, RECT[3] - RECT[2], 0);
    /* normal eu × ev = +z; swapped, −z: facing the floor */
    a.edge_u = facing_down ? ev : eu;
    a.edge_v = facing_down ? eu : ev;
    assert_int_equal(cj_scene_add_light(s, &a, NULL), CJ_OK);
}

static void test_rectangle_emitter(void **state) {
    (void)state;
    double peak = 0.0;
    double *ref = malloc(sizeof(double) * W * H);
    assert_non_null(ref);
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            double fx, fy;
            floor_point(x, y, &fx, &fy);
            ref[y * W + x] = RHO / PI * PI * LE * rect_ff(fx, fy, RECT, RH);
            if (ref[y * W + x] > peak) peak = ref[y * W + x];
        }
    /* the oracle itself: an infinite emitter fills the hemisphere (F = 1), and at one point
     * the form factor matches a 2000 × 2000 midpoint sum of cos θ cos θ′ / (π r²) dA */
    assert_true(fabs(4 * ff_corner(1e9, 1e9, 1.0) - 1.0) < 1e-8);
    {
        const double qx = 0.9, qy = -0.6;
        const int N = 2000;
        double du = (RECT[1] - RECT[0]) / N, dv = (RECT[3] - RECT[2]) / N, sum = 0.0;
        for (int i = 0; i < N; ++i)
            for (int j = 0; j < N; ++j) {
                double dx = RECT[0] + (i + 0.5) * du - qx, dy = RECT[2] + (j + 0.5) * dv - qy;
                double r2 = dx * dx + dy * dy + RH * RH;
                sum += RH * RH / (PI * r2 * r2) * du * dv;
            }
        double f = rect_ff(qx, qy, RECT, RH);
        printf("oracle: form factor at (%g, %g) %.8f, midpoint sum %.8f\n", qx, qy, f, sum);
        assert_true(fabs(f - sum) < 1e-6 * f);
    }

    double worst_r = 0, worst_t = 0, sum_t = 0, sum_ref = 0;
    for (int trace = 0; trace < 2; ++trace) {
        cj_scene *s = floor_scene(CJ_LIGHT_RADIOMETRIC, 0.0);
        add_emitter(s, 1);
        cj_render_image *img = draw(s, trace, trace ? SPP : 1);
        for (int i = 0; i < W * H; ++i) {
            double e = fabs(img->rgba[4 * i] - ref[i]) / peak;
            if (trace) {
                sum_t += img->rgba[4 * i];
                sum_ref += ref[i];
                if (e > worst_t) worst_t = e;
            } else if (e > worst_r) {
                worst_r = e;
            }
        }
        cj_render_image_destroy(img);
        cj_scene_destroy(s);
    }
    double bias = fabs(sum_t - sum_ref) / sum_ref;
    printf("rectangle emitter (L_e %g, %gx%g at height %g), peak radiance %.5f: render (exact "
           "polygon irradiance) worst %.2e of the peak (tol 1e-5); trace (%d area samples per "
           "pixel) worst %.2e of the peak (tol %.0e), mean off by %.2e (tol %.0e)\n",
           LE, RECT[1] - RECT[0], RECT[3] - RECT[2], RH, peak, worst_r, SPP, worst_t, NOISE_TOL,
           bias, BIAS_TOL);
    assert_true(worst_r <= 1e-5);
    assert_true(worst_t <= NOISE_TOL);
    assert_true(bias <= BIAS_TOL);

    /* one-sided: the emitter facing up leaves the floor below it dark in both renderers; the
     * camera above sees its emitting side, drawn with its radiance L_e by both */
    for (int trace = 0; trace < 2; ++trace) {
        cj_scene *s = floor_scene(CJ_LIGHT_RADIOMETRIC, 0.0);
        add_emitter(s, 0);
        cj_render_image *img = draw(s, trace, trace ? 4 : 1);
        double mx = 0, pix = 2 * HALF / W;
        int seen = 0, inside = 0;
        for (int y = 0; y < H; ++y)
            for (int x = 0; x < W; ++x) {
                double fx, fy;
                floor_point(x, y, &fx, &fy);
                const float v = img->rgba[4 * (y * W + x)];
                if (fx > RECT[0] + pix && fx < RECT[1] - pix && fy > RECT[2] + pix &&
                    fy < RECT[3] - pix) {
                    inside++;
                    seen += v == (float)LE;
                } else if (fx < RECT[0] - pix || fx > RECT[1] + pix || fy < RECT[2] - pix ||
                           fy > RECT[3] + pix) {
                    mx = fmax(mx, v);
                }
            }
        printf("%s: emitter facing away, brightest floor pixel outside its outline %g; the "
               "emitter itself L_e = %g at %d of the %d pixels inside it\n",
               trace ? "trace" : "render", mx, LE, seen, inside);
        assert_true(mx == 0.0);
        assert_int_equal(seen, inside);
        cj_render_image_destroy(img);
        cj_scene_destroy(s);
    }
    free(ref);
}

static void test_legacy_unchanged(void **state) {
    (void)state;
    for (int trace = 0; trace < 2; ++trace) {
        cj_scene *s = floor_scene(CJ_LIGHT_LEGACY, 0.0);
        cj_light p = cj_light_defaults(CJ_LIGHT_POINT);
        p.position = cj_v3(LP[0], LP[1], LP[2]);
        p.intensity = LI;
        p.casts_shadows = 0;
        assert_int_equal(cj_scene_add_light(s, &p, NULL), CJ_OK);
        cj_render_image *img = draw(s, trace, 1);
        double worst = 0;
        for (int y = 0; y < H; ++y)
            for (int x = 0; x < W; ++x) {
                double fx, fy;
                floor_point(x, y, &fx, &fy);
                double dx = LP[0] - fx, dy = LP[1] - fy;
                double ref = RHO * LI * LP[2] / sqrt(dx * dx + dy * dy + LP[2] * LP[2]);
                double e = fabs(img->rgba[4 * ((size_t)y * W + x)] - ref) / ref;
                if (e > worst) worst = e;
            }
        printf("legacy %s: radiance ρ I cos θ (no falloff), worst relative error %.2e\n",
               trace ? "trace" : "render", worst);
        assert_true(worst <= 1e-5);
        cj_render_image_destroy(img);
        cj_scene_destroy(s);
    }
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_point_and_directional),
        cmocka_unit_test(test_rectangle_emitter),
        cmocka_unit_test(test_legacy_unchanged),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

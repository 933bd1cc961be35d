/* Emissive surfaces as lights in the path tracer (docs/light.md): a material with `emission` on
 * a planar patch or a triangle mesh is sampled for next-event estimation (its triangles picked
 * by area, MIS against BRDF samples that meet it), not only found by chance.
 *
 * Scene: a Lambertian floor z = 0 (ρ = 0.6) seen from above, and over it a rectangle
 * [x0, x1] × [y0, y1] at height h parallel to it whose material emits radiance L_e (and
 * reflects nothing). The floor's radiance is ρ L_e F with F the form factor of the rectangle
 * from the floor point: Σ with signs over the four rectangles with a corner above the point of
 * F_c(a, b) = (1/2π)[X/√(1+X²) atan(Y/√(1+X²)) + Y/√(1+Y²) atan(X/√(1+Y²))], X = a/h, Y = b/h
 * (checked here against a midpoint sum of cos θ cos θ′ / (π r²) over the rectangle).
 *
 * Checked, at equal samples per pixel, with the emitter as a planar patch (identity transform)
 * and as a two-triangle mesh placed by a node translation:
 *  - sampled as a light: the mean over the floor within BIAS_TOL of the oracle's, the RMS pixel
 *    error within RMS_TOL of the peak;
 *  - found by chance (cj_trace_options.emission_by_chance): also unbiased, and its RMS error at
 *    least GAIN times larger (the variance drop, printed);
 *  - the emitter itself seen by camera rays: L_e exactly. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "casteljau/mesh.h"
#include "casteljau/render.h"
#include "casteljau/scene.h"
#include "casteljau/trace.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define W        48
#define H        48
#define SPP      64
#define BIAS_TOL 5e-3
#define RMS_TOL  0.03
#define GAIN     2.0

static const double PI = 3.14159265358979323846;
static const double RHO = 0.6, HALF = 2.0, LE = 3.0, EH = 0.8;
static const double RECT[4] = {-0.7, 0.5, -0.4, 0.8}; /* x0, x1, y0, y1 */

static double ff_corner(double a, double b, double h) {
    const double X = a / h, Y = b / h, sx = sqrt(1 + X * X), sy = sqrt(1 + Y * Y);
    return (X / sx * atan(Y / sx) + Y / sy * atan(X / sy)) / (2 * PI);
}

static double rect_ff(double px, double py) {
    const double xs[2] = {RECT[0] - px, RECT[1] - px}, ys[2] = {RECT[2] - py, RECT[3] - py};
    double f = 0.0;
    for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 2; ++j) {
            const double sgn = (i == j) ? 1.0 : -1.0;
            const double sx = xs[i] < 0 ? -1.0 : 1.0, sy = ys[j] < 0 ? -1.0 : 1.0;
            f += sgn * sx * sy * ff_corner(fabs(xs[i]), fabs(ys[j]), EH);
        }
    return f;
}

static cj_scene *scene_with_emitter(int as_mesh) {
    cj_scene *s;
    assert_int_equal(cj_scene_create(NULL, &s), CJ_OK);
    cj_camera cam = cj_camera_defaults();
    cam.projection = CJ_PROJ_ORTHOGRAPHIC;
    cam.ortho_height = 2 * HALF;
    cam.eye = cj_v3(0, 0, 10);
    cam.gaze = cj_v3(0, 0, -1);
    cam.up = cj_v3(0, 1, 0);
    assert_int_equal(cj_scene_set_camera(s, &cam), CJ_OK);
    cj_scene_settings st = cj_scene_settings_defaults();
    st.width = W;
    st.height = H;
    st.light_model = CJ_LIGHT_RADIOMETRIC;
    st.max_depth = 4;
    assert_int_equal(cj_scene_set_settings(s, &st), CJ_OK);
    cj_material fm = cj_material_defaults();
    fm.color = cj_rgb_make(RHO, RHO, RHO);
    fm.ka = fm.ks = 0.0;
    fm.kd = 1.0;
    fm.two_sided = 1;
    cj_material em = cj_material_defaults();
    em.color = cj_rgb_make(0, 0, 0);
    em.ka = em.kd = em.ks = 0.0;
    em.emission = cj_rgb_make(LE, LE, LE);
    em.two_sided = 1;
    int fmi, emi, gi;
    assert_int_equal(cj_scene_add_material(s, &fm, &fmi), CJ_OK);
    assert_int_equal(cj_scene_add_material(s, &em, &emi), CJ_OK);
    cj_geometry g;
    memset(&g, 0, sizeof g);
    g.kind = CJ_GEOM_PLANAR;
    assert_int_equal(cj_planar_patch_init(&g.u.planar, cj_v3(-HALF, -HALF, 0),
                                          cj_v3(2 * HALF, 0, 0), cj_v3(0, 2 * HALF, 0)),
                     CJ_OK);
    assert_int_equal(cj_scene_add_geometry(s, &g, &gi), CJ_OK);
    cj_node n = cj_node_defaults(gi, fmi);
    assert_int_equal(cj_scene_add_node(s, &n, NULL), CJ_OK);
    memset(&g, 0, sizeof g);
    const double w = RECT[1] - RECT[0], d = RECT[3] - RECT[2];
    if (as_mesh) { /* object space at the origin, placed by the node */
        g.kind = CJ_GEOM_MESH;
        assert_int_equal(cj_mesh_create(NULL, &g.u.mesh), CJ_OK);
        const double v[4][3] = {{0, 0, 0}, {w, 0, 0}, {w, d, 0}, {0, d, 0}}, nz[3] = {0, 0, 1};
        for (int k = 0; k < 4; ++k)
            assert_int_equal(cj_mesh_add_vertex(g.u.mesh, v[k], nz, NULL, NULL), CJ_OK);
        assert_int_equal(cj_mesh_add_triangle(g.u.mesh, 0, 1, 2, 0), CJ_OK);
        assert_int_equal(cj_mesh_add_triangle(g.u.mesh, 0, 2, 3, 0), CJ_OK);
    } else {
        g.kind = CJ_GEOM_PLANAR;
        assert_int_equal(cj_planar_patch_init(&g.u.planar, cj_v3(RECT[0], RECT[2], EH),
                                              cj_v3(w, 0, 0), cj_v3(0, d, 0)),
                         CJ_OK);
    }
    assert_int_equal(cj_scene_add_geometry(s, &g, &gi), CJ_OK);
    if (as_mesh) cj_mesh_destroy(g.u.mesh); /* the scene keeps a deep copy */
    n = cj_node_defaults(gi, emi);
    if (as_mesh) n.local.translate = cj_v3(RECT[0], RECT[2], EH);
    assert_int_equal(cj_scene_add_node(s, &n, NULL), CJ_OK);
    return s;
}

typedef struct errs {
    double rms, bias;
} errs;

static errs measure(const cj_scene *s, int by_chance, int *seen, int *inside) {
    cj_render_options o = cj_render_options_defaults();
    o.spp = SPP;
    cj_trace_options to;
    memset(&to, 0, sizeof to);
    to.integrator = CJ_INTEGRATOR_PATH;
    to.emission_by_chance = by_chance;
    cj_render_image *img = NULL;
    assert_int_equal(cj_render_trace_with_options(s, &o, &to, 0, NULL, &img, NULL), CJ_OK);
    double peak = 0, sum = 0, sum_ref = 0, se = 0;
    int n = 0;
    *seen = *inside = 0;
    const double pix = 2 * HALF / W;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            const double fx = -HALF + (x + 0.5) * pix, fy = -HALF + (y + 0.5) * pix;
            const float v = img->rgba[4 * (y * W + x)];
            if (fx > RECT[0] - pix && fx < RECT[1] + pix && fy > RECT[2] - pix &&
                fy < RECT[3] + pix) { /* the emitter's outline, seen from above */
                if (fx > RECT[0] + pix && fx < RECT[1] - pix && fy > RECT[2] + pix &&
                    fy < RECT[3] - pix) {
                    ++*inside;
                    *seen += v == (float)LE;
                }
                continue;
            }
            double ref = 0.0; /* the pixel's mean (the image's box filter): 4 × 4 midpoints */
            for (int i = 0; i < 16; ++i)
                ref += RHO * LE *
                       rect_ff(fx + ((i % 4) + 0.5 - 2.0) * pix / 4,
                               fy + ((i / 4) + 0.5 - 2.0) * pix / 4) /
                       16.0;
            peak = fmax(peak, ref);
            sum += v;
            sum_ref += ref;
            se += (v - ref) * (v - ref);
            n++;
        }
    cj_render_image_destroy(img);
    errs e = {sqrt(se / n) / peak, (sum - sum_ref) / sum_ref};
    return e;
}

static void test_oracle(void **state) {
    (void)state;
    const double qx = 1.1, qy = -0.9;
    const int N = 1000;
    const double du = (RECT[1] - RECT[0]) / N, dv = (RECT[3] - RECT[2]) / N;
    double sum = 0.0;
    for (int i = 0; i < N; ++i)
        for (int j = 0; j < N; ++j) {
            const double dx = RECT[0] + (i + 0.5) * du - qx, dy = RECT[2] + (j + 0.5) * dv - qy;
            const double r2 = dx * dx + dy * dy + EH * EH;
            sum += EH * EH / (PI * r2 * r2) * du * dv;
        }
    const double f = rect_ff(qx, qy);
    printf("oracle: form factor at (%g, %g) %.8f, midpoint sum %.8f\n", qx, qy, f, sum);
    assert_true(fabs(f - sum) < 1e-5 * f);
}

static void test_emissive_nee(void **state) {
    (void)state;
    static const char *const what[2] = {"planar patch", "mesh (2 triangles, translated)"};
    for (int as_mesh = 0; as_mesh < 2; ++as_mesh) {
        cj_scene *s = scene_with_emitter(as_mesh);
        int seen, inside;
        const errs nee = measure(s, 0, &seen, &inside);
        printf("%s, %d spp: sampled as a light: RMS %.4f of the peak, mean off by %.2e; the "
               "emitter L_e at %d of %d pixels inside it\n",
               what[as_mesh], SPP, nee.rms, nee.bias, seen, inside);
        assert_int_equal(seen, inside);
        const errs chance = measure(s, 1, &seen, &inside);
        printf("%s, %d spp: found by chance: RMS %.4f of the peak, mean off by %.2e; RMS ratio "
               "%.2f (variance ratio %.1f)\n",
               what[as_mesh], SPP, chance.rms, chance.bias, chance.rms / nee.rms,
               (chance.rms / nee.rms) * (chance.rms / nee.rms));
        assert_true(fabs(nee.bias) <= BIAS_TOL);
        assert_true(nee.rms <= RMS_TOL);
        assert_true(fabs(chance.bias) <= 4 * BIAS_TOL);
        assert_true(chance.rms >= GAIN * nee.rms);
        cj_scene_destroy(s);
    }
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_oracle),
        cmocka_unit_test(test_emissive_nee),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

/* Motion blur (docs/light.md; cj_anim_sample_motion, cj_renderer_set_motion) against its closed
 * form. A lit diffuse square (radiance 0.8 where it is, black background, orthographic camera,
 * one world unit per pixel) slides along x at constant speed v while the shutter is open. The
 * box shutter averages the pixel's coverage over time; for the column [a, a + 1] and the square
 * [L(t), R(t)] the coverage is c(R − a) − c(L − a) with c(u) = clamp(u, 0, 1), and its mean
 * over an edge sweeping [e0, e1] is (C(e1 − a) − C(e0 − a)) / (e1 − e0), C the integral of c:
 * 0 below 0, u²/2 on [0, 1], u − 1/2 above: linear ramps of coverage at both edges, each as wide
 * as the distance travelled. Each camera sample is a Bernoulli draw of probability p (the mean
 * coverage) times 0.8, so a column mean over n samples has standard error
 * 0.8 √(p(1 − p)/n) at most (stratification only lowers it): every column must be within 4.5 of
 * them. The animation goes through the document reader ("shutter", "shutter_poses"), the
 * poses through cj_anim_sample_motion, the render through a renderer. Also: bit-identical for
 * 1 and 3 threads, a static scene with a motion is the image without one, the stage report,
 * and the refusals. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "casteljau/anim_json.h"
#include "casteljau/renderer.h"
#include "casteljau/scene_json.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define W 64
#define H 16

/* The square spans x in [-16, 0] + translate, y in [-4, 4]; the image x in [-32, 32]. */
static const char SCENE[] =
    "{\"camera\": {\"eye\": [0, 0, 5], \"gaze\": [0, 0, -1], \"up\": [0, 1, 0],\n"
    "  \"near\": -0.1, \"far\": -20, \"projection\": \"orthographic\", \"ortho_height\": 16},\n"
    " \"settings\": {\"width\": 64, \"height\": 16, \"spp\": 1024, \"seed\": 3},\n"
    " \"lights\": [{\"type\": \"directional\", \"direction\": [0, 0, -1]}],\n"
    " \"materials\": [{\"name\": \"m\", \"color\": [0.8, 0.8, 0.8], \"ka\": 0, \"kd\": 1,\n"
    "   \"ks\": 0}],\n"
    " \"objects\": [{\"name\": \"sq\", \"material\": \"m\", \"geometry\": {\"type\": \"planar\",\n"
    "   \"origin\": [-16, -4, 0], \"edge_u\": [16, 0, 0], \"edge_v\": [0, 8, 0]}}]}\n";

/* 10 units per second, frame 5 at t = 5 s (translate 0); shutter [-0.5, 0.5] frames at 1 fps:
 * translate from -5 to 5 while open. */
static const char DOC[] =
    "{\"fps\": 1, \"frames\": [5, 5], \"shutter\": [-0.5, 0.5], \"shutter_poses\": 4,\n"
    " \"channels\": [{\"target\": \"nodes[\\\"sq\\\"].translate\", \"type\": \"vector\",\n"
    "   \"interpolation\": \"linear\", \"times\": [0, 10], \"values\": [[-50, 0, 0], [50, 0, "
    "0]]}]}\n";

static double C(double u) {
    return u <= 0.0 ? 0.0 : (u <= 1.0 ? 0.5 * u * u : u - 0.5);
}

/* The mean coverage of the column [a, a + 1] by [L0 + s, R0 + s], s uniform in [s0, s1]. */
static double mean_coverage(double a, double L0, double R0, double s0, double s1) {
    const double r = (C(R0 + s1 - a) - C(R0 + s0 - a)) / (s1 - s0);
    const double l = (C(L0 + s1 - a) - C(L0 + s0 - a)) / (s1 - s0);
    return r - l;
}

typedef struct fixture {
    cj_scene *scene;
    cj_anim_doc *doc;
    cj_xform3 *world;
    cj_motion motion;
} fixture;

static void load(fixture *f, const char *doc_text) {
    memset(f, 0, sizeof *f);
    assert_int_equal(cj_scene_parse_json(SCENE, "motion_scene.json", NULL, NULL, &f->scene), CJ_OK);
    assert_int_equal(cj_anim_doc_parse(doc_text, "motion.json", "", &f->doc), CJ_OK);
    assert_int_equal(cj_anim_doc_attach(f->doc, f->scene), CJ_OK);
    assert_int_equal(cj_anim_doc_frame(f->doc, f->scene, 5, NULL), CJ_OK);
    const size_t n = cj_scene_node_count(f->scene);
    f->world = malloc((size_t)f->doc->shutter_poses * n * sizeof *f->world);
    assert_non_null(f->world);
    const double t = 5.0 / f->doc->fps;
    assert_int_equal(cj_anim_sample_motion(
                         f->scene, f->doc->anim, t + f->doc->shutter[0] / f->doc->fps,
                         t + f->doc->shutter[1] / f->doc->fps, f->doc->shutter_poses, f->world),
                     CJ_OK);
    assert_int_equal(cj_anim_pose(f->scene, f->doc->anim, t, NULL), CJ_OK);
    f->motion.poses = f->doc->shutter_poses;
    f->motion.node_count = n;
    f->motion.world = f->world;
}

static void unload(fixture *f) {
    free(f->world);
    cj_anim_doc_destroy(f->doc);
    cj_scene_destroy(f->scene);
}

static cj_render_image *draw(const fixture *f, const cj_motion *m, int spp, int threads,
                             cj_stage_report *rep) {
    cj_renderer_options o = cj_renderer_options_defaults();
    o.render.spp = spp;
    o.render.threads = threads;
    cj_renderer *r = NULL;
    assert_int_equal(cj_renderer_create(&o, NULL, &r), CJ_OK);
    assert_int_equal(cj_renderer_set_motion(r, m), CJ_OK);
    cj_render_image *img = NULL;
    assert_int_equal(cj_renderer_draw(r, f->scene, CJ_BACKEND_TRACE, 0, &img, rep), CJ_OK);
    cj_renderer_destroy(r);
    return img;
}

static void test_linear_ramp(void **state) {
    (void)state;
    fixture f;
    load(&f, DOC);
    cj_stage_report rep;
    cj_render_image *img = draw(&f, &f.motion, 1024, 0, &rep);
    const cj_stage *st = cj_stage_report_find(&rep, "motion_blur");
    assert_non_null(st);
    assert_true(st->ran);
    printf("stage motion_blur: %s\n", st->why);
    const int rows0 = 5, rows1 = 11; /* world y in [-3, 3]: inside the square */
    const double n = 1024.0 * (rows1 - rows0);
    double worst_z = 0.0, worst_dev = 0.0, chi2 = 0.0, instant_dev = 0.0;
    int ramp_px = 0;
    for (int x = 0; x < W; ++x) {
        double sum = 0.0;
        for (int y = rows0; y < rows1; ++y) sum += img->rgba[4 * (y * W + x)];
        const double mean = sum / (rows1 - rows0);
        const double a = x - 32.0, p = mean_coverage(a, -16.0, 0.0, -5.0, 5.0);
        const double se = 0.8 * sqrt(p * (1.0 - p) / n), dev = fabs(mean - 0.8 * p);
        if (p > 0.0 && p < 1.0) ramp_px++;
        if (se > 0.0) {
            worst_z = fmax(worst_z, dev / se);
            chi2 += (dev / se) * (dev / se);
        } else {
            assert_true(dev < 1e-6); /* covered or empty for the whole shutter: exact */
        }
        worst_dev = fmax(worst_dev, dev);
        /* the sharp square of the frame's instant, for contrast */
        const double inst = 0.8 * mean_coverage(a, -16.0, 0.0, -1e-9, 1e-9);
        instant_dev = fmax(instant_dev, fabs(mean - inst));
        if (x % 4 == 0 || (x >= 10 && x <= 38 && x % 2 == 0))
            printf("column %2d: mean %.5f  exact %.5f  (4.5 s.e. %.5f)\n", x, mean, 0.8 * p,
                   4.5 * se);
    }
    printf("%d columns on the ramps; worst |mean - exact| %.5f = %.2f s.e. (bound 4.5); "
           "sum of squared z %.1f over %d; the unblurred square is off by up to %.3f\n",
           ramp_px, worst_dev, worst_z, chi2, ramp_px, instant_dev);
    assert_int_equal(ramp_px, 20); /* two ramps, each 10 px wide */
    assert_true(worst_z < 4.5);
    assert_true(instant_dev > 0.3); /* the test sees the blur */
    cj_render_image_destroy(img);
    unload(&f);
}

static void test_threads_and_static(void **state) {
    (void)state;
    fixture f;
    load(&f, DOC);
    cj_render_image *a = draw(&f, &f.motion, 16, 1, NULL), *b = draw(&f, &f.motion, 16, 3, NULL);
    assert_memory_equal(a->rgba, b->rgba, sizeof(float) * 4 * W * H);
    printf("motion blur at 16 spp: bit-identical for 1 and 3 threads\n");
    cj_render_image_destroy(a);
    cj_render_image_destroy(b);
    /* every pose equal: the object is static, the image exactly the unblurred one */
    for (int k = 1; k < f.motion.poses; ++k) f.world[k] = f.world[0];
    cj_stage_report rep;
    a = draw(&f, &f.motion, 16, 0, &rep);
    b = draw(&f, NULL, 16, 0, NULL);
    assert_memory_equal(a->rgba, b->rgba, sizeof(float) * 4 * W * H);
    const cj_stage *st = cj_stage_report_find(&rep, "motion_blur");
    assert_non_null(st);
    assert_false(st->ran);
    printf("a motion whose poses are equal: the unblurred image bit for bit (%s)\n", st->why);
    cj_render_image_destroy(a);
    cj_render_image_destroy(b);
    unload(&f);
}

static void test_refusals(void **state) {
    (void)state;
    fixture f;
    load(&f, DOC);
    cj_renderer *r = NULL;
    cj_renderer_options o = cj_renderer_options_defaults();
    o.render.spp = 4; /* the rasterizer's 1, 4 or 16 */
    assert_int_equal(cj_renderer_create(&o, NULL, &r), CJ_OK);
    cj_motion m = f.motion;
    m.poses = 1;
    assert_int_equal(cj_renderer_set_motion(r, &m), CJ_ERR_RANGE);
    printf("1 pose: %s\n", cj_last_error());
    m = f.motion;
    f.world[1].m[0][3] = NAN;
    assert_int_equal(cj_renderer_set_motion(r, &m), CJ_ERR_NONFINITE);
    printf("NaN: %s\n", cj_last_error());
    f.world[1].m[0][3] = 0.0;
    m.node_count = 2; /* the scene has 1 node */
    m.poses = 2;
    assert_int_equal(cj_renderer_set_motion(r, &m), CJ_OK);
    cj_render_image *img = NULL;
    assert_int_equal(cj_renderer_draw(r, f.scene, CJ_BACKEND_TRACE, 0, &img, NULL),
                     CJ_ERR_DIMENSION);
    printf("node count: %s\n", cj_last_error());
    assert_null(img);
    /* the rasterizer ignores the motion: the frame's instant, the square's edge at x = 0 */
    assert_int_equal(cj_renderer_draw(r, f.scene, CJ_BACKEND_RASTER, 0, &img, NULL), CJ_OK);
    assert_true(img->rgba[4 * (8 * W + 31)] > 0.79f && img->rgba[4 * (8 * W + 32)] == 0.0f);
    printf("the rasterizer draws the frame's instant (sharp edge at x = 0)\n");
    cj_render_image_destroy(img);
    cj_renderer_destroy(r);
    unload(&f);
    static const struct {
        const char *doc, *what;
    } bad[] = {{"{\"shutter\": [0.5, 0.2]}", "closing before opening"},
               {"{\"shutter\": [-2, 0.2]}", "open before -1"},
               {"{\"shutter\": [0, 1.5]}", "close after 1"},
               {"{\"shutter\": [0, 0.5], \"shutter_poses\": 1}", "1 pose"},
               {"{\"shutter\": [0, 0.5], \"shutter_poses\": 2.5}", "a fractional count"},
               {"{\"shutter\": [0]}", "one number"}};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; ++i) {
        cj_anim_doc *d = NULL;
        assert_int_not_equal(cj_anim_doc_parse(bad[i].doc, "bad.json", "", &d), CJ_OK);
        assert_null(d);
        printf("%s: %s\n", bad[i].what, cj_last_error());
    }
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_linear_ramp),
        cmocka_unit_test(test_threads_and_static),
        cmocka_unit_test(test_refusals),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

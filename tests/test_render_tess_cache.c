/* The renderer's tessellation cache (cj_render_options.cache) with incremental, per-patch
 * tessellation: the demo teapot under an orthographic camera (the object tolerance a frame needs
 * is then independent of the edits), then a seeded random sequence of control-point edits
 * (coincident copies moved together, as an editor does). After every edit the cached render is
 * bit-identical to a one-shot render of the edited scene without a cache, and the stage report
 * shows the work was incremental: patches_planned <= the patches edited, the rest reused. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "render_test_util.h"
#include "rng.h"

static double stage_value(const cj_stage_report *r, const char *key) {
    const cj_stage *s = cj_stage_report_find(r, "tessellate_patches");
    assert_non_null(s);
    for (int i = 0; i < s->extra_count; ++i)
        if (!strcmp(s->extra[i].key, key)) return s->extra[i].value;
    fail_msg("tessellate_patches has no value %s", key);
    return 0.0;
}

static void test_edits_same_image(void **state) {
    (void)state;
    const uint64_t seed = cj_test_seed("test_render_tess_cache", 19);
    cj_rng rng;
    cj_rng_init(&rng, seed);
    cj_scene *s = NULL;
    assert_int_equal(cj_render_demo_scene(CJ_TEAPOT_PATH, NULL, &s), CJ_OK);
    cj_camera cam = *cj_scene_get_camera(s);
    cam.projection = CJ_PROJ_ORTHOGRAPHIC;
    cam.ortho_height = 7.0;
    assert_int_equal(cj_scene_set_camera(s, &cam), CJ_OK);
    cj_scene_node_mut(s, 0)->overlay.flags = 0;
    cj_geometry *g = cj_scene_geometry_mut(s, cj_scene_node(s, 0)->geometry);
    assert_int_equal(g->kind, CJ_GEOM_PATCHES);
    const size_t np = g->u.patches.count;
    cj_render_options o = cj_render_options_defaults();
    o.width = 160;
    o.height = 120;
    o.tol_px = 0.5;
    cj_render_options oc = o;
    assert_int_equal(cj_render_cache_create(NULL, &oc.cache), CJ_OK);
    cj_stage_report rep;
    cj_render_image_destroy(render(s, &oc, 0, &rep)); /* cold */
    assert_true(stage_value(&rep, "patches_planned") == (double)np);
    cj_render_image_destroy(render(s, &oc, 0, &rep)); /* warm: nothing redone */
    assert_true(stage_value(&rep, "patches_planned") == 0.0);
    assert_true(stage_value(&rep, "patches_built") == 0.0);
    assert_true(stage_value(&rep, "patches_reused") == (double)np);
    assert_true(stage_value(&rep, "cache_hits") == 1.0);
    const int edits = 24;
    double planned = 0.0, built = 0.0, reused = 0.0;
    for (int e = 0; e < edits; ++e) {
        const size_t q = (size_t)cj_rng_int(&rng, 0, (int)np - 1);
        const int i = cj_rng_int(&rng, 0, 15);
        const double d[3] = {cj_rng_range(&rng, -0.2, 0.2), cj_rng_range(&rng, -0.2, 0.2),
                             cj_rng_range(&rng, -0.2, 0.2)};
        double at[3];
        memcpy(at, g->u.patches.patches[q].pts + 3 * i, sizeof at);
        int touched = 0;
        for (size_t r = 0; r < np; ++r) {
            double *pts = (double *)g->u.patches.patches[r].pts;
            int hit = 0;
            for (int j = 0; j < 16; ++j)
                if (pts[3 * j] == at[0] && pts[3 * j + 1] == at[1] && pts[3 * j + 2] == at[2]) {
                    for (int k = 0; k < 3; ++k) pts[3 * j + k] = at[k] + d[k];
                    hit = 1;
                }
            touched += hit;
        }
        cj_render_image *cached = render(s, &oc, 0, &rep);
        cj_render_image *one_shot = render(s, &o, 0, NULL);
        if (!same_image(cached, one_shot))
            fail_msg("seed %llu edit %d: the cached render differs from the one-shot render",
                     (unsigned long long)seed, e);
        const double p = stage_value(&rep, "patches_planned");
        if (p > (double)touched)
            fail_msg("seed %llu edit %d: %g patches planned for %d edited",
                     (unsigned long long)seed, e, p, touched);
        if (e == edits - 1) dump(cached, "render_tess_cache_last_edit");
        planned += p;
        built += stage_value(&rep, "patches_built");
        reused += stage_value(&rep, "patches_reused");
        cj_render_image_destroy(cached);
        cj_render_image_destroy(one_shot);
    }
    printf("test_render_tess_cache: teapot, orthographic, %d random control-point edits: every "
           "cached render == the one-shot render bit for bit; per edit %.2f patches planned, %.2f "
           "built, %.2f reused of %zu (cold frame: all planned; warm frame: none)\n",
           edits, planned / edits, built / edits, reused / edits, np);
    cj_render_cache_destroy(oc.cache);
    cj_scene_destroy(s);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_edits_same_image),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

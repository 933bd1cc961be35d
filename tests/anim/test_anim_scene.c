/* Channels on scene paths: resolved once, posed in place (idempotent in t), control points
 * flagged for re-tessellation, the stage report, and every kind of bad path refused by name. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "casteljau/anim_scene.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

static cj_scene *build(void) {
    cj_scene *s = NULL;
    assert_int_equal(cj_scene_create(NULL, &s), CJ_OK);
    cj_light l = cj_light_defaults(CJ_LIGHT_POINT);
    int idx;
    assert_int_equal(cj_scene_add_light(s, &l, &idx), CJ_OK);
    cj_material m = cj_material_defaults();
    assert_int_equal(cj_scene_add_material(s, &m, &idx), CJ_OK);
    double pts[16 * 3];
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i) {
            pts[3 * (4 * j + i)] = i;
            pts[3 * (4 * j + i) + 1] = j;
            pts[3 * (4 * j + i) + 2] = (i == 1 || i == 2) && (j == 1 || j == 2) ? 1 : 0;
        }
    cj_patch patch = cj_patch_view(3, 3, pts, NULL);
    cj_geometry g;
    memset(&g, 0, sizeof g);
    g.kind = CJ_GEOM_PATCHES;
    g.u.patches.count = 1;
    g.u.patches.patches = &patch;
    assert_int_equal(cj_scene_add_geometry(s, &g, &idx), CJ_OK);
    memset(&g, 0, sizeof g);
    g.kind = CJ_GEOM_SPHERE;
    g.u.sphere.radius = 1;
    assert_int_equal(cj_scene_add_geometry(s, &g, &idx), CJ_OK);
    cj_node n;
    memset(&n, 0, sizeof n);
    n.name = "sheet";
    n.parent = -1;
    n.local = cj_transform_identity();
    n.geometry = 0;
    n.material = 0;
    n.visible = 1;
    assert_int_equal(cj_scene_add_node(s, &n, &idx), CJ_OK);
    n.name = "ball";
    n.geometry = 1;
    assert_int_equal(cj_scene_add_node(s, &n, &idx), CJ_OK);
    return s;
}

static void add(cj_anim *a, const char *path, cj_channel_kind kind, cj_interp interp, int dim,
                size_t n, const double *t, const double *v) {
    cj_channel_desc d = cj_channel_desc_make(kind, interp, dim);
    d.count = n;
    d.times = t;
    d.values = v;
    if (cj_anim_add(a, path, &d) != CJ_OK) fail_msg("add %s: %s", path, cj_last_error());
}

static void test_pose(void **state) {
    (void)state;
    cj_scene *s = build();
    cj_anim *a = NULL;
    assert_int_equal(cj_anim_create(NULL, &a), CJ_OK);
    const double t3[3] = {0, 1, 2};
    const double tr[9] = {0, 0, 0, 1, 2, 3, 2, 0, 0};
    add(a, "nodes[\"ball\"].translate", CJ_CHANNEL_VECTOR, CJ_INTERP_CATMULL_ROM, 3, 3, t3, tr);
    const double q[12] = {1, 0, 0, 0, cos(0.5), sin(0.5), 0, 0, cos(1), 0, sin(1), 0};
    add(a, "nodes[0].rotation", CJ_CHANNEL_QUATERNION, CJ_INTERP_SQUAD, 4, 3, t3, q);
    const double eye[9] = {0, 0, 5, 5, 0, 0, 0, 0, -5};
    add(a, "camera.eye", CJ_CHANNEL_VECTOR, CJ_INTERP_CATMULL_ROM, 3, 3, t3, eye);
    const double look[3] = {0, 0.5, 0};
    add(a, "camera.look_at", CJ_CHANNEL_VECTOR, CJ_INTERP_STEP, 3, 1, t3, look);
    const double inten[3] = {1, 3, 2};
    add(a, "lights[0].intensity", CJ_CHANNEL_VECTOR, CJ_INTERP_BEZIER_AUTO, 1, 3, t3, inten);
    const double kd[2] = {0.2, 0.9};
    add(a, "materials[0].kd", CJ_CHANNEL_VECTOR, CJ_INTERP_LINEAR, 1, 2, t3, kd);
    const double cp[6] = {1, 1, 1, 1, 1, 3};
    add(a, "nodes[0].patches[0].points[5]", CJ_CHANNEL_VECTOR, CJ_INTERP_LINEAR, 3, 2, t3 + 1, cp);
    assert_true(cj_anim_animates_control_points(a));
    assert_int_equal(cj_anim_pose(s, a, 0.5, NULL), CJ_ERR_ARGUMENT); /* not bound yet */
    assert_int_equal(cj_anim_bind(a, s), CJ_OK);
    double t0, t1;
    cj_anim_range(a, &t0, &t1);
    assert_true(t0 == 0 && t1 == 2);
    /* pose at 1.3, at 0.2, back at 1.3: the same scene (posing depends on t only) */
    cj_anim_pose_info info;
    assert_int_equal(cj_anim_pose(s, a, 1.3, &info), CJ_OK);
    assert_true(info.channels == 7 && info.camera && info.control_points);
    cj_node n1 = *cj_scene_node(s, 1), n0 = *cj_scene_node(s, 0);
    cj_camera c1 = *cj_scene_get_camera(s);
    const double *pts = cj_scene_geometry(s, 0)->u.patches.patches[0].pts;
    double p5[3];
    memcpy(p5, pts + 15, sizeof p5);
    assert_int_equal(cj_anim_pose(s, a, 0.2, &info), CJ_OK);
    assert_int_equal(cj_anim_pose(s, a, 1.3, &info), CJ_OK);
    assert_memory_equal(&n1.local, &cj_scene_node(s, 1)->local, sizeof n1.local);
    assert_memory_equal(&n0.local, &cj_scene_node(s, 0)->local, sizeof n0.local);
    assert_memory_equal(&c1, cj_scene_get_camera(s), sizeof c1);
    /* values are the channels' */
    double v[4];
    assert_int_equal(cj_channel_eval(cj_anim_channel(a, 0), 1.3, v), CJ_OK);
    assert_true(n1.local.translate.x == v[0] && n1.local.translate.y == v[1] &&
                n1.local.translate.z == v[2]);
    assert_int_equal(cj_channel_eval(cj_anim_channel(a, 1), 1.3, v), CJ_OK);
    assert_memory_equal(v, n0.local.rotation, sizeof(double) * 4);
    assert_int_equal(cj_channel_eval(cj_anim_channel(a, 2), 1.3, v), CJ_OK);
    assert_true(c1.eye.x == v[0] && c1.eye.z == v[2]);
    assert_true(fabs(c1.gaze.x - (0 - v[0])) < 1e-15 && fabs(c1.gaze.y - 0.5) < 1e-15);
    assert_true(cj_scene_material(s, 0)->kd == 0.9); /* past its last key: held */
    assert_true(p5[0] == 1 && p5[1] == 1 && fabs(p5[2] - (1 + 2 * 0.3)) < 1e-15);
    assert_true(cj_scene_light(s, 0)->intensity >= 1 && cj_scene_light(s, 0)->intensity <= 3);
    assert_int_equal(cj_scene_check(s), CJ_OK);
    printf("posed 7 channels (Catmull-Rom translate of a node by name, squad rotation, camera "
           "eye + look_at, auto-clamped light intensity, material kd, a patch control point): "
           "values = the channels', re-posing at t = 1.3 after t = 0.2 bit-identical, scene "
           "valid; control points flagged\n");
    /* the stage report */
    cj_stage_report r;
    cj_stage_report_init(&r, "animate");
    cj_anim_report_stages(&r, a, &info, NULL, NULL, NULL, NULL);
    assert_true(cj_stage_report_find(&r, "keyframes")->ran);
    assert_true(!cj_stage_report_find(&r, "spring_forces")->ran);
    assert_true(!cj_stage_report_find(&r, "particle_pass")->ran);
    assert_true(!cj_stage_report_find(&r, "collisions")->ran);
    assert_true(cj_stage_report_find(&r, "retessellate")->ran);
    printf("stage report: keyframes ran (%s); spring_forces left out (%s); retessellate ran (%s)\n",
           cj_stage_report_find(&r, "keyframes")->why,
           cj_stage_report_find(&r, "spring_forces")->why,
           cj_stage_report_find(&r, "retessellate")->why);
    /* with a particle system (colliders) and no control points */
    cj_anim *b = NULL;
    assert_int_equal(cj_anim_create(NULL, &b), CJ_OK);
    add(b, "nodes[1].scale", CJ_CHANNEL_VECTOR, CJ_INTERP_LINEAR, 3, 2, t3, tr);
    cj_particles_desc pd;
    memset(&pd, 0, sizeof pd);
    pd.capacity = 10;
    cj_plane_collider pl = {{0, 0, 1}, 0, 0};
    pd.plane_count = 1;
    pd.planes = &pl;
    cj_particles *p = NULL;
    assert_int_equal(cj_particles_create(&pd, NULL, &p), CJ_OK);
    cj_stage_report_init(&r, "animate");
    cj_anim_report_stages(&r, b, NULL, NULL, NULL, p, NULL);
    assert_true(cj_stage_report_find(&r, "particle_pass")->ran);
    assert_true(cj_stage_report_find(&r, "collisions")->ran);
    assert_true(!cj_stage_report_find(&r, "flocking")->ran);
    assert_true(!cj_stage_report_find(&r, "retessellate")->ran);
    cj_particles_destroy(p);
    cj_anim_destroy(b);
    cj_anim_destroy(a);
    cj_scene_destroy(s);
}

static void expect_bind_fail(const char *path, cj_channel_kind kind, int dim, cj_status want,
                             const char *needle) {
    cj_scene *s = build();
    cj_anim *a = NULL;
    assert_int_equal(cj_anim_create(NULL, &a), CJ_OK);
    const double t[1] = {0}, v[4] = {1, 0, 0, 0};
    add(a, "nodes[0].translate", CJ_CHANNEL_VECTOR, CJ_INTERP_LINEAR, 3, 1, t, v);
    add(a, path, kind, CJ_INTERP_LINEAR, dim, 1, t, v);
    const cj_status st = cj_anim_bind(a, s);
    if (st != want || !strstr(cj_last_error(), needle))
        fail_msg("%s: status %d '%s', expected %d mentioning '%s'", path, (int)st, cj_last_error(),
                 (int)want, needle);
    printf("  refused: %s\n", cj_last_error());
    cj_anim_destroy(a);
    cj_scene_destroy(s);
}

static void test_bad_paths(void **state) {
    (void)state;
    printf("bad channel targets:\n");
    expect_bind_fail("nodes[7].translate", CJ_CHANNEL_VECTOR, 3, CJ_ERR_ARGUMENT,
                     "channel 1: nodes[7]");
    expect_bind_fail("nodes[\"teapot\"].translate", CJ_CHANNEL_VECTOR, 3, CJ_ERR_ARGUMENT,
                     "no node has that name");
    expect_bind_fail("nodes[0].colour", CJ_CHANNEL_VECTOR, 3, CJ_ERR_ARGUMENT, "nodes[0].colour");
    expect_bind_fail("camera.zoom", CJ_CHANNEL_VECTOR, 1, CJ_ERR_ARGUMENT, "camera.zoom");
    expect_bind_fail("nodes[0].translate", CJ_CHANNEL_VECTOR, 1, CJ_ERR_DIMENSION, "dimension 3");
    expect_bind_fail("nodes[0].rotation", CJ_CHANNEL_VECTOR, 4, CJ_ERR_DIMENSION, "quaternion");
    expect_bind_fail("nodes[1].patches[0].points[0]", CJ_CHANNEL_VECTOR, 3, CJ_ERR_ARGUMENT,
                     "no patches");
    expect_bind_fail("nodes[0].patches[0].points[16]", CJ_CHANNEL_VECTOR, 3, CJ_ERR_ARGUMENT,
                     "index 16");
    expect_bind_fail("lights[0].intensity.x", CJ_CHANNEL_VECTOR, 1, CJ_ERR_ARGUMENT,
                     "unexpected text");
    /* keys out of order reach the caller with the path */
    cj_anim *a = NULL;
    assert_int_equal(cj_anim_create(NULL, &a), CJ_OK);
    const double t[2] = {1, 0.5}, v[2] = {0, 1};
    cj_channel_desc d = cj_channel_desc_make(CJ_CHANNEL_VECTOR, CJ_INTERP_LINEAR, 1);
    d.count = 2;
    d.times = t;
    d.values = v;
    assert_int_equal(cj_anim_add(a, "lights[0].intensity", &d), CJ_ERR_ARGUMENT);
    assert_non_null(strstr(cj_last_error(), "lights[0].intensity"));
    assert_non_null(strstr(cj_last_error(), "key 1"));
    printf("  refused: %s\n", cj_last_error());
    cj_anim_destroy(a);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_pose),
        cmocka_unit_test(test_bad_paths),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

/* Animation documents parsed from JSON: every channel kind reaches the channel it describes
 * (Euler in degrees, glTF [in, out] tangent pairs, Hermite tangents, paths at constant speed),
 * and errors carry file, line and JSON path. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "casteljau/anim_json.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

static const char DOC[] =
    "{\"fps\": 10, \"frames\": [2, 7],\n"
    " \"channels\": [\n"
    "  {\"target\": \"nodes[0].rotation\", \"type\": \"euler\", \"euler_order\": \"zyx\",\n"
    "   \"degrees\": true, \"times\": [0, 1], \"values\": [[0, 0, 0], [0, 0, 90]]},\n"
    "  {\"target\": \"lights[0].intensity\", \"interpolation\": \"gltf_cubic\",\n"
    "   \"times\": [0, 2], \"values\": [1, 3], \"tangents\": [[0, 0.5], [1.5, 0]]},\n"
    "  {\"target\": \"materials[0].kd\", \"interpolation\": \"hermite\",\n"
    "   \"times\": [0, 1], \"values\": [0.2, 0.6], \"tangents\": [0.1, -0.3]},\n"
    "  {\"target\": \"camera.eye\", \"path\": {\"points\": [[0, 0, 5], [4, 0, 5], [4, 3, 5]]},\n"
    "   \"start\": 1, \"duration\": 2, \"ease\": \"trapezoid\", \"accel\": 0.2}\n"
    " ]}\n";

static void test_channels_from_json(void **state) {
    (void)state;
    cj_anim_doc *doc = NULL;
    if (cj_anim_doc_parse(DOC, "doc.json", "", &doc) != CJ_OK) fail_msg("%s", cj_last_error());
    assert_true(doc->fps == 10 && doc->frame_first == 2 && doc->frame_last == 7);
    assert_int_equal(cj_anim_channel_count(doc->anim), 4);
    /* Euler zyx in degrees: 90 degrees about z at t = 1, half of it at t = 0.5 */
    double q[4];
    assert_int_equal(cj_channel_eval_quat(cj_anim_channel(doc->anim, 0), 0.5, q), CJ_OK);
    assert_true(fabs(q[0] - cos(M_PI / 8)) < 1e-15 && fabs(q[3] - sin(M_PI / 8)) < 1e-15);
    /* glTF cubic: p(s) = (2s³−3s²+1)·1 + (s³−2s²+s)·td·0.5 + (−2s³+3s²)·3 + (s³−s²)·td·1.5 */
    double v, vg;
    assert_int_equal(cj_channel_eval(cj_anim_channel(doc->anim, 1), 0.5, &v), CJ_OK);
    vg = v;
    const double s = 0.25, td = 2, s2 = s * s, s3 = s2 * s;
    const double want = (2 * s3 - 3 * s2 + 1) + (s3 - 2 * s2 + s) * td * 0.5 +
                        (-2 * s3 + 3 * s2) * 3 + (s3 - s2) * td * 1.5;
    assert_true(fabs(v - want) < 1e-14);
    /* Hermite with tangents 0.1 and −0.3 over [0, 1] */
    assert_int_equal(cj_channel_eval(cj_anim_channel(doc->anim, 2), 0.5, &v), CJ_OK);
    assert_true(fabs(v - (0.5 * 0.2 + 0.125 * 0.1 + 0.5 * 0.6 - 0.125 * -0.3)) < 1e-15);
    /* the path channel has no keyframe channel; its range is [start, start + duration] */
    assert_null(cj_anim_channel(doc->anim, 3));
    double t0, t1;
    cj_anim_range(doc->anim, &t0, &t1);
    assert_true(t0 == 0 && t1 == 3);
    printf("JSON channels: Euler zyx in degrees, glTF [in, out] tangents (%.15f vs the spec's "
           "%.15f), Hermite tangents and a trapezoid-eased path reach their channels\n",
           vg, want);
    cj_anim_doc_destroy(doc);
}

static void test_path_pose(void **state) {
    (void)state;
    cj_anim_doc *doc = NULL;
    assert_int_equal(cj_anim_doc_parse(DOC, "doc.json", "", &doc), CJ_OK);
    cj_scene *scene = NULL;
    assert_int_equal(cj_scene_create(NULL, &scene), CJ_OK);
    cj_light l = cj_light_defaults(CJ_LIGHT_POINT);
    cj_material m = cj_material_defaults();
    int idx;
    assert_int_equal(cj_scene_add_light(scene, &l, &idx), CJ_OK);
    assert_int_equal(cj_scene_add_material(scene, &m, &idx), CJ_OK);
    cj_geometry g;
    memset(&g, 0, sizeof g);
    g.kind = CJ_GEOM_SPHERE;
    g.u.sphere.radius = 1;
    assert_int_equal(cj_scene_add_geometry(scene, &g, &idx), CJ_OK);
    cj_node n;
    memset(&n, 0, sizeof n);
    n.parent = -1;
    n.local = cj_transform_identity();
    n.geometry = 0;
    n.material = 0;
    n.visible = 1;
    assert_int_equal(cj_scene_add_node(scene, &n, &idx), CJ_OK);
    assert_int_equal(cj_anim_doc_attach(doc, scene), CJ_OK);
    /* the eye moves along the spline through (0,0,5), (4,0,5), (4,3,5); the path has no
     * closed-form length, so check the ease profile through the positions: during the cruise
     * (time fraction in [0.2, 0.8]) equal time steps give equal chord steps to within the
     * curvature's effect, and the eye starts and ends at the path's ends */
    double prev[3] = {0, 0, 0}, d_first = 0, d_mid = 0;
    for (int k = 0; k <= 40; ++k) {
        const double t = 1 + 2.0 * k / 40;
        assert_int_equal(cj_anim_doc_frame(doc, scene, 0, NULL), CJ_OK);
        cj_anim_pose_info info;
        assert_int_equal(cj_anim_pose(scene, doc->anim, t, &info), CJ_OK);
        const cj_camera *c = cj_scene_get_camera(scene);
        const double e[3] = {c->eye.x, c->eye.y, c->eye.z};
        if (k == 0) assert_true(fabs(e[0]) < 1e-12 && fabs(e[1]) < 1e-12);
        if (k == 40) assert_true(fabs(e[0] - 4) < 1e-12 && fabs(e[1] - 3) < 1e-12);
        if (k > 0) {
            const double step = sqrt(pow(e[0] - prev[0], 2) + pow(e[1] - prev[1], 2));
            if (k == 1) d_first = step;
            if (k == 20) d_mid = step;
        }
        memcpy(prev, e, sizeof prev);
    }
    printf("path channel on camera.eye: starts and ends at the path's ends, accelerates (first "
           "step %.4f, cruise step %.4f)\n",
           d_first, d_mid);
    assert_true(d_first < 0.2 * d_mid);
    cj_scene_destroy(scene);
    cj_anim_doc_destroy(doc);
}

static void expect(const char *text, cj_status want, const char *needle) {
    cj_anim_doc *doc = NULL;
    const cj_status st = cj_anim_doc_parse(text, "bad.json", "", &doc);
    if (st != want || !strstr(cj_last_error(), needle))
        fail_msg("status %d '%s', expected %d with '%s'", (int)st, cj_last_error(), (int)want,
                 needle);
    assert_null(doc);
    printf("  refused: %s\n", cj_last_error());
}

static void test_errors(void **state) {
    (void)state;
    printf("bad documents:\n");
    expect("{\"channels\": [\n {\"target\": \"camera.eye\", \"times\": [0, 1],\n"
           "  \"values\": [[0, 0, 0], [1, 1]]}]}",
           CJ_ERR_PARSE, "bad.json:3: channels[0].values[1] must hold 3 numbers");
    expect("{\"channels\": [{\"target\": \"camera.eye\",\n \"times\": [0, 1],\n"
           " \"values\": [[0, 0, 0]]}]}",
           CJ_ERR_PARSE, "bad.json:3: channels[0].values has 1 entries");
    expect("{\"fps\": 0}", CJ_ERR_RANGE,
           "bad.json:1: document.fps = 0 must be a number in [0.001, 10000]");
    expect("{\"frames\": [5, 2]}", CJ_ERR_RANGE, "frames must be [first, last]");
    expect("{\"channels\": [{\"target\": \"camera.eye\", \"path\": {\"points\": [[0, 0, 0], "
           "[1, 0, 0]]},\n \"duration\": 0}]}",
           CJ_ERR_RANGE, "bad.json:1: channels[0].duration must be given and > 0");
    expect("{\"channels\": [{\"target\": \"camera.eye\", \"interpolation\": \"cubic\",\n"
           " \"times\": [0], \"values\": [[0, 0, 0]]}]}",
           CJ_ERR_PARSE, "interpolation must be one of: step, linear");
    expect("{\"channels\": [\n\n  {\"target\": 3}]}", CJ_ERR_PARSE,
           "bad.json:3: channels[0].target");
    expect("{\"channels\": [}", CJ_ERR_PARSE,
           "bad.json:1:15: JSON syntax error (line 1, column 15)");
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_channels_from_json),
        cmocka_unit_test(test_path_pose),
        cmocka_unit_test(test_errors),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

/* Image textures of a scene (viz/): the shipped teapot texture is read bottom row first and
 * decoded from sRGB to linear floats (checked against the IEC 61966-2-1 formula at every
 * code); a missing image is named with the scene file, the line and the JSON path. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "casteljau/scene_json.h"
#include "casteljau/scene_textures.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

static const cj_scene_json_options OPTS = {CJ_TEAPOT_PATH};

static double srgb(int c) {
    double x = c / 255.0;
    return x <= 0.04045 ? x / 12.92 : pow((x + 0.055) / 1.055, 2.4);
}

static void test_decode(void **state) {
    (void)state;
    for (int c = 0; c < 256; ++c) {
        double want = srgb(c), got = cj_srgb8_to_linear((unsigned char)c);
        if (!(fabs(got - want) <= 6e-8 * want + 1e-12))
            fail_msg("code %d: %.9g vs %.9g", c, got, want);
    }
    assert_true(cj_srgb8_to_linear(0) == 0.0f && cj_srgb8_to_linear(255) == 1.0f);
    printf("test_scene_textures: sRGB decode of all 256 codes within float rounding of the "
           "formula\n");
}

static void test_teapot_texture(void **state) {
    (void)state;
    cj_scene *s = NULL;
    assert_int_equal(cj_scene_load_json_with_options(CJ_SCENES_DIR "/teapot.json", &OPTS, NULL, &s),
                     CJ_OK);
    assert_null(cj_scene_texture(s, 0)->texels);
    if (cj_scene_load_textures(s, CJ_SCENES_DIR)) fail_msg("%s", cj_last_error());
    const cj_texture *t = cj_scene_texture(s, 0);
    assert_int_equal(t->width, 256);
    assert_int_equal(t->height, 256);
    /* The red square of scripts/make_scene_textures.py sits at u, v in [0.04, 0.12): with
     * rows bottom first it is near texel row 20, not near row 235. */
    const float *lo = t->texels + 4 * (20 * 256 + 20), *hi = t->texels + 4 * (235 * 256 + 20);
    assert_true(fabs(lo[0] - srgb(200)) < 1e-6 && fabs(lo[1] - srgb(30)) < 1e-6);
    assert_true(lo[3] == 1.0f);
    assert_true(fabs(hi[0] - srgb(245)) < 1e-6 && fabs(hi[2] - srgb(236)) < 1e-6);
    /* Loading again changes nothing (textures with pixels are skipped). */
    const float *before = t->texels;
    assert_int_equal(cj_scene_load_textures(s, CJ_SCENES_DIR), CJ_OK);
    assert_ptr_equal(cj_scene_texture(s, 0)->texels, before);
    cj_scene_destroy(s);
    printf("test_scene_textures: scenes/teapot.json's image texture: 256 x 256 linear texels, "
           "bottom row first\n");
}

static void test_missing_texture(void **state) {
    (void)state;
    const char *doc = "{\n\"textures\": [{\"name\": \"c\", \"type\": \"checker\"},\n"
                      "  {\"name\": \"wood\",\n   \"type\": \"image\", \"path\": \"nope.png\"}],\n"
                      "\"objects\": []}\n";
    cj_scene *s = NULL;
    assert_int_equal(cj_scene_parse_json(doc, "scene.json", "/tmp", NULL, &s), CJ_OK);
    assert_int_not_equal(cj_scene_load_textures(s, "/tmp/cj_no_such_folder"), CJ_OK);
    const char *want = "scene.json:4: textures[1].path: cannot read image texture "
                       "'/tmp/cj_no_such_folder/nope.png'";
    if (strncmp(cj_last_error(), want, strlen(want))) fail_msg("got '%s'", cj_last_error());
    assert_null(cj_scene_texture(s, 1)->texels);
    cj_scene_destroy(s);
    printf("test_scene_textures: a missing image is named '%s...'\n", want);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_decode),
        cmocka_unit_test(test_teapot_texture),
        cmocka_unit_test(test_missing_texture),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

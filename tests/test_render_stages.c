/* The rasterizer pipeline (issue 8, "Only the effects the scene calls for"): a stage runs iff
 * the scene uses its feature; removing a feature that changes nothing (a light of zero
 * intensity, a white texture) gives a bit-identical image; the image is bit-identical for
 * threads 1/2/3 and tile sizes 8/64/100; edge cases (empty scene, a curve alone, refused
 * options, geometry through the eye plane); sRGB output rounding; the tessellation cache.
 * Scenes are built from code (render_scenes.h). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "render_test_util.h"

static const char *all_stages[] = {"tessellate_patches",
                                   "tessellate_surfaces",
                                   "meshes",
                                   "vertex_normals",
                                   "texture_coords",
                                   "cull_backfaces",
                                   "sort_transparent",
                                   "shade_setup",
                                   "mipmaps",
                                   "shade_unlit",
                                   "shade_flat",
                                   "shade_gouraud",
                                   "shade_phong",
                                   "texture",
                                   "overlay_lines",
                                   "transparency",
                                   "resolve"};
#define NSTAGES (sizeof all_stages / sizeof all_stages[0])

/* Asserts that exactly the stages in `expect` (comma separated) ran among all_stages. */
static void expect_stages(const cj_scene *s, const cj_render_options *o, const char *expect) {
    cj_stage_report rep;
    cj_render_image_destroy(render(s, o, 0, &rep));
    for (size_t i = 0; i < NSTAGES; ++i) {
        char key[64];
        snprintf(key, sizeof key, ",%s,", all_stages[i]);
        char list[512];
        snprintf(list, sizeof list, ",%s,", expect);
        int want = strstr(list, key) != NULL;
        if (ran(&rep, all_stages[i]) != want)
            fail_msg("stage %s: ran %d, expected %d (scene features: %s)", all_stages[i],
                     ran(&rep, all_stages[i]), want, expect);
    }
}

static void test_stage_iff_feature(void **state) {
    (void)state;
    cj_render_options o = cj_render_options_defaults();
    o.width = 96;
    o.height = 72;
    o.spp = 1;
    rs_sphere_scene sc;
    rs_sphere(&sc, 0);
    /* no lights, one-sided opaque untextured sphere */
    expect_stages(sc.s, &o, "tessellate_surfaces,cull_backfaces,shade_unlit");
    /* an ambient light alone: still unlit (no normals) */
    cj_light amb = cj_light_defaults(CJ_LIGHT_AMBIENT);
    amb.intensity = 0.3;
    assert_int_equal(cj_scene_add_light(sc.s, &amb, NULL), CJ_OK);
    expect_stages(sc.s, &o, "tessellate_surfaces,cull_backfaces,shade_unlit");
    /* a point light: Phong (the default material) with normals */
    cj_light pt = cj_light_defaults(CJ_LIGHT_POINT);
    assert_int_equal(cj_scene_add_light(sc.s, &pt, NULL), CJ_OK);
    expect_stages(sc.s, &o, "tessellate_surfaces,cull_backfaces,vertex_normals,shade_phong");
    cj_material *m = cj_scene_material_mut(sc.s, sc.mat);
    m->shading = CJ_SHADE_FLAT;
    expect_stages(sc.s, &o, "tessellate_surfaces,cull_backfaces,shade_setup,shade_flat");
    m->shading = CJ_SHADE_GOURAUD;
    expect_stages(sc.s, &o,
                  "tessellate_surfaces,cull_backfaces,vertex_normals,shade_setup,shade_gouraud");
    m->shading = CJ_SHADE_PHONG;
    m->two_sided = 1;
    expect_stages(sc.s, &o, "tessellate_surfaces,vertex_normals,shade_phong");
    m->two_sided = 0;
    /* a checker texture: (u, v) and sampling */
    cj_texture ck = cj_texture_defaults(CJ_TEX_CHECKER);
    int ti;
    assert_int_equal(cj_scene_add_texture(sc.s, &ck, &ti), CJ_OK);
    m = cj_scene_material_mut(sc.s, sc.mat);
    m->texture = ti;
    expect_stages(sc.s, &o,
                  "tessellate_surfaces,cull_backfaces,vertex_normals,texture_coords,shade_phong,"
                  "texture");
    /* a trilinear image texture: mip-maps too */
    cj_texture im = cj_texture_defaults(CJ_TEX_IMAGE);
    im.filter = CJ_TEX_TRILINEAR;
    im.path = "white.png";
    assert_int_equal(cj_scene_add_texture(sc.s, &im, &ti), CJ_OK);
    float px[16 * 4];
    for (int i = 0; i < 64; ++i) px[i] = 1.0f;
    assert_int_equal(cj_scene_set_texture_pixels(sc.s, ti, 4, 4, px), CJ_OK);
    m = cj_scene_material_mut(sc.s, sc.mat);
    m->texture = ti;
    expect_stages(sc.s, &o,
                  "tessellate_surfaces,cull_backfaces,vertex_normals,texture_coords,mipmaps,"
                  "shade_phong,texture");
    m->texture = -1;
    /* transparency: sorting and blending */
    m->opacity = 0.5;
    expect_stages(sc.s, &o,
                  "tessellate_surfaces,cull_backfaces,vertex_normals,sort_transparent,"
                  "shade_phong,transparency");
    m->opacity = 1.0;
    /* supersampling: resolve */
    o.spp = 4;
    expect_stages(sc.s, &o,
                  "tessellate_surfaces,cull_backfaces,vertex_normals,shade_phong,resolve");
    o.spp = 1;
    /* overlays: the line pass; a patch object: patch tessellation */
    cj_scene_node_mut(sc.s, sc.node)->overlay.flags = CJ_OVERLAY_WIREFRAME;
    expect_stages(sc.s, &o,
                  "tessellate_surfaces,cull_backfaces,vertex_normals,shade_phong,overlay_lines");
    cj_scene_node_mut(sc.s, sc.node)->overlay.flags = 0;
    rs_add_patch_quad(sc.s, sc.mat, 0.0, 0);
    expect_stages(sc.s, &o,
                  "tessellate_patches,tessellate_surfaces,cull_backfaces,vertex_normals,"
                  "shade_phong");
    rs_add_curve(sc.s, sc.mat, -3.0);
    expect_stages(sc.s, &o,
                  "tessellate_patches,tessellate_surfaces,cull_backfaces,vertex_normals,"
                  "shade_phong,overlay_lines");
    cj_scene_destroy(sc.s);
    printf("test_stage_iff_feature: 12 scenes, each feature switches exactly its stages\n");
}

static void test_neutral_features_bit_identical(void **state) {
    (void)state;
    cj_render_options o = cj_render_options_defaults();
    o.width = 120;
    o.height = 90;
    o.spp = 4;
    rs_sphere_scene sc;
    rs_sphere(&sc, 1);
    cj_render_image *ref = render(sc.s, &o, 0, NULL);
    /* a point light and an ambient light of zero intensity */
    cj_light z = cj_light_defaults(CJ_LIGHT_POINT);
    z.intensity = 0.0;
    z.position = cj_v3(-3, 1, 2);
    assert_int_equal(cj_scene_add_light(sc.s, &z, NULL), CJ_OK);
    z = cj_light_defaults(CJ_LIGHT_AMBIENT);
    z.intensity = 0.0;
    assert_int_equal(cj_scene_add_light(sc.s, &z, NULL), CJ_OK);
    cj_render_image *img = render(sc.s, &o, 0, NULL);
    assert_true(same_image(ref, img));
    cj_render_image_destroy(img);
    /* white textures: an all-ones image (each filter) and a white checker */
    const cj_tex_filter filters[3] = {CJ_TEX_NEAREST, CJ_TEX_BILINEAR, CJ_TEX_TRILINEAR};
    float px[8 * 4 * 4];
    for (int i = 0; i < 128; ++i) px[i] = 1.0f;
    int checked = 0;
    for (int f = 0; f < 4; ++f) {
        cj_texture t = cj_texture_defaults(f < 3 ? CJ_TEX_IMAGE : CJ_TEX_CHECKER);
        int ti;
        if (f < 3) {
            t.filter = filters[f];
            t.path = "white";
        } else {
            t.filter = CJ_TEX_BILINEAR;
            t.checker_a = t.checker_b = cj_rgb_make(1, 1, 1);
        }
        assert_int_equal(cj_scene_add_texture(sc.s, &t, &ti), CJ_OK);
        if (f < 3) assert_int_equal(cj_scene_set_texture_pixels(sc.s, ti, 8, 4, px), CJ_OK);
        cj_scene_material_mut(sc.s, sc.mat)->texture = ti;
        cj_stage_report rep;
        img = render(sc.s, &o, 0, &rep);
        assert_true(ran(&rep, "texture"));
        assert_true(same_image(ref, img));
        cj_render_image_destroy(img);
        ++checked;
    }
    cj_render_image_destroy(ref);
    cj_scene_destroy(sc.s);
    printf("test_neutral_features_bit_identical: 2 zero lights, %d white textures: same image\n",
           checked);
}

static void test_threads_tiles_identical(void **state) {
    (void)state;
    cj_scene *s = rs_feature_scene();
    cj_render_options o = cj_render_options_defaults();
    o.width = 173;
    o.height = 131;
    o.spp = 4;
    o.threads = 1;
    o.tile_size = 64;
    cj_stage_report rep;
    cj_render_image *ref = render(s, &o, CJ_IMAGE_IDS | CJ_IMAGE_DEPTH, &rep);
    assert_true(ran(&rep, "transparency") && ran(&rep, "overlay_lines") && ran(&rep, "texture"));
    dump(ref, "features");
    const int threads[3] = {1, 2, 3}, tiles[3] = {8, 64, 100};
    int runs = 0;
    for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b) {
            o.threads = threads[a];
            o.tile_size = tiles[b];
            cj_render_image *img = render(s, &o, CJ_IMAGE_IDS | CJ_IMAGE_DEPTH, NULL);
            size_t n = (size_t)o.width * (size_t)o.height;
            if (!same_image(ref, img) || memcmp(ref->ids, img->ids, n * 4) ||
                memcmp(ref->depth, img->depth, n * 4))
                fail_msg("threads %d, tile %d: image differs", threads[a], tiles[b]);
            cj_render_image_destroy(img);
            ++runs;
        }
    cj_render_image_destroy(ref);
    cj_scene_destroy(s);
    printf("test_threads_tiles_identical: %d runs (threads 1/2/3 x tiles 8/64/100), spp 4, "
           "transparency, texture, overlays: bit-identical colour, ids and depth\n",
           runs);
}

static void test_edge_cases(void **state) {
    (void)state;
    cj_scene *s;
    rs_check(cj_scene_create(NULL, &s));
    cj_scene_settings set = cj_scene_settings_defaults();
    set.background = cj_rgb_make(0.25, 0.5, 0.125);
    set.width = 40;
    set.height = 30;
    rs_check(cj_scene_set_settings(s, &set));
    /* nothing in the scene: the background, alpha 0, every stage but the always ones left out */
    cj_stage_report rep;
    cj_render_image *img = render(s, NULL, CJ_IMAGE_IDS | CJ_IMAGE_DEPTH, &rep);
    for (int i = 0; i < 40 * 30; ++i) {
        assert_true(img->rgba[4 * i] == 0.25f && img->rgba[4 * i + 1] == 0.5f &&
                    img->rgba[4 * i + 2] == 0.125f && img->rgba[4 * i + 3] == 0.0f);
        assert_true(img->ids[i] == 0 && img->depth[i] == 1.0f);
    }
    assert_false(ran(&rep, "shade_unlit") || ran(&rep, "overlay_lines"));
    cj_render_image_destroy(img);
    /* only a curve: the line pass alone */
    cj_material m = cj_material_defaults();
    int mi;
    rs_check(cj_scene_add_material(s, &m, &mi));
    rs_add_curve(s, mi, 0.0);
    img = render(s, NULL, 0, &rep);
    assert_true(ran(&rep, "overlay_lines") &&
                cj_stage_report_find(&rep, "overlay_lines")->out > 20);
    cj_render_image_destroy(img);
    /* refused options and data: nothing is returned */
    cj_render_options o = cj_render_options_defaults();
    cj_render_image *none = NULL;
    o.spp = 3;
    assert_int_equal(cj_render_raster(s, &o, 0, NULL, &none, NULL), CJ_ERR_RANGE);
    o.spp = 1;
    o.tile_size = 4;
    assert_int_equal(cj_render_raster(s, &o, 0, NULL, &none, NULL), CJ_ERR_RANGE);
    o.tile_size = 0;
    o.tol_px = -1.0;
    assert_int_equal(cj_render_raster(s, &o, 0, NULL, &none, NULL), CJ_ERR_RANGE);
    o.tol_px = 0.0;
    cj_texture t = cj_texture_defaults(CJ_TEX_IMAGE);
    t.path = "missing.png";
    int ti;
    rs_check(cj_scene_add_texture(s, &t, &ti));
    m.texture = ti;
    rs_check(cj_scene_add_material(s, &m, &mi));
    cj_geometry g;
    memset(&g, 0, sizeof g);
    g.kind = CJ_GEOM_SPHERE;
    g.u.sphere.radius = 0.5;
    int gi;
    rs_check(cj_scene_add_geometry(s, &g, &gi));
    cj_node n = cj_node_defaults(gi, mi);
    rs_check(cj_scene_add_node(s, &n, NULL));
    assert_int_equal(cj_render_raster(s, &o, 0, NULL, &none, NULL), CJ_ERR_ARGUMENT);
    assert_non_null(strstr(cj_last_error(), "textures[0]"));
    assert_null(none);
    cj_scene_destroy(s);
    /* a curved patch through the eye plane: tessellated (relaxing the tolerance if the near
     * plane asks for too much), clipped, rendered */
    rs_sphere_scene sc;
    rs_sphere(&sc, 1);
    rs_add_patch_quad(sc.s, sc.mat, 4.8, 0);
    cj_scene_material_mut(sc.s, sc.mat)->two_sided = 1;
    o = cj_render_options_defaults();
    o.width = 120;
    o.height = 90;
    cj_render_image_destroy(render(sc.s, &o, 0, &rep));
    const cj_stage *tp = cj_stage_report_find(&rep, "tessellate_patches");
    const cj_stage *rz = cj_stage_report_find(&rep, "rasterize");
    assert_true(tp->out > 0 && tp->extra[1].value > 0.0);
    assert_true(rz->extra[0].value > 0); /* triangles cut by the near plane */
    printf("test_edge_cases: a patch through the eye plane: %llu triangles, bound %.3g px, %g "
           "clipped\n",
           (unsigned long long)tp->out, tp->extra[1].value, rz->extra[0].value);
    cj_scene_destroy(sc.s);
    printf("test_edge_cases: empty scene = background with alpha 0; a curve alone; spp 3, tile 4, "
           "tol -1 and an image texture without pixels refused\n");
}

static void test_srgb(void **state) {
    (void)state;
    cj_render_image *img = NULL;
    const int n = 4096;
    assert_int_equal(cj_render_image_create(n, 1, 0, NULL, &img), CJ_OK);
    for (int i = 0; i < n; ++i) {
        double x = (double)i / (n - 1);
        img->rgba[4 * i] = (float)x;
        img->rgba[4 * i + 1] = (float)(x * x);
        img->rgba[4 * i + 2] = (float)(x - 0.5); /* negative half clamps to 0 */
        img->rgba[4 * i + 3] = (float)x;
    }
    uint8_t *px = malloc(4 * (size_t)n);
    assert_non_null(px);
    assert_int_equal(cj_render_image_to_srgb8(img, px, 0), CJ_OK);
    int checked = 0;
    for (int i = 0; i < n; ++i)
        for (int c = 0; c < 3; ++c) {
            double v = img->rgba[4 * i + c];
            v = v < 0 ? 0 : v > 1 ? 1 : v;
            double e = v <= 0.0031308 ? 12.92 * v : 1.055 * pow(v, 1 / 2.4) - 0.055;
            double code = 255.0 * e;
            if (fabs(code - floor(code) - 0.5) < 1e-4) continue; /* a tie to within rounding */
            assert_int_equal(px[4 * i + c], (int)floor(code + 0.5));
            ++checked;
        }
    img->rgba[5] = NAN;
    assert_int_equal(cj_render_image_to_srgb8(img, px, 0), CJ_ERR_NONFINITE);
    free(px);
    cj_render_image_destroy(img);
    printf("test_srgb: %d channel values rounded to the nearest sRGB code; NaN refused\n", checked);
}

static void test_tessellation_cache(void **state) {
    (void)state;
    rs_sphere_scene sc;
    rs_sphere(&sc, 1);
    int pn = rs_add_patch_quad(sc.s, sc.mat, -1.0, CJ_OVERLAY_CONTROL_NET);
    cj_render_options o = cj_render_options_defaults();
    o.width = 160;
    o.height = 120;
    cj_render_image *ref = render(sc.s, &o, 0, NULL);
    cj_render_cache *cache = NULL;
    assert_int_equal(cj_render_cache_create(NULL, &cache), CJ_OK);
    o.cache = cache;
    double hits[5];
    const cj_stage *st;
    cj_stage_report rep;
    for (int i = 0; i < 2; ++i) { /* cold, then warm: the same image as without a cache */
        cj_render_image *img = render(sc.s, &o, 0, &rep);
        assert_true(same_image(ref, img));
        cj_render_image_destroy(img);
        st = cj_stage_report_find(&rep, "tessellate_patches");
        hits[i] = st->extra[st->extra_count - 1].value;
    }
    /* the camera a little farther: the cached, finer mesh is reused and still within tol */
    cj_camera cam = *cj_scene_get_camera(sc.s);
    cam.eye = cj_v3(0, 0, 6);
    rs_check(cj_scene_set_camera(sc.s, &cam));
    cj_render_image_destroy(render(sc.s, &o, 0, &rep));
    st = cj_stage_report_find(&rep, "tessellate_patches");
    hits[2] = st->extra[st->extra_count - 1].value;
    assert_true(st->extra[1].value <= 0.25); /* bound_px */
    /* much farther: more than 2x coarser is allowed, so it tessellates again */
    cam.eye = cj_v3(0, 0, 30);
    rs_check(cj_scene_set_camera(sc.s, &cam));
    cj_render_image_destroy(render(sc.s, &o, 0, &rep));
    st = cj_stage_report_find(&rep, "tessellate_patches");
    hits[3] = st->extra[st->extra_count - 1].value;
    /* a control point moved: the key changes, it tessellates again */
    cj_geometry *g = cj_scene_geometry_mut(sc.s, cj_scene_node(sc.s, pn)->geometry);
    ((double *)g->u.patches.patches[0].pts)[2] += 0.25;
    cj_render_image_destroy(render(sc.s, &o, 0, &rep));
    st = cj_stage_report_find(&rep, "tessellate_patches");
    hits[4] = st->extra[st->extra_count - 1].value;
    assert_true(hits[0] == 0 && hits[1] == 1 && hits[2] == 1 && hits[3] == 0 && hits[4] == 0);
    cj_render_cache_destroy(cache);
    cj_render_image_destroy(ref);
    cj_scene_destroy(sc.s);
    printf("test_tessellation_cache: cold miss, warm hit with the same image, hit when 1.2x "
           "farther (bound still <= tol), miss at 6x and after a control point moved\n");
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_stage_iff_feature),
        cmocka_unit_test(test_neutral_features_bit_identical),
        cmocka_unit_test(test_threads_tiles_identical),
        cmocka_unit_test(test_edge_cases),
        cmocka_unit_test(test_srgb),
        cmocka_unit_test(test_tessellation_cache),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

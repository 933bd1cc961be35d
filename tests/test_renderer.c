/* The renderer object (casteljau/renderer.h): a renderer reused across frames gives images
 * bit-identical (colour, ids, depth) to one-shot calls, for 1, 2 and 3 threads and both back
 * ends, through a sequence of scene edits between frames (nothing, a control point moved, a
 * material and a light changed, a node hidden and shown again, spp changed, the size changed);
 * its stage report says what it reused (tessellation cache hits and misses, BVHs reused and
 * built, pool, buffers and image reused); a cancelled frame leaves it usable; bad options are
 * refused; its scene mesh is the one-shot call's. Scenes: the trace demo (teapot, floor, mirror and
 * glass spheres) and the feature scene of the rasterizer tests (textures, transparency, overlays,
 * curves). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "casteljau/mesh.h"
#include "casteljau/renderer.h"
#include "render_test_util.h"

static int same_planes(const cj_render_image *a, const cj_render_image *b) {
    if (a->width != b->width || a->height != b->height) return 0;
    size_t n = (size_t)a->width * (size_t)a->height;
    if (memcmp(a->rgba, b->rgba, n * 4 * sizeof(float))) return 0;
    if ((a->ids == NULL) != (b->ids == NULL) || (a->depth == NULL) != (b->depth == NULL)) return 0;
    if (a->ids && memcmp(a->ids, b->ids, n * sizeof(uint32_t))) return 0;
    if (a->depth && memcmp(a->depth, b->depth, n * sizeof(float))) return 0;
    return 1;
}

static double value(const cj_stage_report *r, const char *stage, const char *key) {
    const cj_stage *s = cj_stage_report_find(r, stage);
    if (!s) fail_msg("no stage %s", stage);
    for (int i = 0; i < s->extra_count; ++i)
        if (!strcmp(s->extra[i].key, key)) return s->extra[i].value;
    fail_msg("stage %s has no value %s", stage, key);
    return 0.0;
}

static cj_render_image *one_shot(const cj_scene *s, cj_backend be, const cj_renderer_options *o,
                                 unsigned planes) {
    cj_render_image *img = NULL;
    cj_status st =
        be == CJ_BACKEND_TRACE
            ? cj_render_trace_with_options(s, &o->render, &o->trace, planes, NULL, &img, NULL)
            : cj_render_raster(s, &o->render, planes, NULL, &img, NULL);
    if (st) fail_msg("one-shot render failed: %s", cj_last_error());
    return img;
}

/* The first node whose geometry is a Bézier patch set, or -1. */
static int patch_node(const cj_scene *s) {
    for (size_t i = 0; i < cj_scene_node_count(s); ++i) {
        const cj_node *n = cj_scene_node(s, (int)i);
        if (n->geometry >= 0 && cj_scene_geometry(s, n->geometry)->kind == CJ_GEOM_PATCHES)
            return (int)i;
    }
    return -1;
}

enum { E_NONE, E_WARM, E_POINT, E_LOOK, E_HIDE, E_SHOW, E_SPP, E_SIZE, E_COUNT };
static const char *edit_name[E_COUNT] = {
    "first frame",         "no edit",
    "control point moved", "material and light",
    "patch node hidden",   "shown again",
    "spp changed",         "size changed (trace: same image; raster: bound kept)"};

static void edit(cj_scene *s, int e, cj_renderer_options *o) {
    int pn = patch_node(s);
    assert_true(pn >= 0);
    cj_node *n = cj_scene_node_mut(s, pn);
    switch (e) {
    case E_POINT: {
        cj_geometry *g = cj_scene_geometry_mut(s, n->geometry);
        ((double *)g->u.patches.patches[0].pts)[4] += 0.05;
        break;
    }
    case E_LOOK: {
        cj_material *m = cj_scene_material_mut(s, 0);
        m->color.g *= 0.5;
        cj_light *l = cj_scene_light_mut(s, (int)cj_scene_light_count(s) - 1);
        l->intensity *= 0.7;
        break;
    }
    case E_HIDE:
        n->visible = 0;
        break;
    case E_SHOW:
        n->visible = 1;
        break;
    case E_SPP:
        o->render.spp = 4;
        break;
    case E_SIZE:
        o->render.width += 24;
        break;
    default:
        break;
    }
}

/* One renderer through every edit, each frame compared with the one-shot call. */
static void run_sequence(cj_scene *(*make)(void), const char *name, cj_backend be, int threads) {
    cj_scene *s = make();
    cj_renderer_options o = cj_renderer_options_defaults();
    o.render.width = 80;
    o.render.height = 60;
    o.render.spp = 1;
    o.render.tile_size = 16;
    o.render.threads = threads;
    cj_renderer *r = NULL;
    assert_int_equal(cj_renderer_create(&o, NULL, &r), CJ_OK);
    const unsigned planes = CJ_IMAGE_IDS | CJ_IMAGE_DEPTH;
    cj_render_image *img = NULL, *prev = NULL;
    const char *stage = be == CJ_BACKEND_TRACE ? "build_bvh" : "tessellate_patches";
    const char *hit = be == CJ_BACKEND_TRACE ? "bvh_reused" : "cache_hits";
    const char *miss = be == CJ_BACKEND_TRACE ? "bvh_built" : "cache_misses";
    for (int e = 0; e < E_COUNT; ++e) {
        edit(s, e, &o);
        assert_int_equal(cj_renderer_set_options(r, &o), CJ_OK);
        cj_stage_report rep;
        cj_status st = cj_renderer_draw(r, s, be, planes, &img, &rep);
        if (st) fail_msg("%s frame %d: %s", name, e, cj_last_error());
        cj_render_image *ref = one_shot(s, be, &o, planes);
        /* a new size moves the needed tolerance: the rasterizer may draw a cached mesh up to
         * 2x finer than a fresh one (renderer.h), so only the bound is promised there */
        if (be == CJ_BACKEND_RASTER && e == E_SIZE)
            assert_true(value(&rep, "tessellate_patches", "bound_px") <=
                        value(&rep, "tessellate_patches", "tol_px"));
        else if (!same_planes(img, ref))
            fail_msg("%s, %s, %d thread(s), after '%s': the reused renderer's image differs from "
                     "the one-shot call's",
                     name, be == CJ_BACKEND_TRACE ? "trace" : "raster", threads, edit_name[e]);
        cj_render_image_destroy(ref);
        double h = value(&rep, stage, hit), m = value(&rep, stage, miss);
        double frame = value(&rep, "frame", "frame");
        assert_true(frame == e + 1);
        /* the renderer keeps the same stage table */
        assert_int_equal(cj_renderer_report(r)->count, rep.count);
        assert_true(value(cj_renderer_report(r), "frame", "frame") == frame);
        if (e == E_NONE) assert_true(h == 0 && m >= 1);
        if (e == E_WARM || e == E_LOOK || e == E_SPP) assert_true(h >= 1 && m == 0);
        if (e == E_POINT) assert_true(m >= 1);
        if (e == E_HIDE) assert_true(m == 0);
        /* shown again: the hidden node's entry is back (raster) or was dropped (trace) */
        if (e == E_SHOW) assert_true(be == CJ_BACKEND_TRACE ? m >= 1 : (h >= 1 && m == 0));
        if (e >= E_WARM) {
            assert_true(value(&rep, "frame", "pool_reused") == 1);
            assert_true(value(&rep, "frame", "image_reused") == (e == E_SIZE ? 0 : 1));
            assert_true(e == E_SIZE || img == prev);
        }
        if (be == CJ_BACKEND_RASTER && e >= E_WARM && e != E_SPP)
            assert_true(value(&rep, "frame", "buffers_reused") == 1);
        prev = img;
    }
    printf("test_renderer: %s, %s, %d thread(s): %d frames bit-identical to one-shot calls "
           "(colour, ids, depth); reuse as expected per edit\n",
           name, be == CJ_BACKEND_TRACE ? "trace" : "raster", threads, E_COUNT);
    cj_render_image_destroy(img);
    cj_renderer_destroy(r);
    cj_scene_destroy(s);
}

static cj_scene *teapot_scene(void) {
    cj_scene *s = NULL;
    rs_check(cj_trace_demo_scene(CJ_TEAPOT_PATH, NULL, &s));
    return s;
}

static void test_teapot_sequence(void **state) {
    (void)state;
    for (int th = 1; th <= 3; ++th) {
        run_sequence(teapot_scene, "trace demo", CJ_BACKEND_RASTER, th);
        run_sequence(teapot_scene, "trace demo", CJ_BACKEND_TRACE, th);
    }
}

static void test_feature_sequence(void **state) {
    (void)state;
    for (int th = 1; th <= 3; ++th) {
        run_sequence(rs_feature_scene, "feature scene", CJ_BACKEND_RASTER, th);
        run_sequence(rs_feature_scene, "feature scene", CJ_BACKEND_TRACE, th);
    }
}

/* Both back ends alternate on one renderer (one pool, one scheduler): still the same images. */
static void test_alternating(void **state) {
    (void)state;
    cj_scene *s = teapot_scene();
    cj_renderer_options o = cj_renderer_options_defaults();
    o.render.width = 64;
    o.render.height = 48;
    o.render.spp = 1;
    o.render.threads = 2;
    cj_renderer *r = NULL;
    assert_int_equal(cj_renderer_create(&o, NULL, &r), CJ_OK);
    cj_render_image *a = NULL, *b = NULL;
    for (int k = 0; k < 4; ++k) {
        cj_backend be = k % 2 ? CJ_BACKEND_TRACE : CJ_BACKEND_RASTER;
        cj_render_image **img = k % 2 ? &b : &a;
        assert_int_equal(cj_renderer_draw(r, s, be, 0, img, NULL), CJ_OK);
        cj_render_image *ref = one_shot(s, be, &o, 0);
        assert_true(same_planes(*img, ref));
        cj_render_image_destroy(ref);
    }
    cj_render_image_destroy(a);
    cj_render_image_destroy(b);
    cj_renderer_destroy(r);
    cj_scene_destroy(s);
    printf("test_alternating: raster, trace, raster, trace on one renderer: each frame equal to "
           "its one-shot call\n");
}

static int cancel_at_2(void *user, uint64_t done, uint64_t total) {
    (void)user;
    (void)total;
    return done >= 2;
}

/* A cancelled frame returns CJ_ERR_CANCELLED, keeps the caller's image pointer, and the next
 * frame (progress callback removed) is the one-shot image. */
static void test_cancel_then_draw(void **state) {
    (void)state;
    cj_scene *s = teapot_scene();
    cj_renderer_options o = cj_renderer_options_defaults();
    o.render.width = 64;
    o.render.height = 48;
    o.render.tile_size = 16;
    o.render.spp = 1;
    o.render.threads = 2;
    cj_renderer *r = NULL;
    assert_int_equal(cj_renderer_create(&o, NULL, &r), CJ_OK);
    for (int be = 0; be < 2; ++be) {
        cj_render_image *img = NULL;
        o.render.progress = cancel_at_2;
        assert_int_equal(cj_renderer_set_options(r, &o), CJ_OK);
        assert_int_equal(cj_renderer_draw(r, s, (cj_backend)be, 0, &img, NULL), CJ_ERR_CANCELLED);
        assert_null(img);
        o.render.progress = NULL;
        assert_int_equal(cj_renderer_set_options(r, &o), CJ_OK);
        assert_int_equal(cj_renderer_draw(r, s, (cj_backend)be, 0, &img, NULL), CJ_OK);
        cj_render_image *keep = img;
        o.render.progress = cancel_at_2;
        assert_int_equal(cj_renderer_set_options(r, &o), CJ_OK);
        assert_int_equal(cj_renderer_draw(r, s, (cj_backend)be, 0, &img, NULL), CJ_ERR_CANCELLED);
        assert_ptr_equal(img, keep);
        o.render.progress = NULL;
        assert_int_equal(cj_renderer_set_options(r, &o), CJ_OK);
        assert_int_equal(cj_renderer_draw(r, s, (cj_backend)be, 0, &img, NULL), CJ_OK);
        cj_render_image *ref = one_shot(s, (cj_backend)be, &o, 0);
        assert_true(same_planes(img, ref));
        cj_render_image_destroy(ref);
        cj_render_image_destroy(img);
    }
    cj_renderer_destroy(r);
    cj_scene_destroy(s);
    printf("test_cancel_then_draw: a cancelled frame (both back ends) leaves no new image, keeps "
           "a reused one, and the next frame is the one-shot image\n");
}

static void test_options(void **state) {
    (void)state;
    cj_renderer *r = NULL;
    cj_renderer_options o = cj_renderer_options_defaults();
    int refused = 0;
    o.render.threads = -1;
    refused += cj_renderer_create(&o, NULL, &r) == CJ_ERR_RANGE;
    o = cj_renderer_options_defaults();
    o.render.tile_size = 4;
    refused += cj_renderer_create(&o, NULL, &r) == CJ_ERR_RANGE;
    o = cj_renderer_options_defaults();
    o.render.tol_px = NAN;
    refused += cj_renderer_create(&o, NULL, &r) == CJ_ERR_RANGE;
    o = cj_renderer_options_defaults();
    o.trace.indirect_samples = 5000;
    refused += cj_renderer_create(&o, NULL, &r) == CJ_ERR_RANGE;
    assert_int_equal(refused, 4);
    assert_null(r);
    assert_int_equal(cj_renderer_create(NULL, NULL, &r), CJ_OK);
    o = cj_renderer_options_defaults();
    o.render.spp = -2;
    assert_int_equal(cj_renderer_set_options(r, &o), CJ_ERR_RANGE);
    assert_int_equal(cj_renderer_get_options(r)->render.spp, 0); /* the old options stay */
    /* an option only the scene can judge is refused at the draw */
    rs_sphere_scene sc;
    rs_sphere(&sc, 1);
    o.render.spp = 3;
    o.render.width = 32;
    o.render.height = 32;
    assert_int_equal(cj_renderer_set_options(r, &o), CJ_OK);
    cj_render_image *img = NULL;
    assert_int_equal(cj_renderer_draw(r, sc.s, CJ_BACKEND_RASTER, 0, &img, NULL), CJ_ERR_RANGE);
    assert_null(img);
    assert_int_equal(cj_renderer_draw(r, sc.s, CJ_BACKEND_TRACE, 0, &img, NULL), CJ_OK);
    cj_render_image_destroy(img);
    cj_scene_destroy(sc.s);
    cj_renderer_destroy(r);
    printf("test_options: 4 bad options refused at creation, one by set_options (old kept), "
           "spp 3 refused by the rasterizer at the draw and taken by the tracer\n");
}

/* cj_renderer_scene_mesh: the one-shot call's mesh, cold and warm (from the cache). */
static void test_scene_mesh(void **state) {
    (void)state;
    cj_scene *s = teapot_scene();
    cj_renderer_options o = cj_renderer_options_defaults();
    o.render.width = 96;
    o.render.height = 72;
    cj_renderer *r = NULL;
    assert_int_equal(cj_renderer_create(&o, NULL, &r), CJ_OK);
    cj_mesh *ref = NULL;
    assert_int_equal(cj_render_scene_mesh(s, &o.render, NULL, &ref), CJ_OK);
    assert_true(ref->triangle_count > 1000);
    for (int k = 0; k < 2; ++k) {
        cj_mesh *m = NULL;
        assert_int_equal(cj_renderer_scene_mesh(r, s, &m), CJ_OK);
        assert_int_equal(m->vertex_count, ref->vertex_count);
        assert_int_equal(m->triangle_count, ref->triangle_count);
        assert_memory_equal(m->positions, ref->positions, 3 * sizeof(double) * m->vertex_count);
        assert_memory_equal(m->triangles, ref->triangles, 3 * sizeof(uint32_t) * m->triangle_count);
        cj_mesh_destroy(m);
    }
    cj_mesh_destroy(ref);
    cj_renderer_destroy(r);
    cj_scene_destroy(s);
    printf("test_scene_mesh: the renderer's mesh equals the one-shot mesh, cold and from its "
           "cache\n");
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_teapot_sequence), cmocka_unit_test(test_feature_sequence),
        cmocka_unit_test(test_alternating),     cmocka_unit_test(test_cancel_then_draw),
        cmocka_unit_test(test_options),         cmocka_unit_test(test_scene_mesh),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

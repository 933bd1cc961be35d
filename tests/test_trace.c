/* The ray tracer (raster/: trace.h):
 *  - only the effects the scene calls for: a mirror material casts reflection rays; setting its
 *    mirror to 0 removes every reflection ray (stage left out); no shadow rays when no light
 *    casts shadows or no material receives them; refraction rays only into transmissive ones;
 *  - a shadowed floor point has exactly the ambient radiance c_r r_a I_a; a lit one the Phong
 *    value computed here by hand (from the exact ray-plane hit);
 *  - no acne at 1e6 scale (every floor pixel lit), no light leaking at 1e-6 scale (a floor under
 *    a roof 1e-6 above it stays at the ambient value everywhere);
 *  - Snell's law and total internal reflection of cj_trace_refract;
 *  - the image (spp 4, glass, mirror, area light, glossy) is bit-identical for 1, 2, 3 threads
 *    and tile sizes 8, 32;
 *  - the signature image against the rasterizer's id buffer on the demo scene: they differ only
 *    within a one-pixel band around silhouettes (counted);
 *  - the cosine sampler (Malley): over 1e5 samples about a random normal, mean cos θ = 2/3 and
 *    P(cos θ > 1/2) = 3/4 (exact for pdf cos θ / π) within 4 standard errors, all on the
 *    normal's hemisphere;
 *  - one-bounce diffuse interreflection: indirect 0 gives the default image bit for bit and no
 *    indirect ray; a diffuse floor under an empty sky of radiance B shows exactly kd c B (the
 *    furnace value) with hits × N indirect rays; bit-identical for 1, 2, 3 threads. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "casteljau/render.h"
#include "casteljau/scene.h"
#include "casteljau/scene_json.h"
#include "casteljau/trace.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Floor y = 0 (size 40 s), a sphere of radius s at height 2 s, a point light at 10 s straight
 * above it and an ambient light; every length scaled by s and moved by `shift`. */
static cj_scene *sphere_scene(double s, cj_vec3 shift, double mirror, int w) {
    cj_scene *sc;
    assert_int_equal(cj_scene_create(NULL, &sc), CJ_OK);
    cj_camera cam = cj_camera_defaults();
    cam.eye = cj_v3_add(shift, cj_v3(0, 3 * s, 8 * s));
    cam.gaze = cj_v3(0, -3, -8);
    cam.near = -0.1 * s;
    cam.far = -100 * s;
    assert_int_equal(cj_scene_set_camera(sc, &cam), CJ_OK);
    cj_scene_settings set = cj_scene_settings_defaults();
    set.width = w;
    set.height = w;
    set.spp = 1;
    assert_int_equal(cj_scene_set_settings(sc, &set), CJ_OK);
    cj_light amb = cj_light_defaults(CJ_LIGHT_AMBIENT), pt = cj_light_defaults(CJ_LIGHT_POINT);
    amb.intensity = 0.5;
    pt.position = cj_v3_add(shift, cj_v3(0, 10 * s, 0));
    assert_int_equal(cj_scene_add_light(sc, &amb, NULL), CJ_OK);
    assert_int_equal(cj_scene_add_light(sc, &pt, NULL), CJ_OK);
    cj_material fm = cj_material_defaults(), sm = cj_material_defaults();
    fm.color = cj_rgb_make(1, 0.8, 0.6);
    fm.ka = 0.2;
    fm.kd = 0.8;
    fm.ks = 0.0;
    sm.mirror = mirror;
    int ifm, ism, ig1, ig2;
    assert_int_equal(cj_scene_add_material(sc, &fm, &ifm), CJ_OK);
    assert_int_equal(cj_scene_add_material(sc, &sm, &ism), CJ_OK);
    cj_geometry g;
    memset(&g, 0, sizeof g);
    g.kind = CJ_GEOM_PLANAR;
    assert_int_equal(cj_planar_patch_init(&g.u.planar, cj_v3_add(shift, cj_v3(-20 * s, 0, 20 * s)),
                                          cj_v3(40 * s, 0, 0), cj_v3(0, 0, -40 * s)),
                     CJ_OK);
    assert_int_equal(cj_scene_add_geometry(sc, &g, &ig1), CJ_OK);
    memset(&g, 0, sizeof g);
    g.kind = CJ_GEOM_SPHERE;
    g.u.sphere.center = cj_v3_add(shift, cj_v3(0, 2 * s, 0));
    g.u.sphere.radius = s;
    assert_int_equal(cj_scene_add_geometry(sc, &g, &ig2), CJ_OK);
    cj_node n1 = cj_node_defaults(ig1, ifm), n2 = cj_node_defaults(ig2, ism);
    assert_int_equal(cj_scene_add_node(sc, &n1, NULL), CJ_OK);
    assert_int_equal(cj_scene_add_node(sc, &n2, NULL), CJ_OK);
    return sc;
}

static cj_render_image *trace(const cj_scene *sc, int threads, int tile, unsigned planes,
                              cj_stage_report *rep) {
    cj_render_options o = cj_render_options_defaults();
    o.threads = threads;
    o.tile_size = tile;
    cj_render_image *img = NULL;
    cj_status st = cj_render_trace(sc, &o, planes, NULL, &img, rep);
    if (st) fprintf(stderr, "trace: %s\n", cj_last_error());
    assert_int_equal(st, CJ_OK);
    return img;
}

static void test_only_called_effects(void **state) {
    (void)state;
    cj_scene *sc = sphere_scene(1.0, cj_v3(0, 0, 0), 0.7, 41);
    cj_stage_report rep;
    cj_render_image *img = trace(sc, 2, 0, 0, &rep);
    const cj_stage *refl = cj_stage_report_find(&rep, "reflection_rays");
    const cj_stage *shadow = cj_stage_report_find(&rep, "shadow_rays");
    const cj_stage *refr = cj_stage_report_find(&rep, "refraction_rays");
    assert_non_null(refl);
    assert_true(refl->ran && refl->in > 0);
    assert_true(shadow->ran && shadow->in > 0);
    assert_true(!refr->ran && refr->in == 0);
    uint64_t with = refl->in;
    cj_render_image_destroy(img);
    /* Remove the mirror: no reflection ray at all. */
    cj_scene_material_mut(sc, 1)->mirror = 0.0;
    img = trace(sc, 2, 0, 0, &rep);
    refl = cj_stage_report_find(&rep, "reflection_rays");
    assert_true(!refl->ran && refl->in == 0);
    cj_render_image_destroy(img);
    /* No material receives shadows: no shadow ray; then no light casts them. */
    cj_scene_material_mut(sc, 0)->receives_shadows = 0;
    cj_scene_material_mut(sc, 1)->receives_shadows = 0;
    img = trace(sc, 2, 0, 0, &rep);
    assert_true(cj_stage_report_find(&rep, "shadow_rays")->in == 0);
    cj_render_image_destroy(img);
    cj_scene_material_mut(sc, 0)->receives_shadows = 1;
    cj_scene_light_mut(sc, 1)->casts_shadows = 0;
    img = trace(sc, 2, 0, 0, &rep);
    assert_true(cj_stage_report_find(&rep, "shadow_rays")->in == 0);
    cj_render_image_destroy(img);
    /* A transmissive sphere: refraction rays appear. */
    cj_scene_material_mut(sc, 1)->transmission = 0.9;
    img = trace(sc, 2, 0, 0, &rep);
    refr = cj_stage_report_find(&rep, "refraction_rays");
    assert_true(refr->ran && refr->in > 0);
    cj_render_image_destroy(img);
    cj_scene_destroy(sc);
    printf("  mirror 0.7: %llu reflection rays; mirror 0: none (stage left out); no receiving "
           "material / no casting light: no shadow ray; transmission 0.9: refraction rays\n",
           (unsigned long long)with);
}

/* Radiance of the floor point seen through pixel (x, y), by hand; -1 if the ray misses the floor
 * or hits the sphere first. shadowed receives whether the segment to the light crosses it. */
static double floor_by_hand(const cj_scene *sc, int w, int x, int y, double s, cj_vec3 shift,
                            int *shadowed, double *amb) {
    cj_vec3 o, d;
    assert_int_equal(cj_camera_ray(cj_scene_get_camera(sc), w, w, x + 0.5, y + 0.5, &o, &d), CJ_OK);
    if (!(d.y < 0)) return -1;
    double t = (shift.y - o.y) / d.y;
    cj_vec3 p = cj_v3_add(o, cj_v3_scale(d, t));
    if (fabs(p.x - shift.x) > 19.9 * s || fabs(p.z - shift.z) > 19.9 * s)
        return -1; /* off the floor */
    cj_vec3 c = cj_v3_add(shift, cj_v3(0, 2 * s, 0));
    /* the sphere in front of the floor point? */
    cj_vec3 oc = cj_v3_sub(o, c);
    double b = cj_v3_dot(oc, d), cc = cj_v3_dot(oc, oc) - s * s;
    if (b * b - cc > 0 && -b - sqrt(b * b - cc) < t) return -1;
    cj_vec3 L = cj_v3_add(shift, cj_v3(0, 10 * s, 0));
    cj_vec3 l = cj_v3_sub(L, p);
    double ll = cj_v3_norm(l);
    cj_vec3 lu = cj_v3_scale(l, 1 / ll);
    cj_vec3 pc = cj_v3_sub(p, c);
    double bb = cj_v3_dot(pc, lu), c2 = cj_v3_dot(pc, pc) - s * s;
    *shadowed = bb * bb - c2 > 0 && -bb - sqrt(bb * bb - c2) > 0;
    *amb = 0.2 * 0.5; /* r_a I_a, red channel (c_r = 1) */
    return *amb + 0.8 * lu.y;
}

static void test_shadows_and_scales(void **state) {
    (void)state;
    const double scales[3] = {1.0, 1e6, 1e-6};
    const int w = 41;
    for (int si = 0; si < 3; si++) {
        double s = scales[si];
        cj_vec3 shift = cj_v3(3 * s, 0.0, -2 * s);
        cj_scene *sc = sphere_scene(s, shift, 0.0, w);
        cj_render_image *img = trace(sc, 2, 0, 0, NULL);
        long lit = 0, dark = 0, bad = 0;
        double worst = 0;
        for (int y = 0; y < w; y++)
            for (int x = 0; x < w; x++) {
                int sh;
                double amb;
                double e = floor_by_hand(sc, w, x, y, s, shift, &sh, &amb);
                if (e < 0) continue;
                double got = img->rgba[4 * ((size_t)y * w + x)];
                double expect = sh ? amb : e;
                double err = fabs(got - expect);
                if (err > 1e-5) {
                    bad++;
                    if (bad < 5)
                        fprintf(stderr, "scale %g pixel (%d, %d): %g, by hand %g (shadowed %d)\n",
                                s, x, y, got, expect, sh);
                }
                if (err > worst) worst = err;
                if (sh)
                    dark++;
                else
                    lit++;
            }
        printf("  scale %g (shifted by %g): %ld lit floor pixels, %ld shadowed (ambient only); "
               "largest difference from Phong by hand %.2e\n",
               s, 3 * s, lit, dark, worst);
        assert_true(dark > 10 && lit > 100);
        assert_true(bad <= 2); /* at most a pixel or two on the shadow's rim */
        cj_render_image_destroy(img);
        cj_scene_destroy(sc);
    }
}

/* A floor under a roof 1e-6 above it, the light above the roof: nothing may leak. */
static void test_no_leak_under_thin_roof(void **state) {
    (void)state;
    const double h = 1e-6;
    cj_scene *sc;
    assert_int_equal(cj_scene_create(NULL, &sc), CJ_OK);
    cj_camera cam = cj_camera_defaults();
    cam.eye = cj_v3(0, 0.5 * h, 0);
    cam.gaze = cj_v3(0, -0.2 * h, -1e-6);
    cam.near = -1e-9;
    cam.far = -10;
    cam.fov_y = 1.0;
    assert_int_equal(cj_scene_set_camera(sc, &cam), CJ_OK);
    cj_scene_settings set = cj_scene_settings_defaults();
    set.width = set.height = 48;
    assert_int_equal(cj_scene_set_settings(sc, &set), CJ_OK);
    cj_light amb = cj_light_defaults(CJ_LIGHT_AMBIENT), pt = cj_light_defaults(CJ_LIGHT_POINT);
    amb.intensity = 0.5;
    pt.position = cj_v3(0, 1, 0);
    cj_light dir = cj_light_defaults(CJ_LIGHT_DIRECTIONAL);
    dir.direction = cj_v3(0.3, -1, 0.2);
    assert_int_equal(cj_scene_add_light(sc, &amb, NULL), CJ_OK);
    assert_int_equal(cj_scene_add_light(sc, &pt, NULL), CJ_OK);
    assert_int_equal(cj_scene_add_light(sc, &dir, NULL), CJ_OK);
    cj_material m = cj_material_defaults();
    m.color = cj_rgb_make(1, 1, 1);
    m.ka = 0.2;
    m.ks = 0.0;
    m.two_sided = 1;
    int im, ig1, ig2;
    assert_int_equal(cj_scene_add_material(sc, &m, &im), CJ_OK);
    cj_geometry g;
    memset(&g, 0, sizeof g);
    g.kind = CJ_GEOM_PLANAR;
    assert_int_equal(
        cj_planar_patch_init(&g.u.planar, cj_v3(-1, 0, 1), cj_v3(2, 0, 0), cj_v3(0, 0, -2)), CJ_OK);
    assert_int_equal(cj_scene_add_geometry(sc, &g, &ig1), CJ_OK);
    assert_int_equal(
        cj_planar_patch_init(&g.u.planar, cj_v3(-1, h, 1), cj_v3(2, 0, 0), cj_v3(0, 0, -2)), CJ_OK);
    assert_int_equal(cj_scene_add_geometry(sc, &g, &ig2), CJ_OK);
    cj_node n1 = cj_node_defaults(ig1, im), n2 = cj_node_defaults(ig2, im);
    assert_int_equal(cj_scene_add_node(sc, &n1, NULL), CJ_OK);
    assert_int_equal(cj_scene_add_node(sc, &n2, NULL), CJ_OK);
    cj_render_image *img = trace(sc, 2, 0, CJ_IMAGE_IDS, NULL);
    long floor_px = 0, roof_px = 0, leaks = 0;
    for (int i = 0; i < 48 * 48; i++) {
        if (img->ids[i] == 1) floor_px++;
        if (img->ids[i] == 2) roof_px++;
        if (img->ids[i] && fabsf(img->rgba[4 * i] - 0.1f) > 1e-6f) leaks++;
    }
    printf("  thin roof 1e-6 above the floor: %ld floor and %ld roof pixels, %ld brighter than "
           "ambient (leaks)\n",
           floor_px, roof_px, leaks);
    assert_true(floor_px > 100 && roof_px > 100);
    assert_int_equal(leaks, 0);
    cj_render_image_destroy(img);
    cj_scene_destroy(sc);
}

static void test_refract(void **state) {
    (void)state;
    /* Snell: n1 sin θ1 = n2 sin θ2 for a sweep of angles; TIR past the critical angle. */
    int tir = 0, ok = 0;
    for (int i = 0; i < 90; i++) {
        double th = i * 3.14159265358979323846 / 180.0;
        cj_vec3 d = cj_v3(sin(th), -cos(th), 0), n = cj_v3(0, 1, 0), t;
        assert_true(cj_trace_refract(d, n, 1.0, 1.5, &t));
        assert_true(fabs(sin(th) - 1.5 * t.x) < 1e-12 && t.y < 0);
        if (cj_trace_refract(d, n, 1.5, 1.0, &t)) {
            assert_true(1.5 * sin(th) <= 1.0 + 1e-12);
            assert_true(fabs(1.5 * sin(th) - t.x) < 1e-12);
            ok++;
        } else {
            assert_true(1.5 * sin(th) > 1.0 - 1e-12);
            tir++;
        }
    }
    printf("  Snell's law on 90 angles both ways; glass -> air: %d refracted, %d totally "
           "reflected (critical angle 41.8 deg)\n",
           ok, tir);
    assert_int_equal(ok, 42);
}

static void test_threads_bit_identical(void **state) {
    (void)state;
    cj_scene *sc = sphere_scene(1.0, cj_v3(0, 0, 0), 0.5, 48);
    cj_scene_material_mut(sc, 1)->transmission = 0.5;
    cj_scene_material_mut(sc, 1)->glossiness = 50;
    cj_light area = cj_light_defaults(CJ_LIGHT_AREA);
    area.position = cj_v3(-1, 8, -1);
    area.edge_u = cj_v3(2, 0, 0);
    area.edge_v = cj_v3(0, 0, 2);
    area.intensity = 0.5;
    assert_int_equal(cj_scene_add_light(sc, &area, NULL), CJ_OK);
    cj_scene_settings set = *cj_scene_get_settings(sc);
    set.spp = 4;
    assert_int_equal(cj_scene_set_settings(sc, &set), CJ_OK);
    cj_render_image *ref = trace(sc, 1, 0, CJ_IMAGE_IDS, NULL);
    const int th[4] = {2, 3, 2, 1}, tile[4] = {0, 8, 32, 8};
    for (int k = 0; k < 4; k++) {
        cj_render_image *img = trace(sc, th[k], tile[k], CJ_IMAGE_IDS, NULL);
        assert_memory_equal(ref->rgba, img->rgba, sizeof(float) * 4 * 48 * 48);
        assert_memory_equal(ref->ids, img->ids, sizeof(uint32_t) * 48 * 48);
        cj_render_image_destroy(img);
    }
    /* A different seed changes the picture (sampling is really used). */
    cj_render_options o = cj_render_options_defaults();
    o.use_seed = 1;
    o.seed = 12345;
    cj_render_image *other = NULL;
    assert_int_equal(cj_render_trace(sc, &o, 0, NULL, &other, NULL), CJ_OK);
    assert_true(memcmp(ref->rgba, other->rgba, sizeof(float) * 4 * 48 * 48) != 0);
    cj_render_image_destroy(other);
    /* Plain random sampling: another image, still the same for any thread count. */
    cj_trace_options to = {1, 0, 0, 0, 0};
    cj_render_image *r1 = NULL, *r2 = NULL;
    o = cj_render_options_defaults();
    o.threads = 1;
    assert_int_equal(cj_render_trace_with_options(sc, &o, &to, 0, NULL, &r1, NULL), CJ_OK);
    o.threads = 2;
    o.tile_size = 8;
    assert_int_equal(cj_render_trace_with_options(sc, &o, &to, 0, NULL, &r2, NULL), CJ_OK);
    assert_memory_equal(r1->rgba, r2->rgba, sizeof(float) * 4 * 48 * 48);
    assert_true(memcmp(ref->rgba, r1->rgba, sizeof(float) * 4 * 48 * 48) != 0);
    cj_render_image_destroy(r1);
    cj_render_image_destroy(r2);
    cj_render_image_destroy(ref);
    cj_scene_destroy(sc);
    printf("  spp 4, area light, glossy mirror, glass: image and ids bit-identical for 1, 2, 3 "
           "threads and tiles 8 and 32 (also with plain random sampling); another seed gives "
           "another image\n");
}

/* Signature image vs the rasterizer's ids: differing pixels must lie in the one-pixel band
 * around a silhouette (a neighbour shows another object in the traced or the rasterized
 * image). */
static void compare_ids(const char *name, const cj_scene *sc, int W, int H) {
    cj_render_options o = cj_render_options_defaults();
    o.width = W;
    o.height = H;
    o.spp = 1;
    o.threads = 2;
    cj_render_image *tr = NULL, *ra = NULL;
    assert_int_equal(cj_render_trace(sc, &o, CJ_IMAGE_IDS, NULL, &tr, NULL), CJ_OK);
    assert_int_equal(cj_render_raster(sc, &o, CJ_IMAGE_IDS, NULL, &ra, NULL), CJ_OK);
    /* the rasterizer's id buffer holds opaque surfaces only (transparent ones are blended over
     * it): compare where the first traced hit is opaque */
    unsigned char see_through[256] = {0};
    for (size_t i = 0; i < cj_scene_node_count(sc); i++) {
        const cj_node *nd = cj_scene_node(sc, (int)i);
        if (nd->material >= 0 && nd->id < 256 && cj_scene_material(sc, nd->material)->opacity < 1.0)
            see_through[nd->id] = 1;
    }
    long differ = 0, outside_band = 0, objects = 0, skipped = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            uint32_t a = tr->ids[y * W + x], b = ra->ids[y * W + x];
            if (a < 256 && see_through[a]) {
                skipped++;
                continue;
            }
            if (a) objects++;
            if (a == b) continue;
            differ++;
            /* on a silhouette: some neighbour in either image shows another object */
            int edge = 0;
            for (int dy = -1; dy <= 1; dy++)
                for (int dx = -1; dx <= 1; dx++) {
                    int xx = x + dx, yy = y + dy;
                    if (xx < 0 || yy < 0 || xx >= W || yy >= H) continue;
                    if (tr->ids[yy * W + xx] != a || ra->ids[yy * W + xx] != b) edge = 1;
                }
            if (!edge && ++outside_band <= 3) {
                fprintf(stderr, "%s pixel (%d, %d): traced id %u, raster id %u\n", name, x, y, a,
                        b);
                for (int dy = 2; dy >= -2; dy--) {
                    for (int dx = -2; dx <= 2; dx++) {
                        int xx = x + dx, yy = y + dy;
                        if (xx < 0 || yy < 0 || xx >= W || yy >= H) continue;
                        fprintf(stderr, " %u/%u", tr->ids[yy * W + xx], ra->ids[yy * W + xx]);
                    }
                    fprintf(stderr, "\n");
                }
            }
        }
    printf("  signature vs rasterizer ids, %s (%dx%d): %ld opaque object pixels (%ld behind a "
           "transparent first hit not compared), %ld differ, all within the one-pixel silhouette "
           "band except %ld\n",
           name, W, H, objects, skipped, differ, outside_band);
    assert_int_equal(outside_band, 0);
    assert_true(differ < objects / 20);
    cj_render_image_destroy(tr);
    cj_render_image_destroy(ra);
}

static double patch_max_err(const cj_stage_report *rep) {
    const cj_stage *s = cj_stage_report_find(rep, "patch_rays");
    assert_non_null(s);
    for (int i = 0; i < s->extra_count; i++)
        if (strcmp(s->extra[i].key, "max_err") == 0) return s->extra[i].value;
    fail_msg("patch_rays has no max_err");
    return 0;
}

/* cj_trace_options.patch_tolerance: out-of-range values are refused with no image; a coarse
 * tolerance really loosens the patch intersection (a larger distance to the ray reached). */
static void test_patch_tolerance_option(void **state) {
    (void)state;
    cj_scene *sc;
    assert_int_equal(cj_trace_demo_scene(CJ_TEAPOT_PATH, NULL, &sc), CJ_OK);
    cj_render_options o = cj_render_options_defaults();
    o.width = 40;
    o.height = 30;
    o.spp = 1;
    o.threads = 1;
    const double bad[4] = {-1e-7, NAN, 2.0, INFINITY};
    for (int k = 0; k < 4; k++) {
        cj_trace_options to = {0, bad[k], 0, 0, 0};
        cj_render_image *img = NULL;
        assert_int_equal(cj_render_trace_with_options(sc, &o, &to, 0, NULL, &img, NULL),
                         CJ_ERR_RANGE);
        assert_null(img);
    }
    double err[2];
    const double tol[2] = {1e-2, 0};
    for (int k = 0; k < 2; k++) {
        cj_trace_options to = {0, tol[k], 0, 0, 0};
        cj_render_image *img = NULL;
        cj_stage_report rep;
        assert_int_equal(cj_render_trace_with_options(sc, &o, &to, 0, NULL, &img, &rep), CJ_OK);
        err[k] = patch_max_err(&rep);
        cj_render_image_destroy(img);
    }
    /* the teapot's box diagonal is ~8: tolerance 1e-2 allows ~0.08, the default ~8e-7 */
    assert_true(err[0] > 1e2 * err[1]);
    assert_true(err[0] < 0.2);
    cj_scene_destroy(sc);
    printf("  patch_tolerance: -1e-7, NaN, 2, inf refused (CJ_ERR_RANGE, no image); largest "
           "distance to the ray reached on the demo teapot %.3g at 1e-2 vs %.3g by default\n",
           err[0], err[1]);
}

static void test_signature_vs_raster(void **state) {
    (void)state;
    cj_scene *sc;
    assert_int_equal(cj_trace_demo_scene(CJ_TEAPOT_PATH, NULL, &sc), CJ_OK);
    compare_ids("demo", sc, 200, 150);
    cj_scene_destroy(sc);
    /* shipped scenes whose textures are procedural (no image files to load) */
    const char *files[3] = {"quadrics.json", "raytrace.json", "transparent.json"};
    cj_scene_json_options jo = {CJ_TEAPOT_PATH};
    for (int i = 0; i < 3; i++) {
        char path[512];
        snprintf(path, sizeof path, "%s/%s", CJ_SCENES_DIR, files[i]);
        cj_status st = cj_scene_load_json_with_options(path, &jo, NULL, &sc);
        if (st) fprintf(stderr, "%s\n", cj_last_error());
        assert_int_equal(st, CJ_OK);
        compare_ids(files[i], sc, 160, 120);
        cj_scene_destroy(sc);
    }
}

static void test_cosine_sampler(void **state) {
    (void)state;
    const int n = 100000;
    uint64_t z = 0x5eedc05ull;
    printf("  seed 0x%llx\n", (unsigned long long)z);
    cj_vec3 nrm = cj_v3_normalize(cj_v3(0.3, -0.8, 0.52));
    double sum = 0.0, sum2 = 0.0;
    int above = 0;
    for (int i = 0; i < n; i++) {
        double u[2];
        for (int k = 0; k < 2; k++) {
            z = z * 6364136223846793005ull + 1442695040888963407ull;
            u[k] = (double)(z >> 11) * 0x1p-53;
        }
        cj_vec3 d = cj_trace_cosine_sample(nrm, u[0], u[1]);
        assert_true(fabs(cj_v3_dot(d, d) - 1.0) < 1e-12);
        double c = cj_v3_dot(d, nrm);
        assert_true(c >= -1e-15);
        sum += c;
        sum2 += c * c;
        above += c > 0.5;
    }
    /* pdf cos θ / π: E[cos θ] = 2/3, Var = 1/2 − 4/9 = 1/18; P(cos θ > 1/2) = 1 − 1/4 = 3/4 */
    double mean = sum / n, se = sqrt(1.0 / 18.0 / n);
    double frac = (double)above / n, se2 = sqrt(0.75 * 0.25 / n);
    printf("  cosine sampler, %d samples: mean cos %.5f (2/3, %.1f se), P(cos > 1/2) %.5f (3/4, "
           "%.1f se), mean cos^2 %.5f (1/2)\n",
           n, mean, fabs(mean - 2.0 / 3.0) / se, frac, fabs(frac - 0.75) / se2, sum2 / n);
    assert_true(fabs(mean - 2.0 / 3.0) < 4 * se);
    assert_true(fabs(frac - 0.75) < 4 * se2);
}

static cj_render_image *trace_ind(const cj_scene *sc, int threads, int tile, int indirect,
                                  cj_stage_report *rep) {
    cj_render_options o = cj_render_options_defaults();
    o.threads = threads;
    o.tile_size = tile;
    cj_trace_options to = {0, 0, indirect, 0, 0};
    cj_render_image *img = NULL;
    assert_int_equal(cj_render_trace_with_options(sc, &o, &to, 0, NULL, &img, rep), CJ_OK);
    return img;
}

static void test_indirect(void **state) {
    (void)state;
    const int W = 32;
    /* Off: the default image bit for bit, no indirect ray. */
    cj_scene *sc = sphere_scene(1.0, cj_v3(0, 0, 0), 0.5, W);
    cj_stage_report rep;
    cj_render_image *ref = trace(sc, 1, 0, 0, NULL);
    cj_render_image *off = trace_ind(sc, 2, 8, 0, &rep);
    assert_memory_equal(ref->rgba, off->rgba, sizeof(float) * 4 * W * W);
    const cj_stage *ind = cj_stage_report_find(&rep, "indirect_rays");
    assert_non_null(ind);
    assert_true(!ind->ran && ind->in == 0);
    cj_render_image_destroy(off);
    /* On: more light on the floor near the sphere, same image for any thread count. */
    cj_render_image *on1 = trace_ind(sc, 1, 0, 8, &rep);
    ind = cj_stage_report_find(&rep, "indirect_rays");
    assert_true(ind->ran && ind->in > 0 && ind->out > 0);
    uint64_t cast = ind->in, hits = ind->out;
    assert_true(memcmp(ref->rgba, on1->rgba, sizeof(float) * 4 * W * W) != 0);
    const int th[3] = {2, 3, 2}, tile[3] = {0, 8, 32};
    for (int k = 0; k < 3; k++) {
        cj_render_image *img = trace_ind(sc, th[k], tile[k], 8, NULL);
        assert_memory_equal(on1->rgba, img->rgba, sizeof(float) * 4 * W * W);
        cj_render_image_destroy(img);
    }
    cj_render_image_destroy(on1);
    cj_render_image_destroy(ref);
    /* Out of range. */
    cj_render_options o = cj_render_options_defaults();
    cj_trace_options bad = {0, 0, -1, 0, 0};
    cj_render_image *none = NULL;
    assert_int_equal(cj_render_trace_with_options(sc, &o, &bad, 0, NULL, &none, NULL),
                     CJ_ERR_RANGE);
    assert_null(none);
    /* Furnace: the floor alone (sphere hidden), lit only by a zero ambient, under a sky of
     * radiance B: every indirect ray escapes, so each floor pixel is kd c B exactly. */
    cj_scene_node_mut(sc, 1)->visible = 0;
    cj_scene_light_mut(sc, 0)->intensity = 0.0;
    cj_scene_light_mut(sc, 1)->intensity = 0.0;
    cj_scene_settings set = *cj_scene_get_settings(sc);
    set.background = cj_rgb_make(0.5, 0.25, 1.0);
    assert_int_equal(cj_scene_set_settings(sc, &set), CJ_OK);
    const int N = 5;
    cj_render_image *fur = trace_ind(sc, 2, 0, N, &rep);
    ind = cj_stage_report_find(&rep, "indirect_rays");
    const cj_stage *prim = cj_stage_report_find(&rep, "primary_rays");
    assert_true(prim->out > 0);
    assert_true(ind->in == prim->out * (uint64_t)N);
    assert_true(ind->out == 0);
    const cj_material *fm = cj_scene_material(sc, 0);
    double want[3] = {fm->kd * fm->color.r * 0.5, fm->kd * fm->color.g * 0.25,
                      fm->kd * fm->color.b * 1.0};
    int floor_px = 0;
    double worst = 0.0;
    for (int i = 0; i < W * W; i++) {
        const float *p = fur->rgba + 4 * i;
        if (p[3] == 0.0f) continue;
        floor_px++;
        for (int k = 0; k < 3; k++) worst = fmax(worst, fabs(p[k] - want[k]));
    }
    assert_int_equal((uint64_t)floor_px, prim->out);
    assert_true(worst < 1e-6);
    cj_render_image_destroy(fur);
    cj_scene_destroy(sc);
    printf("  indirect 0: default image bit for bit, stage left out; indirect 8: %llu rays (%llu "
           "hit), bit-identical for 1, 2, 3 threads; furnace: %d floor pixels x %d = %llu rays, "
           "|pixel - kd c B| <= %.2g\n",
           (unsigned long long)cast, (unsigned long long)hits, floor_px, N,
           (unsigned long long)ind->in, worst);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_only_called_effects),
        cmocka_unit_test(test_shadows_and_scales),
        cmocka_unit_test(test_no_leak_under_thin_roof),
        cmocka_unit_test(test_refract),
        cmocka_unit_test(test_threads_bit_identical),
        cmocka_unit_test(test_signature_vs_raster),
        cmocka_unit_test(test_patch_tolerance_option),
        cmocka_unit_test(test_cosine_sampler),
        cmocka_unit_test(test_indirect),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

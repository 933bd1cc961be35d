/* The rasterizer pipeline (issue 8, "Only the effects the scene calls for", shading, textures,
 * transparency, overlays): a stage runs iff the scene uses its feature; removing a feature
 * that changes nothing (a light of zero intensity, a white texture) gives a bit-identical
 * image; the image is bit-identical for threads 1/2/3 and tile sizes 8/64/100; a lit sphere's
 * Phong shading matches the formula evaluated by hand on the exact sphere; the sphere's
 * silhouette matches the exact projected conic except within one pixel; two interpenetrating
 * transparent quads blend in the exact per-pixel depth order (the BSP split; a painter's order
 * by centroid fails it); the screen-space tessellation bound. Scenes are built from code. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "casteljau/render.h"
#include "render_scenes.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int ran(const cj_stage_report *r, const char *name) {
    const cj_stage *s = cj_stage_report_find(r, name);
    assert_non_null(s);
    return s->ran;
}

/* Renders and returns the report; the image is freed unless wanted. */
static cj_render_image *render(const cj_scene *s, const cj_render_options *o, unsigned planes,
                               cj_stage_report *rep) {
    cj_render_image *img = NULL;
    cj_stage_report local;
    cj_status st = cj_render_raster(s, o, planes, NULL, &img, rep ? rep : &local);
    if (st) fprintf(stderr, "render failed: %s\n", cj_last_error());
    assert_int_equal(st, CJ_OK);
    return img;
}

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
    cj_render_options o = cj_render_options_default();
    o.width = 96;
    o.height = 72;
    o.spp = 1;
    rs_sphere_scene sc;
    rs_sphere(&sc, 0);
    /* no lights, one-sided opaque untextured sphere */
    expect_stages(sc.s, &o, "tessellate_surfaces,cull_backfaces,shade_unlit");
    /* an ambient light alone: still unlit (no normals) */
    cj_light amb = cj_light_default(CJ_LIGHT_AMBIENT);
    amb.intensity = 0.3;
    assert_int_equal(cj_scene_add_light(sc.s, &amb, NULL), CJ_OK);
    expect_stages(sc.s, &o, "tessellate_surfaces,cull_backfaces,shade_unlit");
    /* a point light: Phong (the default material) with normals */
    cj_light pt = cj_light_default(CJ_LIGHT_POINT);
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
    cj_texture ck = cj_texture_default(CJ_TEX_CHECKER);
    int ti;
    assert_int_equal(cj_scene_add_texture(sc.s, &ck, &ti), CJ_OK);
    m = cj_scene_material_mut(sc.s, sc.mat);
    m->texture = ti;
    expect_stages(sc.s, &o,
                  "tessellate_surfaces,cull_backfaces,vertex_normals,texture_coords,shade_phong,"
                  "texture");
    /* a trilinear image texture: mip-maps too */
    cj_texture im = cj_texture_default(CJ_TEX_IMAGE);
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

/* CJ_RENDER_DUMP=dir writes the images a test looks at as PPM (sRGB), to look at them. */
static void dump(const cj_render_image *img, const char *name) {
    const char *dir = getenv("CJ_RENDER_DUMP");
    if (!dir) return;
    char path[512];
    snprintf(path, sizeof path, "%s/%s.ppm", dir, name);
    FILE *f = fopen(path, "wb");
    if (!f) return;
    uint8_t *px = malloc((size_t)img->width * (size_t)img->height * 4);
    if (px && cj_render_image_to_srgb8(img, px, 0) == CJ_OK) {
        fprintf(f, "P6\n%d %d\n255\n", img->width, img->height);
        for (int y = img->height - 1; y >= 0; --y)
            for (int x = 0; x < img->width; ++x)
                fwrite(px + 4 * ((size_t)y * img->width + x), 1, 3, f);
    }
    free(px);
    fclose(f);
}

static int same_image(const cj_render_image *a, const cj_render_image *b) {
    size_t n = (size_t)a->width * (size_t)a->height;
    return a->width == b->width && a->height == b->height &&
           !memcmp(a->rgba, b->rgba, n * 4 * sizeof(float));
}

static void test_neutral_features_bit_identical(void **state) {
    (void)state;
    cj_render_options o = cj_render_options_default();
    o.width = 120;
    o.height = 90;
    o.spp = 4;
    rs_sphere_scene sc;
    rs_sphere(&sc, 1);
    cj_render_image *ref = render(sc.s, &o, 0, NULL);
    /* a point light and an ambient light of zero intensity */
    cj_light z = cj_light_default(CJ_LIGHT_POINT);
    z.intensity = 0.0;
    z.position = cj_v3(-3, 1, 2);
    assert_int_equal(cj_scene_add_light(sc.s, &z, NULL), CJ_OK);
    z = cj_light_default(CJ_LIGHT_AMBIENT);
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
        cj_texture t = cj_texture_default(f < 3 ? CJ_TEX_IMAGE : CJ_TEX_CHECKER);
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
    cj_render_options o = cj_render_options_default();
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

/* The primary ray through pixel point (px, py) of the scene's camera, computed here from the
 * seed's camera frame (w = -g/|g|, u = t x w / |t x w|, v = w x u), not by the renderer. */
static void ray_through(const cj_camera *c, int W, int H, double px, double py, cj_vec3 *dir) {
    cj_vec3 w = cj_v3_normalize(cj_v3_scale(c->gaze, -1.0));
    cj_vec3 u = cj_v3_normalize(cj_v3_cross(c->up, w)), v = cj_v3_cross(w, u);
    double ty = tan(0.5 * c->fov_y), tx = ty * W / H;
    double nx = 2.0 * px / W - 1.0, ny = 2.0 * py / H - 1.0;
    *dir = cj_v3_normalize(cj_v3_add(cj_v3_scale(w, -1.0),
                                     cj_v3_add(cj_v3_scale(u, nx * tx), cj_v3_scale(v, ny * ty))));
}

/* Nearest hit of the ray e + t d with the sphere |x - c| = r (t > 0), or 0. */
static int hit_sphere(cj_vec3 e, cj_vec3 d, cj_vec3 c, double r, cj_vec3 *p) {
    cj_vec3 oc = cj_v3_sub(e, c);
    double b = cj_v3_dot(oc, d), q = cj_v3_dot(oc, oc) - r * r, disc = b * b - q;
    if (disc <= 0.0) return 0;
    double t = -b - sqrt(disc);
    if (t <= 0.0) return 0;
    *p = cj_v3_add(e, cj_v3_scale(d, t));
    return 1;
}

static void test_phong_by_hand(void **state) {
    (void)state;
    rs_sphere_scene sc;
    rs_sphere(&sc, 1);
    cj_render_options o = cj_render_options_default();
    o.width = o.height = 200;
    o.spp = 1;
    double worst = 0.0;
    int checked = 0;
    for (int pass = 0; pass < 2; ++pass) {
        if (pass == 1) { /* a spot light too: cone 9 degrees, exponent 4 */
            cj_light sp = cj_light_default(CJ_LIGHT_SPOT);
            sp.position = cj_v3(-2, 2, 3);
            sp.direction = cj_v3(2, -2, -3);
            sp.spot_angle = 9.0 * 3.14159265358979323846 / 180.0;
            sp.spot_exponent = 4.0;
            sp.intensity = 0.7;
            assert_int_equal(cj_scene_add_light(sc.s, &sp, NULL), CJ_OK);
        }
        cj_render_image *img = render(sc.s, &o, 0, NULL);
        dump(img, pass ? "phong_spot" : "phong");
        const cj_camera *cam = cj_scene_camera(sc.s);
        const cj_material *m = cj_scene_material(sc.s, sc.mat);
        for (int y = 2; y < o.height; y += 4)
            for (int x = 3; x < o.width; x += 4) {
                cj_vec3 d, p;
                ray_through(cam, o.width, o.height, x + 0.5, y + 0.5, &d);
                if (!hit_sphere(cam->eye, d, cj_v3(0, 0, 0), 1.0, &p)) continue;
                cj_vec3 n = p, v = cj_v3_normalize(cj_v3_sub(cam->eye, p));
                if (cj_v3_dot(n, v) < 0.3) continue; /* away from the silhouette */
                double L[3] = {0, 0, 0}, cr[3] = {m->color.r, m->color.g, m->color.b};
                double cp[3] = {m->specular.r, m->specular.g, m->specular.b};
                int skip = 0;
                for (size_t i = 0; i < cj_scene_light_count(sc.s); ++i) {
                    const cj_light *l = cj_scene_light(sc.s, (int)i);
                    double I[3] = {l->color.r * l->intensity, l->color.g * l->intensity,
                                   l->color.b * l->intensity};
                    if (l->kind == CJ_LIGHT_AMBIENT) {
                        for (int k = 0; k < 3; ++k) L[k] += cr[k] * m->ka * I[k];
                        continue;
                    }
                    cj_vec3 ld = l->kind == CJ_LIGHT_DIRECTIONAL
                                     ? cj_v3_normalize(cj_v3_scale(l->direction, -1.0))
                                     : cj_v3_normalize(cj_v3_sub(l->position, p));
                    double f = 1.0;
                    if (l->kind == CJ_LIGHT_SPOT) { /* (cos θ)^e inside the cone, 0 outside */
                        double ct = -cj_v3_dot(cj_v3_normalize(l->direction), ld);
                        if (fabs(ct - cos(l->spot_angle)) < 0.01) skip = 1; /* the cone's rim */
                        f = ct >= cos(l->spot_angle) ? pow(ct, l->spot_exponent) : 0.0;
                    }
                    cj_vec3 h = cj_v3_normalize(cj_v3_add(ld, v));
                    double nl = fmax(0.0, cj_v3_dot(n, ld)), nh = fmax(0.0, cj_v3_dot(n, h));
                    for (int k = 0; k < 3; ++k)
                        L[k] += f * (cr[k] * m->kd * I[k] * nl +
                                     cp[k] * m->ks * I[k] * pow(nh, m->alpha));
                }
                if (skip) continue;
                const float *px = img->rgba + 4 * ((size_t)y * (size_t)o.width + (size_t)x);
                for (int k = 0; k < 3; ++k) {
                    double e = fabs(px[k] - L[k]);
                    if (e > worst) worst = e;
                    if (e > 4e-3)
                        fail_msg("pass %d, pixel (%d, %d) channel %d: rendered %.6f, Phong "
                                 "formula %.6f",
                                 pass, x, y, k, px[k], L[k]);
                }
                assert_float_equal(px[3], 1.0, 0.0);
                ++checked;
            }
        cj_render_image_destroy(img);
    }
    assert_true(checked > 600);
    cj_scene_destroy(sc.s);
    printf("test_phong_by_hand: %d pixels of a lit sphere (ambient, point, directional, then also "
           "a spot light; alpha 32) vs the Phong formula on the exact sphere: max |error| %.2e "
           "(limit 4e-3)\n",
           checked, worst);
}

static void test_sphere_silhouette(void **state) {
    (void)state;
    int mism_total = 0, pixels = 0;
    for (int off = 0; off < 2; ++off) {
        rs_sphere_scene sc;
        rs_sphere(&sc, 0);
        cj_vec3 centre = off ? cj_v3(1.1, -0.7, -0.5) : cj_v3(0, 0, 0);
        cj_scene_node_mut(sc.s, sc.node)->local.translate = centre;
        cj_render_options o = cj_render_options_default();
        o.width = 211;
        o.height = 157;
        o.spp = 1;
        cj_render_image *img = render(sc.s, &o, CJ_IMAGE_IDS, NULL);
        const cj_camera *cam = cj_scene_camera(sc.s);
        /* exact classification of every pixel centre: the ray meets the sphere */
        uint8_t *in = malloc((size_t)o.width * (size_t)o.height);
        assert_non_null(in);
        for (int y = 0; y < o.height; ++y)
            for (int x = 0; x < o.width; ++x) {
                cj_vec3 d, p;
                ray_through(cam, o.width, o.height, x + 0.5, y + 0.5, &d);
                in[y * o.width + x] = (uint8_t)hit_sphere(cam->eye, d, centre, 1.0, &p);
            }
        /* centred: the silhouette is the circle of radius f_px r / sqrt(d^2 - r^2) */
        double fpx = o.height / (2.0 * tan(0.5 * cam->fov_y));
        double rho = fpx * 1.0 / sqrt(25.0 - 1.0);
        int mism = 0;
        for (int y = 0; y < o.height; ++y)
            for (int x = 0; x < o.width; ++x) {
                int got = img->ids[y * o.width + x] != 0, want = in[y * o.width + x];
                if (got == want) continue;
                ++mism;
                if (!off) {
                    double s = hypot(x + 0.5 - 0.5 * o.width, y + 0.5 - 0.5 * o.height);
                    if (fabs(s - rho) >= 1.0)
                        fail_msg("pixel (%d, %d) %.3f px from the exact silhouette", x, y,
                                 fabs(s - rho));
                } else {
                    int near = 0; /* the exact boundary passes within the 3x3 neighbourhood */
                    for (int dy = -1; dy <= 1; ++dy)
                        for (int dx = -1; dx <= 1; ++dx) {
                            int xx = x + dx, yy = y + dy;
                            if (xx >= 0 && yy >= 0 && xx < o.width && yy < o.height &&
                                in[yy * o.width + xx] != want)
                                near = 1;
                        }
                    if (!near) fail_msg("pixel (%d, %d) misclassified away from the conic", x, y);
                }
            }
        mism_total += mism;
        pixels += o.width * o.height;
        free(in);
        cj_render_image_destroy(img);
        cj_scene_destroy(sc.s);
    }
    /* orthographic: the silhouette is the circle of radius r / (pixel size) */
    rs_sphere_scene sc;
    rs_sphere(&sc, 0);
    cj_camera cam = *cj_scene_camera(sc.s);
    cam.projection = CJ_PROJ_ORTHOGRAPHIC;
    cam.ortho_height = 3.0;
    rs_check(cj_scene_set_camera(sc.s, &cam));
    cj_render_options o = cj_render_options_default();
    o.width = 200;
    o.height = 150;
    o.spp = 1;
    cj_render_image *img = render(sc.s, &o, CJ_IMAGE_IDS, NULL);
    double px = cam.ortho_height / o.height;
    int mism = 0;
    for (int y = 0; y < o.height; ++y)
        for (int x = 0; x < o.width; ++x) {
            double X = (x + 0.5 - 0.5 * o.width) * px, Y = (y + 0.5 - 0.5 * o.height) * px;
            int want = hypot(X, Y) < 1.0, got = img->ids[y * o.width + x] != 0;
            if (want == got) continue;
            ++mism;
            if (fabs(hypot(X, Y) - 1.0) >= px)
                fail_msg("orthographic: pixel (%d, %d) %.3f px from the exact silhouette", x, y,
                         fabs(hypot(X, Y) - 1.0) / px);
        }
    cj_render_image_destroy(img);
    cj_scene_destroy(sc.s);
    printf("test_sphere_silhouette: %d pixels of a centred and an off-axis sphere, %d differ "
           "from the exact projected conic, all within 1 px of it; orthographic: %d of %d\n",
           pixels, mism_total, mism, o.width * o.height);
}

/* Two transparent quads crossing along the y axis: z = x/2 and z = -x/2. Left of the crossing
 * one is in front, right of it the other, so no order of whole quads is right everywhere. */
static void test_bsp_interpenetrating(void **state) {
    (void)state;
    cj_scene *s;
    rs_check(cj_scene_create(NULL, &s));
    cj_camera cam = cj_camera_default();
    cam.fov_y = 40.0 * 3.14159265358979323846 / 180.0;
    rs_check(cj_scene_set_camera(s, &cam));
    const double sl[2] = {0.5, -0.5};
    const cj_rgb col[2] = {{1, 0, 0}, {0, 0, 1}};
    for (int q = 0; q < 2; ++q) {
        cj_material m = cj_material_default();
        m.color = col[q];
        m.opacity = 0.5;
        m.two_sided = 1;
        int mi, gi;
        rs_check(cj_scene_add_material(s, &m, &mi));
        cj_geometry g;
        memset(&g, 0, sizeof g);
        g.kind = CJ_GEOM_PLANAR;
        rs_check(cj_planar_patch_init(&g.u.planar, cj_v3(-1, -1, -sl[q]), cj_v3(2, 0, 2 * sl[q]),
                                      cj_v3(0, 2, 0)));
        rs_check(cj_scene_add_geometry(s, &g, &gi));
        cj_node n = cj_render_node(gi, mi);
        rs_check(cj_scene_add_node(s, &n, NULL));
    }
    cj_render_options o = cj_render_options_default();
    o.width = 160;
    o.height = 120;
    o.spp = 1;
    cj_stage_report rep;
    cj_render_image *img = render(s, &o, 0, &rep);
    dump(img, "bsp");
    const cj_stage *st = cj_stage_report_find(&rep, "sort_transparent");
    assert_true(st->ran);
    int counts[2] = {0, 0};
    for (int y = 0; y < o.height; ++y)
        for (int x = 0; x < o.width; ++x) {
            cj_vec3 d;
            ray_through(&cam, o.width, o.height, x + 0.5, y + 0.5, &d);
            double t[2];
            int ok = 1;
            for (int q = 0; q < 2; ++q) { /* plane z = sl x: e_z + t d_z = sl (e_x + t d_x) */
                t[q] = (sl[q] * cam.eye.x - cam.eye.z) / (d.z - sl[q] * d.x);
                cj_vec3 p = cj_v3_add(cam.eye, cj_v3_scale(d, t[q]));
                if (fabs(p.x) > 0.97 || fabs(p.y) > 0.97 || fabs(p.x) < 0.03) ok = 0;
            }
            if (!ok) continue;
            int far = t[0] > t[1] ? 0 : 1, near = 1 - far;
            double c[4] = {0, 0, 0, 0}, fc[3] = {col[far].r, col[far].g, col[far].b},
                   nc[3] = {col[near].r, col[near].g, col[near].b};
            for (int k = 0; k < 3; ++k) c[k] += 0.5 * (fc[k] - c[k]);
            c[3] += 0.5 * (1 - c[3]);
            for (int k = 0; k < 3; ++k) c[k] += 0.5 * (nc[k] - c[k]);
            c[3] += 0.5 * (1 - c[3]);
            const float *px = img->rgba + 4 * ((size_t)y * (size_t)o.width + (size_t)x);
            for (int k = 0; k < 4; ++k)
                if (fabs(px[k] - c[k]) > 1e-6)
                    fail_msg(
                        "pixel (%d, %d): channel %d is %.4f, back-to-front blending gives %.4f", x,
                        y, k, px[k], c[k]);
            ++counts[near];
        }
    assert_true(counts[0] > 500 && counts[1] > 500);
    assert_true(st->extra_count > 0 && st->extra[0].value > 0); /* bsp_splits */
    double cut = st->extra[0].value;
    cj_render_image_destroy(img);
    cj_scene_destroy(s);
    /* a lone convex transparent object: the painter's test accepts its order, nothing is cut */
    rs_sphere_scene sc;
    rs_sphere(&sc, 1);
    cj_scene_material_mut(sc.s, sc.mat)->opacity = 0.5;
    cj_render_image_destroy(render(sc.s, &o, 0, &rep));
    st = cj_stage_report_find(&rep, "sort_transparent");
    assert_true(st->ran && st->in > 100 && st->out == st->in);
    assert_true(st->extra[0].value == 0.0);
    cj_scene_destroy(sc.s);
    printf("test_bsp_interpenetrating: a lone transparent sphere (%llu triangles): painter's "
           "order exact, 0 cuts\n",
           (unsigned long long)st->in);
    printf("test_bsp_interpenetrating: %d pixels with the red quad in front, %d with the blue "
           "one, each blended far-to-near exactly (BSP cut %g triangles)\n",
           counts[0], counts[1], cut);
}

static size_t tris_of(const cj_stage_report *r, const char *stage) {
    return (size_t)cj_stage_report_find(r, stage)->out;
}

static void test_view_tessellation(void **state) {
    (void)state;
    rs_sphere_scene sc;
    rs_sphere(&sc, 0);
    rs_add_patch_quad(sc.s, sc.mat, -2.0, 0);
    cj_render_options o = cj_render_options_default();
    o.width = 320;
    o.height = 240;
    const double tols[3] = {1.0, 0.25, 0.1};
    size_t prev_p = 0, prev_s = 0;
    for (int i = 0; i < 3; ++i) {
        o.tol_px = tols[i];
        cj_stage_report rep;
        cj_render_image_destroy(render(sc.s, &o, 0, &rep));
        const cj_stage *p = cj_stage_report_find(&rep, "tessellate_patches");
        const cj_stage *q = cj_stage_report_find(&rep, "tessellate_surfaces");
        double bp = p->extra[1].value, bs = q->extra[0].value;
        assert_true(bp > 0.0 && bp <= tols[i]);
        assert_true(bs > 0.0 && bs <= tols[i]);
        assert_true(tris_of(&rep, "tessellate_patches") > prev_p);
        assert_true(tris_of(&rep, "tessellate_surfaces") > prev_s);
        prev_p = tris_of(&rep, "tessellate_patches");
        prev_s = tris_of(&rep, "tessellate_surfaces");
        printf("test_view_tessellation: tol %.2f px: patch %zu triangles (bound %.3f px), sphere "
               "%zu triangles (bound %.3f px)\n",
               tols[i], prev_p, bp, prev_s, bs);
    }
    /* the same sphere farther away gets fewer triangles; out of view, none */
    o.tol_px = 0.25;
    cj_stage_report near, far, gone;
    cj_render_image_destroy(render(sc.s, &o, 0, &near));
    cj_scene_node_mut(sc.s, sc.node)->local.translate = cj_v3(0, 0, -20);
    cj_render_image_destroy(render(sc.s, &o, 0, &far));
    cj_scene_node_mut(sc.s, sc.node)->local.translate = cj_v3(0, 0, 30);
    cj_render_image_destroy(render(sc.s, &o, 0, &gone));
    size_t tn = tris_of(&near, "tessellate_surfaces"), tf = tris_of(&far, "tessellate_surfaces");
    assert_true(tf * 4 < tn);
    assert_int_equal(tris_of(&gone, "tessellate_surfaces"), 0);
    cj_scene_destroy(sc.s);
    printf("test_view_tessellation: sphere at distance 5: %zu triangles, at 25: %zu, behind the "
           "camera: 0\n",
           tn, tf);
}

static void test_edge_cases(void **state) {
    (void)state;
    cj_scene *s;
    rs_check(cj_scene_create(NULL, &s));
    cj_scene_settings set = cj_scene_settings_default();
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
    cj_material m = cj_material_default();
    int mi;
    rs_check(cj_scene_add_material(s, &m, &mi));
    rs_add_curve(s, mi, 0.0);
    img = render(s, NULL, 0, &rep);
    assert_true(ran(&rep, "overlay_lines") &&
                cj_stage_report_find(&rep, "overlay_lines")->out > 20);
    cj_render_image_destroy(img);
    /* refused options and data: nothing is returned */
    cj_render_options o = cj_render_options_default();
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
    cj_texture t = cj_texture_default(CJ_TEX_IMAGE);
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
    cj_node n = cj_render_node(gi, mi);
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
    o = cj_render_options_default();
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
    cj_render_options o = cj_render_options_default();
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
    cj_camera cam = *cj_scene_camera(sc.s);
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
        cmocka_unit_test(test_phong_by_hand),
        cmocka_unit_test(test_sphere_silhouette),
        cmocka_unit_test(test_bsp_interpenetrating),
        cmocka_unit_test(test_view_tessellation),
        cmocka_unit_test(test_edge_cases),
        cmocka_unit_test(test_srgb),
        cmocka_unit_test(test_tessellation_cache),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

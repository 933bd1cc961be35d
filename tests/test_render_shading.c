/* The rasterizer's pictures against exact references (issue 8): a lit sphere's Phong shading
 * (ambient, point, directional and spot lights) vs the formula evaluated by hand on the exact
 * sphere; the sphere's silhouette vs the exact projected conic (perspective, off-axis,
 * orthographic) except within one pixel; two interpenetrating transparent quads blended in the
 * exact per-pixel depth order (the BSP cut; no order of whole quads is right) and a lone
 * convex transparent object needing no cut; the screen-space tessellation bound. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "render_test_util.h"

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
    cj_render_options o = cj_render_options_defaults();
    o.width = o.height = 200;
    o.spp = 1;
    double worst = 0.0;
    int checked = 0;
    for (int pass = 0; pass < 2; ++pass) {
        if (pass == 1) { /* a spot light too: cone 9 degrees, exponent 4 */
            cj_light sp = cj_light_defaults(CJ_LIGHT_SPOT);
            sp.position = cj_v3(-2, 2, 3);
            sp.direction = cj_v3(2, -2, -3);
            sp.spot_angle = 9.0 * 3.14159265358979323846 / 180.0;
            sp.spot_exponent = 4.0;
            sp.intensity = 0.7;
            assert_int_equal(cj_scene_add_light(sc.s, &sp, NULL), CJ_OK);
        }
        cj_render_image *img = render(sc.s, &o, 0, NULL);
        dump(img, pass ? "phong_spot" : "phong");
        const cj_camera *cam = cj_scene_get_camera(sc.s);
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
        cj_render_options o = cj_render_options_defaults();
        o.width = 211;
        o.height = 157;
        o.spp = 1;
        cj_render_image *img = render(sc.s, &o, CJ_IMAGE_IDS, NULL);
        const cj_camera *cam = cj_scene_get_camera(sc.s);
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
    cj_camera cam = *cj_scene_get_camera(sc.s);
    cam.projection = CJ_PROJ_ORTHOGRAPHIC;
    cam.ortho_height = 3.0;
    rs_check(cj_scene_set_camera(sc.s, &cam));
    cj_render_options o = cj_render_options_defaults();
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
    cj_camera cam = cj_camera_defaults();
    cam.fov_y = 40.0 * 3.14159265358979323846 / 180.0;
    rs_check(cj_scene_set_camera(s, &cam));
    const double sl[2] = {0.5, -0.5};
    const cj_rgb col[2] = {{1, 0, 0}, {0, 0, 1}};
    for (int q = 0; q < 2; ++q) {
        cj_material m = cj_material_defaults();
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
        cj_node n = cj_node_defaults(gi, mi);
        rs_check(cj_scene_add_node(s, &n, NULL));
    }
    cj_render_options o = cj_render_options_defaults();
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
    cj_render_options o = cj_render_options_defaults();
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

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_phong_by_hand),
        cmocka_unit_test(test_sphere_silhouette),
        cmocka_unit_test(test_bsp_interpenetrating),
        cmocka_unit_test(test_view_tessellation),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

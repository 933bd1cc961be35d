/* Cross-check of the rasterizer against VTK (OpenGL through Mesa llvmpipe, offscreen under a
 * private Xvfb) and against exact oracles:
 *  - a tessellated sphere drawn by VTK: its mask agrees with the EXACT projected conic of the
 *    sphere (pixel centres classified in 256-bit MPFR) except within one pixel of the conic, its
 *    depth lies in the exact interval the inscribed mesh allows (between the sphere and the
 *    largest ball inside the mesh), its radiance within 1/255 of exact Lambert + ambient,
 *    perspective and orthographic; the mask shifted by 2 px must fail the same check;
 *  - our cj_render_raster against VTK drawing the same triangles (cj_render_scene_mesh): a
 *    sphere, six quadrics (perspective Phong; orthographic flat), the teapot, a floor cut by
 *    the near and far planes; with and without specular highlights (VTK's specular line
 *    replaced by ours). Object ids agree everywhere
 *    except within a one-pixel band around silhouettes (0 differing pixels outside it), depth
 *    agrees to float rounding plus the vertex-snapping allowance off the band, colours within
 *    CJ_COLOUR_TOL per channel, vtkImageDifference's thresholded error 0; and our sphere's mask
 *    against the exact conic;
 *  - the .vtp export and the refusals of the VTK renderer.
 * The test starts its own Xvfb (tests/support/xvfb.c), so it runs where there is no display.
 * CJ_VTK_RENDER_DUMP=<dir> writes the pictures as PNG for a look. */
#define _POSIX_C_SOURCE 200809L
#define _DEFAULT_SOURCE
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "casteljau/image_io.h"
#include "casteljau/patchset.h"
#include "casteljau/render.h"
#include "casteljau/quadric.h"
#include "casteljau/tessellate.h"
#include "casteljau/vtk_render.h"
#include "vtk_render_check.h"
#include "vtk_render_test.h"
#include "xvfb.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* ---- our renderer against VTK, same triangles ------------------------------------------------ */

/* Diffuse-only lighting (ambient + one directional + one point light, no specular: VTK's
 * specular term is Phong's (r.v)^alpha, ours Blinn's (n.h)^alpha), Phong shading, 1 spp. */
static int g_point_light = 1; /* new_scene adds the point light */

static cj_scene *new_scene(const cj_camera *cam, int w, int h) {
    cj_scene *sc = NULL;
    assert_int_equal(cj_scene_create(NULL, &sc), CJ_OK);
    assert_int_equal(cj_scene_set_camera(sc, cam), CJ_OK);
    cj_scene_settings set = cj_scene_settings_defaults();
    set.width = w;
    set.height = h;
    set.spp = 1;
    set.tol_px = 0.25;
    set.background = cj_rgb_make(0.05, 0.05, 0.1);
    assert_int_equal(cj_scene_set_settings(sc, &set), CJ_OK);
    cj_light amb = cj_light_defaults(CJ_LIGHT_AMBIENT);
    amb.intensity = 0.25;
    cj_light dir = cj_light_defaults(CJ_LIGHT_DIRECTIONAL);
    dir.direction = cj_v3(-0.4, -1.0, -0.6);
    dir.intensity = 0.6;
    cj_light pt = cj_light_defaults(CJ_LIGHT_POINT);
    pt.position = cj_v3(4.0, 3.0, 6.0);
    pt.intensity = 0.5;
    pt.color = cj_rgb_make(1.0, 0.9, 0.8);
    assert_int_equal(cj_scene_add_light(sc, &amb, NULL), CJ_OK);
    assert_int_equal(cj_scene_add_light(sc, &dir, NULL), CJ_OK);
    if (g_point_light) assert_int_equal(cj_scene_add_light(sc, &pt, NULL), CJ_OK);
    return sc;
}

static cj_shading g_shading = CJ_SHADE_PHONG; /* the shading add_material gives */
static double g_ks = 0.0;                     /* its specular coefficient */
static unsigned g_vtk_flags = 0;              /* the VTK view's flags */

static int add_material(cj_scene *sc, cj_rgb colour, int two_sided) {
    cj_material m = cj_material_defaults();
    m.color = colour;
    m.ks = g_ks;
    m.alpha = 24.0;
    m.ka = 0.3;
    m.kd = 0.9;
    m.shading = g_shading;
    m.two_sided = two_sided;
    int idx = -1;
    assert_int_equal(cj_scene_add_material(sc, &m, &idx), CJ_OK);
    return idx;
}

static void add_object(cj_scene *sc, const cj_geometry *g, int mat, cj_vec3 at, double turn) {
    int gi = -1;
    assert_int_equal(cj_scene_add_geometry(sc, g, &gi), CJ_OK);
    cj_node n = cj_node_defaults(gi, mat);
    n.local.translate = at;
    n.local.rotation[0] = cos(turn / 2); /* about the axis (1, 1, 0)/sqrt 2 */
    n.local.rotation[1] = sin(turn / 2) / sqrt(2.0);
    n.local.rotation[2] = sin(turn / 2) / sqrt(2.0);
    n.local.rotation[3] = 0.0;
    assert_int_equal(cj_scene_add_node(sc, &n, NULL), CJ_OK);
}

/* Pixel i is in the one-pixel band around a silhouette when its 3 x 3 neighbourhood shows more
 * than one id in our image or in VTK's (object against background, or against another
 * object). */
static int in_band(const cj_check_planes *a, const cj_check_planes *b, int x, int y) {
    const size_t i = (size_t)y * a->w + x;
    for (int dy = -1; dy <= 1; dy++)
        for (int dx = -1; dx <= 1; dx++) {
            const int xx = x + dx, yy = y + dy;
            if (xx < 0 || yy < 0 || xx >= a->w || yy >= a->h) continue;
            const size_t j = (size_t)yy * a->w + xx;
            if (a->ids[j] != a->ids[i] || b->ids[j] != b->ids[i]) return 1;
        }
    return 0;
}

/* Largest pseudodepth step from pixel i to a 4-neighbour covered by the same object. */
static double depth_step(const cj_check_planes *a, int x, int y) {
    const size_t i = (size_t)y * a->w + x;
    double step = 0.0;
    const int nb[4][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
    for (int k = 0; k < 4; k++) {
        const int xx = x + nb[k][0], yy = y + nb[k][1];
        if (xx < 0 || yy < 0 || xx >= a->w || yy >= a->h) continue;
        const size_t j = (size_t)yy * a->w + xx;
        if (a->ids[j] == a->ids[i]) step = fmax(step, fabs((double)a->depth[j] - a->depth[i]));
    }
    return step;
}

static uint8_t to8(float v) {
    return (uint8_t)lrint(255.0 * (v < 0.0f ? 0.0f : v > 1.0f ? 1.0f : v));
}

static void compare_with_vtk(const char *name, cj_scene *sc, int w, int h) {
    cj_render_options opt = cj_render_options_defaults();
    opt.width = w;
    opt.height = h;
    opt.spp = 1;
    cj_render_image *img = NULL;
    cj_status st = cj_render_raster(sc, &opt, CJ_IMAGE_IDS | CJ_IMAGE_DEPTH, NULL, &img, NULL);
    if (st != CJ_OK) fail_msg("%s: cj_render_raster: %s", name, cj_last_error());
    cj_mesh *mesh = NULL;
    if ((st = cj_render_scene_mesh(sc, &opt, NULL, &mesh)) != CJ_OK)
        fail_msg("%s: cj_render_scene_mesh: %s", name, cj_last_error());
    cj_vtk_renderer *r = NULL;
    if ((st = cj_vtk_renderer_create_scene(sc, mesh, w, h, g_vtk_flags, &r)) != CJ_OK)
        fail_msg("%s: VTK: %s", name, cj_last_error());
    cj_check_planes vtk, ours = {w, h, img->rgba, img->ids, img->depth};
    cj_check_planes_alloc(&vtk, w, h);
    cj_vtk_frame frame = {vtk.rgba, vtk.ids, vtk.depth};
    if ((st = cj_vtk_renderer_draw(r, &frame, NULL)) != CJ_OK)
        fail_msg("%s: VTK draw: %s", name, cj_last_error());
    cj_vtk_renderer_destroy(r);
    char pic[128];
    snprintf(pic, sizeof pic, "%s_ours", name);
    dump_png(pic, w, h, ours.rgba);
    snprintf(pic, sizeof pic, "%s_vtk", name);
    dump_png(pic, w, h, vtk.rgba);

    size_t covered = 0, differ = 0, differ_out = 0, band = 0;
    size_t dchecked = 0, dbeyond = 0, cchecked = 0, cbeyond = 0;
    double dmax = 0.0, dmax_rel = 0.0, cmax = 0.0;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            const size_t i = (size_t)y * w + x;
            covered += ours.ids[i] != 0;
            const int b = in_band(&ours, &vtk, x, y);
            band += b;
            if (ours.ids[i] != vtk.ids[i]) {
                differ++;
                if (!b) {
                    differ_out++;
                    if (differ_out <= 5)
                        printf("  %s: pixel (%d, %d): our id %u, VTK's %u, outside the band\n",
                               name, x, y, (unsigned)ours.ids[i], (unsigned)vtk.ids[i]);
                }
                continue;
            }
            if (b || !ours.ids[i]) continue;
            /* depth: the same plane sampled at the same pixel centre by both; they differ by
             * float/24-bit rounding and by the 1/256-px vertex snapping of either rasterizer,
             * which moves a plane by at most its step per pixel / 128 */
            const double step = depth_step(&ours, x, y);
            const double dd = fabs((double)ours.depth[i] - vtk.depth[i]);
            const double tol = CJ_DEPTH_TOL + step / 128.0;
            dchecked++;
            dbeyond += dd > tol;
            dmax = fmax(dmax, dd);
            if (step > 0) dmax_rel = fmax(dmax_rel, dd / step);
            /* colour, in 8-bit linear units as VTK writes them */
            for (int c = 0; c < 3; c++) {
                const double cd =
                    fabs((double)to8(ours.rgba[4 * i + c]) - 255.0 * vtk.rgba[4 * i + c]);
                cmax = fmax(cmax, cd);
                if (cd > CJ_COLOUR_TOL && cbeyond < 8)
                    printf("  %s: pixel (%d, %d) channel %d: ours %.4f, VTK %.4f\n", name, x, y, c,
                           (double)ours.rgba[4 * i + c], (double)vtk.rgba[4 * i + c]);
                cbeyond += cd > CJ_COLOUR_TOL;
            }
            cchecked++;
        }
    printf("%s: %dx%d, %zu triangles; ours covers %zu pixels; ids differ at %zu pixels, %zu of "
           "them outside the one-pixel silhouette band (%zu pixels)\n",
           name, w, h, mesh->triangle_count, covered, differ, differ_out, band);
    printf("%s: depth at %zu pixels off the band: max |ours - VTK| %.3g pseudodepth (%.3g of the "
           "pixel-to-pixel step), %zu beyond %.0e + step/128\n",
           name, dchecked, dmax, dmax_rel, dbeyond, CJ_DEPTH_TOL);
    printf("%s: colour (%s, 8-bit linear) at %zu pixels: max |ours - VTK| %.0f, %zu channels "
           "beyond %d\n",
           name, g_ks > 0 ? "ambient + diffuse + specular" : "ambient + diffuse", cchecked, cmax,
           cbeyond, CJ_COLOUR_TOL);

    /* vtkImageDifference on the pictures, background included */
    uint8_t *a8 = malloc((size_t)w * h * 4), *b8 = malloc((size_t)w * h * 4);
    assert_non_null(a8);
    assert_non_null(b8);
    /* Inside the silhouette band the two pictures may show different surfaces (or, for
     * two-sided materials, normals flipped by different rules at grazing angles): the band
     * takes VTK's pixels in both, so the difference measures the shading everywhere else. */
    for (size_t i = 0; i < (size_t)w * h * 4; i++) {
        const int x = (int)(i / 4 % (size_t)w), y = (int)(i / 4 / (size_t)w);
        b8[i] = to8(vtk.rgba[i]);
        a8[i] = in_band(&ours, &vtk, x, y) ? b8[i] : to8(ours.rgba[i]);
    }
    double err = 0.0, terr = 0.0;
    assert_int_equal(cj_vtk_image_difference(a8, b8, w, h, CJ_IMAGEDIFF_THRESHOLD, &err, &terr),
                     CJ_OK);
    printf("%s: vtkImageDifference (threshold %d): error %.4g, thresholded error %.4g (must be "
           "<= %g)\n",
           name, CJ_IMAGEDIFF_THRESHOLD, err, terr, CJ_IMAGEDIFF_MAX);
    free(a8);
    free(b8);

    assert_true(covered > 0);
    assert_int_equal(differ_out, 0);
    assert_int_equal(dbeyond, 0);
    assert_int_equal(cbeyond, 0);
    assert_true(terr <= CJ_IMAGEDIFF_MAX);
    cj_check_planes_free(&vtk);
    cj_mesh_destroy(mesh);
    cj_render_image_destroy(img);
}

static cj_camera view_camera(cj_vec3 eye, cj_vec3 at, cj_vec3 up, double fov_deg) {
    cj_camera cam = cj_camera_defaults();
    cam.eye = eye;
    cam.gaze = cj_v3_sub(at, eye);
    cam.up = up;
    cam.near = -0.5;
    cam.far = -50.0;
    cam.fov_y = fov_deg * M_PI / 180.0;
    return cam;
}

static void test_ours_vs_vtk_sphere(void **state) {
    (void)state;
    const int w = 400, h = 300;
    const cj_camera cam = view_camera(cj_v3(0.8, 1.1, 4.5), cj_v3(0, 0, 0), cj_v3(0.1, 1, 0), 40);
    cj_scene *sc = new_scene(&cam, w, h);
    cj_geometry g = {0};
    g.kind = CJ_GEOM_SPHERE;
    g.u.sphere.center = cj_v3(0.3, -0.2, 0.1);
    g.u.sphere.radius = 1.0;
    add_object(sc, &g, add_material(sc, cj_rgb_make(0.8, 0.5, 0.3), 0), cj_v3(0, 0, 0), 0.0);
    compare_with_vtk("sphere", sc, w, h);

    /* the scene's drawn mesh exported with its camera */
    {
        cj_render_options o = cj_render_options_defaults();
        cj_mesh *mesh = NULL;
        assert_int_equal(cj_render_scene_mesh(sc, &o, NULL, &mesh), CJ_OK);
        char path[] = "/tmp/cj_vtk_scene_XXXXXX";
        const int fd = mkstemp(path);
        assert_true(fd >= 0);
        close(fd);
        if (cj_vtk_write_scene(path, sc, mesh, 0, 0) != CJ_OK)
            fail_msg("scene export: %s", cj_last_error());
        FILE *f = fopen(path, "rb");
        assert_non_null(f);
        static char text[1 << 14];
        const size_t got = fread(text, 1, sizeof text - 1, f);
        fclose(f);
        text[got] = '\0';
        char want[64];
        snprintf(want, sizeof want, "NumberOfPolys=\"%zu\"", mesh->triangle_count);
        assert_non_null(strstr(text, want));
        printf("sphere: cj_vtk_write_scene wrote the %zu drawn triangles with the camera\n",
               mesh->triangle_count);
        remove(path);
        cj_mesh_destroy(mesh);
    }

    /* our sphere's silhouette against the exact projected conic */
    cj_render_options opt = cj_render_options_defaults();
    opt.width = w;
    opt.height = h;
    opt.spp = 1;
    cj_render_image *img = NULL;
    assert_int_equal(cj_render_raster(sc, &opt, CJ_IMAGE_IDS | CJ_IMAGE_DEPTH, NULL, &img, NULL),
                     CJ_OK);
    cj_sphere_oracle orc;
    cj_sphere_oracle_init(&orc, &cam, w, h, g.u.sphere.center, g.u.sphere.radius);
    cj_silhouette_stats sil;
    cj_silhouette_check(&orc, img->ids, &sil);
    printf("sphere: OUR mask vs the exact projected conic: %zu pixels differ, farthest %.3f px "
           "from the conic, %zu beyond 1 px\n",
           sil.differ, sil.max_dist, sil.beyond);
    assert_int_equal(sil.beyond, 0);
    cj_sphere_oracle_clear(&orc);
    cj_render_image_destroy(img);
    cj_scene_destroy(sc);

    /* orthographic, non-square: ours against VTK and against the exact (circular) outline */
    cj_camera oc = view_camera(cj_v3(-2.0, 0.5, 3.0), cj_v3(0, 0, 0), cj_v3(0, 1, 0), 40);
    oc.projection = CJ_PROJ_ORTHOGRAPHIC;
    oc.ortho_height = 3.0;
    const int ow = 240, oh = 300;
    sc = new_scene(&oc, ow, oh);
    add_object(sc, &g, add_material(sc, cj_rgb_make(0.8, 0.5, 0.3), 0), cj_v3(0, 0, 0), 0.0);
    compare_with_vtk("sphere_ortho", sc, ow, oh);
    opt.width = ow;
    opt.height = oh;
    assert_int_equal(cj_render_raster(sc, &opt, CJ_IMAGE_IDS, NULL, &img, NULL), CJ_OK);
    cj_sphere_oracle_init(&orc, &oc, ow, oh, g.u.sphere.center, g.u.sphere.radius);
    cj_silhouette_check(&orc, img->ids, &sil);
    printf("sphere_ortho: OUR mask vs the exact outline: %zu pixels differ, farthest %.3f px, "
           "%zu beyond 1 px\n",
           sil.differ, sil.max_dist, sil.beyond);
    assert_int_equal(sil.beyond, 0);
    cj_sphere_oracle_clear(&orc);
    cj_render_image_destroy(img);
    cj_scene_destroy(sc);
}

static void quadrics_case(const char *name, const cj_camera *cam, int w, int h) {
    cj_scene *sc = new_scene(cam, w, h);
    cj_quadric q[6];
    assert_int_equal(cj_quadric_ellipsoid(&q[0], 1.0, 0.7, 0.5), CJ_OK);
    assert_int_equal(cj_quadric_hyperboloid1(&q[1], 0.5, 0.5, 0.6, -1.0, 1.0), CJ_OK);
    assert_int_equal(cj_quadric_hyperboloid2(&q[2], 0.5, 0.5, 0.5, 0, 1.2), CJ_OK);
    assert_int_equal(cj_quadric_cone(&q[3], 0.6, 0.6, 1.0, 0.0, 1.2), CJ_OK);
    assert_int_equal(cj_quadric_paraboloid(&q[4], 0.6, 0.6, 1.1), CJ_OK);
    assert_int_equal(cj_quadric_hyperbolic_paraboloid(&q[5], 1.0, 1.0, -0.9, 0.9, -0.9, 0.9),
                     CJ_OK);
    const cj_vec3 at[6] = {cj_v3(-2.4, 0, -1.3),   cj_v3(0, 0, -1.5),      cj_v3(2.4, -0.3, -1.5),
                           cj_v3(-2.4, -0.5, 1.3), cj_v3(-0.2, -0.8, 1.0), cj_v3(2.2, 0, 1.2)};
    const cj_rgb col[6] = {cj_rgb_make(0.9, 0.3, 0.2), cj_rgb_make(0.3, 0.8, 0.3),
                           cj_rgb_make(0.2, 0.4, 0.9), cj_rgb_make(0.9, 0.8, 0.2),
                           cj_rgb_make(0.7, 0.3, 0.8), cj_rgb_make(0.3, 0.8, 0.8)};
    for (int k = 0; k < 6; k++) {
        cj_geometry g = {0};
        g.kind = CJ_GEOM_QUADRIC;
        g.u.quadric = q[k];
        add_object(sc, &g, add_material(sc, col[k], k != 0), at[k], 0.4 + 0.3 * k);
    }
    compare_with_vtk(name, sc, w, h);
    cj_scene_destroy(sc);
}

static void test_ours_vs_vtk_quadrics(void **state) {
    (void)state;
    const cj_camera cam = view_camera(cj_v3(0.8, 4.0, 6.2), cj_v3(0, -0.3, 0), cj_v3(0, 1, 0), 50);
    quadrics_case("quadrics", &cam, 480, 360);
}

/* Orthographic projection and flat shading (one normal per triangle in both renderers). */
static void test_ours_vs_vtk_quadrics_ortho_flat(void **state) {
    (void)state;
    cj_camera cam = view_camera(cj_v3(-1.0, 5.0, 5.0), cj_v3(0, -0.3, 0), cj_v3(0, 1, 0), 50);
    cam.projection = CJ_PROJ_ORTHOGRAPHIC;
    cam.ortho_height = 6.0;
    g_shading = CJ_SHADE_FLAT;
    quadrics_case("quadrics_ortho_flat", &cam, 400, 320);
    g_shading = CJ_SHADE_PHONG;
}

static void teapot_case(const char *name) {
    const int w = 512, h = 384;
    const cj_camera cam =
        view_camera(cj_v3(5.5, -7.0, 5.0), cj_v3(0.0, 0.0, 1.4), cj_v3(0, 0, 1), 38);
    cj_scene *sc = new_scene(&cam, w, h);
    cj_patchset *set = NULL;
    if (cj_patchset_load_bpt(CJ_TEAPOT_PATH, NULL, &set) != CJ_OK) fail_msg("%s", cj_last_error());
    cj_geometry g = {0};
    g.kind = CJ_GEOM_PATCHES;
    g.u.patches.count = set->count;
    g.u.patches.patches = set->patches;
    /* Two-sided, as the demo draws it (the teapot's patch set is open): both renderers light
     * the side each triangle shows, chosen by the triangle's own facing. Flipping by the
     * interpolated normal instead lit the wrong side of a few pixels near the silhouettes. */
    add_object(sc, &g, add_material(sc, cj_rgb_make(0.8, 0.6, 0.4), 1), cj_v3(0, 0, 0), 0.0);
    cj_patchset_destroy(set);
    compare_with_vtk(name, sc, w, h);
    cj_scene_destroy(sc);
}

static void test_ours_vs_vtk_teapot(void **state) {
    (void)state;
    teapot_case("teapot");
}

/* Clipping: a floor reaching from behind the eye to beyond the far plane (two big triangles
 * cut by both planes, in homogeneous coordinates by ours, by OpenGL's clipper in VTK) under a
 * sphere, seen at a grazing angle. */
static void test_ours_vs_vtk_clipping(void **state) {
    (void)state;
    const int w = 400, h = 300;
    cj_camera cam = view_camera(cj_v3(0.0, 1.2, 4.0), cj_v3(0.0, 0.3, 0.0), cj_v3(0, 1, 0), 60);
    cam.near = -0.3;
    cam.far = -30.0;
    cj_scene *sc = new_scene(&cam, w, h);
    cj_geometry g = {0};
    g.kind = CJ_GEOM_PLANAR;
    assert_int_equal(
        cj_planar_patch_init(&g.u.planar, cj_v3(-20, 0, 40), cj_v3(40, 0, 0), cj_v3(0, 0, -100)),
        CJ_OK);
    add_object(sc, &g, add_material(sc, cj_rgb_make(0.6, 0.7, 0.6), 1), cj_v3(0, 0, 0), 0.0);
    cj_geometry b = {0};
    b.kind = CJ_GEOM_SPHERE;
    b.u.sphere.center = cj_v3(0.4, 0.8, 0.0);
    b.u.sphere.radius = 0.8;
    add_object(sc, &b, add_material(sc, cj_rgb_make(0.8, 0.4, 0.3), 0), cj_v3(0, 0, 0), 0.0);
    compare_with_vtk("clipping", sc, w, h);
    cj_scene_destroy(sc);
}

/* Specular highlights (r_s 0.3, alpha 24) with VTK's specular line replaced by ours
 * (CJ_VTK_BLINN_SPECULAR); without the replacement VTK's Phong lobe differs from ours by up to
 * 36/255 on the teapot (11838 channels beyond the tolerance), so the test sees the patch. */
static void test_ours_vs_vtk_specular(void **state) {
    (void)state;
    g_ks = 0.3;
    g_vtk_flags = CJ_VTK_BLINN_SPECULAR;
    teapot_case("teapot_specular");
    const cj_camera cam = view_camera(cj_v3(0.8, 4.0, 6.2), cj_v3(0, -0.3, 0), cj_v3(0, 1, 0), 50);
    quadrics_case("quadrics_specular", &cam, 480, 360);
    /* only directional lights: VTK writes another light loop, which the renderer avoids by
     * adding a negligible positional light (see CJ_VTK_BLINN_SPECULAR) */
    g_point_light = 0;
    quadrics_case("quadrics_specular_directional", &cam, 480, 360);
    g_point_light = 1;
    g_ks = 0.0;
    g_vtk_flags = 0;
}

/* The .vtp export: the scene's triangles with normals, object ids and the camera. */
static void test_export_vtp(void **state) {
    (void)state;
    const cj_vec3 c = cj_v3(0.3, -0.2, 0.1);
    double delta = 0.0;
    cj_mesh *m = sphere_mesh(c, 1.0, 24, 12, &delta);
    cj_material mat = cj_material_defaults();
    const cj_camera cam = view_camera(cj_v3(0.8, 1.1, 4.5), cj_v3(0, 0, 0), cj_v3(0, 1, 0), 40);
    cj_vtk_view view = {cam, NULL, 0, cj_rgb_make(0, 0, 0), 64, 48, 0};
    cj_vtk_object obj[2] = {{m, &mat, 3}, {m, &mat, 9}};
    char path[] = "/tmp/cj_vtk_render_XXXXXX";
    const int fd = mkstemp(path);
    assert_true(fd >= 0);
    close(fd);
    if (cj_vtk_write_scene_mesh(path, &view, obj, 2) != CJ_OK)
        fail_msg("export: %s", cj_last_error());
    FILE *f = fopen(path, "rb");
    assert_non_null(f);
    static char text[1 << 16];
    const size_t got = fread(text, 1, sizeof text - 1, f);
    fclose(f);
    text[got] = '\0'; /* the XML header precedes the raw appended data */
    char want_pts[64], want_polys[64];
    snprintf(want_pts, sizeof want_pts, "NumberOfPoints=\"%zu\"", 2 * m->vertex_count);
    snprintf(want_polys, sizeof want_polys, "NumberOfPolys=\"%zu\"", 2 * m->triangle_count);
    assert_non_null(strstr(text, "<VTKFile type=\"PolyData\""));
    assert_non_null(strstr(text, want_pts));
    assert_non_null(strstr(text, want_polys));
    assert_non_null(strstr(text, "Name=\"object_id\""));
    assert_non_null(strstr(text, "Name=\"Normals\""));
    assert_non_null(strstr(text, "Name=\"camera_eye_gaze_up"));
    printf("export: %s holds %s, %s, object ids, normals and the camera\n", path, want_pts,
           want_polys);
    remove(path);
    /* a bad destination fails with CJ_ERR_IO and leaves nothing */
    assert_int_equal(cj_vtk_write_scene_mesh("/nonexistent-dir/x.vtp", &view, obj, 2), CJ_ERR_IO);
    /* bad input is refused before anything is written */
    cj_vtk_object bad = {m, &mat, 0};
    assert_int_equal(cj_vtk_write_scene_mesh(path, &view, &bad, 1), CJ_ERR_ARGUMENT);
    cj_mesh_destroy(m);
}

/* Refusals: bad views, objects and lights are errors naming the input, never a crash. */
static void test_refusals(void **state) {
    (void)state;
    double delta = 0.0;
    cj_mesh *m = sphere_mesh(cj_v3(0, 0, 0), 1.0, 8, 4, &delta);
    cj_material mat = cj_material_defaults();
    cj_light spot = cj_light_defaults(CJ_LIGHT_SPOT);
    const cj_camera cam = view_camera(cj_v3(0, 0, 5), cj_v3(0, 0, 0), cj_v3(0, 1, 0), 40);
    cj_vtk_view view = {cam, NULL, 0, cj_rgb_make(0, 0, 0), 32, 32, 0};
    cj_vtk_object obj = {m, &mat, 1};
    float depth[32 * 32];
    cj_vtk_frame frame = {NULL, NULL, depth};
    assert_int_equal(cj_vtk_render_mesh(&view, &obj, 0, &frame, NULL), CJ_ERR_ARGUMENT);
    view.width = 0;
    assert_int_equal(cj_vtk_render_mesh(&view, &obj, 1, &frame, NULL), CJ_ERR_ARGUMENT);
    view.width = 32;
    view.camera.near = 1.0; /* near must be negative */
    assert_int_not_equal(cj_vtk_render_mesh(&view, &obj, 1, &frame, NULL), CJ_OK);
    view.camera = cam;
    view.lights = &spot;
    view.light_count = 1;
    assert_int_equal(cj_vtk_render_mesh(&view, &obj, 1, &frame, NULL), CJ_ERR_UNSUPPORTED);
    view.light_count = 0;
    mat.kd = -1.0;
    assert_int_equal(cj_vtk_render_mesh(&view, &obj, 1, &frame, NULL), CJ_ERR_RANGE);
    mat = cj_material_defaults();
    m->positions[4] = NAN;
    assert_int_equal(cj_vtk_render_mesh(&view, &obj, 1, &frame, NULL), CJ_ERR_NONFINITE);
    printf("refusals: no objects, zero width, near >= 0, a spot light, kd < 0, a NaN vertex: "
           "each refused (%s)\n",
           cj_last_error());
    /* no display: an error, not VTK's abort() */
    m->positions[4] = 0.0;
    char *display = strdup(getenv("DISPLAY"));
    assert_non_null(display);
    unsetenv("DISPLAY");
    assert_int_equal(cj_vtk_render_mesh(&view, &obj, 1, &frame, NULL), CJ_ERR_UNSUPPORTED);
    setenv("DISPLAY", ":987", 1); /* (a display nobody serves) */
    assert_int_equal(cj_vtk_render_mesh(&view, &obj, 1, &frame, NULL), CJ_ERR_UNSUPPORTED);
    printf("refusals: without a display: %s\n", cj_last_error());
    setenv("DISPLAY", display, 1);
    free(display);
    assert_int_equal(cj_vtk_render_mesh(&view, &obj, 1, &frame, NULL), CJ_OK);
    cj_mesh_destroy(m);
}

/* GCC names AddressSanitizer builds __SANITIZE_ADDRESS__, clang through __has_feature. */
#if defined(__has_feature)
#if __has_feature(address_sanitizer)
#define CJ_TEST_ASAN 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__) || defined(CJ_TEST_ASAN)
#include <dlfcn.h>
/* Mesa unloads its DRI driver when the last GL context goes, leaving blocks the driver still
 * referenced from its own globals: LeakSanitizer then reports them as leaks of an "<unknown
 * module>". Keeping the driver resident keeps them reachable, so the sanitizer pass reports
 * only real leaks (ours or VTK's). */
static void keep_mesa_driver_loaded(void) {
    static const char *const paths[] = {"/usr/lib/x86_64-linux-gnu/dri/swrast_dri.so",
                                        "/usr/lib/dri/swrast_dri.so",
                                        "/usr/lib64/dri/swrast_dri.so"};
    for (size_t i = 0; i < sizeof paths / sizeof paths[0]; i++)
        if (dlopen(paths[i], RTLD_NOW | RTLD_NODELETE | RTLD_GLOBAL)) return;
}
#else
static void keep_mesa_driver_loaded(void) {}
#endif

int main(void) {
    keep_mesa_driver_loaded();
    const pid_t xvfb = cj_test_xvfb_start(1280, 1280);
    if (xvfb < 0) {
        fprintf(stderr, "test_vtk_render: cannot start Xvfb\n");
        return 1;
    }
    printf("test_vtk_render: private X server on DISPLAY=%s (Mesa llvmpipe)\n", getenv("DISPLAY"));
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_vtk_sphere_perspective),
        cmocka_unit_test(test_vtk_sphere_orthographic),
        cmocka_unit_test(test_ours_vs_vtk_sphere),
        cmocka_unit_test(test_ours_vs_vtk_quadrics),
        cmocka_unit_test(test_ours_vs_vtk_quadrics_ortho_flat),
        cmocka_unit_test(test_ours_vs_vtk_teapot),
        cmocka_unit_test(test_ours_vs_vtk_specular),
        cmocka_unit_test(test_ours_vs_vtk_clipping),
        cmocka_unit_test(test_export_vtp),
        cmocka_unit_test(test_refusals),
    };
    const int failed = cmocka_run_group_tests(tests, NULL, NULL);
    cj_test_xvfb_stop(xvfb);
    return failed;
}

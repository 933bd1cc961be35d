/* Part of test_vtk_render (see test_vtk_render.c): VTK alone against the exact sphere — its
 * mask against the exact projected conic, its depth inside the interval the inscribed mesh
 * allows, its radiance against exact Lambert + ambient — and the helpers both files use. */
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

/* ---- a tessellated sphere whose deviation is known exactly --------------------------------- */

/* A lat-long sphere of nu × nv cells around `c`. *delta receives max over triangles of
 * r − dist(c, plane of the triangle): the mesh is convex and inscribed, so it contains the ball
 * of radius r − delta and lies inside the sphere. */
cj_mesh *sphere_mesh(cj_vec3 c, double r, int nu, int nv, double *delta) {
    cj_quadric q;
    assert_int_equal(cj_quadric_ellipsoid(&q, r, r, r), CJ_OK);
    cj_param_surface s;
    cj_quadric_surface(&q, &s);
    cj_mesh *m = NULL;
    assert_int_equal(cj_mesh_create(NULL, &m), CJ_OK);
    assert_int_equal(cj_tessellate_surface(&s, nu, nv, 1, m, NULL), CJ_OK);
    double worst = 0.0;
    for (size_t t = 0; t < m->triangle_count; t++) {
        const double *a = m->positions + 3 * m->triangles[3 * t];
        const double *b = m->positions + 3 * m->triangles[3 * t + 1];
        const double *p = m->positions + 3 * m->triangles[3 * t + 2];
        cj_vec3 n = cj_v3_cross(cj_v3(b[0] - a[0], b[1] - a[1], b[2] - a[2]),
                                cj_v3(p[0] - a[0], p[1] - a[1], p[2] - a[2]));
        const double len = cj_v3_norm(n);
        if (len == 0.0) continue;
        const double d = fabs(n.x * a[0] + n.y * a[1] + n.z * a[2]) / len;
        if (r - d > worst) worst = r - d;
    }
    for (size_t v = 0; v < m->vertex_count; v++) {
        m->positions[3 * v] += c.x;
        m->positions[3 * v + 1] += c.y;
        m->positions[3 * v + 2] += c.z;
    }
    *delta = worst;
    return m;
}

/* ---- pictures ------------------------------------------------------------------------------- */

void dump_png(const char *name, int w, int h, const float *rgba) {
    const char *dir = getenv("CJ_VTK_RENDER_DUMP");
    if (!dir || !*dir) return;
    uint8_t *px = malloc((size_t)w * h * 4);
    assert_non_null(px);
    for (size_t i = 0; i < (size_t)w * h * 4; i++) {
        double v = rgba[i];
        if (i % 4 != 3) /* linear -> sRGB for viewing */
            v = v <= 0.0031308 ? 12.92 * v : 1.055 * pow(v, 1.0 / 2.4) - 0.055;
        v = v < 0 ? 0 : v > 1 ? 1 : v;
        px[i] = (uint8_t)lround(v * 255.0);
        if (i % 4 == 3) px[i] = 255;
    }
    char path[512];
    snprintf(path, sizeof path, "%s/%s.png", dir, name);
    if (cj_image_write(path, w, h, px, 0) != CJ_OK)
        printf("  (could not write %s: %s)\n", path, cj_last_error());
    else
        printf("  wrote %s\n", path);
    free(px);
}

/* ---- VTK against the exact sphere -------------------------------------------------------------
 */

static void vtk_sphere_case(const char *name, const cj_camera *cam, int w, int h) {
    const cj_vec3 c = cj_v3(0.3, -0.2, 0.1);
    const double r = 1.0;
    double delta = 0.0;
    cj_mesh *m = sphere_mesh(c, r, 192, 96, &delta);
    cj_material mat = cj_material_defaults();
    mat.ks = 0.0;
    cj_light lights[2] = {cj_light_defaults(CJ_LIGHT_DIRECTIONAL),
                          cj_light_defaults(CJ_LIGHT_AMBIENT)};
    lights[0].direction = cj_v3(-1, -1, -2);
    lights[1].intensity = 0.2;
    cj_vtk_view view = {*cam, lights, 2, cj_rgb_make(0, 0, 0), w, h, 0};
    cj_vtk_object obj = {m, &mat, 7};
    cj_check_planes vtk;
    cj_check_planes_alloc(&vtk, w, h);
    cj_vtk_frame frame = {vtk.rgba, vtk.ids, vtk.depth};
    cj_vtk_timing tm;
    cj_status st = cj_vtk_render_mesh(&view, &obj, 1, &frame, &tm);
    if (st != CJ_OK) fail_msg("VTK render: %s", cj_last_error());
    dump_png(name, w, h, vtk.rgba);

    size_t covered = 0, wrong_id = 0;
    for (size_t i = 0; i < (size_t)w * h; i++) {
        covered += vtk.ids[i] != 0;
        wrong_id += vtk.ids[i] != 0 && vtk.ids[i] != 7;
        /* the id pass and the depth buffer must tell the same coverage */
        if ((vtk.ids[i] != 0) != (vtk.depth[i] < 1.0f))
            fail_msg("%s: pixel %zu: id %u but depth %g", name, i, (unsigned)vtk.ids[i],
                     (double)vtk.depth[i]);
    }
    assert_int_equal(wrong_id, 0);
    assert_true(covered > (size_t)w * h / 20);

    cj_sphere_oracle orc;
    cj_sphere_oracle_init(&orc, cam, w, h, c, r);
    cj_silhouette_stats sil;
    cj_silhouette_check(&orc, vtk.ids, &sil);
    printf("%s: VTK %dx%d, sphere of %zu triangles (inscribed, deviation %.3g = %.3f px): "
           "%zu covered pixels; mask vs exact conic: %zu differ, farthest %.3f px from the "
           "conic, %zu beyond 1 px\n",
           name, w, h, m->triangle_count, delta, delta * orc.px_per_unit, covered, sil.differ,
           sil.max_dist, sil.beyond);
    assert_int_equal(sil.beyond, 0);

    cj_depth_interval_stats dep;
    cj_sphere_depth_check(&orc, r - delta, vtk.ids, vtk.depth, &dep);
    printf("%s: depth at %zu pixels whose ray meets the inner ball: outside [sphere, inner "
           "ball] by at most %.3g (pseudodepth; interval width up to %.3g), %zu beyond the "
           "tolerance %.1g\n",
           name, dep.checked, dep.max_excess, dep.max_width, dep.beyond, CJ_DEPTH_TOL);
    assert_true(dep.checked > covered / 2);
    assert_int_equal(dep.beyond, 0);

    /* Lighting: the diffuse + ambient radiance of the exact sphere at the pixel's hit point,
     * c_r (r_a I_a + r_d I max(0, n.l)); VTK's 8-bit value must be within 1/255 of it (0.5/255
     * quantisation; the rest is the interpolated normals of the mesh, < 1e-3 rad off here),
     * where the ray meets the sphere at more than a grazing angle (cos of incidence >= 0.1;
     * closer to the silhouette the mesh is hit up to delta / cos away from the sphere's hit
     * point, where the normal differs). */
    cj_vec3 u, v, wv;
    assert_int_equal(cj_camera_basis(cam, &u, &v, &wv), CJ_OK);
    const cj_vec3 l = cj_v3_normalize(cj_v3_scale(lights[0].direction, -1.0));
    const double lc[3] = {cj_v3_dot(l, u), cj_v3_dot(l, v), cj_v3_dot(l, wv)};
    double worst = 0.0;
    size_t lit = 0, off = 0;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            double hit[3];
            const size_t i = (size_t)y * w + x;
            if (!vtk.ids[i] || !cj_sphere_hit(&orc, x, y, r - delta, hit)) continue;
            assert_true(cj_sphere_hit(&orc, x, y, r, hit));
            /* grazing rays meet the mesh far from the sphere's hit point: skip them */
            double nl = 0.0, nd = 0.0, dd = 0.0;
            for (int k = 0; k < 3; k++) {
                const double n = (hit[k] - orc.C[k]) / r;
                const double dk =
                    cam->projection == CJ_PROJ_ORTHOGRAPHIC ? (k == 2 ? -1.0 : 0.0) : hit[k];
                nl += n * lc[k];
                nd += n * dk;
                dd += dk * dk;
            }
            if (-nd / sqrt(dd) < 0.1) continue;
            const double want = mat.color.r * (mat.ka * lights[1].intensity +
                                               mat.kd * lights[0].intensity * fmax(0.0, nl));
            const double d = fabs(vtk.rgba[4 * i] - want);
            worst = fmax(worst, d);
            off += d > 1.0 / 255.0;
            lit++;
        }
    printf(
        "%s: VTK radiance vs exact Lambert + ambient of the sphere at %zu non-grazing pixels: max "
        "|diff| %.2f/255, %zu beyond 1/255\n",
        name, lit, worst * 255.0, off);
    assert_int_equal(off, 0);

    /* The checker has teeth: the same mask shifted by 2 pixels must fail it. */
    uint32_t *shifted = calloc((size_t)w * h, sizeof *shifted);
    assert_non_null(shifted);
    for (int y = 0; y < h; y++)
        for (int x = 2; x < w; x++) shifted[(size_t)y * w + x] = vtk.ids[(size_t)y * w + x - 2];
    cj_silhouette_stats bad;
    cj_silhouette_check(&orc, shifted, &bad);
    printf("%s: the mask shifted by 2 px: %zu pixels beyond 1 px of the conic (must be > 0)\n",
           name, bad.beyond);
    assert_true(bad.beyond > 0);
    free(shifted);
    cj_sphere_oracle_clear(&orc);
    cj_check_planes_free(&vtk);
    cj_mesh_destroy(m);
}

void test_vtk_sphere_perspective(void **state) {
    (void)state;
    cj_camera cam = cj_camera_defaults();
    cam.eye = cj_v3(0.8, 1.1, 4.5);
    cam.gaze = cj_v3(-0.8, -1.1, -4.5);
    cam.up = cj_v3(0.1, 1, 0);
    cam.near = -1.0;
    cam.far = -20.0;
    cam.fov_y = 40.0 * M_PI / 180.0;
    vtk_sphere_case("vtk_sphere_persp", &cam, 320, 240);
}

void test_vtk_sphere_orthographic(void **state) {
    (void)state;
    cj_camera cam = cj_camera_defaults();
    cam.eye = cj_v3(-2.0, 0.5, 3.0);
    cam.gaze = cj_v3(2.0, -0.5, -3.0);
    cam.projection = CJ_PROJ_ORTHOGRAPHIC;
    cam.ortho_height = 3.0;
    cam.near = -0.5;
    cam.far = -10.0;
    vtk_sphere_case("vtk_sphere_ortho", &cam, 240, 300);
}

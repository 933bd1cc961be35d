/* bench_trace, accuracy against time (issue 9):
 *  1. the demo scene with the teapot as patches at tolerances 1e-3..1e-9 (relative to its box
 *     diagonal): ms per frame and pixels differing by more than 1/255 from the same scene with
 *     the teapot as a fine mesh;
 *  2. RMSE against spp on the shipped scenes/raytrace.json at a small size, stratified vs
 *     plain random, against a 1024-spp reference;
 *  3. POV-Ray (when `povray` is on PATH) and our tracer on an equivalent scene: spheres, a
 *     floor, a mirror ball and a glass ball, same size and max depth, ms per frame. */
#define _POSIX_C_SOURCE 200809L
#include "bench_trace_more.h"

#include "bench_clock.h"
#include "casteljau/render.h"
#include "casteljau/scene_json.h"
#include "casteljau/trace.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int trace(const cj_scene *sc, int w, int h, int spp, int threads, double ptol, int random,
                 cj_render_image **img, double *ms) {
    cj_render_options o = cj_render_options_defaults();
    o.width = w;
    o.height = h;
    o.spp = spp;
    o.threads = threads;
    o.use_seed = 1;
    o.seed = 777;
    cj_trace_options to = {random, ptol, 0, 0, 0};
    double t0 = cj_bench_wall();
    if (cj_render_trace_with_options(sc, &o, &to, 0, NULL, img, NULL)) {
        printf("  trace failed: %s\n", cj_last_error());
        return 1;
    }
    *ms = 1e3 * (cj_bench_wall() - t0);
    return 0;
}

void bench_trace_tolerance(const char *teapot_bpt, const cj_mesh *fine, double fine_tol) {
    const int W = 160, H = 120;
    cj_scene *sc;
    if (cj_trace_demo_scene(teapot_bpt, NULL, &sc)) return;
    printf("\npatch tolerance, demo scene %dx%d, spp 1, 2 threads: pixels differing by > 1/255 "
           "from the teapot as a %.0e mesh (%zu tri)\n",
           W, H, fine_tol, fine->triangle_count);
    cj_render_image *img[7];
    double ms[7];
    const double tols[7] = {1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9};
    for (int k = 0; k < 7; k++)
        if (trace(sc, W, H, 1, 2, tols[k], 0, &img[k], &ms[k])) return;
    cj_geometry gm;
    memset(&gm, 0, sizeof gm);
    gm.kind = CJ_GEOM_MESH;
    gm.u.mesh = (cj_mesh *)fine;
    int gi;
    cj_render_image *ref;
    double ref_ms;
    if (cj_scene_add_geometry(sc, &gm, &gi) == CJ_OK) {
        cj_scene_node_mut(sc, 0)->geometry = gi;
        if (trace(sc, W, H, 1, 2, 0, 0, &ref, &ref_ms)) return;
        printf("  teapot as mesh %.0e (reference) %8.1f ms/frame\n", fine_tol, ref_ms);
        size_t np = (size_t)W * H;
        for (int k = 0; k < 7; k++) {
            size_t diff = 0;
            double worst = 0;
            for (size_t i = 0; i < np; i++) {
                double d = 0;
                for (int c = 0; c < 3; c++) {
                    double e = fabs((double)img[k]->rgba[4 * i + c] - ref->rgba[4 * i + c]);
                    if (e > d) d = e;
                }
                if (d > 1.0 / 255) diff++;
                if (d > worst) worst = d;
            }
            printf("  teapot as patches, tol %.0e    %8.1f ms/frame  %5zu pixels differ "
                   "(%.2f%%), largest difference %.3f\n",
                   tols[k], ms[k], diff, 100.0 * (double)diff / (double)np, worst);
        }
        cj_render_image_destroy(ref);
    }
    for (int k = 0; k < 7; k++) cj_render_image_destroy(img[k]);
    cj_scene_destroy(sc);
}

void bench_trace_rmse_shipped(const char *scene_json, const char *teapot_bpt) {
    const int W = 96, H = 72, REF = 1024;
    cj_scene_json_options jo = {teapot_bpt};
    cj_scene *sc;
    if (cj_scene_load_json_with_options(scene_json, &jo, NULL, &sc)) {
        printf("\n(cannot load %s: %s)\n", scene_json, cj_last_error());
        return;
    }
    cj_render_image *ref;
    double ref_ms;
    if (trace(sc, W, H, REF, 2, 0, 0, &ref, &ref_ms)) return;
    printf("\nscenes/raytrace.json, %dx%d, RMSE against %d spp (stratified, %.0f ms), 2 "
           "threads\n",
           W, H, REF, ref_ms);
    size_t np = (size_t)W * H;
    for (int mode = 0; mode < 2; mode++) {
        printf("  %s sampling\n", mode ? "plain random" : "stratified");
        double prev = 0;
        for (int spp = 1; spp <= 256; spp *= 4) {
            cj_render_image *img;
            double ms;
            if (trace(sc, W, H, spp, 2, 0, mode, &img, &ms)) break;
            double e = 0;
            for (size_t i = 0; i < np; i++)
                for (int c = 0; c < 3; c++) {
                    double d = (double)img->rgba[4 * i + c] - ref->rgba[4 * i + c];
                    e += d * d;
                }
            e = sqrt(e / (3.0 * (double)np));
            printf("    spp %4d: RMSE %.5f  %8.1f ms/frame", spp, e, ms);
            if (prev > 0) printf("  ratio to 1/4 the samples %.2f (1/sqrt(n): 0.50)", e / prev);
            printf("\n");
            prev = e;
            cj_render_image_destroy(img);
        }
    }
    cj_render_image_destroy(ref);
    cj_scene_destroy(sc);
}

/* The POV-Ray comparison scene, built once for both renderers. World: right-handed, y up;
 * POV-Ray is left-handed, so its z is ours negated. */
typedef struct pov_ball {
    double x, y, z, r, cr, cg, cb;
    int kind; /* 0 diffuse, 1 mirror, 2 glass */
} pov_ball;

static const pov_ball balls[5] = {
    {-2.6, 1.0, -1.0, 1.0, 0.8, 0.2, 0.2, 0}, {2.6, 0.8, -0.5, 0.8, 0.2, 0.7, 0.2, 0},
    {0.0, 0.6, 2.0, 0.6, 0.2, 0.3, 0.9, 0},   {-0.6, 1.2, -3.0, 1.2, 0.9, 0.9, 0.9, 1},
    {0.9, 1.0, 0.5, 1.0, 1.0, 1.0, 1.0, 2},
};

static cj_scene *pov_scene_ours(void) {
    cj_scene *sc;
    if (cj_scene_create(NULL, &sc)) return NULL;
    cj_camera cam = cj_camera_defaults();
    cam.eye = cj_v3(0, 2.5, 9);
    cam.gaze = cj_v3(0, -1.5, -9);
    cam.fov_y = 40 * 3.14159265358979323846 / 180;
    cam.far = -200;
    cj_scene_set_camera(sc, &cam);
    cj_scene_settings set = cj_scene_settings_defaults();
    set.background = (cj_rgb){0.05, 0.06, 0.09};
    cj_scene_set_settings(sc, &set);
    cj_light amb = cj_light_defaults(CJ_LIGHT_AMBIENT), pt = cj_light_defaults(CJ_LIGHT_POINT);
    amb.intensity = 1.0;
    pt.position = cj_v3(-4, 7, 5);
    pt.intensity = 1.0;
    pt.casts_shadows = 1;
    cj_scene_add_light(sc, &amb, NULL);
    cj_scene_add_light(sc, &pt, NULL);
    cj_node n;
    memset(&n, 0, sizeof n);
    n.parent = -1;
    n.local = cj_transform_identity();
    n.visible = 1;
    n.overlay.iso_count = 1;
    n.overlay.normal_length = 0.1;
    cj_material m = cj_material_defaults();
    m.color = (cj_rgb){0.8, 0.8, 0.8};
    m.ka = 0.1;
    m.kd = 0.7;
    m.ks = 0.3;
    m.alpha = 40;
    cj_geometry g;
    memset(&g, 0, sizeof g);
    g.kind = CJ_GEOM_PLANAR;
    cj_planar_patch_init(&g.u.planar, cj_v3(-100, 0, 100), cj_v3(200, 0, 0), cj_v3(0, 0, -200));
    cj_scene_add_material(sc, &m, &n.material);
    cj_scene_add_geometry(sc, &g, &n.geometry);
    cj_scene_add_node(sc, &n, NULL);
    for (int i = 0; i < 5; i++) {
        const pov_ball *b = &balls[i];
        cj_material mb = m;
        mb.color = (cj_rgb){b->cr, b->cg, b->cb};
        if (b->kind == 1) {
            mb.kd = 0.05;
            mb.mirror = 0.9;
        } else if (b->kind == 2) {
            mb.kd = 0.02;
            mb.ka = 0;
            mb.transmission = 0.9;
            mb.ior = 1.5;
        }
        memset(&g, 0, sizeof g);
        g.kind = CJ_GEOM_SPHERE;
        g.u.sphere.center = cj_v3(b->x, b->y, b->z);
        g.u.sphere.radius = b->r;
        cj_scene_add_material(sc, &mb, &n.material);
        cj_scene_add_geometry(sc, &g, &n.geometry);
        cj_scene_add_node(sc, &n, NULL);
    }
    return sc;
}

static int pov_write(const char *path) {
    FILE *f = fopen(path, "w");
    if (!f) return 1;
    /* POV-Ray's camera angle is the horizontal field of view: 2 atan(tan(20°) 4/3). */
    double hfov =
        2 * atan(tan(20 * 3.14159265358979323846 / 180) * 4.0 / 3.0) * 180 / 3.14159265358979323846;
    fprintf(f,
            "#version 3.7;\nglobal_settings { assumed_gamma 1.0 max_trace_level 6 "
            "ambient_light rgb 1 }\nbackground { rgb <0.05, 0.06, 0.09> }\n"
            "camera { perspective location <0, 2.5, -9> look_at <0, 1, 0> right x*4/3 angle "
            "%.6f }\n"
            "light_source { <-4, 7, -5> rgb 1 }\n"
            "plane { y, 0 pigment { rgb 0.8 } finish { ambient 0.1 diffuse 0.7 phong 0.3 "
            "phong_size 40 } }\n",
            hfov);
    for (int i = 0; i < 5; i++) {
        const pov_ball *b = &balls[i];
        fprintf(f, "sphere { <%g, %g, %g>, %g ", b->x, b->y, -b->z, b->r);
        if (b->kind == 0)
            fprintf(f,
                    "pigment { rgb <%g, %g, %g> } finish { ambient 0.1 diffuse 0.7 phong 0.3 "
                    "phong_size 40 } }\n",
                    b->cr, b->cg, b->cb);
        else if (b->kind == 1)
            fprintf(f,
                    "pigment { rgb <%g, %g, %g> } finish { ambient 0.1 diffuse 0.05 phong "
                    "0.3 phong_size 40 reflection 0.9 } }\n",
                    b->cr, b->cg, b->cb);
        else
            fprintf(f, "pigment { rgbf <1, 1, 1, 0.9> } finish { ambient 0 diffuse 0.02 phong "
                       "0.3 phong_size 40 } interior { ior 1.5 } }\n");
    }
    fclose(f);
    return 0;
}

static int cmp_double(const void *a, const void *b) {
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

void bench_trace_povray(void) {
    const int W = 320, H = 240, DEPTH = 6;
    printf("\nPOV-Ray side by side: 5 spheres (a mirror, a glass ball) on a floor, a point "
           "light, %dx%d, max depth %d, no antialiasing; median of 3 (wall clock)\n",
           W, H, DEPTH);
    if (system("command -v povray > /dev/null 2>&1") != 0) {
        printf("  skipped: povray is not on PATH (Debian: apt-get install -y povray)\n");
        return;
    }
    const char *pov = "/tmp/cj_bench_trace.pov", *png = "/tmp/cj_bench_trace_pov.png";
    if (pov_write(pov)) {
        printf("  skipped: cannot write %s\n", pov);
        return;
    }
    cj_scene *sc = pov_scene_ours();
    if (!sc) return;
    for (int th = 1; th <= 2; th++) {
        double tp[3], tc[3];
        char cmd[512];
        snprintf(cmd, sizeof cmd,
                 "povray +I%s +O%s +FN +W%d +H%d -A -D +WT%d -GA +MV3.7 > /dev/null 2>&1", pov, png,
                 W, H, th);
        int ok = 1;
        for (int r = 0; r < 3; r++) {
            double t0 = cj_bench_wall();
            if (system(cmd) != 0) ok = 0;
            tp[r] = 1e3 * (cj_bench_wall() - t0);
            cj_render_options o = cj_render_options_defaults();
            o.width = W;
            o.height = H;
            o.spp = 1;
            o.max_depth = DEPTH;
            o.threads = th;
            cj_render_image *img;
            t0 = cj_bench_wall();
            if (cj_render_trace(sc, &o, 0, NULL, &img, NULL)) {
                printf("  trace failed: %s\n", cj_last_error());
                cj_scene_destroy(sc);
                return;
            }
            tc[r] = 1e3 * (cj_bench_wall() - t0);
            if (r == 0 && th == 1) {
                /* our frame next to POV-Ray's, for looking at (binary PPM, gamma 2.2) */
                FILE *f = fopen("/tmp/cj_bench_trace_ours.ppm", "wb");
                if (f) {
                    fprintf(f, "P6 %d %d 255\n", W, H);
                    for (int y = H - 1; y >= 0; y--)
                        for (int x = 0; x < W; x++)
                            for (int c = 0; c < 3; c++) {
                                double v = img->rgba[4 * ((size_t)y * W + x) + c];
                                v = v < 0 ? 0 : v > 1 ? 1 : v;
                                fputc((int)(255 * pow(v, 1 / 2.2) + 0.5), f);
                            }
                    fclose(f);
                }
            }
            cj_render_image_destroy(img);
        }
        qsort(tp, 3, sizeof *tp, cmp_double);
        qsort(tc, 3, sizeof *tc, cmp_double);
        printf("  %d thread%s: POV-Ray %8.1f ms/frame (process: parse + render + write)%s,  "
               "casteljau %8.1f ms/frame (cj_render_trace)  ratio %.2f\n",
               th, th > 1 ? "s" : " ", tp[1], ok ? "" : " [povray exited non-zero]", tc[1],
               tc[1] / tp[1]);
    }
    printf("  images: %s (POV-Ray), /tmp/cj_bench_trace_ours.ppm (casteljau)\n", png);
    cj_scene_destroy(sc);
}

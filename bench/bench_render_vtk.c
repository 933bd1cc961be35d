/* bench_render_vtk: the Utah teapot at 1024 × 1024 and 0.25 px tolerance, Phong shading at
 * 1 sample per pixel, rendered by our rasterizer (cj_render_raster) and by VTK with Mesa's
 * llvmpipe drawing THE SAME triangles (cj_render_scene_mesh), in the same run, interleaved
 * repetitions, medians in ms per frame; on 1 and 2 threads (ours: the threads option; llvmpipe:
 * LP_NUM_THREADS, read when Mesa creates its screen, so each thread count runs in a child
 * process forked before any GL). A private Xvfb provides the display (tests/support/xvfb.c).
 *
 * What each figure includes:
 *   ours from patches  cj_render_raster of the teapot scene: view-dependent tessellation (every
 *                      frame), culling, clipping, rasterization, deferred Phong shading into
 *                      a float RGBA image;
 *   ours warm cache    the same with a tessellation cache (cj_render_cache): the camera
 *                      stands still, so every frame after the first re-uses the mesh;
 *   ours same mesh     cj_render_raster of a scene holding the triangles of the first one as a
 *                      mesh object: the same work minus the tessellation;
 *   VTK render         vtkRenderWindow::Render + glFinish of those triangles, uploaded once;
 *   VTK + read         plus reading the RGBA8 frame back into memory (ours is in memory).
 * The CPU columns are process CPU time per frame (all threads, Mesa's included): the work
 * done, which a loaded machine does not inflate the way it inflates wall time.
 * Usage: bench_render_vtk [--size N] [--reps R] [--tol-px T] */
#define _POSIX_C_SOURCE 200809L
#define _DEFAULT_SOURCE
#include "bench_clock.h"
#include "casteljau/patchset.h"
#include "casteljau/render.h"
#include "casteljau/vtk_render.h"
#include "xvfb.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#ifndef CJ_TEAPOT_PATH
#define CJ_TEAPOT_PATH "data/teapot.bpt"
#endif

static void die(const char *what) {
    fprintf(stderr, "bench_render_vtk: %s: %s\n", what, cj_last_error());
    exit(1);
}

/* The teapot filling a square frame: ambient + point + directional light, plastic Phong. */
/* mesh == NULL: the teapot's Bézier patches; else that world-space mesh as it is. */
static cj_scene *teapot_scene(int size, double tol_px, const cj_mesh *mesh) {
    cj_scene *sc = NULL;
    if (cj_scene_create(NULL, &sc) != CJ_OK) die("scene");
    cj_camera cam = cj_camera_defaults();
    cam.eye = cj_v3(5.0, -6.5, 4.5);
    cam.gaze = cj_v3_sub(cj_v3(0.2, 0.0, 1.4), cam.eye);
    cam.up = cj_v3(0, 0, 1);
    cam.near = -0.5;
    cam.far = -50.0;
    cam.fov_y = 34.0 * M_PI / 180.0;
    cj_scene_settings set = cj_scene_settings_defaults();
    set.width = set.height = size;
    set.spp = 1;
    set.tol_px = tol_px;
    set.background = cj_rgb_make(0.05, 0.05, 0.1);
    if (cj_scene_set_camera(sc, &cam) || cj_scene_set_settings(sc, &set)) die("camera");
    cj_light l[3] = {cj_light_defaults(CJ_LIGHT_AMBIENT), cj_light_defaults(CJ_LIGHT_POINT),
                     cj_light_defaults(CJ_LIGHT_DIRECTIONAL)};
    l[0].intensity = 0.2;
    l[1].position = cj_v3(4.0, -3.0, 7.0);
    l[1].intensity = 0.7;
    l[2].direction = cj_v3(-0.3, 1.0, -0.5);
    l[2].intensity = 0.4;
    for (int i = 0; i < 3; i++)
        if (cj_scene_add_light(sc, &l[i], NULL)) die("light");
    cj_material m = cj_material_defaults();
    m.color = cj_rgb_make(0.8, 0.6, 0.4);
    m.shading = CJ_SHADE_PHONG;
    int mi = -1, gi = -1;
    if (cj_scene_add_material(sc, &m, &mi)) die("material");
    cj_geometry g;
    memset(&g, 0, sizeof g);
    cj_patchset *ps = NULL;
    if (mesh) {
        g.kind = CJ_GEOM_MESH;
        g.u.mesh = (cj_mesh *)mesh; /* deep-copied by the scene */
    } else {
        if (cj_patchset_load_bpt(CJ_TEAPOT_PATH, NULL, &ps)) die(CJ_TEAPOT_PATH);
        g.kind = CJ_GEOM_PATCHES;
        g.u.patches.count = ps->count;
        g.u.patches.patches = ps->patches;
    }
    if (cj_scene_add_geometry(sc, &g, &gi)) die("geometry");
    cj_patchset_destroy(ps);
    cj_node n = cj_node_defaults(gi, mi);
    if (cj_scene_add_node(sc, &n, NULL)) die("node");
    return sc;
}

/* Threads of this process (Mesa's rasterizer threads show up here). */
static int count_threads(void) {
    int n = -1;
    char line[256];
    FILE *f = fopen("/proc/self/status", "r");
    if (!f) return -1;
    while (fgets(line, sizeof line, f))
        if (!strncmp(line, "Threads:", 8)) n = atoi(line + 8);
    fclose(f);
    return n;
}

enum { OURS_PATCHES, OURS_WARM, OURS_MESH, VTK_RENDER, VTK_READ, NCOL };

static void run(int threads, int size, int reps, double tol_px) {
    cj_scene *sc = teapot_scene(size, tol_px, NULL);
    cj_render_options opt = cj_render_options_defaults();
    opt.threads = threads;
    cj_mesh *mesh = NULL;
    if (cj_render_scene_mesh(sc, &opt, NULL, &mesh)) die("cj_render_scene_mesh");
    /* the same triangles as a mesh object: our renderer without the tessellation */
    cj_scene *sm = teapot_scene(size, tol_px, mesh);
    /* a tessellation cache: a still camera re-uses the teapot's mesh after the first frame */
    cj_render_options warm = opt;
    if (cj_render_cache_create(NULL, &warm.cache)) die("cache");
    cj_vtk_renderer *vr = NULL;
    if (cj_vtk_renderer_create_scene(sc, mesh, size, size, 0, &vr)) die("VTK renderer");
    float *rgba = malloc(sizeof(float) * 4 * (size_t)size * size);
    double *wall = malloc(sizeof(double) * NCOL * reps),
           *cpu = malloc(sizeof(double) * NCOL * reps);
    if (!rgba || !wall || !cpu) {
        fprintf(stderr, "bench_render_vtk: out of memory\n");
        exit(1);
    }
    const cj_vtk_frame frame = {rgba, NULL, NULL};
    cj_render_image *first = NULL;
    size_t differ = 0;
    for (int r = -2; r < reps; r++) { /* two warm-up rounds (VTK uploads, compiles shaders) */
        double w[NCOL + 1], c[NCOL + 1];
        for (int k = OURS_PATCHES; k <= OURS_MESH; k++) {
            cj_render_image *img = NULL;
            c[k] = cj_bench_process_cpu();
            w[k] = cj_bench_wall();
            if (cj_render_raster(k == OURS_MESH ? sm : sc, k == OURS_WARM ? &warm : &opt, 0, NULL,
                                 &img, NULL))
                die("cj_render_raster");
            w[k] = cj_bench_wall() - w[k];
            c[k] = cj_bench_process_cpu() - c[k];
            if (r == -2 && k == OURS_PATCHES) {
                first = img; /* kept to check that the columns draw the same picture */
                continue;
            }
            if (r == -2 && k == OURS_MESH) {
                for (size_t i = 0; i < 4 * (size_t)size * size; i++)
                    differ += fabsf(first->rgba[i] - img->rgba[i]) > 0.5f / 255.0f;
                cj_render_image_destroy(first);
            }
            cj_render_image_destroy(img);
        }
        cj_vtk_timing tv;
        c[VTK_READ] = cj_bench_process_cpu();
        if (cj_vtk_renderer_draw(vr, &frame, &tv)) die("VTK draw");
        c[VTK_READ] = cj_bench_process_cpu() - c[VTK_READ];
        w[VTK_RENDER] = tv.render;
        w[VTK_READ] = tv.render + tv.readback;
        c[VTK_RENDER] = c[VTK_READ]; /* (not separable: the read-back is ~1 ms) */
        if (r < 0) continue;
        for (int k = 0; k < NCOL; k++) {
            wall[k * reps + r] = w[k];
            cpu[k * reps + r] = c[k];
        }
    }
    char gl[128] = "?";
    if (cj_vtk_renderer_gl_name(vr, gl, sizeof gl))
        snprintf(gl, sizeof gl, "? (%s)", cj_last_error());
    double mw[NCOL], mc[NCOL];
    for (int k = 0; k < NCOL; k++) {
        mw[k] = 1e3 * cj_bench_median(wall + k * reps, reps);
        mc[k] = 1e3 * cj_bench_median(cpu + k * reps, reps);
    }
    printf("%7d | %9zu | %12.1f | %10.1f | %10.1f | %10.1f | %10.1f || %10.1f | %10.1f | "
           "%10.1f\n",
           threads, mesh->triangle_count, mw[OURS_PATCHES], mw[OURS_WARM], mw[OURS_MESH],
           mw[VTK_RENDER], mw[VTK_READ], mc[OURS_WARM], mc[OURS_MESH], mc[VTK_READ]);
    printf("        | VTK through %s, LP_NUM_THREADS=%s, %d threads in the process; ours from "
           "patches vs the same mesh: %zu channels differ by more than 0.5/255\n",
           gl, getenv("LP_NUM_THREADS"), count_threads(), differ);
    fflush(stdout);
    free(rgba);
    free(wall);
    free(cpu);
    cj_vtk_renderer_destroy(vr);
    cj_render_cache_destroy(warm.cache);
    cj_mesh_destroy(mesh);
    cj_scene_destroy(sm);
    cj_scene_destroy(sc);
}

int main(int argc, char **argv) {
    int size = 1024, reps = 15;
    double tol_px = 0.25;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--size") && i + 1 < argc)
            size = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--reps") && i + 1 < argc)
            reps = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--tol-px") && i + 1 < argc)
            tol_px = atof(argv[++i]);
        else {
            fprintf(stderr, "usage: bench_render_vtk [--size N] [--reps R] [--tol-px T]\n");
            return 2;
        }
    }
    if (size < 16 || size > 4096 || reps < 1 || !(tol_px > 0)) {
        fprintf(stderr, "bench_render_vtk: size 16..4096, reps >= 1, tol-px > 0\n");
        return 2;
    }
    const pid_t xvfb = cj_test_xvfb_start(size, size);
    if (xvfb < 0) return 1;
    double load = -1.0;
    FILE *la = fopen("/proc/loadavg", "r");
    if (la) {
        if (fscanf(la, "%lf", &load) != 1) load = -1.0;
        fclose(la);
    }
    printf("teapot %dx%d, tol %.2f px, Phong, 1 spp; median of %d interleaved frames, ms; "
           "%ld CPUs, load average %.1f at start\n",
           size, size, tol_px, reps, sysconf(_SC_NPROCESSORS_ONLN), load);
    printf("        |           | wall: ours   | ours       | ours       | VTK        | VTK        "
           "|| CPU: ours  | ours       | VTK\n");
    printf("threads | triangles | from patches | warm cache | same mesh  | render     | + read     "
           "|| warm cache | same mesh  | + read\n");
    fflush(stdout);
    int status = 0;
    for (int threads = 1; threads <= 2; threads++) {
        const pid_t child = fork();
        if (child < 0) {
            perror("fork");
            status = 1;
            break;
        }
        if (child == 0) {
            char n[8];
            snprintf(n, sizeof n, "%d", threads);
            setenv("LP_NUM_THREADS", n, 1); /* before Mesa creates its screen */
            run(threads, size, reps, tol_px);
            _exit(0);
        }
        int st = 0;
        waitpid(child, &st, 0);
        if (!WIFEXITED(st) || WEXITSTATUS(st) != 0) status = 1;
    }
    cj_test_xvfb_stop(xvfb);
    return status;
}

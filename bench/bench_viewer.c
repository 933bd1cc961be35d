/* bench_viewer: dragging one control point of the teapot in `casteljau view` at 1024 x 1024
 * (the render demo scene at 1 sample per pixel, re-tessellated at 0.25 px every frame, rendered
 * by our rasterizer, uploaded as a texture and swapped), driven by a replay script under a
 * private Xvfb (Mesa llvmpipe). Per-frame wall times come from the viewer itself
 * (--frame-times: render + upload + draw + swap + glFinish); the table gives their median, 90th
 * and 99th percentiles and maximum for 1 and 2 renderer threads, and, for comparison, the
 * median of cj_render_raster alone on the same scene in this process.
 *
 *   bench_viewer [FRAMES]      (default 60 drag steps)
 */
#define _POSIX_C_SOURCE 200809L
#include "bench_clock.h"
#include "casteljau/render.h"
#include "casteljau/scene_json.h"
#include "casteljau/viewer_scene.h"
#include "xvfb.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

enum { W = 1024, H = 1024 };

static double pct(double *v, size_t n, double p) {
    qsort(v, n, sizeof *v, cj_bench_cmp_double);
    size_t i = (size_t)ceil(p * (double)n) - 1;
    return v[i < n ? i : n - 1];
}

int main(int argc, char **argv) {
    const int frames = argc > 1 ? atoi(argv[1]) : 60;
    if (frames < 2 || frames > 100000) return fprintf(stderr, "usage: bench_viewer [FRAMES]\n"), 2;
    cj_scene *s = NULL;
    if (cj_render_demo_scene(CJ_TEAPOT_PATH, NULL, &s))
        return fprintf(stderr, "%s\n", cj_last_error()), 1;
    cj_scene_settings set = *cj_scene_settings_get(s);
    set.width = W, set.height = H, set.spp = 1, set.tol_px = 0.25;
    cj_scene_set_settings(s, &set);
    /* In-process reference: cj_render_raster alone (2 threads), median of 5. */
    double rr[5];
    size_t tris = 0;
    float *depth = malloc((size_t)W * H * sizeof *depth);
    for (int i = 0; i < 5; ++i) {
        cj_render_options ro = cj_render_options_default();
        ro.threads = 2;
        cj_render_image *img = NULL;
        cj_stage_report rep;
        const double t0 = cj_bench_wall();
        if (cj_render_raster(s, &ro, i == 0 ? CJ_IMAGE_DEPTH : 0, NULL, &img, &rep))
            return fprintf(stderr, "%s\n", cj_last_error()), 1;
        rr[i] = cj_bench_wall() - t0;
        const cj_stage *st = cj_stage_report_find(&rep, "tessellate_patches");
        tris = st ? (size_t)st->out : 0;
        if (i == 0 && depth) memcpy(depth, img->depth, (size_t)W * H * sizeof *depth);
        cj_render_image_destroy(img);
    }
    /* A visible control point near the middle of the picture: the one the viewer picks. */
    const cj_camera cam0 = *cj_scene_camera(s);
    cj_vscene *vs = NULL;
    if (cj_vscene_create(s, &vs)) return fprintf(stderr, "%s\n", cj_last_error()), 1;
    size_t picked = 0;
    double q[3], best = INFINITY;
    for (size_t k = 0; k < cj_vscene_point_count(vs); ++k)
        if (cj_vscene_project(vs, k, W, H, q) && q[0] >= 0 && q[1] >= 0 && q[0] < W && q[1] < H &&
            q[2] <= depth[(size_t)q[1] * W + (size_t)q[0]] + CJ_VSCENE_DEPTH_TOL) {
            const double d = hypot(q[0] - 0.55 * W, q[1] - 0.6 * H);
            if (d < best) best = d, picked = k;
        }
    cj_vscene_project(vs, picked, W, H, q);
    cj_vec3 start;
    cj_vscene_point(vs, picked, &start);
    const int x = (int)floor(q[0]), y = H - 1 - (int)floor(q[1]);
    cj_vscene_destroy(vs);
    free(depth);

    char script[] = "/tmp/cj_bench_viewer_XXXXXX";
    const int fd = mkstemp(script);
    if (fd < 0) return 1;
    FILE *f = fdopen(fd, "w");
    fprintf(f, "press left %d %d\n", x, y);
    for (int i = 1; i <= frames; ++i) { /* a circle of 40 px radius: the net keeps changing */
        const double a = 6.283185307179586 * i / frames;
        fprintf(f, "move %.3f %.3f\n", x + 40 * sin(a), y - 40 * (1 - cos(a)));
    }
    fprintf(f, "release left %d %d\nsave %s.json\n", x, y, script);
    fclose(f);

    const pid_t xvfb = cj_test_xvfb_start(1280, 1100);
    if (xvfb < 0) return fprintf(stderr, "bench_viewer: cannot start Xvfb\n"), 1;
    printf("bench_viewer: teapot demo scene %d x %d, 1 spp, tol 0.25 px (%zu triangles), "
           "dragging control point %zu along a 40 px circle, %d frames, Xvfb + Mesa llvmpipe\n",
           W, H, tris, picked, frames);
    printf("cj_render_raster alone (2 threads, in process): median %.1f ms\n",
           1e3 * pct(rr, 5, 0.5));
    printf("%-8s %7s | wall: %8s %8s %8s %8s | process CPU: %8s %8s\n", "threads", "frames",
           "median", "p90", "p99", "max", "median", "p99");
    for (int threads = 1; threads <= 2; ++threads) {
        char times[] = "/tmp/cj_bench_viewer_times_XXXXXX";
        const int tfd = mkstemp(times);
        if (tfd < 0) return 1;
        char cmd[2048];
        snprintf(cmd, sizeof cmd,
                 "%s view --teapot --width %d --height %d --spp 1 --tol-px 0.25 --threads %d "
                 "--replay %s --hide-overlay --frame-times %s",
                 CJ_CLI, W, H, threads, script, times);
        if (system(cmd) != 0) return fprintf(stderr, "bench_viewer: the viewer failed\n"), 1;
        FILE *tf = fdopen(tfd, "r");
        double *v = malloc(((size_t)frames + 8) * sizeof *v);
        double *c = malloc(((size_t)frames + 8) * sizeof *c);
        size_t n = 0;
        double t, u;
        while (v && c && n < (size_t)frames + 8 && fscanf(tf, "%lf %lf", &t, &u) == 2)
            v[n] = t, c[n++] = u;
        fclose(tf);
        unlink(times);
        /* frame 0 is the first picture, frame 1 the press: the drag frames follow */
        if (!v || !c || n < 3) return fprintf(stderr, "bench_viewer: no frame times\n"), 1;
        double *d = v + 2, *e = c + 2;
        const size_t nd = n - 2;
        printf("%-8d %7zu | wall: %6.1fms %6.1fms %6.1fms %6.1fms | process CPU: %6.1fms %6.1fms\n",
               threads, nd, 1e3 * pct(d, nd, 0.5), 1e3 * pct(d, nd, 0.9), 1e3 * pct(d, nd, 0.99),
               1e3 * pct(d, nd, 1.0), 1e3 * pct(e, nd, 0.5), 1e3 * pct(e, nd, 0.99));
        free(v);
        free(c);
        /* the drag really moved that point and not the camera: the circle brings the point back
         * to its start (to rounding), while an orbit would have rewritten the camera */
        char saved[64];
        snprintf(saved, sizeof saved, "%s.json", script);
        cj_scene_json_options jo = {CJ_TEAPOT_PATH};
        cj_scene *m = NULL;
        cj_vscene *vm = NULL;
        cj_vec3 end;
        if (cj_scene_load_json_ex(saved, &jo, NULL, &m) || cj_vscene_create(m, &vm) ||
            cj_vscene_point(vm, picked, &end) ||
            cj_v3_norm(cj_v3_sub(end, start)) > 1e-9 * cj_v3_norm(start) + 1e-12 ||
            memcmp(cj_scene_camera(cj_vscene_scene(vm)), &cam0, sizeof cam0))
            return fprintf(stderr, "bench_viewer: the replay did not drag point %zu\n", picked), 1;
        cj_vscene_destroy(vm);
        unlink(saved);
    }
    unlink(script);
    cj_test_xvfb_stop(xvfb);
    return 0;
}

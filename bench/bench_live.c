/* bench_live: the "Live" rows of issue 19 on the Utah teapot demo scene (cj_render_demo_scene:
 * teapot with its control net, checkered floor, three lights) at 1024 x 1024, 1 spp, the
 * scene's 0.25 px tolerance, rasterized:
 *   drag   one control point of patch 0 moves a little each frame (alternating up and down);
 *   orbit  the camera turns 1 degree about the teapot each frame, nothing else changes;
 *   approach  the camera moves 0.5 % of its distance closer to the point it looks at each
 *          frame (a steady zoom: each frame needs a slightly finer tolerance; the render
 *          cache's band policy decides how often the teapot is re-tessellated);
 * each drawn two ways: ONE-SHOT (cj_render_raster per frame: what every command and the
 * viewer did before the renderer, the behaviour of today's main) and RENDERER (one cj_renderer
 * for all frames: its tessellation cache, pool, buffers and image kept).
 *
 * Usage: bench_live [stages] [frames (default 12)] [threads (default 2)]
 *            prints per workload and path: median wall ms per frame, median CPU ms per frame
 *            (process CPU time: every thread) and the minima of both, cache hits/misses of
 *            the last frame;
 *            `stages` adds the renderer's last stage report (JSON)
 *        bench_live cg drag|orbit|approach oneshot|renderer [frames (default 2)]
 *            one warm-up frame, then `frames` frames with callgrind collecting only those:
 *            valgrind --tool=callgrind --collect-atstart=no bench_live cg drag renderer 2
 *            (instructions per frame = the total / frames); 1 thread.
 * Today's figures: compile this file with -DCJ_LIVE_ONESHOT_ONLY against the main branch's
 * libraries (docs/rasterizer.md, "The renderer object", says how); only one-shot rows run. */
#define _POSIX_C_SOURCE 200809L
#include "bench_clock.h"

#ifdef CJ_LIVE_ONESHOT_ONLY
/* Built against a tree without the renderer (the main branch before issue 19) to quote today's
 * figures: only the one-shot rows run. */
#include "casteljau/render.h"
typedef struct cj_renderer cj_renderer;
typedef struct cj_renderer_options {
    cj_render_options render;
} cj_renderer_options;
enum { CJ_BACKEND_RASTER };
static cj_renderer_options cj_renderer_options_defaults(void) {
    cj_renderer_options o = {cj_render_options_defaults()};
    return o;
}
static cj_status cj_renderer_create(const cj_renderer_options *o, const void *a, cj_renderer **r) {
    (void)o, (void)a, (void)r;
    return CJ_ERR_ARGUMENT;
}
static cj_status cj_renderer_draw(cj_renderer *r, const cj_scene *s, int be, unsigned planes,
                                  cj_render_image **img, cj_stage_report *rep) {
    (void)r, (void)s, (void)be, (void)planes, (void)img, (void)rep;
    return CJ_ERR_ARGUMENT;
}
static void cj_renderer_destroy(cj_renderer *r) {
    (void)r;
}
#define HAVE_RENDERER 0
#else
#include "casteljau/renderer.h"
#define HAVE_RENDERER 1
#endif

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <valgrind/callgrind.h>

#ifndef CJ_TEAPOT_PATH
#define CJ_TEAPOT_PATH "data/teapot.bpt"
#endif

enum { DRAG, ORBIT, APPROACH, WORKLOADS };
static const char *workload_name[WORKLOADS] = {"drag a teapot control point", "orbit the camera",
                                               "approach (camera 0.5 % closer per frame)"};

static void die(const char *what) {
    fprintf(stderr, "bench_live: %s: %s\n", what, cj_last_error());
    exit(1);
}

static cj_scene *teapot(void) {
    cj_scene *s = NULL;
    if (cj_render_demo_scene(CJ_TEAPOT_PATH, NULL, &s)) die("demo scene");
    cj_scene_settings set = *cj_scene_get_settings(s);
    set.width = 1024;
    set.height = 1024;
    set.spp = 1;
    if (cj_scene_set_settings(s, &set)) die("settings");
    return s;
}

/* The first patch set's first patch: its control point 5 (an inner point) moves. */
static double *drag_point(cj_scene *s) {
    for (size_t i = 0; i < cj_scene_node_count(s); ++i) {
        const cj_node *n = cj_scene_node(s, (int)i);
        if (n->geometry < 0) continue;
        cj_geometry *g = cj_scene_geometry_mut(s, n->geometry);
        if (g->kind == CJ_GEOM_PATCHES) return (double *)g->u.patches.patches[0].pts + 3 * 5;
    }
    die("no patch set");
    return NULL;
}

/* The edit before frame f. */
static void step(cj_scene *s, int workload, int f, double *pt, const cj_camera *cam0) {
    if (workload == DRAG) {
        pt[1] += (f % 2 ? -1.0 : 1.0) * 0.01; /* a little up, then back down */
        return;
    }
    cj_camera cam = *cam0;
    if (workload == APPROACH) {
        const cj_vec3 target = cj_v3_add(cam0->eye, cam0->gaze);
        const double k = pow(0.995, (double)f);
        cam.eye = cj_v3_add(target, cj_v3_scale(cj_v3_sub(cam0->eye, target), k));
        cam.gaze = cj_v3_sub(target, cam.eye);
        if (cj_scene_set_camera(s, &cam)) die("camera");
        return;
    }
    /* eye and gaze turned about the vertical axis through the point looked at */
    double a = (double)f * 3.14159265358979323846 / 180.0, ca = cos(a), sa = sin(a);
    cj_vec3 target = cj_v3_add(cam0->eye, cam0->gaze);
    cj_vec3 off = cj_v3_sub(cam0->eye, target);
    cam.eye = cj_v3_add(target, cj_v3(ca * off.x - sa * off.z, off.y, sa * off.x + ca * off.z));
    cam.gaze = cj_v3(ca * cam0->gaze.x - sa * cam0->gaze.z, cam0->gaze.y,
                     sa * cam0->gaze.x + ca * cam0->gaze.z);
    if (cj_scene_set_camera(s, &cam)) die("camera");
}

static double value(const cj_stage_report *r, const char *stage, const char *key) {
    const cj_stage *s = cj_stage_report_find(r, stage);
    for (int i = 0; s && i < s->extra_count; ++i)
        if (!strcmp(s->extra[i].key, key)) return s->extra[i].value;
    return -1.0;
}

/* One frame by the chosen path. */
static void frame(cj_renderer *r, cj_scene *s, const cj_render_options *o, cj_render_image **img,
                  cj_stage_report *rep) {
    if (r) {
        if (cj_renderer_draw(r, s, CJ_BACKEND_RASTER, 0, img, rep)) die("renderer draw");
        return;
    }
    cj_render_image *one = NULL;
    if (cj_render_raster(s, o, 0, NULL, &one, rep)) die("one-shot render");
    cj_render_image_destroy(*img);
    *img = one;
}

/* FNV-1a of the last frame's float pixels: a speed-up that must not change the image shows the
 * same figure before and after. */
static uint64_t image_hash(const cj_render_image *img) {
    uint64_t h = 1469598103934665603u;
    const unsigned char *b = (const unsigned char *)img->rgba;
    for (size_t i = 0; i < (size_t)img->width * (size_t)img->height * 4 * sizeof(float); ++i)
        h = (h ^ b[i]) * 1099511628211u;
    return h;
}

static int print_stages = 0; /* `stages`: the last renderer frame's stage report */

static void run(int workload, int renderer, int frames, int threads) {
    cj_scene *s = teapot();
    double *pt = drag_point(s);
    cj_camera cam0 = *cj_scene_get_camera(s);
    cj_renderer_options ro = cj_renderer_options_defaults();
    ro.render.threads = threads;
    cj_renderer *r = NULL;
    if (renderer && cj_renderer_create(&ro, NULL, &r)) die("renderer");
    cj_render_image *img = NULL;
    cj_stage_report rep;
    double *wall = malloc(sizeof(double) * (size_t)frames);
    double *cpu = malloc(sizeof(double) * (size_t)frames);
    if (!wall || !cpu) die("memory");
    frame(r, s, &ro.render, &img, &rep); /* the cold frame is not counted */
    double built = 0.0;                  /* patches built over the counted frames (renderer) */
    for (int f = 0; f < frames; ++f) {
        step(s, workload, f + 1, pt, &cam0);
        double w0 = cj_bench_wall(), c0 = cj_bench_process_cpu();
        frame(r, s, &ro.render, &img, &rep);
        wall[f] = cj_bench_wall() - w0;
        cpu[f] = cj_bench_process_cpu() - c0;
        if (r) built += value(&rep, "tessellate_patches", "patches_built");
    }
    double tess = cj_stage_report_find(&rep, "tessellate_patches")->seconds;
    double wmin = wall[0], cmin = cpu[0];
    for (int f = 1; f < frames; ++f) {
        wmin = wall[f] < wmin ? wall[f] : wmin;
        cmin = cpu[f] < cmin ? cpu[f] : cmin;
    }
    /* the minimum too: on a shared machine the least disturbed frame is the steadier figure */
    printf("  %-9s median %7.1f ms wall, %7.1f ms CPU per frame (min %.1f, %.1f); last frame: "
           "tessellation %6.1f ms, cache hits %g, misses %g",
           renderer ? "renderer" : "one-shot", 1e3 * cj_bench_median(wall, (size_t)frames),
           1e3 * cj_bench_median(cpu, (size_t)frames), 1e3 * wmin, 1e3 * cmin, 1e3 * tess,
           value(&rep, "tessellate_patches", "cache_hits"),
           value(&rep, "tessellate_patches", "cache_misses"));
    if (r) printf("; %g patches built in %d frames", built, frames);
    printf("\n");
    if (print_stages && renderer) {
        cj_stage_report_json(&rep, stdout);
        fputc('\n', stdout);
    }
    free(wall);
    free(cpu);
    cj_render_image_destroy(img);
    cj_renderer_destroy(r);
    cj_scene_destroy(s);
}

static int callgrind(int workload, int renderer, int frames) {
    cj_scene *s = teapot();
    double *pt = drag_point(s);
    cj_camera cam0 = *cj_scene_get_camera(s);
    cj_renderer_options ro = cj_renderer_options_defaults();
    ro.render.threads = 1;
    cj_renderer *r = NULL;
    if (renderer && cj_renderer_create(&ro, NULL, &r)) die("renderer");
    cj_render_image *img = NULL;
    cj_stage_report rep;
    frame(r, s, &ro.render, &img, &rep);
    CALLGRIND_START_INSTRUMENTATION;
    CALLGRIND_TOGGLE_COLLECT;
    for (int f = 0; f < frames; ++f) {
        step(s, workload, f + 1, pt, &cam0);
        frame(r, s, &ro.render, &img, &rep);
    }
    CALLGRIND_TOGGLE_COLLECT;
    CALLGRIND_STOP_INSTRUMENTATION;
    printf("%s, %s: %d frames collected (divide the callgrind total by %d); last image hash "
           "%016llx\n",
           workload_name[workload], renderer ? "renderer" : "one-shot", frames, frames,
           (unsigned long long)image_hash(img));
    cj_render_image_destroy(img);
    cj_renderer_destroy(r);
    cj_scene_destroy(s);
    return 0;
}

int main(int argc, char **argv) {
    if (argc > 1 && !strcmp(argv[1], "cg")) {
        if (argc < 4) {
            fprintf(stderr, "usage: bench_live cg drag|orbit|approach oneshot|renderer [frames]\n");
            return 2;
        }
        int frames = argc > 4 ? atoi(argv[4]) : 2;
        const int w = !strcmp(argv[2], "orbit")      ? ORBIT
                      : !strcmp(argv[2], "approach") ? APPROACH
                                                     : DRAG;
        return callgrind(w, !strcmp(argv[3], "renderer"), frames > 0 ? frames : 2);
    }
    int arg = 1;
    if (argc > 1 && !strcmp(argv[1], "stages")) {
        print_stages = 1;
        arg = 2;
    }
    int frames = argc > arg ? atoi(argv[arg]) : 12;
    int threads = argc > arg + 1 ? atoi(argv[arg + 1]) : 2;
    if (frames < 1) frames = 12;
    if (threads < 1) threads = 2;
    printf("bench_live: teapot demo scene, 1024 x 1024, 1 spp, tol 0.25 px, rasterized, %d "
           "thread(s), median of %d frames after a cold one\n",
           threads, frames);
    for (int w = 0; w < WORKLOADS; ++w) {
        printf("%s:\n", workload_name[w]);
        run(w, 0, frames, threads);
        if (HAVE_RENDERER) run(w, 1, frames, threads);
    }
    return 0;
}

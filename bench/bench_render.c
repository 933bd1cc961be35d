/* bench_render: the rasterizer pipeline on the Utah teapot at 1024 x 1024, 0.25 px tolerance
 * (issue 8): tessellation and raster time, ms per frame for flat, Gouraud, Phong, textured and
 * 4x/16x supersampled on 1 and 2 threads, Gouraud/Phong fill rates, the cost of each effect
 * from the stage report, and the peak memory of a 4096 x 4096 frame at 16 spp.
 * Usage: bench_render [repeats (default 3)]
 *        bench_render effects [repeats]   only the cost of each effect and the peak memory
 *        bench_render warm N      N warm-cache 1024 x 1024 Phong frames (for profilers)
 *        bench_render frame 0|1   one 256 x 256 Phong frame of the teapot, without (0) or with (1)
 *                                 features the scene defines but does not use (a texture, a
 *                                 transparent material, lights of zero intensity), to compare
 *                                 instruction counts under valgrind --tool=callgrind */
#define _POSIX_C_SOURCE 200809L
#include "bench_clock.h"
#include "casteljau/render.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#ifndef CJ_TEAPOT_PATH
#define CJ_TEAPOT_PATH "data/teapot.bpt"
#endif

static double stage_sec(const cj_stage_report *r, const char *name) {
    const cj_stage *s = cj_stage_report_find(r, name);
    return s ? s->seconds : 0.0;
}

/* The stage's "cpu_seconds" value (the workers' CPU time), or its wall seconds. */
static double stage_cpu(const cj_stage_report *r, const char *name) {
    const cj_stage *s = cj_stage_report_find(r, name);
    if (!s) return 0.0;
    for (int i = 0; i < s->extra_count; ++i)
        if (!strcmp(s->extra[i].key, "cpu_seconds")) return s->extra[i].value;
    return s->seconds;
}

static uint64_t stage_in(const cj_stage_report *r, const char *name) {
    const cj_stage *s = cj_stage_report_find(r, name);
    return s ? s->in : 0;
}

/* The demo teapot alone (no floor, no control net), with the given shading and texture. */
static cj_scene *teapot(cj_shading shading, int textured, int transparent_sphere) {
    cj_scene *s = NULL;
    if (cj_render_demo_scene(CJ_TEAPOT_PATH, NULL, &s)) {
        fprintf(stderr, "bench_render: %s\n", cj_last_error());
        exit(1);
    }
    cj_scene_node_mut(s, 0)->overlay.flags = 0;
    cj_scene_node_mut(s, 1)->visible = 0;
    cj_material *m = cj_scene_material_mut(s, 0);
    m->shading = shading;
    if (!textured) {
        m->texture = -1;
        m->color = cj_rgb_make(0.8, 0.3, 0.2);
    }
    if (transparent_sphere) {
        cj_material g = cj_material_defaults();
        g.opacity = 0.4;
        g.color = cj_rgb_make(0.3, 0.5, 0.9);
        int mi, gi;
        cj_geometry geo;
        memset(&geo, 0, sizeof geo);
        geo.kind = CJ_GEOM_SPHERE;
        geo.u.sphere.center = cj_v3(0.8, 1.2, 2.2);
        geo.u.sphere.radius = 1.0;
        if (cj_scene_add_material(s, &g, &mi) || cj_scene_add_geometry(s, &geo, &gi)) exit(1);
        cj_node n = cj_node_defaults(gi, mi);
        if (cj_scene_add_node(s, &n, NULL)) exit(1);
    }
    return s;
}

typedef struct run_result {
    double frame_ms, cpu_ms, tess_ms, run_ms, raster_ms, shade_ms;
    cj_stage_report rep;
} run_result;

/* Median over `reps` renders of the wall time per frame (and the stage report of the median). */
static run_result measure(const cj_scene *s, int w, int spp, int threads, int reps,
                          cj_render_cache *cache) {
    cj_render_options o = cj_render_options_defaults();
    o.cache = cache;
    o.width = o.height = w;
    o.spp = spp;
    o.threads = threads;
    o.tol_px = 0.25;
    double t[16], cpu[16];
    cj_stage_report reps_[16];
    if (reps > 16) reps = 16;
    if (cache) { /* warm the cache: the measured frames reuse the tessellation */
        cj_render_image *img = NULL;
        if (cj_render_raster(s, &o, 0, NULL, &img, NULL)) exit(1);
        cj_render_image_destroy(img);
    }
    for (int i = 0; i < reps; ++i) {
        cj_render_image *img = NULL;
        double a = cj_bench_wall(), ca = cj_bench_process_cpu();
        if (cj_render_raster(s, &o, 0, NULL, &img, &reps_[i])) {
            fprintf(stderr, "bench_render: %s\n", cj_last_error());
            exit(1);
        }
        t[i] = cj_bench_wall() - a;
        cpu[i] = cj_bench_process_cpu() - ca;
        cj_render_image_destroy(img);
    }
    double sorted[16];
    memcpy(sorted, t, sizeof(double) * (size_t)reps);
    qsort(sorted, (size_t)reps, sizeof(double), cj_bench_cmp_double);
    int med = 0;
    for (int i = 0; i < reps; ++i)
        if (t[i] == sorted[reps / 2]) med = i;
    run_result r;
    r.rep = reps_[med];
    r.frame_ms = 1e3 * t[med];
    memcpy(sorted, cpu, sizeof(double) * (size_t)reps);
    qsort(sorted, (size_t)reps, sizeof(double), cj_bench_cmp_double);
    r.cpu_ms = 1e3 * sorted[reps / 2];
    r.tess_ms = 1e3 * stage_sec(&r.rep, "tessellate_patches");
    r.run_ms = 1e3 * cj_stage_report_find(&r.rep, "rasterize")->extra[2].value;
    r.raster_ms = 1e3 * stage_sec(&r.rep, "rasterize");
    r.shade_ms = 0.0;
    const char *shade[] = {"shade_unlit", "shade_flat", "shade_gouraud", "shade_phong"};
    for (int i = 0; i < 4; ++i) r.shade_ms += 1e3 * stage_sec(&r.rep, shade[i]);
    return r;
}

static void peak_memory(void) {
    fflush(stdout);
    pid_t pid = fork();
    if (pid == 0) {
        cj_scene *s = teapot(CJ_SHADE_PHONG, 1, 0);
        cj_render_options o = cj_render_options_defaults();
        o.width = o.height = 4096;
        o.spp = 16;
        cj_render_image *img = NULL;
        int rc = cj_render_raster(s, &o, 0, NULL, &img, NULL) != CJ_OK;
        cj_render_image_destroy(img);
        cj_scene_destroy(s);
        _exit(rc);
    }
    int status = 0;
    struct rusage ru;
    if (pid < 0 || waitpid(pid, &status, 0) < 0 || getrusage(RUSAGE_CHILDREN, &ru) != 0 ||
        !WIFEXITED(status) || WEXITSTATUS(status)) {
        printf("peak memory: the 4096 x 4096 render failed\n");
        return;
    }
    printf("peak memory of a 4096 x 4096 frame at 16 spp (textured Phong teapot, 2 threads): "
           "%.0f MiB maxrss (the image alone: 4096^2 x 16 bytes = 256 MiB)\n",
           ru.ru_maxrss / 1024.0);
}

/* One frame for the callgrind comparison of an unused effect's cost. */
static int one_frame(int unused) {
    cj_scene *s = teapot(CJ_SHADE_PHONG, 0, 0);
    if (unused) {
        cj_texture t = cj_texture_defaults(CJ_TEX_CHECKER);
        cj_material m = cj_material_defaults();
        m.opacity = 0.5;
        cj_light l = cj_light_defaults(CJ_LIGHT_SPOT);
        l.intensity = 0.0;
        cj_light a = cj_light_defaults(CJ_LIGHT_AMBIENT);
        a.intensity = 0.0;
        if (cj_scene_add_texture(s, &t, NULL) || cj_scene_add_material(s, &m, NULL) ||
            cj_scene_add_light(s, &l, NULL) || cj_scene_add_light(s, &a, NULL))
            return 1;
    }
    cj_render_options o = cj_render_options_defaults();
    o.width = o.height = 256;
    o.spp = 1;
    o.threads = 1;
    cj_render_image *img = NULL;
    cj_stage_report rep;
    if (cj_render_raster(s, &o, 0, NULL, &img, &rep)) return 1;
    printf("frame %d: %.1f ms\n", unused, 1e3 * rep.total_seconds);
    cj_render_image_destroy(img);
    cj_scene_destroy(s);
    return 0;
}

int main(int argc, char **argv) {
    if (argc > 2 && !strcmp(argv[1], "frame")) return one_frame(atoi(argv[2]));
    if (argc > 2 && !strcmp(argv[1], "warm")) { /* N warm Phong frames (for profilers) */
        cj_scene *s = teapot(CJ_SHADE_PHONG, 0, 0);
        cj_render_cache *cache = NULL;
        if (cj_render_cache_create(NULL, &cache)) return 1;
        run_result r = measure(s, 1024, 1, 1, atoi(argv[2]), cache);
        printf("warm phong frame: %.1f ms wall, %.1f ms cpu\n", r.frame_ms, r.cpu_ms);
        cj_render_cache_destroy(cache);
        cj_scene_destroy(s);
        return 0;
    }
    int effects_only = argc > 1 && !strcmp(argv[1], "effects");
    int reps = argc > 1 + effects_only ? atoi(argv[1 + effects_only]) : 3;
    if (reps < 1) reps = 1;
    printf("bench_render: Utah teapot (demo camera), 1024 x 1024, tol 0.25 px, median of %d "
           "frames; times in ms.\n  frame = wall time of the whole cj_render_raster call; cpu = "
           "its CPU time (all threads; "
           "on a shared machine the honest cost); tess = tessellation; "
           "tiles = wall time of the tile run (visibility + shading + output); raster, shade = "
           "their parts summed over the workers\n\n",
           reps);
    if (effects_only) goto effects; /* bench_render effects [reps]: only the last part */
    printf("%-26s %7s %7s %7s %7s %8s %8s %8s %8s %10s\n", "config", "threads", "frame", "cpu",
           "tess", "non-tess", "tiles", "raster", "shade", "triangles");
    struct {
        const char *name;
        cj_shading sh;
        int tex, spp;
    } cfg[] = {{"flat", CJ_SHADE_FLAT, 0, 1},
               {"gouraud", CJ_SHADE_GOURAUD, 0, 1},
               {"phong", CJ_SHADE_PHONG, 0, 1},
               {"phong + texture", CJ_SHADE_PHONG, 1, 1},
               {"phong + texture, 4 spp", CJ_SHADE_PHONG, 1, 4},
               {"phong + texture, 16 spp", CJ_SHADE_PHONG, 1, 16}};
    double fill[2] = {0, 0};
    for (size_t c = 0; c < sizeof cfg / sizeof cfg[0]; ++c) {
        cj_scene *s = teapot(cfg[c].sh, cfg[c].tex, 0);
        for (int th = 1; th <= 2; ++th) {
            run_result r = measure(s, 1024, cfg[c].spp, th, reps, NULL);
            printf("%-26s %7d %7.1f %7.1f %7.1f %8.1f %8.1f %8.1f %8.1f %10llu\n", cfg[c].name, th,
                   r.frame_ms, r.cpu_ms, r.tess_ms, r.frame_ms - r.tess_ms, r.run_ms, r.raster_ms,
                   r.shade_ms,
                   (unsigned long long)cj_stage_report_find(&r.rep, "tessellate_patches")->out);
            if (th == 1 && !cfg[c].tex &&
                (cfg[c].sh == CJ_SHADE_GOURAUD || cfg[c].sh == CJ_SHADE_PHONG)) {
                const char *st = cfg[c].sh == CJ_SHADE_GOURAUD ? "shade_gouraud" : "shade_phong";
                fill[cfg[c].sh == CJ_SHADE_PHONG] =
                    stage_in(&r.rep, st) / stage_cpu(&r.rep, st) / 1e6;
            }
        }
        cj_scene_destroy(s);
    }
    printf("\nshading fill rate (1 thread, deferred, per shaded sample, worker CPU time): Gouraud "
           "%.1f Msamples/s, "
           "Phong %.1f Msamples/s\n",
           fill[0], fill[1]);

    /* the same frames with a warm tessellation cache (a still camera: the viewer, animation of
     * transforms) */
    printf("\nwith a warm tessellation cache (cj_render_cache; the same view, so the same "
           "image):\n");
    printf("%-26s %7s %7s %7s %8s %8s %8s\n", "config", "threads", "frame", "cpu", "tiles",
           "raster", "shade");
    for (size_t c = 0; c < sizeof cfg / sizeof cfg[0]; ++c) {
        cj_scene *s = teapot(cfg[c].sh, cfg[c].tex, 0);
        for (int th = 1; th <= 2; ++th) {
            cj_render_cache *cache = NULL;
            if (cj_render_cache_create(NULL, &cache)) return 1;
            run_result r = measure(s, 1024, cfg[c].spp, th, reps, cache);
            printf("%-26s %7d %7.1f %7.1f %8.1f %8.1f %8.1f\n", cfg[c].name, th, r.frame_ms,
                   r.cpu_ms, r.run_ms, r.raster_ms, r.shade_ms);
            cj_render_cache_destroy(cache);
        }
        cj_scene_destroy(s);
    }
effects:;
    cj_render_cache *cache = NULL;
    if (cj_render_cache_create(NULL, &cache)) return 1;

    printf("\ncost of each effect (1 thread, 1024 x 1024, warm tessellation cache; frame CPU ms "
           "and the change; stage seconds (wall, summed over workers) from the report):\n");
    cj_scene *base = teapot(CJ_SHADE_PHONG, 0, 0);
    run_result r0 = measure(base, 1024, 1, 1, reps, cache);
    printf("  phong, untextured, opaque, 1 spp: cpu %.1f, shade_phong %.1f\n", r0.cpu_ms,
           1e3 * stage_sec(&r0.rep, "shade_phong"));
    cj_scene *tex = teapot(CJ_SHADE_PHONG, 1, 0);
    run_result r1 = measure(tex, 1024, 1, 1, reps, cache);
    printf("  + checker texture:    cpu %.1f (%+.1f), shade_phong incl. texture %.1f\n", r1.cpu_ms,
           r1.cpu_ms - r0.cpu_ms, 1e3 * stage_sec(&r1.rep, "texture"));
    cj_scene *tr = teapot(CJ_SHADE_PHONG, 0, 1);
    run_result r2 = measure(tr, 1024, 1, 1, reps, cache);
    printf("  + transparent sphere: cpu %.1f (%+.1f), sort_transparent %.1f, transparency %.1f "
           "(%llu triangles, %llu fragments)\n",
           r2.cpu_ms, r2.cpu_ms - r0.cpu_ms, 1e3 * stage_sec(&r2.rep, "sort_transparent"),
           1e3 * stage_sec(&r2.rep, "transparency"),
           (unsigned long long)cj_stage_report_find(&r2.rep, "transparency")->in,
           (unsigned long long)cj_stage_report_find(&r2.rep, "transparency")->out);
    run_result r3 = measure(base, 1024, 4, 1, reps, cache);
    printf("  4 spp instead of 1:   cpu %.1f (%+.1f), rasterize %.1f, resolve %.1f\n", r3.cpu_ms,
           r3.cpu_ms - r0.cpu_ms, r3.raster_ms, 1e3 * stage_sec(&r3.rep, "resolve"));
    run_result r5 = measure(base, 1024, 16, 1, reps, cache);
    printf("  16 spp instead of 1:  cpu %.1f (%+.1f), rasterize %.1f, resolve %.1f\n", r5.cpu_ms,
           r5.cpu_ms - r0.cpu_ms, r5.raster_ms, 1e3 * stage_sec(&r5.rep, "resolve"));
    cj_scene_node_mut(base, 0)->overlay.flags = CJ_OVERLAY_CONTROL_NET;
    run_result r4 = measure(base, 1024, 1, 1, reps, cache);
    printf("  + control net:        cpu %.1f (%+.1f), overlay_lines %.1f\n", r4.cpu_ms,
           r4.cpu_ms - r0.cpu_ms, 1e3 * stage_sec(&r4.rep, "overlay_lines"));
    cj_scene_destroy(base);
    cj_scene_destroy(tex);
    cj_scene_destroy(tr);
    cj_render_cache_destroy(cache);
    peak_memory();
    return 0;
}

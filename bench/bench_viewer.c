/* bench_viewer: `casteljau view` on the demo teapot under a private Xvfb (Mesa llvmpipe).
 *
 * 1. Replay drag (deterministic): one control point dragged along a 40 px circle at 1024 x 1024,
 *    1 spp, 0.25 px (the viewer draws drag frames at 1 px), through a replay script; a replay waits
 * for every picture, so the viewer's
 *    --frame-times give the cost of a drag frame (render + upload + draw + swap + glFinish):
 *    median, 90th and 99th percentiles and maximum for 1 and 2 renderer threads, and the median
 *    of cj_render_raster alone in this process.
 * 2. Live drag at the viewer's default size (the scene's 800 x 600): real X input (xdotool
 *    mouse moves every 20 ms for about 4 s) on a control point and on the background (orbit),
 *    2 renderer threads; from the viewer's --timeline: pictures shown per second while the
 *    mouse moves and the median render time of a drag frame.
 * 3. Input during a ray-traced pass (800 x 600, 2 threads): R, then repeatedly a key (G, a new
 *    state) while pass 3 or 4 runs; from the timeline: key -> the window redrawn (the old
 *    picture with the new overlay), key -> the pass cancelled, key -> the first picture of the
 *    new state (the quick pass). Times are taken where the viewer receives the key.
 *
 *   bench_viewer [FRAMES] [--live]    (FRAMES: replay drag steps, default 60; --live: 2 and 3 only)
 */
#define _POSIX_C_SOURCE 200809L
#include "bench_clock.h"
#include "casteljau/render.h"
#include "casteljau/scene_json.h"
#include "casteljau/viewer_scene.h"
#include "xvfb.h"

#include <sys/wait.h>

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

static int cj_vtrace_spp_of(int pass) {
    static const int spp[] = {1, 1, 4, 16, 64}; /* the viewer's passes (viewer_render.c) */
    return spp[pass];
}

static int replay_drag(int frames);
static int live(void);

int main(int argc, char **argv) {
    int frames = 60, live_only = 0;
    for (int i = 1; i < argc; ++i) {
        if (!strcmp(argv[i], "--live"))
            live_only = 1;
        else
            frames = atoi(argv[i]);
    }
    if (frames < 2 || frames > 100000)
        return fprintf(stderr, "usage: bench_viewer [FRAMES] [--live]\n"), 2;
    const pid_t xvfb = cj_test_xvfb_start(1280, 1100);
    if (xvfb < 0) return fprintf(stderr, "bench_viewer: cannot start Xvfb\n"), 1;
    int rc = live_only ? 0 : replay_drag(frames);
    if (!rc) rc = live();
    cj_test_xvfb_stop(xvfb);
    return rc;
}

static int replay_drag(int frames) {
    cj_scene *s = NULL;
    if (cj_render_demo_scene(CJ_TEAPOT_PATH, NULL, &s))
        return fprintf(stderr, "%s\n", cj_last_error()), 1;
    cj_scene_settings set = *cj_scene_get_settings(s);
    set.width = W, set.height = H, set.spp = 1, set.tol_px = 0.25;
    cj_scene_set_settings(s, &set);
    /* In-process reference: cj_render_raster alone (2 threads), median of 5. */
    double rr[5];
    size_t tris = 0;
    float *depth = malloc((size_t)W * H * sizeof *depth);
    for (int i = 0; i < 5; ++i) {
        cj_render_options ro = cj_render_options_defaults();
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
    const cj_camera cam0 = *cj_scene_get_camera(s);
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

    printf("1. replay drag: teapot demo scene %d x %d, 1 spp, tol 0.25 px (%zu triangles; the "
           "viewer's drag frames at 1 px), dragging control point %zu along a 40 px circle, %d "
           "frames, Xvfb + Mesa llvmpipe\n",
           W, H, tris, picked, frames);
    printf("cj_render_raster alone at 0.25 px (2 threads, in process): median %.1f ms\n",
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
        /* frame 0 is the first picture, frame 1 the press (a redraw): the drag frames follow */
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
        if (cj_scene_load_json_with_options(saved, &jo, NULL, &m) || cj_vscene_create(m, &vm) ||
            cj_vscene_point(vm, picked, &end) ||
            cj_v3_norm(cj_v3_sub(end, start)) > 1e-9 * cj_v3_norm(start) + 1e-12 ||
            memcmp(cj_scene_get_camera(cj_vscene_scene(vm)), &cam0, sizeof cam0))
            return fprintf(stderr, "bench_viewer: the replay did not drag point %zu\n", picked), 1;
        cj_vscene_destroy(vm);
        unlink(saved);
    }
    unlink(script);
    return 0;
}

/* ---- 2 and 3: live input through xdotool, figures from the viewer's timeline ---------------- */

static void sleep_us(long us) {
    struct timespec ts = {us / 1000000, (us % 1000000) * 1000};
    nanosleep(&ts, NULL);
}

typedef struct tline {
    double t;
    char text[120];
} tline;

/* The timeline's lines (caller frees). */
static tline *read_timeline(const char *path, size_t *n) {
    FILE *f = fopen(path, "r");
    size_t cap = 1024;
    tline *l = malloc(cap * sizeof *l);
    *n = 0;
    if (!f || !l) {
        if (f) fclose(f);
        return l;
    }
    char buf[256];
    while (fgets(buf, sizeof buf, f)) {
        if (*n == cap) {
            tline *nl = realloc(l, 2 * cap * sizeof *l);
            if (!nl) break;
            l = nl, cap *= 2;
        }
        char *rest = NULL;
        l[*n].t = strtod(buf, &rest);
        snprintf(l[*n].text, sizeof l[*n].text, "%s", rest && *rest == ' ' ? rest + 1 : "");
        l[*n].text[strcspn(l[*n].text, "\n")] = '\0';
        ++*n;
    }
    fclose(f);
    return l;
}

static int starts(const char *s, const char *p) {
    return !strncmp(s, p, strlen(p));
}

/* The last timeline line starting with `p`, or -1 (polls up to timeout seconds). */
static long wait_for(const char *path, size_t from, const char *p, double timeout) {
    for (double w = 0; w < timeout; w += 0.05) {
        size_t n;
        tline *l = read_timeline(path, &n);
        long at = -1;
        for (size_t i = from; i < n && at < 0; ++i)
            if (starts(l[i].text, p)) at = (long)i;
        free(l);
        if (at >= 0) return at;
        sleep_us(50000);
    }
    return -1;
}

static size_t timeline_lines(const char *path) {
    size_t n;
    free(read_timeline(path, &n));
    return n;
}

static int xdo(const char *cmd) {
    return system(cmd) == 0 ? 0 : (fprintf(stderr, "bench_viewer: failed: %.200s\n", cmd), 1);
}

/* Window coordinates of a visible control point near (fx, fy) of a w x h teapot view. */
static int visible_point(int w, int h, double fx, double fy, int *x, int *y) {
    cj_scene *s = NULL;
    if (cj_render_demo_scene(CJ_TEAPOT_PATH, NULL, &s)) return 1;
    cj_render_options ro = cj_render_options_defaults();
    ro.spp = 1;
    cj_render_image *img = NULL;
    if (cj_render_raster(s, &ro, CJ_IMAGE_DEPTH, NULL, &img, NULL)) return 1;
    cj_vscene *vs = NULL;
    if (cj_vscene_create(s, &vs)) return 1;
    double q[3], best = INFINITY, bq[2] = {0, 0};
    for (size_t k = 0; k < cj_vscene_point_count(vs); ++k)
        if (cj_vscene_project(vs, k, w, h, q) && q[0] >= 0 && q[1] >= 0 && q[0] < w && q[1] < h &&
            q[2] <= img->depth[(size_t)q[1] * (size_t)w + (size_t)q[0]] + CJ_VSCENE_DEPTH_TOL) {
            const double d = hypot(q[0] - fx * w, q[1] - fy * h);
            if (d < best) best = d, bq[0] = q[0], bq[1] = q[1];
        }
    *x = (int)floor(bq[0]);
    *y = h - 1 - (int)floor(bq[1]);
    cj_render_image_destroy(img);
    cj_vscene_destroy(vs);
    return 0;
}

/* Drags from window (x, y) along a 40 px circle, a move every 20 ms for `moves` moves; prints
 * pictures per second and the median render of a drag frame. */
static int live_drag(const char *tpath, const char *what, int x, int y, int moves) {
    const size_t from = timeline_lines(tpath);
    size_t cap = (size_t)moves * 64 + 512;
    char *cmd = malloc(cap);
    if (!cmd) return 1;
    size_t n = (size_t)snprintf(cmd, cap,
                                "W=$(cat /tmp/cj_bench_viewer_win); xdotool mousemove --window $W "
                                "%d %d sleep 0.2 mousedown 1",
                                x, y);
    for (int i = 1; i <= moves && n < cap; ++i) {
        const double a = 6.283185307179586 * i / moves;
        n += (size_t)snprintf(cmd + n, cap - n, " sleep 0.02 mousemove --window $W %d %d",
                              (int)lround(x + 40 * sin(a)), (int)lround(y - 40 * (1 - cos(a))));
    }
    if (n < cap) snprintf(cmd + n, cap - n, " sleep 0.05 mouseup 1");
    const int rc = xdo(cmd);
    free(cmd);
    if (rc || wait_for(tpath, from, "button 0 release", 20) < 0) return 1;
    sleep_us(200000);
    size_t nl;
    tline *l = read_timeline(tpath, &nl);
    double t0 = -1, t1 = -1;
    size_t shown = 0, nr = 0;
    double *rs = malloc(nl * sizeof *rs);
    unsigned long last = 0;
    for (size_t i = from; i < nl && rs; ++i) {
        if (starts(l[i].text, "button 0 press")) t0 = l[i].t;
        if (starts(l[i].text, "button 0 release")) t1 = l[i].t;
        unsigned long gen;
        double sec;
        int pass;
        if (t0 >= 0 && t1 < 0 && sscanf(l[i].text, "shown gen %lu", &gen) == 1 && gen != last)
            ++shown, last = gen;
        if (t0 >= 0 && t1 < 0 &&
            sscanf(l[i].text, "done gen %lu pass %d tiles %*u/%*u in %lf", &gen, &pass, &sec) == 3)
            rs[nr++] = sec;
    }
    if (t0 < 0 || t1 <= t0 || !rs) return free(l), free(rs), 1;
    printf("%-28s %6.2f s %4d moves %4zu pictures: %5.2f per second | drag frame render median "
           "%.1f ms\n",
           what, t1 - t0, moves, shown, shown / (t1 - t0), nr ? 1e3 * pct(rs, nr, 0.5) : NAN);
    free(l);
    free(rs);
    return 0;
}

/* R (when press_r), then `keys` times: wait for pass `pass` to start, press G; key -> redraw /
 * cancel / first picture of the new state. */
static int live_trace(const char *tpath, int keys, int pass, int press_r) {
    size_t from = timeline_lines(tpath);
    if (press_r && xdo("xdotool key r")) return 1;
    double rd[64], cd[64], nd[64];
    unsigned long long done_sum = 0, total_sum = 0;
    int k = 0;
    for (; k < keys && k < 64; ++k) {
        char p[64];
        long at = -1;
        /* the running pass: `pass` of the newest job */
        for (double w = 0; w < 300 && at < 0; w += 0.05) {
            size_t n;
            tline *l = read_timeline(tpath, &n);
            snprintf(p, sizeof p, "trace pass %d", pass);
            for (size_t i = from; i < n; ++i)
                if (starts(l[i].text, "start gen") && strstr(l[i].text, p)) at = (long)i;
            free(l);
            if (at < 0) sleep_us(50000);
        }
        if (at < 0) return fprintf(stderr, "bench_viewer: pass %d never started\n", pass), 1;
        sleep_us(300000);
        from = timeline_lines(tpath);
        if (xdo("xdotool key g")) return 1;
        const long key = wait_for(tpath, from, "key 71", 10);
        const long sub = key >= 0 ? wait_for(tpath, (size_t)key, "submit gen", 10) : -1;
        const long can = key >= 0 ? wait_for(tpath, (size_t)key, "cancelled gen", 30) : -1;
        if (sub < 0 || can < 0) return fprintf(stderr, "bench_viewer: no cancel\n"), 1;
        size_t n;
        tline *l = read_timeline(tpath, &n);
        unsigned long gen = 0;
        unsigned long long d = 0, t = 0;
        sscanf(l[sub].text, "submit gen %lu", &gen);
        sscanf(l[can].text, "cancelled gen %*u pass %*d tiles %llu/%llu", &d, &t);
        done_sum += d, total_sum += t;
        const double tk = l[key].t;
        cd[k] = l[can].t - tk;
        free(l);
        const long red = wait_for(tpath, (size_t)key, "shown gen", 10);
        snprintf(p, sizeof p, "shown gen %lu ", gen);
        const long neu = wait_for(tpath, (size_t)key, p, 60);
        if (red < 0 || neu < 0) return fprintf(stderr, "bench_viewer: nothing shown\n"), 1;
        l = read_timeline(tpath, &n);
        rd[k] = l[red].t - tk;
        nd[k] = l[neu].t - tk;
        from = (size_t)neu;
        free(l);
    }
    printf("%d keys during pass %d (%d spp): key -> window redrawn median %.1f ms (max %.1f) | "
           "key -> pass cancelled median %.1f ms (max %.1f; %llu of %llu tiles drawn) | key -> "
           "first picture of the new state median %.1f ms (max %.1f)\n",
           k, pass + 1, cj_vtrace_spp_of(pass), 1e3 * pct(rd, (size_t)k, 0.5),
           1e3 * pct(rd, (size_t)k, 1.0), 1e3 * pct(cd, (size_t)k, 0.5),
           1e3 * pct(cd, (size_t)k, 1.0), done_sum, total_sum, 1e3 * pct(nd, (size_t)k, 0.5),
           1e3 * pct(nd, (size_t)k, 1.0));
    return 0;
}

static int live(void) {
    const int w = 800, h = 600; /* the demo scene's own size: the viewer's default */
    char tpath[] = "/tmp/cj_bench_viewer_tl_XXXXXX";
    const int fd = mkstemp(tpath);
    if (fd < 0) return 1;
    close(fd);
    char title[64], cmd[1024];
    snprintf(title, sizeof title, "cj-bench-viewer-%d", (int)getpid());
    const pid_t child = fork();
    if (child < 0) return 1;
    if (child == 0) {
        execl(CJ_CLI, CJ_CLI, "view", "--teapot", "--threads", "2", "--title", title, "--timeline",
              tpath, (char *)NULL);
        _exit(4);
    }
    snprintf(cmd, sizeof cmd,
             "W=$(timeout 60 xdotool search --sync --onlyvisible --name '^%s$' | head -1) && "
             "xdotool windowfocus --sync $W && echo $W > /tmp/cj_bench_viewer_win",
             title);
    int rc = xdo(cmd);
    if (!rc && wait_for(tpath, 0, "shown gen 1 ", 120) < 0) rc = 1;
    int px = 0, py = 0;
    if (!rc) rc = visible_point(w, h, 0.55, 0.6, &px, &py);
    if (!rc) {
        printf("2. live drag, %d x %d (the viewer's default), 2 renderer threads, a mouse move "
               "every 20 ms (xdotool):\n",
               w, h);
        rc = live_drag(tpath, "control point drag", px, py, 200);
    }
    if (!rc) rc = live_drag(tpath, "orbit (drag the background)", 60, 60, 200);
    if (!rc) {
        printf("3. input during a ray-traced pass, %d x %d, 2 renderer threads:\n", w, h);
        rc = live_trace(tpath, 8, 2, 1);
    }
    if (!rc) rc = live_trace(tpath, 4, 3, 0);
    xdo("xdotool key Escape");
    int status = 0;
    waitpid(child, &status, 0);
    unlink(tpath);
    unlink("/tmp/cj_bench_viewer_win");
    return rc;
}

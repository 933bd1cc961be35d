/* `casteljau view --teapot` with a REAL mouse drag of a control point (xdotool under a private
 * Xvfb), the viewer's --timeline and the window's pixels read back from the X server:
 *   - drag frames re-tessellate through the tessellation cache (patches planned and built per
 *     frame are in the timeline), and a drag frame still tessellating when a newer drag state
 *     arrives is dropped ("cancelled ... preparing drag"): at least one such drop in a fast drag
 *     (the drag is repeated, up to 4 times, until one lands in a frame's preparation; how many
 *     drops happen is a timing figure, printed);
 *   - never two drag frames dropped in a row (a frame is shown at least every other state), and
 *     drag frames are shown during the drag;
 *   - after the release the window shows the still view: pixel for pixel `casteljau render` of
 *     the scene the viewer saved (ctrl+S). */
#define _DEFAULT_SOURCE
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "casteljau/image_io.h"
#include "casteljau/render.h"
#include "casteljau/viewer_scene.h"
#include "cli_run.h"
#include "support/timeline.h"
#include "support/xvfb.h"

#include <X11/Xlib.h>
#include <X11/Xutil.h>

#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

static char dir[] = "/tmp/cj_viewer_drag_XXXXXX";
enum { W = 320, H = 240 };

static int sh(const char *cmd) {
    cj_cli_result r;
    assert_int_equal(cj_cli_shell(cmd, &r), 0);
    const int st = r.status;
    if (st) printf("command failed (%d): %s\n%s%s", st, cmd, r.out, r.err);
    cj_cli_result_free(&r);
    return st;
}

/* A visible control point of the demo teapot at W x H (as test_viewer_window picks one): its
 * window pixel (x right, y down). */
static void visible_point(int *x, int *y) {
    cj_scene *s = NULL;
    assert_int_equal(cj_render_demo_scene(CJ_TEAPOT_PATH, NULL, &s), CJ_OK);
    cj_scene_settings set = *cj_scene_get_settings(s);
    set.width = W, set.height = H, set.spp = 1;
    assert_int_equal(cj_scene_set_settings(s, &set), CJ_OK);
    cj_render_image *img = NULL;
    cj_render_options ro = cj_render_options_defaults();
    assert_int_equal(cj_render_raster(s, &ro, CJ_IMAGE_DEPTH, NULL, &img, NULL), CJ_OK);
    cj_vscene *vs = NULL;
    assert_int_equal(cj_vscene_create(s, &vs), CJ_OK);
    size_t picked = 0;
    double q[3];
    int found = 0;
    for (size_t k = 0; k < cj_vscene_point_count(vs) && !found; k += 7)
        if (cj_vscene_project(vs, k, W, H, q) && q[0] > 60 && q[0] < W - 60 && q[1] > 60 &&
            q[1] < H - 60)
            found = cj_vscene_pick(vs, W, H, img->depth, floor(q[0]) + 0.5, floor(q[1]) + 0.5, 8,
                                   &picked);
    assert_true(found);
    assert_true(cj_vscene_project(vs, picked, W, H, q));
    *x = (int)floor(q[0]);
    *y = H - 1 - (int)floor(q[1]);
    cj_render_image_destroy(img);
    cj_vscene_destroy(vs);
}

/* The window's pixels as the X server holds them, 0xRRGGBB. */
static unsigned *grab(Display *dpy, Window win) {
    XImage *im = XGetImage(dpy, win, 0, 0, W, H, AllPlanes, ZPixmap);
    assert_non_null(im);
    unsigned *px = malloc(sizeof *px * W * H);
    assert_non_null(px);
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) px[y * W + x] = (unsigned)XGetPixel(im, x, y) & 0xffffffu;
    XDestroyImage(im);
    return px;
}

/* Interactive generations submitted, drag frames dropped while preparing, drag frames done
 * with tessellation work, and whether two drops ever followed each other with no frame done
 * between them. */
typedef struct drag_stats {
    int interactive, dropped, done_tess, shown_drag, consecutive_drops;
    int whole;      /* drag frames that re-planned all 32 patches (the tolerance left its band) */
    size_t planned; /* patches planned by drag frames */
    unsigned long last_interactive;
} drag_stats;

static void scan(const char *tl, long from, drag_stats *ds) {
    memset(ds, 0, sizeof *ds);
    static unsigned char inter[1 << 16];
    memset(inter, 0, sizeof inter);
    int dropped_last = 0;
    for (const char *line = tl + from; *line;) {
        const char *end = strchr(line, '\n');
        const char *ev = strchr(line, ' ');
        unsigned long g = 0;
        unsigned long long d = 0, t = 0;
        size_t planned = 0, built = 0;
        if (ev && sscanf(ev, " submit gen %lu", &g) == 1 && strstr(ev, "interactive") &&
            (!end || strstr(ev, "interactive") < end)) {
            ++ds->interactive;
            ds->last_interactive = g;
            inter[g & 0xffff] = 1;
        } else if (ev && sscanf(ev, " cancelled gen %lu pass 0 tiles %llu/%llu", &g, &d, &t) == 3 &&
                   strstr(ev, "preparing drag") && (!end || strstr(ev, "preparing drag") < end)) {
            assert_true(inter[g & 0xffff]); /* only drag frames are dropped so */
            assert_true(t == 0);            /* before any tile */
            ++ds->dropped;
            ds->consecutive_drops += dropped_last;
            dropped_last = 1;
        } else if (ev && sscanf(ev, " done gen %lu pass 0 tiles %llu/%llu in %*f s patches %zu/%zu",
                                &g, &d, &t, &planned, &built) == 5) {
            dropped_last = 0;
            if (inter[g & 0xffff] && built > 0) ++ds->done_tess;
            if (inter[g & 0xffff]) ds->planned += planned, ds->whole += planned >= 32;
        } else if (ev && sscanf(ev, " shown gen %lu", &g) == 1 && inter[g & 0xffff]) {
            ++ds->shown_drag;
        }
        if (!end) break;
        line = end + 1;
    }
}

/* Pixels of the PNG at `png` that differ from the window's. */
static long differ_window(const unsigned *win, const char *png) {
    int w, h;
    uint8_t *x = NULL;
    assert_int_equal(cj_image_read(png, &w, &h, &x), CJ_OK);
    assert_int_equal(w, W);
    assert_int_equal(h, H);
    long n = 0;
    for (long y = 0; y < H; ++y)
        for (long c = 0; c < W; ++c) {
            const uint8_t *p = x + 4 * ((H - 1 - y) * W + c); /* rows bottom-up */
            const unsigned rgb = (unsigned)p[0] << 16 | (unsigned)p[1] << 8 | p[2];
            n += rgb != win[y * W + c];
        }
    cj_image_free(x);
    return n;
}

static void test_drag_drops_preparing_frames(void **state) {
    (void)state;
    int px, py;
    visible_point(&px, &py);
    char title[64], tpath[512], cmd[8192];
    snprintf(title, sizeof title, "cj-drag-%d", (int)getpid());
    snprintf(tpath, sizeof tpath, "%s/timeline.txt", dir);
    const pid_t child = fork();
    assert_true(child >= 0);
    if (child == 0) {
        char w[16], h[16];
        snprintf(w, sizeof w, "%d", W);
        snprintf(h, sizeof h, "%d", H);
        if (chdir(dir)) _exit(3);
        execl(CJ_CLI, CJ_CLI, "view", "--teapot", "--width", w, "--height", h, "--spp", "1",
              "--threads", "1", "--hide-overlay", "--title", title, "--timeline", tpath,
              (char *)NULL);
        _exit(4);
    }
    snprintf(cmd, sizeof cmd,
             "W=$(timeout 30 xdotool search --sync --onlyvisible --name '^%s$' | head -1) && "
             "xdotool windowfocus --sync $W && echo $W > %s/win.txt",
             title, dir);
    assert_int_equal(sh(cmd), 0);
    char wpath[512];
    snprintf(wpath, sizeof wpath, "%s/win.txt", dir);
    FILE *wf = fopen(wpath, "r");
    assert_non_null(wf);
    unsigned long wid = 0;
    assert_int_equal(fscanf(wf, "%lu", &wid), 1);
    fclose(wf);
    assert_true(cj_timeline_wait_line(tpath, 0, "shown gen 1 ", 60) >= 0);
    /* the first frame's time sets how long the button stays down after the moves, so that a
     * drag frame can finish while the button is held whatever the build's speed (a sanitizer
     * build's frame takes about 0.8 s, a release build's about 0.05 s) */
    double frame_s = 0.0;
    {
        char *tl = cj_timeline_read(tpath);
        const char *d1 = strstr(tl, "done gen 1 ");
        assert_non_null(d1);
        const char *in = strstr(d1, " in ");
        assert_true(in && sscanf(in, " in %lf", &frame_s) == 1);
        free(tl);
    }
    const double hold_s = fmax(0.2, 3.0 * frame_s);

    /* a fast drag: press on the point, 40 moves a few ms apart, hold, release; repeated (the point
     * goes back and forth) until a drag frame was dropped while tessellating */
    drag_stats ds;
    int tries = 0, x = px, y = py;
    long from = cj_timeline_size(tpath);
    do {
        from = cj_timeline_size(tpath);
        int n = snprintf(cmd, sizeof cmd,
                         "xdotool mousemove --window %lu %d %d sleep 0.2 mousedown 1 sleep 0.05",
                         wid, x, y);
        const int dir_x = tries % 2 ? -1 : 1;
        for (int i = 1; i <= 40; ++i)
            n += snprintf(cmd + n, sizeof cmd - (size_t)n,
                          " mousemove --window %lu %d %d sleep 0.004", wid, x + dir_x * i,
                          y + (i % 3));
        x += dir_x * 40;
        y += 40 % 3;
        snprintf(cmd + n, sizeof cmd - (size_t)n, " sleep %.2f mouseup 1", hold_s);
        assert_int_equal(sh(cmd), 0);
        assert_true(cj_timeline_wait_line(tpath, from, "button 0 release", 20) >= 0);
        char *tl = cj_timeline_read(tpath);
        scan(tl, from, &ds);
        assert_non_null(strstr(tl + from, "drag point")); /* the press picked the point */
        free(tl);
        ++tries;
    } while (ds.dropped == 0 && tries < 4);
    /* the still view after the release: the next (non-interactive) submit, shown */
    const long rel = cj_timeline_wait_line(tpath, from, "button 0 release", 20);
    const long still = cj_timeline_wait_line(tpath, rel, "submit gen", 20);
    assert_true(still >= 0);
    char *tl = cj_timeline_read(tpath);
    unsigned long gen_still = 0;
    const char *sub = strstr(tl + still, "submit");
    assert_int_equal(sscanf(sub, "submit gen %lu", &gen_still), 1);
    const char *eol = strchr(sub, '\n'), *inter = strstr(sub, "interactive");
    assert_true(inter == NULL || (eol && inter > eol)); /* the still view: not a drag frame */
    free(tl);
    char want[64];
    snprintf(want, sizeof want, "shown gen %lu ", gen_still);
    assert_true(cj_timeline_wait_line(tpath, still, want, 60) >= 0);
    cj_test_sleep(0.3);
    Display *dpy = XOpenDisplay(NULL);
    assert_non_null(dpy);
    unsigned *win = grab(dpy, (Window)wid);
    XCloseDisplay(dpy);

    tl = cj_timeline_read(tpath);
    drag_stats all;
    scan(tl, 0, &all);
    free(tl);
    assert_true(ds.dropped >= 1);
    assert_int_equal(all.consecutive_drops, 0);
    assert_true(all.done_tess >= 1);
    assert_true(all.shown_drag >= 1);

    /* the still view == `casteljau render` of the saved scene */
    assert_int_equal(sh("xdotool key ctrl+s"), 0);
    snprintf(cmd, sizeof cmd,
             "for i in $(seq 50); do [ -s %s/teapot_scene.json ] && break; "
             "sleep 0.1; done; sleep 0.3",
             dir);
    assert_int_equal(sh(cmd), 0);
    assert_int_equal(sh("xdotool key Escape"), 0);
    int status = -1;
    for (int i = 0; i < 300; ++i) {
        if (waitpid(child, &status, WNOHANG) == child) break;
        cj_test_sleep(0.1);
        if (i == 299) {
            kill(child, SIGKILL);
            waitpid(child, &status, 0);
        }
    }
    assert_true(WIFEXITED(status) && WEXITSTATUS(status) == 0);
    snprintf(cmd, sizeof cmd, "cd %s && %s render teapot_scene.json -o still.png --threads 2", dir,
             CJ_CLI);
    assert_int_equal(sh(cmd), 0);
    char png[600];
    snprintf(png, sizeof png, "%s/still.png", dir);
    const long diff = differ_window(win, png);
    free(win);
    assert_int_equal(diff, 0);
    printf("real drag of a teapot control point (%d drag%s of 40 moves): %d drag states, %d drag "
           "frames dropped while tessellating (never two in a row), %d drag frames re-tessellated "
           "and drawn (%zu patches planned in all, %d frames re-planning all 32), %d presentations "
           "of drag frames; the still view after the release == "
           "`casteljau render` of the "
           "saved scene, 0 of %d pixels differ\n",
           tries, tries > 1 ? "s" : "", all.interactive, all.dropped, all.done_tess, all.planned,
           all.whole, all.shown_drag, W * H);
}

int main(void) {
    if (!mkdtemp(dir)) return 1;
    setenv("LSAN_OPTIONS", "detect_leaks=0", 1); /* Mesa's driver: see test_viewer_window */
    const pid_t xvfb = cj_test_xvfb_start(1024, 768);
    if (xvfb < 0) {
        fprintf(stderr, "test_viewer_drag: cannot start Xvfb\n");
        return 1;
    }
    printf("test_viewer_drag: private X server on DISPLAY=%s, files in %s\n", getenv("DISPLAY"),
           dir);
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_drag_drops_preparing_frames),
    };
    const int rc = cmocka_run_group_tests(tests, NULL, NULL);
    cj_test_xvfb_stop(xvfb);
    char cmd[600];
    snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
    if (!rc && system(cmd) != 0) return 1;
    return rc;
}

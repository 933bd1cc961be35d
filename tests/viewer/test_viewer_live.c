/* `casteljau view` driven by REAL X input (xdotool) under a private Xvfb (Mesa llvmpipe), the
 * window's pixels read back from the X server (XGetImage), and the viewer's --timeline:
 *   - keys redraw at once: F1 shows the help (the window's pixels change with no other event),
 *     / hides it again (the pixels are those before F1, bit for bit), O hides the overlay;
 *   - a ray-traced pass in flight is interrupted by a key: the pass is cancelled before it drew
 *     all its tiles and the next picture shown is of the new state (the time from the key to it
 *     is printed, not asserted: it is a timing figure, measured in bench_viewer);
 *   - the progressive passes of a replay equal `casteljau trace` of the saved scene at the same
 *     samples per pixel, pixel for pixel. */
#define _DEFAULT_SOURCE
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "casteljau/image_io.h"
#include "cli_run.h"
#include "support/png_diff.h"
#include "support/timeline.h"
#include "support/xvfb.h"

#include <X11/Xlib.h>
#include <X11/Xutil.h>

#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

static char dir[] = "/tmp/cj_viewer_live_XXXXXX";
enum { W = 320, H = 240 };

static int sh(const char *cmd) {
    cj_cli_result r;
    assert_int_equal(cj_cli_shell(cmd, &r), 0);
    const int st = r.status;
    if (st) printf("command failed (%d): %s\n%s%s", st, cmd, r.out, r.err);
    cj_cli_result_free(&r);
    return st;
}

/* The window's pixels as the X server holds them (what the screen shows), 0xRRGGBB. */
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

static long differ(const unsigned *a, const unsigned *b) {
    long n = 0;
    for (long i = 0; i < (long)W * H; ++i) n += a[i] != b[i];
    return n;
}

/* Waits until the window's pixels stop changing (two equal grabs 0.3 s apart). */
static unsigned *grab_settled(Display *dpy, Window win) {
    unsigned *a = grab(dpy, win);
    for (int i = 0; i < 40; ++i) {
        cj_test_sleep(0.3);
        unsigned *b = grab(dpy, win);
        const long d = differ(a, b);
        free(a);
        a = b;
        if (!d) break;
    }
    return a;
}

static double time_of(const char *tl, long at) {
    return strtod(tl + at, NULL);
}

static void test_real_keys_and_interrupt(void **state) {
    (void)state;
    char title[64], tpath[512], cmd[2048];
    snprintf(title, sizeof title, "cj-live-%d", (int)getpid());
    snprintf(tpath, sizeof tpath, "%s/timeline.txt", dir);
    const pid_t child = fork();
    assert_true(child >= 0);
    if (child == 0) {
        char w[16], h[16];
        snprintf(w, sizeof w, "%d", W);
        snprintf(h, sizeof h, "%d", H);
        execl(CJ_CLI, CJ_CLI, "view", "--teapot", "--width", w, "--height", h, "--threads", "1",
              "--title", title, "--timeline", tpath, (char *)NULL);
        _exit(4);
    }
    /* the window, focused, its first picture shown */
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
    Display *dpy = XOpenDisplay(NULL);
    assert_non_null(dpy);
    unsigned *before = grab_settled(dpy, (Window)wid);

    /* F1: the help appears with no other event; / hides it: the very pixels of before */
    assert_int_equal(sh("xdotool key F1"), 0);
    unsigned *help = grab_settled(dpy, (Window)wid);
    const long help_px = differ(before, help);
    assert_true(help_px > 2000);
    assert_int_equal(sh("xdotool key slash"), 0);
    unsigned *nohelp = grab_settled(dpy, (Window)wid);
    assert_int_equal(differ(before, nohelp), 0);
    assert_int_equal(sh("xdotool key o"), 0);
    unsigned *bare = grab_settled(dpy, (Window)wid);
    const long overlay_px = differ(before, bare);
    assert_true(overlay_px > 500);
    printf("real keys: F1 changed %ld of %d window pixels at once, / restored the picture "
           "before F1 bit for bit, O (overlay off) changed %ld\n",
           help_px, W * H, overlay_px);

    /* R: ray tracing, progressive; a key while pass 4 (16 spp) runs cancels it at once */
    long from = cj_timeline_size(tpath);
    assert_int_equal(sh("xdotool key r"), 0);
    /* a hang guard, not a speed test: the sanitizer build's Debug tracer needs about 65 s of
     * CPU for the 4 spp pass alone on one thread, more while other tests share the machine */
    const long started = cj_timeline_wait_line(tpath, from, "trace pass 3", 600);
    assert_true(started >= 0);
    cj_test_sleep(0.3);
    from = cj_timeline_size(tpath);
    assert_int_equal(sh("xdotool key g"), 0); /* shading: a new state */
    const long key_at = cj_timeline_wait_line(tpath, from, "key 71", 10);
    assert_true(key_at >= 0);
    const long submit_at = cj_timeline_wait_line(tpath, key_at, "submit gen", 10);
    assert_true(submit_at >= 0);
    char *tl = cj_timeline_read(tpath);
    unsigned long gen_old = 0, gen_new = 0;
    assert_int_equal(sscanf(strstr(tl + submit_at, "submit"), "submit gen %lu", &gen_new), 1);
    free(tl);
    const long cancel_at = cj_timeline_wait_line(tpath, key_at, "cancelled gen", 30);
    assert_true(cancel_at >= 0);
    char want[64];
    snprintf(want, sizeof want, "shown gen %lu ", gen_new);
    const long next_shown = cj_timeline_wait_line(tpath, cancel_at, want, 60);
    assert_true(next_shown >= 0);
    tl = cj_timeline_read(tpath);
    int pass = -1;
    unsigned long long done = 0, total = 0;
    assert_int_equal(sscanf(strstr(tl + cancel_at, "cancelled"),
                            "cancelled gen %lu pass %d tiles %llu/%llu", &gen_old, &pass, &done,
                            &total),
                     4);
    assert_int_equal(pass, 3);
    assert_true(total > 0 && done < total); /* interrupted: not every tile was drawn */
    assert_true(gen_new > gen_old);         /* the next picture shows the state after the key */
    const double t_key = time_of(tl, key_at), t_cancel = time_of(tl, cancel_at),
                 t_shown = time_of(tl, next_shown);
    printf("ray-traced view: pass 4 (16 spp, gen %lu) cancelled by a key after %llu of %llu tiles "
           "(%.0f ms after the key); the first picture of the new state (gen %lu, quick pass) "
           "shown %.0f ms after the key (one renderer thread, figures only)\n",
           gen_old, done, total, 1e3 * (t_cancel - t_key), gen_new, 1e3 * (t_shown - t_key));
    free(tl);
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
    XCloseDisplay(dpy);
    free(before);
    free(help);
    free(nohelp);
    free(bare);
}

static void test_traced_passes_equal_offline(void **state) {
    (void)state;
    char path[512], cmd[4096];
    snprintf(path, sizeof path, "%s/trace.txt", dir);
    FILE *f = fopen(path, "w");
    assert_non_null(f);
    /* R draws the quick pass; each frame (a screenshot too) the next: 1 spp, then 4 spp */
    fputs("key n\nkey r\nscreenshot pass1.png\nscreenshot pass2.png\nsave traced.json\n", f);
    fclose(f);
    snprintf(cmd, sizeof cmd,
             "cd %s && %s view --teapot --width 160 --height 120 --threads 2 --hide-overlay "
             "--replay trace.txt && %s trace traced.json -o t1.png --spp 1 --threads 2 && "
             "%s trace traced.json -o t4.png --spp 4 --threads 2",
             dir, CJ_CLI, CJ_CLI, CJ_CLI);
    assert_int_equal(sh(cmd), 0);
    assert_int_equal(cj_test_png_differ(dir, "pass1.png", "t1.png"), 0);
    assert_int_equal(cj_test_png_differ(dir, "pass2.png", "t4.png"), 0);
    assert_true(cj_test_png_differ(dir, "pass1.png", "pass2.png") > 0);
    printf("replayed ray-traced passes 2 (1 spp) and 3 (4 spp) == `casteljau trace` of the saved "
           "scene at 1 and 4 spp: 0 of %d pixels differ\n",
           160 * 120);
}

int main(void) {
    if (!mkdtemp(dir)) return 1;
    setenv("LSAN_OPTIONS", "detect_leaks=0", 1); /* Mesa's driver: see test_viewer_window */
    const pid_t xvfb = cj_test_xvfb_start(1024, 768);
    if (xvfb < 0) {
        fprintf(stderr, "test_viewer_live: cannot start Xvfb\n");
        return 1;
    }
    printf("test_viewer_live: private X server on DISPLAY=%s, files in %s\n", getenv("DISPLAY"),
           dir);
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_real_keys_and_interrupt),
        cmocka_unit_test(test_traced_passes_equal_offline),
    };
    const int rc = cmocka_run_group_tests(tests, NULL, NULL);
    cj_test_xvfb_stop(xvfb);
    char cmd[600];
    snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
    if (!rc && system(cmd) != 0) return 1;
    return rc;
}

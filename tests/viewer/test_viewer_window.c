/* `casteljau view` in a real window under a private Xvfb (Mesa llvmpipe), driven by replay
 * scripts and by real X input events (xdotool):
 *   - without a display: one line on stderr, exit status 1;
 *   - 2D: a scripted drag moves exactly the picked point to the place the cursor displacement
 *     gives, and nothing else; after a session of edits (drag, elevate, split, insert, delete,
 *     weights, undo/redo, pan, zoom, construction, frames, hull) the back buffer equals
 *     `casteljau plot` of the saved file pixel for pixel;
 *   - 3D: orbit, pan, zoom, control nets, shading, tolerance and a control-point drag on the
 *     camera plane; the point's new projection is where the cursor went, the other points are
 *     bit-identical, and the back buffer equals `casteljau render` of the saved scene;
 *   - xdotool: a real mouse drag, ctrl+S and Escape sent to the running window.
 * The test starts its own X server, so it runs where there is no display. */
#define _DEFAULT_SOURCE
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "casteljau/image_io.h"
#include "casteljau/render.h"
#include "casteljau/scene_bspline.h"
#include "casteljau/scene_json.h"
#include "casteljau/viewer_model.h"
#include "casteljau/viewer_scene.h"
#include "cli_run.h"
#include "support/png_diff.h"
#include "support/xvfb.h"

#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

static char dir[] = "/tmp/cj_viewer_test_XXXXXX";

static void write_file(const char *name, const char *text) {
    char p[512];
    snprintf(p, sizeof p, "%s/%s", dir, name);
    FILE *f = fopen(p, "w");
    assert_non_null(f);
    fputs(text, f);
    fclose(f);
}

static const char curves[] =
    "{\"width\": 480, \"height\": 360, \"items\": [\n"
    " {\"type\": \"bezier\", \"points\": [[0,0],[1,2.4],[3.2,2.6],[4,0.2]]},\n"
    " {\"type\": \"bezier\", \"points\": [[1,0],[1,1],[0,1]],"
    "  \"weights\": [1, 0.70710678118654757, 1], \"color\": \"#d62728\"},\n"
    " {\"type\": \"catmull-rom\", \"kind\": \"centripetal\","
    "  \"points\": [[0,-1],[1,-0.4],[2,-1.2],[3,-0.3],[4,-1]]}]}\n";

static int run(const char *cmd, cj_cli_result *r) {
    char full[4096];
    snprintf(full, sizeof full, "cd %s && %s", dir, cmd);
    assert_int_equal(cj_cli_shell(full, r), 0);
    return r->status;
}

/* Window coordinates (y down) of the pixel that holds curve ci's point pi. */
static void window_xy(const cj_vdoc *d, const cj_vview *v, size_t ci, size_t pi, int *x, int *y,
                      double px[2]) {
    const cj_vcurve *c = cj_vdoc_curve(d, ci);
    cj_vview_to_px(v, c->pts[2 * pi], c->pts[2 * pi + 1], px);
    *x = (int)floor(px[0]);
    *y = v->height - 1 - (int)floor(px[1]);
}

/* Checks that only point (ci, pi) differs between a and b, and that it is at `want`. */
static void only_point_moved(const cj_vdoc *a, const cj_vdoc *b, size_t ci, size_t pi,
                             const double want[2]) {
    assert_int_equal(cj_vdoc_curve_count(a), cj_vdoc_curve_count(b));
    for (size_t c = 0; c < cj_vdoc_curve_count(a); ++c) {
        const cj_vcurve *x = cj_vdoc_curve(a, c), *y = cj_vdoc_curve(b, c);
        assert_int_equal(x->count, y->count);
        for (size_t i = 0; i < x->count; ++i) {
            if (c == ci && i == pi) {
                assert_memory_equal(y->pts + 2 * i, want, 2 * sizeof(double));
                assert_true(memcmp(x->pts + 2 * i, y->pts + 2 * i, 2 * sizeof(double)) != 0);
            } else {
                assert_memory_equal(x->pts + 2 * i, y->pts + 2 * i, 2 * sizeof(double));
            }
        }
    }
}

static void test_no_display(void **state) {
    (void)state;
    cj_cli_result r;
    char cmd[1024];
    snprintf(cmd, sizeof cmd, "env -u DISPLAY -u WAYLAND_DISPLAY %s view curves.json", CJ_CLI);
    assert_int_equal(run(cmd, &r), 1);
    assert_int_equal(r.out_len, 0);
    assert_non_null(strstr(r.err, "no display"));
    assert_non_null(strchr(r.err, '\n'));
    assert_true(strchr(r.err, '\n') == r.err + r.err_len - 1); /* exactly one line */
    printf("no display: exit 1, one line: %s", r.err);
    cj_cli_result_free(&r);
}

static void test_2d_drag_and_pixels(void **state) {
    (void)state;
    char path[512], buf[2048];
    snprintf(path, sizeof path, "%s/curves.json", dir);
    cj_vdoc *d = NULL;
    cj_vview v;
    cj_vdoc_display disp;
    assert_int_equal(cj_vdoc_load_json(path, &d, &v, &disp), CJ_OK);
    int x, y;
    double p0[2], want[2];
    window_xy(d, &v, 0, 2, &x, &y, p0);
    /* drag by (+37, +12) window pixels = (+37, −12) framebuffer pixels */
    snprintf(buf, sizeof buf, "drag left %d %d %d %d steps 6\nsave dragged.json\n", x, y, x + 37,
             y + 12);
    write_file("drag.txt", buf);
    cj_cli_result r;
    snprintf(buf, sizeof buf, "%s view curves.json --replay drag.txt --hide-overlay", CJ_CLI);
    assert_int_equal(run(buf, &r), 0);
    cj_cli_result_free(&r);
    /* the cursor points at pixel centres: press at (x + 0.5, ...), the point keeps its offset */
    cj_vview_from_px(&v, p0[0] + 37.0, p0[1] - 12.0, want);
    cj_vdoc *e = NULL;
    cj_vview ve;
    snprintf(path, sizeof path, "%s/dragged.json", dir);
    assert_int_equal(cj_vdoc_load_json(path, &e, &ve, &disp), CJ_OK);
    only_point_moved(d, e, 0, 2, want);
    printf("2D replay drag: curve 0 point 2 picked at window (%d, %d), dragged (+37, +12) in 6 "
           "moves: saved at exactly (%.17g, %.17g), every other point bit-identical\n",
           x, y, want[0], want[1]);
    cj_vdoc_destroy(e);

    /* A session of edits, then the back buffer against `casteljau plot` of the saved file. */
    snprintf(buf, sizeof buf,
             "drag left %d %d %d %d\n"
             "select 1 1\nkey w\nkey e\nkey h\n"
             "select 0 1\nkey i\nt 0.35\nkey c\nkey f\nkey s\nkey z ctrl\nkey y ctrl\n"
             "select 2 3\nkey delete\nkey z ctrl\nkey z shift ctrl\n"
             "drag left 5 5 25 15\nscroll 1\nscroll -0.5\n"
             "select 0 0\nkey k\nkey m\n"
             "screenshot bare.png\nsave session.json\nkey o\nkey f1\nscreenshot overlay.png\n",
             x, y, x - 20, y + 30);
    write_file("session.txt", buf);
    snprintf(buf, sizeof buf,
             "%s view curves.json --replay session.txt --hide-overlay && "
             "%s plot session.json -o plot.png",
             CJ_CLI, CJ_CLI);
    assert_int_equal(run(buf, &r), 0);
    cj_cli_result_free(&r);
    const long n = cj_test_png_differ(dir, "bare.png", "plot.png");
    assert_int_equal(n, 0);
    assert_true(cj_test_png_differ(dir, "overlay.png", "plot.png") >
                1000); /* the overlay is really drawn */
    printf("2D session (drag, weight, elevate, hull, insert, construction, frame, split, undo, "
           "redo, delete, pan, zoom): back buffer == `casteljau plot` of the saved file, 0 of "
           "%d pixels differ; with the overlay and help shown they do differ\n",
           v.width * v.height);
    cj_vdoc_destroy(d);
}

/* The scene set to W x H at 1 spp, its depth plane (what the viewer picks against: the same
 * deterministic render) into *depth, and its editable points. */
static cj_vscene *pickable(cj_scene *s, int W, int H, cj_render_image **depth) {
    cj_scene_settings set = *cj_scene_get_settings(s);
    set.width = W, set.height = H, set.spp = 1;
    assert_int_equal(cj_scene_set_settings(s, &set), CJ_OK);
    cj_render_options ro = cj_render_options_defaults();
    assert_int_equal(cj_render_raster(s, &ro, CJ_IMAGE_DEPTH, NULL, depth, NULL), CJ_OK);
    cj_vscene *vs = NULL;
    assert_int_equal(cj_vscene_create(s, &vs), CJ_OK);
    return vs;
}

static void test_3d_drag_and_pixels(void **state) {
    (void)state;
    const int W = 320, H = 240;
    cj_scene *s = NULL;
    assert_int_equal(cj_render_demo_scene(CJ_TEAPOT_PATH, NULL, &s), CJ_OK);
    cj_render_image *img = NULL;
    cj_vscene *vs = pickable(s, W, H, &img);
    /* a visible control point on screen: the pick at the centre of its own pixel */
    size_t k = 0, picked = 0;
    double q[3];
    int found = 0;
    for (k = 0; k < cj_vscene_point_count(vs) && !found; k += 7)
        if (cj_vscene_project(vs, k, W, H, q) && q[0] > 40 && q[0] < W - 40 && q[1] > 40 &&
            q[1] < H - 40)
            found = cj_vscene_pick(vs, W, H, img->depth, floor(q[0]) + 0.5, floor(q[1]) + 0.5, 8,
                                   &picked);
    cj_render_image_destroy(img);
    assert_true(found);
    cj_vec3 before;
    cj_vscene_point(vs, picked, &before);
    cj_vscene_project(vs, picked, W, H, q);
    const int x = (int)floor(q[0]), y = H - 1 - (int)floor(q[1]);
    char buf[2048];
    snprintf(buf, sizeof buf,
             "drag left %d %d %d %d steps 2\nsave moved.json\n"
             "key n\nkey g\nkey -\ndrag left 10 10 40 25 steps 2\n"
             "drag right 100 100 90 110 steps 1\nscroll 1\n"
             "screenshot bare3d.png\nsave scene3d.json\nkey o\nscreenshot overlay3d.png\n",
             x, y, x + 15, y - 9);
    write_file("s3d.txt", buf);
    cj_cli_result r;
    snprintf(buf, sizeof buf,
             "%s view --teapot --width %d --height %d --spp 1 --threads 2 --replay s3d.txt "
             "--hide-overlay && %s render scene3d.json -o render3d.png --threads 2",
             CJ_CLI, W, H, CJ_CLI);
    assert_int_equal(run(buf, &r), 0);
    cj_cli_result_free(&r);
    /* The dragged point: moved by the cursor's displacement on screen, all others untouched. */
    char path[512];
    snprintf(path, sizeof path, "%s/moved.json", dir);
    cj_scene_json_options jo = {CJ_TEAPOT_PATH};
    cj_scene *m = NULL;
    assert_int_equal(cj_scene_load_json_with_options(path, &jo, NULL, &m), CJ_OK);
    cj_vscene *vm = NULL;
    assert_int_equal(cj_vscene_create(m, &vm), CJ_OK);
    assert_int_equal(cj_vscene_point_count(vm), cj_vscene_point_count(vs));
    /* the picked point and the copies of it that neighbouring patches keep (linked by default)
     * moved, to the same place; every other point is bit-identical */
    size_t moved = 0, shared = 0;
    cj_vec3 after;
    cj_vscene_point(vm, picked, &after);
    for (size_t i = 0; i < cj_vscene_point_count(vs); ++i) {
        cj_vec3 a, b;
        cj_vscene_point(vs, i, &a);
        cj_vscene_point(vm, i, &b);
        const int coincident = !memcmp(&a, &before, sizeof a);
        shared += coincident;
        if (memcmp(&a, &b, sizeof a)) {
            ++moved;
            assert_true(coincident);
            assert_memory_equal(&b, &after, sizeof b);
        } else {
            assert_false(coincident);
        }
    }
    assert_int_equal(moved, shared);
    assert_true(moved >= 1);
    double q1[3];
    assert_true(cj_vscene_project(vm, picked, W, H, q1));
    const double err = fmax(fabs(q1[0] - (q[0] + 15)), fabs(q1[1] - (q[1] + 9)));
    assert_true(err < 1e-6);
    const long n = cj_test_png_differ(dir, "bare3d.png", "render3d.png");
    assert_int_equal(n, 0);
    assert_true(cj_test_png_differ(dir, "overlay3d.png", "render3d.png") > 100);
    printf("3D replay: control point %zu of the teapot dragged (+15, -9) px on the camera plane "
           "(with the %zu other patch corners at the same place): its projection moved by that "
           "within %.1e px, the other %zu points bit-identical; "
           "after nets/shading/tolerance/orbit/pan/zoom the back buffer == `casteljau render` "
           "of the saved scene, 0 of %d pixels differ\n",
           picked, moved - 1, err, cj_vscene_point_count(vs) - moved, W * H);
    cj_vscene_destroy(vm);
    cj_vscene_destroy(vs);
}

/* A B-spline surface edited as such: a net point of the bicubic sheet of scenes/bsplines.json
 * picked and dragged by a replay; the saved file keeps the "bspline_surface" with that net point
 * (and its coincident ones) moved and every other bit-identical, and the back buffer equals
 * `casteljau render` of the saved scene. */
static void test_3d_bspline_drag(void **state) {
    (void)state;
    const int W = 320, H = 240;
    cj_scene *s = NULL;
    assert_int_equal(cj_scene_load_json(CJ_BSPLINES_PATH, NULL, &s), CJ_OK);
    cj_render_image *img = NULL;
    cj_vscene *vs = pickable(s, W, H, &img);
    /* a visible net point of the polynomial surface (the bicubic sheet) */
    size_t picked = 0;
    double q[3];
    int found = 0;
    for (size_t k = 0; k < cj_vscene_point_count(vs) && !found; ++k) {
        const int gi = cj_scene_node(s, cj_vscene_point_node(vs, k))->geometry;
        const cj_bspline_surface *b = cj_scene_geometry_bspline(s, gi);
        if (!b || b->weights) continue;
        if (cj_vscene_project(vs, k, W, H, q) && q[0] > 30 && q[0] < W - 30 && q[1] > 30 &&
            q[1] < H - 30)
            found = cj_vscene_pick(vs, W, H, img->depth, floor(q[0]) + 0.5, floor(q[1]) + 0.5, 8,
                                   &picked) &&
                    cj_scene_node(s, cj_vscene_point_node(vs, picked))->geometry == gi;
    }
    cj_render_image_destroy(img);
    assert_true(found);
    cj_vec3 before;
    cj_vscene_point(vs, picked, &before);
    cj_vscene_project(vs, picked, W, H, q);
    const int x = (int)floor(q[0]), y = H - 1 - (int)floor(q[1]);
    char buf[2048];
    snprintf(buf, sizeof buf,
             "drag left %d %d %d %d steps 3\nscreenshot bsurf.png\nsave bsurf.json\n", x, y, x + 12,
             y - 10);
    write_file("bsurf.txt", buf);
    cj_cli_result r;
    snprintf(buf, sizeof buf,
             "%s view %s --width %d --height %d --spp 1 --threads 2 --replay bsurf.txt "
             "--hide-overlay && %s render bsurf.json -o bsurf_render.png --threads 2",
             CJ_CLI, CJ_BSPLINES_PATH, W, H, CJ_CLI);
    assert_int_equal(run(buf, &r), 0);
    cj_cli_result_free(&r);
    char path[512];
    snprintf(path, sizeof path, "%s/bsurf.json", dir);
    cj_scene *m = NULL;
    assert_int_equal(cj_scene_load_json(path, NULL, &m), CJ_OK);
    cj_vscene *vm = NULL;
    assert_int_equal(cj_vscene_create(m, &vm), CJ_OK);
    assert_int_equal(cj_vscene_point_count(vm), cj_vscene_point_count(vs));
    const int gi = cj_scene_node(m, cj_vscene_point_node(vm, picked))->geometry;
    assert_non_null(cj_scene_geometry_bspline(m, gi));
    size_t moved = 0, shared = 0;
    for (size_t i = 0; i < cj_vscene_point_count(vs); ++i) {
        cj_vec3 a, b;
        cj_vscene_point(vs, i, &a);
        cj_vscene_point(vm, i, &b);
        const int coincident = !memcmp(&a, &before, sizeof a) &&
                               cj_vscene_point_node(vs, i) == cj_vscene_point_node(vs, picked);
        shared += coincident;
        if (memcmp(&a, &b, sizeof a)) {
            ++moved;
            assert_true(coincident);
        }
    }
    assert_int_equal(moved, shared);
    assert_true(moved >= 1);
    double q1[3];
    assert_true(cj_vscene_project(vm, picked, W, H, q1));
    const double err = fmax(fabs(q1[0] - (q[0] + 12)), fabs(q1[1] - (q[1] + 10)));
    assert_true(err < 1e-6);
    const long n = cj_test_png_differ(dir, "bsurf.png", "bsurf_render.png");
    assert_int_equal(n, 0);
    printf("3D replay on a B-spline surface: net point %zu of the bicubic sheet dragged (+12, "
           "-10) px: saved as bspline_surface with that point moved (projection within %.1e px), "
           "the other %zu net points bit-identical; the back buffer == `casteljau render` of the "
           "saved scene, 0 of %d pixels differ\n",
           picked, err, cj_vscene_point_count(vs) - moved, W * H);
    cj_vscene_destroy(vm);
    cj_vscene_destroy(vs);
}

/* Playback: each drawn frame advances the animation by one frame, so after Space and three more
 * pictures the viewer shows frame 4, which `casteljau animate` renders to the same pixels. */
static void test_animation(void **state) {
    (void)state;
    write_file("anim.txt", "key space\nframe\nframe\nscreenshot anim_view.png\n");
    char buf[2048];
    snprintf(buf, sizeof buf,
             "%s view %s --width 160 --height 120 --spp 1 --hide-overlay --replay anim.txt && "
             "%s animate %s -o anim_%%d.png --frames 4:4 --width 160 --height 120 --spp 1 "
             "--quiet",
             CJ_CLI, CJ_ANIM_PATH, CJ_CLI, CJ_ANIM_PATH);
    cj_cli_result r;
    assert_int_equal(run(buf, &r), 0);
    cj_cli_result_free(&r);
    assert_int_equal(cj_test_png_differ(dir, "anim_view.png", "anim_4.png"), 0);
    printf("animation playback (scenes/anim_flyby.json): frame 4 in the viewer == `casteljau "
           "animate` frame 4, 0 of %d pixels differ\n",
           160 * 120);
}

static void test_xdotool(void **state) {
    (void)state;
    char path[512], buf[2048];
    snprintf(path, sizeof path, "%s/live.json", dir);
    write_file("live.json", curves);
    cj_vdoc *d = NULL;
    cj_vview v;
    cj_vdoc_display disp;
    assert_int_equal(cj_vdoc_load_json(path, &d, &v, &disp), CJ_OK);
    int x, y;
    double p0[2], want[2];
    window_xy(d, &v, 0, 1, &x, &y, p0);
    char title[64];
    snprintf(title, sizeof title, "cj-xdotool-%d", (int)getpid());
    const pid_t child = fork();
    assert_true(child >= 0);
    if (child == 0) {
        if (chdir(dir)) _exit(3);
        execl(CJ_CLI, CJ_CLI, "view", "live.json", "--title", title, "--hide-overlay",
              (char *)NULL);
        _exit(4);
    }
    cj_cli_result r;
    snprintf(buf, sizeof buf,
             "W=$(timeout 20 xdotool search --sync --onlyvisible --name '^%s$' | head -1) && "
             "xdotool windowfocus --sync $W && sleep 0.3 && "
             "xdotool mousemove --window $W %d %d && sleep 0.2 && xdotool mousedown 1 && "
             "sleep 0.2 && xdotool mousemove --window $W %d %d && sleep 0.2 && "
             "xdotool mousemove --window $W %d %d && sleep 0.2 && xdotool mouseup 1 && "
             "sleep 0.2 && xdotool key ctrl+s && sleep 0.3 && xdotool key Escape",
             title, x, y, x + 10, y + 3, x - 25, y + 40);
    int rc = cj_cli_shell(buf, &r);
    int status = -1;
    for (int i = 0; i < 200; ++i) { /* up to 20 s for the window to close */
        if (waitpid(child, &status, WNOHANG) == child) break;
        usleep(100000);
        if (i == 199) {
            kill(child, SIGKILL);
            waitpid(child, &status, 0);
        }
    }
    assert_int_equal(rc, 0);
    if (r.status != 0) printf("xdotool: %s %s\n", r.out, r.err);
    assert_int_equal(r.status, 0);
    cj_cli_result_free(&r);
    assert_true(WIFEXITED(status) && WEXITSTATUS(status) == 0);
    cj_vview_from_px(&v, p0[0] - 25.0, p0[1] - 40.0, want);
    cj_vdoc *e = NULL;
    cj_vview ve;
    assert_int_equal(cj_vdoc_load_json(path, &e, &ve, &disp), CJ_OK);
    only_point_moved(d, e, 0, 1, want);
    printf("xdotool: real X events (mouse drag by (-25, +40) through (+10, +3), ctrl+S, Escape) "
           "sent to the running window: the file it saved has curve 0 point 1 at exactly "
           "(%.17g, %.17g) and every other point bit-identical; the viewer exited 0\n",
           want[0], want[1]);
    cj_vdoc_destroy(d);
    cj_vdoc_destroy(e);
}

int main(void) {
    if (!mkdtemp(dir)) return 1;
    write_file("curves.json", curves);
    /* Under the sanitizers the viewers this test starts are not leak-checked: glfwTerminate
     * unloads Mesa's driver, whose allocations then show as "<unknown module>" and cannot be
     * suppressed by name. The editor code is leak-checked in process by test_viewer_model and
     * the window code was run under valgrind (see the notes). */
    setenv("LSAN_OPTIONS", "detect_leaks=0", 1);
    const pid_t xvfb = cj_test_xvfb_start(1024, 768);
    if (xvfb < 0) {
        fprintf(stderr, "test_viewer_window: cannot start Xvfb\n");
        return 1;
    }
    printf("test_viewer_window: private X server on DISPLAY=%s, files in %s\n", getenv("DISPLAY"),
           dir);
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_no_display),         cmocka_unit_test(test_2d_drag_and_pixels),
        cmocka_unit_test(test_3d_drag_and_pixels), cmocka_unit_test(test_3d_bspline_drag),
        cmocka_unit_test(test_animation),          cmocka_unit_test(test_xdotool),
    };
    const int rc = cmocka_run_group_tests(tests, NULL, NULL);
    cj_test_xvfb_stop(xvfb);
    char cmd[600];
    snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
    if (!rc && system(cmd) != 0) return 1;
    return rc;
}

/* The designer's 2D editor in the real window, driven by real X events (xdotool) under a
 * private Xvfb: a B-spline point dragged, a NURBS weight changed and a knot inserted at the
 * cursor, saved with ctrl+S; the window's last picture (--screenshot at exit) equals
 * `casteljau plot` of the saved file pixel for pixel. Snapping (P): a point dragged onto another
 * curve is saved on that curve (its distance to the curve certified by nearest.h, and checked
 * with the MPFR B-spline oracle at the curve parameter). The help lists the new keys. */
#define _DEFAULT_SOURCE
#include "casteljau/image_io.h"
#include "casteljau/viewer_model.h"
#include "cli_run.h"
#include "oracle_bspline.h"
#include "support/check.h"
#include "support/png_diff.h"
#include "support/xvfb.h"

#include <float.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

/* viewer_input.c (private to the viewer, in the library): the help panel's lines. */
const char *const *cj_viewer_help(int mode3d);

static char dir[] = "/tmp/cj_viewer_design_XXXXXX";

static const char doc_text[] =
    "{\"width\": 400, \"height\": 300, \"axes\": false, \"margin\": 0, \"view\": [0, 0, 4, 3],\n"
    " \"items\": [\n"
    "  {\"type\": \"bspline\", \"degree\": 3,\n"
    "   \"points\": [[0.3,0.5],[0.8,2.5],[1.6,0.4],[2.4,2.6],[3.2,0.6],[3.7,2.2],[3.9,1.0]]},\n"
    "  {\"type\": \"bspline\", \"degree\": 2, \"weights\": [1, 3, 1, 0.5],\n"
    "   \"points\": [[0.5,2.8],[2.0,1.0],[3.5,2.8],[3.8,1.5]]},\n"
    "  {\"type\": \"bezier\", \"points\": [[0.2, 1.2], [1.2, 1.3]]}]}\n";

static void write_file(const char *name, const char *text) {
    char p[600];
    snprintf(p, sizeof p, "%s/%s", dir, name);
    FILE *f = fopen(p, "w");
    if (!f) exit(1);
    fputs(text, f);
    fclose(f);
}

static cj_vdoc *load(const char *name, cj_vview *v) {
    char p[600];
    snprintf(p, sizeof p, "%s/%s", dir, name);
    cj_vdoc *d = NULL;
    cj_vdoc_display disp;
    if (cj_vdoc_load_json(p, &d, v, &disp)) {
        fprintf(stderr, "%s\n", cj_last_error());
        exit(1);
    }
    return d;
}

/* Window coordinates (y down) of the pixel holding a data point. */
static void window_xy(const cj_vview *v, const double *p, int *x, int *y) {
    double q[2];
    cj_vview_to_px(v, p[0], p[1], q);
    *x = (int)floor(q[0]);
    *y = v->height - 1 - (int)floor(q[1]);
}

/* Runs the viewer on `doc` with `extra` options in a window titled uniquely, sends it the
 * xdotool commands `actions` (with $W the window), and waits for it to exit. */
static int session(const char *doc, const char *shot, const char *actions) {
    char title[64], cmd[4096];
    snprintf(title, sizeof title, "cj-design-%d", (int)getpid());
    const pid_t child = fork();
    if (child < 0) return -1;
    if (child == 0) {
        if (chdir(dir)) _exit(3);
        execl(CJ_CLI, CJ_CLI, "view", doc, "--title", title, "--hide-overlay", "--screenshot", shot,
              (char *)NULL);
        _exit(4);
    }
    snprintf(cmd, sizeof cmd,
             "W=$(timeout 20 xdotool search --sync --onlyvisible --name '^%s$' | head -1) && "
             "xdotool windowfocus --sync $W && sleep 0.3 && %s && sleep 0.3 && "
             "xdotool key ctrl+s && sleep 0.3 && xdotool key Escape",
             title, actions);
    cj_cli_result r;
    const int rc = cj_cli_shell(cmd, &r);
    int status = -1;
    for (int i = 0; i < 300; ++i) { /* up to 30 s for the window to close */
        if (waitpid(child, &status, WNOHANG) == child) break;
        usleep(100000);
        if (i == 299) {
            kill(child, SIGKILL);
            waitpid(child, &status, 0);
        }
    }
    if (rc || r.status) fprintf(stderr, "xdotool: %s %s\n", r.out, r.err);
    const int ok = !rc && !r.status && WIFEXITED(status) && WEXITSTATUS(status) == 0;
    cj_cli_result_free(&r);
    return ok ? 0 : -1;
}

/* A drag with the left button from (x0, y0) to (x1, y1) in a few moves, as xdotool commands. */
static void drag_cmd(char *buf, size_t size, int x0, int y0, int x1, int y1) {
    snprintf(buf, size,
             "xdotool mousemove --window $W %d %d && sleep 0.2 && xdotool mousedown 1 && "
             "sleep 0.2 && xdotool mousemove --window $W %d %d && sleep 0.2 && "
             "xdotool mousemove --window $W %d %d && sleep 0.2 && xdotool mouseup 1 && sleep 0.2",
             x0, y0, (x0 + x1) / 2, (y0 + y1) / 2 + 3, x1, y1);
}

static void test_edit_and_pixels(void) {
    write_file("edit.json", doc_text);
    cj_vview v;
    cj_vdoc *d = load("edit.json", &v);
    const cj_vcurve *bs = cj_vdoc_curve(d, 0), *nu = cj_vdoc_curve(d, 1);
    int x0, y0, x1, y1, xc, yc;
    window_xy(&v, bs->pts + 2 * 3, &x0, &y0);
    window_xy(&v, nu->pts + 2 * 1, &x1, &y1);
    /* a point on the B-spline's first span for the knot insertion */
    double on[2];
    const cj_bspline b = cj_vcurve_bspline(bs);
    cj_bspline_eval(&b, 0.1, on);
    window_xy(&v, on, &xc, &yc);
    char a[1024], c[1024], acts[3072];
    drag_cmd(a, sizeof a, x0, y0, x0 + 30, y0 + 25);
    /* press and release on the NURBS point selects it (no motion: no move) */
    snprintf(c, sizeof c,
             "xdotool mousemove --window $W %d %d && sleep 0.2 && xdotool click 1 && sleep 0.2 "
             "&& xdotool key w && sleep 0.2 && xdotool key w && sleep 0.2 && xdotool key shift+w "
             "&& sleep 0.2 && xdotool key w && sleep 0.2",
             x1, y1);
    snprintf(acts, sizeof acts,
             "%s && %s && xdotool key Tab && sleep 0.2 && xdotool key Tab && sleep 0.2 && "
             "xdotool mousemove --window $W %d %d && sleep 0.2 && xdotool key i && sleep 0.2",
             a, c, xc, yc);
    CHECK(session("edit.json", "edit_window.png", acts) == 0, "the session ran");
    cj_cli_result r;
    char cmd[1024];
    snprintf(cmd, sizeof cmd, "cd %s && %s plot edit.json -o edit_plot.png", dir, CJ_CLI);
    CHECK(cj_cli_shell(cmd, &r) == 0 && r.status == 0, "casteljau plot: %s", r.err);
    cj_cli_result_free(&r);
    cj_vview ve;
    cj_vdoc *e = load("edit.json", &ve);
    const cj_vcurve *bs2 = cj_vdoc_curve(e, 0), *nu2 = cj_vdoc_curve(e, 1);
    /* the drag: (+30, +25) window pixels = (+0.3, -0.25) data units at 100 px per unit */
    double want[2], q[2];
    cj_vview_to_px(&v, bs->pts[6], bs->pts[7], q);
    cj_vview_from_px(&v, q[0] + 30, q[1] - 25, want);
    CHECK(bs2->count == bs->count + 1, "a knot was inserted: %zu points", bs2->count);
    CHECK(bs2->knot_vector[4] > 0 && bs2->knot_vector[4] < 0.25, "the new knot %g near 0.1",
          bs2->knot_vector[4]);
    /* after the insertion at u < 0.25 the dragged point 3 is point 4 */
    CHECK(!memcmp(bs2->pts + 8, want, sizeof want) || !memcmp(bs2->pts + 6, want, sizeof want),
          "dragged point saved at (%.17g, %.17g)", want[0], want[1]);
    const double w = 3.0 * 1.25 * 1.25 / 1.25 * 1.25;
    CHECK(nu2->weights[1] == w, "weight %.17g, expected %.17g", nu2->weights[1], w);
    const long n = cj_test_png_differ(dir, "edit_window.png", "edit_plot.png");
    CHECK(n == 0, "%ld pixels differ between the window and casteljau plot", n);
    printf("xdotool session: a cubic B-spline point dragged by (+30, +25) px, a NURBS weight "
           "x1.25 x1.25 /1.25 x1.25 (now %.17g), a knot inserted at the cursor (%.6g), ctrl+S, "
           "Escape: the saved file has them, and the window's last picture equals `casteljau "
           "plot` of the saved file: %ld of %d pixels differ\n",
           nu2->weights[1], bs2->knot_vector[4], n, v.width * v.height);
    cj_vdoc_destroy(d);
    cj_vdoc_destroy(e);
}

static void test_snap_drag(void) {
    write_file("snap.json", doc_text);
    cj_vview v;
    cj_vdoc *d = load("snap.json", &v);
    /* drag the line's end point (curve 2, point 1) to 6 px beside the B-spline at u = 0.5 */
    const cj_vcurve *line = cj_vdoc_curve(d, 2);
    double target[2];
    const cj_bspline b = cj_vcurve_bspline(cj_vdoc_curve(d, 0));
    double dv[4];
    cj_bspline_eval_derivs(&b, 0.5, 1, dv);
    const double len = hypot(dv[2], dv[3]);
    target[0] = dv[0] - 0.06 * dv[3] / len; /* 6 px off the curve along its normal */
    target[1] = dv[1] + 0.06 * dv[2] / len;
    int x0, y0, x1, y1;
    window_xy(&v, line->pts + 2, &x0, &y0);
    window_xy(&v, target, &x1, &y1);
    char a[1024], acts[2048];
    drag_cmd(a, sizeof a, x0, y0, x1, y1);
    snprintf(acts, sizeof acts, "xdotool key p && sleep 0.2 && %s", a);
    CHECK(session("snap.json", "snap_window.png", acts) == 0, "the session ran");
    cj_vview ve;
    cj_vdoc *e = load("snap.json", &ve);
    const double *p = cj_vdoc_curve(e, 2)->pts + 2;
    cj_vsnap s;
    CHECK(cj_vcurve_nearest(cj_vdoc_curve(e, 0), p, 1e-12, &s) == CJ_OK, "%s", cj_last_error());
    const double ulp = DBL_EPSILON * fmax(fabs(p[0]), fabs(p[1]));
    CHECK(s.distance <= 64 * ulp, "the saved point is %g from the B-spline (certified)",
          s.distance);
    /* the oracle: |p - c(u)| in MPFR at the parameter found */
    const cj_vcurve *c = cj_vdoc_curve(e, 0);
    const cj_obsp o = {c->degree, 2, (int)c->count, c->pts, NULL, c->knot_vector};
    double mag = 0;
    const double ex = cj_obsp_abs_error(&o, 0, s.u, p[0], &mag);
    const double ey = cj_obsp_abs_error(&o, 1, s.u, p[1], &mag);
    CHECK(hypot(ex, ey) <= 4 * ulp, "oracle: %g from c(%.17g)", hypot(ex, ey), s.u);
    /* nearest.h's distance bounds |c(u) - p| at its u: the oracle must agree */
    CHECK(hypot(ex, ey) <= s.distance * (1 + 4 * DBL_EPSILON), "oracle %g above the certified %g",
          hypot(ex, ey), s.distance);
    /* where a plain drag leaves it: its pixel position plus the cursor's displacement */
    double q[2], plain[2];
    cj_vview_to_px(&v, line->pts[2], line->pts[3], q);
    cj_vview_from_px(&v, q[0] + (x1 - x0), q[1] - (y1 - y0), plain);
    CHECK(hypot(p[0] - plain[0], p[1] - plain[1]) > 0.02,
          "the point snapped (moved %g from the "
          "cursor's place)",
          hypot(p[0] - plain[0], p[1] - plain[1]));
    printf("snap (P) with a real drag: the line's end point dropped 6 px beside the B-spline is "
           "saved at (%.17g, %.17g), on the B-spline at u = %.9g: certified distance %.2g, "
           "oracle |p - c(u)| = %.2g (%.1f ulps); %.3g units from where a plain drag leaves it\n",
           p[0], p[1], s.u, s.distance, hypot(ex, ey), hypot(ex, ey) / ulp,
           hypot(p[0] - plain[0], p[1] - plain[1]));
    cj_vdoc_destroy(d);
    cj_vdoc_destroy(e);
}

static void test_help(void) {
    int snap = 0, isect = 0, knot = 0;
    for (const char *const *l = cj_viewer_help(0); *l; ++l) {
        snap |= strstr(*l, "P  snap") != NULL;
        isect |= strstr(*l, "T  intersections") != NULL;
        knot |= strstr(*l, "insert a knot") != NULL;
    }
    CHECK(snap && isect && knot, "help lists P %d, T %d, knot insertion %d", snap, isect, knot);
    printf("help: the 2D help lists P (snap), T (intersections) and I (insert a knot)\n");
}

int main(void) {
    if (!mkdtemp(dir)) return 1;
    setenv("LSAN_OPTIONS", "detect_leaks=0", 1); /* Mesa's driver: see test_viewer_window */
    const pid_t xvfb = cj_test_xvfb_start(1024, 768);
    if (xvfb < 0) {
        fprintf(stderr, "test_viewer_design: cannot start Xvfb\n");
        return 1;
    }
    printf("test_viewer_design: private X server on DISPLAY=%s, files in %s\n", getenv("DISPLAY"),
           dir);
    test_help();
    test_edit_and_pixels();
    test_snap_drag();
    cj_test_xvfb_stop(xvfb);
    char cmd[700];
    snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
    if (!cj_check_failures && system(cmd) != 0) return 1;
    return cj_check_exit();
}

/* Contract of `casteljau interp` and `casteljau contour`: output syntax and values (against the
 * library in-process), `interp | eval` composition, and bad input (exit 2, one stderr line,
 * nothing on stdout). */
#define _POSIX_C_SOURCE 200809L
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "cli_run.h"

#include "casteljau/bezier.h"
#include "casteljau/catmull_rom.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifndef CJ_CLI
#error "CJ_CLI (path of the casteljau executable) must be defined by the build"
#endif

#define OUTMAX (1 << 22)
static char out[OUTMAX], err[4096];

/* Runs `casteljau <args>`; stdout into out, stderr into err; returns the exit status. */
static int run(const char *args) {
    char cmd[8192];
    snprintf(cmd, sizeof cmd, "'%s' %s", CJ_CLI, args);
    cj_cli_result r;
    assert_int_equal(cj_cli_shell(cmd, &r), 0);
    assert_true(r.out_len < OUTMAX && r.err_len < sizeof err);
    memcpy(out, r.out, r.out_len + 1);
    memcpy(err, r.err, r.err_len + 1);
    const int status = r.status;
    cj_cli_result_free(&r);
    return status;
}

/* Parses "x,y;x,y;..." (one line) into pts; returns the number of points. */
static int parse_line(const char *line, double *pts, int dim) {
    int n = 0;
    const char *s = line;
    while (*s && *s != '\n') {
        for (int k = 0; k < dim; ++k) {
            char *end;
            pts[n * dim + k] = strtod(s, &end);
            assert_true(end != s);
            s = end;
            if (k + 1 < dim) {
                assert_true(*s == ',');
                ++s;
            }
        }
        ++n;
        if (*s == ';') ++s;
    }
    return n;
}

static int count_lines(const char *s) {
    int n = 0;
    for (; *s; ++s) n += *s == '\n';
    return n;
}

static void test_interp_output_and_composition(void **state) {
    (void)state;
    const double pts[] = {0, 0, 1, 2, 3, 1, 4, 4, 6, 3.5};
    const char *ptext = "0,0;1,2;3,1;4,4;6,3.5";
    double segs[4 * 8];
    cj_spline_options o = cj_spline_defaults();
    assert_int_equal(cj_catmull_rom(pts, 5, 2, &o, segs, 4, NULL, NULL), CJ_OK);
    static char args[8192];
    snprintf(args, sizeof args, "interp --points '%s'", ptext);
    assert_int_equal(run(args), 0);
    assert_int_equal(count_lines(out), 4);
    static char lines[4][1024];
    const char *s = out;
    for (int j = 0; j < 4; ++j) {
        const char *nl = strchr(s, '\n');
        memcpy(lines[j], s, (size_t)(nl - s));
        lines[j][nl - s] = '\0';
        double got[8];
        assert_int_equal(parse_line(lines[j], got, 2), 4);
        for (int i = 0; i < 8; ++i) assert_true(got[i] == segs[j * 8 + i]); /* %.17g exact */
        s = nl + 1;
    }
    /* composition: each printed segment is a valid --points for eval */
    for (int j = 0; j < 4; j += 3) { /* first and last segment (each run costs a start-up) */
        snprintf(args, sizeof args, "eval --points '%s' 0 0.5 1", lines[j]);
        assert_int_equal(run(args), 0);
        double v[6];
        assert_int_equal(
            sscanf(out, "%lf %lf\n%lf %lf\n%lf %lf", &v[0], &v[1], &v[2], &v[3], &v[4], &v[5]), 6);
        assert_true(v[0] == pts[2 * j] && v[1] == pts[2 * j + 1]);
        assert_true(v[4] == pts[2 * j + 2] && v[5] == pts[2 * j + 3]);
        double mid[2];
        cj_bezier b = cj_bezier_view(3, 2, segs + 8 * j);
        cj_bezier_eval_decasteljau(&b, 0.5, mid);
        assert_true(v[2] == mid[0] && v[3] == mid[1]);
    }
    /* tension and kinds */
    assert_int_equal(run("interp --tension 0 --points '0,0;1,1;2,0'"), 0);
    double g[8];
    parse_line(out, g, 2); /* κ = 0: inner control points on the end points */
    assert_true(g[2] == 0 && g[3] == 0 && g[4] == 1 && g[5] == 1);
    assert_int_equal(run("interp --kind centripetal --closed --points '0,0;1,0;1,1;0,1'"), 0);
    assert_int_equal(count_lines(out), 4);
    assert_int_equal(run("interp --kind kochanek-bartels --bias 0.3 --points '0,0;1,0;1,1'"), 0);
    assert_int_equal(count_lines(out), 2);
    printf("interp: 4 catmull-rom segments equal the library's bit for bit; first and last "
           "compose with 'casteljau eval --points' (ends exact, midpoint identical)\n");
}

static void test_interp_polynomial(void **state) {
    (void)state;
    /* x = t^3 sampled at t = 0,1,2,4: the Bézier form over [0,4] of 64 u^3 is 0,0,0,64 */
    assert_int_equal(run("interp --kind polynomial --params '0;1;2;4' --points '0;1;8;64'"), 0);
    double p[4];
    assert_int_equal(count_lines(out), 1);
    assert_int_equal(parse_line(out, p, 1), 4);
    for (int i = 0; i < 3; ++i) assert_true(fabs(p[i]) < 1e-13);
    assert_true(fabs(p[3] - 64) < 1e-12);
    /* default parameters: equispaced on [0,1]; eval at k/3 returns the points */
    assert_int_equal(run("interp --kind polynomial --points '0,0;1,2;3,1;4,4'"), 0);
    static char line[1024], args[2048];
    const size_t ll = strcspn(out, "\n");
    assert_true(ll < sizeof line);
    memcpy(line, out, ll);
    line[ll] = '\0';
    snprintf(args, sizeof args, "eval --points '%s' 0 0.33333333333333331 0.66666666666666663 1",
             line);
    assert_int_equal(run(args), 0);
    double v[8];
    assert_int_equal(sscanf(out, "%lf %lf %lf %lf %lf %lf %lf %lf", &v[0], &v[1], &v[2], &v[3],
                            &v[4], &v[5], &v[6], &v[7]),
                     8);
    const double want[8] = {0, 0, 1, 2, 3, 1, 4, 4};
    for (int i = 0; i < 8; ++i) assert_true(fabs(v[i] - want[i]) < 1e-13);
    printf("interp --kind polynomial: known cubic recovered; output composes with eval\n");
}

static void expect_usage_error(const char *args) {
    const int rc = run(args);
    if (rc != 2 || out[0] != '\0' || count_lines(err) != 1)
        fail_msg("'%s': exit %d, stdout '%s', stderr '%s'", args, rc, out, err);
    printf("  exit 2: %s", err);
}

static void test_bad_input(void **state) {
    (void)state;
    printf("bad input (nothing on stdout, one line on stderr):\n");
    expect_usage_error("interp");
    expect_usage_error("interp --points '0,0;1,x'");
    expect_usage_error("interp --kind bspline --points '0,0;1,1'");
    expect_usage_error("interp --params '0;1' --points '0,0;1,1'");
    expect_usage_error("interp --kind centripetal --points '0,0;1,1;1,1;2,0'");
    expect_usage_error("interp --kind polynomial --params '0;1;1' --points '0;1;2'");
    expect_usage_error("interp --kind polynomial --tension 0.3 --points '0;1;2'");
    expect_usage_error("contour --circle 0,0,1");
    expect_usage_error("contour --circle 0,0,1 --line 1,1,0 --box -1,-1,1,1");
    expect_usage_error("contour --poly '1,2' --box -1,-1,1,1");
}

static void test_contour(void **state) {
    (void)state;
    assert_int_equal(run("contour --circle 1,2,1.5 --box -1,0,3,4 --tol 1e-7 --grid 8,10"), 0);
    assert_int_equal(count_lines(out), 1);
    static double xy[2 * 200000];
    const int n = parse_line(out, xy, 2);
    assert_true(n > 10);
    assert_true(xy[0] == xy[2 * n - 2] && xy[1] == xy[2 * n - 1]); /* closed loop */
    double worst = 0;
    for (int i = 0; i < n; ++i)
        worst = fmax(worst, fabs(hypot(xy[2 * i] - 1, xy[2 * i + 1] - 2) - 1.5));
    assert_true(worst <= 1e-7);
    /* a quartic with two loops (product of two circles) */
    assert_int_equal(run("contour --poly '0.5625,0,0,-2.5,0,1.5,0,0,0,0,1,0,2,0,1' --box "
                         "-2,-2,2,2 --stats"),
                     0);
    assert_int_equal(count_lines(out), 2);
    assert_non_null(strstr(err, "closed 2"));
    printf("contour: circle -> one closed polyline within tol (max distance %.2e, %d points); "
           "quartic -> 2 loops\n",
           worst, n);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_interp_output_and_composition),
        cmocka_unit_test(test_interp_polynomial),
        cmocka_unit_test(test_bad_input),
        cmocka_unit_test(test_contour),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

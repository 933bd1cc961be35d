/* Contract test of `casteljau tessellate`, run as a child process: the teapot and a single
 * patch to OBJ and PLY, the printed triangle count matching the file, the printed bound within
 * --tol and the measured deviation within the bound, --uniform; a rational patch (--weights)
 * on the exact cylinder; bad input gives one line on stderr, nothing on stdout, exit status 2
 * and no output file. */
#define _POSIX_C_SOURCE 200809L
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "cli_run.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#ifndef CJ_CLI
#define CJ_CLI "casteljau"
#endif

typedef struct result {
    int status;
    char out[4096];
    char err[4096];
} result;

static char dir[64];

static void run(result *r, const char *const *args) {
    assert_int_equal(cj_cli_run_into(CJ_CLI, "tessellate", args, &r->status, r->out, sizeof r->out,
                                     r->err, sizeof r->err),
                     0);
}

static double field(const char *out, const char *key) {
    const char *p = strstr(out, key);
    assert_non_null(p);
    return strtod(p + strlen(key), NULL);
}

static size_t count_prefix(const char *path, const char *prefix) {
    FILE *f = fopen(path, "r");
    assert_non_null(f);
    char line[512];
    size_t n = 0;
    while (fgets(line, sizeof line, f))
        if (!strncmp(line, prefix, strlen(prefix))) ++n;
    fclose(f);
    return n;
}

static void test_teapot_obj(void **state) {
    (void)state;
    char obj[128];
    snprintf(obj, sizeof obj, "%s/teapot.obj", dir);
    result r;
    const char *args[] = {"--teapot", "--tol", "0.01", "-o", obj, NULL};
    run(&r, args);
    assert_int_equal(r.status, 0);
    assert_string_equal(r.err, "");
    const double tris = field(r.out, "triangles "), bound = field(r.out, "bound "),
                 meas = field(r.out, "measured ");
    assert_true(field(r.out, "patches ") == 32);
    assert_true(bound <= 0.01 && bound > 0);
    assert_true(meas <= bound && meas > 0);
    assert_true((size_t)tris == count_prefix(obj, "f "));
    assert_int_equal(count_prefix(obj, "g patch_"), 32);
    unlink(obj);
    /* uniform and PLY */
    char ply[128];
    snprintf(ply, sizeof ply, "%s/t.ply", dir);
    const char *args2[] = {"--teapot", "--uniform", "5", "-o", ply, NULL};
    run(&r, args2);
    assert_int_equal(r.status, 0);
    assert_true(field(r.out, "triangles ") <= 32 * 50 && field(r.out, "triangles ") > 32 * 40);
    assert_int_equal(access(ply, F_OK), 0);
    unlink(ply);
    printf("teapot: --tol 0.01 -> OBJ with the printed triangle count, 32 groups, bound <= tol, "
           "measured <= bound; --uniform 5 -> PLY\n");
}

static void test_single_patch(void **state) {
    (void)state;
    char obj[128];
    snprintf(obj, sizeof obj, "%s/p.obj", dir);
    result r;
    /* the saddle z = uv over the unit square: bilinear patch; uniform 4 has bound 1/64 exactly
     * (the error of the two-triangle split of each cell peaks at the cell centre) */
    const char *args[] = {
        "--patch", "0,0,0;1,0,0;0,1,0;1,1,1", "--degree", "1,1", "--uniform", "4", "-o", obj, NULL};
    run(&r, args);
    assert_int_equal(r.status, 0);
    assert_true(field(r.out, "triangles ") == 32);
    const double bound = field(r.out, "bound "), meas = field(r.out, "measured ");
    assert_true(bound >= 1.0 / 64 && bound < 1.0 / 64 * (1 + 1e-9));
    assert_true(meas <= bound && meas > 0.99 / 64);
    unlink(obj);
    printf("single bilinear patch: 32 triangles, bound 1/64 (tight: measured %.6g)\n", meas);
}

static void test_rational_patch(void **state) {
    (void)state;
    char obj[128];
    snprintf(obj, sizeof obj, "%s/r.obj", dir);
    result r;
    /* a quarter of the unit cylinder: rational quadratic in u (weights 1, 1/sqrt2, 1),
     * straight in v; every OBJ vertex must lie on the cylinder, the bound within --tol and the
     * measured deviation within the bound, and the bound at least the sagitta of the longest
     * chord between consecutive vertices of the bottom edge */
    const char *args[] = {"--patch",   "1,0,0;1,1,0;0,1,0;1,0,1;1,1,1;0,1,1",
                          "--degree",  "2,1",
                          "--weights", "1;0.70710678118654752;1;1;0.70710678118654752;1",
                          "--tol",     "1e-3",
                          "-o",        obj,
                          NULL};
    run(&r, args);
    assert_int_equal(r.status, 0);
    assert_string_equal(r.err, "");
    const double bound = field(r.out, "bound "), meas = field(r.out, "measured ");
    assert_true(bound <= 1e-3 && bound > 0);
    assert_true(meas <= bound && meas > 0);
    FILE *f = fopen(obj, "r");
    assert_non_null(f);
    char line[512];
    size_t nv = 0;
    double angles[4096];
    size_t na = 0;
    while (fgets(line, sizeof line, f)) {
        double x, y, z;
        if (sscanf(line, "v %lf %lf %lf", &x, &y, &z) != 3) continue;
        ++nv;
        assert_true(fabs(hypot(x, y) - 1.0) < 1e-14);
        if (z == 0.0 && na < 4096) angles[na++] = atan2(y, x);
    }
    fclose(f);
    assert_true(nv > 0 && na >= 2);
    /* longest gap between consecutive bottom-edge angles (sorted) */
    for (size_t i = 1; i < na; ++i)
        for (size_t j = i; j > 0 && angles[j] < angles[j - 1]; --j) {
            const double t = angles[j];
            angles[j] = angles[j - 1];
            angles[j - 1] = t;
        }
    double gap = 0.0;
    for (size_t i = 1; i < na; ++i) gap = fmax(gap, angles[i] - angles[i - 1]);
    const double sagitta = 1.0 - cos(gap / 2.0);
    assert_true(sagitta <= bound);
    unlink(obj);
    printf("rational quarter cylinder (--weights): %zu vertices on the cylinder, bound %.4g <= "
           "tol, measured %.4g <= bound, longest edge chord's sagitta %.4g <= bound\n",
           nv, bound, meas, sagitta);
}

static void expect_usage_error(const char *const *args, const char *out_path, const char *needle) {
    result r;
    run(&r, args);
    assert_int_equal(r.status, 2);
    assert_string_equal(r.out, "");
    const char *nl = strchr(r.err, '\n');
    assert_non_null(nl);
    assert_true(nl[1] == '\0'); /* exactly one line */
    if (needle && !strstr(r.err, needle)) fail_msg("stderr '%s' lacks '%s'", r.err, needle);
    if (out_path) assert_int_equal(access(out_path, F_OK), -1);
}

static void test_bad_input(void **state) {
    (void)state;
    char obj[128];
    snprintf(obj, sizeof obj, "%s/bad.obj", dir);
    const char *a1[] = {"--patch", "0,0,0;1,0,0;0,1,0", "--degree", "1,1", "-o", obj, NULL};
    expect_usage_error(a1, obj, "needs (M+1)(N+1) = 4");
    const char *a2[] = {"--patch", "0,0,0;1,0,nan;0,1,0;1,1,1", "--degree", "1,1", "-o", obj, NULL};
    expect_usage_error(a2, obj, "point 1");
    const char *a3[] = {"--teapot", "--tol", "-1", "-o", obj, NULL};
    expect_usage_error(a3, obj, "--tol");
    const char *a4[] = {"--teapot", "--tol", "0.1", "--uniform", "3", "-o", obj, NULL};
    expect_usage_error(a4, obj, "not both");
    const char *a5[] = {"--teapot", "-o", "x.stl", NULL};
    expect_usage_error(a5, "x.stl", ".obj, .ply or .vtu");
    const char *a6[] = {"--teapot", NULL};
    expect_usage_error(a6, NULL, "-o");
    const char *a7[] = {"--patch", "0,0;1,0;0,1;1,1", "--degree", "1,1", "-o", obj, NULL};
    expect_usage_error(a7, obj, "3");
    const char *a8[] = {"--patch", "0,0,0;1,0,0;0,1,0;1,1,1", "--degree", "1", "-o", obj, NULL};
    expect_usage_error(a8, obj, "--degree");
    const char *a9[] = {"--teapot", "--bogus", "1", "-o", obj, NULL};
    expect_usage_error(a9, obj, "--bogus");
    const char *a10[] = {
        "--patch", "0,0,0;1,0,0;0,1,0;1,1,1", "--degree", "1,1", "--tol", "1e-300", "-o", obj,
        NULL};
    expect_usage_error(a10, obj, "triangles"); /* predicted before any work */
    const char *a11[] = {
        "--patch", "0,0,0;1,0,0;0,1,0;1,1,1", "--degree", "1,1", "--weights", "1;2;3", "-o", obj,
        NULL};
    expect_usage_error(a11, obj, "--weights has 3 values");
    const char *a12[] = {
        "--patch", "0,0,0;1,0,0;0,1,0;1,1,1", "--degree", "1,1", "--weights", "1;2;0;4", "-o", obj,
        NULL};
    expect_usage_error(a12, obj, "weight 2");
    const char *a13[] = {"--patch",   "0,0,0;1,0,0;0,1,0;1,1,1",
                         "--degree",  "1,1",
                         "--weights", "1;2;nan;4",
                         "-o",        obj,
                         NULL};
    expect_usage_error(a13, obj, "--weights");
    const char *a14[] = {"--teapot", "--weights", "1", "-o", obj, NULL};
    expect_usage_error(a14, obj, "only for --patch");
    printf("bad input (wrong point count, NaN, bad --tol, --tol with --uniform, extension, no -o, "
           "2D points, bad --degree, unknown option, unreachable tolerance, wrong weight count, "
           "a zero or NaN weight, --weights without --patch): one stderr line, empty stdout, "
           "exit 2, no file\n");
}

int main(void) {
    snprintf(dir, sizeof dir, "/tmp/cj_cli_tess_XXXXXX");
    if (!mkdtemp(dir)) return 1;
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_teapot_obj),
        cmocka_unit_test(test_single_patch),
        cmocka_unit_test(test_rational_patch),
        cmocka_unit_test(test_bad_input),
    };
    int rc = cmocka_run_group_tests(tests, NULL, NULL);
    char p[128];
    snprintf(p, sizeof p, "%s/stdout", dir);
    unlink(p);
    snprintf(p, sizeof p, "%s/stderr", dir);
    unlink(p);
    rmdir(dir);
    return rc;
}

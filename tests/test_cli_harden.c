/* The casteljau tool under hostile and first-contact use (issue 14): options in any order,
 * --opt=value, "--", unknown options named, --version, --help that states the output and the
 * defaults, parameters from standard input, one-line messages with control characters escaped,
 * no inf or nan ever printed (CJ_ERR_RANGE, exit 2), bounded work (contour tolerances and
 * output caps), messages that speak of what the user gave, and start-up without OpenImageIO. */
#define _DEFAULT_SOURCE /* mkdtemp */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <dirent.h>
#include <sys/mount.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cmocka.h>

#include "cli_run.h"

#ifndef CJ_CLI
#error "CJ_CLI must name the casteljau executable"
#endif

static const char *exe = CJ_CLI;

/* Runs `casteljau args...` (NULL-terminated); the result must be freed. */
static cj_cli_result run(const char *first, ...) {
    char *argv[64];
    int n = 0;
    argv[n++] = (char *)exe;
    va_list ap;
    va_start(ap, first);
    for (const char *a = first; a && n < 63; a = va_arg(ap, const char *)) argv[n++] = (char *)a;
    va_end(ap);
    argv[n] = NULL;
    cj_cli_result r;
    assert_int_equal(cj_cli_spawn(argv, &r), 0);
    return r;
}

static cj_cli_result shell(const char *fmt, ...) {
    char cmd[4096];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(cmd, sizeof cmd, fmt, ap);
    va_end(ap);
    cj_cli_result r;
    assert_int_equal(cj_cli_shell(cmd, &r), 0);
    return r;
}

/* Exit 2, nothing on stdout, exactly one line on stderr starting "casteljau <cmd>: ", and the
 * line contains `must` (if not NULL) and not `must_not` (if not NULL). */
static void expect_refusal(cj_cli_result *r, const char *what, const char *cmd, const char *must,
                           const char *must_not) {
    if (r->status != 2) fail_msg("%s: exit %d, expected 2 (stderr: %s)", what, r->status, r->err);
    if (r->out_len) fail_msg("%s: stdout not empty: %.200s", what, r->out);
    const char *nl = strchr(r->err, '\n');
    if (!nl || nl[1] != '\0') fail_msg("%s: stderr is not one line: '%s'", what, r->err);
    char prefix[64];
    snprintf(prefix, sizeof prefix, "casteljau %s: ", cmd);
    if (strncmp(r->err, prefix, strlen(prefix)))
        fail_msg("%s: message does not start with '%s': %s", what, prefix, r->err);
    if (must && !strstr(r->err, must)) fail_msg("%s: message lacks '%s': %s", what, must, r->err);
    if (must_not && strstr(r->err, must_not))
        fail_msg("%s: message should not say '%s': %s", what, must_not, r->err);
    cj_cli_result_free(r);
}

static void expect_output(cj_cli_result *r, const char *what, const char *want) {
    if (r->status != 0) fail_msg("%s: exit %d (stderr: %s)", what, r->status, r->err);
    if (strcmp(r->out, want)) fail_msg("%s: stdout '%s', expected '%s'", what, r->out, want);
    cj_cli_result_free(r);
}

static const char *P = "0,0;1,2;2,0";

static void test_option_syntax(void **state) {
    (void)state;
    cj_cli_result r = run("eval", "0.5", "--points=0,0;1,2;2,0", "-0.5", NULL);
    expect_output(&r, "parameters before, between and after options", "1 1\n-1 -3\n");
    r = run("eval", "--points", P, "--", "-1", NULL);
    expect_output(&r, "'--' before a negative parameter", "-2 -8\n");
    r = run("eval", "--points", P, "0.5", "--bound", "--method=compensated", NULL);
    assert_int_equal(r.status, 0);
    assert_non_null(strstr(r.out, " | "));
    cj_cli_result_free(&r);
    r = run("eval", "-x", "--points", P, "0.5", NULL);
    expect_refusal(&r, "unknown short option", "eval", "unknown option '-x'", "--points");
    r = run("eval", "--frobnicate=3", "--points", P, "0.5", NULL);
    expect_refusal(&r, "unknown long option", "eval", "unknown option '--frobnicate'", NULL);
    r = run("interp", "--closed=yes", "--points", P, NULL);
    expect_refusal(&r, "a value for a flag", "interp", "takes no value", NULL);
    r = run("contour", "--circle=0,0,1", "--box=-2,-2,2,2", "--grid=4", NULL);
    assert_int_equal(r.status, 0);
    cj_cli_result_free(&r);
    r = run("tessellate", "-q", "--teapot", "-o", "x.obj", NULL);
    expect_refusal(&r, "tessellate unknown option", "tessellate", "unknown option '-q'", NULL);
    printf("test_cli_harden: options in any order, --opt=value, '--' before negative numbers, "
           "unknown options named\n");
}

static void test_version_and_help(void **state) {
    (void)state;
    cj_cli_result r = run("--version", NULL);
    expect_output(&r, "casteljau --version", "casteljau " CJ_VERSION "\n");
    r = run("eval", "--version", NULL);
    expect_output(&r, "casteljau eval --version", "casteljau " CJ_VERSION "\n");
    const char *cmds[] = {"eval", "interp", "contour", "plot", "tessellate"};
    for (size_t i = 0; i < sizeof cmds / sizeof cmds[0]; ++i) {
        r = run(cmds[i], "--help", NULL);
        if (r.status != 0) fail_msg("%s --help: exit %d", cmds[i], r.status);
        /* Every command states what it prints (or writes) and its defaults. */
        if (!strstr(r.out, "Output") || !strstr(r.out, "default") || !strstr(r.out, "Exit status"))
            fail_msg("%s --help does not state its output, defaults and exit status:\n%s", cmds[i],
                     r.out);
        cj_cli_result_free(&r);
    }
    printf("test_cli_harden: --version; every command's --help states output, defaults, exit "
           "status\n");
}

static void test_stdin_parameters(void **state) {
    (void)state;
    cj_cli_result r = shell("printf '0 0.5\\n  1\\n' | '%s' eval --points '%s'", exe, P);
    expect_output(&r, "parameters from stdin", "0 0\n1 1\n2 0\n");
    /* A long list: far more than fits on a command line in one go. */
    r = shell("awk 'BEGIN{for(i=0;i<200000;i++) print i/200000}' | '%s' eval --points '%s' | wc "
              "-l",
              exe, P);
    assert_int_equal(r.status, 0);
    assert_int_equal(atoi(r.out), 200000);
    cj_cli_result_free(&r);
    r = shell("printf '0 x 1' | '%s' eval --points '%s'", exe, P);
    expect_refusal(&r, "bad stdin parameter", "eval", "standard input, parameter 1", NULL);
    r = run("eval", "--points", P, NULL); /* stdin is /dev/null here */
    expect_refusal(&r, "no parameters anywhere", "eval", "no parameter", NULL);
    printf("test_cli_harden: eval reads parameters from stdin when none are given (200000 "
           "checked)\n");
}

static void test_one_line_messages(void **state) {
    (void)state;
    cj_cli_result r = run("eval", "--points", "0,0;1,x\ny", "0.5", NULL);
    expect_refusal(&r, "newline in a coordinate", "eval", "x\\ny", NULL);
    r = run("eval", "--method", "a\tb\x1b[31m", "--points", P, "0.5", NULL);
    expect_refusal(&r, "control characters in a method", "eval", "a\\tb\\x1b[31m", NULL);
    r = run("contour", "--poly", "1,2\n3", "--box", "0,0,1,1", NULL);
    expect_refusal(&r, "newline in --poly", "contour", NULL, NULL);
    printf("test_cli_harden: echoed input has its control characters escaped; one line\n");
}

static void test_never_inf(void **state) {
    (void)state;
    cj_cli_result r = run("eval", "--method", "bernstein", "--bound", "--points",
                          "1.7e308,1.7e308;1.7e308,1.7e308", "0.5", NULL);
    expect_refusal(&r, "bound overflow", "eval", "overflows", NULL);
    const char *pts = "-1e308,0;1e308,0;-1e308,1;1e308,1";
    r = run("interp", "--points", pts, NULL);
    expect_refusal(&r, "Catmull-Rom overflow", "interp", "overflows", NULL);
    r = run("interp", "--kind", "centripetal", "--points", "-1e308,0;1e308,0;0,1", NULL);
    expect_refusal(&r, "centripetal far apart", "interp", "too far apart", "coincide");
    r = run("interp", "--tension", "1e308", "--points", "0,0;1,0;2,1;3,1", NULL);
    expect_refusal(&r, "huge tension", "interp", "overflows", NULL);
    r = run("interp", "--kind", "kochanek-bartels", "--tension", "-1e308", "--bias", "1e308",
            "--points", "0,0;1,0;2,1;3,1", NULL);
    expect_refusal(&r, "huge KB parameters", "interp", "overflows", NULL);
    r = run("interp", "--kind", "polynomial", "--params", "-1e308;0;1e308", "--points", "0;1;2",
            NULL);
    expect_refusal(&r, "polynomial over a huge interval", "interp", "1e+308", "LAPACK");
    /* Whatever succeeds prints finite numbers only. */
    r = run("interp", "--closed", "--points", pts, NULL);
    if (r.status == 0 && (strstr(r.out, "inf") || strstr(r.out, "nan")))
        fail_msg("closed spline printed %s", r.out);
    cj_cli_result_free(&r);
    printf("test_cli_harden: overflowing bounds and control points refused (exit 2), never "
           "printed as inf\n");
}

static void test_contour_bounded(void **state) {
    (void)state;
    cj_cli_result r = run("contour", "--circle", "0,0,1.9", "--box", "-2,-2,2,2", "--grid", "4096",
                          "--tol", "1e-300", NULL);
    expect_refusal(&r, "tolerance 1e-300", "contour", "--tol", NULL);
    r = run("contour", "--ellipse", "0,0,2,1,0.3", "--box", "-3,-3,3,3", "--tol", "1e-31", NULL);
    expect_refusal(&r, "tolerance 1e-31", "contour", "--tol", NULL);
    r = run("contour", "--circle", "0,0,1", "--box", "-1e308,-1e308,1e308,1e308", NULL);
    expect_refusal(&r, "box sides overflow", "contour", "--box", "tol");
    r = run("contour", "--circle", "0,0,1", "--box", "-2,-2,2,2", "--max-points", "10", NULL);
    expect_refusal(&r, "output cap", "contour", "--max-points", NULL);
    r = run("contour", "--circle", "0,0,1", "--box", "-2,-2,2,2", "--max-points", "100000", NULL);
    assert_int_equal(r.status, 0);
    cj_cli_result_free(&r);
    printf("test_cli_harden: contour refuses tolerances doubles cannot resolve and output above "
           "--max-points, before the work\n");
}

static void test_startup_without_oiio(void **state) {
    (void)state;
    /* The dynamic loader lists every library it maps: eval must not map OpenImageIO. */
    cj_cli_result r = shell("LD_DEBUG=libs '%s' eval --points '%s' 0.5 2>&1 >/dev/null | grep -c "
                            "'calling init:.*OpenImageIO' || true",
                            exe, P);
    assert_int_equal(atoi(r.out), 0);
    cj_cli_result_free(&r);
    /* ... while an image-writing command does (so the check above can see it). */
    r = shell("cd \"$(mktemp -d)\" && LD_DEBUG=libs '%s' plot --demo --width 300 --height 200 -o "
              "g.png 2>&1 >/dev/null | grep -c 'calling init:.*OpenImageIO'",
              exe);
    if (atoi(r.out) < 1) fail_msg("plot did not load OpenImageIO? %s", r.out);
    cj_cli_result_free(&r);
    printf("test_cli_harden: eval maps no OpenImageIO (LD_DEBUG=libs); plot loads it on use\n");
}

static int dir_entries(const char *d) {
    DIR *h = opendir(d);
    assert_non_null(h);
    int n = 0;
    struct dirent *e;
    while ((e = readdir(h)))
        if (strcmp(e->d_name, ".") && strcmp(e->d_name, "..")) ++n;
    closedir(h);
    return n;
}

static char *slurp(const char *path, size_t *len) {
    FILE *f = fopen(path, "rb");
    if (!f) return NULL;
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fseek(f, 0, SEEK_SET);
    char *b = malloc((size_t)n + 1);
    assert_non_null(b);
    assert_int_equal(fread(b, 1, (size_t)n, f), (size_t)n);
    fclose(f);
    *len = (size_t)n;
    return b;
}

/* Each writer: a small good file first, then a large one over it into a folder that holds
 * about 40 KB. The large write must exit 1 with one line on stderr, keep the small file
 * byte for byte, and leave nothing else behind. `limit` is the shell prefix that makes the
 * folder "full" ("" on a small tmpfs; a file-size limit otherwise). */
static void full_disk_writers(const char *d, const char *limit, const char *how) {
    static const struct {
        const char *name, *small, *big;
    } cases[] = {
        /* the large ones are 57-204 KB */
        {"g.png", "plot --demo --width 64 --height 64", "plot --demo --width 600 --height 400"},
        {"g.jpg", "plot --demo --width 64 --height 64", "plot --demo --width 600 --height 400"},
        {"g.tif", "plot --demo --width 64 --height 64", "plot --demo --width 600 --height 400"},
        {"t.obj", "tessellate --teapot --uniform 1", "tessellate --teapot --tol 0.1"},
        {"t.ply", "tessellate --teapot --uniform 1", "tessellate --teapot --tol 0.1"},
        {"t.vtu", "tessellate --teapot --uniform 1", "tessellate --teapot --tol 0.1"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        char path[600];
        snprintf(path, sizeof path, "%s/%s", d, cases[i].name);
        cj_cli_result r = shell("'%s' %s -o '%s'", exe, cases[i].small, path);
        if (r.status != 0) fail_msg("%s: small write failed: %s", cases[i].name, r.err);
        cj_cli_result_free(&r);
        size_t n0 = 0, n1 = 0;
        char *before = slurp(path, &n0);
        assert_non_null(before);
        r = shell("%s '%s' %s -o '%s'", limit, exe, cases[i].big, path);
        if (r.status != 1)
            fail_msg("%s (%s): exit %d, expected 1; stderr %s", cases[i].name, how, r.status,
                     r.err);
        const char *nl = strchr(r.err, '\n');
        if (!nl || nl[1]) fail_msg("%s: stderr is not one line: %s", cases[i].name, r.err);
        cj_cli_result_free(&r);
        char *after = slurp(path, &n1);
        assert_non_null(after);
        if (n0 != n1 || memcmp(before, after, n0))
            fail_msg("%s (%s): the previous file was changed", cases[i].name, how);
        free(before);
        free(after);
        if (dir_entries(d) != 1) fail_msg("%s (%s): files left behind", cases[i].name, how);
        unlink(path);
    }
}

static void test_full_disk(void **state) {
    (void)state;
    char d[] = "/tmp/cj_test_cli_full_XXXXXX";
    assert_non_null(mkdtemp(d));
    if (mount("tmpfs", d, "tmpfs", 0, "size=40k") == 0) {
        full_disk_writers(d, "", "40 KB tmpfs");
        assert_int_equal(umount(d), 0);
        printf("test_cli_harden: on a full 40 KB tmpfs, PNG, JPEG, TIFF, OBJ, PLY and .vtu writes "
               "exit 1 and keep the previous file, nothing left behind\n");
    } else {
        /* Not root: a file-size limit fails write(2) as a full disk does (EFBIG for ENOSPC;
         * dash counts 512-byte blocks). */
        full_disk_writers(d, "trap '' XFSZ; ulimit -f 80;", "40 KB file-size limit");
        printf("test_cli_harden: no tmpfs here (not root): under a 40 KB file-size limit, PNG, "
               "JPEG, TIFF, OBJ, PLY and .vtu writes exit 1 and keep the previous file\n");
    }
    rmdir(d);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_option_syntax),
        cmocka_unit_test(test_version_and_help),
        cmocka_unit_test(test_stdin_parameters),
        cmocka_unit_test(test_one_line_messages),
        cmocka_unit_test(test_never_inf),
        cmocka_unit_test(test_contour_bounded),
        cmocka_unit_test(test_startup_without_oiio),
        cmocka_unit_test(test_full_disk),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

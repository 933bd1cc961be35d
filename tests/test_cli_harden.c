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
    cj_cli_result r = cj_cli_shellf("printf '0 0.5\\n  1\\n' | '%s' eval --points '%s'", exe, P);
    expect_output(&r, "parameters from stdin", "0 0\n1 1\n2 0\n");
    /* A long list: far more than fits on a command line in one go. */
    r = cj_cli_shellf(
        "awk 'BEGIN{for(i=0;i<200000;i++) print i/200000}' | '%s' eval --points '%s' | wc "
        "-l",
        exe, P);
    assert_int_equal(r.status, 0);
    assert_int_equal(atoi(r.out), 200000);
    cj_cli_result_free(&r);
    r = cj_cli_shellf("printf '0 x 1' | '%s' eval --points '%s'", exe, P);
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
    cj_cli_result r =
        cj_cli_shellf("LD_DEBUG=libs '%s' eval --points '%s' 0.5 2>&1 >/dev/null | grep -c "
                      "'calling init:.*OpenImageIO' || true",
                      exe, P);
    assert_int_equal(atoi(r.out), 0);
    cj_cli_result_free(&r);
    /* Nor does a PNG (libpng directly) ... */
    r = cj_cli_shellf(
        "cd \"$(mktemp -d)\" && LD_DEBUG=libs '%s' plot --demo --width 300 --height 200 -o "
        "g.png 2>&1 >/dev/null | grep -c 'calling init:.*OpenImageIO' || true",
        exe);
    assert_int_equal(atoi(r.out), 0);
    cj_cli_result_free(&r);
    /* ... while a TIFF does (so the checks above can see it). */
    r = cj_cli_shellf(
        "cd \"$(mktemp -d)\" && LD_DEBUG=libs '%s' plot --demo --width 300 --height 200 -o "
        "g.tif 2>&1 >/dev/null | grep -c 'calling init:.*OpenImageIO'",
        exe);
    if (atoi(r.out) < 1) fail_msg("plot -o g.tif did not load OpenImageIO? %s", r.out);
    cj_cli_result_free(&r);
    printf("test_cli_harden: eval and plot -o x.png map no OpenImageIO (LD_DEBUG=libs); plot -o "
           "x.tif loads it on use\n");
}

static char *slurp(const char *path, size_t *len);

static int file_exists(const char *p) {
    return access(p, F_OK) == 0;
}

static void test_tessellate_first_contact(void **state) {
    (void)state;
    char d[] = "/tmp/cj_test_cli_tess_XXXXXX";
    assert_non_null(mkdtemp(d));
    char obj[600], vtu[600], bpt[600];
    snprintf(obj, sizeof obj, "%s/t.obj", d);
    snprintf(vtu, sizeof vtu, "%s/t.vtu", d);
    snprintf(bpt, sizeof bpt, "%s/one.bpt", d);
    /* --uniform 4096 on the teapot: 1.07e9 triangles, refused at once with the figure */
    cj_cli_result r = run("tessellate", "--teapot", "--uniform", "4096", "-o", obj, NULL);
    expect_refusal(&r, "teapot uniform 4096", "tessellate", "predicted", NULL);
    assert_false(file_exists(obj));
    r = run("tessellate", "--patch", "0,0,0;1,0,0;0,1,0;1,22550,0", "--degree", "1,1", "--tol",
            "0.01", "-o", obj, NULL);
    expect_refusal(&r, "stretched bilinear patch", "tessellate", "--max-triangles", NULL);
    r = run("tessellate", "--patch", "0,0,0;1,0,0;2,0,0;0,1,0;1,1,1;2,1,0;0,2,0;1,2,0;2,2,0",
            "--degree", "2,2", "--weights", "1;1;1;1;4096.5;1;1;1;1", "-o", obj, NULL);
    expect_refusal(&r, "rational weight 4096.5", "tessellate", "--max-triangles", NULL);
    r = run("tessellate", "--teapot", "--max-triangles", "5000", "-o", obj, NULL);
    expect_refusal(&r, "teapot over a small --max-triangles", "tessellate", "5000", NULL);
    /* degenerate patches: refused, no empty mesh written */
    r = run("tessellate", "--patch", "1,1,1;1,1,1;1,1,1;1,1,1", "--degree", "1,1", "-o", obj, NULL);
    expect_refusal(&r, "all control points equal", "tessellate", "degenerate", NULL);
    r = run("tessellate", "--patch", "1,1,1", "--degree", "0,0", "-o", obj, NULL);
    expect_refusal(&r, "degree 0,0", "tessellate", "degenerate", NULL);
    assert_false(file_exists(obj));
    /* equal huge weights: the plain bilinear patch, same mesh */
    r = run("tessellate", "--patch", "0,0,0;1,0,0;0,1,0;1,1,1", "--degree", "1,1", "--weights",
            "1e308;1e308;1e308;1e308", "-o", obj, NULL);
    cj_cli_result plain =
        run("tessellate", "--patch", "0,0,0;1,0,0;0,1,0;1,1,1", "--degree", "1,1", "-o", obj, NULL);
    assert_int_equal(r.status, 0);
    assert_int_equal(plain.status, 0);
    assert_non_null(strstr(r.out, "triangles "));
    if (strncmp(strstr(r.out, "triangles "), strstr(plain.out, "triangles "), 16))
        fail_msg("weights 1e308 gave %s, the plain patch %s", r.out, plain.out);
    cj_cli_result_free(&r);
    cj_cli_result_free(&plain);
    /* --bpt and .vtu */
    FILE *f = fopen(bpt, "w");
    assert_non_null(f);
    fputs("1\n1 1\n0 0 0\n1 0 0\n0 1 0\n1 1 1\n", f);
    fclose(f);
    r = run("tessellate", "--bpt", bpt, "--uniform", "2", "-o", vtu, NULL);
    if (r.status != 0 || strncmp(r.out, "patches 1\ntriangles 8\nvertices 9\n", 33))
        fail_msg("--bpt to .vtu: exit %d, %s%s", r.status, r.out, r.err);
    cj_cli_result_free(&r);
    size_t n = 0;
    char *x = slurp(vtu, &n);
    assert_non_null(x);
    assert_non_null(strstr(x, "<VTKFile type=\"UnstructuredGrid\""));
    assert_non_null(strstr(x, "NumberOfPoints=\"9\" NumberOfCells=\"8\""));
    assert_non_null(strstr(x, "</VTKFile>"));
    free(x);
    r = run("tessellate", "--bpt", "/nonexistent.bpt", "-o", obj, NULL);
    expect_refusal(&r, "missing --bpt", "tessellate", "nonexistent.bpt", NULL);
    unlink(vtu);
    unlink(bpt);
    rmdir(d);
    printf("test_cli_harden: tessellate predicts and refuses oversized meshes (teapot uniform "
           "4096, stretched and heavy-weight patches), refuses degenerate patches, treats equal "
           "huge weights as the polynomial, reads --bpt and writes .vtu\n");
}

static void test_plot_first_contact(void **state) {
    (void)state;
    char d[] = "/tmp/cj_test_cli_plot_XXXXXX";
    assert_non_null(mkdtemp(d));
    char out[600], js[600];
    snprintf(out, sizeof out, "%s/p.png", d);
    snprintf(js, sizeof js, "%s/p.json", d);
    cj_cli_result r = run("plot", "--demo", "--width", "64", "--height", "64", "-o", out, NULL);
    if (r.status != 0 || !strstr(r.out, "(64 x 64)"))
        fail_msg("plot --width 64 --height 64: exit %d, %s%s", r.status, r.out, r.err);
    cj_cli_result_free(&r);
    snprintf(out, sizeof out, "%s/p.jpg", d);
    r = run("plot", "--demo", "--width=200", "--height=120", "-o", out, NULL);
    assert_int_equal(r.status, 0);
    cj_cli_result_free(&r);
    size_t n = 0;
    char *x = slurp(out, &n);
    assert_non_null(x);
    assert_true(n > 3 && (unsigned char)x[0] == 0xff && (unsigned char)x[1] == 0xd8);
    free(x);
    unlink(out);
    r = run("plot", "--demo", "-o", "", NULL);
    expect_refusal(&r, "empty output name", "plot", "-o", NULL);
    snprintf(out, sizeof out, "%s/p.nosuchformat", d);
    r = run("plot", "--demo", "-o", out, NULL);
    expect_refusal(&r, "unknown image format", "plot", "nosuchformat", NULL);
    assert_false(file_exists(out));
    snprintf(out, sizeof out, "%s/p.png", d);
    unlink(out);
    FILE *f = fopen(js, "w");
    assert_non_null(f);
    fputs("{\"items\": [{\"type\": \"points\", \"points\": [[1, 2]]}]}", f);
    fclose(f);
    r = run("plot", js, "-o", out, NULL);
    assert_int_equal(r.status, 0); /* a one-point item is valid */
    cj_cli_result_free(&r);
    /* a long title, and 200 implicit degree-32 items at grid 1024: refused before the work */
    f = fopen(js, "w");
    assert_non_null(f);
    fputs("{\"title\": \"", f);
    for (int i = 0; i < 2000; ++i) fputc('x', f);
    fputs("\", \"items\": [{\"type\": \"points\", \"points\": [[1, 2]]}]}", f);
    fclose(f);
    r = run("plot", js, "-o", out, NULL);
    expect_refusal(&r, "2000-byte title", "plot", "title", NULL);
    f = fopen(js, "w");
    assert_non_null(f);
    fputs("{\"items\": [", f);
    for (int i = 0; i < 200; ++i) {
        fprintf(f,
                "%s{\"type\": \"implicit\", \"grid\": 1024, \"box\": [-1,-1,1,1], "
                "\"poly\": {\"degree\": 32, \"coef\": [-1",
                i ? "," : "");
        for (int k = 1; k < 561; ++k) fputs(k == 3 || k == 5 ? ",1" : ",0", f);
        fputs("]}}", f);
    }
    fputs("]}", f);
    fclose(f);
    r = run("plot", js, "-o", out, NULL);
    expect_refusal(&r, "200 degree-32 implicit items", "plot", "items[", NULL);
    /* a JSON file just over 64 MiB (the limit said so but let 128 MiB through) */
    f = fopen(js, "w");
    assert_non_null(f);
    assert_int_equal(fseek(f, (64L << 20) + 16, SEEK_SET), 0);
    fputc(' ', f);
    fclose(f);
    r = run("plot", js, "-o", out, NULL);
    expect_refusal(&r, "65 MiB of JSON", "plot", "64 MiB", NULL);
    unlink(js);
    unlink(out);
    rmdir(d);
    printf("test_cli_harden: plot renders 64x64 and one-point items, writes JPEG for .jpg, "
           "checks -o before any work, refuses long titles, too much implicit work and JSON "
           "over 64 MiB\n");
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
        cj_cli_result r = cj_cli_shellf("'%s' %s -o '%s'", exe, cases[i].small, path);
        if (r.status != 0) fail_msg("%s: small write failed: %s", cases[i].name, r.err);
        cj_cli_result_free(&r);
        size_t n0 = 0, n1 = 0;
        char *before = slurp(path, &n0);
        assert_non_null(before);
        r = cj_cli_shellf("%s '%s' %s -o '%s'", limit, exe, cases[i].big, path);
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
    /* Two CTest programs from this file (CJ_HARDEN_GROUP 1 and 2), so each stays short. */
#if CJ_HARDEN_GROUP == 1
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_option_syntax),
        cmocka_unit_test(test_version_and_help),
        cmocka_unit_test(test_stdin_parameters),
        cmocka_unit_test(test_one_line_messages),
        cmocka_unit_test(test_never_inf),
        cmocka_unit_test(test_contour_bounded),
        cmocka_unit_test(test_startup_without_oiio),
    };
    (void)test_full_disk, (void)test_tessellate_first_contact, (void)test_plot_first_contact;
#else
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_full_disk),
        cmocka_unit_test(test_tessellate_first_contact),
        cmocka_unit_test(test_plot_first_contact),
    };
    (void)test_option_syntax, (void)test_version_and_help, (void)test_stdin_parameters;
    (void)test_one_line_messages, (void)test_never_inf, (void)test_contour_bounded;
    (void)test_startup_without_oiio;
#endif
    return cmocka_run_group_tests(tests, NULL, NULL);
}

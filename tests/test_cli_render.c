/* Contract test of `casteljau render`, run as a child process: --demo and the shipped scenes
 * write a PNG (and an EXR) and nothing on stdout; --stage-report prints the report as JSON on
 * stdout; bad input (an unknown key, a value out of range, a JSON syntax error, a missing file,
 * bad options) gives one stderr line naming the file, line and JSON path, nothing on stdout,
 * no image file and exit status 2. */
#define _POSIX_C_SOURCE 200809L
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "cli_run.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#ifndef CJ_CLI
#define CJ_CLI "casteljau"
#endif
#ifndef CJ_SCENES_DIR
#define CJ_SCENES_DIR "scenes"
#endif

typedef struct result {
    int status;
    char out[16384];
    char err[4096];
} result;

static char dir[64];

static void run(result *r, const char *const *args) {
    assert_int_equal(cj_cli_run_into(CJ_CLI, "render", args, &r->status, r->out, sizeof r->out,
                                     r->err, sizeof r->err),
                     0);
}

static int file_starts_with(const char *path, const unsigned char *magic, size_t n) {
    FILE *f = fopen(path, "rb");
    if (!f) return 0;
    unsigned char buf[16];
    size_t got = fread(buf, 1, n, f);
    fclose(f);
    return got == n && !memcmp(buf, magic, n);
}

static const unsigned char png_magic[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};

static void test_demo(void **state) {
    (void)state;
    char png[128];
    snprintf(png, sizeof png, "%s/demo.png", dir);
    result r;
    const char *args[] = {"--demo", "-o",    png, "--width",   "160", "--height",
                          "120",    "--spp", "1", "--threads", "2",   NULL};
    run(&r, args);
    assert_int_equal(r.status, 0);
    assert_string_equal(r.out, "");
    assert_string_equal(r.err, "");
    assert_true(file_starts_with(png, png_magic, 8));
    printf("test_demo: --demo wrote a PNG, stdout and stderr empty\n");
}

static void test_stage_report(void **state) {
    (void)state;
    char png[128];
    snprintf(png, sizeof png, "%s/report.png", dir);
    result r;
    const char *args[] = {"--demo", "-o",       png,   "--width",        "120", "--height",
                          "90",     "--tol-px", "0.5", "--stage-report", NULL};
    run(&r, args);
    assert_int_equal(r.status, 0);
    assert_string_equal(r.err, "");
    assert_true(!strncmp(r.out, "{\"renderer\":\"raster\",", 21));
    size_t n = strlen(r.out);
    assert_true(n > 2 && r.out[n - 2] == '}' && r.out[n - 1] == '\n');
    const char *must[] = {"\"tessellate_patches\",\"ran\":true",
                          "\"shade_phong\",\"ran\":true",
                          "\"texture\",\"ran\":true",
                          "\"overlay_lines\",\"ran\":true",
                          "\"resolve\",\"ran\":true",
                          "\"transparency\",\"ran\":false,\"why\":\"no transparent material\"",
                          "\"tol_px\":0.5"};
    for (size_t i = 0; i < sizeof must / sizeof must[0]; ++i)
        if (!strstr(r.out, must[i])) fail_msg("stage report lacks %s:\n%s", must[i], r.out);
    printf("test_stage_report: JSON report on stdout with every stage, run or not, and why\n");
}

static void test_scenes_and_exr(void **state) {
    (void)state;
    const char *names[] = {"teapot", "quadrics", "revolution", "transparent"};
    int done = 0;
    for (size_t i = 0; i < sizeof names / sizeof names[0]; ++i) {
        char scene[512], png[128];
        snprintf(scene, sizeof scene, "%s/%s.json", CJ_SCENES_DIR, names[i]);
        if (access(scene, R_OK) != 0) continue;
        snprintf(png, sizeof png, "%s/%s.png", dir, names[i]);
        result r;
        const char *args[] = {scene, "-o", png, "--width", "96", "--height", "72", NULL};
        run(&r, args);
        if (r.status != 0) fail_msg("%s: status %d: %s", scene, r.status, r.err);
        assert_string_equal(r.out, "");
        assert_true(file_starts_with(png, png_magic, 8));
        ++done;
    }
    char exr[128];
    snprintf(exr, sizeof exr, "%s/demo.exr", dir);
    result r;
    const char *args[] = {"--demo", "-o", exr, "--width", "64", "--height", "48", NULL};
    run(&r, args);
    assert_int_equal(r.status, 0);
    const unsigned char exr_magic[4] = {0x76, 0x2f, 0x31, 0x01};
    assert_true(file_starts_with(exr, exr_magic, 4));
    printf("test_scenes_and_exr: %d shipped scenes to PNG, the demo to EXR\n", done);
}

/* A bad run: exit 2, one line on stderr containing each of `need`, nothing on stdout, and no
 * image left behind. */
static void expect_bad(const char *const *args, const char *image, const char *need1,
                       const char *need2) {
    result r;
    run(&r, args);
    if (r.status != 2) fail_msg("status %d (stderr: %s)", r.status, r.err);
    assert_string_equal(r.out, "");
    size_t n = strlen(r.err);
    assert_true(n > 1 && r.err[n - 1] == '\n' && !memchr(r.err, '\n', n - 1));
    if (need1 && !strstr(r.err, need1)) fail_msg("stderr lacks '%s': %s", need1, r.err);
    if (need2 && !strstr(r.err, need2)) fail_msg("stderr lacks '%s': %s", need2, r.err);
    if (image) assert_int_not_equal(access(image, F_OK), 0);
}

static void write_file(const char *path, const char *text) {
    FILE *f = fopen(path, "w");
    assert_non_null(f);
    fputs(text, f);
    fclose(f);
}

static void test_bad_input(void **state) {
    (void)state;
    char scene[128], png[128];
    snprintf(png, sizeof png, "%s/bad.png", dir);
    snprintf(scene, sizeof scene, "%s/bad.json", dir);
    write_file(scene, "{\n  \"materials\": [\n    {\"name\": \"m\", \"alpha\": -3}\n  ],\n"
                      "  \"objects\": [{\"material\": \"m\", \"geometry\": {\"type\": \"sphere\", "
                      "\"radius\": 1}}]\n}\n");
    const char *a1[] = {scene, "-o", png, NULL};
    expect_bad(a1, png, "bad.json:3", "materials[0].alpha");
    write_file(scene, "{\n  \"objects\": [\n    {\"geometry\": {\"type\": \"sphere\", "
                      "\"radius\": 1, \"colour\": 2}}\n  ]\n}\n");
    expect_bad(a1, png, "bad.json:3", "colour");
    write_file(scene, "{\n  \"objects\": [\n    {\"geometry\": \n}\n");
    expect_bad(a1, png, "bad.json", NULL);
    char missing[128];
    snprintf(missing, sizeof missing, "%s/none.json", dir);
    const char *a2[] = {missing, "-o", png, NULL};
    expect_bad(a2, png, "none.json", NULL);
    const char *a3[] = {"--demo", "-o", png, "--spp", "3", NULL};
    expect_bad(a3, png, "--spp", NULL);
    const char *a4[] = {"--demo", NULL};
    expect_bad(a4, NULL, "-o", NULL);
    char jpg[128];
    snprintf(jpg, sizeof jpg, "%s/out.jpg", dir);
    const char *a5[] = {"--demo", "-o", jpg, NULL};
    expect_bad(a5, jpg, ".png or .exr", NULL);
    const char *a6[] = {"--demo", "-o", png, "--tol-px", "0", NULL};
    expect_bad(a6, png, "--tol-px", NULL);
    const char *a7[] = {"--demo", "-o", "/nonexistent-dir/x.png", NULL};
    expect_bad(a7, "/nonexistent-dir/x.png", "nonexistent-dir", NULL);
    printf("test_bad_input: 9 bad runs: exit 2, one stderr line (file:line and JSON path for "
           "scene errors), empty stdout, no image\n");
}

int main(void) {
    snprintf(dir, sizeof dir, "/tmp/cj_cli_render_XXXXXX");
    if (!mkdtemp(dir)) return 1;
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_demo),
        cmocka_unit_test(test_stage_report),
        cmocka_unit_test(test_scenes_and_exr),
        cmocka_unit_test(test_bad_input),
    };
    int rc = cmocka_run_group_tests(tests, NULL, NULL);
    char cmd[128];
    snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
    if (system(cmd) != 0) fprintf(stderr, "could not remove %s\n", dir);
    return rc;
}

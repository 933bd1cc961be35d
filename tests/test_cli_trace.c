/* Contract test of `casteljau trace`, run as a child process: --demo and a shipped scene write
 * a PNG and nothing on stdout; --stage-report prints the tracer's report (rays of each kind) as
 * JSON on stdout; --signature writes the id image; bad input (a missing or malformed scene,
 * bad options) gives one stderr line, nothing on stdout, no image file and exit status 2. */
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

typedef struct result {
    int status;
    char out[16384];
    char err[4096];
} result;

static char dir[64];

static void run(result *r, const char *const *args) {
    assert_int_equal(cj_cli_run_into(CJ_CLI, "trace", args, &r->status, r->out, sizeof r->out,
                                     r->err, sizeof r->err),
                     0);
}

static int is_png(const char *path) {
    static const unsigned char magic[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    FILE *f = fopen(path, "rb");
    if (!f) return 0;
    unsigned char buf[8];
    size_t got = fread(buf, 1, 8, f);
    fclose(f);
    return got == 8 && !memcmp(buf, magic, 8);
}

static void test_demo_and_report(void **state) {
    (void)state;
    char png[128];
    snprintf(png, sizeof png, "%s/demo.png", dir);
    result r;
    const char *a1[] = {"--demo",   "-o", png,         "--width", "64",
                        "--height", "48", "--threads", "2",       NULL};
    run(&r, a1);
    assert_int_equal(r.status, 0);
    assert_string_equal(r.out, "");
    assert_string_equal(r.err, "");
    assert_true(is_png(png));
    const char *a2[] = {
        "--demo", "-o",          png, "--width", "48", "--height",       "36", "--spp",
        "2",      "--max-depth", "3", "--seed",  "9",  "--stage-report", NULL};
    run(&r, a2);
    assert_int_equal(r.status, 0);
    assert_string_equal(r.err, "");
    assert_true(!strncmp(r.out, "{\"renderer\":\"trace\",", 20));
    const char *must[] = {"\"primary_rays\",\"ran\":true", "\"shadow_rays\",\"ran\":true",
                          "\"reflection_rays\",\"ran\":true", "\"refraction_rays\",\"ran\":true",
                          "\"transparency_rays\",\"ran\":false"};
    for (int i = 0; i < 5; i++) {
        if (!strstr(r.out, must[i])) fprintf(stderr, "missing %s in\n%s\n", must[i], r.out);
        assert_non_null(strstr(r.out, must[i]));
    }
    char sig[128];
    snprintf(sig, sizeof sig, "%s/sig.png", dir);
    const char *a3[] = {CJ_SCENES_DIR "/quadrics.json",
                        "-o",
                        sig,
                        "--width",
                        "40",
                        "--height",
                        "30",
                        "--signature",
                        NULL};
    run(&r, a3);
    assert_int_equal(r.status, 0);
    assert_true(is_png(sig));
    printf("test_demo_and_report: --demo PNG, --stage-report JSON with each ray kind, a shipped "
           "scene's signature image\n");
}

static void test_bad_input(void **state) {
    (void)state;
    char png[128], bad[128];
    snprintf(png, sizeof png, "%s/bad.png", dir);
    snprintf(bad, sizeof bad, "%s/bad.json", dir);
    FILE *f = fopen(bad, "w");
    assert_non_null(f);
    fputs("{\n  \"camera\": {\"eye\": [0, 0, 5]},\n  \"nonsense\": 1\n}\n", f);
    fclose(f);
    const char *cases[][12] = {
        {"/no/such/scene.json", "-o", png, NULL},
        {bad, "-o", png, NULL},
        {"--demo", NULL},
        {"--demo", "-o", "x.bmp", NULL},
        {"--demo", "-o", png, "--spp", "0", NULL},
        {"--demo", "-o", png, "--max-depth", "-1", NULL},
        {"--demo", "-o", png, "--seed", "abc", NULL},
        {"--demo", "-o", png, "--threads", "0", NULL},
        {"--demo", "-o", png, "--frobnicate", "1", NULL},
        {"--demo", bad, "-o", png, NULL},
    };
    int n = (int)(sizeof cases / sizeof cases[0]);
    for (int i = 0; i < n; i++) {
        result r;
        unlink(png);
        run(&r, cases[i]);
        if (r.status != 2) fprintf(stderr, "case %d: status %d err %s\n", i, r.status, r.err);
        assert_int_equal(r.status, 2);
        assert_string_equal(r.out, "");
        size_t len = strlen(r.err);
        assert_true(len > 0 && r.err[len - 1] == '\n' && strchr(r.err, '\n') == r.err + len - 1);
        assert_true(!strncmp(r.err, "casteljau trace: ", 17));
        assert_int_equal(access(png, F_OK), -1);
    }
    printf("test_bad_input: %d bad inputs: exit 2, one stderr line, nothing on stdout, no file\n",
           n);
}

static int setup(void **state) {
    (void)state;
    snprintf(dir, sizeof dir, "/tmp/cj_cli_trace_XXXXXX");
    return mkdtemp(dir) ? 0 : -1;
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_demo_and_report),
        cmocka_unit_test(test_bad_input),
    };
    return cmocka_run_group_tests(tests, setup, NULL);
}

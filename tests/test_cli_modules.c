/* What the casteljau program maps at start-up (issue 20's start-up row, issue 25's "graphics
 * libraries loaded only when view runs"): no GLFW, OpenGL, X11, xcb, FFmpeg, cairo or
 * OpenImageIO library, neither among everything `ldd` resolves nor among what `eval` maps
 * (LD_DEBUG=libs). They live in modules opened by the commands that need them; a missing film
 * or vector-plot module is a one-line error and no file. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>

#include "support/cli_run.h"

static const char *const deferred[] = {"libglfw",    "libGL",      "libGLX",
                                       "libGLEW",    "libavcodec", "libavformat",
                                       "libswscale", "libavutil",  "libOpenImageIO"};
enum { NDEFERRED = sizeof deferred / sizeof deferred[0] };

static void test_program_links_none(void **state) {
    (void)state;
    cj_cli_result r = cj_cli_shellf("ldd '%s'", CJ_CLI);
    assert_int_equal(r.status, 0);
    assert_non_null(strstr(r.out, "libc.so")); /* the check can see the libraries */
    for (size_t i = 0; i < NDEFERRED; ++i)
        if (strstr(r.out, deferred[i])) fail_msg("casteljau links %s:\n%s", deferred[i], r.out);
    cj_cli_result_free(&r);
    r = cj_cli_shellf("LD_DEBUG=libs '%s' eval --points '0,0;1,1' 0.5 2>&1 >/dev/null | grep "
                      "'calling init:' || true",
                      CJ_CLI);
    for (size_t i = 0; i < NDEFERRED; ++i)
        if (strstr(r.out, deferred[i])) fail_msg("eval maps %s:\n%s", deferred[i], r.out);
    cj_cli_result_free(&r);
    printf("test_cli_modules: casteljau needs (ldd) and eval maps no GLFW, OpenGL, X11, xcb, "
           "FFmpeg, cairo or OpenImageIO library\n");
}

/* Runs `cmd` (a shell line that ends by listing its fresh folder) with a module's variable
 * pointing nowhere: exit 1 or 2, one line on stderr naming the variable and the module, and no
 * file `left` in the folder. */
static void expect_missing_module(const char *cmd, const char *variable, const char *module,
                                  const char *left) {
    cj_cli_result r = cj_cli_shellf("cd \"$(mktemp -d)\" && %s; s=$?; ls; exit $s", cmd);
    if (r.status != 1 && r.status != 2) fail_msg("exit status %d: %s", r.status, r.err);
    if (!strstr(r.err, variable) || !strstr(r.err, module)) fail_msg("message: %s", r.err);
    if (!cj_cli_one_line(r.err)) fail_msg("more than one line: %s", r.err);
    if (strstr(r.out, left)) fail_msg("a file was left: %s", r.out);
    printf("  %s", r.err);
    cj_cli_result_free(&r);
}

static void test_missing_film_module(void **state) {
    (void)state;
    char cmd[1024];
    snprintf(cmd, sizeof cmd,
             "CJ_VIDEO_PLUGIN=/nonexistent/libv.so '%s' animate '%s' -o f.mp4 --frames 0:2 "
             "--width 64 --height 48",
             CJ_CLI, CJ_ANIM_PATH);
    expect_missing_module(cmd, "CJ_VIDEO_PLUGIN", "film module", "f.mp4");
    printf("test_cli_modules: a missing film module is a one-line error naming CJ_VIDEO_PLUGIN, "
           "and no file\n");
}

static void test_missing_cairo_module(void **state) {
    (void)state;
    char cmd[1024];
    snprintf(cmd, sizeof cmd, "CJ_CAIRO_PLUGIN=/nonexistent/libc.so '%s' plot --demo -o p.svg",
             CJ_CLI);
    expect_missing_module(cmd, "CJ_CAIRO_PLUGIN", "vector plot module", "p.svg");
    printf("test_cli_modules: a missing vector plot module is a one-line error naming "
           "CJ_CAIRO_PLUGIN, before any work, and no file\n");
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_program_links_none),
        cmocka_unit_test(test_missing_film_module),
        cmocka_unit_test(test_missing_cairo_module),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

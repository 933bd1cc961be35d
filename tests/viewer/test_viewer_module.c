/* The viewer is a module opened only by `view` (issue 25; test_cli_modules checks that the
 * program links no graphics library): `view` reports a missing module and a module that
 * cannot load (a file that is not a library) in one clear line, exit status 1 or 2, never a
 * crash; without a display the module loads and says "no display". */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "support/cli_run.h"

static void expect_view_error(const char *env, const char *want1, const char *want2) {
    cj_cli_result r = cj_cli_shellf("env -u DISPLAY %s '%s' view --teapot", env, CJ_CLI);
    if (r.status != 1 && r.status != 2) fail_msg("exit status %d: %s", r.status, r.err);
    if (!strstr(r.err, want1) || (want2 && !strstr(r.err, want2)))
        fail_msg("message '%s' lacks '%s' / '%s'", r.err, want1, want2 ? want2 : "");
    if (!cj_cli_one_line(r.err)) fail_msg("more than one line: %s", r.err);
    printf("  %s -> %s", env[0] ? env : "(default)", r.err);
    cj_cli_result_free(&r);
}

static void test_view_errors(void **state) {
    (void)state;
    expect_view_error("CJ_VIEWER_PLUGIN=/nonexistent/libcasteljau_viewer.so", "CJ_VIEWER_PLUGIN",
                      "/nonexistent");
    /* a file that exists but is no library: dlopen's reason is in the message */
    cj_cli_result r =
        cj_cli_shellf("f=$(mktemp) && echo junk > \"$f\" && env -u DISPLAY "
                      "CJ_VIEWER_PLUGIN=\"$f\" '%s' view --teapot; s=$?; rm -f \"$f\"; exit $s",
                      CJ_CLI);
    if (r.status != 1 && r.status != 2) fail_msg("exit status %d: %s", r.status, r.err);
    if (!strstr(r.err, "cannot be loaded") || !strstr(r.err, "GLFW"))
        fail_msg("message: %s", r.err);
    printf("  junk module -> %s", r.err);
    cj_cli_result_free(&r);
    /* the real module, no display: it loads, and the window says why it cannot open */
    expect_view_error("", "no display", NULL);
    printf("test_viewer_module: a missing or broken viewer module and a missing display are "
           "one-line errors\n");
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_view_errors),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

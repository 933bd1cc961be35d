/* An unknown command names the nearest one when it is a slip ("rendr" -> did you mean
 * 'render'?, a swap, a cut-short name), and only then ("x", "--demo", "compile" suggest
 * nothing); always exit status 2 and one line on stderr, nothing on stdout. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "support/cli_run.h"

static void expect(const char *typed, const char *suggestion) {
    char *argv[] = {(char *)CJ_CLI, (char *)typed, NULL};
    cj_cli_result r;
    assert_int_equal(cj_cli_spawn(argv, &r), 0);
    if (r.status != 2) fail_msg("'%s': exit status %d", typed, r.status);
    if (r.out_len) fail_msg("'%s': printed on stdout: %s", typed, r.out);
    const char *nl = strchr(r.err, '\n');
    if (!nl || nl[1]) fail_msg("'%s': not one line: %s", typed, r.err);
    if (!strstr(r.err, "unknown command") || !strstr(r.err, typed))
        fail_msg("'%s': message: %s", typed, r.err);
    char want[128];
    snprintf(want, sizeof want, "did you mean '%s'?", suggestion ? suggestion : "");
    if (suggestion ? !strstr(r.err, want) : strstr(r.err, "did you mean") != NULL)
        fail_msg("'%s': expected %s, got: %s", typed, suggestion ? want : "no suggestion", r.err);
    printf("  %-8s -> %s", typed, r.err);
    cj_cli_result_free(&r);
}

static void test_unknown_commands(void **state) {
    (void)state;
    expect("rendr", "render");    /* a letter left out */
    expect("tarce", "trace");     /* two letters swapped */
    expect("plto", "plot");       /* swapped at the end */
    expect("animat", "animate");  /* cut short */
    expect("tess", "tessellate"); /* cut short, far in edits */
    expect("evall", "eval");      /* one letter too many */
    expect("x", NULL);
    expect("--demo", NULL);
    expect("compile", NULL);
    printf("test_cli_commands: unknown commands suggest the nearest command only when near\n");
}

int main(void) {
    const struct CMUnitTest tests[] = {cmocka_unit_test(test_unknown_commands)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}

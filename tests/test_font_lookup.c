/* The default font comes from fontconfig (raster/src/text.c): with fonts-dejavu-core installed
 * (scripts/setup.sh) it is DejaVuSans.ttf wherever fontconfig knows it, and it opens; CJ_FONT
 * overrides it. With a fontconfig configuration that knows no fonts, `casteljau plot` fails
 * with one line saying what to install or set, and writes nothing. */
#define _GNU_SOURCE
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>

#include "casteljau/text.h"
#include "support/cli_run.h"

static void test_default_font(void **state) {
    (void)state;
    unsetenv("CJ_FONT");
    const char *path = cj_font_find_default();
    if (!path) fail_msg("no default font: %s", cj_last_error());
    const char *base = strrchr(path, '/');
    if (!base || strcmp(base, "/DejaVuSans.ttf") != 0)
        fail_msg("fontconfig chose '%s', not DejaVuSans.ttf", path);
    cj_font *font = NULL;
    assert_int_equal(cj_font_open(NULL, &font), CJ_OK);
    double adv = 0;
    assert_int_equal(cj_font_measure(font, 14, "Hg", &adv, NULL, NULL), CJ_OK);
    assert_true(adv > 5 && adv < 40);
    cj_font_close(font);
    /* the same answer again (looked up once) */
    assert_string_equal(cj_font_find_default(), path);
    printf("test_font_lookup: fontconfig finds %s, which opens and measures\n", path);
}

static void test_no_font(void **state) {
    (void)state;
    char dir[] = "/tmp/cj_test_font_XXXXXX";
    assert_non_null(mkdtemp(dir));
    char cmd[2048];
    snprintf(cmd, sizeof cmd,
             "cd '%s' && printf '<?xml version=\"1.0\"?>\\n<fontconfig><cachedir>%s/cache"
             "</cachedir></fontconfig>\\n' > empty.conf && env -u CJ_FONT "
             "FONTCONFIG_FILE='%s/empty.conf' '%s' plot --demo --width 96 --height 64 -o g.png",
             dir, dir, dir, CJ_CLI);
    cj_cli_result r;
    assert_int_equal(cj_cli_shell(cmd, &r), 0);
    if (r.status == 0) fail_msg("plot succeeded without fonts");
    if (!strstr(r.err, "no font for text") || !strstr(r.err, "fonts-dejavu-core") ||
        !strstr(r.err, "CJ_FONT"))
        fail_msg("message: %s", r.err);
    const char *nl = strchr(r.err, '\n');
    if (nl && nl[1]) fail_msg("more than one line: %s", r.err);
    printf("  no fonts -> exit %d: %s", r.status, r.err);
    cj_cli_result_free(&r);
    char png[128];
    snprintf(png, sizeof png, "%s/g.png", dir);
    assert_int_equal(access(png, F_OK), -1);
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    assert_int_equal(system(cmd), 0);
    /* CJ_FONT naming no file: said so */
    snprintf(cmd, sizeof cmd, "CJ_FONT=/nonexistent.ttf '%s' plot --demo -o /nonexistent/x.png",
             CJ_CLI);
    assert_int_equal(cj_cli_shell(cmd, &r), 0);
    assert_true(r.status != 0);
    if (!strstr(r.err, "/nonexistent")) fail_msg("message: %s", r.err);
    cj_cli_result_free(&r);
    printf("test_font_lookup: without any font (empty fontconfig) plot fails in one line naming "
           "the package and CJ_FONT, and writes nothing\n");
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_default_font),
        cmocka_unit_test(test_no_font),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

/* Pixel comparison of two PNG files for the tests that hold a program's picture against an
 * offline one (the viewer's screenshots against `casteljau plot`, `render` or `trace`). */
#ifndef CJ_TEST_PNG_DIFF_H
#define CJ_TEST_PNG_DIFF_H

/* How many pixels of dir/a and dir/b differ in any channel; -1 when their sizes differ, -2 when
 * either cannot be read. */
long cj_test_png_differ(const char *dir, const char *a, const char *b);

#endif

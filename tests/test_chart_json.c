/* Chart panels of the plot JSON (app/chart_json.c): a chart document and a chart panel next to
 * a geometry panel parse and render (a marker at the pixel cj_chart_map gives, checked against
 * the documented log mapping), and bad fields are refused naming their JSON path. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "plot_json.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

static void test_chart_document(void **state) {
    (void)state;
    const char *doc_text =
        "{\"kind\": \"chart\", \"width\": 400, \"height\": 300, \"title\": \"t\","
        " \"x\": {\"scale\": \"log\", \"title\": \"ns\", \"range\": [1, 1000]},"
        " \"y\": {\"scale\": \"log\"}, \"legend\": \"outside\","
        " \"series\": [{\"label\": \"a\", \"points\": [[10, 1e-3], [100, 1e-1]],"
        "   \"color\": \"#ff0000\", \"marker\": \"square\", \"marker_radius\": 6, \"line_width\": "
        "0}],"
        " \"annotations\": [{\"at\": [10, 1e-3], \"text\": \"cheap\"}]}";
    cj_plot_doc doc;
    assert_int_equal(cj_plot_json_parse("chart.json", doc_text, &doc), 0);
    assert_int_equal((int)doc.npanels, 1);
    assert_non_null(doc.charts[0]);
    assert_null(doc.panels[0]);
    cj_framebuffer *fb = NULL;
    assert_int_equal(cj_framebuffer_create(doc.width, doc.height, 0, NULL, &fb), CJ_OK);
    assert_int_equal(cj_plot_doc_render(&doc, fb, NULL), CJ_OK);
    /* without a font: plot area [12, 388] x [12, 288]; x log over [1, 1000], y whole decades
     * [1e-3, 1e-1] */
    const double px = 12 + (1.0 / 3) * 376, py = 12 + 1.0 * 276;
    double mx, my;
    assert_int_equal(cj_chart_map(doc.charts[0], 400, 300, 0, 100, 1e-1, &mx, &my), CJ_OK);
    assert_true(fabs(mx - 12 - 2.0 / 3 * 376) < 1e-9 && fabs(my - py) < 1e-9);
    const cj_rgba m =
        fb->pixels[(ptrdiff_t)floor(12.0 + 3) * fb->stride + (ptrdiff_t)floor(px + 3)];
    assert_true(m.r > 200 && m.g < 60 && m.b < 60); /* inside the 6 px square at (10, 1e-3) */
    printf("chart document: square marker at the documented log position\n");
    cj_framebuffer_destroy(fb);
    cj_plot_doc_free(&doc);
}

static void test_chart_panel_and_errors(void **state) {
    (void)state;
    cj_plot_doc doc;
    const char *mixed = "{\"panels\": [{\"items\": [{\"type\": \"points\", \"points\": [[0,0]]}]},"
                        " {\"kind\": \"chart\", \"series\": [{\"points\": [[1, 2], [3, 4]]}]}]}";
    assert_int_equal(cj_plot_json_parse("chart.json", mixed, &doc), 0);
    assert_int_equal((int)doc.npanels, 2);
    assert_non_null(doc.panels[0]);
    assert_non_null(doc.charts[1]);
    cj_plot_doc_free(&doc);
    static const struct {
        const char *text, *expect;
    } bad[] = {
        {"{\"kind\": \"chart\", \"series\": []}", "document.series is not an array"},
        {"{\"kind\": \"chart\", \"series\": [{\"points\": [[1, 2]], \"marker\": \"star\"}]}",
         "document.series[0].marker \"star\" is not one of"},
        {"{\"kind\": \"chart\", \"x\": {\"scale\": \"log\"}, \"series\": [{\"points\": [[0, 2]]}]}",
         "series 0 point 0 has x = 0"},
        {"{\"kind\": \"chart\", \"series\": [{\"points\": [[1, 2]]}], \"bogus\": 1}",
         "document.bogus is not a known key"},
        {"{\"panels\": [{\"kind\": \"chart\", \"series\": [{\"points\": [[1, 2]]}],"
         " \"annotations\": [{\"at\": [1, 2]}]}]}",
         "panels[0].annotations[0] has no text"},
        {"{\"kind\": \"chart\", \"y\": {\"range\": [2, 1]}, \"series\": [{\"points\": [[1, 2]]}]}",
         "document.y.range"},
        {"{\"kind\": \"chart\", \"series\": [{\"points\": [[1, 2]], \"line_width\": 0,"
         " \"marker\": \"none\"}]}",
         "nothing to draw"},
        {"{\"kind\": \"chart\", \"legend\": \"middle\", \"series\": [{\"points\": [[1, 2]]}]}",
         "document.legend \"middle\" is not one of"},
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; ++i) {
        assert_int_not_equal(cj_plot_json_parse("chart.json", bad[i].text, &doc), CJ_OK);
        const char *why = cj_last_error();
        if (!strstr(why, bad[i].expect) || strncmp(why, "chart.json:", 11))
            fail_msg("case %zu: '%s' lacks '%s'", i, why, bad[i].expect);
    }
    printf("chart panel next to a geometry panel; %zu bad documents refused with their JSON path\n",
           sizeof bad / sizeof bad[0]);
}

int main(void) {
    const struct CMUnitTest tests[] = {cmocka_unit_test(test_chart_document),
                                       cmocka_unit_test(test_chart_panel_and_errors)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}

/* The JSON plot format of `casteljau plot` (app/plot_json.c), in-process: every kind of bad
 * field is refused with a message naming its JSON path and nothing allocated; good documents
 * produce the expected panels and render. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "plot_json.h"

#include <stdio.h>
#include <string.h>

typedef struct bad_case {
    const char *json;
    const char *expect; /* substring of the message */
} bad_case;

static const bad_case bad_cases[] = {
    {"{\"items\": [", "bad.json:1:12: JSON syntax error (line 1, column 12)"},
    {"{\n  \"items\": [\n    {\"type\": \"bezier\" \"points\": []}\n  ]\n}",
     "bad.json:3:23: JSON syntax error (line 3,"},
    {"[1, 2]", "document is not a JSON object"},
    {"{}", "missing \"items\""},
    {"{\"items\": []}", "items is not a non-empty array"},
    {"{\"items\": [3]}", "items[0] is not an object"},
    {"{\"items\": [{\"type\": \"bezier\", \"points\": [[0,0],[1,1]]},"
     " {\"type\": \"bezier\", \"points\": [[0,0],[1,1],[2,0],[3]]}]}",
     "bad.json:1: items[1].points[3] must be an array of 2 numbers, not 1"},
    {"{\"items\": [{\"type\": \"bezier\", \"points\": [[0,0],[1,\"a\"]]}]}",
     "items[0].points[1][1] must be a number, not a string"},
    {"{\"items\": [{\"type\": \"bezier\", \"points\": {\"x\": 1}}]}",
     "items[0].points must be an array, not an object"},
    {"{\"items\": [{\"type\": \"bezier\", \"points\": []}]}", "items[0].points must not be empty"},
    {"{\"items\": [{\"type\": \"bezier\", \"points\": [[0,0],[1,1e999]]}]}",
     "items[0].points[1][1] is not finite"},
    {"{\"items\": [{\"type\": \"bezier\"}]}", "items[0]: a bezier needs \"points\""},
    {"{\"items\": [{\"type\": \"bezier\", \"colour\": \"#fff\", \"points\": [[0,0],[1,1]]}]}",
     "items[0].colour is not a known key (expected one of: type, points"},
    {"{\"items\": [{\"type\": \"bezier\", \"color\": \"bleu\", \"points\": [[0,0],[1,1]]}]}",
     "items[0].color is not a colour"},
    {"{\"items\": [{\"type\": \"bezier\", \"color\": \"#12345\", \"points\": [[0,0],[1,1]]}]}",
     "items[0].color is not a colour"},
    {"{\"items\": [{\"type\": \"bezier\", \"width\": \"2\", \"points\": [[0,0],[1,1]]}]}",
     "items[0].width must be a number, not a string"},
    {"{\"items\": [{\"type\": \"bezier\", \"hull\": 1, \"points\": [[0,0],[1,1]]}]}",
     "items[0].hull must be true or false, not a number"},
    {"{\"items\": [{\"type\": \"bezier\", \"construction_t\": 1.5, \"points\": [[0,0],[1,1]]}]}",
     "items[0].construction_t must be in [0, 1], not 1.5"},
    {"{\"items\": [{\"type\": \"bezier\", \"frames_t\": [0.5, -1], \"points\": [[0,0],[1,1]]}]}",
     "items[0].frames_t[1] must be in [0, 1], not -1"},
    {"{\"items\": [{\"type\": \"bezier\", \"points\": [[0,0],[1,1]], \"weights\": [1]}]}",
     "items[0].weights is not an array of 2 weights (one per point)"},
    {"{\"items\": [{\"type\": \"bezier\", \"points\": [[0,0],[1,1]], \"weights\": [1, 0]}]}",
     "items[0].weights[1] must be > 0, not 0"},
    {"{\"items\": [{\"type\": \"bezier\", \"points\": [[0,0],[1,1]], \"weights\": [1, \"x\"]}]}",
     "items[0].weights[1] must be a number, not a string"},
    {"{\"items\": [{\"type\": \"spline\", \"points\": [[0,0],[1,1]]}]}",
     "items[0].type 'spline' is not"},
    {"{\"items\": [{\"points\": [[0,0],[1,1]]}]}", "items[0].type is missing"},
    {"{\"items\": [{\"type\": \"implicit\", \"line\": [1, 1, 0]}]}",
     "items[0]: a \"line\" needs a \"box\""},
    {"{\"items\": [{\"type\": \"implicit\"}]}", "items[0]: an implicit item needs one of"},
    {"{\"items\": [{\"type\": \"implicit\", \"circle\": [0, 0, 1], \"ellipse\": [0,0,1,1,0]}]}",
     "items[0] has both \"circle\" and \"ellipse\""},
    {"{\"items\": [{\"type\": \"implicit\", \"circle\": [0, 0]}]}",
     "items[0].circle must be an array of 3 numbers, not 2"},
    {"{\"items\": [{\"type\": \"implicit\", \"circle\": [0, 0, -1]}]}",
     "items[0].circle: the radius -1 is not positive"},
    {"{\"items\": [{\"type\": \"implicit\", \"circle\": [0, 0, 1], \"box\": [1, 0, 0, 1]}]}",
     "items[0].box is not [x0, y0, x1, y1]"},
    {"{\"items\": [{\"type\": \"implicit\", \"circle\": [9, 9, 1], \"box\": [0,0,1,1]}]}",
     "items[0]: the implicit curve has no point in the box"},
    {"{\"items\": [{\"type\": \"implicit\", \"poly\": {\"degree\": 2, \"coef\": [1,2,3]},"
     " \"box\": [0,0,1,1]}]}",
     "items[0].poly.coef is not an array of 6 numbers (degree 2)"},
    {"{\"items\": [{\"type\": \"implicit\", \"poly\": {\"degree\": 2.5, \"coef\": []},"
     " \"box\": [0,0,1,1]}]}",
     "items[0].poly.degree must be an integer, not 2.5"},
    {"{\"items\": [{\"type\": \"catmull-rom\", \"kind\": \"centripetal\","
     " \"points\": [[0,0],[1,1],[1,1],[2,0]]}]}",
     "items[0]: "},
    {"{\"items\": [{\"type\": \"catmull-rom\", \"kind\": \"cubic\", \"points\": [[0,0],[1,1]]}]}",
     "items[0].kind \"cubic\" is not one of uniform, centripetal, chordal"},
    {"{\"items\": [{\"type\": \"catmull-rom\", \"closed\": true, \"points\": [[0,0],[1,1]]}]}",
     "items[0].points has 2 points, at least 3 needed"},
    {"{\"items\": [{\"type\": \"polyline\", \"points\": [[0,0]]}]}",
     "items[0].points has 1 point, at least 2 needed"},
    {"{\"width\": 10, \"items\": [{\"type\": \"points\", \"points\": [[0,0]]}]}",
     "width must be in [64, 8192], not 10"},
    {"{\"height\": 100.5, \"items\": [{\"type\": \"points\", \"points\": [[0,0]]}]}",
     "height must be an integer, not 100.5"},
    {"{\"view\": [0, 0, 0, 1], \"items\": [{\"type\": \"points\", \"points\": [[0,0]]}]}",
     "view: "},
    {"{\"panels\": [{\"items\": [{\"type\": \"points\", \"points\": [[0,0],[1,1]]}]},"
     " {\"title\": \"x\"}]}",
     "panels[1]: missing \"items\""},
    {"{\"panels\": [{\"items\": [{\"type\": \"points\", \"points\": [[0,0],[1,1]],"
     " \"radius\": 0}]}]}",
     "panels[0].items[0].radius must be in [0.1, "},
    {"{\"panels\": [{\"items\": [{\"type\": \"points\", \"points\": [[0,0]]}],"
     " \"width\": 3}]}",
     "panels[0].width is not a known key"},
    {"{\"panels\": [], \"columns\": 1}", "panels is not an array of 1 to 64 panels"},
    {"{\"items\": [{\"type\": \"points\", \"points\": [[0,0]]}], \"panels\": []}",
     "document.items is not a known key"},
};

static void test_bad_documents(void **state) {
    (void)state;
    const size_t n = sizeof bad_cases / sizeof bad_cases[0];
    for (size_t i = 0; i < n; ++i) {
        cj_plot_doc doc;
        const cj_status rc = cj_plot_json_parse("bad.json", bad_cases[i].json, &doc);
        const char *why = rc ? cj_last_error() : "";
        /* every message names the document and the line of the bad value */
        int line = 0;
        if (rc == CJ_OK || !strstr(why, bad_cases[i].expect) || strchr(why, '\n') ||
            sscanf(why, "bad.json:%d:", &line) != 1 || line < 1) {
            printf("case %zu: rc %d, message '%s', expected '%s'\n", i, rc, why,
                   bad_cases[i].expect);
            fail();
        }
        assert_int_equal(doc.npanels, 0);
    }
    printf("test_plot_json: %zu bad documents refused, each message naming the document, the line "
           "and the JSON path\n",
           n);
}

/* The status of a refusal is the kit's own, kept up to the entry points (a value out of range is
 * CJ_ERR_RANGE, not infinite CJ_ERR_NONFINITE, a wrong type CJ_ERR_PARSE), deep in panels,
 * charts, curve items and pages alike. */
static void test_statuses(void **state) {
    (void)state;
    static const struct {
        const char *json;
        cj_status status;
    } cases[] = {
        {"{\"width\": 10, \"items\": [{\"type\": \"points\", \"points\": [[0,0]]}]}", CJ_ERR_RANGE},
        {"{\"width\": \"9\", \"items\": [{\"type\": \"points\", \"points\": [[0,0]]}]}",
         CJ_ERR_PARSE},
        {"{\"items\": [{\"type\": \"bezier\", \"points\": [[0,0],[1,1]], \"weights\": [1, 0]}]}",
         CJ_ERR_RANGE},
        {"{\"items\": [{\"type\": \"bezier\", \"points\": [[0,0],[1,1e999]]}]}", CJ_ERR_NONFINITE},
        {"{\"items\": [{\"type\": \"bezier\", \"construction_t\": 1.5, \"points\": "
         "[[0,0],[1,1]]}]}",
         CJ_ERR_RANGE},
        {"{\"panels\": [{\"items\": [{\"type\": \"points\", \"points\": [[0,0],[1,1]],"
         " \"radius\": 0}]}]}",
         CJ_ERR_RANGE},
        {"{\"panels\": [{\"items\": [{\"type\": \"implicit\", \"poly\": {\"degree\": 40, "
         "\"coef\": []}, \"box\": [0,0,1,1]}]}]}",
         CJ_ERR_RANGE},
        {"{\"kind\": \"chart\", \"series\": [{\"points\": [[0,1]], \"line_width\": 20}]}",
         CJ_ERR_RANGE},
        {"{\"items\": [{\"type\": \"catmull-rom\", \"tension\": 11, \"points\": [[0,0],[1,1]]}]}",
         CJ_ERR_RANGE},
        {"{\"items\": [{\"type\": \"polyline\", \"points\": [[0,0]]}]}", CJ_ERR_PARSE},
    };
    const size_t n = sizeof cases / sizeof cases[0];
    for (size_t i = 0; i < n; ++i) {
        cj_plot_doc doc;
        const cj_status rc = cj_plot_json_parse("st.json", cases[i].json, &doc);
        if (rc != cases[i].status) {
            printf("case %zu: status %d, expected %d (%s)\n", i, rc, cases[i].status,
                   rc ? cj_last_error() : "accepted");
            fail();
        }
        if (!rc) cj_plot_doc_free(&doc);
    }
    /* a page reads its items with the same readers */
    cj_plot_json_page page;
    assert_int_equal(cj_plot_json_read_page("p.json",
                                            "{\"margin\": -1, \"items\": [{\"type\": "
                                            "\"bezier\", \"points\": [[0,0],[1,1]]}]}",
                                            &page),
                     CJ_ERR_RANGE);
    assert_int_equal(cj_plot_json_read_page("p.json",
                                            "{\"items\": [{\"type\": \"bezier\", \"width\": 99, "
                                            "\"points\": [[0,0],[1,1]]}]}",
                                            &page),
                     CJ_ERR_RANGE);
    printf("test_plot_json: %zu documents and 2 pages refused with the kit's own status (range, "
           "not finite, type)\n",
           n);
}

/* Colours by name (CSS basic names, any case) as well as "#rrggbb". */
static void test_named_colours(void **state) {
    (void)state;
    static const struct {
        const char *name;
        uint8_t r, g, b, a;
    } cases[] = {{"red", 255, 0, 0, 255},
                 {"Navy", 0, 0, 128, 255},
                 {"GREY", 128, 128, 128, 255},
                 {"orange", 255, 165, 0, 255},
                 {"transparent", 0, 0, 0, 0}};
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        char json[256];
        snprintf(json, sizeof json,
                 "{\"background\": \"%s\", \"items\": [{\"type\": \"points\", "
                 "\"points\": [[0,0],[1,1]]}]}",
                 cases[i].name);
        cj_plot_doc doc;
        assert_int_equal(cj_plot_json_parse("good.json", json, &doc), 0);
        assert_int_equal(doc.background.r, cases[i].r);
        assert_int_equal(doc.background.g, cases[i].g);
        assert_int_equal(doc.background.b, cases[i].b);
        assert_int_equal(doc.background.a, cases[i].a);
        cj_plot_doc_free(&doc);
    }
    printf("test_plot_json: named colours (red, Navy, GREY, orange, transparent) give their "
           "CSS values; 'bleu' is refused naming the accepted forms\n");
}

static void test_good_documents(void **state) {
    (void)state;
    const char *single =
        "{\"width\": 300, \"height\": 200, \"background\": \"#fafafa\", \"title\": \"t\","
        " \"axes\": false, \"margin\": 4, \"items\": ["
        " {\"type\": \"bezier\", \"points\": [[0,0],[1,2],[2,0]], \"weights\": [1, 2, 1],"
        "  \"construction_t\": 0.4, \"frames_t\": [0.5]},"
        " {\"type\": \"bezier\", \"points\": [[0,0],[1,2],[2,0]], \"hull\": true,"
        "  \"construction_t\": 0.5, \"frames_t\": [0, 1], \"normals\": false},"
        " {\"type\": \"catmull-rom\", \"points\": [[0,0],[1,1],[2,0]], \"closed\": true,"
        "  \"tension\": 0.3, \"knots\": false, \"color\": \"#abc\"},"
        " {\"type\": \"implicit\", \"ellipse\": [1, 0, 1, 0.5, 0.3], \"grid\": 16},"
        " {\"type\": \"implicit\", \"poly\": {\"degree\": 2, \"coef\": [-1, 0, 0, 1, 0, 1]},"
        "  \"box\": [-2, -2, 2, 2], \"color\": \"#11223380\"},"
        " {\"type\": \"implicit\", \"line\": [1, -1, 0], \"box\": [-1, -1, 1, 1]},"
        " {\"type\": \"polyline\", \"points\": [[0,0],[1,1]], \"closed\": true, \"markers\": "
        "true},"
        " {\"type\": \"points\", \"points\": [[0.5, 0.5]], \"radius\": 3}]}";
    cj_plot_doc doc;
    assert_int_equal(cj_plot_json_parse("good.json", single, &doc), 0);
    assert_int_equal(doc.width, 300);
    assert_int_equal(doc.height, 200);
    assert_int_equal(doc.npanels, 1);
    assert_int_equal(cj_plot_item_count(doc.panels[0]), 8);
    assert_int_equal(doc.background.r, 0xfa);
    cj_framebuffer *fb = NULL;
    assert_int_equal(cj_framebuffer_create(doc.width, doc.height, 0, NULL, &fb), CJ_OK);
    assert_int_equal(cj_plot_doc_render(&doc, fb, NULL), CJ_OK);
    assert_int_equal(fb->pixels[0].r, 0xfa); /* corner: background */
    cj_framebuffer_destroy(fb);
    cj_plot_doc_free(&doc);

    const char *multi = "{\"columns\": 3, \"panels\": ["
                        " {\"items\": [{\"type\": \"points\", \"points\": [[0,0],[1,1]]}]},"
                        " {\"items\": [{\"type\": \"points\", \"points\": [[0,0],[1,1]]}]},"
                        " {\"items\": [{\"type\": \"points\", \"points\": [[0,0],[1,1]]}]},"
                        " {\"items\": [{\"type\": \"points\", \"points\": [[0,0],[1,1]]}]}]}";
    assert_int_equal(cj_plot_json_parse("good.json", multi, &doc), 0);
    assert_int_equal(doc.npanels, 4);
    assert_int_equal(doc.columns, 3);
    assert_int_equal(doc.width, 800);
    assert_int_equal(doc.height, 600);
    cj_plot_doc_free(&doc);
    printf("test_plot_json: every item kind and option accepted; single and multi-panel "
           "documents parse and render\n");
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_bad_documents),
        cmocka_unit_test(test_good_documents),
        cmocka_unit_test(test_named_colours),
        cmocka_unit_test(test_statuses),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

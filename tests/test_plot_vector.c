/* `casteljau plot -o x.svg | x.pdf` (issue 25): the SVG is XML whose root is an <svg> of the
 * PNG's size in px, drawing with paths and glyphs only (geometry and chart panels); the PDF,
 * rendered back by poppler's pdftoppm at 72 dpi (one point per pixel), is close to the PNG of the
 * same plot pixel for pixel. */
#define _POSIX_C_SOURCE 200809L /* mkdtemp */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "cli_run.h"
#include "casteljau/image_io.h"

#include <expat.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static char dir[256];

static void run(const char *args, int want_status, cj_cli_result *r) {
    char cmd[2048];
    snprintf(cmd, sizeof cmd, "cd %s && %s %s", dir, CJ_CLI, args);
    assert_int_equal(cj_cli_shell(cmd, r), 0);
    if (r->status != want_status)
        fail_msg("'%s': status %d (want %d), stderr: %s", args, r->status, want_status, r->err);
}

typedef struct svg_count {
    int depth, root_ok, paths, uses, symbols, images, others;
    char width[32], height[32];
} svg_count;

static void XMLCALL on_start(void *user, const XML_Char *name, const XML_Char **attrs) {
    svg_count *c = user;
    if (c->depth++ == 0) {
        c->root_ok = !strcmp(name, "svg");
        for (int i = 0; attrs[i]; i += 2) {
            if (!strcmp(attrs[i], "width")) snprintf(c->width, sizeof c->width, "%s", attrs[i + 1]);
            if (!strcmp(attrs[i], "height"))
                snprintf(c->height, sizeof c->height, "%s", attrs[i + 1]);
        }
        return;
    }
    if (!strcmp(name, "path"))
        ++c->paths;
    else if (!strcmp(name, "use"))
        ++c->uses;
    else if (!strcmp(name, "symbol"))
        ++c->symbols;
    else if (!strcmp(name, "image"))
        ++c->images;
    else
        ++c->others;
}

static void XMLCALL on_end(void *user, const XML_Char *name) {
    (void)name;
    --((svg_count *)user)->depth;
}

static void parse_svg(const char *name, svg_count *c) {
    char p[512];
    snprintf(p, sizeof p, "%s/%s", dir, name);
    FILE *f = fopen(p, "rb");
    assert_non_null(f);
    memset(c, 0, sizeof *c);
    XML_Parser x = XML_ParserCreate(NULL);
    XML_SetUserData(x, c);
    XML_SetElementHandler(x, on_start, on_end);
    char buf[65536];
    size_t n;
    int ok = 1;
    do {
        n = fread(buf, 1, sizeof buf, f);
        ok = XML_Parse(x, buf, (int)n, n == 0) != XML_STATUS_ERROR;
        if (!ok)
            fail_msg("%s is not well-formed XML: %s at line %lu", name,
                     XML_ErrorString(XML_GetErrorCode(x)),
                     (unsigned long)XML_GetCurrentLineNumber(x));
    } while (n > 0);
    XML_ParserFree(x);
    fclose(f);
    assert_int_equal(c->depth, 0);
}

static void test_svg(void **state) {
    (void)state;
    cj_cli_result r;
    run("plot --demo -o demo.svg", 0, &r);
    assert_non_null(strstr(r.out, "wrote demo.svg (1500 x 900)"));
    cj_cli_result_free(&r);
    svg_count c;
    parse_svg("demo.svg", &c);
    printf("demo.svg: <svg width=\"%s\" height=\"%s\">, %d paths, %d glyph symbols, %d glyph "
           "uses, %d images\n",
           c.width, c.height, c.paths, c.symbols, c.uses, c.images);
    assert_true(c.root_ok);
    assert_string_equal(c.width, "1500px");
    assert_string_equal(c.height, "900px");
    /* six panels: each has a frame, grid lines, ticks, curves and markers as paths */
    assert_true(c.paths > 300);
    /* text as glyphs: the six titles alone have more than 150 characters */
    assert_true(c.symbols > 20 && c.uses > 150);
    assert_int_equal(c.images, 0);

    /* a chart panel next to a geometry panel: both drawn as vectors */
    char p[512];
    snprintf(p, sizeof p, "%s/mixed.json", dir);
    FILE *f = fopen(p, "w");
    assert_non_null(f);
    fputs("{\"width\": 600, \"height\": 300, \"columns\": 2, \"panels\": [{\"items\": [{\"type\": "
          "\"bezier\", \"points\": [[0,0],[1,2],[2,0]]}]}, {\"kind\": \"chart\", \"series\": "
          "[{\"points\": [[1, 2], [3, 4]]}]}]}",
          f);
    fclose(f);
    run("plot mixed.json -o mixed.svg", 0, &r);
    cj_cli_result_free(&r);
    parse_svg("mixed.svg", &c);
    printf("mixed.svg: %d paths, %d glyph uses, %d images\n", c.paths, c.uses, c.images);
    assert_int_equal(c.images, 0);
    assert_true(c.paths > 40 && c.uses > 10);
    /* a directory that does not exist: refused before any work, nothing written */
    run("plot --demo -o no/such/dir/x.svg", 1, &r);
    printf("missing directory: %s", r.err);
    assert_non_null(strstr(r.err, "no/such/dir/x.svg"));
    cj_cli_result_free(&r);
}

/* Writes `stem`.pdf and `stem`.png from the same plot arguments, renders the PDF back with
 * pdftoppm and compares the two pictures. */
static void compare_pdf_png(const char *input, const char *stem) {
    cj_cli_result r;
    char args[512];
    snprintf(args, sizeof args, "plot %s -o %s.pdf", input, stem);
    run(args, 0, &r);
    cj_cli_result_free(&r);
    snprintf(args, sizeof args, "plot %s -o %s.png", input, stem);
    run(args, 0, &r);
    cj_cli_result_free(&r);
    char p[512], head[6] = {0};
    snprintf(p, sizeof p, "%s/%s.pdf", dir, stem);
    FILE *f = fopen(p, "rb");
    assert_non_null(f);
    assert_int_equal(fread(head, 1, 5, f), 5);
    fclose(f);
    assert_string_equal(head, "%PDF-");
    char cmd[700];
    snprintf(cmd, sizeof cmd, "cd %s && pdftoppm -r 72 -singlefile %s.pdf %s_pdf", dir, stem, stem);
    assert_int_equal(cj_cli_shell(cmd, &r), 0);
    if (r.status != 0) fail_msg("pdftoppm failed: %s", r.err);
    cj_cli_result_free(&r);
    int w1, h1, w2, h2;
    uint8_t *a = NULL, *b = NULL;
    snprintf(p, sizeof p, "%s/%s_pdf.ppm", dir, stem);
    assert_int_equal(cj_image_read(p, &w1, &h1, &a), 0);
    snprintf(p, sizeof p, "%s/%s.png", dir, stem);
    assert_int_equal(cj_image_read(p, &w2, &h2, &b), 0);
    assert_int_equal(w1, w2);
    assert_int_equal(h1, h2);
    /* Pixel for pixel, then as ink per 20 x 20 block (blocks every 10 pixels): the
     * rasterizers differ in where they put a one-pixel line on a pixel boundary (ours spreads
     * it over two rows, poppler snaps it to one) and in sub-pixel text positions (ours rounds
     * the pen), which moves ink by a pixel but keeps it in its block; a layout difference changes
     * whole blocks (the PNG against itself moved by 1, 3, 5 pixels: 8.6, 21.8, 24.6 levels). */
    double sum = 0, worst_block = 0;
    int wbx = 0, wby = 0;
    for (size_t i = 0; i < (size_t)w1 * h1; ++i)
        for (int k = 0; k < 3; ++k) sum += abs(a[4 * i + k] - b[4 * i + k]);
    for (int by = 0; by + 20 <= h1; by += 10)
        for (int bx = 0; bx + 20 <= w1; bx += 10) {
            long ink = 0;
            for (int y = by; y < by + 20; ++y)
                for (int x = bx; x < bx + 20; ++x)
                    for (int k = 0; k < 3; ++k) {
                        const size_t i = 4 * ((size_t)y * w1 + x) + k;
                        ink += a[i] - b[i];
                    }
            const double d = labs(ink) / 1200.0;
            if (d > worst_block) worst_block = d, wbx = bx, wby = by;
        }
    printf("%s.pdf rendered at 72 dpi vs %s.png (%d x %d): mean |difference| %.2f levels "
           "per sample; ink of 20x20 blocks differs by at most %.2f levels (at %d, %d from the "
           "bottom left)\n",
           stem, stem, w1, h1, sum / (3.0 * w1 * h1), worst_block, wbx, wby);
    assert_true(sum / (3.0 * w1 * h1) < 3.5);
    assert_true(worst_block < 10.0);
    cj_image_free(a);
    cj_image_free(b);
}

static void test_pdf_matches_png(void **state) {
    (void)state;
    compare_pdf_png("--demo", "demo");
    compare_pdf_png("mixed.json", "mixed"); /* written by test_svg: a chart panel too */
}

int main(void) {
    snprintf(dir, sizeof dir, "/tmp/cj_plot_vector_XXXXXX");
    if (!mkdtemp(dir)) return 1;
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_svg),
        cmocka_unit_test(test_pdf_matches_png),
    };
    const int rc = cmocka_run_group_tests(tests, NULL, NULL);
    char cmd[300];
    snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
    if (system(cmd) != 0) return 1;
    return rc;
}

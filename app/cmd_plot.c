/* casteljau plot: render a JSON plot description (or the built-in gallery) to an image.
 *
 *   casteljau plot FILE.json -o OUT.png [--width W] [--height H]
 *   casteljau plot --demo -o OUT.png [--width W] [--height H]
 *
 * Contract: bad arguments or a bad document print one line on stderr naming what is wrong
 * (for the document: the file and the JSON path of the field), nothing on stdout, exit status
 * 2, and no output file (the destination is checked before any work, and the image is written
 * to a temporary file renamed into place only when complete). A missing font or a failed write
 * (a full disk) exits with status 1, leaving an existing file untouched. Success prints one
 * line "wrote OUT.png (W x H)" on stdout. Builds without OpenImageIO report that plot is
 * unavailable (status 2). */
#include "cli.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char plot_usage[] =
    "usage: casteljau plot FILE.json -o OUT.png [--width W] [--height H]\n"
    "       casteljau plot --demo -o OUT.png [--width W] [--height H]\n"
    "Renders a plot described in JSON ('-' reads standard input; the format is in\n"
    "  " CJ_DOC_DIR "/README.md) or the built-in gallery (--demo).\n"
    "  -o, --output  the image; its extension chooses the format, through OpenImageIO:\n"
    "                .png, .jpg/.jpeg (no alpha: composited over black), .tif, .exr, .bmp, ...\n"
    "                or vector graphics with the same layout, drawn by cairo: .svg, .pdf\n"
    "  --width, --height  image size in pixels, 64..8192 (default: the document's, else\n"
    "                800 x 600; the demo is 1500 x 900)\n"
    "Options may come in any order, as --opt value or --opt=value.\n"
    "Colours: \"#rgb\", \"#rrggbb\", \"#rrggbbaa\" or a CSS name (\"red\", \"navy\", \"grey\",\n"
    "\"orange\", \"transparent\", ...; any case).\n"
    "Limits per document: 64 MiB of JSON, 64 panels, 10000 items, 1000000 points, titles of\n"
    "1024 bytes, implicit curves of 2e9 (grid+1)^2 x terms in all.\n"
    "Output: the image file, written atomically (complete or not at all), and one line\n"
    "'wrote OUT (W x H)' on stdout. Exit status 0; 2 for a bad argument, document or\n"
    "destination (one line on stderr naming the file and JSON path); 1 when the font is\n"
    "missing, memory runs out or the write fails (an existing file is kept).\n";

#ifndef CJ_HAVE_PLOT

int cmd_plot(int argc, char **argv) {
    for (int i = 1; i < argc; ++i)
        if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
            fputs(plot_usage, stdout);
            return 0;
        }
    return cli_fail("plot", "this build has no image output: reconfigure with "
                            "-DCJ_WITH_OIIO=ON (needs libopenimageio-dev)");
}

#else

#include "plot_json.h"
#include "plot_vector.h"

#include "casteljau/image_io.h"
#include "casteljau/text.h"
#include "cli_guard.h"
#include "file_internal.h"

/* The gallery: the same JSON format users write, so the demo also exercises the parser. */
static const char demo_json[] =
    "{\"width\": 1500, \"height\": 900, \"columns\": 3, \"panels\": ["
    /* 1: a cubic with its de Casteljau construction (seed figure 12) and a Frenet frame. */
    "{\"title\": \"Cubic B\xc3\xa9zier, de Casteljau at t = 0.25\","
    " \"items\": [{\"type\": \"bezier\", \"points\": [[0,0],[1,2.4],[3.2,2.6],[4,0.2]],"
    "  \"construction_t\": 0.25, \"frames_t\": [0.7]}]},"
    /* 2: Catmull-Rom through points, uniform and centripetal, with the knots. */
    "{\"title\": \"Catmull-Rom: uniform and centripetal\","
    " \"items\": ["
    "  {\"type\": \"catmull-rom\", \"kind\": \"uniform\", \"tension\": 0.5, \"color\": \"#1f77b4\","
    "   \"points\": [[0,0],[1,1.6],[1.4,1.7],[3,0.2],[4,1.8],[5.2,1.2],[6,2.4]]},"
    "  {\"type\": \"catmull-rom\", \"kind\": \"centripetal\", \"color\": \"#ff7f0e\","
    "   \"width\": 1.75, \"knots\": false,"
    "   \"points\": [[0,0],[1,1.6],[1.4,1.7],[3,0.2],[4,1.8],[5.2,1.2],[6,2.4]]}]},"
    /* 3: a degree-10 curve inside the convex hull of its control points. */
    "{\"title\": \"Degree 10 inside its convex hull\","
    " \"items\": [{\"type\": \"bezier\", \"color\": \"#2ca02c\", \"hull\": true,"
    "  \"points\": [[0,0],[0.6,2.2],[1.5,-0.6],[2.1,2.8],[3,1.1],[3.6,3.1],[4.4,-0.4],"
    "              [5,2.2],[5.7,0.3],[6.3,2.6],[7,1]]}]},"
    /* 4: implicit curves contoured to polylines. */
    "{\"title\": \"Implicit: lemniscate, circle, ellipse\","
    " \"items\": ["
    "  {\"type\": \"implicit\", \"color\": \"#d62728\", \"box\": [-1.6,-1,1.6,1],"
    "   \"poly\": {\"degree\": 4, \"coef\": [0, 0,0, -2,0,2, 0,0,0,0, 1,0,2,0,1]}},"
    "  {\"type\": \"implicit\", \"color\": \"#1f77b4\", \"circle\": [0, 0, 1.2]},"
    "  {\"type\": \"implicit\", \"color\": \"#9467bd\", \"ellipse\": [0, 0, 1.55, 0.65, 0.35]}]},"
    /* 5: rational quadratics: the exact quarter circle (weights 1, cos 45°, 1) and others. */
    "{\"title\": \"Rational quadratics: w\xe2\x82\x81 = 0.5, cos 45\xc2\xb0, 2\","
    " \"view\": [-0.12, -0.12, 1.12, 1.12], \"items\": ["
    "  {\"type\": \"implicit\", \"color\": \"#c8c8c8\", \"width\": 1, \"circle\": [0, 0, 1]},"
    "  {\"type\": \"bezier\", \"color\": \"#ff7f0e\", \"width\": 2,"
    "   \"control_polygon\": false, \"control_points\": false,"
    "   \"points\": [[1,0],[1,1],[0,1]], \"weights\": [1, 0.5, 1]},"
    "  {\"type\": \"bezier\", \"color\": \"#2ca02c\", \"width\": 2,"
    "   \"control_polygon\": false, \"control_points\": false,"
    "   \"points\": [[1,0],[1,1],[0,1]], \"weights\": [1, 2, 1]},"
    "  {\"type\": \"bezier\", \"color\": \"#1f77b4\", \"construction_t\": 0.5,"
    "   \"points\": [[1,0],[1,1],[0,1]], \"weights\": [1, 0.70710678118654757, 1]}]},"
    /* 6: unit tangents and (left) normals along an S-shaped cubic with an inflection. */
    "{\"title\": \"Tangents and normals along an S-curve\","
    " \"items\": [{\"type\": \"bezier\", \"color\": \"#8c564b\","
    "  \"points\": [[0,0],[1.4,2.2],[1.6,-1.2],[3,1]],"
    "  \"frames_t\": [0.1, 0.3, 0.5, 0.7, 0.9]}]}"
    "]}";

static char *read_file(const char *path, char *why, size_t why_size) {
    char *text = NULL;
    size_t len = 0;
    if (cj_file_read_input(path, PLOT_JSON_MAX_BYTES, "plot document", &text, &len)) {
        snprintf(why, why_size, "%s", cj_last_error());
        return NULL;
    }
    if (strlen(text) != len) {
        snprintf(why, why_size, "'%s' contains a NUL byte: not a JSON text file", path);
        free(text);
        return NULL;
    }
    return text;
}

static int parse_side(const char *opt, const char *s, int *out) {
    char *end = NULL;
    long v = strtol(s, &end, 10);
    if (end == s || *end || v < PLOT_JSON_MIN_SIDE || v > PLOT_JSON_MAX_SIDE)
        return cli_fail("plot", "%s '%s' is not a whole number of pixels in [%d, %d]", opt, s,
                        PLOT_JSON_MIN_SIDE, PLOT_JSON_MAX_SIDE);
    *out = (int)v;
    return 0;
}

int cmd_plot(int argc, char **argv) {
    const char *input = NULL, *output = NULL;
    int demo = 0, width = 0, height = 0;
    enum { O_OUT, O_WIDTH, O_HEIGHT, O_DEMO };
    static const cli_opt opts[] = {
        {"--output", "-o", 1}, {"--width", NULL, 1}, {"--height", NULL, 1}, {"--demo", NULL, 0}};
    cli_parser ps;
    cli_parser_init(&ps, "plot", plot_usage, argc, argv, opts, sizeof opts / sizeof opts[0]);
    for (;;) {
        const char *v;
        char q[160];
        const int k = cli_next(&ps, &v);
        if (k == CLI_END) break;
        if (k == CLI_EXIT_OK) return 0;
        if (k == CLI_BAD) return CLI_EXIT_USAGE;
        if (k == CLI_POSITIONAL) {
            if (input)
                return cli_fail("plot", "more than one input file ('%s', '%s')", input,
                                cli_quote(v, q, sizeof q));
            input = v;
        } else if (k == O_OUT) {
            output = v;
        } else if (k == O_WIDTH || k == O_HEIGHT) {
            if (parse_side(opts[k].name, v, k == O_WIDTH ? &width : &height)) return CLI_EXIT_USAGE;
        } else {
            demo = 1;
        }
    }
    if (demo && input) return cli_fail("plot", "give either FILE.json or --demo, not both");
    if (!demo && !input) return cli_fail("plot", "no input: give FILE.json or --demo");
    if (!output) return cli_fail("plot", "no output: give -o OUT.png");
    /* Before any work: a name, a format and a directory that can take the image. */
    const int vector = plot_vector_format(output);
    char why[512] = "";
    if (vector && plot_vector_check(output, why, sizeof why))
        return cli_error("plot", "-o: %s", why);
    cj_status st = vector ? CJ_OK : cj_image_check_destination(output, 0);
    if (st)
        return st == CJ_ERR_ARGUMENT ? cli_fail("plot", "-o: %s", cj_last_error())
                                     : cli_error("plot", "-o: %s", cj_last_error());

    char *text = NULL;
    if (!demo && !(text = read_file(input, why, sizeof why))) return cli_fail("plot", "%s", why);
    if (cli_guard_output("plot", "-o", output)) {
        free(text);
        return CLI_EXIT_USAGE;
    }
    cj_plot_doc doc;
    st = cj_plot_json_parse(demo ? "demo" : input, demo ? demo_json : text, &doc);
    free(text);
    if (st)
        return st == CJ_ERR_NOMEM ? cli_error("plot", "%s", cj_last_error())
                                  : cli_fail("plot", "%s", cj_last_error());
    if (width) doc.width = width;
    if (height) doc.height = height;

    cj_font *font = NULL;
    cj_framebuffer *fb = NULL;
    int status = 0;
    st = cj_font_open(NULL, &font);
    if (st) status = cli_error("plot", "%s", cj_last_error());
    if (!status && vector) { /* SVG or PDF through cairo (plot_vector.c) */
        const int vs = plot_vector_write(&doc, font, output, why, sizeof why);
        if (vs == CJ_ERR_NOMEM || vs == CJ_ERR_IO)
            status = cli_error("plot", "%s", why);
        else if (vs)
            status = cli_fail("plot", "%s: %s", demo ? "demo" : input, why);
        else
            printf("wrote %s (%d x %d)\n", output, doc.width, doc.height);
        cj_font_close(font);
        cj_plot_doc_free(&doc);
        return status;
    }
    if (!status && (st = cj_framebuffer_create(doc.width, doc.height, 0, NULL, &fb)))
        status = cli_error("plot", "%s", cj_last_error());
    if (!status && (st = cj_plot_doc_render(&doc, fb, font))) {
        /* Rendering fails only on data it cannot draw (e.g. a panel too small for its text). */
        const int usage = st != CJ_ERR_NOMEM && st != CJ_ERR_IO;
        status = (usage ? cli_fail : cli_error)("plot", "%s: cannot render %s: %s",
                                                demo ? "demo" : input, cj_plot_doc_where(&doc),
                                                cj_last_error());
    }
    if (!status && (st = cj_image_write(output, fb->width, fb->height, (const uint8_t *)fb->pixels,
                                        (size_t)fb->stride * sizeof *fb->pixels)))
        status = st == CJ_ERR_ARGUMENT ? cli_fail("plot", "%s", cj_last_error())
                                       : cli_error("plot", "%s", cj_last_error());
    if (!status) printf("wrote %s (%d x %d)\n", output, fb->width, fb->height);
    cj_framebuffer_destroy(fb);
    cj_font_close(font);
    cj_plot_doc_free(&doc);
    return status;
}

#endif

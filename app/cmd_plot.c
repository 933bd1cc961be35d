/* casteljau plot: render a JSON plot description (or the built-in gallery) to a PNG image.
 *
 *   casteljau plot FILE.json -o OUT.png [--width W] [--height H]
 *   casteljau plot --demo -o OUT.png [--width W] [--height H]
 *
 * Contract: bad arguments or a bad document print one line on stderr naming what is wrong
 * (for the document: the JSON path of the field), nothing on stdout, exit status 2, and no
 * output file (the image is written to a temporary file renamed into place only at the end).
 * A missing font or an unwritable destination exits with status 1. Success prints one line
 * "wrote OUT.png (W x H)" on stdout. Builds without OpenImageIO report that plot is
 * unavailable (status 2). */
#include "cli.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char plot_usage[] =
    "usage: casteljau plot FILE.json -o OUT.png [--width W] [--height H]\n"
    "       casteljau plot --demo -o OUT.png [--width W] [--height H]\n"
    "Renders a plot described in JSON (see the README) or the built-in gallery to PNG.\n";

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

#include "casteljau/image_io.h"
#include "casteljau/text.h"

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
    FILE *f = strcmp(path, "-") ? fopen(path, "rb") : stdin;
    if (!f) {
        snprintf(why, why_size, "cannot open '%s'", path);
        return NULL;
    }
    size_t cap = 1 << 16, n = 0;
    char *buf = malloc(cap);
    while (buf) {
        n += fread(buf + n, 1, cap - n - 1, f);
        if (ferror(f)) {
            snprintf(why, why_size, "cannot read '%s'", path);
            free(buf);
            buf = NULL;
            break;
        }
        if (feof(f)) break;
        if (cap > ((size_t)64 << 20)) {
            snprintf(why, why_size, "'%s' is larger than 64 MiB", path);
            free(buf);
            buf = NULL;
            break;
        }
        char *nb = realloc(buf, cap * 2);
        if (!nb) free(buf);
        buf = nb;
        cap *= 2;
    }
    if (f != stdin) fclose(f);
    if (!buf) {
        if (!*why) snprintf(why, why_size, "out of memory reading '%s'", path);
        return NULL;
    }
    buf[n] = '\0';
    if (strlen(buf) != n) {
        snprintf(why, why_size, "'%s' contains a NUL byte: not a JSON text file", path);
        free(buf);
        return NULL;
    }
    return buf;
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
    for (int i = 1; i < argc; ++i) {
        const char *a = argv[i];
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            fputs(plot_usage, stdout);
            return 0;
        } else if (!strcmp(a, "-o") || !strcmp(a, "--output")) {
            if (++i >= argc) return cli_fail("plot", "%s needs a file name", a);
            output = argv[i];
        } else if (!strcmp(a, "--width") || !strcmp(a, "--height")) {
            if (++i >= argc) return cli_fail("plot", "%s needs a value", a);
            if (parse_side(a, argv[i], a[2] == 'w' ? &width : &height)) return CLI_EXIT_USAGE;
        } else if (!strcmp(a, "--demo")) {
            demo = 1;
        } else if (a[0] == '-' && a[1] != '\0') {
            return cli_fail("plot", "unknown option '%s' (try --help)", a);
        } else {
            if (input) return cli_fail("plot", "more than one input file ('%s', '%s')", input, a);
            input = a;
        }
    }
    if (demo && input) return cli_fail("plot", "give either FILE.json or --demo, not both");
    if (!demo && !input) return cli_fail("plot", "no input: give FILE.json or --demo");
    if (!output) return cli_fail("plot", "no output: give -o OUT.png");

    char why[512] = "";
    char *text = NULL;
    if (!demo && !(text = read_file(input, why, sizeof why))) return cli_fail("plot", "%s", why);
    plot_doc doc;
    int rc = plot_json_parse(demo ? demo_json : text, &doc, why, sizeof why);
    free(text);
    if (rc) return cli_fail("plot", "%s: %s", demo ? "demo" : input, why);
    if (width) doc.width = width;
    if (height) doc.height = height;

    cj_font *font = NULL;
    cj_framebuffer *fb = NULL;
    int status = 0;
    cj_status st = cj_font_open(NULL, &font);
    if (st) {
        fprintf(stderr, "casteljau plot: %s\n", cj_last_error());
        status = 1;
    }
    if (!status && (st = cj_framebuffer_create(doc.width, doc.height, 0, NULL, &fb))) {
        fprintf(stderr, "casteljau plot: %s\n", cj_last_error());
        status = 1;
    }
    if (!status && (st = plot_doc_render(&doc, fb, font))) {
        /* Rendering fails only on data it cannot draw (e.g. a panel too small for its text). */
        fprintf(stderr, "casteljau plot: cannot render: %s\n", cj_last_error());
        status = st == CJ_ERR_NOMEM || st == CJ_ERR_IO ? 1 : CLI_EXIT_USAGE;
    }
    if (!status &&
        (st = cj_image_write_png(output, fb->width, fb->height, (const uint8_t *)fb->pixels,
                                 (size_t)fb->stride * sizeof *fb->pixels))) {
        fprintf(stderr, "casteljau plot: %s\n", cj_last_error());
        status = 1;
    }
    if (!status) printf("wrote %s (%d x %d)\n", output, fb->width, fb->height);
    cj_framebuffer_destroy(fb);
    cj_font_close(font);
    plot_doc_free(&doc);
    return status;
}

#endif

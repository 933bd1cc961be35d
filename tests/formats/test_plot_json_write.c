/* The one writer of the plot format (formats/src/plot_json_write.c) and the JSON writing kit
 * under it (scene/src/json_write.c):
 *  - shortest numbers: for seeded random doubles (random bit patterns: normal, subnormal, huge,
 *    tiny) and a list of tricky ones, cj_json_number_text reads back exactly and has as few
 *    significant digits as the brute-force oracle (the first of "%.1g" .. "%.17g" that reads
 *    back); 5.6 is "5.6", 2^-1074 is "5e-324";
 *  - round trip: a page with every field and tricky numbers, written, read back (every double
 *    bit-identical), written again (the two files byte-identical); a title with quotes, a
 *    backslash and control characters survives cJSON's escaper;
 *  - refusals: a Kochanek-Bartels spline (CJ_ERR_UNSUPPORTED, naming the curve), a folder that
 *    does not exist (CJ_ERR_IO, the old file untouched). */
#define _POSIX_C_SOURCE 200809L
#include "json_write_internal.h"
#include "plot_json.h"

#include "check.h"
#include "rng.h"

#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* Significant digits of a "%g" text: from the first nonzero digit of the mantissa to its last
 * nonzero one ("100" and "1e+02" both have one). */
static int sig_digits(const char *s) {
    int first = -1, last = -1, i = 0;
    for (; *s && *s != 'e' && *s != 'E'; ++s) {
        if (*s < '0' || *s > '9') continue;
        if (*s != '0') {
            if (first < 0) first = i;
            last = i;
        }
        ++i;
    }
    return first < 0 ? 0 : last - first + 1;
}

static int oracle_digits(double v) {
    char buf[64];
    for (int p = 1; p <= 17; ++p) {
        snprintf(buf, sizeof buf, "%.*g", p, v);
        if (strtod(buf, NULL) == v) return sig_digits(buf);
    }
    return -1;
}

static double from_bits(uint64_t b) {
    double d;
    memcpy(&d, &b, sizeof d);
    return d;
}

static void check_number(double v) {
    char buf[CJ_JSON_NUMBER_MAX];
    cj_json_number_text(v, buf);
    CHECK(strtod(buf, NULL) == v && signbit(strtod(buf, NULL)) == signbit(v),
          "%.17g written \"%s\" reads back as %.17g", v, buf, strtod(buf, NULL));
    CHECK(sig_digits(buf) == oracle_digits(v), "%.17g written \"%s\" (%d digits; shortest has %d)",
          v, buf, sig_digits(buf), oracle_digits(v));
}

static void test_shortest(void) {
    const double tricky[] = {5.6,
                             0.1,
                             0.1 + 0.2,
                             1.0 / 3.0,
                             2.0 / 3.0,
                             1e23,
                             9007199254740993.0,
                             123456789012345680.0,
                             DBL_MAX,
                             DBL_MIN,
                             DBL_TRUE_MIN,
                             -DBL_TRUE_MIN * 3,
                             0x1.fffffffffffffp-1023,
                             5e-324,
                             -0.0,
                             0.0,
                             1.0,
                             -2.5,
                             100.0,
                             1e-7,
                             299792458.0,
                             3.141592653589793,
                             2.718281828459045};
    for (size_t i = 0; i < sizeof tricky / sizeof tricky[0]; ++i) check_number(tricky[i]);
    char buf[CJ_JSON_NUMBER_MAX];
    cj_json_number_text(5.6, buf);
    CHECK(!strcmp(buf, "5.6"), "5.6 written \"%s\"", buf);
    cj_json_number_text(DBL_TRUE_MIN, buf);
    CHECK(!strcmp(buf, "5e-324"), "2^-1074 written \"%s\"", buf);
    cj_json_number_text(NAN, buf);
    CHECK(!strcmp(buf, "null"), "NaN written \"%s\"", buf);
    cj_json_number_text(-INFINITY, buf);
    CHECK(!strcmp(buf, "null"), "-Inf written \"%s\"", buf);

    const uint64_t seed = cj_test_seed("test_plot_json_write", 20261126);
    cj_rng rng;
    cj_rng_init(&rng, seed);
    int n = 0;
    for (int i = 0; i < 200000; ++i) {
        double v = from_bits(cj_rng_next(&rng));
        if (i % 4 == 1) v = from_bits(cj_rng_next(&rng) & 0x000fffffffffffffull); /* subnormal */
        if (i % 4 == 2) v = cj_rng_range(&rng, -1000.0, 1000.0);
        if (i % 4 == 3) v = round(cj_rng_range(&rng, -1e6, 1e6)) / 1000.0; /* short decimals */
        if (!isfinite(v)) continue;
        check_number(v);
        ++n;
    }
    printf("shortest numbers: %zu tricky and %d random doubles (seed %llu) read back exactly, "
           "with the oracle's digit count\n",
           sizeof tricky / sizeof tricky[0], n, (unsigned long long)seed);
}

static char *read_text(const char *path) {
    FILE *f = fopen(path, "rb");
    if (!f) return NULL;
    char *buf = calloc(1, 1 << 20);
    size_t n = buf ? fread(buf, 1, (1 << 20) - 1, f) : 0;
    (void)n;
    fclose(f);
    return buf;
}

static int same_doubles(const double *a, const double *b, size_t n) {
    return !n || !memcmp(a, b, n * sizeof *a);
}

static int same_curve(const cj_plot_json_curve *a, const cj_plot_json_curve *b) {
    const cj_plot_bezier_opts *x = &a->bezier, *y = &b->bezier;
    int same = a->spline == b->spline && a->count == b->count &&
               same_doubles(a->points, b->points, 2 * a->count) && !a->weights == !b->weights &&
               (!a->weights || same_doubles(a->weights, b->weights, a->count)) &&
               !memcmp(&x->color, &y->color, sizeof x->color) &&
               same_doubles(&x->width, &y->width, 1);
    if (a->spline)
        return same && a->spline_options.kind == b->spline_options.kind &&
               same_doubles(&a->spline_options.tension, &b->spline_options.tension, 1) &&
               a->spline_options.closed == b->spline_options.closed && a->knots == b->knots;
    return same && x->control_polygon == y->control_polygon &&
           x->control_points == y->control_points && x->hull == y->hull &&
           x->normals == y->normals && x->construction == y->construction &&
           (!x->construction || same_doubles(&x->construction_t, &y->construction_t, 1)) &&
           x->nframes == y->nframes && same_doubles(x->frames_t, y->frames_t, x->nframes);
}

static int same_page(const cj_plot_json_page *a, const cj_plot_json_page *b) {
    int same = a->width == b->width && a->height == b->height &&
               !memcmp(&a->background, &b->background, sizeof a->background) &&
               a->axes == b->axes && same_doubles(&a->margin, &b->margin, 1) &&
               !a->title == !b->title && (!a->title || !strcmp(a->title, b->title)) &&
               a->have_view == b->have_view && same_doubles(a->view, b->view, 4) &&
               a->ncurves == b->ncurves;
    for (size_t i = 0; same && i < a->ncurves; ++i) same = same_curve(&a->curves[i], &b->curves[i]);
    return same;
}

static void test_round_trip(const char *dir) {
    double bez[] = {0.1, 0.2, 5.6, 1.0 / 3.0, 1e-300, -2.5, DBL_TRUE_MIN, 123456.789};
    double w[] = {1.0, 0.30000000000000004, 1.75, 1.0 / 7.0};
    double spl[] = {0, 0, 1, 2.0 / 3.0, 2, -0.1, 3, 1e10};
    cj_plot_json_curve curves[2];
    memset(curves, 0, sizeof curves);
    curves[0].points = bez;
    curves[0].count = 4;
    curves[0].weights = w;
    curves[0].bezier = cj_plot_bezier_defaults();
    curves[0].bezier.color = cj_rgba_make(1, 2, 3, 4);
    curves[0].bezier.width = 2.7;
    curves[0].bezier.hull = 1;
    curves[0].bezier.construction = 1;
    curves[0].bezier.construction_t = 0.1;
    curves[0].bezier.nframes = 2;
    curves[0].bezier.frames_t[0] = 1.0 / 3.0;
    curves[0].bezier.frames_t[1] = 0.7;
    curves[1].spline = 1;
    curves[1].points = spl;
    curves[1].count = 4;
    curves[1].bezier = cj_plot_bezier_defaults();
    curves[1].bezier.width = 0.3;
    curves[1].spline_options = cj_spline_defaults();
    curves[1].spline_options.kind = CJ_SPLINE_CENTRIPETAL;
    curves[1].spline_options.tension = -0.45;
    curves[1].spline_options.closed = 1;
    curves[1].knots = 0;
    char title[] = "a \"quoted\" \\ title\twith\ncontrol \x01 characters";
    cj_plot_json_page page = {640,   480, {250, 251, 252, 128},        0, 0.5,
                              title, 1,   {-1.1, 0.2, 5.6, 7.0 / 3.0}, 2, curves};
    char p1[512], p2[512];
    snprintf(p1, sizeof p1, "%s/page1.json", dir);
    snprintf(p2, sizeof p2, "%s/page2.json", dir);
    CHECK(cj_plot_json_write_page(&page, p1) == CJ_OK, "write: %s", cj_last_error());
    char *t1 = read_text(p1);
    CHECK(t1 && strstr(t1, "5.6") && !strstr(t1, "5.5999"), "5.6 not in its shortest form:\n%s",
          t1 ? t1 : "(unreadable)");
    cj_plot_json_page back;
    const cj_status rc = cj_plot_json_read_page(p1, t1 ? t1 : "", &back);
    CHECK(rc == CJ_OK, "read back: %s", cj_last_error());
    if (!rc) {
        CHECK(same_page(&page, &back), "the page read back differs from the page written");
        CHECK(cj_plot_json_write_page(&back, p2) == CJ_OK, "write again: %s", cj_last_error());
        char *t2 = read_text(p2);
        CHECK(t1 && t2 && !strcmp(t1, t2), "the second file differs from the first");
        free(t2);
        cj_plot_json_page_free(&back);
    }
    free(t1);
    remove(p2);
    printf("round trip: a page of a rational Bezier and a closed centripetal spline with tricky "
           "numbers and an escaped title read back bit-identical and writes the same bytes\n");

    /* refusals */
    curves[1].spline_options.kind = CJ_SPLINE_KOCHANEK_BARTELS;
    CHECK(cj_plot_json_write_page(&page, p2) == CJ_ERR_UNSUPPORTED, "a Kochanek-Bartels spline");
    CHECK(strstr(cj_last_error(), "curve 1"), "message: %s", cj_last_error());
    CHECK(access(p2, F_OK) != 0, "a refused page left a file");
    curves[1].spline_options.kind = CJ_SPLINE_CHORDAL;
    char bad[600];
    snprintf(bad, sizeof bad, "%s/no-such-folder/page.json", dir);
    CHECK(cj_plot_json_write_page(&page, bad) == CJ_ERR_IO, "a missing folder");
    t1 = read_text(p1);
    page.width = 100;
    curves[0].bezier.construction_t = 0.9;
    char ro[600];
    snprintf(ro, sizeof ro, "%s/page1.json", dir);
    CHECK(cj_plot_json_write_page(&page, ro) == CJ_OK, "overwrite: %s", cj_last_error());
    char *t3 = read_text(ro);
    CHECK(t1 && t3 && strcmp(t1, t3) && strstr(t3, "\"width\":\t100"),
          "the file was not replaced:\n%s", t3 ? t3 : "");
    free(t1);
    free(t3);
    remove(p1);
    printf("refusals: a Kochanek-Bartels spline (CJ_ERR_UNSUPPORTED naming curve 1, no file), a "
           "missing folder (CJ_ERR_IO); an existing file is replaced whole\n");
}

int main(void) {
    char dir[] = "/tmp/cj_plot_write_XXXXXX";
    if (!mkdtemp(dir)) return 1;
    test_shortest();
    test_round_trip(dir);
    rmdir(dir);
    return cj_check_exit();
}

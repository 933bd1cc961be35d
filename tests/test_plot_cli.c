#define _POSIX_C_SOURCE 200809L /* mkdtemp, WEXITSTATUS */
/* `casteljau plot` end to end: golden images of the gallery and of a JSON plot (compared with
 * a tolerance that survives FreeType/hinting differences), the error contract for bad JSON
 * and bad arguments (exit 2, one line on stderr naming the JSON path, nothing on stdout, no
 * output file, an existing output left alone), and unwritable destinations (exit 1, nothing). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "casteljau/image_io.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#ifndef CJ_CASTELJAU_EXE
#error "CJ_CASTELJAU_EXE must name the casteljau binary"
#endif
#ifndef CJ_GOLDEN_DIR
#error "CJ_GOLDEN_DIR must name tests/golden"
#endif

static char dir[64];

static int exists(const char *path) {
    struct stat st;
    return stat(path, &st) == 0;
}

static char *slurp(const char *path) {
    FILE *f = fopen(path, "rb");
    if (!f) return NULL;
    char *buf = calloc(1, 1 << 16);
    size_t n = fread(buf, 1, (1 << 16) - 1, f);
    buf[n] = '\0';
    fclose(f);
    return buf;
}

static void spit(const char *path, const char *text) {
    FILE *f = fopen(path, "wb");
    assert_non_null(f);
    fputs(text, f);
    fclose(f);
}

/* Runs `casteljau <args>`; stdout/stderr go to files in dir. Returns the exit status. */
static int run(const char *args) {
    char cmd[2048];
    int len = snprintf(cmd, sizeof cmd, "'%s' %s >'%s/out.txt' 2>'%s/err.txt'", CJ_CASTELJAU_EXE,
                       args, dir, dir);
    assert_true(len > 0 && (size_t)len < sizeof cmd); /* a truncated command would test nothing */
    int st = system(cmd);
    assert_true(WIFEXITED(st));
    return WEXITSTATUS(st);
}

/* Counts pixels of a that differ from every pixel of b in their 3x3 neighbourhood by more
 * than `tol` in some channel (a one-pixel shift of a glyph or an edge is not a difference). */
static long far_pixels(const uint8_t *a, const uint8_t *b, int w, int h, int tol) {
    long count = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const uint8_t *p = a + 4 * ((size_t)y * w + x);
            int best = 256;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    int xx = x + dx, yy = y + dy;
                    if (xx < 0 || yy < 0 || xx >= w || yy >= h) continue;
                    const uint8_t *q = b + 4 * ((size_t)yy * w + xx);
                    int m = 0;
                    for (int k = 0; k < 4; ++k) {
                        int d = abs((int)p[k] - (int)q[k]);
                        if (d > m) m = d;
                    }
                    if (m < best) best = m;
                }
            if (best > tol) ++count;
        }
    return count;
}

/* Fraction of pixels that differ (both directions) between two PNG files of equal size. */
static double image_difference(const char *got, const char *want) {
    int w1, h1, w2, h2;
    uint8_t *a = NULL, *b = NULL;
    assert_int_equal(cj_image_read(got, &w1, &h1, &a), CJ_OK);
    assert_int_equal(cj_image_read(want, &w2, &h2, &b), CJ_OK);
    assert_int_equal(w1, w2);
    assert_int_equal(h1, h2);
    long n = far_pixels(a, b, w1, h1, 64) + far_pixels(b, a, w1, h1, 64);
    cj_image_free(a);
    cj_image_free(b);
    return (double)n / (2.0 * w1 * h1);
}

/* Allowed share of differing pixels; a removed curve or a moved label exceeds it (checked). */
#define GOLDEN_MAX_DIFF 0.001

static void test_golden_gallery(void **state) {
    (void)state;
    char out[256], args[512];
    snprintf(out, sizeof out, "%s/gallery.png", dir);
    snprintf(args, sizeof args, "plot --demo --width 750 --height 450 -o '%s'", out);
    assert_int_equal(run(args), 0);
    char *o = slurp("out.txt");
    free(o);
    double d = image_difference(out, CJ_GOLDEN_DIR "/gallery_750x450.png");
    printf("test_plot_cli: gallery 750x450 vs golden: %.4f %% of pixels differ (limit %.2f %%)\n",
           100 * d, 100 * GOLDEN_MAX_DIFF);
    assert_true(d <= GOLDEN_MAX_DIFF);
    remove(out);
}

static void test_golden_json(void **state) {
    (void)state;
    char out[256], args[1024];
    snprintf(out, sizeof out, "%s/quadratic.png", dir);
    snprintf(args, sizeof args, "plot '%s/quadratic.json' -o '%s'", CJ_GOLDEN_DIR, out);
    assert_int_equal(run(args), 0);
    char path[256];
    snprintf(path, sizeof path, "%s/out.txt", dir);
    char *o = slurp(path);
    assert_non_null(strstr(o, "wrote"));
    free(o);
    double d = image_difference(out, CJ_GOLDEN_DIR "/quadratic.png");
    printf("test_plot_cli: quadratic.json vs golden: %.4f %% of pixels differ\n", 100 * d);
    assert_true(d <= GOLDEN_MAX_DIFF);

    /* The comparison can fail: the same plot without its curve differs enough. */
    char *doc = slurp(CJ_GOLDEN_DIR "/quadratic.json");
    assert_non_null(doc);
    char *cut = strstr(doc, "\"color\": \"#1f77b4\", \"width\": 2.5");
    assert_non_null(cut);
    const char *white = "\"color\": \"#ffffff\", \"width\": 0.1"; /* curve invisible */
    memcpy(cut, white, strlen(white));
    char json[256];
    snprintf(json, sizeof json, "%s/nocurve.json", dir);
    spit(json, doc);
    free(doc);
    snprintf(args, sizeof args, "plot '%s' -o '%s'", json, out);
    assert_int_equal(run(args), 0);
    double d2 = image_difference(out, CJ_GOLDEN_DIR "/quadratic.png");
    printf("test_plot_cli: the same plot with an invisible curve: %.4f %% differ (must exceed "
           "the limit)\n",
           100 * d2);
    assert_true(d2 > 3 * GOLDEN_MAX_DIFF);
    remove(out);
    remove(json);
}

typedef struct bad_case {
    const char *json;   /* document text, or NULL to use `args` alone */
    const char *args;   /* extra arguments (after the input file when json != NULL) */
    const char *expect; /* substring of the one-line message */
} bad_case;

/* The CLI contract on a few representative failures (every JSON error path is checked
 * in-process by test_plot_json, which is much faster than starting the tool each time). */
static const bad_case bad_cases[] = {
    {"{\"items\": [", "", "JSON syntax error (line 1, column 12)"},
    {"{\"items\": [{\"type\": \"bezier\", \"points\": [[0,0],[1,1]]},"
     " {\"type\": \"bezier\", \"points\": [[0,0],[1,1],[2,0],[3]]}]}",
     "", "bad.json:1: items[1].points[3] must be an array of 2 numbers, not 1"},
    {"{\"items\": [{\"type\": \"points\", \"points\": [[0,0],[1,1]]}]}", "--width abc",
     "--width 'abc' is not a whole number"},
    {"{\"items\": [{\"type\": \"points\", \"points\": [[0,0],[1,1]]}]}", "--frobnicate",
     "unknown option '--frobnicate'"},
    {NULL, "plot", "no input"},
    {NULL, "plot /nonexistent/plot.json", "cannot open '/nonexistent/plot.json'"},
};

static void test_bad_input_contract(void **state) {
    (void)state;
    char out[256], in[256], args[2048], path[256];
    snprintf(out, sizeof out, "%s/bad.png", dir);
    snprintf(in, sizeof in, "%s/bad.json", dir);
    const size_t n = sizeof bad_cases / sizeof bad_cases[0];
    for (size_t i = 0; i < n; ++i) {
        const bad_case *c = &bad_cases[i];
        if (c->json) {
            spit(in, c->json);
            snprintf(args, sizeof args, "plot '%s' -o '%s' %s", in, out, c->args);
        } else if (strstr(c->args, "--demo") || !strcmp(c->args, "plot")) {
            snprintf(args, sizeof args, "%s", c->args);
        } else {
            snprintf(args, sizeof args, "%s -o '%s'", c->args, out);
        }
        int rc = run(args);
        snprintf(path, sizeof path, "%s/err.txt", dir);
        char *err = slurp(path);
        snprintf(path, sizeof path, "%s/out.txt", dir);
        char *o = slurp(path);
        if (rc != 2 || !strstr(err, c->expect) || o[0] != '\0' || exists(out) ||
            strchr(err, '\n') != err + strlen(err) - 1) {
            printf("case %zu: exit %d, stderr '%s', stdout '%s', expected '%s'\n", i, rc, err, o,
                   c->expect);
            fail();
        }
        free(err);
        free(o);
    }
    /* An existing output survives a bad run untouched. */
    spit(out, "previous image");
    spit(in, "{\"items\": [{\"type\": \"bezier\"}]}");
    snprintf(args, sizeof args, "plot '%s' -o '%s'", in, out);
    assert_int_equal(run(args), 2);
    char *prev = slurp(out);
    assert_string_equal(prev, "previous image");
    free(prev);
    remove(out);
    remove(in);
    printf("test_plot_cli: %zu bad documents/arguments: exit 2, one line naming the field, "
           "empty stdout, no output file\n",
           n);
}

static void test_unwritable_destination(void **state) {
    (void)state;
    char args[512];
    snprintf(args, sizeof args, "plot --demo --width 400 --height 300 -o '%s/missing/x.png'", dir);
    assert_int_equal(run(args), 1);
    char path[256];
    snprintf(path, sizeof path, "%s/err.txt", dir);
    char *err = slurp(path);
    assert_non_null(strstr(err, "missing/x.png"));
    free(err);
    snprintf(path, sizeof path, "%s/missing", dir);
    assert_false(exists(path));
    printf("test_plot_cli: missing destination directory: exit 1, nothing created\n");
}

static int setup(void **state) {
    (void)state;
    snprintf(dir, sizeof dir, "/tmp/cj_plot_cli_XXXXXX");
    return mkdtemp(dir) ? 0 : -1;
}

static int teardown(void **state) {
    (void)state;
    char path[128];
    snprintf(path, sizeof path, "%s/out.txt", dir);
    remove(path);
    snprintf(path, sizeof path, "%s/err.txt", dir);
    remove(path);
    return rmdir(dir);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_golden_gallery),
        cmocka_unit_test(test_golden_json),
        cmocka_unit_test(test_bad_input_contract),
        cmocka_unit_test(test_unwritable_destination),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}

#define _POSIX_C_SOURCE 200809L
/* The `fit` command and the B-spline JSON item of `eval --curve` and `plot`: interpolation passes
 * through the points (evaluated back through eval --curve at the chord-length parameters),
 * approximation stays within its tolerance with fewer control points, standard input works, the
 * output is valid JSON that plot draws, and bad input is refused with one line naming it. */
#include "cli_run.h"

#include <cJSON.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static int failures;
#define CHECK(cond, ...)                                                                           \
    do {                                                                                           \
        if (!(cond)) {                                                                             \
            ++failures;                                                                            \
            printf("FAIL line %d: ", __LINE__);                                                    \
            printf(__VA_ARGS__);                                                                   \
            printf("\n");                                                                          \
        }                                                                                          \
    } while (0)

static char dir[64], pts_path[128], json_path[128], cmd[4096];
enum { N = 50 };
static double P[N][2], ts[N];

static int run(const char *command, cj_cli_result *r) {
    if (cj_cli_shell(command, r) != 0) {
        printf("could not run: %s\n", command);
        exit(1);
    }
    return r->status;
}

/* Max distance between the data and `eval --curve file` at the chord parameters. */
static double eval_back(const char *file) {
    char tfile[160];
    snprintf(tfile, sizeof tfile, "%s/ts.txt", dir);
    FILE *f = fopen(tfile, "w");
    for (int i = 0; i < N; ++i) fprintf(f, "%.17g\n", ts[i]);
    fclose(f);
    snprintf(cmd, sizeof cmd, "'%s' eval --curve '%s' < '%s'", CJ_CLI, file, tfile);
    cj_cli_result r;
    run(cmd, &r);
    double worst = -1;
    if (r.status == 0) {
        worst = 0;
        const char *s = r.out;
        for (int i = 0; i < N; ++i) {
            char *e;
            const double x = strtod(s, &e), y = strtod(e, &e);
            s = e;
            worst = fmax(worst, hypot(x - P[i][0], y - P[i][1]));
        }
    } else {
        printf("eval failed: %s\n", r.err);
    }
    cj_cli_result_free(&r);
    return worst;
}

static const cJSON *bspline_item(cJSON *doc) {
    const cJSON *items = cJSON_GetObjectItem(doc, "items");
    return items ? cJSON_GetArrayItem(items, 0) : NULL;
}

int main(void) {
    snprintf(dir, sizeof dir, "/tmp/cj_fit_XXXXXX");
    if (!mkdtemp(dir)) return 1;
    snprintf(pts_path, sizeof pts_path, "%s/pts.txt", dir);
    snprintf(json_path, sizeof json_path, "%s/fit.json", dir);
    FILE *f = fopen(pts_path, "w");
    fprintf(f, "# a spiral\n\n");
    for (int i = 0; i < N; ++i) {
        const double a = 0.2 * i;
        P[i][0] = (1 + 0.1 * a) * cos(a);
        P[i][1] = (1 + 0.1 * a) * sin(a);
        fprintf(f, "%.17g%s%.17g\n", P[i][0], i % 2 ? ", " : " ", P[i][1]);
    }
    fclose(f);
    ts[0] = 0;
    for (int i = 1; i < N; ++i)
        ts[i] = ts[i - 1] + hypot(P[i][0] - P[i - 1][0], P[i][1] - P[i - 1][1]);
    for (int i = 1; i < N; ++i) ts[i] /= ts[N - 1];

    /* Interpolation into a file. */
    cj_cli_result r;
    snprintf(cmd, sizeof cmd, "'%s' fit '%s' -o '%s'", CJ_CLI, pts_path, json_path);
    CHECK(run(cmd, &r) == 0 && r.out_len == 0, "fit -o: status %d, stderr %s", r.status, r.err);
    cj_cli_result_free(&r);
    snprintf(cmd, sizeof cmd, "cat '%s'", json_path);
    run(cmd, &r);
    cJSON *doc = cJSON_Parse(r.out);
    CHECK(doc != NULL, "fit output is not JSON");
    const cJSON *it = doc ? bspline_item(doc) : NULL;
    const cJSON *pts = it ? cJSON_GetObjectItem(it, "points") : NULL;
    CHECK(pts && cJSON_GetArraySize(pts) == N && cJSON_GetObjectItem(it, "degree")->valueint == 3,
          "interpolation: %d control points", pts ? cJSON_GetArraySize(pts) : -1);
    cJSON_Delete(doc);
    cj_cli_result_free(&r);
    const double dev_i = eval_back(json_path);
    CHECK(dev_i >= 0 && dev_i <= 1e-12, "interpolant misses the data by %g", dev_i);

    /* Approximation from standard input, degree 4, centripetal parameters are not chord ones:
     * use chord (default) so that eval_back measures at the fit's parameters. */
    snprintf(cmd, sizeof cmd, "cat '%s' | '%s' fit --tolerance 1e-3 --degree 4 > '%s'", pts_path,
             CJ_CLI, json_path);
    CHECK(run(cmd, &r) == 0, "fit --tolerance from stdin: %s", r.err);
    cj_cli_result_free(&r);
    snprintf(cmd, sizeof cmd, "cat '%s'", json_path);
    run(cmd, &r);
    doc = cJSON_Parse(r.out);
    it = doc ? bspline_item(doc) : NULL;
    pts = it ? cJSON_GetObjectItem(it, "points") : NULL;
    const int m = pts ? cJSON_GetArraySize(pts) : -1;
    const cJSON *title = doc ? cJSON_GetObjectItem(doc, "title") : NULL;
    CHECK(m > 4 && m < N / 2 && title && strstr(title->valuestring, "max deviation"),
          "approximation: %d control points, title %s", m, title ? title->valuestring : "-");
    cJSON_Delete(doc);
    cj_cli_result_free(&r);
    const double dev_a = eval_back(json_path);
    CHECK(dev_a >= 0 && dev_a <= 1e-3, "approximation deviates by %g > 1e-3", dev_a);

#ifdef CJ_TEST_HAVE_PLOT
    snprintf(cmd, sizeof cmd, "'%s' plot '%s' -o '%s/fit.png'", CJ_CLI, json_path, dir);
    CHECK(run(cmd, &r) == 0, "plot of the fit: %s", r.err);
    cj_cli_result_free(&r);
    snprintf(
        cmd, sizeof cmd,
        "echo '{\"items\": [{\"type\": \"bspline\", \"degree\": 2, \"points\": [[0,0],[1,1]]}]}' "
        "| '%s' plot - -o '%s/bad.png'",
        CJ_CLI, dir);
    CHECK(run(cmd, &r) == 2 && strstr(r.err, "items[0]") && strstr(r.err, "too few"),
          "plot of a B-spline with too few points: %d %s", r.status, r.err);
    cj_cli_result_free(&r);
    printf("plot: draws the fit (pieces, control polygon, knot markers) and names a bad item\n");
#endif

    /* Refusals: one line on stderr, exit 2, naming the input. */
    static const struct {
        const char *input, *args, *needle;
    } bad[] = {
        {"1 2\\n3 x\\n", "", "line 2: 'x'"},
        {"1 2\\n3 4 5\\n", "", "line 2: 3 coordinates"},
        {"1 2\\n", "", "at least 2"},
        {"0 0\\n1 1\\n1 1\\n2 0\\n", "", "data points 1 and 2 coincide"},
        {"0 0\\n1 1\\n2 0\\n", "--max-points 3", "only with --tolerance"},
        {"0 0\\n1 1\\n2 0\\n3 3\\n4 0\\n5 5\\n", "--tolerance 1e-9 --max-points 4", "deviation"},
        {"0 0\\n1 1\\n2 0\\n", "--degree 0", "--degree"},
        {"0 0\\n1 1\\n2 0\\n", "--param spline", "unknown --param"},
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; ++i) {
        snprintf(cmd, sizeof cmd, "printf '%s' | '%s' fit %s", bad[i].input, CJ_CLI, bad[i].args);
        run(cmd, &r);
        CHECK(r.status == 2 && strstr(r.err, bad[i].needle) &&
                  strchr(r.err, '\n') == r.err + r.err_len - 1,
              "fit %s on '%s': status %d, stderr '%s' (wanted '%s')", bad[i].args, bad[i].input,
              r.status, r.err, bad[i].needle);
        cj_cli_result_free(&r);
    }
    static const struct {
        const char *json, *args, *needle;
    } ebad[] = {
        {"{\"items\": [{\"type\": \"bezier\", \"points\": [[0,0],[1,1]]}]}", "0.5", "no item"},
        {"{\"type\": \"bspline\", \"degree\": 1, \"points\": [[0],[1],[2]], \"knots\": "
         "[0,0,2,1,1]}",
         "0.5", "knot 3"},
        {"{\"type\": \"bspline\", \"degree\": 1, \"points\": [[0],[1]], \"weights\": [1, 0]}",
         "0.5", "c.json:1: document.weights[1] must be > 0, not 0"},
        {"{\"type\": \"bspline\", \"degree\": 1, \"points\": [[0],[1]]}", "1.5",
         "outside the domain"},
        {"{\"type\": \"bspline\", \"degree\": 1, \"points\": [[0],[1]], \"knot\": [0]}", "0.5",
         "c.json:1: document.knot is not a known key"},
    };
    char cfile[160];
    snprintf(cfile, sizeof cfile, "%s/c.json", dir);
    for (size_t i = 0; i < sizeof ebad / sizeof ebad[0]; ++i) {
        f = fopen(cfile, "w");
        fputs(ebad[i].json, f);
        fclose(f);
        snprintf(cmd, sizeof cmd, "'%s' eval --curve '%s' %s", CJ_CLI, cfile, ebad[i].args);
        run(cmd, &r);
        CHECK(r.status == 2 && strstr(r.err, ebad[i].needle),
              "eval --curve %s: %d '%s' (wanted '%s')", ebad[i].json, r.status, r.err,
              ebad[i].needle);
        cj_cli_result_free(&r);
    }
    /* A NURBS quarter circle: every evaluated point is at distance 1. */
    f = fopen(cfile, "w");
    fputs("{\"type\": \"bspline\", \"degree\": 2, \"points\": [[1,0],[1,1],[0,1]], \"weights\": "
          "[1, 0.70710678118654757, 1]}",
          f);
    fclose(f);
    snprintf(cmd, sizeof cmd, "'%s' eval --curve '%s' 0 0.1 0.3 0.5 0.77 1", CJ_CLI, cfile);
    run(cmd, &r);
    double worst = r.status == 0 ? 0 : 1;
    const char *s = r.out;
    for (int i = 0; i < 6 && r.status == 0; ++i) {
        char *e;
        const double x = strtod(s, &e), y = strtod(e, &e);
        s = e;
        worst = fmax(worst, fabs(hypot(x, y) - 1));
    }
    CHECK(worst <= 4e-16, "NURBS circle through eval --curve: radius off by %g", worst);
    cj_cli_result_free(&r);
    snprintf(cmd, sizeof cmd, "'%s' eval --curve '%s' --derivative 1 --bound 0.5", CJ_CLI, cfile);
    /* a NURBS's derivatives have a proven bound too (the quotient rule's recurrence) */
    CHECK(run(cmd, &r) == 0 && strstr(r.out, " | "), "derivative bound of a NURBS: %d %s", r.status,
          r.err);
    cj_cli_result_free(&r);
    snprintf(cmd, sizeof cmd, "'%s' eval --curve '%s' --derivative 1 --bound 0.5", CJ_CLI,
             json_path);
    CHECK(run(cmd, &r) == 0 && strstr(r.out, " | "), "derivative bound of the fit: %d %s", r.status,
          r.err);
    cj_cli_result_free(&r);
    /* A grid: fit --grid writes the surface, tessellate --surface meshes its Bézier patches. */
    char gfile[160], sfile[160];
    snprintf(gfile, sizeof gfile, "%s/grid.txt", dir);
    snprintf(sfile, sizeof sfile, "%s/surface.json", dir);
    f = fopen(gfile, "w");
    for (int j = 0; j < 6; ++j)
        for (int i = 0; i < 8; ++i)
            fprintf(f, "%g %g %.17g\n", 0.5 * i, 0.5 * j, 0.4 * sin(0.8 * i) * cos(0.7 * j));
    fclose(f);
    snprintf(cmd, sizeof cmd,
             "'%s' fit --grid 8,6 '%s' -o '%s' && '%s' tessellate --surface '%s' -o '%s/s.obj'",
             CJ_CLI, gfile, sfile, CJ_CLI, sfile, dir);
    CHECK(run(cmd, &r) == 0 && strstr(r.out, "patches 15\n"),
          "fit --grid | tessellate --surface: %d %s %s", r.status, r.out, r.err);
    cj_cli_result_free(&r);
    snprintf(cmd, sizeof cmd, "'%s' fit --grid 8,5 '%s'", CJ_CLI, gfile);
    CHECK(run(cmd, &r) == 2 && strstr(r.err, "needs 40 points"), "wrong grid size: %s", r.err);
    cj_cli_result_free(&r);
    f = fopen(sfile, "w");
    fputs("{\"type\": \"nurbs_surface\", \"degree\": [1, 1], \"size\": [2, 2], \"points\": "
          "[[0,0,0],[1,0,0],[0,1,0],[1,1,1]], \"weights\": [1, 1, -1, 1]}",
          f);
    fclose(f);
    snprintf(cmd, sizeof cmd, "'%s' tessellate --surface '%s' -o '%s/s.obj'", CJ_CLI, sfile, dir);
    CHECK(run(cmd, &r) == 2 && strstr(r.err, "surface.json:1: weights[2] must be > 0, not -1"),
          "negative surface weight: %s", r.err);
    cj_cli_result_free(&r);
    printf("surfaces: fit --grid 8,6 then tessellate --surface meshes 15 patches; a wrong grid "
           "size and a negative surface weight are refused naming them\n");
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    run(cmd, &r);
    cj_cli_result_free(&r);
    printf(
        "fit: interpolation through 50 points (eval --curve back at the chord parameters: %.3g), "
        "approximation within 1e-3 from stdin with %d control points (%.3g), 8 bad inputs and 5 "
        "bad curve files refused naming the input, a NURBS quarter circle evaluated on the "
        "circle (%.3g)\n",
        dev_i, m, dev_a, worst);
    if (failures) {
        printf("%d failure(s)\n", failures);
        return 1;
    }
    printf("test_cli_fit: all checks passed\n");
    return 0;
}

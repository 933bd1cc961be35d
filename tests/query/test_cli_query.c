/* Contract of `casteljau intersect` and `casteljau nearest`: text answers on a known document,
 * composition through stdin/stdout (intersect | intersect, intersect | plot), and bad input
 * refused with exit status 2 and one line naming it. */
#include "cli_run.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int failures = 0;
#define CHECK(cond, ...)                                                                           \
    do {                                                                                           \
        if (!(cond)) {                                                                             \
            ++failures;                                                                            \
            printf("FAIL %s:%d: ", __FILE__, __LINE__);                                            \
            printf(__VA_ARGS__);                                                                   \
            printf("\n");                                                                          \
        }                                                                                          \
    } while (0)

static int count_lines(const char *s, const char *prefix) {
    int n = 0;
    for (const char *p = s; p && *p;) {
        if (!strncmp(p, prefix, strlen(prefix))) ++n;
        p = strchr(p, '\n');
        if (p) ++p;
    }
    return n;
}

static int run(const char *cmd, cj_cli_result *r) {
    int rc = cj_cli_shell(cmd, r);
    CHECK(rc == 0, "could not run: %s", cmd);
    return rc;
}

int main(void) {
    const char *exe = CJ_CLI, *doc = CJ_QUERY_DOC;
    char cmd[2048];
    cj_cli_result r;
    int checks = 0;

    snprintf(cmd, sizeof cmd, "%s intersect --self --text %s", exe, doc);
    if (!run(cmd, &r)) {
        CHECK(r.status == 0, "intersect status %d: %s", r.status, r.err);
        CHECK(count_lines(r.out, "crossing ") == 10, "10 crossings expected:\n%s", r.out);
        CHECK(strstr(r.out, "crossing 1 3 1 1 1 0 0 0 ") != NULL, "the exact joint:\n%s", r.out);
        CHECK(strstr(r.out, "crossing 2 2 0.1726731646460") != NULL, "the loop:\n%s", r.out);
        cj_cli_result_free(&r);
        checks += 4;
    }
    /* the output document is a valid input: the same 9 crossings between pairs */
    snprintf(cmd, sizeof cmd, "%s intersect %s | %s intersect --text -", exe, doc, exe);
    if (!run(cmd, &r)) {
        CHECK(r.status == 0 && count_lines(r.out, "crossing ") == 9, "composed: %d\n%s%s", r.status,
              r.out, r.err);
        cj_cli_result_free(&r);
        ++checks;
    }
#ifdef CJ_HAVE_PLOT
    snprintf(cmd, sizeof cmd, "%s intersect --self %s | %s plot - -o %s/query_cli.png", exe, doc,
             exe, CJ_TMP_DIR);
    if (!run(cmd, &r)) {
        CHECK(r.status == 0, "intersect | plot: %d %s", r.status, r.err);
        cj_cli_result_free(&r);
        ++checks;
    }
#endif
    snprintf(cmd, sizeof cmd, "%s nearest --point 1.5,1.2 --text < %s", exe, doc);
    if (!run(cmd, &r)) {
        CHECK(r.status == 0 && count_lines(r.out, "nearest 2 0.259366390378") == 1 &&
                  strstr(r.out, " 0.1371921588667") != NULL,
              "nearest: %d\n%s%s", r.status, r.out, r.err);
        cj_cli_result_free(&r);
        ++checks;
    }
    snprintf(cmd, sizeof cmd, "%s offset --distance 0.15 --tol 1e-5 --text %s", exe, doc);
    if (!run(cmd, &r)) {
        CHECK(r.status == 0 && count_lines(r.out, "deviation ") == 4 &&
                  strstr(r.out, "deviation 2 ") != NULL,
              "offset: %d\n%s%s", r.status, r.out, r.err);
        for (const char *p = strstr(r.out, "deviation "); p; p = strstr(p + 1, "deviation ")) {
            int item, np, cusps;
            double dev;
            CHECK(sscanf(p, "deviation %d %d %lf %d", &item, &np, &dev, &cusps) == 4 && np > 0 &&
                      dev <= 1e-5,
                  "offset deviation line: %.60s", p);
        }
        cj_cli_result_free(&r);
        ++checks;
    }
#ifdef CJ_HAVE_PLOT
    snprintf(cmd, sizeof cmd, "%s offset --distance -0.2 %s | %s plot - -o %s/query_off.png", exe,
             doc, exe, CJ_TMP_DIR);
    if (!run(cmd, &r)) {
        CHECK(r.status == 0, "offset | plot: %d %s", r.status, r.err);
        cj_cli_result_free(&r);
        ++checks;
    }
#endif
    /* bad input: status 2 and one line naming what is wrong */
    const struct {
        const char *json, *args, *needle;
    } bad[] = {
        {"{\"items\":[{\"type\":\"bezier\",\"points\":[[0,0],[1,1]],\"weights\":[1,0]}]}",
         "intersect --self", "-:1: items[0].weights[1] must be > 0, not 0"},
        {"{\"items\":[{\"type\":\"bezier\",\"points\":[[1,1],[1,1]]},"
         "{\"type\":\"bezier\",\"points\":[[0,0],[1,1]]}]}",
         "intersect", "all 2 control points coincide"},
        {"{\"items\":[{\"type\":\"bezier\",\"points\":[[0,0],[1,1]]}]}",
         "intersect --self --tol 1e-30", "tol 1e-30 is below what doubles resolve"},
        {"{\"items\":[{\"type\":\"bezier\",\"points\":[[0,0],[1,\"x\"]]}]}", "intersect",
         "-:1: items[0].points[1][1] must be a number, not a string"},
        {"{\"items\":[{\"type\":\"bezier\",\"points\":[[0,0],[1,1]]}]}", "nearest",
         "missing --point"},
        {"{\"items\": [", "intersect", "JSON syntax error"},
        {"{\"items\":[{\"type\":\"bezier\",\"points\":[[0,0],[1,1]]}]}", "offset",
         "missing --distance"},
        {"{\"items\":[{\"type\":\"bezier\",\"points\":[[0,0],[0,0],[1,1],[2,0]]}]}",
         "offset --distance 0.1", "t = 0"},
        {"{\"items\":[{\"type\":\"bezier\",\"points\":[[0,0],[1,1]]}]}", "intersect --line 0,0,0,0",
         "direction"},
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; ++i) {
        snprintf(cmd, sizeof cmd, "printf '%%s' '%s' | %s %s", bad[i].json, exe, bad[i].args);
        if (run(cmd, &r)) continue;
        CHECK(r.status == 2 && strstr(r.err, bad[i].needle) && count_lines(r.err, "") == 1 &&
                  r.out_len == 0,
              "bad input %zu: status %d, stderr '%s'", i, r.status, r.err);
        cj_cli_result_free(&r);
        ++checks;
    }
    /* the document is written by the writing kit: a number read in and written back keeps its
     * shortest form (cJSON's own printer gives 0.79999999999999993), the added items too */
    snprintf(cmd, sizeof cmd,
             "printf '%%s' '{\"items\":[{\"type\":\"bezier\",\"points\":[[0,0],[1,"
             "0.7999999999999999]]},{\"type\":\"bezier\",\"points\":[[0,1],[1,0]]}]}' | %s "
             "intersect",
             exe);
    if (!run(cmd, &r)) {
        CHECK(r.status == 0 && strstr(r.out, "0.7999999999999999") &&
                  !strstr(r.out, "0.79999999999999993") && strstr(r.out, "\"radius\":\t5"),
              "shortest numbers: %d\n%s%s", r.status, r.out, r.err);
        cj_cli_result_free(&r);
        ++checks;
    }
    /* the plot reader takes bezier items to degree 255, the queries to 48: a bezier of 50
     * points is read, then refused by the query naming the limit */
    char many[1400] = "{\"items\":[{\"type\":\"bezier\",\"points\":[";
    for (int i = 0; i < 50; ++i)
        snprintf(many + strlen(many), sizeof many - strlen(many), "%s[%d,%d]", i ? "," : "", i,
                 i % 3);
    strcat(many, "]}]}");
    snprintf(cmd, sizeof cmd, "printf '%%s' '%s' | %s intersect --self", many, exe);
    if (!run(cmd, &r)) {
        CHECK(
            r.status == 2 &&
                strstr(r.err, "-:1: items[0].points has 50 points: the queries take degree <= 48"),
            "degree 49: %d %s", r.status, r.err);
        cj_cli_result_free(&r);
        ++checks;
    }
    printf("test_cli_query: %d checks (text answers, composition through pipes, %zu bad inputs "
           "refused naming the input, numbers written shortest): %s\n",
           checks, sizeof bad / sizeof bad[0], failures ? "FAILED" : "passed");
    return failures ? 1 : 0;
}

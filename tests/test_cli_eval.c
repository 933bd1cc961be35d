/* Contract test of `casteljau eval`, run as a child process (path in argv[1]):
 * exact reading of decimal and C99 hex-float input, %.17g output, one line per parameter in
 * order, dimensions 1-4, every method, --derivative (K > degree gives zeros), the --bound
 * format and the validity of the printed bounds against the exact MPFR oracle, and the
 * bad-input contract: one line on stderr, nothing on stdout, exit status 2. */
#define _POSIX_C_SOURCE 200809L
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "casteljau/bezier.h"
#include "cli_run.h"
#include "oracle_mpfr.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static const char *exe;
static int runs;

typedef struct result {
    int status; /* exit status, or -1 if the child did not exit normally */
    char out[8192];
    char err[4096];
} result;

/* Runs `casteljau eval <args...>` (args NULL-terminated) and captures both streams. */
static void run_eval(result *r, const char *const *args) {
    assert_int_equal(cj_cli_run_into(exe, "eval", args, &r->status, r->out, sizeof r->out, r->err,
                                     sizeof r->err),
                     0);
    ++runs;
}

/* Splits the output into lines of whitespace-separated tokens. Returns the number of lines;
 * tok[l][j] points into buf (modified). */
static int split_lines(char *buf, char *tok[][20], int ntok[], int maxlines) {
    int nl = 0;
    char *save = NULL;
    for (char *line = strtok_r(buf, "\n", &save); line; line = strtok_r(NULL, "\n", &save)) {
        assert_true(nl < maxlines);
        char *s2 = NULL;
        ntok[nl] = 0;
        for (char *t = strtok_r(line, " ", &s2); t; t = strtok_r(NULL, " ", &s2)) {
            assert_true(ntok[nl] < 20);
            tok[nl][ntok[nl]++] = t;
        }
        ++nl;
    }
    return nl;
}

static void expect_ok(const result *r, const char *what) {
    if (r->status != 0 || r->err[0] != '\0')
        fail_msg("%s: exit status %d, stderr '%s'", what, r->status, r->err);
}

/* A token must be exactly the %.17g rendering of v. */
static void expect_token(const char *tok, double v, const char *what) {
    char want[64];
    snprintf(want, sizeof want, "%.17g", v);
    if (strcmp(tok, want) != 0) fail_msg("%s: printed '%s', expected '%s'", what, tok, want);
}

static void test_exact_input_and_format(void **state) {
    (void)state;
    /* A degree-0 curve is returned unchanged by every method: the output shows exactly how
     * the input was read. 0.1 and its hex spelling must give the same double. */
    const char *const methods[] = {"decasteljau", "bernstein", "horner", "compensated"};
    for (int m = 0; m < 4; ++m) {
        result r;
        run_eval(&r,
                 (const char *const[]){"--method", methods[m], "--points",
                                       "0.1,0x1.999999999999ap-4,-2.5e-3,0x1p-1074", "0.5", NULL});
        expect_ok(&r, "degree 0");
        char *tok[4][20];
        int nt[4];
        assert_int_equal(split_lines(r.out, tok, nt, 4), 1);
        assert_int_equal(nt[0], 4);
        expect_token(tok[0][0], 0.1, "decimal 0.1");
        expect_token(tok[0][1], 0.1, "hex 0x1.999999999999ap-4");
        expect_token(tok[0][2], -2.5e-3, "decimal -2.5e-3");
        expect_token(tok[0][3], 0x1p-1074, "hex subnormal");
    }
    /* Parameters read exactly too: the line 0 -> 1 at t gives t for de Casteljau. */
    result r;
    run_eval(&r,
             (const char *const[]){"--points", "0;1", "0.1", "0x1.8p-3", "1e-300", "0.3", NULL});
    expect_ok(&r, "line");
    char *tok[8][20];
    int nt[8];
    assert_int_equal(split_lines(r.out, tok, nt, 8), 4);
    expect_token(tok[0][0], 0.1, "t = 0.1");
    expect_token(tok[1][0], 0x1.8p-3, "t = 0x1.8p-3");
    expect_token(tok[2][0], 1e-300, "t = 1e-300");
    expect_token(tok[3][0], 0.3, "t = 0.3");
    printf("exact decimal/hex input and %%.17g output: checked for 4 methods\n");
}

/* Random-ish curves of dimension 1..4, several parameters, every method, with --bound: each
 * printed value must equal the library's result bit for bit (the tool adds nothing), lines
 * come in parameter order, and each printed bound must hold against the exact value. */
static void test_values_bounds_all_methods(void **state) {
    (void)state;
    const char *const methods[] = {"decasteljau", "bernstein", "horner", "compensated"};
    const char *const pts_text[] = {
        "0.3;-1.25;2;0x1.8p-2;7",
        "0,0;1,2;2,0",
        "1e8,-1e8,3;1e8,1e8,-2.5;0.125,7,1;-3,3,0.1",
        "1,2,3,4;-4,3,-2,1;0.5,0.25,0.125,0.0625",
    };
    const double pts_val[][20] = {
        {0.3, -1.25, 2, 0x1.8p-2, 7},
        {0, 0, 1, 2, 2, 0},
        {1e8, -1e8, 3, 1e8, 1e8, -2.5, 0.125, 7, 1, -3, 3, 0.1},
        {1, 2, 3, 4, -4, 3, -2, 1, 0.5, 0.25, 0.125, 0.0625},
    };
    const int degree[] = {4, 2, 3, 2}, dims[] = {1, 2, 3, 4};
    const char *const ts_text[] = {"0", "0.25", "0x1p-1", "0.7", "1", "0.999", "1e-7"};
    const int nts = 7;
    mpfr_t val;
    mpfr_init2(val, 256);
    int checked = 0;
    for (int cv = 0; cv < 4; ++cv)
        for (int m = 0; m < 4; ++m) {
            const char *args[20] = {"--method", methods[m], "--bound", "--points", pts_text[cv]};
            int na = 5;
            for (int j = 0; j < nts; ++j) args[na++] = ts_text[j];
            args[na] = NULL;
            result r;
            run_eval(&r, args);
            expect_ok(&r, pts_text[cv]);
            char *tok[10][20];
            int nt[10];
            const int d = dims[cv];
            assert_int_equal(split_lines(r.out, tok, nt, 10), nts);
            const cj_bezier c = cj_bezier_view(degree[cv], d, pts_val[cv]);
            for (int j = 0; j < nts; ++j) {
                assert_int_equal(nt[j], 2 * d + 1);
                assert_string_equal(tok[j][d], "|");
                const double t = strtod(ts_text[j], NULL);
                double v[4];
                assert_int_equal(cj_bezier_eval(&c, (cj_eval_method)m, t, v), CJ_OK);
                for (int k = 0; k < d; ++k) {
                    expect_token(tok[j][k], v[k], "value vs library");
                    const double bound = strtod(tok[j][d + 1 + k], NULL);
                    cj_oracle_bezier(pts_val[cv], degree[cv], d, k, t, 1 << 14, val, NULL);
                    const double err = cj_oracle_abs_error(v[k], val);
                    if (!(err <= bound))
                        fail_msg("%s, method %s, t = %s, coordinate %d: error %.3e > printed "
                                 "bound %.3e",
                                 pts_text[cv], methods[m], ts_text[j], k, err, bound);
                    ++checked;
                }
            }
        }
    mpfr_clear(val);
    printf("values of dims 1-4, 4 methods, %d coordinates: equal to the library, in order, "
           "printed bounds hold against the exact value\n",
           checked);
}

/* --derivative K: values against the exact derivative (hodograph points formed exactly in
 * MPFR-free integer arithmetic: the test curve has small integer points), the bound holds, and
 * K > degree prints zeros. */
static void test_derivatives(void **state) {
    (void)state;
    /* Cubic (0,0) (1,3) (4,-1) (5,2): first hodograph 3*(1,3),(3,-4),(1,3); second 6*(2,-7),
     * (-2,7); third 6*(-4,14). Points of degree 3 - K with exact integer coordinates. */
    const double h[4][8] = {
        {0, 0, 1, 3, 4, -1, 5, 2}, {3, 9, 9, -12, 3, 9}, {12, -42, -12, 42}, {-24, 84}};
    const char *const K[] = {"0", "1", "2", "3"};
    const char *const methods[] = {"decasteljau", "bernstein", "horner", "compensated"};
    mpfr_t val;
    mpfr_init2(val, 256);
    for (int k = 0; k < 4; ++k)
        for (int m = 0; m < 4; ++m) {
            result r;
            run_eval(&r,
                     (const char *const[]){"--method", methods[m], "--derivative", K[k], "--bound",
                                           "--points", "0,0;1,3;4,-1;5,2", "0.3", "0.8", NULL});
            expect_ok(&r, "derivative");
            char *tok[4][20];
            int nt[4];
            assert_int_equal(split_lines(r.out, tok, nt, 4), 2);
            const double ts[2] = {0.3, 0.8};
            for (int j = 0; j < 2; ++j) {
                assert_int_equal(nt[j], 5);
                for (int c = 0; c < 2; ++c) {
                    cj_oracle_bezier(h[k], 3 - k, 2, c, ts[j], 1 << 12, val, NULL);
                    const double v = strtod(tok[j][c], NULL), b = strtod(tok[j][3 + c], NULL);
                    const double err = cj_oracle_abs_error(v, val);
                    if (!(err <= b))
                        fail_msg("derivative %d, method %s, t = %g, coordinate %d: %s is off "
                                 "by %.3e > bound %.3e",
                                 k, methods[m], ts[j], c, tok[j][c], err, b);
                }
            }
        }
    mpfr_clear(val);
    /* K > degree: the zero curve, exactly. */
    result r;
    run_eval(&r, (const char *const[]){"--derivative", "4", "--bound", "--points",
                                       "0,0;1,3;4,-1;5,2", "0.3", "7", NULL});
    expect_ok(&r, "derivative 4 of a cubic");
    assert_string_equal(r.out, "0 0 | 0 0\n0 0 | 0 0\n");
    run_eval(&r, (const char *const[]){"--derivative", "256", "--points", "1;2", "0.5", NULL});
    expect_ok(&r, "derivative 256 of a line");
    assert_string_equal(r.out, "0\n");
    /* A rounding case: the hodograph of 0.1-ish points is inexact, the bound still holds. */
    run_eval(&r, (const char *const[]){"--derivative", "2", "--bound", "--points",
                                       "0.1;0.7;-0.3;0.9;0.2", "0.37", NULL});
    expect_ok(&r, "derivative 2 of a quartic");
    {
        const double b[5] = {0.1, 0.7, -0.3, 0.9, 0.2};
        mpfr_t x[5], tt, acc;
        for (int i = 0; i < 5; ++i) mpfr_init2(x[i], 4096), mpfr_set_d(x[i], b[i], MPFR_RNDN);
        /* exact second hodograph: 12 (b_{i+2} - 2 b_{i+1} + b_i), then exact de Casteljau */
        for (int i = 0; i < 3; ++i) {
            mpfr_sub(x[i], x[i + 2], x[i + 1], MPFR_RNDN);
            mpfr_sub(x[i], x[i], x[i + 1], MPFR_RNDN);
            mpfr_add_d(x[i], x[i], b[i], MPFR_RNDN);
            mpfr_mul_ui(x[i], x[i], 12, MPFR_RNDN);
        }
        mpfr_inits2(4096, tt, acc, (mpfr_ptr)0);
        mpfr_set_d(tt, 0.37, MPFR_RNDN);
        for (int lv = 2; lv > 0; --lv)
            for (int i = 0; i < lv; ++i) {
                mpfr_sub(acc, x[i + 1], x[i], MPFR_RNDN);
                mpfr_mul(acc, acc, tt, MPFR_RNDN);
                mpfr_add(x[i], x[i], acc, MPFR_RNDN);
            }
        char *tok[2][20];
        int nt[2];
        assert_int_equal(split_lines(r.out, tok, nt, 2), 1);
        assert_int_equal(nt[0], 3);
        const double err = cj_oracle_abs_error(strtod(tok[0][0], NULL), x[0]);
        const double bnd = strtod(tok[0][2], NULL);
        if (!(err <= bnd && bnd > 0))
            fail_msg("second derivative: error %.3e, bound %.3e", err, bnd);
        for (int i = 0; i < 5; ++i) mpfr_clear(x[i]);
        mpfr_clears(tt, acc, (mpfr_ptr)0);
    }
    printf("--derivative 0..3 of a cubic for 4 methods within the printed bounds; K > degree "
           "prints zeros\n");
}

static void expect_usage_error(const char *const *args, const char *what) {
    result r;
    run_eval(&r, args);
    if (r.status != 2) fail_msg("%s: exit status %d, expected 2", what, r.status);
    if (r.out[0] != '\0') fail_msg("%s: stdout not empty: '%s'", what, r.out);
    const size_t len = strlen(r.err);
    if (len < 2 || r.err[len - 1] != '\n' || strchr(r.err, '\n') != r.err + len - 1)
        fail_msg("%s: stderr is not exactly one line: '%s'", what, r.err);
    if (strncmp(r.err, "casteljau eval: ", 16) != 0)
        fail_msg("%s: message does not start with 'casteljau eval: ': '%s'", what, r.err);
}

static void test_bad_input(void **state) {
    (void)state;
    static const struct {
        const char *what;
        const char *args[8];
    } cases[] = {
        {"bad number", {"--points", "0,0;1,2x;2,0", "0.5"}},
        {"empty coordinate", {"--points", "0,0;1,;2,0", "0.5"}},
        {"NaN coordinate", {"--points", "0,0;nan,1", "0.5"}},
        {"inf coordinate", {"--points", "0,0;inf,1", "0.5"}},
        {"overflowing coordinate", {"--points", "0,0;1e999,1", "0.5"}},
        {"NaN parameter", {"--points", "0,0;1,1", "0.5", "nan"}},
        {"infinite parameter", {"--points", "0,0;1,1", "-infinity"}},
        {"bad parameter", {"--points", "0,0;1,1", "0.5", "abc"}},
        {"overflowing extrapolation", {"--points", "1,2;3,-4;5,1", "0.5", "1e200"}},
        {"mismatched dimension", {"--points", "0,0;1,2,3;2,0", "0.5"}},
        {"too many coordinates", {"--points", "1,2,3,4,5,6,7,8,9", "0.5"}},
        {"empty points", {"--points", "", "0.5"}},
        {"only a separator", {"--points", ";", "0.5"}},
        {"missing --points", {"0.5"}},
        {"--points without value", {"--points"}},
        {"unknown method", {"--method", "newton", "--points", "0;1", "0.5"}},
        {"--method without value", {"--points", "0;1", "--method"}},
        {"unknown option", {"--frobnicate", "--points", "0;1", "0.5"}},
        {"unknown short option", {"-x", "--points", "0;1", "0.5"}},
        {"flag given a value", {"--bound=yes", "--points", "0;1", "0.5"}},
        {"no T", {"--points", "0;1"}},
        {"negative derivative", {"--derivative", "-1", "--points", "0;1", "0.5"}},
        {"non-numeric derivative", {"--derivative", "two", "--points", "0;1", "0.5"}},
        {"degree above Bernstein's limit",
         {"--method", "bernstein", "--points",
          "0;1;2;3;4;5;6;7;8;9;0;1;2;3;4;5;6;7;8;9;0;1;2;3;4;5;6;7;8;9;0;1;2;3;4;5;6;7;8;9;0;1;2;"
          "3;4;5;6;7;8;9;0;1;2;3;4;5;6;7",
          "0.5"}},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i)
        expect_usage_error(cases[i].args, cases[i].what);
    result r;
    run_eval(&r, (const char *const[]){"--help", NULL});
    assert_int_equal(r.status, 0);
    assert_non_null(strstr(r.out, "usage: casteljau eval"));
    printf("%zu kinds of bad input: exit 2, one line on stderr, nothing on stdout\n",
           sizeof cases / sizeof cases[0]);
}

int main(int argc, char **argv) {
    if (argc < 2) {
        fprintf(stderr, "usage: test_cli_eval /path/to/casteljau\n");
        return 2;
    }
    exe = argv[1];
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_exact_input_and_format),
        cmocka_unit_test(test_values_bounds_all_methods),
        cmocka_unit_test(test_derivatives),
        cmocka_unit_test(test_bad_input),
    };
    const int rc = cmocka_run_group_tests(tests, NULL, NULL);
    printf("(%d runs of %s)\n", runs, exe);
    return rc;
}

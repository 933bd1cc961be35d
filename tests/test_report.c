#define _POSIX_C_SOURCE 200809L /* mkdtemp */
/* `casteljau report --quick` builds (so the report never rots): the files exist, the PNGs are
 * PNGs and the page links them, every number of data.tsv is finite where it must be, and the
 * figures are sane: measured evaluation errors within the proven bounds (de Casteljau,
 * compensated), flattening and tessellation deviations within bounds within the tolerance, segment
 * counts at least ~the continuous optimum, positive times, every section with a Pareto front, and
 * callgrind counts repeating within 0.5 % when valgrind ran. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "test_report.h"

#if defined(__SANITIZE_ADDRESS__)
#define TEST_REPORT_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define TEST_REPORT_ASAN 1
#endif
#endif
#ifndef TEST_REPORT_ASAN
#define TEST_REPORT_ASAN 0
#endif

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>

static char dir[256];

static char *slurp(const char *name, size_t *len) {
    char path[512];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    FILE *f = fopen(path, "rb");
    if (!f) return NULL;
    fseek(f, 0, SEEK_END);
    const long n = ftell(f);
    fseek(f, 0, SEEK_SET);
    char *b = malloc((size_t)n + 1);
    assert_non_null(b);
    assert_int_equal(fread(b, 1, (size_t)n, f), (size_t)n);
    b[n] = 0;
    fclose(f);
    if (len) *len = (size_t)n;
    return b;
}

static int count_of(const char *s, const char *needle) {
    int n = 0;
    for (const char *p = s; (p = strstr(p, needle)); p += strlen(needle)) n++;
    return n;
}

static void test_quick_report(void **state) {
    (void)state;
    snprintf(dir, sizeof dir, "/tmp/cj_report_XXXXXX");
    assert_non_null(mkdtemp(dir));
    char cmd[1024];
    snprintf(cmd, sizeof cmd, "'%s' report --quick -o '%s' >/dev/null", CJ_CLI, dir);
    assert_int_equal(system(cmd), 0);

    char *html = slurp("index.html", NULL), *md = slurp("summary.md", NULL);
    assert_non_null(html);
    assert_non_null(md);
    assert_non_null(strstr(html, "</html>"));
    /* every chart the page shows is a PNG next to it, and summary.md links it too */
    const int imgs = count_of(html, "<img ");
    assert_true(imgs >= 9);
    /* one table per section (the reproducibility note has none) */
    assert_int_equal(count_of(html, "<table>"),
                     count_of(html, "<h2>") - count_of(html, "<h2>Reproducibility</h2>"));
    const char *pngs[6] = {"eval_cond0.png", "eval_cond1.png", "flatten_0.png",
                           "flatten_1.png",  "tess.png",       "arclen.png"};
    for (int i = 0; i < 6; ++i) {
        char ref[64];
        snprintf(ref, sizeof ref, "src=\"%s\"", pngs[i]);
        assert_non_null(strstr(html, ref));
    }
    int pngs_seen = 0;
    for (const char *p = html; (p = strstr(p, "<img src=\"")); ++pngs_seen) {
        p += 10;
        const char *q = strchr(p, '"');
        assert_non_null(q);
        char name[128];
        assert_true(q - p > 4 && q - p < (long)sizeof name);
        memcpy(name, p, (size_t)(q - p));
        name[q - p] = 0;
        size_t n = 0;
        char *png = slurp(name, &n);
        if (!png) fail_msg("the page shows %s, which is not in the folder", name);
        assert_true(n > 2000 && !memcmp(png, "\x89PNG\r\n\x1a\n", 8));
        assert_non_null(strstr(md, name));
        free(png);
    }
    assert_int_equal(pngs_seen, imgs);

    char *tsv = slurp("data.tsv", NULL);
    assert_non_null(tsv);
    int rows = 0, tess_rows = 0, eval_rows = 0, flat_rows = 0, fronts_eval = 0, fronts_flat = 0;
    int arc_rows = 0, fronts_arc = 0, interp_rows = 0, contour_rows = 0, ode_rows = 0;
    int render_rows = 0, trace_rows = 0, tess_surf[4] = {0, 0, 0, 0}, arc_cubic_rows = 0;
    int contour_ellipse_rows = 0, path_rows = 0;
    double path_err[3] = {0, 0, 0}; /* the path tracer's RMSE at 1, 4, 16 spp */
    /* the arc length's chord sum: set x (N = 16, N = 4096) */
    double chord_err[2][2] = {{0, 0}, {0, 0}};
    double ode_err[4][2] = {{0}}; /* integrator x (N = 32, N = 256) */
    double equi_err[2] = {0, 0};  /* equispaced: error at the lowest and the highest degree */
    for (char *line = strtok(tsv, "\n"); line; line = strtok(NULL, "\n")) {
        if (!strncmp(line, "section", 7)) continue;
        char *f[12] = {0};
        int nf = 0;
        for (char *p = line; nf < 12; ++nf) {
            f[nf] = p;
            char *tab = strchr(p, '\t');
            if (!tab) {
                nf++;
                break;
            }
            *tab = 0;
            p = tab + 1;
        }
        assert_int_equal(nf, 12);
        rows++;
        const double ns = strtod(f[7], NULL);
        assert_true(isfinite(ns) && ns > 0.1 && ns < 1e12); /* up to 1000 s */
        const int front = !strcmp(f[11], "front");
        if (!strcmp(f[0], "eval")) {
            eval_rows++;
            fronts_eval += front;
            const double K = strtod(f[3], NULL), emax = strtod(f[4], NULL),
                         emean = strtod(f[5], NULL), bound = strtod(f[6], NULL);
            assert_true(isfinite(K) && K >= 1.0);
            assert_true(isfinite(emax) && emax >= emean && emean >= 0);
            if (!strcmp(f[1], "de Casteljau") || !strcmp(f[1], "compensated")) {
                assert_true(isfinite(bound));
                if (!(emax <= bound))
                    fail_msg("%s at degree %s, cond %g: error %g u > bound %g u", f[1], f[2], K,
                             emax, bound);
            }
        } else if (!strcmp(f[0], "tess")) {
            /* every surface (teapot; sphere, torus, cylinder measured exactly against the true
             * surface): deviation <= bound <= tol, at least 2 triangles per patch */
            tess_rows++;
            const double tol = strtod(f[2], NULL), dev = strtod(f[4], NULL),
                         bound = strtod(f[6], NULL), tris = strtod(f[10], NULL);
            if (!(dev > 0 && dev <= bound && bound <= tol * (1 + 1e-12)))
                fail_msg("tessellation %s at tol %g: deviation %g, bound %g", f[1], tol, dev,
                         bound);
            static const char *const SURF[4] = {"teapot", "sphere", "torus", "cylinder"};
            static const int PATCHES[4] = {32, 8, 16, 4};
            int s = 0;
            while (s < 4 && !strstr(f[1], SURF[s])) s++;
            assert_true(s < 4 && (!strncmp(f[1], "uniform ", 8) || !strncmp(f[1], "adaptive ", 9)));
            tess_surf[s]++;
            assert_true(tris >= 2 * PATCHES[s]);
        } else if (!strcmp(f[0], "ode")) {
            ode_rows++;
            const int N = atoi(f[2]);
            const double emax = strtod(f[4], NULL);
            assert_true(isfinite(emax) && emax > 0 && (N == 32 || N == 256));
            static const char *const INT[4] = {"explicit_euler", "symplectic_euler", "rk4",
                                               "implicit_euler"};
            for (int m = 0; m < 4; ++m)
                if (!strcmp(f[1], INT[m])) ode_err[m][N == 256] = emax;
        } else if (!strcmp(f[0], "contour")) {
            /* the exact distance polyline - circle or ellipse within the tolerance asked for */
            contour_rows++;
            contour_ellipse_rows += strstr(f[1], "(ellipse)") != NULL; /* exact, by Eberly */
            const double tol = strtod(f[2], NULL), dev = strtod(f[4], NULL),
                         pts = strtod(f[10], NULL);
            assert_true(isfinite(dev) && dev > 0 && pts >= 8);
            if (!(dev <= tol)) fail_msg("contour %s at tol %g: deviation %g > tol", f[1], tol, dev);
        } else if (!strcmp(f[0], "interp")) {
            /* Chebyshev: within the Bernstein-ellipse bound; equispaced: Runge's phenomenon */
            interp_rows++;
            const int deg = atoi(f[2]);
            const double K = strtod(f[3], NULL), emax = strtod(f[4], NULL),
                         bound = strtod(f[6], NULL);
            assert_true(isfinite(K) && K >= 1.0 && isfinite(emax) && emax > 0);
            if (!strcmp(f[1], "Chebyshev")) {
                if (!(emax <= bound))
                    fail_msg("Chebyshev interpolation at degree %d: error %g > bound %g", deg, emax,
                             bound);
            } else {
                assert_string_equal(f[1], "equispaced");
                equi_err[deg > 4] = emax;
            }
        } else if (!strcmp(f[0], "arclen")) {
            /* adaptive: the error against the closed form within the tolerance asked for;
             * chord sum: below the second-order bound L^2 ... loosely, error > 0 and < 1 */
            arc_rows++;
            fronts_arc += front;
            const double param = strtod(f[2], NULL), emax = strtod(f[4], NULL),
                         emean = strtod(f[5], NULL);
            assert_true(isfinite(emax) && emax >= emean && emean >= 0);
            /* both sets: parabolas against the closed form, "(cubics)" against the MPFR
             * quadrature; the chord sum of second order (N = 16 -> 4096: error / 65536) */
            const int cubic = strstr(f[1], "(cubics)") != NULL;
            arc_cubic_rows += cubic;
            if (!strncmp(f[1], "chord sum", 9)) {
                assert_true(emax > 0 && emax < 1);
                if (param == 16 || param == 4096) chord_err[cubic][param == 4096] = emax;
            } else {
                const double est = strtod(f[6], NULL);
                assert_true(isfinite(est) && est >= 0);
                if (!(emax <= param)) fail_msg("arc length at tol %g: error %g > tol", param, emax);
            }
        } else if (!strcmp(f[0], "render")) {
            render_rows++;
            report_check_render_row(f);
        } else if (!strcmp(f[0], "trace")) {
            trace_rows++;
            report_check_trace_row(f);
        } else if (!strcmp(f[0], "path")) { /* report_path.c: RMSE, reference noise, corrected */
            const int spp = atoi(f[2]);
            const double e = strtod(f[4], NULL), sref = strtod(f[6], NULL),
                         corr = strtod(f[10], NULL);
            assert_true(isfinite(e) && e > 0 && sref > 0 && sref < 0.5 * e);
            assert_true(corr >= 0 && corr <= e);
            assert_true(spp == 1 || spp == 4 || spp == 16);
            path_err[spp == 1 ? 0 : (spp == 4 ? 1 : 2)] = corr;
            path_rows++;
        } else {
            assert_string_equal(f[0], "flatten");
            flat_rows++;
            fronts_flat += front;
            const double tol = strtod(f[2], NULL), dev = strtod(f[4], NULL),
                         bound = strtod(f[6], NULL), ratio = strtod(f[10], NULL);
            assert_true(dev > 0 && dev <= tol && bound <= tol * (1 + 1e-12) &&
                        bound >= dev * 0.999);
            assert_true(ratio >= 0.9 && ratio < 10);
        }
    }
    assert_int_equal(eval_rows, 4 * 2 * 3); /* quick: 4 methods x 2 degrees x 3 conditions */
    assert_int_equal(flat_rows, 3 * 3);     /* 3 methods x 3 tolerances */
    assert_int_equal(tess_rows, 10);        /* 2 methods x (teapot 2 tols, 3 models 1) */
    assert_int_equal(arc_rows, 4 * 3);      /* 2 sets x adaptive/chord sum x 3 tols or N */
    assert_int_equal(interp_rows, 2 * 3);   /* equispaced/Chebyshev x degrees 4, 12, 24 */
    assert_int_equal(contour_rows, 6);      /* circle: grids 8, 64, ellipse: 64; x 2 tols */
    assert_int_equal(ode_rows, 4 * 2);      /* 4 integrators x N = 32, 256 */
    assert_int_equal(tess_surf[0], 2 * 2);
    assert_int_equal(arc_cubic_rows, 2 * 3);
    assert_int_equal(contour_ellipse_rows, 2);
    for (int set = 0; set < 2; ++set)
        if (!(chord_err[set][1] > 0 && chord_err[set][0] > 1000 * chord_err[set][1]))
            fail_msg("chord sum (set %d): error %g at N = 16, %g at N = 4096", set,
                     chord_err[set][0], chord_err[set][1]);
    for (int s = 1; s < 4; ++s) assert_int_equal(tess_surf[s], 2);
    /* the orders against the closed form: 8x smaller h gains 8^4 = 4096 for RK4 (>= 100
     * required), about 8 for the first-order methods (>= 4 required) */
    for (int m = 0; m < 4; ++m) {
        const double gain = ode_err[m][0] / ode_err[m][1];
        if (!(gain >= (m == 2 ? 100 : 4)))
            fail_msg("integrator %d: error only %g times smaller at N = 256 than at 32", m, gain);
    }
    assert_true(equi_err[1] > 10 * equi_err[0]); /* Runge: degree 24 far worse than 4 */
    /* the path tracer converges as spp^(-1/2): 16 spp between 0.2 and 0.3 of 1 spp's error
     * (1/4 expected; measured 0.238), and the page prints the slope */
    assert_int_equal(path_rows, 3);
    printf("path tracer: corrected RMSE %.4g, %.4g, %.4g at 1, 4, 16 spp (ratio %.3f)\n",
           path_err[0], path_err[1], path_err[2], path_err[2] / path_err[0]);
    assert_true(path_err[2] > 0.2 * path_err[0] && path_err[2] < 0.3 * path_err[0]);
    assert_non_null(strstr(md, "log-log slope"));
    assert_non_null(strstr(html, "src=\"path_convergence.png\""));
    report_check_render_end(html, md);
    report_check_trace_end(html, md);
    assert_true(fronts_eval >= 6 && fronts_flat >= 1 && fronts_arc >= 1);
    /* With valgrind installed (scripts/setup.sh installs it) the counts must have been taken,
     * except in a sanitizer build, which valgrind cannot run: then the page must say so. */
    const char *rep = strstr(md, "differ by ");
    const int have_valgrind = system("valgrind --version >/dev/null 2>&1") == 0;
    if (rep) {
        const double pct = strtod(rep + 10, NULL);
        assert_true(pct >= 0 && pct <= 0.5);
        printf("callgrind counts repeat within %.4f %%\n", pct);
    } else if (TEST_REPORT_ASAN) {
        if (have_valgrind) assert_non_null(strstr(md, "AddressSanitizer"));
        printf("sanitizer build: instruction counts not taken (the page says why)\n");
    } else {
        const char *why = strstr(md, "No instruction counts");
        if (have_valgrind)
            fail_msg("valgrind is installed but the report has no counts: %s",
                     why ? why : "and does not say why");
        printf("valgrind not available: instruction counts not checked\n");
    }
    printf("quick report in %s: index.html links %d PNGs, %d rows (%d eval, %d flatten, %d tess, "
           "%d arclen, %d interp, %d contour, %d ode, %d render, %d trace) finite; errors "
           "within the bounds, "
           "deviations, arc "
           "length errors and contour distances within tol, Chebyshev interpolation within its "
           "bound, integrator orders as expected, Pareto fronts present\n",
           dir, imgs, rows, eval_rows, flat_rows, tess_rows, arc_rows, interp_rows, contour_rows,
           ode_rows, render_rows, trace_rows);
    free(tsv);
    free(html);
    free(md);
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    assert_int_equal(system(cmd), 0);
}

/* The callgrind workloads the full report counts (the quick report does not run them; the
 * "SECTION:all" ones run every cell of a full table): each runs and exits 0, and a malformed
 * spec is refused with the usage status 2. */
static void test_workloads(void **state) {
    (void)state;
    static const char *const OK[] = {"arclen:0:1e-06",   "arclen:1:256:1",     "interp:0:12",
                                     "interp:1:24",      "contour:8:0.01",     "ode:2:256",
                                     "tess:2:0.01:1",    "tess:0:0.01:2",      "tess:3:0.01:3",
                                     "arclen:0:1e-09:1", "contour:16:1e-05:1", "arclen:all",
                                     "interp:all",       "contour:all",        "ode:all"};
    static const char *const BAD[] = {"arclen:2:1",      "interp:1:0", "contour:0:0.1",
                                      "contour:8:0.1:2", "ode:4:16",   "tess:0:0.01:4"};
    char cmd[1024];
    for (size_t i = 0; i < sizeof OK / sizeof *OK; ++i) {
        snprintf(cmd, sizeof cmd, "'%s' report --workload '%s' 2", CJ_CLI, OK[i]);
        if (system(cmd) != 0) fail_msg("workload %s failed", OK[i]);
    }
    for (size_t i = 0; i < sizeof BAD / sizeof *BAD; ++i) {
        snprintf(cmd, sizeof cmd, "'%s' report --workload '%s' 2 2>/dev/null", CJ_CLI, BAD[i]);
        const int st = system(cmd);
        if (!(st != -1 && WIFEXITED(st) && WEXITSTATUS(st) == 2))
            fail_msg("workload %s: status %d, want exit 2", BAD[i], st);
    }
    printf("workloads: %zu specs run (arclen, interp, contour, ode, each also on its whole full "
           "table, tess on the sphere, torus, cylinder), %zu malformed ones refused with status "
           "2\n",
           sizeof OK / sizeof *OK, sizeof BAD / sizeof *BAD);
}

int main(void) {
    const struct CMUnitTest tests[] = {cmocka_unit_test(test_quick_report),
                                       cmocka_unit_test(test_workloads)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}

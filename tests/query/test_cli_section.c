/* Contract of `casteljau section` and `casteljau nearest` on patches: the sphere octant cut at
 * z = 1/2 gives one open curve of cubic pieces on the circle of radius sqrt(3)/2 within the
 * reported deviation <= --tol; the teapot cut at z = 1.5 gives three closed curves (joined across
 * its patches), --json a plot document that plot draws; an OBJ of the lines is written; nearest
 * on the octant from its centre is certified at tol 1e-9; bad input is refused with exit status 2
 * and one line naming it. */
#include "check.h"
#include "cli_run.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define OCTANT                                                                                     \
    "--patch '1,0,0;1,1,0;0,1,0;1,0,1;1,1,1;0,1,1;0,0,1;0,0,1;0,0,1' --degree 2,2 --weights "      \
    "'1;0.70710678118654757;1;0.70710678118654757;0.5;0.70710678118654757;1;0.70710678118654757;"  \
    "1'"

static int count_prefix(const char *s, const char *prefix) {
    int n = 0;
    for (const char *p = s; p && *p;) {
        if (!strncmp(p, prefix, strlen(prefix))) ++n;
        p = strchr(p, '\n');
        if (p) ++p;
    }
    return n;
}

int main(void) {
    const char *exe = CJ_CLI;
    char cmd[2048];
    cj_cli_result r;
    int checks = 0;

    snprintf(cmd, sizeof cmd, "%s section --plane 0,0,1,0.5 --tol 0.01 -o %s/section.obj " OCTANT,
             exe, CJ_TMP_DIR);
    if (cj_cli_shell(cmd, &r) == 0) {
        CHECK(r.status == 0, "section status %d: %s", r.status, r.err);
        CHECK(count_prefix(r.out, "curve 0 open ") == 1, "one open curve:\n%.300s", r.out);
        /* every piece (12 numbers: 4 control points) sampled: on the circle of radius
         * sqrt(3)/2 at z = 1/2 within the reported deviation */
        double worst = 0, dev = -1;
        int pieces = 0;
        for (const char *p = r.out; p && *p;) {
            double B[12];
            if (sscanf(p, "%lf %lf %lf %lf %lf %lf %lf %lf %lf %lf %lf %lf", B, B + 1, B + 2, B + 3,
                       B + 4, B + 5, B + 6, B + 7, B + 8, B + 9, B + 10, B + 11) == 12) {
                for (int i = 0; i <= 16; ++i) {
                    double t = i / 16.0, s = 1 - t, x[3];
                    for (int k = 0; k < 3; ++k)
                        x[k] = s * s * s * B[k] + 3 * s * s * t * B[3 + k] +
                               3 * s * t * t * B[6 + k] + t * t * t * B[9 + k];
                    worst = fmax(worst, hypot(hypot(x[0], x[1]) - sqrt(0.75), x[2] - 0.5));
                }
                ++pieces;
            }
            const char *s = strstr(p, "deviation ");
            if (!strncmp(p, "section ", 8) && s) dev = atof(s + 10);
            p = strchr(p, '\n');
            if (p) ++p;
        }
        CHECK(pieces >= 1 && worst <= dev && dev > 0 && dev <= 0.01,
              "%d pieces, worst %g off the circle, deviation %g", pieces, worst, dev);
        cj_cli_result_free(&r);
        snprintf(cmd, sizeof cmd, "grep -c '^l ' %s/section.obj", CJ_TMP_DIR);
        if (cj_cli_shell(cmd, &r) == 0) {
            CHECK(r.status == 0 && atoi(r.out) == 1, "OBJ lines: %s", r.out);
            cj_cli_result_free(&r);
        }
        checks += 4;
    }
    /* the teapot cut at z = 1.5: body, spout and handle, three closed curves joined over the
     * patches */
    snprintf(cmd, sizeof cmd, "%s section --plane 0,0,1,1.5 --teapot", exe);
    if (cj_cli_shell(cmd, &r) == 0) {
        CHECK(r.status == 0 && count_prefix(r.out, "section patches 32 curves 3 closed 3 ") == 1,
              "teapot section: %d\n%s%s", r.status, r.err, strstr(r.out, "section patches"));
        cj_cli_result_free(&r);
        ++checks;
    }
    /* --json: a plot document of three cubic B-spline items, which plot reads */
    snprintf(cmd, sizeof cmd,
             "%s section --plane 0,0,1,1.5 --teapot --json > %s/section.json && grep -c "
             "'\"bspline\"' %s/section.json",
             exe, CJ_TMP_DIR, CJ_TMP_DIR);
    if (cj_cli_shell(cmd, &r) == 0) {
        CHECK(r.status == 0 && atoi(r.out) == 3, "section --json: %s %s", r.out, r.err);
        cj_cli_result_free(&r);
        ++checks;
    }
#ifdef CJ_HAVE_PLOT
    snprintf(cmd, sizeof cmd, "%s plot %s/section.json -o %s/section.png", exe, CJ_TMP_DIR,
             CJ_TMP_DIR);
    if (cj_cli_shell(cmd, &r) == 0) {
        CHECK(r.status == 0, "plot of the section: %s", r.err);
        cj_cli_result_free(&r);
        ++checks;
    }
#endif
    /* the octant seen from its centre (every point at distance 1), and from (2,2,2): the nearest
     * point is (1,1,1)/sqrt(3) at distance 2 sqrt(3) - 1 */
    const char *pts[2] = {"0,0,0 --tol 1e-9", "2,2,2 --tol 1e-9"};
    const double want[2] = {1.0, 2 * sqrt(3.0) - 1}, tols[2] = {1e-9, 1e-9};
    for (int k = 0; k < 2; ++k) {
        snprintf(cmd, sizeof cmd, "%s nearest --point %s " OCTANT, exe, pts[k]);
        if (cj_cli_shell(cmd, &r) != 0) continue;
        double d = -1, lo = -1, x = 0, y = 0, z = 0;
        const char *s = strstr(r.out, "nearest 0 ");
        if (s) {
            double u, v;
            if (sscanf(s, "nearest 0 %lf %lf %lf %lf %lf %lf %lf", &u, &v, &x, &y, &z, &d, &lo) !=
                7)
                d = -1;
        }
        /* the contract: lower <= true distance <= distance, distance - lower <= tol */
        CHECK(r.status == 0 && lo <= want[k] && want[k] <= d + 1e-15 && d - lo <= tols[k],
              "octant nearest to %s: distance %.17g lower %.17g\n%s", pts[k], d, lo, r.err);
        if (k == 1)
            CHECK(fabs(x - y) < 1e-4 && fabs(y - z) < 1e-4, "nearest point (%g, %g, %g)", x, y, z);
        cj_cli_result_free(&r);
        ++checks;
    }
    /* offset --trim: the parabola's swallowtail dropped (text: deviation I PIECES DEV CUSPS
     * DROPPED) */
    snprintf(cmd, sizeof cmd,
             "printf '%%s' '{\"items\":[{\"type\":\"bezier\",\"points\":[[-1,1],[0,-1],[1,"
             "1]]}]}' | %s offset --distance 0.8 --trim --text -",
             exe);
    if (cj_cli_shell(cmd, &r) == 0) {
        const char *s = strstr(r.out, "deviation 0 ");
        int pieces = 0, cusps = 0, dropped = 0;
        double dev = 0;
        if (s) sscanf(s, "deviation 0 %d %lf %d %d", &pieces, &dev, &cusps, &dropped);
        CHECK(r.status == 0 && pieces > 0 && cusps == 2 && dropped >= 1,
              "offset --trim: %d pieces, %d cusps, %d dropped\n%s", pieces, cusps, dropped, r.err);
        cj_cli_result_free(&r);
        ++checks;
    }
    /* reduce: a parabola elevated to degree 5 comes back as degree 2 at --tol 1e-9 (bound at
     * rounding level); a wavy quintic reduced to degree 3: the proven bound is never below the
     * distance between the two curves at 2001 parameters */
    snprintf(cmd, sizeof cmd,
             "printf '%%s' '{\"items\":[{\"type\":\"bezier\",\"points\":[[0,0],[0.6,1.2],[1.2,1.8],"
             "[1.8,1.8],[2.4,1.2],[3,0]]},{\"type\":\"bezier\",\"points\":[[0,0],[1,2],[2,-1],[3,"
             "1],[4,0],[5,1]]}]}' | %s reduce --tol 1e-9 --text - && printf '%%s' "
             "'{\"items\":[{\"type\":\"bezier\",\"points\":[[0,0],[1,2],[2,-1],[3,1],[4,0],[5,"
             "1]]}]}' | %s reduce --degree 3 --text -",
             exe, exe);
    if (cj_cli_shell(cmd, &r) == 0) {
        int item = -1, from = 0, to = 0, seen = 0;
        double bound = -1, q[6][2];
        const double quintic[6][2] = {{0, 0}, {1, 2}, {2, -1}, {3, 1}, {4, 0}, {5, 1}};
        for (const char *p = r.out; p && *p;) {
            if (sscanf(p, "reduced %d %d %d %lf", &item, &from, &to, &bound) == 4) {
                const char *l = p;
                for (int j = 0; j <= to && j < 6; ++j) {
                    l = strchr(l, '\n');
                    if (!l || sscanf(++l, "%lf %lf", &q[j][0], &q[j][1]) != 2) break;
                }
                if (seen == 0) /* the elevated parabola */
                    CHECK(to == 2 && bound < 1e-12, "elevated parabola: to %d bound %g", to, bound);
                if (seen == 1) /* the quintic: no degree below 5 within 1e-9 */
                    CHECK(to == 5 && bound == 0, "quintic at 1e-9: to %d bound %g", to, bound);
                if (seen == 2 && to == 3) { /* the quintic reduced to a cubic */
                    double worst = 0;
                    for (int i = 0; i <= 2000; ++i) {
                        double t = i / 2000.0, a[6][2], b[4][2];
                        memcpy(a, quintic, sizeof a);
                        memcpy(b, q, sizeof b);
                        for (int rr = 5; rr > 0; --rr)
                            for (int j = 0; j < rr; ++j)
                                for (int k = 0; k < 2; ++k)
                                    a[j][k] = (1 - t) * a[j][k] + t * a[j + 1][k];
                        for (int rr = 3; rr > 0; --rr)
                            for (int j = 0; j < rr; ++j)
                                for (int k = 0; k < 2; ++k)
                                    b[j][k] = (1 - t) * b[j][k] + t * b[j + 1][k];
                        worst = fmax(worst, hypot(a[0][0] - b[0][0], a[0][1] - b[0][1]));
                    }
                    CHECK(worst <= bound && worst > 0, "quintic -> cubic: distance %g, bound %g",
                          worst, bound);
                    printf("reduce: quintic -> cubic, proven bound %.4g, sampled distance %.4g\n",
                           bound, worst);
                }
                ++seen;
            }
            p = strchr(p, '\n');
            if (p) ++p;
        }
        CHECK(r.status == 0 && seen == 3, "reduce: status %d, %d curves\n%s", r.status, seen,
              r.err);
        cj_cli_result_free(&r);
        checks += 4;
    }
    struct {
        const char *args, *needle;
    } bad[] = {
        {"section --plane 0,0,0,1 --teapot", "normal"},
        {"section --plane 0,0,1 --teapot", "--plane"},
        {"section --teapot", "missing --plane"},
        {"section --plane 0,0,1,1", "no model"},
        {"section --plane 0,0,1,1 --teapot --tol -1", "--tol"},
        {"section --plane 0,0,1,1 --patch '0,0,0;1,0,0' --degree 1,1", "--patch"},
        {"section --plane 0,0,1,1 --teapot -o x.png", ".obj or .json"},
        {"section --plane 0,0,1,1 --surface /nonexistent.json", "--surface"},
        {"section --plane 0,0,1,1 --teapot --surface x.json", "give one of"},
        {"nearest --point 0,0 --teapot", "--point"},
        {"nearest --point 0,0,nan --teapot", "--point"},
        {"nearest --point 0,0,0 --teapot --plane 0,0,1,0", "does not apply"},
        {"intersect --trim -", "--trim does not apply"},
        {"reduce docs/none.json", "give one of --degree M or --tol T"},
        {"reduce --degree 0 -", "--degree '0'"},
        {"offset --degree 2 --distance 1 -", "--degree does not apply"},
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; ++i) {
        snprintf(cmd, sizeof cmd, "%s %s", exe, bad[i].args);
        if (cj_cli_shell(cmd, &r) != 0) continue;
        CHECK(r.status == 2 && strstr(r.err, bad[i].needle) && count_prefix(r.err, "") == 1,
              "bad input %zu (%s): status %d, stderr '%s'", i, bad[i].args, r.status, r.err);
        cj_cli_result_free(&r);
        ++checks;
    }
    printf("test_cli_section: %d checks (sphere octant section on its circle within the proven "
           "deviation, OBJ lines, the teapot's three closed curves, --json and plot, nearest on a "
           "patch, offset --trim, reduce against sampled distances, %zu bad "
           "inputs refused)\n",
           checks, sizeof bad / sizeof bad[0]);
    return cj_check_exit();
}

/* casteljau contour: polylines of an implicit curve f(x,y) = 0 inside a box, one per line in
 * the "x,y;x,y;..." syntax (see README). */
#include "cli.h"

#include "casteljau/implicit.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char contour_usage[] =
    "usage: casteljau contour (--circle cx,cy,r | --ellipse cx,cy,rx,ry[,rot] | --line a,b,c |\n"
    "                          --poly \"c0,c1,...\") --box x0,y0,x1,y1 [--tol T] [--grid NX[,NY]]\n"
    "                          [--max-points N] [--stats]\n"
    "Contours f(x,y) = 0 inside the box. --poly takes the coefficients of 1, x, y, x^2, xy,\n"
    "y^2, x^3, ... (graded order; the count fixes the degree, at most 32).\n"
    "  --tol         distance from polyline to curve (default 1e-6 times the larger box side;\n"
    "                at least 2^-40 times the box's largest coordinate or side)\n"
    "  --grid        marching-squares cells (default 64x64, at most 4096 per side)\n"
    "  --max-points  refuse (exit 2, no output) above this many vertices in all (default\n"
    "                1048576, at most 8388608)\n"
    "  --stats       print 'polylines N closed M points P max_residual R' on stderr\n"
    "Options may come in any order, as --opt value or --opt=value; '--' ends the options.\n"
    "Output: one polyline per line as \"x,y;x,y;...\" (%.17g); a closed loop repeats its first\n"
    "point at the end. Exit status 0; 1 (with the output) if some vertex could not be refined\n"
    "to tol; 2 for a bad argument, a tolerance too fine for the box, or too many points (one\n"
    "line on stderr, nothing on stdout).\n";

#define CONTOUR_DEFAULT_MAX_POINTS ((size_t)1 << 20)
/* Half the library's own cap, so that ours is always the one that stops a run. */
#define CONTOUR_MAX_MAX_POINTS (CJ_CONTOUR_MAX_POINTS / 2)

typedef struct buffer {
    char *text;
    size_t len, cap;
    int failed;
    size_t points, max_points;
    int over; /* more than max_points */
} buffer;

static void append(buffer *b, const char *s) {
    const size_t n = strlen(s);
    if (b->failed) return;
    if (b->len + n + 1 > b->cap) {
        size_t nc = b->cap ? b->cap * 2 : 4096;
        while (nc < b->len + n + 1) nc *= 2;
        char *t = realloc(b->text, nc);
        if (!t) {
            b->failed = 1;
            return;
        }
        b->text = t;
        b->cap = nc;
    }
    memcpy(b->text + b->len, s, n + 1);
    b->len += n;
}

static cj_status collect(void *user, const double *xy, size_t npts, int closed, double res) {
    (void)closed;
    (void)res;
    buffer *b = user;
    char num[64];
    if (npts > b->max_points - b->points) {
        b->over = 1;
        return CJ_ERR_CAP;
    }
    b->points += npts;
    for (size_t i = 0; i < npts; ++i) {
        snprintf(num, sizeof num, "%s%.17g,%.17g", i ? ";" : "", xy[2 * i], xy[2 * i + 1]);
        append(b, num);
    }
    append(b, "\n");
    return b->failed ? CJ_ERR_NOMEM : CJ_OK;
}

/* Parses exactly `want` comma-separated numbers (or between want_min and want). */
static int parse_fixed(const char *opt, const char *text, double *out, size_t want_min,
                       size_t want) {
    double *v = NULL;
    size_t n = 0;
    char why[256];
    if (cli_parse_list(text, &v, &n, why, sizeof why))
        return cli_fail("contour", "%s: %s", opt, why);
    if (n < want_min || n > want) {
        free(v);
        if (want_min == want)
            return cli_fail("contour", "%s needs %zu numbers, got %zu", opt, want, n);
        return cli_fail("contour", "%s needs %zu to %zu numbers, got %zu", opt, want_min, want, n);
    }
    memcpy(out, v, sizeof(double) * n);
    free(v);
    return 0;
}

int cmd_contour(int argc, char **argv) {
    const char *shape_opt = NULL, *shape_text = NULL;
    double box[4] = {0, 0, 0, 0}, tol = 0.0;
    int have_box = 0, have_tol = 0, stats_wanted = 0, nx = 64, ny = 64;
    size_t max_points = CONTOUR_DEFAULT_MAX_POINTS;
    enum { O_CIRCLE, O_ELLIPSE, O_LINE, O_POLY, O_BOX, O_TOL, O_GRID, O_STATS, O_MAXPTS };
    static const cli_opt opts[] = {
        {"--circle", NULL, 1}, {"--ellipse", NULL, 1}, {"--line", NULL, 1},
        {"--poly", NULL, 1},   {"--box", NULL, 1},     {"--tol", NULL, 1},
        {"--grid", NULL, 1},   {"--stats", NULL, 0},   {"--max-points", NULL, 1}};
    cli_parser ps;
    cli_parser_init(&ps, "contour", contour_usage, argc, argv, opts, sizeof opts / sizeof opts[0]);
    const char *v;
    int k, status;
    while (cli_next_arg(&ps, &k, &v, &status)) {
        char q[160];
        if (k == CLI_POSITIONAL)
            return cli_fail("contour", "unexpected argument '%s' (try 'casteljau contour --help')",
                            cli_quote(v, q, sizeof q));
        const char *a = opts[k].name;
        if (k <= O_POLY) {
            if (shape_opt)
                return cli_fail("contour", "%s and %s: give exactly one curve", shape_opt, a);
            shape_opt = a;
            shape_text = v;
        } else if (k == O_BOX) {
            if (parse_fixed("--box", v, box, 4, 4)) return CLI_EXIT_USAGE;
            have_box = 1;
        } else if (k == O_TOL) {
            if (cli_parse_double(v, &tol) || !(tol > 0))
                return cli_fail("contour", "--tol '%s' is not a positive number",
                                cli_quote(v, q, sizeof q));
            have_tol = 1;
        } else if (k == O_GRID) {
            double g[2];
            if (parse_fixed("--grid", v, g, 1, 2)) return CLI_EXIT_USAGE;
            const int two = strchr(v, ',') != NULL || strchr(v, ';') != NULL;
            if (!two) g[1] = g[0];
            for (int j = 0; j < 2; ++j)
                if (g[j] != floor(g[j]) || g[j] < 1 || g[j] > 4096)
                    return cli_fail("contour",
                                    "--grid '%s': cell counts must be integers in 1..4096",
                                    cli_quote(v, q, sizeof q));
            nx = (int)g[0];
            ny = (int)g[1];
        } else if (k == O_STATS) {
            stats_wanted = 1;
        } else {
            long m;
            if (cli_parse_int(v, 1, (long)CONTOUR_MAX_MAX_POINTS, &m))
                return cli_fail("contour", "--max-points '%s' is not an integer in 1..%zu",
                                cli_quote(v, q, sizeof q), CONTOUR_MAX_MAX_POINTS);
            max_points = (size_t)m;
        }
    }
    if (status >= 0) return status;
    if (!shape_opt)
        return cli_fail("contour", "missing the curve: --circle, --ellipse, --line or --poly");
    if (!have_box) return cli_fail("contour", "missing --box x0,y0,x1,y1");
    if (!(box[0] < box[2]) || !(box[1] < box[3]))
        return cli_fail("contour", "--box: need x0 < x1 and y0 < y1");
    if (!isfinite(box[2] - box[0]) || !isfinite(box[3] - box[1]))
        return cli_fail("contour",
                        "--box %.17g,%.17g,%.17g,%.17g: its sides overflow the double "
                        "range",
                        box[0], box[1], box[2], box[3]);
    if (!have_tol) tol = 1e-6 * fmax(box[2] - box[0], box[3] - box[1]);
    {
        double scale = fmax(fmax(fabs(box[0]), fabs(box[1])), fmax(fabs(box[2]), fabs(box[3])));
        scale = fmax(scale, fmax(box[2] - box[0], box[3] - box[1]));
        const double min_tol = CJ_CONTOUR_MIN_REL_TOL * scale;
        if (tol < min_tol)
            return cli_fail("contour",
                            "%s %g is finer than doubles resolve in this --box (scale %g): give "
                            "--tol %.3g or more",
                            have_tol ? "--tol" : "the default tolerance (1e-6 of the box side)",
                            tol, scale, min_tol);
    }

    cj_implicit_shape shape;
    cj_implicit f;
    double c[5] = {0, 0, 0, 0, 0}, *coef = NULL;
    cj_status st;
    if (!strcmp(shape_opt, "--circle")) {
        if (parse_fixed(shape_opt, shape_text, c, 3, 3)) return CLI_EXIT_USAGE;
        st = cj_implicit_circle(c[0], c[1], c[2], &shape, &f);
    } else if (!strcmp(shape_opt, "--ellipse")) {
        if (parse_fixed(shape_opt, shape_text, c, 4, 5)) return CLI_EXIT_USAGE;
        st = cj_implicit_ellipse(c[0], c[1], c[2], c[3], c[4], &shape, &f);
    } else if (!strcmp(shape_opt, "--line")) {
        if (parse_fixed(shape_opt, shape_text, c, 3, 3)) return CLI_EXIT_USAGE;
        st = cj_implicit_line(c[0], c[1], c[2], &shape, &f);
    } else {
        size_t n = 0;
        char why[256];
        if (cli_parse_list(shape_text, &coef, &n, why, sizeof why))
            return cli_fail("contour", "--poly: %s", why);
        int deg = -1;
        for (int d = 0; d <= 32; ++d)
            if (cj_implicit_poly_ncoef(d) == n) deg = d;
        if (deg < 0) {
            free(coef);
            return cli_fail("contour",
                            "--poly: %zu coefficients is not (n+1)(n+2)/2 for a degree n <= 32 "
                            "(1, 3, 6, 10, 15, ...)",
                            n);
        }
        st = cj_implicit_poly(deg, coef, &shape, &f);
    }
    if (st) {
        free(coef);
        return cli_fail("contour", "%s: %s", shape_opt, cj_last_error());
    }
    buffer out = {NULL, 0, 0, 0, 0, max_points, 0};
    cj_contour_options o = {nx, ny, tol, NULL};
    cj_contour_stats stats;
    st = cj_implicit_contour(&f, box, &o, collect, &out, &stats);
    int rc = 0;
    if (out.over) {
        rc = cli_fail("contour",
                      "more than %zu points (--max-points): --tol %g is too fine for this curve "
                      "and box",
                      max_points, tol);
    } else if (out.failed) {
        rc = cli_error("contour", "out of memory for the output");
    } else if (st != CJ_OK && st != CJ_ERR_CAP) {
        rc = cli_fail("contour", "%s", cj_last_error());
    } else {
        if (out.text) fputs(out.text, stdout);
        if (stats_wanted)
            fprintf(stderr, "polylines %zu closed %zu points %zu max_residual %.3g\n",
                    stats.polylines, stats.closed, stats.points, stats.max_residual);
        if (st == CJ_ERR_CAP) {
            cli_warn("contour", "%s", cj_last_error());
            rc = 1;
        }
        if (fflush(stdout) != 0 || ferror(stdout))
            rc = cli_error("contour", "cannot write the output");
    }
    free(out.text);
    free(coef);
    return rc;
}

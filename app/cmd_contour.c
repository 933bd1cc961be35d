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
    "                          [--stats]\n"
    "Contours f(x,y) = 0 inside the box and prints one polyline per line as \"x,y;x,y;...\"\n"
    "(%.17g); a closed loop repeats its first point at the end. --poly takes the coefficients\n"
    "of 1, x, y, x^2, xy, y^2, x^3, ... (graded order; the count fixes the degree).\n"
    "Default tol: 1e-6 times the larger box side; default grid 64x64. --stats prints\n"
    "'polylines N closed M points P max_residual R' on stderr. Exit status 1 (with output) if\n"
    "some vertex could not be refined to tol.\n";

typedef struct buffer {
    char *text;
    size_t len, cap;
    int failed;
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
    for (int i = 1; i < argc; ++i) {
        const char *a = argv[i];
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            fputs(contour_usage, stdout);
            return 0;
        } else if (!strcmp(a, "--circle") || !strcmp(a, "--ellipse") || !strcmp(a, "--line") ||
                   !strcmp(a, "--poly")) {
            if (shape_opt)
                return cli_fail("contour", "%s and %s: give exactly one curve", shape_opt, a);
            if (++i >= argc) return cli_fail("contour", "%s needs a value", a);
            shape_opt = a;
            shape_text = argv[i];
        } else if (!strcmp(a, "--box")) {
            if (++i >= argc) return cli_fail("contour", "--box needs a value");
            if (parse_fixed("--box", argv[i], box, 4, 4)) return CLI_EXIT_USAGE;
            have_box = 1;
        } else if (!strcmp(a, "--tol")) {
            if (++i >= argc) return cli_fail("contour", "--tol needs a value");
            if (cli_parse_double(argv[i], &tol) || !(tol > 0))
                return cli_fail("contour", "--tol '%s' is not a positive number", argv[i]);
            have_tol = 1;
        } else if (!strcmp(a, "--grid")) {
            if (++i >= argc) return cli_fail("contour", "--grid needs a value");
            double g[2];
            if (parse_fixed("--grid", argv[i], g, 1, 2)) return CLI_EXIT_USAGE;
            const int two = strchr(argv[i], ',') != NULL || strchr(argv[i], ';') != NULL;
            if (!two) g[1] = g[0];
            for (int k = 0; k < 2; ++k)
                if (g[k] != floor(g[k]) || g[k] < 1 || g[k] > 4096)
                    return cli_fail("contour",
                                    "--grid '%s': cell counts must be integers in "
                                    "1..4096",
                                    argv[i]);
            nx = (int)g[0];
            ny = (int)g[1];
        } else if (!strcmp(a, "--stats")) {
            stats_wanted = 1;
        } else {
            return cli_fail("contour", "unknown argument '%s' (try --help)", a);
        }
    }
    if (!shape_opt)
        return cli_fail("contour", "missing the curve: --circle, --ellipse, --line or --poly");
    if (!have_box) return cli_fail("contour", "missing --box x0,y0,x1,y1");
    if (!(box[0] < box[2]) || !(box[1] < box[3]))
        return cli_fail("contour", "--box: need x0 < x1 and y0 < y1");
    if (!have_tol) tol = 1e-6 * fmax(box[2] - box[0], box[3] - box[1]);

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
    buffer out = {NULL, 0, 0, 0};
    cj_contour_options o = {nx, ny, tol, NULL};
    cj_contour_stats stats;
    st = cj_implicit_contour(&f, box, &o, collect, &out, &stats);
    int rc = 0;
    if (st != CJ_OK && st != CJ_ERR_CAP) {
        rc = cli_fail("contour", "%s", cj_last_error());
    } else {
        if (out.text) fputs(out.text, stdout);
        if (stats_wanted)
            fprintf(stderr, "polylines %zu closed %zu points %zu max_residual %.3g\n",
                    stats.polylines, stats.closed, stats.points, stats.max_residual);
        if (st == CJ_ERR_CAP) {
            fprintf(stderr, "casteljau contour: warning: %s\n", cj_last_error());
            rc = 1;
        }
    }
    free(out.text);
    free(coef);
    return rc;
}

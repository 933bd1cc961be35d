/* casteljau fit: a B-spline through (or near) points read from a file or standard input. */
#include "bspline_json.h"
#include "plot_json.h"
#include "cli.h"
#include "file_internal.h"

#include "casteljau/bspline.h"
#include "casteljau/bspline_fit.h"
#include "casteljau/bspline_surface.h"
#include "surface_json.h"

#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static const char fit_usage[] =
    "usage: casteljau fit [--degree P] [--param uniform|chord|centripetal]\n"
    "                     [--tolerance TOL [--max-points M]] [--start-tangent \"x,y\"]\n"
    "                     [--end-tangent \"x,y\"] [-o FILE.json] [POINTS_FILE]\n"
    "       casteljau fit --grid NU,NV [--degree P] [--param ...] [-o FILE.json] [POINTS_FILE]\n"
    "Fits a clamped B-spline of degree P (default 3) over [0,1] to the points in POINTS_FILE\n"
    "(or standard input): one point per line, its coordinates separated by spaces or commas\n"
    "(1..8 per point, the same on every line); blank lines and lines starting with # are\n"
    "skipped.\n"
    "  --param          parameters of the points (default chord: spacing by distance)\n"
    "  --tolerance      least-squares approximation with the fewest control points found whose\n"
    "                   largest deviation at the points is <= TOL (end points exact); without\n"
    "                   it, interpolation through every point\n"
    "  --max-points     cap on the control points of the approximation (default: the points)\n"
    "  --start-tangent, --end-tangent   derivative at t = 0 / t = 1 (interpolation, P >= 2)\n"
    "  --grid           the points (3D, NU*NV of them, u fastest: point j*NU + i) are a grid:\n"
    "                   write the B-spline surface of degree P in u and v through them, the\n"
    "                   JSON object that 'casteljau tessellate --surface' and scenes read\n"
    "  -o               write the JSON here (complete or not at all) instead of stdout\n"
    "Output: a JSON document for 'casteljau plot' and 'casteljau eval --curve': a title with\n"
    "the counts and the deviation reached, and one item {\"type\": \"bspline\", \"degree\",\n"
    "\"knots\", \"points\"}, followed for 2D data by a \"points\" item with the data.\n"
    "Exit status 0; 2 for bad arguments or input, or a tolerance not reached under the cap\n"
    "(the message says the deviation reached); 1 when out of memory or a write fails.\n";

/* Reads the point lines of f. Returns 0, or -1 after a message (exit status in *rc). */
static int read_points(FILE *f, const char *name, double **out, int *npts, int *dim, int *rc) {
    size_t cap = 1024, n = 0;
    double *v = malloc(sizeof(double) * cap);
    char line[4096];
    int d = 0, lineno = 0;
    if (!v) {
        *rc = cli_error("fit", "out of memory");
        return -1;
    }
    while (fgets(line, sizeof line, f)) {
        ++lineno;
        if (!strchr(line, '\n') && !feof(f)) {
            free(v);
            *rc = cli_fail("fit", "%s, line %d: longer than %zu characters", name, lineno,
                           sizeof line - 2);
            return -1;
        }
        char *s = line;
        while (isspace((unsigned char)*s)) ++s;
        if (!*s || *s == '#') continue;
        int k = 0;
        double x[CJ_MAX_DIM + 1];
        for (char *tok = strtok(s, " \t\r\n,"); tok; tok = strtok(NULL, " \t\r\n,")) {
            char q[80];
            if (k > CJ_MAX_DIM || cli_parse_double(tok, &x[k])) {
                free(v);
                *rc = k > CJ_MAX_DIM ? cli_fail("fit", "%s, line %d: more than %d coordinates",
                                                name, lineno, CJ_MAX_DIM)
                                     : cli_fail("fit", "%s, line %d: '%s' is not a finite number",
                                                name, lineno, cli_quote(tok, q, sizeof q));
                return -1;
            }
            ++k;
        }
        if (k > CJ_MAX_DIM) {
            free(v);
            *rc =
                cli_fail("fit", "%s, line %d: more than %d coordinates", name, lineno, CJ_MAX_DIM);
            return -1;
        }
        if (!d) d = k;
        if (k != d) {
            free(v);
            *rc = cli_fail("fit", "%s, line %d: %d coordinates where the first point has %d", name,
                           lineno, k, d);
            return -1;
        }
        if ((n + 1) * (size_t)d > cap) {
            double *nv = realloc(v, sizeof(double) * cap * 2);
            if (!nv) {
                free(v);
                *rc = cli_error("fit", "out of memory reading %s", name);
                return -1;
            }
            v = nv;
            cap *= 2;
        }
        memcpy(v + n * (size_t)d, x, sizeof(double) * (size_t)d);
        if (++n > 50000000) {
            free(v);
            *rc = cli_fail("fit", "%s: more than 5e7 points", name);
            return -1;
        }
    }
    if (ferror(f)) {
        free(v);
        *rc = cli_error("fit", "cannot read %s", name);
        return -1;
    }
    if (n < 2) {
        free(v);
        *rc = cli_fail("fit", "%s: %zu point%s, at least 2 needed", name, n, n == 1 ? "" : "s");
        return -1;
    }
    *out = v;
    *npts = (int)n;
    *dim = d;
    return 0;
}

/* fit --grid: the interpolating surface, written as its JSON object. */
static int fit_grid(const double *data, int n, int dim, int nu, int nv, int degree,
                    cj_fit_param kind, const char *output) {
    if (dim != 3) return cli_fail("fit", "--grid needs 3D points, not %d coordinates", dim);
    if ((long)nu * nv != n)
        return cli_fail("fit", "--grid %d,%d needs %ld points, the input has %d", nu, nv,
                        (long)nu * nv, n);
    double *P = malloc(sizeof(double) * 3 * (size_t)n);
    double *ku = malloc(sizeof(double) * (size_t)(nu + degree + 1));
    double *kv = malloc(sizeof(double) * (size_t)(nv + degree + 1));
    int rc = 0;
    if (!P || !ku || !kv) {
        rc = cli_error("fit", "out of memory");
    } else if (cj_bspline_surface_interpolate(data, nu, nv, degree, degree, kind, P, ku, kv, NULL,
                                              NULL)) {
        rc = cli_fail("fit", "%s", cj_last_error());
    } else {
        const cj_bspline_surface s = {degree, degree, nu, nv, P, NULL, ku, kv};
        if (output) {
            cj_atomic_file f;
            if (cj_atomic_open(&f, output)) {
                rc = cli_error("fit", "%s", cj_last_error());
            } else {
                if (cj_surface_json_print(f.fp, &s, "fit")) {
                    rc = cli_error("fit", "%s", cj_last_error());
                    cj_atomic_abandon(&f);
                } else if (cj_atomic_commit(&f)) {
                    rc = cli_error("fit", "%s", cj_last_error());
                }
            }
        } else {
            if (cj_surface_json_print(stdout, &s, "fit") || fflush(stdout) != 0 || ferror(stdout))
                rc = cli_error("fit", "cannot write the output");
        }
    }
    free(P);
    free(ku);
    free(kv);
    return rc;
}

int cmd_fit(int argc, char **argv) {
    enum { O_DEGREE, O_PARAM, O_TOL, O_MAXPTS, O_T0, O_T1, O_OUT, O_GRID };
    static const cli_opt opts[] = {{"--degree", NULL, 1},        {"--param", NULL, 1},
                                   {"--tolerance", NULL, 1},     {"--max-points", NULL, 1},
                                   {"--start-tangent", NULL, 1}, {"--end-tangent", NULL, 1},
                                   {"--output", "-o", 1},        {"--grid", NULL, 1}};
    int grid_u = 0, grid_v = 0;
    cli_parser ps;
    cli_parser_init(&ps, "fit", fit_usage, argc, argv, opts, sizeof opts / sizeof opts[0]);
    int degree = 3, status, k;
    long max_pts = -1;
    cj_fit_param kind = CJ_FIT_CHORD;
    double tol = -1.0;
    const char *input = NULL, *output = NULL, *t0_text = NULL, *t1_text = NULL, *v;
    while (cli_next_arg(&ps, &k, &v, &status)) {
        char q[160];
        if (k == CLI_POSITIONAL) {
            if (input)
                return cli_fail("fit", "a second input file '%s' (one at most)",
                                cli_quote(v, q, sizeof q));
            input = v;
        } else if (k == O_DEGREE) {
            long d;
            if (cli_parse_int(v, 1, CJ_BSPLINE_MAX_DEGREE, &d))
                return cli_fail("fit", "--degree '%s' is not an integer in 1..%d",
                                cli_quote(v, q, sizeof q), CJ_BSPLINE_MAX_DEGREE);
            degree = (int)d;
        } else if (k == O_PARAM) {
            if (!strcmp(v, "uniform"))
                kind = CJ_FIT_UNIFORM;
            else if (!strcmp(v, "chord"))
                kind = CJ_FIT_CHORD;
            else if (!strcmp(v, "centripetal"))
                kind = CJ_FIT_CENTRIPETAL;
            else
                return cli_fail("fit", "unknown --param '%s' (uniform, chord, centripetal)",
                                cli_quote(v, q, sizeof q));
        } else if (k == O_TOL) {
            if (cli_parse_double(v, &tol) || !(tol >= 0.0))
                return cli_fail("fit", "--tolerance '%s' is not a finite number >= 0",
                                cli_quote(v, q, sizeof q));
        } else if (k == O_MAXPTS) {
            if (cli_parse_int(v, 2, 50000000, &max_pts))
                return cli_fail("fit", "--max-points '%s' is not an integer in 2..5e7",
                                cli_quote(v, q, sizeof q));
        } else if (k == O_T0) {
            t0_text = v;
        } else if (k == O_T1) {
            t1_text = v;
        } else if (k == O_GRID) {
            char *e;
            const long a = strtol(v, &e, 10), b = *e == ',' ? strtol(e + 1, &e, 10) : 0;
            if (*e || a < 2 || b < 2 || a > 100000 || b > 100000)
                return cli_fail("fit", "--grid '%s' is not NU,NV (two integers >= 2)",
                                cli_quote(v, q, sizeof q));
            grid_u = (int)a;
            grid_v = (int)b;
        } else {
            output = v;
        }
    }
    if (status >= 0) return status;
    if (tol < 0.0 && max_pts >= 0)
        return cli_fail("fit", "--max-points applies only with --tolerance");
    if (tol >= 0.0 && (t0_text || t1_text))
        return cli_fail("fit", "--start-tangent and --end-tangent apply only to interpolation "
                               "(without --tolerance)");
    if (grid_u && (tol >= 0.0 || t0_text || t1_text))
        return cli_fail("fit", "--grid takes neither --tolerance nor end tangents");
    if (grid_u && degree > CJ_PATCH_MAX_DEGREE)
        return cli_fail("fit", "--degree %d exceeds %d for a surface", degree, CJ_PATCH_MAX_DEGREE);
    if (!input && isatty(0))
        return cli_fail("fit", "no points (give a file, or pipe them on standard input)");
    /* a points file is checked as every input is (regular, capped, logged as an input) */
    if (input && cj_file_check_input(input, (size_t)1 << 28, "points file"))
        return cli_fail("fit", "%s", cj_last_error());
    FILE *in = input ? fopen(input, "r") : stdin;
    if (!in) {
        char q[160];
        return cli_fail("fit", "cannot open '%s'", cli_quote(input, q, sizeof q));
    }
    double *data = NULL, *tan0 = NULL, *tan1 = NULL, *P = NULL, *U = NULL;
    int n = 0, dim = 0, rc = 0;
    const int bad_read = read_points(in, input ? input : "standard input", &data, &n, &dim, &rc);
    if (input) fclose(in);
    if (bad_read) return rc;
    char why[256];
    size_t cnt;
    int tdim;
    if (grid_u) {
        rc = fit_grid(data, n, dim, grid_u, grid_v, degree, kind, output);
        goto done;
    }
    if (t0_text && (cli_parse_points(t0_text, &tan0, &cnt, &tdim, why, sizeof why) || cnt != 1 ||
                    tdim != dim)) {
        rc = cli_fail("fit", "--start-tangent is not one point of dimension %d", dim);
        goto done;
    }
    if (t1_text && (cli_parse_points(t1_text, &tan1, &cnt, &tdim, why, sizeof why) || cnt != 1 ||
                    tdim != dim)) {
        rc = cli_fail("fit", "--end-tangent is not one point of dimension %d", dim);
        goto done;
    }
    const int cap = n + 2;
    P = malloc(sizeof(double) * (size_t)cap * (size_t)dim);
    U = malloc(sizeof(double) * (size_t)(cap + degree + 1));
    if (!P || !U) {
        rc = cli_error("fit", "out of memory");
        goto done;
    }
    int m = 0;
    double dev = 0.0;
    cj_status st;
    if (tol < 0.0)
        st = cj_bspline_interpolate(data, n, dim, degree, kind, tan0, tan1, P, U, &m, &dev);
    else
        st = cj_bspline_approximate(data, n, dim, degree, kind, tol, max_pts > 0 ? (int)max_pts : n,
                                    P, U, &m, &dev);
    if (st) {
        rc = cli_fail("fit", "%s", cj_last_error());
        goto done;
    }
    char title[200];
    snprintf(title, sizeof title, "fit: %d points, degree %d, %d control points, %s %.3g", n,
             degree, m, tol < 0.0 ? "interpolation residual" : "max deviation", dev);
    const cj_bspline c = cj_bspline_view(degree, dim, m, P, NULL, U);
    if (output) {
        cj_atomic_file f;
        if (cj_atomic_open(&f, output)) {
            rc = cli_error("fit", "%s", cj_last_error());
            goto done;
        }
        if (cj_plot_json_print_fit(f.fp, &c, data, n, title)) {
            rc = cli_error("fit", "%s", cj_last_error());
            cj_atomic_abandon(&f);
        } else if (cj_atomic_commit(&f)) {
            rc = cli_error("fit", "%s", cj_last_error());
        }
    } else {
        if (cj_plot_json_print_fit(stdout, &c, data, n, title) || fflush(stdout) != 0 ||
            ferror(stdout))
            rc = cli_error("fit", "cannot write the output");
    }
done:
    free(data);
    free(tan0);
    free(tan1);
    free(P);
    free(U);
    return rc;
}

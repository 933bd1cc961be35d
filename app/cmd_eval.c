/* casteljau eval: the evaluation contract other tools and tests rely on (see README). */
#include "cli.h"
#include "eval_bspline.h"

#include "casteljau/bezier.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static const char eval_usage[] =
    "usage: casteljau eval [--method decasteljau|bernstein|horner|compensated]\n"
    "                      [--derivative K] [--bound] --points \"x0,y0;x1,y1;...\" [T ...]\n"
    "       casteljau eval [--derivative K] [--bound] --curve FILE.json [T ...]\n"
    "Evaluates the Bezier curve with these control points (degree = count - 1, any dimension\n"
    "1..8, the same for every point) at each parameter T (usually in [0,1]; decimal or C99 hex\n"
    "floats). Without T on the command line, the parameters are read from standard input,\n"
    "separated by white space (for long lists: 'seq 0 0.001 1 | casteljau eval --points P').\n"
    "Options may come in any order, as --opt value or --opt=value; '--' ends the options.\n"
    "  --method      evaluation algorithm (default decasteljau); compensated is as accurate as\n"
    "                twice the working precision\n"
    "  --derivative  evaluate the K-th derivative instead (default 0)\n"
    "  --bound       append an absolute error bound per coordinate (a-priori; a-posteriori\n"
    "                for compensated)\n"
    "  --curve       evaluate the first B-spline/NURBS item (\"type\": \"bspline\", as 'casteljau\n"
    "                fit' writes it) of this JSON file instead, by de Boor; T must lie in its\n"
    "                domain; --bound is its a-priori bound (also with --derivative, NURBS too)\n"
    "Output: one line per T, in the order given: the coordinates with %.17g separated by one\n"
    "space, and with --bound ' |' and one bound per coordinate. Nothing is printed unless\n"
    "every T evaluates. Exit status 0; 2 for a bad argument or input, or a result that\n"
    "overflows the double range (one line on stderr naming it); 1 when out of memory.\n";

static int parse_method(const char *s, cj_eval_method *m) {
    static const struct {
        const char *name;
        cj_eval_method method;
    } names[] = {{"decasteljau", CJ_EVAL_DECASTELJAU},
                 {"bernstein", CJ_EVAL_BERNSTEIN},
                 {"horner", CJ_EVAL_HORNER},
                 {"compensated", CJ_EVAL_COMPENSATED}};
    for (size_t i = 0; i < sizeof names / sizeof names[0]; ++i)
        if (!strcmp(s, names[i].name)) {
            *m = names[i].method;
            return 0;
        }
    return -1;
}

/* The K-th hodograph's control points are computed with K levels of differences, each
 * scaled: h <- m (h_{i+1} - h_i). Every level costs two roundings, so the computed points
 * differ from the exact ones by at most gamma(2K) A_i, where A is the same recurrence run on
 * absolute values with sums, A <- m (A_{i+1} + A_i), from |b|. This writes A (n-K+1 points),
 * inflated by 1 + gamma(2K+2) for its own roundings. */
static void hodograph_magnitude(const double *pts, int n, int dim, int k, double *a) {
    const size_t count = (size_t)(n + 1) * (size_t)dim;
    for (size_t i = 0; i < count; ++i) a[i] = fabs(pts[i]);
    for (int q = 0; q < k; ++q) {
        const double m = (double)(n - q);
        for (int i = 0; i < (n - q) * dim; ++i) a[i] = m * (a[i + dim] + a[i]);
    }
    const double up = 1.0 + cj_gamma(2 * k + 2);
    for (int i = 0; i < (n - k + 1) * dim; ++i) a[i] *= up;
}

/* Adds to the evaluation bound b the effect of the hodograph's own rounding errors:
 * gamma(2K) Σ A_i B_i^m(|t|) (m = n-K), the magnitude evaluated by de Casteljau on |1-t|, |t|
 * and inflated by 1 + gamma(3m+4) for its roundings. */
static void add_hodograph_error(const double *a, int m, int dim, int k, double t, double *b) {
    double w[(CJ_BEZIER_MAX_DEGREE + 1) * CJ_MAX_DIM];
    memcpy(w, a, sizeof(double) * (size_t)(m + 1) * (size_t)dim);
    const double s = fabs(1.0 - t), at = fabs(t);
    for (int r = m; r > 0; --r)
        for (int i = 0; i < r * dim; ++i) w[i] = s * w[i] + at * w[i + dim];
    const double g = cj_gamma(2 * k) * (1.0 + cj_gamma(3 * m + 6));
    for (int c = 0; c < dim; ++c) b[c] += g * w[c];
}

/* Reads white-space separated parameters from `f` into a growing array. Returns 0, or -1
 * with a message printed (exit status in *rc). */
int eval_read_params(FILE *f, double **ts, size_t *nt, int *rc) {
    size_t cap = 1024, n = 0;
    double *v = malloc(sizeof(double) * cap);
    char tok[128];
    int c = 0;
    while (v) {
        size_t len = 0;
        while ((c = getc(f)) != EOF && (c == ' ' || c == '\t' || c == '\n' || c == '\r'))
            ;
        if (c == EOF) break;
        while (c != EOF && c != ' ' && c != '\t' && c != '\n' && c != '\r') {
            if (len + 1 < sizeof tok) tok[len++] = (char)c;
            c = getc(f);
        }
        tok[len] = '\0';
        if (n == cap) {
            double *nv = realloc(v, sizeof(double) * cap * 2);
            if (!nv) break;
            v = nv;
            cap *= 2;
        }
        if (len + 1 >= sizeof tok || cli_parse_double(tok, &v[n])) {
            char q[80];
            free(v);
            *rc = cli_fail("eval", "standard input, parameter %zu: '%s' is not a finite number", n,
                           cli_quote(tok, q, sizeof q));
            return -1;
        }
        ++n;
        if (c == EOF) break;
    }
    if (!v || (c != EOF && n < cap)) {
        free(v);
        *rc = cli_error("eval", "out of memory reading parameters from standard input");
        return -1;
    }
    if (ferror(f)) {
        free(v);
        *rc = cli_error("eval", "cannot read standard input");
        return -1;
    }
    if (n == 0) {
        free(v);
        *rc = cli_fail("eval", "no parameter T given (on the command line or standard input)");
        return -1;
    }
    *ts = v;
    *nt = n;
    return 0;
}

int cmd_eval(int argc, char **argv) {
    cj_eval_method method = CJ_EVAL_DECASTELJAU;
    int derivative = 0, want_bound = 0;
    const char *points_text = NULL, *curve_path = NULL;
    int have_method = 0;
    enum { O_METHOD, O_DERIV, O_BOUND, O_POINTS, O_CURVE };
    static const cli_opt opts[] = {{"--method", NULL, 1},
                                   {"--derivative", NULL, 1},
                                   {"--bound", NULL, 0},
                                   {"--points", NULL, 1},
                                   {"--curve", NULL, 1}};
    cli_parser ps;
    cli_parser_init(&ps, "eval", eval_usage, argc, argv, opts, sizeof opts / sizeof opts[0]);
    /* Positional parameters are collected in place (argv order), wherever they appear. */
    char **targs = malloc(sizeof(char *) * (size_t)(argc > 0 ? argc : 1));
    if (!targs) return cli_error("eval", "out of memory");
    int ntargs = 0;
    for (;;) {
        const char *v;
        const int k = cli_next(&ps, &v);
        if (k == CLI_END) break;
        if (k == CLI_EXIT_OK || k == CLI_BAD) {
            free(targs);
            return k == CLI_EXIT_OK ? 0 : CLI_EXIT_USAGE;
        }
        int bad = 0;
        char q[160];
        if (k == CLI_POSITIONAL) {
            targs[ntargs++] = (char *)v;
        } else if (k == O_CURVE) {
            curve_path = v;
        } else if (k == O_METHOD) {
            have_method = 1;
            if (parse_method(v, &method))
                bad = cli_fail("eval",
                               "unknown method '%s' (decasteljau, bernstein, horner, compensated)",
                               cli_quote(v, q, sizeof q));
        } else if (k == O_DERIV) {
            long d;
            if (cli_parse_int(v, 0, CJ_BEZIER_MAX_DEGREE + 1, &d))
                bad = cli_fail("eval", "--derivative '%s' is not an order between 0 and %d",
                               cli_quote(v, q, sizeof q), CJ_BEZIER_MAX_DEGREE + 1);
            derivative = (int)d;
        } else if (k == O_BOUND) {
            want_bound = 1;
        } else {
            points_text = v;
        }
        if (bad) {
            free(targs);
            return bad;
        }
    }
    if (curve_path) {
        const int rc = points_text || have_method
                           ? cli_fail("eval", "--curve takes neither --points nor --method")
                           : eval_bspline_run(curve_path, derivative, want_bound, targs, ntargs);
        free(targs);
        return rc;
    }
    if (!points_text) {
        free(targs);
        return cli_fail("eval", "missing --points (try 'casteljau eval --help')");
    }

    double *pts = NULL, *hodo = NULL, *habs = NULL, *ts = NULL, *vals = NULL;
    size_t npts = 0, nt = 0;
    int dim = 0, rc = 0;
    char why[256];
    if (cli_parse_points(points_text, &pts, &npts, &dim, why, sizeof why)) {
        free(targs);
        return cli_fail("eval", "--points: %s", why);
    }
    if (dim > CJ_MAX_DIM) {
        rc = cli_fail("eval", "--points: dimension %d exceeds %d", dim, CJ_MAX_DIM);
        goto done;
    }
    if (ntargs > 0) {
        nt = (size_t)ntargs;
        ts = malloc(sizeof(double) * nt);
        if (!ts) {
            rc = cli_error("eval", "out of memory");
            goto done;
        }
        for (size_t j = 0; j < nt; ++j)
            if (cli_parse_double(targs[j], &ts[j])) {
                rc = cli_fail("eval", "parameter '%s' is not a finite number", targs[j]);
                goto done;
            }
    } else if (isatty(0)) {
        rc = cli_fail("eval", "no parameter T given (give them after the options, or pipe them "
                              "on standard input)");
        goto done;
    } else if (eval_read_params(stdin, &ts, &nt, &rc)) {
        goto done;
    }
    /* Results are computed in full before anything is printed: a bad T prints nothing. */
    vals = malloc(sizeof(double) * nt * (size_t)dim * 2);
    if (!vals) {
        rc = cli_error("eval", "out of memory");
        goto done;
    }

    /* The derivative of order K is itself a Bézier curve (the hodograph): evaluate that. */
    cj_bezier curve = cj_bezier_view((int)npts - 1, dim, pts);
    const int degree = curve.degree;
    if (derivative > 0) {
        int hd = derivative > curve.degree ? 0 : curve.degree - derivative;
        hodo = malloc(sizeof(double) * (size_t)(hd + 1) * (size_t)dim);
        habs = malloc(sizeof(double) * (size_t)(degree + 1) * (size_t)dim);
        if (!hodo || !habs) {
            rc = cli_error("eval", "out of memory");
            goto done;
        }
        cj_status st = cj_bezier_hodograph(&curve, derivative, hodo);
        if (st) {
            rc = cli_fail("eval", "%s", cj_last_error());
            goto done;
        }
        if (want_bound && derivative <= degree)
            hodograph_magnitude(pts, degree, dim, derivative, habs);
        curve = cj_bezier_view(hd, dim, hodo);
    }
    for (size_t j = 0; j < nt && rc == 0; ++j) {
        double *v = vals + j * (size_t)dim * 2, *b = v + dim;
        cj_status st;
        if (method == CJ_EVAL_COMPENSATED)
            st = cj_bezier_eval_compensated(&curve, ts[j], v, want_bound ? b : NULL);
        else {
            st = cj_bezier_eval(&curve, method, ts[j], v);
            if (!st && want_bound) st = cj_bezier_error_bound(&curve, method, ts[j], b);
        }
        if (st) {
            rc = cli_fail("eval", "%s", cj_last_error());
            break;
        }
        if (want_bound && derivative > 0 && derivative <= degree)
            add_hodograph_error(habs, degree - derivative, dim, derivative, ts[j], b);
        /* Never print inf or nan: a result beyond the double range is refused, naming T. */
        for (int k = 0; k < (want_bound ? 2 : 1) * dim && rc == 0; ++k)
            if (!isfinite(v[k]))
                rc = cli_fail("eval",
                              "the %s at T = %.17g, coordinate %d, overflows the double range "
                              "(the control points given to --points are too large)",
                              k < dim ? (derivative ? "derivative" : "value") : "error bound",
                              ts[j], k % dim);
    }
    if (rc) goto done;
    for (size_t j = 0; j < nt; ++j) {
        const double *v = vals + j * (size_t)dim * 2, *b = v + dim;
        for (int k = 0; k < dim; ++k) {
            if (k) putchar(' ');
            cli_print_double(v[k]);
        }
        if (want_bound) {
            fputs(" |", stdout);
            for (int k = 0; k < dim; ++k) {
                putchar(' ');
                cli_print_double(b[k]);
            }
        }
        putchar('\n');
    }
    if (fflush(stdout) != 0 || ferror(stdout)) rc = cli_error("eval", "cannot write the output");
done:
    free(targs);
    free(hodo);
    free(habs);
    free(ts);
    free(vals);
    free(pts);
    return rc;
}

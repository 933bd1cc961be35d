/* casteljau eval: the evaluation contract other tools and tests rely on (see README). */
#include "cli.h"

#include "casteljau/bezier.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char eval_usage[] =
    "usage: casteljau eval [--method decasteljau|bernstein|horner|compensated] "
    "[--derivative K] [--bound] --points \"x0,y0;x1,y1;...\" T [T ...]\n";

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

int cmd_eval(int argc, char **argv) {
    cj_eval_method method = CJ_EVAL_DECASTELJAU;
    int derivative = 0, want_bound = 0;
    const char *points_text = NULL;
    int first_t = -1;
    for (int i = 1; i < argc; ++i) {
        const char *a = argv[i];
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            fputs(eval_usage, stdout);
            return 0;
        } else if (!strcmp(a, "--method")) {
            if (++i >= argc) return cli_fail("eval", "--method needs a value");
            if (parse_method(argv[i], &method))
                return cli_fail("eval",
                                "unknown method '%s' (decasteljau, bernstein, horner, compensated)",
                                argv[i]);
        } else if (!strcmp(a, "--derivative")) {
            if (++i >= argc) return cli_fail("eval", "--derivative needs a value");
            char *end = NULL;
            long k = strtol(argv[i], &end, 10);
            if (end == argv[i] || *end != '\0' || k < 0 || k > CJ_BEZIER_MAX_DEGREE + 1)
                return cli_fail("eval", "--derivative '%s' is not an order between 0 and %d",
                                argv[i], CJ_BEZIER_MAX_DEGREE + 1);
            derivative = (int)k;
        } else if (!strcmp(a, "--bound")) {
            want_bound = 1;
        } else if (!strcmp(a, "--points")) {
            if (++i >= argc) return cli_fail("eval", "--points needs a value");
            points_text = argv[i];
        } else if (a[0] == '-' && a[1] == '-') {
            return cli_fail("eval", "unknown option '%s'", a);
        } else {
            if (first_t < 0) first_t = i;
            /* Parameters must be contiguous at the end, after every option. */
            for (int j = i; j < argc; ++j)
                if (argv[j][0] == '-' && argv[j][1] == '-')
                    return cli_fail("eval", "option '%s' after the parameters", argv[j]);
            break;
        }
    }
    if (!points_text) return cli_fail("eval", "missing --points");
    if (first_t < 0) return cli_fail("eval", "no parameter T given");

    double *pts = NULL, *hodo = NULL, *habs = NULL;
    size_t npts = 0;
    int dim = 0;
    char why[256];
    if (cli_parse_points(points_text, &pts, &npts, &dim, why, sizeof why))
        return cli_fail("eval", "--points: %s", why);
    if (dim > CJ_MAX_DIM) {
        free(pts);
        return cli_fail("eval", "--points: dimension %d exceeds %d", dim, CJ_MAX_DIM);
    }
    const int nt = argc - first_t;
    double *ts = malloc(sizeof(double) * (size_t)nt);
    /* Results are computed in full before anything is printed: a bad T prints nothing. */
    double *vals = malloc(sizeof(double) * (size_t)nt * (size_t)dim * 2);
    int rc = 0;
    if (!ts || !vals) {
        rc = cli_fail("eval", "out of memory");
        goto done;
    }
    for (int j = 0; j < nt; ++j)
        if (cli_parse_double(argv[first_t + j], &ts[j])) {
            rc = cli_fail("eval", "parameter '%s' is not a finite number", argv[first_t + j]);
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
            rc = cli_fail("eval", "out of memory");
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
    for (int j = 0; j < nt && rc == 0; ++j) {
        double *v = vals + (size_t)j * (size_t)dim * 2, *b = v + dim;
        cj_status st;
        if (method == CJ_EVAL_COMPENSATED)
            st = cj_bezier_eval_compensated(&curve, ts[j], v, want_bound ? b : NULL);
        else {
            st = cj_bezier_eval(&curve, method, ts[j], v);
            if (!st && want_bound) st = cj_bezier_error_bound(&curve, method, ts[j], b);
        }
        if (st)
            rc = cli_fail("eval", "%s", cj_last_error());
        else if (want_bound && derivative > 0 && derivative <= degree)
            add_hodograph_error(habs, degree - derivative, dim, derivative, ts[j], b);
    }
    if (rc) goto done;
    for (int j = 0; j < nt; ++j) {
        const double *v = vals + (size_t)j * (size_t)dim * 2, *b = v + dim;
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
done:
    free(hodo);
    free(habs);
    free(ts);
    free(vals);
    free(pts);
    return rc;
}

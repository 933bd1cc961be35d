/* casteljau interp: curves through points, printed as Bézier segments in the --points syntax
 * of `casteljau eval`, one segment per line (see README). */
#include "cli.h"

#include "casteljau/bezier.h"
#include "casteljau/catmull_rom.h"
#include "casteljau/interp.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char interp_usage[] =
    "usage: casteljau interp [--kind catmull-rom|centripetal|chordal|kochanek-bartels|polynomial]\n"
    "                        [--tension K] [--continuity C] [--bias B] [--closed]\n"
    "                        [--params \"t0;t1;...\"] --points \"x0,y0;x1,y1;...\"\n"
    "Curves through the given points (any dimension 1..8, the same for every point).\n"
    "  --kind        catmull-rom (default; uniform), centripetal, chordal, kochanek-bartels\n"
    "                (cubic spline segments), or polynomial (one interpolating polynomial)\n"
    "  --tension     Catmull-Rom tension kappa (default 0.5; kochanek-bartels: 0)\n"
    "  --continuity, --bias   Kochanek-Bartels parameters (default 0)\n"
    "  --closed      a closed spline (the last point joins the first)\n"
    "  --params      polynomial only: one parameter per point (default equispaced on [0,1])\n"
    "Options may come in any order, as --opt value or --opt=value.\n"
    "Output: one Bezier segment per line as \"x,y;x,y;...\" (%.17g), the syntax of\n"
    "'casteljau eval --points'. Splines print cubic segments; polynomial prints one segment of\n"
    "degree N-1 over [min t, max t]. Exit status 0; 2 for a bad argument or input, or control\n"
    "points that overflow the double range (one line on stderr); 1 when out of memory.\n";

enum { KIND_POLY = -1 };

static int parse_kind(const char *s, int *kind) {
    static const struct {
        const char *name;
        int kind;
    } names[] = {{"catmull-rom", CJ_SPLINE_CATMULL_ROM},
                 {"centripetal", CJ_SPLINE_CENTRIPETAL},
                 {"chordal", CJ_SPLINE_CHORDAL},
                 {"kochanek-bartels", CJ_SPLINE_KOCHANEK_BARTELS},
                 {"polynomial", KIND_POLY}};
    for (size_t i = 0; i < sizeof names / sizeof names[0]; ++i)
        if (!strcmp(s, names[i].name)) {
            *kind = names[i].kind;
            return 0;
        }
    return -1;
}

static int all_finite(const double *v, size_t n) {
    for (size_t i = 0; i < n; ++i)
        if (!isfinite(v[i])) return 0;
    return 1;
}

static void print_segment(const double *pts, int npts, int dim) {
    for (int i = 0; i < npts; ++i) {
        if (i) putchar(';');
        for (int k = 0; k < dim; ++k) {
            if (k) putchar(',');
            cli_print_double(pts[i * dim + k]);
        }
    }
    putchar('\n');
}

int cmd_interp(int argc, char **argv) {
    int kind = CJ_SPLINE_CATMULL_ROM, closed = 0;
    double tension = 0.5, continuity = 0.0, bias = 0.0;
    int have_tension = 0, have_cb = 0;
    const char *points_text = NULL, *params_text = NULL;
    enum { O_KIND, O_TENSION, O_CONT, O_BIAS, O_CLOSED, O_POINTS, O_PARAMS };
    static const cli_opt opts[] = {{"--kind", NULL, 1},       {"--tension", NULL, 1},
                                   {"--continuity", NULL, 1}, {"--bias", NULL, 1},
                                   {"--closed", NULL, 0},     {"--points", NULL, 1},
                                   {"--params", NULL, 1}};
    cli_parser ps;
    cli_parser_init(&ps, "interp", interp_usage, argc, argv, opts, sizeof opts / sizeof opts[0]);
    const char *v;
    int k, status;
    while (cli_next_arg(&ps, &k, &v, &status)) {
        char q[160];
        if (k == CLI_POSITIONAL)
            return cli_fail("interp", "unexpected argument '%s' (the points go in --points)",
                            cli_quote(v, q, sizeof q));
        if (k == O_KIND) {
            if (parse_kind(v, &kind))
                return cli_fail("interp",
                                "unknown kind '%s' (catmull-rom, centripetal, chordal, "
                                "kochanek-bartels, polynomial)",
                                cli_quote(v, q, sizeof q));
        } else if (k == O_TENSION || k == O_CONT || k == O_BIAS) {
            double x;
            if (cli_parse_double(v, &x))
                return cli_fail("interp", "%s '%s' is not a finite number", opts[k].name,
                                cli_quote(v, q, sizeof q));
            if (k == O_TENSION) {
                tension = x;
                have_tension = 1;
            } else {
                if (k == O_CONT)
                    continuity = x;
                else
                    bias = x;
                have_cb = 1;
            }
        } else if (k == O_CLOSED) {
            closed = 1;
        } else if (k == O_POINTS) {
            points_text = v;
        } else {
            params_text = v;
        }
    }
    if (status >= 0) return status;
    if (!points_text) return cli_fail("interp", "missing --points (try 'casteljau interp --help')");
    if (kind == KIND_POLY && (have_tension || have_cb || closed))
        return cli_fail("interp", "--tension, --continuity, --bias and --closed apply to the "
                                  "spline kinds, not to --kind polynomial");
    if (kind != KIND_POLY && params_text)
        return cli_fail("interp", "--params applies only to --kind polynomial (splines choose "
                                  "their own knots)");
    if (have_cb && kind != CJ_SPLINE_KOCHANEK_BARTELS)
        return cli_fail("interp", "--continuity and --bias apply only to --kind "
                                  "kochanek-bartels");
    if (kind == CJ_SPLINE_KOCHANEK_BARTELS && !have_tension) tension = 0.0;

    double *pts = NULL, *ts = NULL, *out = NULL;
    size_t npts = 0, nts = 0;
    int dim = 0, rc = 0;
    char why[256];
    if (cli_parse_points(points_text, &pts, &npts, &dim, why, sizeof why))
        return cli_fail("interp", "--points: %s", why);
    if (dim > CJ_MAX_DIM) {
        rc = cli_fail("interp", "--points: dimension %d exceeds %d", dim, CJ_MAX_DIM);
        goto done;
    }
    if (kind == KIND_POLY) {
        if (params_text) {
            if (cli_parse_list(params_text, &ts, &nts, why, sizeof why)) {
                rc = cli_fail("interp", "--params: %s", why);
                goto done;
            }
            if (nts != npts) {
                rc = cli_fail("interp", "--params has %zu values for %zu points", nts, npts);
                goto done;
            }
        } else {
            nts = npts;
            ts = malloc(sizeof(double) * (npts ? npts : 1));
            if (!ts) {
                rc = cli_error("interp", "out of memory");
                goto done;
            }
            if (npts == 1)
                ts[0] = 0.0;
            else if (npts > 1 && cj_interp_equispaced((int)npts - 1, 0.0, 1.0, ts)) {
                rc = cli_fail("interp", "%s", cj_last_error());
                goto done;
            }
        }
        double a = ts[0], b = ts[0];
        for (size_t j = 1; j < nts; ++j) {
            a = ts[j] < a ? ts[j] : a;
            b = ts[j] > b ? ts[j] : b;
        }
        if (npts == 1) b = a + 1.0; /* a constant: any interval */
        if (!(a < b)) {
            rc = cli_fail("interp", "--params: all parameters are equal (%.17g)", a);
            goto done;
        }
        out = malloc(sizeof(double) * npts * (size_t)dim);
        if (!out) {
            rc = cli_error("interp", "out of memory");
            goto done;
        }
        if (cj_interp_points(ts, pts, npts, dim, a, b, out, NULL, NULL)) {
            rc = cli_fail("interp", "%s", cj_last_error());
            goto done;
        }
        if (!all_finite(out, npts * (size_t)dim)) {
            rc = cli_fail("interp", "the interpolating polynomial's control points overflow the "
                                    "double range (--points and --params span too much)");
            goto done;
        }
        print_segment(out, (int)npts, dim);
    } else {
        cj_spline_options o = cj_spline_defaults();
        o.kind = (cj_spline_kind)kind;
        o.tension = tension;
        o.continuity = continuity;
        o.bias = bias;
        o.closed = closed;
        const size_t nseg = cj_spline_segment_count(npts, closed);
        out = malloc(sizeof(double) * 4 * (size_t)dim * (nseg ? nseg : 1));
        if (!out) {
            rc = cli_error("interp", "out of memory");
            goto done;
        }
        if (cj_catmull_rom(pts, npts, dim, &o, out, nseg, NULL, NULL)) {
            rc = cli_fail("interp", "%s", cj_last_error());
            goto done;
        }
        if (!all_finite(out, nseg * 4 * (size_t)dim)) {
            rc = cli_fail("interp", "the spline's control points overflow the double range "
                                    "(--points, --tension, --continuity or --bias too large)");
            goto done;
        }
        for (size_t s = 0; s < nseg; ++s) print_segment(out + s * 4 * (size_t)dim, 4, dim);
    }
    if (!rc && (fflush(stdout) != 0 || ferror(stdout)))
        rc = cli_error("interp", "cannot write the output");
done:
    free(pts);
    free(ts);
    free(out);
    return rc;
}

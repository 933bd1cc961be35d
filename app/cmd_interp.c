/* casteljau interp: curves through points, printed as Bézier segments in the --points syntax
 * of `casteljau eval`, one segment per line (see README). */
#include "cli.h"

#include "casteljau/bezier.h"
#include "casteljau/catmull_rom.h"
#include "casteljau/interp.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char interp_usage[] =
    "usage: casteljau interp [--kind catmull-rom|centripetal|chordal|kochanek-bartels|polynomial]\n"
    "                        [--tension K] [--continuity C] [--bias B] [--closed]\n"
    "                        [--params \"t0;t1;...\"] --points \"x0,y0;x1,y1;...\"\n"
    "Prints one Bezier segment per line as \"x,y;x,y;...\" (%.17g), the syntax of\n"
    "'casteljau eval --points'. Splines print cubic segments; polynomial prints one segment of\n"
    "degree N-1 over [min t, max t] (default parameters: equispaced on [0,1]).\n";

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
    for (int i = 1; i < argc; ++i) {
        const char *a = argv[i];
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            fputs(interp_usage, stdout);
            return 0;
        } else if (!strcmp(a, "--kind")) {
            if (++i >= argc) return cli_fail("interp", "--kind needs a value");
            if (parse_kind(argv[i], &kind))
                return cli_fail("interp",
                                "unknown kind '%s' (catmull-rom, centripetal, chordal, "
                                "kochanek-bartels, polynomial)",
                                argv[i]);
        } else if (!strcmp(a, "--tension") || !strcmp(a, "--continuity") || !strcmp(a, "--bias")) {
            if (++i >= argc) return cli_fail("interp", "%s needs a value", a);
            double v;
            if (cli_parse_double(argv[i], &v))
                return cli_fail("interp", "%s '%s' is not a finite number", a, argv[i]);
            if (a[2] == 't') {
                tension = v;
                have_tension = 1;
            } else {
                if (a[2] == 'c')
                    continuity = v;
                else
                    bias = v;
                have_cb = 1;
            }
        } else if (!strcmp(a, "--closed")) {
            closed = 1;
        } else if (!strcmp(a, "--points")) {
            if (++i >= argc) return cli_fail("interp", "--points needs a value");
            points_text = argv[i];
        } else if (!strcmp(a, "--params")) {
            if (++i >= argc) return cli_fail("interp", "--params needs a value");
            params_text = argv[i];
        } else {
            return cli_fail("interp", "unknown argument '%s' (try --help)", a);
        }
    }
    if (!points_text) return cli_fail("interp", "missing --points");
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
                rc = cli_fail("interp", "out of memory");
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
            rc = cli_fail("interp", "out of memory");
            goto done;
        }
        if (cj_interp_points(ts, pts, npts, dim, a, b, out, NULL, NULL)) {
            rc = cli_fail("interp", "%s", cj_last_error());
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
            rc = cli_fail("interp", "out of memory");
            goto done;
        }
        if (cj_catmull_rom(pts, npts, dim, &o, out, nseg, NULL, NULL)) {
            rc = cli_fail("interp", "%s", cj_last_error());
            goto done;
        }
        for (size_t s = 0; s < nseg; ++s) print_segment(out + s * 4 * (size_t)dim, 4, dim);
    }
done:
    free(pts);
    free(ts);
    free(out);
    return rc;
}

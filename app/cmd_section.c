/* casteljau section: plane sections of Bézier patches as polylines with a proven deviation
 * (patch_section.h); and `casteljau nearest --point X,Y,Z` on patches (patch_nearest.h), which
 * cmd_nearest hands over here when a patch model is given. Both read the models tessellate
 * reads: --teapot, --bpt FILE, or one --patch with --degree (and --weights). */
#include "cli.h"
#include "cli_guard.h"
#include "file_internal.h"

#include "casteljau/patch.h"
#include "casteljau/patch_nearest.h"
#include "casteljau/patch_section.h"
#include "casteljau/patchset.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char section_usage[] =
    "usage: casteljau section --plane NX,NY,NZ,D (--teapot | --bpt FILE |\n"
    "                         --patch \"x,y,z;...\" --degree M,N [--weights \"w;...\"])\n"
    "                         [--tol T] [-o OUT.obj]\n"
    "The section of each Bezier patch by the plane NX x + NY y + NZ z = D, as polylines whose\n"
    "distance to the true section (both ways) is proven <= the reported deviation <= T.\n"
    "  --plane   the plane's normal (need not be unit) and offset\n"
    "  --tol     default 1e-3 times the model's bounding-box diagonal; vertices come about T\n"
    "            apart (the proof is by cells of that size)\n"
    "  -o        also write the polylines as an OBJ file of 'v' and 'l' lines (atomically)\n"
    "Stdout, one line each: 'line P K open|closed N' (patch P, polyline K, N points) then the N\n"
    "points 'X Y Z'; 'unresolved P X Y Z' for a cell smaller than T that may hold a tiny loop or\n"
    "a touching point; finally 'section patches P lines L points N unresolved U ambiguous A\n"
    "deviation D plane_gap G' (A: cells paired at a saddle, a branch point of the section).\n"
    "Polylines are per patch: they meet at shared patch edges but are not joined there.\n"
    "Exit status 0; 2 for a bad argument or input, naming it.\n";

static const char nearest_patch_usage[] =
    "usage: casteljau nearest --point X,Y,Z (--teapot | --bpt FILE |\n"
    "                         --patch \"x,y,z;...\" --degree M,N [--weights \"w;...\"]) [--tol T]\n"
    "The certified nearest point of the patches to (X,Y,Z): branch and bound with proven lower\n"
    "bounds, so the answer is the global minimum within T (default 1e-9 times the size).\n"
    "Stdout: one line per patch 'P U V X Y Z DISTANCE LOWER', then 'nearest P U V X Y Z DISTANCE\n"
    "LOWER' for the nearest patch (LOWER: a proven lower bound over all patches).\n"
    "Exit status 0; 2 for a bad argument or input, naming it.\n";

typedef struct model {
    cj_patchset *set;
    cj_patch single;
    double *pts, *weights;
    const cj_patch *patches;
    size_t count;
    double size;
} model;

static void model_free(model *M) {
    if (M->set) cj_patchset_destroy(M->set);
    free(M->pts);
    free(M->weights);
}

/* Loads the one model given; returns 0 or the exit status (the message printed). */
static int model_load(const char *cmd, int teapot, const char *bpt, const char *patch_text,
                      const char *degree_text, const char *weights_text, model *M) {
    memset(M, 0, sizeof *M);
    int models = (teapot != 0) + (bpt != NULL) + (patch_text != NULL);
    if (models > 1) return cli_fail(cmd, "give one of --teapot, --bpt or --patch");
    if (models == 0) return cli_fail(cmd, "no model: give --teapot, --bpt FILE or --patch");
    if (patch_text && !degree_text) return cli_fail(cmd, "--patch needs --degree M,N");
    if (!patch_text && degree_text) return cli_fail(cmd, "--degree is only for --patch");
    if (!patch_text && weights_text) return cli_fail(cmd, "--weights is only for --patch");
    if (teapot || bpt) {
        cj_status st = cj_patchset_load_bpt(teapot ? cli_teapot_path() : bpt, NULL, &M->set);
        if (st)
            return st == CJ_ERR_NOMEM
                       ? cli_error(cmd, "%s", cj_last_error())
                       : cli_fail(cmd, "%s: %s", teapot ? "teapot data" : "--bpt", cj_last_error());
        M->patches = M->set->patches;
        M->count = M->set->count;
        double lo[3], hi[3];
        if (cj_patchset_bbox(M->set, lo, hi, &M->size)) return cli_fail(cmd, "%s", cj_last_error());
        return 0;
    }
    int m, n;
    if (cli_parse_degree(degree_text, &m, &n))
        return cli_fail(cmd, "--degree '%s': M and N must be integers in 0..%d", degree_text,
                        CJ_PATCH_MAX_DEGREE);
    size_t npts;
    int dim;
    char why[256];
    if (cli_parse_points(patch_text, &M->pts, &npts, &dim, why, sizeof why) != 0)
        return cli_fail(cmd, "--patch: %s", why);
    const size_t need = (size_t)(m + 1) * (size_t)(n + 1);
    if (dim != 3) return cli_fail(cmd, "--patch: points have %d coordinates, patches need 3", dim);
    if (npts != need)
        return cli_fail(cmd, "--patch has %zu points but degree %d,%d needs (M+1)(N+1) = %zu", npts,
                        m, n, need);
    if (weights_text) {
        size_t nw;
        if (cli_parse_list(weights_text, &M->weights, &nw, why, sizeof why) != 0)
            return cli_fail(cmd, "--weights: %s", why);
        if (nw != need)
            return cli_fail(cmd, "--weights has %zu values but --patch has %zu points", nw, need);
    }
    M->single = cj_patch_view(m, n, M->pts, M->weights);
    if (cj_patch_check(&M->single)) return cli_fail(cmd, "--patch: %s", cj_last_error());
    if (cj_patch_size(&M->single, &M->size)) return cli_fail(cmd, "--patch: %s", cj_last_error());
    M->patches = &M->single;
    M->count = 1;
    return 0;
}

static int parse_numbers(const char *cmd, const char *opt, const char *v, double *out, int n) {
    double *vals = NULL;
    size_t count = 0;
    char why[200], q[160];
    if (cli_parse_list(v, &vals, &count, why, sizeof why) != 0)
        return cli_fail(cmd, "%s '%s': %s", opt, cli_quote(v, q, sizeof q), why);
    if ((int)count != n) {
        free(vals);
        return cli_fail(cmd, "%s '%s': expected %d numbers, got %zu", opt,
                        cli_quote(v, q, sizeof q), n, count);
    }
    memcpy(out, vals, (size_t)n * sizeof *out);
    free(vals);
    return 0;
}

enum { O_PLANE, O_POINT, O_TEAPOT, O_BPT, O_PATCH, O_DEGREE, O_WEIGHTS, O_TOL, O_OUT };
static const cli_opt patch_opts[] = {
    {"--plane", NULL, 1},   {"--point", NULL, 1}, {"--teapot", NULL, 0},
    {"--bpt", NULL, 1},     {"--patch", NULL, 1}, {"--degree", NULL, 1},
    {"--weights", NULL, 1}, {"--tol", NULL, 1},   {"--output", "-o", 1}};

typedef struct popts {
    double plane[4], point[3], tol;
    int have_plane, have_point, teapot;
    const char *bpt, *patch, *degree, *weights, *out;
} popts;

static int parse_patch_args(const char *cmd, const char *usage, int argc, char **argv, int section,
                            popts *o) {
    cli_parser ps;
    cli_parser_init(&ps, cmd, usage, argc, argv, patch_opts,
                    sizeof patch_opts / sizeof *patch_opts);
    memset(o, 0, sizeof *o);
    int k, status;
    const char *v;
    while (cli_next_arg(&ps, &k, &v, &status)) {
        char q[160];
        if (k == CLI_POSITIONAL)
            return cli_fail(cmd,
                            "unexpected argument '%s' (the model comes with --teapot, --bpt "
                            "or --patch)",
                            cli_quote(v, q, sizeof q));
        if ((k == O_PLANE || k == O_OUT) && !section)
            return cli_fail(cmd, "%s does not apply to 'nearest' on patches", patch_opts[k].name);
        if (k == O_POINT && section)
            return cli_fail(cmd, "--point does not apply to 'section' (try --plane)");
        switch (k) {
        case O_PLANE:
            if (parse_numbers(cmd, "--plane", v, o->plane, 4)) return CLI_EXIT_USAGE;
            if (o->plane[0] == 0 && o->plane[1] == 0 && o->plane[2] == 0)
                return cli_fail(cmd, "--plane: the normal (NX,NY,NZ) is (0,0,0)");
            o->have_plane = 1;
            break;
        case O_POINT:
            if (parse_numbers(cmd, "--point", v, o->point, 3)) return CLI_EXIT_USAGE;
            o->have_point = 1;
            break;
        case O_TEAPOT:
            o->teapot = 1;
            break;
        case O_BPT:
            o->bpt = v;
            break;
        case O_PATCH:
            o->patch = v;
            break;
        case O_DEGREE:
            o->degree = v;
            break;
        case O_WEIGHTS:
            o->weights = v;
            break;
        case O_TOL:
            if (cli_parse_double(v, &o->tol) || !(o->tol > 0))
                return cli_fail(cmd, "--tol '%s' is not a positive number",
                                cli_quote(v, q, sizeof q));
            break;
        default:
            o->out = v;
            break;
        }
    }
    if (status >= 0) return status;
    if (section && !o->have_plane) return cli_fail(cmd, "missing --plane NX,NY,NZ,D");
    if (!section && !o->have_point) return cli_fail(cmd, "missing --point X,Y,Z");
    if (o->out && !cli_has_ext(o->out, ".obj"))
        return cli_fail(cmd, "output '%s' must end in .obj", o->out);
    return -1;
}

int cmd_section(int argc, char **argv) {
    const char *cmd = "section";
    popts o;
    int rc = parse_patch_args(cmd, section_usage, argc, argv, 1, &o);
    if (rc >= 0) return rc;
    if (o.out && (rc = cli_check_output(cmd, "output", o.out))) return rc;
    model M;
    if ((rc = model_load(cmd, o.teapot, o.bpt, o.patch, o.degree, o.weights, &M))) {
        model_free(&M);
        return rc;
    }
    double tol = o.tol > 0 ? o.tol : 1e-3 * (M.size > 0 ? M.size : 1.0);
    FILE *obj = NULL;
    cj_atomic_file af;
    if (o.out) { /* written atomically: complete or not at all */
        if (cj_atomic_open(&af, o.out) != CJ_OK) {
            model_free(&M);
            return cli_error(cmd, "%s", cj_last_error());
        }
        obj = af.fp;
    }
    long lines = 0, points = 0, unresolved = 0, ambiguous = 0, vbase = 1;
    double deviation = 0, gap = 0;
    for (size_t i = 0; i < M.count && rc == 0; ++i) {
        cj_patch_section s;
        cj_status st = cj_patch_section_plane(&M.patches[i], o.plane, o.plane[3], tol, &s);
        if (st) {
            rc = st == CJ_ERR_NOMEM ? cli_error(cmd, "%s", cj_last_error())
                                    : cli_fail(cmd, "patch %zu: %s", i, cj_last_error());
            break;
        }
        for (int l = 0; l < s.nlines; ++l) {
            int a = s.starts[l], b = s.starts[l + 1];
            printf("line %zu %ld %s %d\n", i, lines, s.closed[l] ? "closed" : "open", b - a);
            for (int j = a; j < b; ++j)
                printf("%.17g %.17g %.17g\n", s.pts[3 * j], s.pts[3 * j + 1], s.pts[3 * j + 2]);
            if (obj) {
                for (int j = a; j < b; ++j)
                    fprintf(obj, "v %.17g %.17g %.17g\n", s.pts[3 * j], s.pts[3 * j + 1],
                            s.pts[3 * j + 2]);
                fprintf(obj, "l");
                for (int j = a; j < b; ++j) fprintf(obj, " %ld", vbase + (j - a));
                if (s.closed[l] && b - a > 1) fprintf(obj, " %ld", vbase);
                fprintf(obj, "\n");
                vbase += b - a;
            }
            ++lines;
        }
        for (int j = 0; j < s.nunresolved; ++j)
            printf("unresolved %zu %.17g %.17g %.17g\n", i, s.unresolved[3 * j],
                   s.unresolved[3 * j + 1], s.unresolved[3 * j + 2]);
        points += s.npts;
        unresolved += s.nunresolved;
        ambiguous += s.ambiguous;
        deviation = fmax(deviation, s.deviation);
        gap = fmax(gap, s.plane_gap);
        cj_patch_section_free(&s);
    }
    if (obj) {
        if (rc != 0)
            cj_atomic_abandon(&af);
        else if (cj_atomic_commit(&af) != CJ_OK)
            rc = cli_error(cmd, "%s", cj_last_error());
    }
    if (rc == 0)
        printf("section patches %zu lines %ld points %ld unresolved %ld ambiguous %ld deviation "
               "%.3g plane_gap %.3g\n",
               M.count, lines, points, unresolved, ambiguous, deviation, gap);
    model_free(&M);
    return rc;
}

int cmd_nearest_patch(int argc, char **argv) {
    const char *cmd = "nearest";
    popts o;
    int rc = parse_patch_args(cmd, nearest_patch_usage, argc, argv, 0, &o);
    if (rc >= 0) return rc;
    model M;
    if ((rc = model_load(cmd, o.teapot, o.bpt, o.patch, o.degree, o.weights, &M))) {
        model_free(&M);
        return rc;
    }
    double scale = fmax(M.size, fmax(fabs(o.point[0]), fmax(fabs(o.point[1]), fabs(o.point[2]))));
    double tol = o.tol > 0 ? o.tol : 1e-9 * (scale > 0 ? scale : 1.0);
    cj_patch_nearest_result best;
    memset(&best, 0, sizeof best);
    size_t bi = 0;
    double lower = INFINITY;
    best.distance = INFINITY;
    for (size_t i = 0; i < M.count; ++i) {
        cj_patch_nearest_result r;
        cj_status st = cj_patch_nearest(&M.patches[i], o.point, tol, &r);
        if (st) {
            rc = st == CJ_ERR_NOMEM ? cli_error(cmd, "%s", cj_last_error())
                                    : cli_fail(cmd, "patch %zu: %s", i, cj_last_error());
            break;
        }
        printf("%zu %.17g %.17g %.17g %.17g %.17g %.17g %.17g\n", i, r.u, r.v, r.point[0],
               r.point[1], r.point[2], r.distance, r.lower);
        lower = fmin(lower, r.lower);
        if (r.distance < best.distance) best = r, bi = i;
    }
    if (rc == 0)
        printf("nearest %zu %.17g %.17g %.17g %.17g %.17g %.17g %.17g\n", bi, best.u, best.v,
               best.point[0], best.point[1], best.point[2], best.distance, lower);
    model_free(&M);
    return rc;
}

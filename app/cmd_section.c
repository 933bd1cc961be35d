/* casteljau section: plane sections of Bézier patches as polylines with a proven deviation
 * (patch_section.h); and `casteljau nearest --point X,Y,Z` on patches (patch_nearest.h), which
 * cmd_nearest hands over here when a patch model is given. Both read the models tessellate
 * reads: --teapot, --bpt FILE, or one --patch with --degree (and --weights). */
#include "cli.h"
#include "cli_guard.h"
#include "file_internal.h"
#include "surface_load.h"

#include "casteljau/patch.h"
#include "casteljau/patch_nearest.h"
#include "casteljau/patch_section.h"
#include "casteljau/patchset.h"

#include <cJSON.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char section_usage[] =
    "usage: casteljau section --plane NX,NY,NZ,D (--teapot | --bpt FILE | --surface FILE.json |\n"
    "                         --patch \"x,y,z;...\" --degree M,N [--weights \"w;...\"])\n"
    "                         [--tol T] [--json] [-o OUT.json|OUT.obj]\n"
    "The section of the model by the plane NX x + NY y + NZ z = D as curves made of cubic Bezier\n"
    "pieces, joined across the patches (a closed curve where the section closes), whose distance "
    "to\n"
    "the true section (both ways) is proven <= the reported deviation <= T.\n"
    "  --plane   the plane's normal (need not be unit) and offset\n"
    "  --surface a B-spline or NURBS surface (JSON, as tessellate --surface reads)\n"
    "  --tol     default 1e-3 times the model's bounding-box diagonal\n"
    "  --json    write the curves to stdout as a plot document (casteljau plot reads it): one\n"
    "            'bspline' item per curve (degree 3, its pieces joined at triple knots) in the\n"
    "            plane's coordinates (axes e1, e2 named in the title; for a horizontal plane x, "
    "y)\n"
    "  -o        also write the curves: OUT.json the plot document, OUT.obj the proven polylines\n"
    "            of the curves ('v' and 'l' lines, joined; a closed curve repeats its first "
    "vertex)\n"
    "Stdout (text): per curve 'curve K open|closed P' then its P pieces, one line of 12 numbers\n"
    "(4 control points X Y Z); 'unresolved X Y Z' for a cell smaller than T that may hold a tiny\n"
    "loop or a touching point; finally 'section patches P curves C closed Z pieces K points N\n"
    "joins J unresolved U ambiguous A deviation D polylines E plane_gap G' (E: the polylines'\n"
    "proven deviation, J: ends of per-patch lines joined at shared patch edges, A: saddle cells,\n"
    "branch points of the section).\n"
    "Exit status 0; 2 for a bad argument or input, naming it.\n";

static const char nearest_patch_usage[] =
    "usage: casteljau nearest --point X,Y,Z (--teapot | --bpt FILE | --surface FILE.json |\n"
    "                         --patch \"x,y,z;...\" --degree M,N [--weights \"w;...\"]) [--tol T]\n"
    "The certified nearest point of the patches to (X,Y,Z): branch and bound with proven lower\n"
    "bounds, so the answer is the global minimum within T (default 1e-9 times the size).\n"
    "Stdout: one line per patch 'P U V X Y Z DISTANCE LOWER', then 'nearest P U V X Y Z DISTANCE\n"
    "LOWER' for the nearest patch (LOWER: a proven lower bound over all patches).\n"
    "Exit status 0; 2 for a bad argument or input, naming it.\n";

typedef struct model {
    cj_patchset *set;
    surface_patches surf;
    cj_patch single;
    double *pts, *weights;
    const cj_patch *patches;
    size_t count;
    double size;
} model;

static void model_free(model *M) {
    if (M->set) cj_patchset_destroy(M->set);
    surface_patches_free(&M->surf);
    free(M->pts);
    free(M->weights);
}

/* Loads the one model given; returns 0 or the exit status (the message printed). */
static int model_load(const char *cmd, int teapot, const char *bpt, const char *surface,
                      const char *patch_text, const char *degree_text, const char *weights_text,
                      model *M) {
    memset(M, 0, sizeof *M);
    int models = (teapot != 0) + (bpt != NULL) + (surface != NULL) + (patch_text != NULL);
    if (models > 1) return cli_fail(cmd, "give one of --teapot, --bpt, --surface or --patch");
    if (models == 0)
        return cli_fail(cmd, "no model: give --teapot, --bpt FILE, --surface FILE or --patch");
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
    if (surface) {
        char why[256];
        int nomem = 0;
        if (surface_load(surface, &M->surf, why, sizeof why, &nomem))
            return nomem ? cli_error(cmd, "--surface: %s", why)
                         : cli_fail(cmd, "--surface: %s", why);
        M->patches = M->surf.patches;
        M->count = M->surf.count;
        double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
        for (size_t i = 0; i < M->count; ++i) {
            const cj_patch *p = &M->patches[i];
            for (int k = 0; k < 3 * (p->deg_u + 1) * (p->deg_v + 1); ++k) {
                lo[k % 3] = fmin(lo[k % 3], p->pts[k]);
                hi[k % 3] = fmax(hi[k % 3], p->pts[k]);
            }
        }
        M->size = sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                       (hi[2] - lo[2]) * (hi[2] - lo[2]));
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

enum {
    O_PLANE,
    O_POINT,
    O_TEAPOT,
    O_BPT,
    O_PATCH,
    O_DEGREE,
    O_WEIGHTS,
    O_TOL,
    O_OUT,
    O_SURFACE,
    O_JSON
};
static const cli_opt patch_opts[] = {
    {"--plane", NULL, 1},  {"--point", NULL, 1},   {"--teapot", NULL, 0},  {"--bpt", NULL, 1},
    {"--patch", NULL, 1},  {"--degree", NULL, 1},  {"--weights", NULL, 1}, {"--tol", NULL, 1},
    {"--output", "-o", 1}, {"--surface", NULL, 1}, {"--json", NULL, 0}};

typedef struct popts {
    double plane[4], point[3], tol;
    int have_plane, have_point, teapot, json;
    const char *bpt, *patch, *degree, *weights, *out, *surface;
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
        if ((k == O_PLANE || k == O_OUT || k == O_JSON) && !section)
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
        case O_SURFACE:
            o->surface = v;
            break;
        case O_JSON:
            o->json = 1;
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
    if (o->out && !cli_has_ext(o->out, ".obj") && !cli_has_ext(o->out, ".json"))
        return cli_fail(cmd, "output '%s' must end in .obj or .json", o->out);
    return -1;
}

/* Axes of the plane's own coordinates: for a plane that is not nearly horizontal e2 is the
 * vertical in it (z up) and e1 = n x e2; else e1 is x projected into it and e2 = n x e1, so
 * that a horizontal cut is drawn in x and y. */
static void plane_frame(const double n[3], double e1[3], double e2[3]) {
    double l = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]), u[3] = {n[0] / l, n[1] / l, n[2] / l};
    double *a = fabs(u[2]) < 0.9 ? e2 : e1, *b = fabs(u[2]) < 0.9 ? e1 : e2;
    double axis[3] = {0, 0, 0};
    axis[fabs(u[2]) < 0.9 ? 2 : 0] = 1;
    double dot = axis[0] * u[0] + axis[1] * u[1] + axis[2] * u[2], al = 0;
    for (int k = 0; k < 3; ++k) a[k] = axis[k] - dot * u[k], al += a[k] * a[k];
    for (int k = 0; k < 3; ++k) a[k] /= sqrt(al);
    b[0] = u[1] * a[2] - u[2] * a[1];
    b[1] = u[2] * a[0] - u[0] * a[2];
    b[2] = u[0] * a[1] - u[1] * a[0];
}

/* The plot document of the section: one cubic B-spline item per curve (its pieces joined at
 * triple knots) in the plane's coordinates, the unresolved points as a points item. */
static cJSON *section_json(const cj_section_curves *s, const double plane[4], double tol) {
    double e1[3], e2[3];
    plane_frame(plane, e1, e2);
    cJSON *doc = cJSON_CreateObject(), *items = cJSON_CreateArray();
    if (!doc || !items) {
        cJSON_Delete(doc), cJSON_Delete(items);
        return NULL;
    }
    char title[512];
    snprintf(title, sizeof title,
             "section by %g x + %g y + %g z = %g: %d curves, %d cubic pieces, deviation <= %.2g "
             "(tol %.2g); axes (%.3g, %.3g, %.3g) and (%.3g, %.3g, %.3g)",
             plane[0], plane[1], plane[2], plane[3], s->nchains, s->npieces, s->deviation, tol,
             e1[0], e1[1], e1[2], e2[0], e2[1], e2[2]);
    int ok = cJSON_AddStringToObject(doc, "title", title) != NULL;
    ok = ok && cJSON_AddItemToObject(doc, "items", items);
    if (!ok) cJSON_Delete(items);
    for (int c = 0; ok && c < s->nchains; ++c) {
        int a = s->piece_starts[c], b = s->piece_starts[c + 1], k = b - a;
        cJSON *it = cJSON_CreateObject(), *pts = cJSON_CreateArray(), *knots = cJSON_CreateArray();
        ok = it && pts && knots && cJSON_AddItemToArray(items, it);
        if (!ok) {
            cJSON_Delete(it), cJSON_Delete(pts), cJSON_Delete(knots);
            break;
        }
        ok = cJSON_AddStringToObject(it, "type", "bspline") &&
             cJSON_AddNumberToObject(it, "degree", 3);
        for (int i = 0; ok && i <= 3 * k; ++i) {
            /* point i: control point i % 3 of piece i / 3, the last one the end of the last */
            const double *x =
                s->ctrl + 12 * (a + (i == 3 * k ? k - 1 : i / 3)) + 3 * (i == 3 * k ? 3 : i % 3);
            double xy[2] = {x[0] * e1[0] + x[1] * e1[1] + x[2] * e1[2],
                            x[0] * e2[0] + x[1] * e2[1] + x[2] * e2[2]};
            cJSON *p = cJSON_CreateDoubleArray(xy, 2);
            ok = p && cJSON_AddItemToArray(pts, p);
        }
        for (int i = 0; ok && i < 3 * k + 5; ++i) {
            int v = i < 4 ? 0 : i >= 3 * k + 1 ? k : (i - 1) / 3;
            cJSON *num = cJSON_CreateNumber(v);
            ok = num && cJSON_AddItemToArray(knots, num);
        }
        ok = ok && cJSON_AddItemToObject(it, "points", pts);
        if (!ok) cJSON_Delete(pts);
        ok = ok && cJSON_AddItemToObject(it, "knots", knots);
        if (!ok) cJSON_Delete(knots);
        ok = ok && cJSON_AddStringToObject(it, "color", s->closed[c] ? "#1f4e9c" : "#2a8a3a") &&
             cJSON_AddFalseToObject(it, "control_polygon") &&
             cJSON_AddFalseToObject(it, "control_points") &&
             cJSON_AddFalseToObject(it, "knot_markers");
    }
    if (ok && s->nunresolved) {
        cJSON *it = cJSON_CreateObject(), *pts = cJSON_CreateArray();
        ok = it && pts && cJSON_AddItemToArray(items, it);
        if (!ok) cJSON_Delete(it), cJSON_Delete(pts);
        for (int i = 0; ok && i < s->nunresolved; ++i) {
            const double *x = s->unresolved + 3 * i;
            double xy[2] = {x[0] * e1[0] + x[1] * e1[1] + x[2] * e1[2],
                            x[0] * e2[0] + x[1] * e2[1] + x[2] * e2[2]};
            cJSON *p = cJSON_CreateDoubleArray(xy, 2);
            ok = p && cJSON_AddItemToArray(pts, p);
        }
        ok = ok && cJSON_AddStringToObject(it, "type", "points");
        ok = ok && cJSON_AddItemToObject(it, "points", pts);
        ok = ok && cJSON_AddStringToObject(it, "color", "#d62728");
    }
    /* a view of the curves' control points with equal scales on both axes (the default image
     * is 800 x 600: a 4:3 box) */
    double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
    for (int i = 0; i < 4 * s->npieces; ++i) {
        const double *x = s->ctrl + 3 * i;
        double xy[2] = {x[0] * e1[0] + x[1] * e1[1] + x[2] * e1[2],
                        x[0] * e2[0] + x[1] * e2[1] + x[2] * e2[2]};
        for (int k = 0; k < 2; ++k) lo[k] = fmin(lo[k], xy[k]), hi[k] = fmax(hi[k], xy[k]);
    }
    if (ok && s->npieces > 0) {
        double cx = 0.5 * (lo[0] + hi[0]), cy = 0.5 * (lo[1] + hi[1]);
        double hw = fmax(0.5 * (hi[0] - lo[0]), 4.0 / 3.0 * 0.5 * (hi[1] - lo[1])) * 1.08 + 1e-12;
        double view[4] = {cx - hw, cy - 0.75 * hw, cx + hw, cy + 0.75 * hw};
        cJSON *v = cJSON_CreateDoubleArray(view, 4);
        ok = v && cJSON_AddItemToObject(doc, "view", v);
    }
    if (!ok) {
        cJSON_Delete(doc);
        return NULL;
    }
    return doc;
}

static void write_obj(FILE *f, const cj_section_curves *s) {
    for (int i = 0; i < s->npts; ++i)
        fprintf(f, "v %.17g %.17g %.17g\n", s->pts[3 * i], s->pts[3 * i + 1], s->pts[3 * i + 2]);
    for (int c = 0; c < s->nchains; ++c) {
        int a = s->pt_starts[c], b = s->pt_starts[c + 1];
        fprintf(f, "l");
        for (int i = a; i < b; ++i) fprintf(f, " %d", i + 1);
        if (s->closed[c] && b - a > 1) fprintf(f, " %d", a + 1);
        fprintf(f, "\n");
    }
}

int cmd_section(int argc, char **argv) {
    const char *cmd = "section";
    popts o;
    int rc = parse_patch_args(cmd, section_usage, argc, argv, 1, &o);
    if (rc >= 0) return rc;
    if (o.out && (rc = cli_check_output(cmd, "output", o.out))) return rc;
    model M;
    if ((rc = model_load(cmd, o.teapot, o.bpt, o.surface, o.patch, o.degree, o.weights, &M))) {
        model_free(&M);
        return rc;
    }
    double tol = o.tol > 0 ? o.tol : 1e-3 * (M.size > 0 ? M.size : 1.0);
    cj_section_curves s;
    cj_status st = cj_patches_section_curves(M.patches, M.count, o.plane, o.plane[3], tol, &s);
    if (st) {
        rc = st == CJ_ERR_NOMEM ? cli_error(cmd, "%s", cj_last_error())
                                : cli_fail(cmd, "%s", cj_last_error());
        model_free(&M);
        return rc;
    }
    cJSON *doc = NULL;
    if (o.json || (o.out && cli_has_ext(o.out, ".json"))) {
        doc = section_json(&s, o.plane, tol);
        if (!doc) rc = cli_error(cmd, "out of memory writing the JSON document");
    }
    if (!rc && o.out) { /* written atomically: complete or not at all */
        cj_atomic_file af;
        if (cj_atomic_open(&af, o.out) != CJ_OK) {
            rc = cli_error(cmd, "%s", cj_last_error());
        } else {
            if (cli_has_ext(o.out, ".obj")) {
                write_obj(af.fp, &s);
            } else {
                char *text = cJSON_Print(doc);
                if (text) fprintf(af.fp, "%s\n", text);
                free(text);
                if (!text) rc = cli_error(cmd, "out of memory writing the JSON document");
            }
            if (rc)
                cj_atomic_abandon(&af);
            else if (cj_atomic_commit(&af) != CJ_OK)
                rc = cli_error(cmd, "%s", cj_last_error());
        }
    }
    if (!rc && o.json) {
        char *text = cJSON_Print(doc);
        if (text)
            printf("%s\n", text);
        else
            rc = cli_error(cmd, "out of memory writing the JSON document");
        free(text);
    } else if (!rc) {
        int closed = 0;
        for (int c = 0; c < s.nchains; ++c) {
            int a = s.piece_starts[c], b = s.piece_starts[c + 1];
            closed += s.closed[c];
            printf("curve %d %s %d\n", c, s.closed[c] ? "closed" : "open", b - a);
            for (int k = a; k < b; ++k) {
                const double *B = s.ctrl + 12 * k;
                for (int i = 0; i < 12; ++i) printf("%.17g%c", B[i], i == 11 ? '\n' : ' ');
            }
        }
        for (int j = 0; j < s.nunresolved; ++j)
            printf("unresolved %.17g %.17g %.17g\n", s.unresolved[3 * j], s.unresolved[3 * j + 1],
                   s.unresolved[3 * j + 2]);
        printf("section patches %zu curves %d closed %d pieces %d points %d joins %d unresolved %d "
               "ambiguous %d deviation %.3g polylines %.3g plane_gap %.3g\n",
               M.count, s.nchains, closed, s.npieces, s.npts, s.joins, s.nunresolved, s.ambiguous,
               s.deviation, s.poly_deviation, s.plane_gap);
    }
    if (!rc && fflush(stdout) != 0) rc = cli_error(cmd, "cannot write standard output");
    cJSON_Delete(doc);
    cj_section_curves_free(&s);
    model_free(&M);
    return rc;
}

int cmd_nearest_patch(int argc, char **argv) {
    const char *cmd = "nearest";
    popts o;
    int rc = parse_patch_args(cmd, nearest_patch_usage, argc, argv, 0, &o);
    if (rc >= 0) return rc;
    model M;
    if ((rc = model_load(cmd, o.teapot, o.bpt, o.surface, o.patch, o.degree, o.weights, &M))) {
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

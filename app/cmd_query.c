/* casteljau intersect / nearest: certified queries on the curves of a plot JSON document
 * (curves/include/casteljau/intersect.h, nearest.h). They read the document `plot` reads and,
 * by default, write it back with the answers added as ordinary plot items, so that
 *     casteljau intersect curves.json | casteljau plot - -o out.png
 * draws the curves with their intersections marked; --text prints one line per answer. */
#include "cli.h"
#include "cli_guard.h"
#include "file_internal.h"
#include "query_doc.h"
#include "json_read_internal.h"
#include "json_write_internal.h"
#include "plot_json.h"

#include "casteljau/bezier.h"
#include "casteljau/intersect.h"
#include "casteljau/nearest.h"
#include "casteljau/offset.h"

#include <cJSON.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define QUERY_MAX_BYTES   ((size_t)64 << 20)
#define QUERY_MAX_RESULTS 4096

static const char intersect_usage[] =
    "usage: casteljau intersect [--tol T] [--self] [--line PX,PY,DX,DY] [--text] [FILE|-]\n"
    "Certified intersections of the \"bezier\" items (polynomial or rational, degree <= 48) of\n"
    "a plot JSON document (the format of 'casteljau plot'; '-' or no FILE reads standard\n"
    "input; a document with \"panels\" is queried panel by panel). Every pair of curves of a\n"
    "panel is intersected; --self adds each curve's self-intersections; --line intersects\n"
    "each curve with the line through (PX,PY) in direction (DX,DY) instead of the pairs.\n"
    "  --tol   distance below which pieces are not split (default 1e-9 times the panel's\n"
    "          size); crossings are refined far below it\n"
    "  --text  one line per result instead of the document:\n"
    "          KIND I J S S_LO S_HI T T_LO T_HI X Y\n"
    "          KIND crossing (proven unique in its box), contact (a tangency or cluster\n"
    "          within tol) or overlap (coincident pieces); I, J the item indices (J = I for a\n"
    "          self-intersection, -1 for the line, whose T is the line parameter); [S_LO,\n"
    "          S_HI] and [T_LO, T_HI] proven to contain the intersection.\n"
    "Output: the document with, per panel, a \"points\" item at the crossings (red), one at\n"
    "the contacts (orange) and a thick \"bezier\" item over each overlap, ready for\n"
    "'casteljau plot - -o out.png'. Exit status 0; 2 for bad input (one line on stderr naming\n"
    "it); 1 when out of memory or the search hit its work cap.\n";

static const char nearest_usage[] =
    "usage: casteljau nearest --point X,Y [--tol T] [--text] [FILE|-]\n"
    "The certified nearest point to (X,Y) on the \"bezier\" items of a plot JSON document (as\n"
    "for 'casteljau intersect'): a global minimum by branch and bound, with a proven lower\n"
    "bound of the distance within T of the distance found.\n"
    "  --tol   default 1e-9 times the size of the curves and the point\n"
    "  --text  one line per curve: I T X Y DISTANCE LOWER, then 'nearest I T X Y DISTANCE\n"
    "          LOWER' for the nearest of all (LOWER the smallest lower bound)\n"
    "Output: the document with, per panel, the point and its nearest point marked and joined.\n"
    "Exit status as for intersect.\n"
    "On patches: casteljau nearest --point X,Y,Z (--teapot | --bpt FILE | --patch ... --degree\n"
    "M,N) [--tol T] (see 'casteljau nearest --point 0,0,0 --teapot --help').\n";

static char *read_all(const char *cmd, const char *path, int *rc) {
    char *data = NULL;
    size_t size = 0;
    const cj_status st = cj_file_read_input(path, QUERY_MAX_BYTES, "document", &data, &size);
    if (st) *rc = cli_fail_status(cmd, st, "%s", cj_last_error());
    return st ? NULL : data;
}

void free_curves(qcurve *cv, int nc) {
    for (int i = 0; i < nc; ++i) {
        free(cv[i].pts);
        free(cv[i].w);
    }
}

/* The bezier items of one panel's "items" array, read by the plot format's one reader of them
 * (cj_plot_json_read_bezier; the document's name and lines in jd). Returns the count, or -1
 * with *rc the command's failure. */
int read_curves(const char *cmd, const cj_json_doc *jd, const cJSON *items, const char *where,
                qcurve *cv, int *rc) {
    int nc = 0, idx = 0;
    cj_status st = CJ_OK;
    for (const cJSON *it = items ? items->child : NULL; it && !st; it = it->next, ++idx) {
        const cJSON *t = cJSON_GetObjectItemCaseSensitive(it, "type");
        if (!cJSON_IsString(t) || strcmp(t->valuestring, "bezier")) continue;
        char ip[CJ_JSON_PATH], p[CJ_JSON_PATH];
        snprintf(p, sizeof p, "%sitems", where);
        cj_json_index(ip, p, (size_t)idx);
        if (nc == QUERY_MAX_CURVES) {
            st = cj_json_fail(jd, it, 0, CJ_ERR_RANGE, "%s: more than %d bezier items", p,
                              QUERY_MAX_CURVES);
            break;
        }
        cj_plot_json_curve k;
        if ((st = cj_plot_json_read_bezier(jd, it, ip, &k))) break;
        if (k.count > CJ_QUERY_MAX_DEGREE + 1) {
            cj_json_join(p, ip, "points");
            st = cj_json_fail(jd, cJSON_GetObjectItemCaseSensitive(it, "points"), 0, CJ_ERR_RANGE,
                              "%s has %zu points: the queries take degree <= %d", p, k.count,
                              CJ_QUERY_MAX_DEGREE);
            cj_plot_json_curve_free(&k);
            break;
        }
        cv[nc].item = idx;
        cv[nc].degree = (int)k.count - 1;
        cv[nc].pts = k.points; /* the curve's arrays pass to cv */
        cv[nc].w = k.weights;
        ++nc;
    }
    if (!st) return nc;
    /* the caller sees only -1: the curves read before the bad item are freed here */
    free_curves(cv, nc);
    *rc = st == CJ_ERR_NOMEM ? cli_error(cmd, "%s", cj_last_error())
                             : cli_fail_status(cmd, st, "%s", cj_last_error());
    return -1;
}

/* Size of a panel: max |coordinate| of its curves (and extra points), at least tiny. */
double panel_size(const qcurve *cv, int nc, const double *extra, int nextra) {
    double s = 0.0;
    for (int i = 0; i < nc; ++i)
        for (int k = 0; k < 2 * (cv[i].degree + 1); ++k)
            if (isfinite(cv[i].pts[k])) s = fmax(s, fabs(cv[i].pts[k]));
    for (int k = 0; k < nextra; ++k)
        if (isfinite(extra[k])) s = fmax(s, fabs(extra[k]));
    return s > 0 ? s : 1.0;
}

cJSON *pair_json(double x, double y) {
    const double xy[2] = {x, y};
    return cj_json_number_array(xy, 2);
}

static cJSON *points_item(const char *color, double radius) {
    cJSON *it = cJSON_CreateObject();
    cJSON_AddStringToObject(it, "type", "points");
    cJSON_AddItemToObject(it, "points", cJSON_CreateArray());
    cJSON_AddStringToObject(it, "color", color);
    cj_json_add_number(it, "radius", radius);
    return it;
}

/* Message of a failed query, naming the panel and items. */
int query_fail(const char *cmd, const char *where, const qcurve *a, const qcurve *b, cj_status st) {
    char items[64];
    if (b && b != a)
        snprintf(items, sizeof items, "items[%d] and items[%d]", a->item, b->item);
    else
        snprintf(items, sizeof items, "items[%d]", a->item);
    if (st == CJ_ERR_CAP || st == CJ_ERR_NOMEM)
        return cli_error(cmd, "%s%s: %s", where, items, cj_last_error());
    return cli_fail(cmd, "%s%s: %s", where, items, cj_last_error());
}

static void print_isect(const cj_isect *r, int i, int j) {
    printf("%s %d %d", cj_isect_kind_name(r->kind), i, j);
    const double v[] = {r->s, r->s_lo, r->s_hi, r->t, r->t_lo, r->t_hi, r->point[0], r->point[1]};
    for (size_t k = 0; k < sizeof v / sizeof v[0]; ++k) {
        printf(" ");
        cli_print_double(v[k]);
    }
    printf("\n");
}

/* Adds the answers of one result to the panel's marker items. */
static void mark(cJSON *items, cJSON *cross, cJSON *contact, const cj_isect *r, const qcurve *a) {
    if (r->kind == CJ_ISECT_CROSSING)
        cJSON_AddItemToArray(cJSON_GetObjectItem(cross, "points"),
                             pair_json(r->point[0], r->point[1]));
    else if (r->kind == CJ_ISECT_CONTACT)
        cJSON_AddItemToArray(cJSON_GetObjectItem(contact, "points"),
                             pair_json(r->point[0], r->point[1]));
    else if (!a->w) { /* the overlapping piece of a, drawn thick */
        double sub[2 * (CJ_QUERY_MAX_DEGREE + 1)];
        cj_bezier b = cj_bezier_view(a->degree, 2, a->pts);
        if (r->s_hi > r->s_lo && cj_bezier_subcurve(&b, r->s_lo, r->s_hi, sub) == CJ_OK) {
            cJSON *it = cJSON_CreateObject(), *pts = cJSON_CreateArray();
            cJSON_AddStringToObject(it, "type", "bezier");
            for (int i = 0; i <= a->degree; ++i)
                cJSON_AddItemToArray(pts, pair_json(sub[2 * i], sub[2 * i + 1]));
            cJSON_AddItemToObject(it, "points", pts);
            cJSON_AddStringToObject(it, "color", "#d6272880");
            cj_json_add_number(it, "width", 7);
            cJSON_AddFalseToObject(it, "control_polygon");
            cJSON_AddFalseToObject(it, "control_points");
            cJSON_AddItemToArray(items, it);
        }
    }
}

static int intersect_panel(cJSON *panel, const char *where, const qopts *o) {
    cJSON *items = cJSON_GetObjectItemCaseSensitive(panel, "items");
    qcurve cv[QUERY_MAX_CURVES];
    int rc = 0, nc = read_curves("intersect", o->json, items, where, cv, &rc);
    if (nc < 0) return rc;
    double tol = o->tol > 0 ? o->tol : 1e-9 * panel_size(cv, nc, o->line, o->have_line ? 2 : 0);
    cj_isect *res = malloc(sizeof(cj_isect) * QUERY_MAX_RESULTS);
    cJSON *cross = points_item("#d62728", 5), *contact = points_item("#ff7f0e", 6);
    if (!res || !cross || !contact) {
        free(res);
        free_curves(cv, nc);
        cJSON_Delete(cross);
        cJSON_Delete(contact);
        return cli_error("intersect", "out of memory");
    }
    for (int i = 0; i < nc && !rc; ++i) {
        cj_bezier2 A = cj_bezier2_view(cv[i].degree, cv[i].pts, cv[i].w);
        int n = 0;
        cj_status st;
        if (o->have_line) {
            st = cj_intersect_line(&A, o->line, o->line + 2, tol, res, QUERY_MAX_RESULTS, &n);
            if (st) rc = query_fail("intersect", where, &cv[i], NULL, st);
            for (int k = 0; k < n && !rc; ++k) {
                if (o->text) print_isect(&res[k], cv[i].item, -1);
                mark(items, cross, contact, &res[k], &cv[i]);
            }
        }
        if (o->self && !rc) {
            st = cj_intersect_self(&A, tol, res, QUERY_MAX_RESULTS, &n);
            if (st) rc = query_fail("intersect", where, &cv[i], &cv[i], st);
            for (int k = 0; k < n && !rc; ++k) {
                if (o->text) print_isect(&res[k], cv[i].item, cv[i].item);
                mark(items, cross, contact, &res[k], &cv[i]);
            }
        }
        for (int j = i + 1; j < nc && !rc && !o->have_line; ++j) {
            cj_bezier2 B = cj_bezier2_view(cv[j].degree, cv[j].pts, cv[j].w);
            st = cj_intersect_curves(&A, &B, tol, res, QUERY_MAX_RESULTS, &n);
            if (st) rc = query_fail("intersect", where, &cv[i], &cv[j], st);
            for (int k = 0; k < n && !rc; ++k) {
                if (o->text) print_isect(&res[k], cv[i].item, cv[j].item);
                mark(items, cross, contact, &res[k], &cv[i]);
            }
        }
    }
    free(res);
    free_curves(cv, nc);
    /* plot refuses an empty points item: add only those with points */
    if (cJSON_GetArraySize(cJSON_GetObjectItem(cross, "points")) > 0)
        cJSON_AddItemToArray(items, cross);
    else
        cJSON_Delete(cross);
    if (cJSON_GetArraySize(cJSON_GetObjectItem(contact, "points")) > 0)
        cJSON_AddItemToArray(items, contact);
    else
        cJSON_Delete(contact);
    return rc;
}

static int nearest_panel(cJSON *panel, const char *where, const qopts *o) {
    cJSON *items = cJSON_GetObjectItemCaseSensitive(panel, "items");
    qcurve cv[QUERY_MAX_CURVES];
    int rc = 0, nc = read_curves("nearest", o->json, items, where, cv, &rc);
    if (nc < 0) return rc;
    if (nc == 0) {
        free_curves(cv, nc);
        return cli_fail("nearest", "%sitems: no bezier item to query", where);
    }
    double tol = o->tol > 0 ? o->tol : 1e-9 * panel_size(cv, nc, o->point, 2);
    cj_nearest best = {0};
    int best_i = -1;
    double lower = INFINITY;
    for (int i = 0; i < nc && !rc; ++i) {
        cj_bezier2 A = cj_bezier2_view(cv[i].degree, cv[i].pts, cv[i].w);
        cj_nearest r;
        cj_status st = cj_nearest_curve(&A, o->point, tol, &r);
        if (st) {
            rc = query_fail("nearest", where, &cv[i], NULL, st);
            break;
        }
        if (o->text) {
            printf("%d", cv[i].item);
            const double v[] = {r.t, r.point[0], r.point[1], r.distance, r.lower};
            for (size_t k = 0; k < 5; ++k) printf(" "), cli_print_double(v[k]);
            printf("\n");
        }
        lower = fmin(lower, r.lower);
        if (best_i < 0 || r.distance < best.distance) best = r, best_i = cv[i].item;
    }
    free_curves(cv, nc);
    if (rc) return rc;
    if (o->text) {
        printf("nearest %d", best_i);
        const double v[] = {best.t, best.point[0], best.point[1], best.distance, lower};
        for (size_t k = 0; k < 5; ++k) printf(" "), cli_print_double(v[k]);
        printf("\n");
    }
    cJSON *line = cJSON_CreateObject(), *lp = cJSON_CreateArray();
    cJSON_AddStringToObject(line, "type", "polyline");
    cJSON_AddItemToArray(lp, pair_json(o->point[0], o->point[1]));
    cJSON_AddItemToArray(lp, pair_json(best.point[0], best.point[1]));
    cJSON_AddItemToObject(line, "points", lp);
    cJSON_AddStringToObject(line, "color", "#7f7f7f");
    cJSON_AddItemToArray(items, line);
    cJSON *q = points_item("#7f7f7f", 5), *n = points_item("#d62728", 5);
    cJSON_AddItemToArray(cJSON_GetObjectItem(q, "points"), pair_json(o->point[0], o->point[1]));
    cJSON_AddItemToArray(cJSON_GetObjectItem(n, "points"), pair_json(best.point[0], best.point[1]));
    cJSON_AddItemToArray(items, q);
    cJSON_AddItemToArray(items, n);
    return 0;
}

static int run_doc(const char *cmd, const char *path, const qopts *o,
                   int (*panel_fn)(cJSON *, const char *, const qopts *)) {
    int rc = 0;
    char *text = read_all(cmd, path, &rc);
    if (!text) return rc;
    cJSON *doc = NULL;
    const cj_status st = cj_json_parse(path, text, &doc);
    if (st) {
        free(text);
        return st == CJ_ERR_NOMEM ? cli_error(cmd, "%s", cj_last_error())
                                  : cli_fail(cmd, "%s", cj_last_error());
    }
    cj_json_lines lines;
    cj_json_doc jd;
    cj_json_doc_init(&jd, &lines, path, text, doc);
    qopts with_doc = *o;
    with_doc.json = &jd;
    o = &with_doc;
    if (!cJSON_IsObject(doc)) {
        cj_json_doc_free(&jd);
        cJSON_Delete(doc);
        free(text);
        return cli_fail(cmd, "the document is not a JSON object");
    }
    cJSON *panels = cJSON_GetObjectItemCaseSensitive(doc, "panels");
    if (panels) {
        int i = 0;
        for (cJSON *p = panels->child; p && !rc; p = p->next, ++i) {
            char where[48];
            snprintf(where, sizeof where, "panels[%d].", i);
            if (cJSON_GetObjectItemCaseSensitive(p, "items")) rc = panel_fn(p, where, o);
        }
    } else if (cJSON_GetObjectItemCaseSensitive(doc, "items")) {
        rc = panel_fn(doc, "", o);
    } else {
        rc = cli_fail(cmd, "the document has neither \"items\" nor \"panels\"");
    }
    if (!rc && !o->text) {
        /* the writing kit: the numbers read in and those added in their shortest exact form */
        if (cj_json_shortest_numbers(doc))
            rc = cli_error(cmd, "out of memory");
        else if (cj_json_print(doc, 1, stdout, cmd))
            rc = cli_error(cmd, "%s", cj_last_error());
    }
    cj_json_doc_free(&jd);
    cJSON_Delete(doc);
    free(text);
    if (!rc && fflush(stdout) != 0) rc = cli_error(cmd, "cannot write standard output");
    return rc;
}

static int parse_numbers(const char *cmd, const char *opt, const char *v, double *out, int n) {
    double *vals = NULL;
    size_t count = 0;
    char why[160];
    if (cli_parse_list(v, &vals, &count, why, sizeof why)) return cli_fail(cmd, "%s: %s", opt, why);
    if ((int)count != n) {
        free(vals);
        return cli_fail(cmd, "%s: need %d numbers, got %zu", opt, n, count);
    }
    memcpy(out, vals, sizeof(double) * (size_t)n);
    free(vals);
    return 0;
}

enum { Q_INTERSECT, Q_NEAREST, Q_OFFSET, Q_REDUCE };

static int query_main(const char *cmd, const char *usage, int argc, char **argv, int which) {
    enum { O_TOL, O_SELF, O_LINE, O_TEXT, O_POINT, O_DIST, O_TRIM, O_DEGREE, O_OUTLINE, O_CAP };
    static const cli_opt opts[] = {
        {"--tol", NULL, 1},     {"--self", NULL, 0},     {"--line", NULL, 1}, {"--text", NULL, 0},
        {"--point", NULL, 1},   {"--distance", NULL, 1}, {"--trim", NULL, 0}, {"--degree", NULL, 1},
        {"--outline", NULL, 0}, {"--cap", NULL, 1}};
    const char *cap_name = NULL;
    cli_parser ps;
    cli_parser_init(&ps, cmd, usage, argc, argv, opts, sizeof opts / sizeof opts[0]);
    qopts o;
    memset(&o, 0, sizeof o);
    const char *path = NULL;
    int k, status, have_point = 0, have_dist = 0;
    const char *v;
    while (cli_next_arg(&ps, &k, &v, &status)) {
        char q[160];
        if (k == CLI_POSITIONAL) {
            if (path)
                return cli_fail(cmd, "unexpected argument '%s' (one FILE)",
                                cli_quote(v, q, sizeof q));
            path = v;
        } else if (k == O_TOL) {
            if (cli_parse_double(v, &o.tol) || !(o.tol > 0))
                return cli_fail(cmd, "--tol '%s' is not a positive number",
                                cli_quote(v, q, sizeof q));
        } else if (k == O_TEXT) {
            o.text = 1;
        } else if (k == O_DEGREE) {
            if (which != Q_REDUCE)
                return cli_fail(cmd, "--degree does not apply to '%s' (try 'casteljau %s --help')",
                                cmd, cmd);
            long m;
            if (cli_parse_int(v, 1, CJ_QUERY_MAX_DEGREE, &m))
                return cli_fail(cmd, "--degree '%s' is not an integer in 1..%d",
                                cli_quote(v, q, sizeof q), CJ_QUERY_MAX_DEGREE);
            o.reduce_to = (int)m;
        } else if (k == O_OUTLINE || k == O_CAP) {
            if (which != Q_OFFSET)
                return cli_fail(cmd, "%s does not apply to '%s' (try 'casteljau %s --help')",
                                opts[k].name, cmd, cmd);
            if (k == O_OUTLINE) {
                o.outline = o.outline ? o.outline : 1;
            } else if (!strcmp(v, "butt") || !strcmp(v, "round") || !strcmp(v, "square")) {
                cap_name = v;
            } else {
                return cli_fail(cmd, "--cap '%s' is not butt, round or square",
                                cli_quote(v, q, sizeof q));
            }
        } else if (k == O_TRIM) {
            if (which != Q_OFFSET)
                return cli_fail(cmd, "--trim does not apply to '%s' (try 'casteljau %s --help')",
                                cmd, cmd);
            o.trim = 1;
        } else if ((which == Q_NEAREST) != (k == O_POINT) || (which == Q_OFFSET) != (k == O_DIST) ||
                   (which != Q_INTERSECT && (k == O_SELF || k == O_LINE))) {
            return cli_fail(cmd, "%s does not apply to '%s' (try 'casteljau %s --help')",
                            opts[k].name, cmd, cmd);
        } else if (k == O_SELF) {
            o.self = 1;
        } else if (k == O_LINE) {
            if (parse_numbers(cmd, "--line", v, o.line, 4)) return CLI_EXIT_USAGE;
            if (o.line[2] == 0 && o.line[3] == 0)
                return cli_fail(cmd, "--line: the direction (DX,DY) is (0,0)");
            o.have_line = 1;
        } else if (k == O_POINT) {
            if (parse_numbers(cmd, "--point", v, o.point, 2)) return CLI_EXIT_USAGE;
            have_point = 1;
        } else {
            if (cli_parse_double(v, &o.distance))
                return cli_fail(cmd, "--distance '%s' is not a finite number",
                                cli_quote(v, q, sizeof q));
            have_dist = 1;
        }
    }
    if (status >= 0) return status;
    if (which == Q_NEAREST && !have_point) return cli_fail(cmd, "missing --point X,Y");
    if (which == Q_OFFSET && !have_dist) return cli_fail(cmd, "missing --distance D");
    if (cap_name && !o.outline) return cli_fail(cmd, "--cap needs --outline");
    if (o.outline && o.trim) return cli_fail(cmd, "give --trim or --outline, not both");
    if (o.outline && o.distance == 0) return cli_fail(cmd, "--outline needs --distance D != 0");
    if (cap_name)
        o.outline = 1 + (!strcmp(cap_name, "round")    ? CJ_OFFSET_CAP_ROUND
                         : !strcmp(cap_name, "square") ? CJ_OFFSET_CAP_SQUARE
                                                       : CJ_OFFSET_CAP_BUTT);
    if (which == Q_REDUCE && (o.reduce_to > 0) == (o.tol > 0))
        return cli_fail(cmd, "give one of --degree M or --tol T");
    return run_doc(cmd, path ? path : "-", &o,
                   which == Q_NEAREST  ? nearest_panel
                   : which == Q_OFFSET ? offset_panel
                   : which == Q_REDUCE ? reduce_panel
                                       : intersect_panel);
}

int cmd_intersect(int argc, char **argv) {
    return query_main("intersect", intersect_usage, argc, argv, Q_INTERSECT);
}

int cmd_nearest(int argc, char **argv) {
    /* a patch model makes it the 3D query (cmd_section.c) */
    for (int i = 1; i < argc && strcmp(argv[i], "--") != 0; ++i)
        if (!strncmp(argv[i], "--teapot", 8) || !strncmp(argv[i], "--bpt", 5) ||
            !strncmp(argv[i], "--patch", 7) || !strncmp(argv[i], "--surface", 9))
            return cmd_nearest_patch(argc, argv);
    return query_main("nearest", nearest_usage, argc, argv, Q_NEAREST);
}

int cmd_offset(int argc, char **argv) {
    return query_main("offset", offset_usage, argc, argv, Q_OFFSET);
}

int cmd_reduce(int argc, char **argv) {
    return query_main("reduce", reduce_usage, argc, argv, Q_REDUCE);
}

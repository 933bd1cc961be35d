/* casteljau offset and casteljau reduce: offsets (raw, trimmed, outlines with caps) and degree
 * reduction of the "bezier" items of a plot document (the walk of the document is cmd_query.c's
 * run_doc). */
#include "cli.h"
#include "query_doc.h"

#include "casteljau/bezier.h"
#include "casteljau/offset.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

const char offset_usage[] =
    "usage: casteljau offset --distance D [--tol T] [--trim | --outline [--cap "
    "butt|round|square]]\n"
    "                        [--text] [FILE|-]\n"
    "Offsets the \"bezier\" items of a plot JSON document (as for 'casteljau intersect') by D\n"
    "(positive: to the left of the direction of travel) as cubic Bezier pieces, each proven\n"
    "within T of the exact offset (cusps followed, loops kept: see\n"
    "  " CJ_DOC_DIR "/queries.md).\n"
    "  --tol   default 1e-6 times the size of the curves and D\n"
    "  --trim  cut the offset at its self-crossings and drop the spans nearer to the curve\n"
    "          than D (swallowtails of tight bends; an arc offset inwards past its radius)\n"
    "  --outline  the outline of the stroke of half-width |D| instead: the offsets at +|D| and\n"
    "          -|D| joined by end caps into one closed loop (an open curve), or two closed loops\n"
    "          (a closed curve: round joins at a corner of the seam)\n"
    "  --cap   the end caps of --outline: butt (default), round (a proven half circle) or square\n"
    "A cusp of a curve (its derivative vanishes) is completed by an arc of radius |D| about it.\n"
    "  --text  one line per piece: I K X0 Y0 X1 Y1 X2 Y2 X3 Y3 (item, piece), then\n"
    "          'deviation I PIECES DEV CUSPS [DROPPED]' per curve (DROPPED with --trim)\n"
    "Output: the document with the pieces added as \"bezier\" items (purple). Exit status as\n"
    "for intersect.\n";

const char reduce_usage[] =
    "usage: casteljau reduce (--degree M | --tol T) [--text] [FILE|-]\n"
    "Lowers the degree of the polynomial \"bezier\" items of a plot JSON document (as for\n"
    "'casteljau intersect'): least squares on the control points, end points kept, with a PROVEN\n"
    "bound on max |c(t) - r(t)| (both curves written in the higher degree are convex\n"
    "combinations of their control points with the same weights; see\n"
    "  " CJ_DOC_DIR "/queries.md).\n"
    "  --degree  the degree M to reduce to (curves of degree <= M are left as they are)\n"
    "  --tol     instead: the lowest degree whose proven bound is <= T (a curve that no lower\n"
    "            degree represents within T is left as it is)\n"
    "  --text    one line per curve: 'reduced I FROM TO BOUND' then the TO+1 points X Y\n"
    "Output: the document with each reduced curve added as a \"bezier\" item (orange). Rational\n"
    "items are refused naming them. Exit status as for intersect.\n";

int offset_panel(cJSON *panel, const char *where, const qopts *o) {
    cJSON *items = cJSON_GetObjectItemCaseSensitive(panel, "items");
    qcurve cv[QUERY_MAX_CURVES];
    int rc = 0, nc = read_curves("offset", o->json, items, where, cv, &rc);
    if (nc < 0) return rc;
    double dd[1] = {o->distance};
    double tol = o->tol > 0 ? o->tol : 1e-6 * (panel_size(cv, nc, dd, 1) + fabs(o->distance));
    enum { CAP = 1 << 16 };
    double *pts = malloc(sizeof(double) * 8 * CAP), *kept = malloc(sizeof(double) * 8 * CAP);
    if (!pts || !kept) {
        free(pts);
        free(kept);
        free_curves(cv, nc);
        return cli_error("offset", "out of memory");
    }
    for (int i = 0; i < nc && !rc; ++i) {
        cj_bezier2 A = cj_bezier2_view(cv[i].degree, cv[i].pts, cv[i].w);
        int np = 0, cusps = 0;
        double dev = 0;
        cj_status st =
            o->outline
                ? cj_offset_outline(&A, fabs(o->distance), tol, (cj_offset_cap)(o->outline - 1),
                                    pts, NULL, CAP, &np, &dev, &cusps)
                : cj_offset_curve(&A, o->distance, tol, pts, NULL, CAP, &np, &dev, &cusps);
        if (st) {
            rc = query_fail("offset", where, &cv[i], NULL, st);
            break;
        }
        int dropped = 0;
        const double *out = pts;
        if (o->trim) {
            int nk = 0;
            st = cj_offset_trim(&A, o->distance, tol, pts, np, dev, kept, NULL, CAP, &nk, &dropped);
            if (st) {
                rc = query_fail("offset", where, &cv[i], NULL, st);
                break;
            }
            np = nk;
            out = kept;
        }
        for (int k = 0; k < np; ++k) {
            if (o->text) {
                printf("%d %d", cv[i].item, k);
                for (int j = 0; j < 8; ++j) printf(" "), cli_print_double(out[8 * k + j]);
                printf("\n");
            }
            cJSON *it = cJSON_CreateObject(), *pa = cJSON_CreateArray();
            cJSON_AddStringToObject(it, "type", "bezier");
            for (int j = 0; j < 4; ++j)
                cJSON_AddItemToArray(pa, pair_json(out[8 * k + 2 * j], out[8 * k + 2 * j + 1]));
            cJSON_AddItemToObject(it, "points", pa);
            cJSON_AddStringToObject(it, "color", "#9467bd");
            cJSON_AddFalseToObject(it, "control_polygon");
            cJSON_AddFalseToObject(it, "control_points");
            cJSON_AddItemToArray(items, it);
        }
        if (o->text) {
            printf("deviation %d %d ", cv[i].item, np);
            cli_print_double(dev);
            printf(" %d", cusps);
            if (o->trim) printf(" %d", dropped);
            printf("\n");
        }
    }
    free(pts);
    free(kept);
    free_curves(cv, nc);
    return rc;
}

int reduce_panel(cJSON *panel, const char *where, const qopts *o) {
    cJSON *items = cJSON_GetObjectItemCaseSensitive(panel, "items");
    qcurve cv[QUERY_MAX_CURVES];
    int rc = 0, nc = read_curves("reduce", o->json, items, where, cv, &rc);
    if (nc < 0) return rc;
    double out[2 * (CJ_QUERY_MAX_DEGREE + 1)];
    for (int i = 0; i < nc && !rc; ++i) {
        if (cv[i].w) {
            rc = cli_fail("reduce", "%sitems[%d]: a rational curve (weights) is not reduced", where,
                          cv[i].item);
            break;
        }
        int n = cv[i].degree, to = n;
        double bound = 0.0;
        cj_bezier c = cj_bezier_view(n, 2, cv[i].pts);
        for (int m = o->reduce_to ? o->reduce_to : 1; m < n; ++m) {
            double b;
            cj_status st = cj_bezier_reduce(&c, m, out, &b);
            if (st) {
                rc = query_fail("reduce", where, &cv[i], NULL, st);
                break;
            }
            if (o->reduce_to || b <= o->tol) {
                to = m, bound = b;
                break;
            }
        }
        if (rc) break;
        if (to == n) memcpy(out, cv[i].pts, sizeof(double) * 2 * (size_t)(n + 1));
        if (o->text) {
            printf("reduced %d %d %d ", cv[i].item, n, to);
            cli_print_double(bound);
            printf("\n");
            for (int j = 0; j <= to; ++j) {
                cli_print_double(out[2 * j]);
                printf(" ");
                cli_print_double(out[2 * j + 1]);
                printf("\n");
            }
        }
        if (to == n) continue;
        cJSON *it = cJSON_CreateObject(), *pa = cJSON_CreateArray();
        cJSON_AddStringToObject(it, "type", "bezier");
        for (int j = 0; j <= to; ++j)
            cJSON_AddItemToArray(pa, pair_json(out[2 * j], out[2 * j + 1]));
        cJSON_AddItemToObject(it, "points", pa);
        cJSON_AddStringToObject(it, "color", "#ff7f0e");
        cJSON_AddItemToArray(items, it);
    }
    free_curves(cv, nc);
    return rc;
}

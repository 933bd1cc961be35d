/* Private to the casteljau tool: the plot-document curves shared by the query commands
 * (cmd_query.c: intersect, nearest, the document walk; cmd_offset.c: offset, reduce). */
#ifndef CASTELJAU_APP_QUERY_DOC_H
#define CASTELJAU_APP_QUERY_DOC_H

#include "casteljau/status.h"
#include "json_read_internal.h"

#include <cJSON.h>

#define QUERY_MAX_CURVES 256

typedef struct qcurve {
    int item; /* index in the panel's items */
    int degree;
    double *pts, *w;
} qcurve;

typedef struct qopts {
    int reduce_to; /* reduce: --degree M (0: by --tol) */
    int outline;   /* offset --outline: 1 + the cap (cj_offset_cap) */
    double tol;    /* 0: default */
    int self, have_line, text;
    double line[4];
    double point[2];
    double distance;
    int trim;                /* offset: drop the loops (cj_offset_trim) */
    const cj_json_doc *json; /* the document being read (run_doc), for messages */
} qopts;

/* The bezier items of one panel's "items" array into cv (at most QUERY_MAX_CURVES), checked
 * with the JSON kit (the document's name and lines in jd). Returns the count, or -1 with *rc the
 * exit status (the message printed). */
int read_curves(const char *cmd, const cj_json_doc *jd, const cJSON *items, const char *where,
                qcurve *cv, int *rc);
void free_curves(qcurve *cv, int nc);
/* Max |coordinate| of the curves (and of nextra extra values), at least tiny. */
double panel_size(const qcurve *cv, int nc, const double *extra, int nextra);
cJSON *pair_json(double x, double y);
/* The failure of a library call on items a (and b), exit status by kind. */
int query_fail(const char *cmd, const char *where, const qcurve *a, const qcurve *b, cj_status st);

extern const char offset_usage[], reduce_usage[];
int offset_panel(cJSON *panel, const char *where, const qopts *o);
int reduce_panel(cJSON *panel, const char *where, const qopts *o);

#endif

/* Private to the casteljau tool: the B-spline / NURBS curve item of the JSON documents that
 * `fit` writes and `eval --curve` and `plot` read:
 *     {"type": "bspline", "degree": p, "points": [[x, y, ...], ...],
 *      "knots": [t_0, ..., t_{n+p+1}]   (optional: clamped and uniform on [0, 1]),
 *      "weights": [w_0, ..., w_n]        (optional: a NURBS)}
 * Every point has the same dimension (1..8; 1..7 with weights). Rules of casteljau/bspline.h. */
#ifndef CASTELJAU_APP_BSPLINE_JSON_H
#define CASTELJAU_APP_BSPLINE_JSON_H

#include "casteljau/bspline.h"

#include <cJSON.h>
#include <stddef.h>
#include <stdio.h>

typedef struct cj_bsp_json {
    int degree, dim, npts;
    double *pts, *weights, *knots; /* owned; weights NULL for a polynomial B-spline */
} cj_bsp_json;

struct cj_json_doc; /* the checked-JSON kit's document (scene/src/json_read_internal.h) */

/* Parses item (at JSON path `path` of the document doc, read through the checked-JSON kit) into
 * out (free with cj_bsp_json_free). extra_keys: NULL-terminated field names also allowed (drawing
 * options of plot), may be NULL. max_points caps the control points. Returns CJ_OK, or the
 * kit's status with cj_last_error() "<document>:<line>: <path> ..." and nothing allocated. */
cj_status cj_bsp_json_parse(const struct cj_json_doc *doc, const cJSON *item, const char *path,
                            const char *const *extra_keys, size_t max_points, cj_bsp_json *out);

void cj_bsp_json_free(cj_bsp_json *b);

static inline cj_bspline cj_bsp_json_view(const cj_bsp_json *b) {
    return cj_bspline_view(b->degree, b->dim, b->npts, b->pts, b->weights, b->knots);
}

/* The first "bspline" item of a document: the object itself, or in its "items", or in the
 * "items" of one of its "panels". Writes its JSON path to path[path_size]; NULL if none. */
const cJSON *cj_bsp_json_find(const cJSON *doc, char *path, size_t path_size);

/* The item as a cJSON tree (the caller deletes it): numbers in their shortest exact form, so
 * that it reads back bit-identical; printed with cJSON's printer by whoever writes the document
 * (cj_plot_json_print_fit). NULL when out of memory. */
cJSON *cj_bsp_json_item(const cj_bspline *c);

#endif

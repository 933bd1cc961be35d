/* The surface document (surface_json.h): read and written by the scene layer's one reader and
 * writer of the B-spline surface object. */
#include "surface_json.h"

#include "bspline_surface_json_internal.h"
#include "json_write_internal.h"

#include <cJSON.h>
#include <string.h>

cj_status cj_surface_json_parse(const char *name, const char *text, cj_bspline_surface *out) {
    cJSON *root = NULL;
    memset(out, 0, sizeof *out);
    CJ_JSON_TRY(cj_json_parse(name, text, &root));
    cj_json_lines lines;
    cj_json_doc d;
    cj_json_doc_init(&d, &lines, name, text, root);
    const cj_status st = cj_json_read_bspline_surface(&d, root, "", 0, out);
    cj_json_doc_free(&d);
    cJSON_Delete(root);
    return st;
}

void cj_surface_json_free(cj_bspline_surface *s) {
    cj_json_bspline_surface_free(s);
}

cj_status cj_surface_json_print(FILE *f, const cj_bspline_surface *s, const char *what) {
    cJSON *root = cJSON_CreateObject();
    cj_status st = root ? cj_json_add_bspline_surface(root, s)
                        : cj_fail(CJ_ERR_NOMEM, "out of memory writing the surface");
    if (st) st = cj_fail(st, "%s: %s", what, cj_last_error());
    if (!st) st = cj_json_print(root, 1, f, what);
    cJSON_Delete(root);
    return st;
}

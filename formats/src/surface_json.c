/* The surface document (surface_json.h): read by the scene layer's one reader of the
 * B-spline surface object, written with the writing kit. */
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

static int add(cJSON *obj, const char *key, cJSON *item) {
    if (item && cJSON_AddItemToObject(obj, key, item)) return 0;
    cJSON_Delete(item);
    return -1;
}

cj_status cj_surface_json_print(FILE *f, const cj_bspline_surface *s, const char *what) {
    const int n = s->npts_u * s->npts_v;
    const double degree[2] = {s->deg_u, s->deg_v}, size[2] = {s->npts_u, s->npts_v};
    cJSON *root = cJSON_CreateObject(), *pts = cj_json_point_array(s->pts, (size_t)n, 3);
    int bad =
        !root || !pts ||
        add(root, "type", cJSON_CreateString(s->weights ? "nurbs_surface" : "bspline_surface")) ||
        add(root, "degree", cj_json_number_array(degree, 2)) ||
        add(root, "size", cj_json_number_array(size, 2)) ||
        add(root, "knots_u",
            cj_json_number_array(s->knots_u, (size_t)(s->npts_u + s->deg_u + 1))) ||
        add(root, "knots_v", cj_json_number_array(s->knots_v, (size_t)(s->npts_v + s->deg_v + 1)));
    if (!bad && s->weights) bad = add(root, "weights", cj_json_number_array(s->weights, (size_t)n));
    if (!bad) {
        bad = add(root, "points", pts); /* takes pts, also on failure */
        pts = NULL;
    }
    const cj_status st = bad ? cj_fail(CJ_ERR_NOMEM, "%s: out of memory writing the surface", what)
                             : cj_json_print(root, 1, f, what);
    cJSON_Delete(pts);
    cJSON_Delete(root);
    return st;
}

/* The one reader and writer of the B-spline / NURBS surface object
 * (bspline_surface_json_internal.h). */
#include "bspline_surface_json_internal.h"

#include "json_write_internal.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAX_POINTS 1000000

void cj_json_bspline_surface_free(cj_bspline_surface *s) {
    free((double *)s->pts);
    free((double *)s->weights);
    free((double *)s->knots_u);
    free((double *)s->knots_v);
    memset(s, 0, sizeof *s);
}

/* Two whole numbers in [lo, hi] under key ("degree": [p, q], "size": [nu, nv]). */
static cj_status int_pair(const cj_json_doc *d, const cJSON *obj, const char *path, const char *key,
                          int lo, int hi, int *a, int *b) {
    const cJSON *v = NULL;
    double two[2];
    char p[CJ_JSON_PATH], q[CJ_JSON_PATH];
    cj_json_join(p, path, key);
    CJ_JSON_TRY(cj_json_require(d, obj, path, key, &v));
    CJ_JSON_TRY(cj_json_array_at(d, v, p, 2, two));
    cj_json_index(q, p, 0);
    CJ_JSON_TRY(cj_json_int_at(d, v->child, q, lo, hi, a));
    cj_json_index(q, p, 1);
    return cj_json_int_at(d, v->child->next, q, lo, hi, b);
}

/* The knots of one direction: given, or clamped uniform on [0, 1]. */
static cj_status read_knots(const cj_json_doc *d, const cJSON *obj, const char *path, int dir,
                            int count, int degree, double **out) {
    const char *key = dir ? "knots_v" : "knots_u";
    const size_t want = (size_t)(count + degree + 1);
    const cJSON *kn = cJSON_GetObjectItemCaseSensitive(obj, key);
    char p[CJ_JSON_PATH];
    cj_json_join(p, path, key);
    size_t got = 0;
    if (kn) return cj_json_numbers(d, kn, p, 0, CJ_JSON_ANY, 0.0, want, out, &got);
    if (!(*out = malloc(sizeof(double) * want)))
        return cj_json_fail(d, obj, 0, CJ_ERR_NOMEM, "%s: out of memory", p);
    const cj_status st = cj_bspline_uniform_knots(count, degree, 0.0, 1.0, 1, *out);
    if (!st) return CJ_OK;
    free(*out);
    *out = NULL;
    char msg[400];
    snprintf(msg, sizeof msg, "%s", cj_last_error());
    return cj_json_fail(d, obj, 0, st, "%s: %s", p, msg);
}

static cj_status read_surface(const cj_json_doc *d, const cJSON *obj, const char *path, int named,
                              cj_bspline_surface *s) {
    static const char *const types[] = {"bspline_surface", "nurbs_surface", NULL};
    static const char *const keys[] = {"type",    "degree",  "size", "points", "knots_u",
                                       "knots_v", "weights", "name", NULL};
    static const char *const keys_unnamed[] = {"type",    "degree",  "size",    "points",
                                               "knots_u", "knots_v", "weights", NULL};
    char p[CJ_JSON_PATH];
    const cJSON *t = NULL;
    int nurbs = 0;
    CJ_JSON_TRY(cj_json_object(d, obj, path, named ? keys : keys_unnamed));
    CJ_JSON_TRY(cj_json_require(d, obj, path, "type", &t));
    CJ_JSON_TRY(cj_json_enum(d, obj, path, "type", types, &nurbs));
    const cJSON *wn = cJSON_GetObjectItemCaseSensitive(obj, "weights");
    cj_json_join(p, path, "weights");
    if (wn && !nurbs)
        return cj_json_fail(d, wn, 1, CJ_ERR_PARSE,
                            "%s are given for a bspline_surface (weights make a nurbs_surface)", p);
    CJ_JSON_TRY(int_pair(d, obj, path, "degree", 1, CJ_PATCH_MAX_DEGREE, &s->deg_u, &s->deg_v));
    CJ_JSON_TRY(int_pair(d, obj, path, "size", 2, MAX_POINTS / 2, &s->npts_u, &s->npts_v));
    const size_t n = (size_t)s->npts_u * (size_t)s->npts_v;
    cj_json_join(p, path, "size");
    if (n > MAX_POINTS)
        return cj_json_fail(d, cJSON_GetObjectItemCaseSensitive(obj, "size"), 0, CJ_ERR_RANGE,
                            "%s: %d x %d is more than 1e6 control points", p, s->npts_u, s->npts_v);
    const cJSON *pn = NULL;
    size_t got = 0;
    double *arr = NULL;
    CJ_JSON_TRY(cj_json_require(d, obj, path, "points", &pn));
    cj_json_join(p, path, "points");
    CJ_JSON_TRY(cj_json_numbers(d, pn, p, 3, CJ_JSON_ANY, 0.0, n, &arr, &got));
    s->pts = arr;
    if (nurbs) {
        CJ_JSON_TRY(cj_json_require(d, obj, path, "weights", &wn));
        cj_json_join(p, path, "weights");
        CJ_JSON_TRY(cj_json_numbers(d, wn, p, 0, CJ_JSON_GT, 0.0, n, &arr, &got));
        s->weights = arr;
    }
    CJ_JSON_TRY(read_knots(d, obj, path, 0, s->npts_u, s->deg_u, &arr));
    s->knots_u = arr;
    CJ_JSON_TRY(read_knots(d, obj, path, 1, s->npts_v, s->deg_v, &arr));
    s->knots_v = arr;
    int patches = 0;
    const cj_status st = cj_bspline_surface_patch_count(s, &patches);
    if (st) {
        char msg[400];
        snprintf(msg, sizeof msg, "%s", cj_last_error());
        return cj_json_fail(d, obj, 0, st, "%s: %s", *path ? path : "document", msg);
    }
    return CJ_OK;
}

cj_status cj_json_read_bspline_surface(const cj_json_doc *d, const cJSON *obj, const char *path,
                                       int named, cj_bspline_surface *out) {
    memset(out, 0, sizeof *out);
    const cj_status st = read_surface(d, obj, path, named, out);
    if (st) cj_json_bspline_surface_free(out);
    return st;
}

/* Adds item (taking it) under key; 0, or -1 when out of memory. */
static int add(cJSON *obj, const char *key, cJSON *item) {
    if (item && cJSON_AddItemToObject(obj, key, item)) return 0;
    cJSON_Delete(item);
    return -1;
}

cj_status cj_json_add_bspline_surface(cJSON *obj, const cj_bspline_surface *s) {
    const size_t n = (size_t)s->npts_u * (size_t)s->npts_v;
    const double degree[2] = {s->deg_u, s->deg_v}, size[2] = {s->npts_u, s->npts_v};
    const int bad =
        add(obj, "type", cJSON_CreateString(s->weights ? "nurbs_surface" : "bspline_surface")) ||
        add(obj, "degree", cj_json_number_array(degree, 2)) ||
        add(obj, "size", cj_json_number_array(size, 2)) ||
        add(obj, "points", cj_json_point_array(s->pts, n, 3)) ||
        add(obj, "knots_u", cj_json_number_array(s->knots_u, (size_t)(s->npts_u + s->deg_u + 1))) ||
        add(obj, "knots_v", cj_json_number_array(s->knots_v, (size_t)(s->npts_v + s->deg_v + 1))) ||
        (s->weights && add(obj, "weights", cj_json_number_array(s->weights, n)));
    return bad ? cj_fail(CJ_ERR_NOMEM, "out of memory writing a %dx%d B-spline surface", s->npts_u,
                         s->npts_v)
               : CJ_OK;
}

/* B-spline / NURBS surfaces in the tool's JSON. See surface_json.h. */
#include "surface_json.h"

#include "error_internal.h"
#include "file_internal.h"
#include "json_read_internal.h"
#include "json_write_internal.h"

#include <cJSON.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#define SURFACE_JSON_MAX_BYTES ((size_t)256 << 20)

static int fail(char *why, size_t n, const char *fmt, ...) {
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(why, n, fmt, ap);
    va_end(ap);
    return -1;
}

static char *slurp(const char *path, char *why, size_t n, int *nomem) {
    char *data = NULL;
    size_t size = 0;
    const cj_status st =
        cj_file_read_input(path, SURFACE_JSON_MAX_BYTES, "surface document", &data, &size);
    *nomem = st == CJ_ERR_NOMEM;
    if (st) fail(why, n, "%s", cj_last_error());
    return st ? NULL : data;
}

/* Two whole numbers in [lo, hi] ("degree": [p, q], "size": [nu, nv]). */
static cj_status int_pair(const cj_json_doc *d, const cJSON *root, const char *key, int lo, int hi,
                          int *a, int *b) {
    const cJSON *v = NULL;
    double two[2];
    CJ_JSON_TRY(cj_json_require(d, root, "", key, &v));
    CJ_JSON_TRY(cj_json_array_at(d, v, key, 2, two));
    char p[CJ_JSON_PATH];
    cj_json_index(p, key, 0);
    CJ_JSON_TRY(cj_json_int_at(d, v->child, p, lo, hi, a));
    cj_json_index(p, key, 1);
    return cj_json_int_at(d, v->child->next, p, lo, hi, b);
}

/* The surface of the document root, checked with the kit, into its arrays (malloc'd). */
static cj_status read_surface(const cj_json_doc *d, const cJSON *root, cj_bspline_surface *s) {
    static const char *const types[] = {"bspline_surface", "nurbs_surface", NULL};
    static const char *const keys[] = {"type",    "degree",  "size",    "points",
                                       "knots_u", "knots_v", "weights", NULL};
    const cJSON *t = NULL;
    int nurbs = 0;
    CJ_JSON_TRY(cj_json_object(d, root, "", keys));
    CJ_JSON_TRY(cj_json_require(d, root, "", "type", &t));
    CJ_JSON_TRY(cj_json_enum(d, root, "", "type", types, &nurbs));
    const cJSON *wn = cJSON_GetObjectItemCaseSensitive(root, "weights");
    if (wn && !nurbs)
        return cj_json_fail(d, wn, 1, CJ_ERR_PARSE,
                            "weights are given for a bspline_surface (weights make a "
                            "nurbs_surface)");
    CJ_JSON_TRY(int_pair(d, root, "degree", 1, CJ_PATCH_MAX_DEGREE, &s->deg_u, &s->deg_v));
    CJ_JSON_TRY(int_pair(d, root, "size", 2, 100000, &s->npts_u, &s->npts_v));
    const size_t n = (size_t)s->npts_u * (size_t)s->npts_v;
    if (n > 10000000)
        return cj_json_fail(d, cJSON_GetObjectItemCaseSensitive(root, "size"), 0, CJ_ERR_RANGE,
                            "size: more than 1e7 control points");
    const cJSON *pn = NULL;
    size_t got = 0;
    double *pts = NULL, *w = NULL, *knots[2] = {NULL, NULL};
    CJ_JSON_TRY(cj_json_require(d, root, "", "points", &pn));
    CJ_JSON_TRY(cj_json_numbers(d, pn, "points", 3, CJ_JSON_ANY, 0.0, n, &pts, &got));
    s->pts = pts;
    if (nurbs) {
        CJ_JSON_TRY(cj_json_require(d, root, "", "weights", &wn));
        CJ_JSON_TRY(cj_json_numbers(d, wn, "weights", 0, CJ_JSON_GT, 0.0, n, &w, &got));
        s->weights = w;
    }
    for (int dir = 0; dir < 2; ++dir) {
        const char *key = dir ? "knots_v" : "knots_u";
        const int cnt = dir ? s->npts_v : s->npts_u, deg = dir ? s->deg_v : s->deg_u;
        const size_t want = (size_t)(cnt + deg + 1);
        const cJSON *kn = cJSON_GetObjectItemCaseSensitive(root, key);
        if (kn) {
            CJ_JSON_TRY(cj_json_numbers(d, kn, key, 0, CJ_JSON_ANY, 0.0, want, &knots[dir], &got));
        } else if (!(knots[dir] = malloc(sizeof(double) * want))) {
            return cj_fail(CJ_ERR_NOMEM, "%s: out of memory", d->name);
        } else if (cj_bspline_uniform_knots(cnt, deg, 0.0, 1.0, 1, knots[dir])) {
            free(knots[dir]);
            return cj_json_relabel(d, root, CJ_ERR_PARSE);
        }
        if (dir)
            s->knots_v = knots[dir];
        else
            s->knots_u = knots[dir];
    }
    return CJ_OK;
}

int surface_json_load(const char *path, surface_patches *out, char *why, size_t n, int *nomem) {
    memset(out, 0, sizeof *out);
    *nomem = 0;
    char *text = slurp(path, why, n, nomem);
    if (!text) return -1;
    cJSON *root = NULL;
    cj_status st = cj_json_parse(path, text, &root);
    cj_bspline_surface s;
    memset(&s, 0, sizeof s);
    if (!st) {
        cj_json_lines lines;
        cj_json_doc d;
        cj_json_doc_init(&d, &lines, path, text, root);
        st = read_surface(&d, root, &s);
        cj_json_doc_free(&d);
    }
    cJSON_Delete(root);
    free(text);
    const int p = s.deg_u, q = s.deg_v;
    int np = 0;
    if (!st) st = cj_bspline_surface_patch_count(&s, &np);
    const size_t per = (size_t)(p + 1) * (size_t)(q + 1);
    if (!st) {
        out->pts = malloc(sizeof(double) * 3 * per * (size_t)np);
        out->weights = s.weights ? malloc(sizeof(double) * per * (size_t)np) : NULL;
        out->patches = calloc((size_t)np, sizeof *out->patches);
        if (!out->pts || !out->patches || (s.weights && !out->weights))
            st = cj_fail(CJ_ERR_NOMEM, "out of memory for %d patches", np);
    }
    if (!st) st = cj_bspline_surface_to_patches(&s, out->pts, out->weights, NULL, NULL, np, NULL);
    if (!st) {
        for (int i = 0; i < np; ++i)
            out->patches[i] = cj_patch_view(p, q, out->pts + 3 * per * (size_t)i,
                                            out->weights ? out->weights + per * (size_t)i : NULL);
        out->count = (size_t)np;
    }
    free((double *)s.pts);
    free((double *)s.weights);
    free((double *)s.knots_u);
    free((double *)s.knots_v);
    if (st) {
        *nomem = st == CJ_ERR_NOMEM;
        fail(why, n, "%s", cj_last_error());
        surface_json_free(out);
        return -1;
    }
    return 0;
}

void surface_json_free(surface_patches *s) {
    free(s->patches);
    free(s->pts);
    free(s->weights);
    memset(s, 0, sizeof *s);
}

static int add(cJSON *obj, const char *key, cJSON *item) {
    if (item && cJSON_AddItemToObject(obj, key, item)) return 0;
    cJSON_Delete(item);
    return -1;
}

int surface_json_write(FILE *f, const cj_bspline_surface *s) {
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
    const cj_status st = bad ? cj_fail(CJ_ERR_NOMEM, "fit: out of memory writing the surface")
                             : cj_json_print(root, 1, f, "fit");
    cJSON_Delete(pts);
    cJSON_Delete(root);
    return st ? -1 : 0;
}

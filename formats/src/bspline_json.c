/* The B-spline curve item of the tool's JSON documents. See bspline_json.h. */
#include "bspline_json.h"

#include "json_read_internal.h"
#include "json_write_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

cj_status cj_bsp_json_parse(const cj_json_doc *doc, const cJSON *item, const char *path,
                            const char *const *extra_keys, size_t max_points, cj_bsp_json *out) {
    static const char *const base[] = {"type", "degree", "points", "knots", "weights"};
    const char *keys[24];
    size_t nk = 0;
    for (size_t i = 0; i < sizeof base / sizeof base[0]; ++i) keys[nk++] = base[i];
    for (size_t i = 0; extra_keys && extra_keys[i] && nk < 23; ++i) keys[nk++] = extra_keys[i];
    keys[nk] = NULL;
    memset(out, 0, sizeof *out);
    CJ_JSON_TRY(cj_json_object(doc, item, path, keys));
    char p[CJ_JSON_PATH];
    const cJSON *dv = NULL, *pv = NULL;
    CJ_JSON_TRY(cj_json_require(doc, item, path, "degree", &dv));
    cj_json_join(p, path, "degree");
    CJ_JSON_TRY(cj_json_int_at(doc, dv, p, 0, CJ_BSPLINE_MAX_DEGREE, &out->degree));
    CJ_JSON_TRY(cj_json_require(doc, item, path, "points", &pv));
    cj_json_join(p, path, "points");
    CJ_JSON_TRY(cj_json_list(doc, pv, p));
    const int np = cJSON_GetArraySize(pv);
    if ((size_t)np > max_points)
        return cj_json_fail(doc, pv, 0, CJ_ERR_RANGE, "%s: more than %zu control points", p,
                            max_points);
    const cJSON *first = pv->child;
    const int dim = cJSON_IsArray(first) ? cJSON_GetArraySize(first) : 0;
    if (first && (dim < 1 || dim > CJ_MAX_DIM))
        return cj_json_fail(doc, first, 0, CJ_ERR_PARSE,
                            "%s[0] must be an array of 1 to %d numbers, not %s", p, CJ_MAX_DIM,
                            cj_json_type_name(first));
    size_t count = 0;
    CJ_JSON_TRY(cj_json_numbers(doc, pv, p, dim, CJ_JSON_ANY, 0.0, 0, &out->pts, &count));
    out->dim = dim;
    out->npts = np;
    const int nk_want = np + out->degree + 1;
    const cJSON *kv = cJSON_GetObjectItemCaseSensitive(item, "knots");
    cj_status st = CJ_OK;
    if (kv) {
        cj_json_join(p, path, "knots");
        if (cJSON_IsArray(kv) && cJSON_GetArraySize(kv) != nk_want)
            st = cj_json_fail(doc, kv, 0, CJ_ERR_PARSE,
                              "%s has %d values; %d points of degree %d need %d (points + "
                              "degree + 1)",
                              p, cJSON_GetArraySize(kv), np, out->degree, nk_want);
        if (!st)
            st = cj_json_numbers(doc, kv, p, 0, CJ_JSON_ANY, 0.0, (size_t)nk_want, &out->knots,
                                 &count);
    } else {
        out->knots = malloc(sizeof(double) * (size_t)nk_want);
        if (!out->knots || cj_bspline_uniform_knots(np, out->degree, 0.0, 1.0, 1, out->knots))
            st = cj_json_fail(doc, item, 0, CJ_ERR_PARSE, "%s: %d points are too few for degree %d",
                              path, np, out->degree);
    }
    const cJSON *wv = cJSON_GetObjectItemCaseSensitive(item, "weights");
    if (!st && wv) {
        cj_json_join(p, path, "weights");
        st = cj_json_numbers(doc, wv, p, 0, CJ_JSON_GT, 0.0, (size_t)np, &out->weights, &count);
    }
    if (!st) {
        const cj_bspline c = cj_bsp_json_view(out);
        if (cj_bspline_check(&c))
            st = cj_json_fail(doc, item, 0, CJ_ERR_PARSE, "%s: %s", path, cj_last_error());
    }
    if (st) cj_bsp_json_free(out);
    return st;
}

void cj_bsp_json_free(cj_bsp_json *b) {
    free(b->pts);
    free(b->weights);
    free(b->knots);
    b->pts = b->weights = b->knots = NULL;
}

static int is_bspline(const cJSON *o) {
    const cJSON *t = cJSON_GetObjectItemCaseSensitive(o, "type");
    return cJSON_IsObject(o) && cJSON_IsString(t) && !strcmp(t->valuestring, "bspline");
}

static const cJSON *in_items(const cJSON *o, const char *prefix, char *path, size_t n) {
    const cJSON *items = cJSON_GetObjectItemCaseSensitive(o, "items");
    if (!cJSON_IsArray(items)) return NULL;
    int i = 0;
    for (const cJSON *it = items->child; it; it = it->next, ++i)
        if (is_bspline(it)) {
            snprintf(path, n, "%sitems[%d]", prefix, i);
            return it;
        }
    return NULL;
}

const cJSON *cj_bsp_json_find(const cJSON *doc, char *path, size_t n) {
    if (is_bspline(doc)) {
        snprintf(path, n, "document");
        return doc;
    }
    const cJSON *it = in_items(doc, "", path, n);
    if (it) return it;
    const cJSON *panels = cJSON_GetObjectItemCaseSensitive(doc, "panels");
    if (!cJSON_IsArray(panels)) return NULL;
    int i = 0;
    for (const cJSON *pn = panels->child; pn; pn = pn->next, ++i) {
        char prefix[64];
        snprintf(prefix, sizeof prefix, "panels[%d].", i);
        if ((it = in_items(pn, prefix, path, n))) return it;
    }
    return NULL;
}

cJSON *cj_bsp_json_item(const cj_bspline *c) {
    cJSON *it = cJSON_CreateObject(), *pts = cj_json_point_array(c->pts, (size_t)c->npts, c->dim);
    int bad = !it || !pts || !cJSON_AddStringToObject(it, "type", "bspline") ||
              cj_json_add_number(it, "degree", c->degree);
    cJSON *knots = bad ? NULL : cj_json_number_array(c->knots, (size_t)(c->npts + c->degree + 1));
    if (!bad && (!knots || !cJSON_AddItemToObject(it, "knots", knots))) {
        cJSON_Delete(knots);
        bad = 1;
    }
    if (!bad && c->weights) {
        cJSON *w = cj_json_number_array(c->weights, (size_t)c->npts);
        if (!w || !cJSON_AddItemToObject(it, "weights", w)) {
            cJSON_Delete(w);
            bad = 1;
        }
    }
    if (!bad && !cJSON_AddItemToObject(it, "points", pts))
        bad = 1;
    else if (!bad)
        pts = NULL;
    cJSON_Delete(pts);
    if (bad) {
        cJSON_Delete(it);
        return NULL;
    }
    return it;
}

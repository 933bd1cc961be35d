/* The B-spline curve item of the tool's JSON documents. See bspline_json.h. */
#include "bspline_json.h"

#include "json_write_internal.h"

#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

static int fail(char *why, size_t n, const char *fmt, ...) {
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(why, n, fmt, ap);
    va_end(ap);
    return -1;
}

/* A JSON array of count finite numbers into a new array. */
static int numbers(const cJSON *v, const char *path, const char *name, double **out, int *count,
                   char *why, size_t n) {
    if (!cJSON_IsArray(v)) return fail(why, n, "%s.%s is not an array of numbers", path, name);
    const int m = cJSON_GetArraySize(v);
    double *a = malloc(sizeof(double) * (size_t)(m > 0 ? m : 1));
    if (!a) return fail(why, n, "%s.%s: out of memory", path, name);
    int i = 0;
    for (const cJSON *e = v->child; e; e = e->next, ++i) {
        if (!cJSON_IsNumber(e) || !isfinite(e->valuedouble)) {
            free(a);
            return fail(why, n, "%s.%s[%d] is not a finite number", path, name, i);
        }
        a[i] = e->valuedouble;
    }
    *out = a;
    *count = m;
    return 0;
}

int cj_bsp_json_parse(const cJSON *item, const char *path, const char *const *extra_keys,
                      size_t max_points, cj_bsp_json *out, char *why, size_t why_size) {
    static const char *const keys[] = {"type", "degree", "points", "knots", "weights", NULL};
    memset(out, 0, sizeof *out);
    if (!cJSON_IsObject(item)) return fail(why, why_size, "%s is not an object", path);
    for (const cJSON *f = item->child; f; f = f->next) {
        int ok = 0;
        for (int i = 0; keys[i] && !ok; ++i) ok = !strcmp(f->string, keys[i]);
        for (int i = 0; extra_keys && extra_keys[i] && !ok; ++i)
            ok = !strcmp(f->string, extra_keys[i]);
        if (!ok) return fail(why, why_size, "%s: unknown field \"%s\"", path, f->string);
    }
    const cJSON *dv = cJSON_GetObjectItemCaseSensitive(item, "degree");
    if (!dv || !cJSON_IsNumber(dv) || dv->valuedouble != floor(dv->valuedouble) ||
        dv->valuedouble < 0 || dv->valuedouble > CJ_BSPLINE_MAX_DEGREE)
        return fail(why, why_size, "%s.degree is missing or not an integer in 0..%d", path,
                    CJ_BSPLINE_MAX_DEGREE);
    out->degree = (int)dv->valuedouble;
    const cJSON *pv = cJSON_GetObjectItemCaseSensitive(item, "points");
    if (!pv || !cJSON_IsArray(pv) || cJSON_GetArraySize(pv) == 0)
        return fail(why, why_size, "%s.points is missing or not a non-empty array of points", path);
    const int np = cJSON_GetArraySize(pv);
    if ((size_t)np > max_points)
        return fail(why, why_size, "%s.points: more than %zu control points", path, max_points);
    const cJSON *first = pv->child;
    const int dim = cJSON_IsArray(first) ? cJSON_GetArraySize(first) : 0;
    if (dim < 1 || dim > CJ_MAX_DIM)
        return fail(why, why_size, "%s.points[0] is not an array of 1..%d numbers", path,
                    CJ_MAX_DIM);
    out->dim = dim;
    out->npts = np;
    out->pts = malloc(sizeof(double) * (size_t)np * (size_t)dim);
    if (!out->pts) return fail(why, why_size, "%s.points: out of memory", path);
    int i = 0;
    for (const cJSON *e = pv->child; e; e = e->next, ++i) {
        if (!cJSON_IsArray(e) || cJSON_GetArraySize(e) != dim) {
            cj_bsp_json_free(out);
            return fail(why, why_size, "%s.points[%d] does not have %d coordinates like points[0]",
                        path, i, dim);
        }
        int k = 0;
        for (const cJSON *x = e->child; x; x = x->next, ++k) {
            if (!cJSON_IsNumber(x) || !isfinite(x->valuedouble)) {
                cj_bsp_json_free(out);
                return fail(why, why_size, "%s.points[%d][%d] is not a finite number", path, i, k);
            }
            out->pts[(size_t)i * (size_t)dim + (size_t)k] = x->valuedouble;
        }
    }
    const int nk_want = np + out->degree + 1;
    const cJSON *kv = cJSON_GetObjectItemCaseSensitive(item, "knots");
    int nk = 0;
    if (kv) {
        if (numbers(kv, path, "knots", &out->knots, &nk, why, why_size)) {
            cj_bsp_json_free(out);
            return -1;
        }
        if (nk != nk_want) {
            cj_bsp_json_free(out);
            return fail(why, why_size,
                        "%s.knots has %d values; %d points of degree %d need %d (points + degree "
                        "+ 1)",
                        path, nk, np, out->degree, nk_want);
        }
    } else {
        out->knots = malloc(sizeof(double) * (size_t)nk_want);
        if (!out->knots || cj_bspline_uniform_knots(np, out->degree, 0.0, 1.0, 1, out->knots)) {
            cj_bsp_json_free(out);
            return fail(why, why_size, "%s: %d points are too few for degree %d", path, np,
                        out->degree);
        }
    }
    const cJSON *wv = cJSON_GetObjectItemCaseSensitive(item, "weights");
    if (wv) {
        int nw = 0;
        if (numbers(wv, path, "weights", &out->weights, &nw, why, why_size)) {
            cj_bsp_json_free(out);
            return -1;
        }
        if (nw != np) {
            cj_bsp_json_free(out);
            return fail(why, why_size, "%s.weights has %d values for %d points", path, nw, np);
        }
    }
    const cj_bspline c = cj_bsp_json_view(out);
    if (cj_bspline_check(&c)) {
        fail(why, why_size, "%s: %s", path, cj_last_error());
        cj_bsp_json_free(out);
        return -1;
    }
    return 0;
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

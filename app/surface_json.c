/* B-spline / NURBS surfaces in the tool's JSON. See surface_json.h. */
#include "surface_json.h"

#include "error_internal.h"
#include "file_internal.h"
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

/* An array of exactly `want` finite numbers (or of `want` triples when triple). */
static int numbers(const cJSON *v, const char *name, size_t want, int triple, double **out,
                   char *why, size_t n) {
    if (!cJSON_IsArray(v) || (size_t)cJSON_GetArraySize(v) != want)
        return fail(why, n, "%s must be an array of %zu %s", name, want,
                    triple ? "[x, y, z] points" : "numbers");
    double *a = malloc(sizeof(double) * (want ? want : 1) * (triple ? 3 : 1));
    if (!a) return fail(why, n, "%s: out of memory", name);
    size_t i = 0;
    for (const cJSON *e = v->child; e; e = e->next, ++i) {
        const cJSON *x = triple ? e->child : e;
        for (int c = 0; c < (triple ? 3 : 1); ++c, x = x ? x->next : NULL) {
            if ((triple && (!cJSON_IsArray(e) || cJSON_GetArraySize(e) != 3)) || !x ||
                !cJSON_IsNumber(x) || !isfinite(x->valuedouble)) {
                free(a);
                return triple ? fail(why, n, "%s[%zu] is not [x, y, z] of finite numbers", name, i)
                              : fail(why, n, "%s[%zu] is not a finite number", name, i);
            }
            a[triple ? 3 * i + (size_t)c : i] = x->valuedouble;
        }
    }
    *out = a;
    return 0;
}

static int int_pair(const cJSON *v, const char *name, int lo, int hi, int *a, int *b, char *why,
                    size_t n) {
    if (!cJSON_IsArray(v) || cJSON_GetArraySize(v) != 2 || !cJSON_IsNumber(v->child) ||
        !cJSON_IsNumber(v->child->next))
        return fail(why, n, "%s must be two integers", name);
    const double x = v->child->valuedouble, y = v->child->next->valuedouble;
    if (x != floor(x) || y != floor(y) || x < lo || y < lo || x > hi || y > hi)
        return fail(why, n, "%s must be two integers in %d..%d", name, lo, hi);
    *a = (int)x;
    *b = (int)y;
    return 0;
}

int surface_json_load(const char *path, surface_patches *out, char *why, size_t n, int *nomem) {
    memset(out, 0, sizeof *out);
    *nomem = 0;
    char *text = slurp(path, why, n, nomem);
    if (!text) return -1;
    cJSON *doc = cJSON_Parse(text);
    free(text);
    if (!doc) return fail(why, n, "'%s' is not valid JSON", path);
    int r = 0, nurbs = 0, p = 0, q = 0, nu = 0, nv = 0;
    double *pts = NULL, *w = NULL, *ku = NULL, *kv = NULL;
    const cJSON *t = cJSON_GetObjectItemCaseSensitive(doc, "type");
    if (!cJSON_IsString(t) ||
        (strcmp(t->valuestring, "bspline_surface") && strcmp(t->valuestring, "nurbs_surface")))
        r = fail(why, n, "type must be \"bspline_surface\" or \"nurbs_surface\"");
    else
        nurbs = !strcmp(t->valuestring, "nurbs_surface");
    static const char *const keys[] = {"type",    "degree",  "size",    "points",
                                       "knots_u", "knots_v", "weights", NULL};
    for (const cJSON *f = doc->child; f && !r; f = f->next) {
        int ok = 0;
        for (int i = 0; keys[i] && !ok; ++i) ok = !strcmp(f->string, keys[i]);
        if (!ok || (!nurbs && !strcmp(f->string, "weights")))
            r = fail(why, n, "unknown field \"%s\"%s", f->string,
                     ok ? " (weights make a nurbs_surface)" : "");
    }
    if (!r)
        r = int_pair(cJSON_GetObjectItemCaseSensitive(doc, "degree"), "degree", 1,
                     CJ_PATCH_MAX_DEGREE, &p, &q, why, n);
    if (!r)
        r = int_pair(cJSON_GetObjectItemCaseSensitive(doc, "size"), "size", 2, 100000, &nu, &nv,
                     why, n);
    if (!r && (double)nu * nv > 1e7) r = fail(why, n, "size: more than 1e7 control points");
    if (!r)
        r = numbers(cJSON_GetObjectItemCaseSensitive(doc, "points"), "points",
                    (size_t)nu * (size_t)nv, 1, &pts, why, n);
    if (!r && nurbs)
        r = numbers(cJSON_GetObjectItemCaseSensitive(doc, "weights"), "weights",
                    (size_t)nu * (size_t)nv, 0, &w, why, n);
    for (int dir = 0; dir < 2 && !r; ++dir) {
        const char *key = dir ? "knots_v" : "knots_u";
        const int cnt = dir ? nv : nu, deg = dir ? q : p;
        double **dst = dir ? &kv : &ku;
        const cJSON *kn = cJSON_GetObjectItemCaseSensitive(doc, key);
        if (kn)
            r = numbers(kn, key, (size_t)(cnt + deg + 1), 0, dst, why, n);
        else if (!(*dst = malloc(sizeof(double) * (size_t)(cnt + deg + 1))))
            r = fail(why, n, "out of memory");
        else if (cj_bspline_uniform_knots(cnt, deg, 0.0, 1.0, 1, *dst))
            r = fail(why, n, "%s", cj_last_error());
    }
    cJSON_Delete(doc);
    const cj_bspline_surface s = {p, q, nu, nv, pts, w, ku, kv};
    int np = 0;
    if (!r && cj_bspline_surface_patch_count(&s, &np)) r = fail(why, n, "%s", cj_last_error());
    const size_t per = (size_t)(p + 1) * (size_t)(q + 1);
    if (!r) {
        out->pts = malloc(sizeof(double) * 3 * per * (size_t)np);
        out->weights = w ? malloc(sizeof(double) * per * (size_t)np) : NULL;
        out->patches = calloc((size_t)np, sizeof *out->patches);
        if (!out->pts || !out->patches || (w && !out->weights)) {
            *nomem = 1;
            r = fail(why, n, "out of memory for %d patches", np);
        }
    }
    if (!r && cj_bspline_surface_to_patches(&s, out->pts, out->weights, NULL, NULL, np, NULL))
        r = fail(why, n, "%s", cj_last_error());
    if (!r) {
        for (int i = 0; i < np; ++i)
            out->patches[i] = cj_patch_view(p, q, out->pts + 3 * per * (size_t)i,
                                            out->weights ? out->weights + per * (size_t)i : NULL);
        out->count = (size_t)np;
    }
    free(pts);
    free(w);
    free(ku);
    free(kv);
    if (r) surface_json_free(out);
    return r;
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

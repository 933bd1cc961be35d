/* The animation document reader's own accessors (bounded numbers and vectors, key lists), on
 * the shared checked-JSON kit (json_read.c), which also gives the lines of messages. */
#include "anim_json_internal.h"

#include <math.h>
#include <stdint.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

cj_status aj_channel_line(actx *c, const cJSON *n) {
    cj_anim_doc *d = c->doc;
    if (!d) return CJ_OK;
    if (d->channel_line_count == d->channel_line_cap) {
        size_t cap = d->channel_line_cap ? 2 * d->channel_line_cap : 16;
        int *p = realloc(d->channel_lines, sizeof *p * cap);
        if (!p) return cj_fail(CJ_ERR_NOMEM, "no memory for the channels' lines");
        d->channel_lines = p;
        d->channel_line_cap = cap;
    }
    d->channel_lines[d->channel_line_count++] = cj_json_line(&c->json, n);
    return CJ_OK;
}

cj_status aj_num_in(const actx *c, const cJSON *obj, const char *path, const char *key, double lo,
                    double hi, int integer, double *out) {
    const cJSON *n = cJSON_GetObjectItemCaseSensitive(obj, key);
    if (!n) return CJ_OK;
    if (!cJSON_IsNumber(n) || !isfinite(n->valuedouble))
        return cj_json_fail(&c->json, n, 0, CJ_ERR_PARSE, "%s.%s must be a finite number", path,
                            key);
    const double v = n->valuedouble;
    if (!(v >= lo && v <= hi) || (integer && v != floor(v)))
        return cj_json_fail(&c->json, n, 0, CJ_ERR_RANGE, "%s.%s = %g must be %s in [%g, %g]", path,
                            key, v, integer ? "an integer" : "a number", lo, hi);
    *out = v;
    return CJ_OK;
}

cj_status aj_vec3_in(const actx *c, const cJSON *obj, const char *path, const char *key,
                     double bound, double *out) {
    double v[3] = {out[0], out[1], out[2]};
    cj_status st = aj_vec3(c, obj, path, key, v);
    if (st) return st;
    const double len = hypot(hypot(v[0], v[1]), v[2]); /* no overflow for 1e200 */
    if (!(len <= bound))
        return cj_json_fail(&c->json, cJSON_GetObjectItemCaseSensitive(obj, key), 0, CJ_ERR_RANGE,
                            "%s.%s has length %g, over the limit of %g", path, key, len, bound);
    memcpy(out, v, sizeof v);
    return CJ_OK;
}

/* An array of exactly `len` numbers (len 0: any length up to cap) into v; *count the length. */
cj_status aj_nums(const actx *c, const cJSON *n, const char *path, int len, double *v, size_t cap,
                  size_t *count) {
    if (!cJSON_IsArray(n))
        return cj_json_fail(&c->json, n, 0, CJ_ERR_PARSE, "%s must be an array", path);
    const size_t m = (size_t)cJSON_GetArraySize(n);
    if ((len && m != (size_t)len) || m > cap)
        return cj_json_fail(&c->json, n, 0, CJ_ERR_PARSE, "%s must hold %s%zu numbers", path,
                            len ? "" : "at most ", len ? (size_t)len : cap);
    size_t i = 0;
    for (const cJSON *e = n->child; e; e = e->next, ++i) {
        if (!cJSON_IsNumber(e) || !isfinite(e->valuedouble))
            return cj_json_fail(&c->json, e, 0, CJ_ERR_PARSE, "%s[%zu] must be a finite number",
                                path, i);
        v[i] = e->valuedouble;
    }
    if (count) *count = m;
    return CJ_OK;
}

cj_status aj_vec3(const actx *c, const cJSON *obj, const char *path, const char *key, double *out) {
    const cJSON *n = cJSON_GetObjectItemCaseSensitive(obj, key);
    if (!n) return CJ_OK;
    char p[300];
    snprintf(p, sizeof p, "%s.%s", path, key);
    return aj_nums(c, n, p, 3, out, 3, NULL);
}

cj_status aj_pick(const actx *c, const cJSON *obj, const char *path, const char *key,
                  const char *const *names, int *out) {
    const cJSON *n = cJSON_GetObjectItemCaseSensitive(obj, key);
    if (!n) return CJ_OK;
    if (cJSON_IsString(n))
        for (int i = 0; names[i]; ++i)
            if (!strcmp(names[i], n->valuestring)) {
                *out = i;
                return CJ_OK;
            }
    char list[400] = "";
    for (int i = 0; names[i]; ++i) {
        strncat(list, i ? ", " : "", sizeof list - strlen(list) - 1);
        strncat(list, names[i], sizeof list - strlen(list) - 1);
    }
    return cj_json_fail(&c->json, n, 0, CJ_ERR_PARSE, "%s.%s must be one of: %s", path, key, list);
}

/* A list of keys' values: numbers (dim 1) or arrays of dim numbers; malloc'ed, key-major. */
cj_status aj_key_values(const actx *c, const cJSON *arr, const char *path, int *dim, size_t want,
                        double **out) {
    if (!cJSON_IsArray(arr) || cJSON_GetArraySize(arr) < 1)
        return cj_json_fail(&c->json, arr, 0, CJ_ERR_PARSE, "%s must be a non-empty array", path);
    const size_t m = (size_t)cJSON_GetArraySize(arr);
    if (want && m != want)
        return cj_json_fail(&c->json, arr, 0, CJ_ERR_PARSE,
                            "%s has %zu entries, one per key (%zu) expected", path, m, want);
    const int d = cJSON_IsArray(arr->child) ? cJSON_GetArraySize(arr->child) : 1;
    if (*dim && d != *dim)
        return cj_json_fail(&c->json, arr, 0, CJ_ERR_PARSE, "%s entries must have %d numbers", path,
                            *dim);
    if (d < 1 || d > 8)
        return cj_json_fail(&c->json, arr, 0, CJ_ERR_PARSE, "%s entries hold 1..8 numbers", path);
    double *v = malloc(sizeof(double) * m * (size_t)d);
    if (!v) return cj_fail(CJ_ERR_NOMEM, "no memory for %s", path);
    size_t i = 0;
    for (const cJSON *e = arr->child; e; e = e->next, ++i) {
        char p[300];
        snprintf(p, sizeof p, "%s[%zu]", path, i);
        cj_status st;
        if (d == 1 && cJSON_IsNumber(e)) {
            st = isfinite(e->valuedouble)
                     ? CJ_OK
                     : cj_json_fail(&c->json, e, 0, CJ_ERR_PARSE, "%s must be finite", p);
            v[i] = e->valuedouble;
        } else {
            st = aj_nums(c, e, p, d, v + i * (size_t)d, (size_t)d, NULL);
        }
        if (st != CJ_OK) {
            free(v);
            return st;
        }
    }
    *dim = d;
    *out = v;
    return CJ_OK;
}

/* The checked-JSON reading kit (json_read_internal.h), shared by the scene reader
 * (scene_json*.c), the animation reader (anim_json*.c) and the plot reader (formats/): messages
 * "<name>:<line>: <path> ..." (the lines come from json_lines.c) and the checked accessors. */
#include "json_read_internal.h"

#include "json_write_internal.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const double DEG = 3.14159265358979323846 / 180.0;

/* ---- messages ------------------------------------------------------------------------------- */

cj_status cj_json_fail(const cj_json_doc *c, const cJSON *node, int at_key, cj_status st,
                       const char *fmt, ...) {
    char msg[768];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    int line = at_key ? cj_json_key_line(c, node) : cj_json_line(c, node);
    return cj_fail(st, "%s:%d: %s", c->name, line, msg);
}

cj_status cj_json_relabel(const cj_json_doc *c, const cJSON *node, cj_status st) {
    char msg[768];
    snprintf(msg, sizeof msg, "%s", cj_last_error());
    return cj_fail(st, "%s:%d: %s", c->name, cj_json_line(c, node), msg);
}

void cj_json_join(char *dst, const char *path, const char *key) {
    if (path[0])
        snprintf(dst, CJ_JSON_PATH, "%s.%s", path, key);
    else
        snprintf(dst, CJ_JSON_PATH, "%s", key);
}

void cj_json_index(char *dst, const char *path, size_t i) {
    snprintf(dst, CJ_JSON_PATH, "%s[%zu]", path, i);
}

/* ---- checked accessors ---------------------------------------------------------------------- */

const char *cj_json_type_name(const cJSON *n) {
    if (cJSON_IsObject(n)) return "an object";
    if (cJSON_IsArray(n)) return "an array";
    if (cJSON_IsString(n)) return "a string";
    if (cJSON_IsNumber(n)) return "a number";
    if (cJSON_IsBool(n)) return "a boolean";
    return "null";
}

cj_status cj_json_object(const cj_json_doc *c, const cJSON *obj, const char *path,
                         const char *const *allowed) {
    if (!cJSON_IsObject(obj))
        return cj_json_fail(c, obj, 0, CJ_ERR_PARSE, "%s must be an object, not %s",
                            path[0] ? path : "document", cj_json_type_name(obj));
    for (const cJSON *m = obj->child; m; m = m->next) {
        int known = 0;
        for (const char *const *a = allowed; *a && !known; ++a) known = !strcmp(*a, m->string);
        if (!known) {
            char list[512] = "";
            size_t len = 0;
            for (const char *const *a = allowed; *a; ++a) {
                int w =
                    snprintf(list + len, sizeof list - len, "%s%s", a == allowed ? "" : ", ", *a);
                if (w < 0 || (size_t)w >= sizeof list - len) break;
                len += (size_t)w;
            }
            char p[CJ_JSON_PATH];
            cj_json_join(p, path, m->string);
            return cj_json_fail(c, m, 1, CJ_ERR_PARSE,
                                "%s is not a known key (expected one of: %s)", p, list);
        }
        for (const cJSON *o = obj->child; o != m; o = o->next)
            if (!strcmp(o->string, m->string)) {
                char p[CJ_JSON_PATH];
                cj_json_join(p, path, m->string);
                return cj_json_fail(c, m, 1, CJ_ERR_PARSE, "%s is given twice (line %d)", p,
                                    cj_json_key_line(c, o));
            }
    }
    return CJ_OK;
}

cj_status cj_json_require(const cj_json_doc *c, const cJSON *obj, const char *path, const char *key,
                          const cJSON **out) {
    const cJSON *m = cJSON_GetObjectItemCaseSensitive(obj, key);
    if (!m)
        return cj_json_fail(c, obj, 0, CJ_ERR_PARSE, "%s: missing key \"%s\"",
                            path[0] ? path : "document", key);
    *out = m;
    return CJ_OK;
}

static cj_status check_range(const cj_json_doc *c, const cJSON *n, const char *p, cj_json_range r,
                             double lo, double hi, double v) {
    int ok = 1;
    char what[64] = "";
    switch (r) {
    case CJ_JSON_ANY:
        break;
    case CJ_JSON_GE:
        ok = v >= lo;
        snprintf(what, sizeof what, ">= %g", lo);
        break;
    case CJ_JSON_GT:
        ok = v > lo;
        snprintf(what, sizeof what, "> %g", lo);
        break;
    case CJ_JSON_LT:
        ok = v < hi;
        snprintf(what, sizeof what, "< %g", hi);
        break;
    case CJ_JSON_IN:
        ok = v >= lo && v <= hi;
        snprintf(what, sizeof what, "in [%g, %g]", lo, hi);
        break;
    case CJ_JSON_OPEN:
        ok = v > lo && v < hi;
        snprintf(what, sizeof what, "in (%g, %g)", lo, hi);
        break;
    }
    if (ok) return CJ_OK;
    char given[CJ_JSON_NUMBER_MAX];
    cj_json_number_text(v, given);
    return cj_json_fail(c, n, 0, CJ_ERR_RANGE, "%s must be %s, not %s", p, what, given);
}

static cj_status number_node(const cj_json_doc *c, const cJSON *n, const char *p, double *v) {
    if (!cJSON_IsNumber(n))
        return cj_json_fail(c, n, 0, CJ_ERR_PARSE, "%s must be a number, not %s", p,
                            cj_json_type_name(n));
    if (!isfinite(n->valuedouble))
        return cj_json_fail(c, n, 0, CJ_ERR_NONFINITE, "%s is not finite", p);
    *v = n->valuedouble;
    return CJ_OK;
}

cj_status cj_json_number_at(const cj_json_doc *c, const cJSON *n, const char *path, cj_json_range r,
                            double lo, double hi, double *out) {
    double v = 0.0;
    cj_status st = number_node(c, n, path, &v);
    if (!st) st = check_range(c, n, path, r, lo, hi, v);
    if (!st) *out = v;
    return st;
}

cj_status cj_json_int_at(const cj_json_doc *c, const cJSON *n, const char *path, double lo,
                         double hi, int *out) {
    double v;
    cj_status st = number_node(c, n, path, &v);
    if (st) return st;
    if (v != floor(v)) {
        char given[CJ_JSON_NUMBER_MAX];
        cj_json_number_text(v, given);
        return cj_json_fail(c, n, 0, CJ_ERR_PARSE, "%s must be an integer, not %s", path, given);
    }
    st = check_range(c, n, path, CJ_JSON_IN, lo, hi, v);
    if (!st) *out = (int)v;
    return st;
}

cj_status cj_json_bool_at(const cj_json_doc *c, const cJSON *n, const char *path, int *out) {
    if (!cJSON_IsBool(n))
        return cj_json_fail(c, n, 0, CJ_ERR_PARSE, "%s must be true or false, not %s", path,
                            cj_json_type_name(n));
    *out = cJSON_IsTrue(n) ? 1 : 0;
    return CJ_OK;
}

cj_status cj_json_string_at(const cj_json_doc *c, const cJSON *n, const char *path,
                            const char **out) {
    if (!cJSON_IsString(n))
        return cj_json_fail(c, n, 0, CJ_ERR_PARSE, "%s must be a string, not %s", path,
                            cj_json_type_name(n));
    *out = n->valuestring;
    return CJ_OK;
}

cj_status cj_json_num(const cj_json_doc *c, const cJSON *obj, const char *path, const char *key,
                      cj_json_range r, double lo, double hi, double *out) {
    const cJSON *n = cJSON_GetObjectItemCaseSensitive(obj, key);
    if (!n) return CJ_OK;
    char p[CJ_JSON_PATH];
    cj_json_join(p, path, key);
    return cj_json_number_at(c, n, p, r, lo, hi, out);
}

cj_status cj_json_int(const cj_json_doc *c, const cJSON *obj, const char *path, const char *key,
                      double lo, double hi, int *out) {
    const cJSON *n = cJSON_GetObjectItemCaseSensitive(obj, key);
    if (!n) return CJ_OK;
    char p[CJ_JSON_PATH];
    cj_json_join(p, path, key);
    return cj_json_int_at(c, n, p, lo, hi, out);
}

cj_status cj_json_bool(const cj_json_doc *c, const cJSON *obj, const char *path, const char *key,
                       int *out) {
    const cJSON *n = cJSON_GetObjectItemCaseSensitive(obj, key);
    if (!n) return CJ_OK;
    char p[CJ_JSON_PATH];
    cj_json_join(p, path, key);
    return cj_json_bool_at(c, n, p, out);
}

/* A fixed-length array of numbers at node n. */
static cj_status fixed_array(const cj_json_doc *c, const cJSON *n, const char *p, int len,
                             double *v, const char *what) {
    if (!cJSON_IsArray(n) || cJSON_GetArraySize(n) != len) {
        if (cJSON_IsArray(n))
            return cj_json_fail(c, n, 0, CJ_ERR_PARSE, "%s must be %s, not %d", p, what,
                                cJSON_GetArraySize(n));
        return cj_json_fail(c, n, 0, CJ_ERR_PARSE, "%s must be %s, not %s", p, what,
                            cj_json_type_name(n));
    }
    int k = 0;
    for (const cJSON *e = n->child; e; e = e->next, ++k) {
        char pe[CJ_JSON_PATH];
        cj_json_index(pe, p, (size_t)k);
        cj_status st = number_node(c, e, pe, &v[k]);
        if (st) return st;
    }
    return CJ_OK;
}

cj_status cj_json_array_at(const cj_json_doc *c, const cJSON *n, const char *path, int len,
                           double *out) {
    char what[48];
    snprintf(what, sizeof what, "an array of %d numbers", len);
    return fixed_array(c, n, path, len, out, what);
}

cj_status cj_json_vec3(const cj_json_doc *c, const cJSON *obj, const char *path, const char *key,
                       cj_vec3 *out) {
    const cJSON *n = cJSON_GetObjectItemCaseSensitive(obj, key);
    if (!n) return CJ_OK;
    char p[CJ_JSON_PATH];
    cj_json_join(p, path, key);
    double v[3];
    cj_status st = fixed_array(c, n, p, 3, v, "an array of 3 numbers");
    if (!st) *out = cj_v3(v[0], v[1], v[2]);
    return st;
}

cj_status cj_json_rgb(const cj_json_doc *c, const cJSON *obj, const char *path, const char *key,
                      double max, cj_rgb *out) {
    const cJSON *n = cJSON_GetObjectItemCaseSensitive(obj, key);
    if (!n) return CJ_OK;
    char p[CJ_JSON_PATH];
    cj_json_join(p, path, key);
    double v[3];
    cj_status st = fixed_array(c, n, p, 3, v, "an array of 3 numbers (linear RGB)");
    if (st) return st;
    const cJSON *e = n->child;
    for (int k = 0; k < 3; ++k, e = e->next) {
        char pe[CJ_JSON_PATH];
        cj_json_index(pe, p, (size_t)k);
        st = max >= 0 ? check_range(c, e, pe, CJ_JSON_IN, 0, max, v[k])
                      : check_range(c, e, pe, CJ_JSON_GE, 0, 0, v[k]);
        if (st) return st;
    }
    *out = cj_rgb_make(v[0], v[1], v[2]);
    return CJ_OK;
}

cj_status cj_json_string(const cj_json_doc *c, const cJSON *obj, const char *path, const char *key,
                         const char **out) {
    const cJSON *n = cJSON_GetObjectItemCaseSensitive(obj, key);
    if (!n) return CJ_OK;
    char p[CJ_JSON_PATH];
    cj_json_join(p, path, key);
    return cj_json_string_at(c, n, p, out);
}

cj_status cj_json_enum(const cj_json_doc *c, const cJSON *obj, const char *path, const char *key,
                       const char *const *names, int *out) {
    const char *s = NULL;
    cj_status st = cj_json_string(c, obj, path, key, &s);
    if (st || !s) return st;
    for (int i = 0; names[i]; ++i)
        if (!strcmp(names[i], s)) {
            *out = i;
            return CJ_OK;
        }
    char list[256] = "";
    size_t len = 0;
    for (int i = 0; names[i]; ++i) {
        int w = snprintf(list + len, sizeof list - len, "%s%s", i ? ", " : "", names[i]);
        if (w < 0 || (size_t)w >= sizeof list - len) break;
        len += (size_t)w;
    }
    char p[CJ_JSON_PATH];
    cj_json_join(p, path, key);
    return cj_json_fail(c, cJSON_GetObjectItemCaseSensitive(obj, key), 0, CJ_ERR_PARSE,
                        "%s \"%s\" is not one of %s", p, s, list);
}

/* The numbers of arr: exactly `want` entries when want > 0, else at least `min` (min 1: "must
 * not be empty"). */
static cj_status numbers(const cj_json_doc *c, const cJSON *arr, const char *path, int dim,
                         cj_json_range r, double lo, size_t min, size_t want, double **out,
                         size_t *count) {
    if (!cJSON_IsArray(arr))
        return cj_json_fail(c, arr, 0, CJ_ERR_PARSE, "%s must be an array, not %s", path,
                            cj_json_type_name(arr));
    size_t n = (size_t)cJSON_GetArraySize(arr);
    if (n == 0 && min <= 1)
        return cj_json_fail(c, arr, 0, CJ_ERR_PARSE, "%s must not be empty", path);
    if (!want && n < min) {
        const char *noun = dim > 0 ? "point" : "number";
        return cj_json_fail(c, arr, 0, CJ_ERR_PARSE, "%s has %zu %s%s, at least %zu needed", path,
                            n, noun, n == 1 ? "" : "s", min);
    }
    if (want && n != want)
        return cj_json_fail(c, arr, 0, CJ_ERR_PARSE, "%s must have %zu entries, not %zu", path,
                            want, n);
    size_t per = dim > 0 ? (size_t)dim : 1;
    double *v = malloc(n * per * sizeof *v);
    if (!v) return cj_fail(CJ_ERR_NOMEM, "%s: out of memory reading %s", c->name, path);
    size_t i = 0;
    for (const cJSON *e = arr->child; e; e = e->next, ++i) {
        /* Fast path for well-formed entries (big inline meshes); messages are only built on
         * the slow path below, which finds and names the fault. */
        if (dim > 0 && cJSON_IsArray(e)) {
            int k = 0;
            const cJSON *x = e->child;
            for (; x && k < dim && cJSON_IsNumber(x) && isfinite(x->valuedouble); x = x->next)
                v[i * per + (size_t)k++] = x->valuedouble;
            if (k == dim && !x) continue;
        } else if (dim <= 0 && cJSON_IsNumber(e) && isfinite(e->valuedouble) &&
                   (r == CJ_JSON_ANY || (r == CJ_JSON_GE && e->valuedouble >= lo) ||
                    (r == CJ_JSON_GT && e->valuedouble > lo))) {
            v[i] = e->valuedouble;
            continue;
        }
        char pe[CJ_JSON_PATH];
        cj_json_index(pe, path, i);
        cj_status st;
        if (dim > 0) {
            char what[48];
            snprintf(what, sizeof what, "an array of %d numbers", dim);
            st = fixed_array(c, e, pe, dim, v + i * per, what);
        } else {
            st = number_node(c, e, pe, v + i);
            if (!st) st = check_range(c, e, pe, r, lo, 0, v[i]);
        }
        if (st) {
            free(v);
            return st;
        }
    }
    *out = v;
    *count = n;
    return CJ_OK;
}

cj_status cj_json_numbers(const cj_json_doc *c, const cJSON *arr, const char *path, int dim,
                          cj_json_range r, double lo, size_t want, double **out, size_t *count) {
    return numbers(c, arr, path, dim, r, lo, 1, want, out, count);
}

cj_status cj_json_numbers_at_least(const cj_json_doc *c, const cJSON *arr, const char *path,
                                   int dim, cj_json_range r, double lo, size_t min, double **out,
                                   size_t *count) {
    return numbers(c, arr, path, dim, r, lo, min, 0, out, count);
}

/* An angle given as key_deg or key_rad (not both), converted to radians. */
cj_status cj_json_angle(const cj_json_doc *c, const cJSON *obj, const char *path, const char *key,
                        cj_json_range r, double lo_rad, double hi_rad, double *out) {
    char kd[64], kr[64];
    snprintf(kd, sizeof kd, "%s_deg", key);
    snprintf(kr, sizeof kr, "%s_rad", key);
    const cJSON *nd = cJSON_GetObjectItemCaseSensitive(obj, kd);
    const cJSON *nr = cJSON_GetObjectItemCaseSensitive(obj, kr);
    if (nd && nr)
        return cj_json_fail(c, nr, 1, CJ_ERR_PARSE, "%s: give either \"%s\" or \"%s\", not both",
                            path, kd, kr);
    if (nd) {
        double v = *out / DEG;
        CJ_JSON_TRY(cj_json_num(c, obj, path, kd, r, lo_rad / DEG, hi_rad / DEG, &v));
        *out = v * DEG;
    } else if (nr) {
        CJ_JSON_TRY(cj_json_num(c, obj, path, kr, r, lo_rad, hi_rad, out));
    }
    return CJ_OK;
}

cj_status cj_json_list(const cj_json_doc *c, const cJSON *arr, const char *p) {
    if (!cJSON_IsArray(arr))
        return cj_json_fail(c, arr, 0, CJ_ERR_PARSE, "%s must be an array, not %s", p,
                            cj_json_type_name(arr));
    return CJ_OK;
}

cj_status cj_json_resolve(const cj_json_doc *c, const char *base_dir, const cJSON *node,
                          const char *path, const char *rel, char *dst, size_t cap) {
    int w;
    if (rel[0] == '/' || !base_dir || !base_dir[0])
        w = snprintf(dst, cap, "%s", rel);
    else
        w = snprintf(dst, cap, "%s/%s", base_dir, rel);
    if (w < 0 || (size_t)w >= cap)
        return cj_json_fail(c, node, 0, CJ_ERR_RANGE, "%s: path too long", path);
    return CJ_OK;
}

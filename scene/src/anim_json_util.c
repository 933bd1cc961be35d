/* The animation document reader's helpers: a line for every JSON value (scanned in document
 * order, paired with cJSON's nodes in pre-order) and checked accessors. */
#include "anim_json_internal.h"

#include <math.h>
#include <stdint.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- line numbers: values scanned in document order, paired with cJSON's pre-order -------- */

static void push_scan(actx *c, int line) {
    if (c->nscan == c->capscan) {
        c->capscan = c->capscan ? 2 * c->capscan : 256;
        int *p = realloc(c->scan, sizeof *p * c->capscan);
        if (!p) return;
        c->scan = p;
    }
    c->scan[c->nscan++] = line;
}

static const char *scan_value(actx *c, const char *s, int *line, int depth);

/* Whitespace as cJSON reads it: every byte from 1 to 32 (so "\x12" between values too). */
static const char *skip_ws(const char *s, int *line) {
    while (*s && (unsigned char)*s <= 32) {
        if (*s == '\n') ++*line;
        ++s;
    }
    return s;
}

static const char *skip_string(const char *s) {
    ++s;
    while (*s && *s != '"') s += (*s == '\\' && s[1]) ? 2 : 1;
    return *s ? s + 1 : s;
}

/* Skips one whole value (deeper than the scan records), counting its lines. */
static const char *skip_value(const char *s, int *line) {
    int depth = 0;
    do {
        if (*s == '"') {
            s = skip_string(s);
            continue;
        }
        if (*s == '{' || *s == '[') ++depth;
        if (*s == '}' || *s == ']') --depth;
        if (*s == '\n') ++*line;
        if (*s) ++s;
    } while (*s && depth > 0);
    return s;
}

static const char *scan_value(actx *c, const char *s, int *line, int depth) {
    s = skip_ws(s, line);
    push_scan(c, *line);
    /* cJSON accepted the text, so it is nested at most CJSON_NESTING_LIMIT deep; the guard only
     * keeps a scan of any other text finite (it must consume the value, or the caller's loop
     * would never advance). */
    if (depth > CJSON_NESTING_LIMIT) return skip_value(s, line);
    if (*s == '{' || *s == '[') {
        const char close = *s == '{' ? '}' : ']';
        const int obj = *s == '{';
        ++s;
        for (;;) {
            s = skip_ws(s, line);
            if (*s == close || !*s) return *s ? s + 1 : s;
            if (obj) {
                s = skip_string(s);
                s = skip_ws(s, line);
                if (*s == ':') ++s;
            }
            s = scan_value(c, s, line, depth + 1);
            s = skip_ws(s, line);
            if (*s == ',') ++s;
        }
    }
    if (*s == '"') return skip_string(s);
    const char *start = s;
    while (*s && *s != ',' && *s != '}' && *s != ']' && (unsigned char)*s > 32) ++s;
    /* always move on (a stray closing bracket), so that no caller's loop can stall */
    return s == start && *s ? s + 1 : s;
}

static void pair_nodes(actx *c, const cJSON *n, size_t *k) {
    if (c->n == c->cap) {
        c->cap = c->cap ? 2 * c->cap : 256;
        const cJSON **pn = realloc(c->nodes, sizeof *pn * c->cap);
        int *pl = pn ? realloc(c->lines, sizeof *pl * c->cap) : NULL;
        if (pn) c->nodes = pn;
        if (!pn || !pl) return;
        c->lines = pl;
    }
    c->nodes[c->n] = n;
    c->lines[c->n] = *k < c->nscan ? c->scan[*k] : 0;
    ++c->n;
    ++*k;
    for (const cJSON *ch = n->child; ch; ch = ch->next) pair_nodes(c, ch, k);
}

/* Lines are looked up by node for every channel and emitter: the table is sorted by node
 * address once (aj_lines), so that each lookup is a binary search, not a walk through every
 * value of the document (quadratic for a document of many channels). */
typedef struct node_line {
    const cJSON *node;
    int line;
} node_line;

static int by_node(const void *a, const void *b) {
    const uintptr_t x = (uintptr_t)((const node_line *)a)->node,
                    y = (uintptr_t)((const node_line *)b)->node;
    return x < y ? -1 : x > y;
}

static void sort_lines(actx *c) {
    node_line *t = malloc(sizeof *t * (c->n ? c->n : 1));
    if (!t) {
        c->n = 0; /* no lines rather than a slow lookup */
        return;
    }
    for (size_t i = 0; i < c->n; ++i) t[i] = (node_line){c->nodes[i], c->lines[i]};
    qsort(t, c->n, sizeof *t, by_node);
    for (size_t i = 0; i < c->n; ++i) c->nodes[i] = t[i].node, c->lines[i] = t[i].line;
    free(t);
}

static int line_of(const actx *c, const cJSON *n) {
    size_t lo = 0, hi = c->n;
    while (lo < hi) {
        const size_t mid = lo + (hi - lo) / 2;
        if ((uintptr_t)c->nodes[mid] < (uintptr_t)n)
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo < c->n && c->nodes[lo] == n ? c->lines[lo] : 0;
}

int aj_line(const actx *c, const cJSON *n) {
    return line_of(c, n);
}

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
    d->channel_lines[d->channel_line_count++] = line_of(c, n);
    return CJ_OK;
}

cj_status aj_jfail(const actx *c, const cJSON *n, cj_status st, const char *fmt, ...) {
    char msg[512];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    return cj_fail(st, "%s:%d: %s", c->name, line_of(c, n), msg);
}

/* ---- checked accessors --------------------------------------------------------------------- */

cj_status aj_keys(const actx *c, const cJSON *obj, const char *path, const char *const *ok) {
    if (!cJSON_IsObject(obj)) return aj_jfail(c, obj, CJ_ERR_PARSE, "%s must be an object", path);
    for (const cJSON *k = obj->child; k; k = k->next) {
        int found = 0;
        for (const char *const *a = ok; *a; ++a) found |= !strcmp(*a, k->string);
        if (!found)
            return aj_jfail(c, k, CJ_ERR_PARSE, "%s.%s is not a known key", path, k->string);
        for (const cJSON *d = obj->child; d != k; d = d->next)
            if (!strcmp(d->string, k->string))
                return aj_jfail(c, k, CJ_ERR_PARSE, "%s.%s appears twice", path, k->string);
    }
    return CJ_OK;
}

cj_status aj_num(const actx *c, const cJSON *obj, const char *path, const char *key, double lo,
                 double *out) {
    const cJSON *n = cJSON_GetObjectItemCaseSensitive(obj, key);
    if (!n) return CJ_OK;
    if (!cJSON_IsNumber(n) || !isfinite(n->valuedouble))
        return aj_jfail(c, n, CJ_ERR_PARSE, "%s.%s must be a finite number", path, key);
    if (n->valuedouble < lo)
        return aj_jfail(c, n, CJ_ERR_RANGE, "%s.%s must be >= %g", path, key, lo);
    *out = n->valuedouble;
    return CJ_OK;
}

cj_status aj_num_in(const actx *c, const cJSON *obj, const char *path, const char *key, double lo,
                    double hi, int integer, double *out) {
    const cJSON *n = cJSON_GetObjectItemCaseSensitive(obj, key);
    if (!n) return CJ_OK;
    if (!cJSON_IsNumber(n) || !isfinite(n->valuedouble))
        return aj_jfail(c, n, CJ_ERR_PARSE, "%s.%s must be a finite number", path, key);
    const double v = n->valuedouble;
    if (!(v >= lo && v <= hi) || (integer && v != floor(v)))
        return aj_jfail(c, n, CJ_ERR_RANGE, "%s.%s = %g must be %s in [%g, %g]", path, key, v,
                        integer ? "an integer" : "a number", lo, hi);
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
        return aj_jfail(c, cJSON_GetObjectItemCaseSensitive(obj, key), CJ_ERR_RANGE,
                        "%s.%s has length %g, over the limit of %g", path, key, len, bound);
    memcpy(out, v, sizeof v);
    return CJ_OK;
}

/* An array of exactly `len` numbers (len 0: any length up to cap) into v; *count the length. */
cj_status aj_nums(const actx *c, const cJSON *n, const char *path, int len, double *v, size_t cap,
                  size_t *count) {
    if (!cJSON_IsArray(n)) return aj_jfail(c, n, CJ_ERR_PARSE, "%s must be an array", path);
    const size_t m = (size_t)cJSON_GetArraySize(n);
    if ((len && m != (size_t)len) || m > cap)
        return aj_jfail(c, n, CJ_ERR_PARSE, "%s must hold %s%zu numbers", path,
                        len ? "" : "at most ", len ? (size_t)len : cap);
    size_t i = 0;
    for (const cJSON *e = n->child; e; e = e->next, ++i) {
        if (!cJSON_IsNumber(e) || !isfinite(e->valuedouble))
            return aj_jfail(c, e, CJ_ERR_PARSE, "%s[%zu] must be a finite number", path, i);
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
    return aj_jfail(c, n, CJ_ERR_PARSE, "%s.%s must be one of: %s", path, key, list);
}

/* A list of keys' values: numbers (dim 1) or arrays of dim numbers; malloc'ed, key-major. */
cj_status aj_key_values(const actx *c, const cJSON *arr, const char *path, int *dim, size_t want,
                        double **out) {
    if (!cJSON_IsArray(arr) || cJSON_GetArraySize(arr) < 1)
        return aj_jfail(c, arr, CJ_ERR_PARSE, "%s must be a non-empty array", path);
    const size_t m = (size_t)cJSON_GetArraySize(arr);
    if (want && m != want)
        return aj_jfail(c, arr, CJ_ERR_PARSE, "%s has %zu entries, one per key (%zu) expected",
                        path, m, want);
    const int d = cJSON_IsArray(arr->child) ? cJSON_GetArraySize(arr->child) : 1;
    if (*dim && d != *dim)
        return aj_jfail(c, arr, CJ_ERR_PARSE, "%s entries must have %d numbers", path, *dim);
    if (d < 1 || d > 8) return aj_jfail(c, arr, CJ_ERR_PARSE, "%s entries hold 1..8 numbers", path);
    double *v = malloc(sizeof(double) * m * (size_t)d);
    if (!v) return cj_fail(CJ_ERR_NOMEM, "no memory for %s", path);
    size_t i = 0;
    for (const cJSON *e = arr->child; e; e = e->next, ++i) {
        char p[300];
        snprintf(p, sizeof p, "%s[%zu]", path, i);
        cj_status st;
        if (d == 1 && cJSON_IsNumber(e)) {
            st = isfinite(e->valuedouble) ? CJ_OK
                                          : aj_jfail(c, e, CJ_ERR_PARSE, "%s must be finite", p);
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

void aj_lines(actx *c, const char *text, const cJSON *root) {
    int line = 1;
    scan_value(c, text, &line, 0);
    size_t k = 0;
    pair_nodes(c, root, &k);
    sort_lines(c);
}

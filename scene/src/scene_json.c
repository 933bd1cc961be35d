/* The JSON scene reader: lines of values, checked accessors, entry points. cJSON keeps no
 * positions, so when a message needs a line a scanner walks the raw text once (cJSON accepted
 * it, so it is valid JSON) and records the line of every value in document order; a node's
 * position in a pre-order walk of the cJSON tree is its index in that list. */
#include "scene_json_internal.h"
#include "file_internal.h"
#include "json_depth_internal.h"

#include <assert.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- lines ---------------------------------------------------------------------------------- */

typedef struct scanner {
    const char *s;
    int line;
    int *vals; /* pairs (line, key_line) in document order */
    size_t n, cap;
    int ok;
} scanner;

static void skip_ws(scanner *sc) {
    while (*sc->s && (unsigned char)*sc->s <= 32) {
        if (*sc->s == '\n') sc->line++;
        sc->s++;
    }
}

static void skip_string(scanner *sc) {
    sc->s++; /* opening quote */
    while (*sc->s && *sc->s != '"') {
        if (*sc->s == '\\' && sc->s[1]) sc->s++;
        if (*sc->s == '\n') sc->line++;
        sc->s++;
    }
    if (*sc->s) sc->s++;
}

static void record(scanner *sc, int line, int key_line) {
    if (sc->n + 2 > sc->cap) {
        size_t nc = sc->cap ? 2 * sc->cap : 256;
        int *d = realloc(sc->vals, nc * sizeof *d);
        if (!d) {
            sc->ok = 0;
            return;
        }
        sc->vals = d;
        sc->cap = nc;
    }
    sc->vals[sc->n++] = line;
    sc->vals[sc->n++] = key_line;
}

/* The text is valid JSON (cJSON parsed it), so the scanner only has to find token starts. */
static void scan_value(scanner *sc, int key_line, int depth) {
    skip_ws(sc);
    record(sc, sc->line, key_line ? key_line : sc->line);
    char ch = *sc->s;
    if (ch == '{' || ch == '[') {
        const char close = ch == '{' ? '}' : ']';
        sc->s++;
        skip_ws(sc);
        if (*sc->s == close) {
            sc->s++;
            return;
        }
        while (*sc->s && sc->ok && depth < 4096) {
            skip_ws(sc);
            int kl = 0;
            if (close == '}') {
                kl = sc->line;
                skip_string(sc);
                skip_ws(sc);
                if (*sc->s == ':') sc->s++;
            }
            scan_value(sc, kl, depth + 1);
            skip_ws(sc);
            if (*sc->s == ',') {
                sc->s++;
                continue;
            }
            if (*sc->s == close) sc->s++;
            return;
        }
    } else if (ch == '"') {
        skip_string(sc);
    } else {
        while (*sc->s && *sc->s != ',' && *sc->s != ']' && *sc->s != '}' &&
               (unsigned char)*sc->s > 32)
            sc->s++;
    }
}

/* Pre-order index of `target` below (and including) the sibling list starting at n, counting
 * from *k; 1 when found. */
static int preorder_index(const cJSON *n, const cJSON *target, size_t *k) {
    for (; n; n = n->next) {
        if (n == target) return 1;
        (*k)++;
        if (n->child && preorder_index(n->child, target, k)) return 1;
    }
    return 0;
}

/* The (line, key line) pair of node, scanning the text on the first request; NULL if unknown. */
static const int *node_lines(const jctx *c, const cJSON *node) {
    jlines *l = c->lines;
    if (!l || !node) return NULL;
    if (!l->scanned) {
        scanner sc = {l->text, 1, NULL, 0, 0, 1};
        if ((unsigned char)sc.s[0] == 0xEF && (unsigned char)sc.s[1] == 0xBB &&
            (unsigned char)sc.s[2] == 0xBF)
            sc.s += 3;
        scan_value(&sc, 0, 0);
        l->vals = sc.vals;
        l->n = sc.n / 2;
        l->scanned = sc.ok ? 1 : -1;
    }
    if (l->scanned < 0) return NULL;
    size_t k = 0;
    if (!preorder_index(l->root, node, &k) || k >= l->n) return NULL;
    return l->vals + 2 * k;
}

int cj_json_line_(const jctx *c, const cJSON *node) {
    const int *v = node_lines(c, node);
    return v ? v[0] : 0;
}

int cj_json_key_line_(const jctx *c, const cJSON *node) {
    const int *v = node_lines(c, node);
    return v ? v[1] : 0;
}

/* ---- messages ------------------------------------------------------------------------------- */

cj_status cj_json_fail_(const jctx *c, const cJSON *node, int at_key, cj_status st, const char *fmt,
                        ...) {
    char msg[768];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    int line = at_key ? cj_json_key_line_(c, node) : cj_json_line_(c, node);
    return cj_fail(st, "%s:%d: %s", c->name, line, msg);
}

cj_status cj_json_relabel_(const jctx *c, const cJSON *node, cj_status st) {
    char msg[768];
    snprintf(msg, sizeof msg, "%s", cj_last_error());
    return cj_fail(st, "%s:%d: %s", c->name, cj_json_line_(c, node), msg);
}

void cj_json_join_(char *dst, const char *path, const char *key) {
    if (path[0])
        snprintf(dst, JPATH, "%s.%s", path, key);
    else
        snprintf(dst, JPATH, "%s", key);
}

void cj_json_index_(char *dst, const char *path, size_t i) {
    snprintf(dst, JPATH, "%s[%zu]", path, i);
}

/* ---- checked accessors ---------------------------------------------------------------------- */

static const char *type_name(const cJSON *n) {
    if (cJSON_IsObject(n)) return "an object";
    if (cJSON_IsArray(n)) return "an array";
    if (cJSON_IsString(n)) return "a string";
    if (cJSON_IsNumber(n)) return "a number";
    if (cJSON_IsBool(n)) return "a boolean";
    return "null";
}

cj_status cj_json_object_(const jctx *c, const cJSON *obj, const char *path,
                          const char *const *allowed) {
    if (!cJSON_IsObject(obj))
        return cj_json_fail_(c, obj, 0, CJ_ERR_PARSE, "%s must be an object, not %s",
                             path[0] ? path : "document", type_name(obj));
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
            char p[JPATH];
            cj_json_join_(p, path, m->string);
            return cj_json_fail_(c, m, 1, CJ_ERR_PARSE,
                                 "%s is not a known key (expected one of: %s)", p, list);
        }
        for (const cJSON *o = obj->child; o != m; o = o->next)
            if (!strcmp(o->string, m->string)) {
                char p[JPATH];
                cj_json_join_(p, path, m->string);
                return cj_json_fail_(c, m, 1, CJ_ERR_PARSE, "%s is given twice (line %d)", p,
                                     cj_json_key_line_(c, o));
            }
    }
    return CJ_OK;
}

cj_status cj_json_require_(const jctx *c, const cJSON *obj, const char *path, const char *key,
                           const cJSON **out) {
    const cJSON *m = cJSON_GetObjectItemCaseSensitive(obj, key);
    if (!m)
        return cj_json_fail_(c, obj, 0, CJ_ERR_PARSE, "%s: missing key \"%s\"",
                             path[0] ? path : "document", key);
    *out = m;
    return CJ_OK;
}

static cj_status check_range(const jctx *c, const cJSON *n, const char *p, jrange r, double lo,
                             double hi, double v) {
    int ok = 1;
    char what[64] = "";
    switch (r) {
    case R_ANY:
        break;
    case R_GE:
        ok = v >= lo;
        snprintf(what, sizeof what, ">= %g", lo);
        break;
    case R_GT:
        ok = v > lo;
        snprintf(what, sizeof what, "> %g", lo);
        break;
    case R_LT:
        ok = v < hi;
        snprintf(what, sizeof what, "< %g", hi);
        break;
    case R_IN:
        ok = v >= lo && v <= hi;
        snprintf(what, sizeof what, "in [%g, %g]", lo, hi);
        break;
    case R_OPEN:
        ok = v > lo && v < hi;
        snprintf(what, sizeof what, "in (%g, %g)", lo, hi);
        break;
    }
    if (!ok) return cj_json_fail_(c, n, 0, CJ_ERR_RANGE, "%s must be %s", p, what);
    return CJ_OK;
}

static cj_status number_node(const jctx *c, const cJSON *n, const char *p, double *v) {
    if (!cJSON_IsNumber(n))
        return cj_json_fail_(c, n, 0, CJ_ERR_PARSE, "%s must be a number, not %s", p, type_name(n));
    if (!isfinite(n->valuedouble))
        return cj_json_fail_(c, n, 0, CJ_ERR_NONFINITE, "%s is not finite", p);
    *v = n->valuedouble;
    return CJ_OK;
}

cj_status cj_json_num_(const jctx *c, const cJSON *obj, const char *path, const char *key, jrange r,
                       double lo, double hi, double *out) {
    const cJSON *n = cJSON_GetObjectItemCaseSensitive(obj, key);
    if (!n) return CJ_OK;
    char p[JPATH];
    cj_json_join_(p, path, key);
    double v;
    cj_status st = number_node(c, n, p, &v);
    if (!st) st = check_range(c, n, p, r, lo, hi, v);
    if (!st) *out = v;
    return st;
}

cj_status cj_json_int_(const jctx *c, const cJSON *obj, const char *path, const char *key,
                       double lo, double hi, int *out) {
    const cJSON *n = cJSON_GetObjectItemCaseSensitive(obj, key);
    if (!n) return CJ_OK;
    char p[JPATH];
    cj_json_join_(p, path, key);
    double v;
    cj_status st = number_node(c, n, p, &v);
    if (st) return st;
    if (v != floor(v)) return cj_json_fail_(c, n, 0, CJ_ERR_PARSE, "%s must be an integer", p);
    st = check_range(c, n, p, R_IN, lo, hi, v);
    if (!st) *out = (int)v;
    return st;
}

cj_status cj_json_bool_(const jctx *c, const cJSON *obj, const char *path, const char *key,
                        int *out) {
    const cJSON *n = cJSON_GetObjectItemCaseSensitive(obj, key);
    if (!n) return CJ_OK;
    if (!cJSON_IsBool(n)) {
        char p[JPATH];
        cj_json_join_(p, path, key);
        return cj_json_fail_(c, n, 0, CJ_ERR_PARSE, "%s must be true or false, not %s", p,
                             type_name(n));
    }
    *out = cJSON_IsTrue(n) ? 1 : 0;
    return CJ_OK;
}

/* A fixed-length array of numbers at node n. */
static cj_status fixed_array(const jctx *c, const cJSON *n, const char *p, int len, double *v,
                             const char *what) {
    if (!cJSON_IsArray(n) || cJSON_GetArraySize(n) != len)
        return cj_json_fail_(c, n, 0, CJ_ERR_PARSE, "%s must be %s", p, what);
    int k = 0;
    for (const cJSON *e = n->child; e; e = e->next, ++k) {
        char pe[JPATH];
        cj_json_index_(pe, p, (size_t)k);
        cj_status st = number_node(c, e, pe, &v[k]);
        if (st) return st;
    }
    return CJ_OK;
}

cj_status cj_json_vec3_(const jctx *c, const cJSON *obj, const char *path, const char *key,
                        cj_vec3 *out) {
    const cJSON *n = cJSON_GetObjectItemCaseSensitive(obj, key);
    if (!n) return CJ_OK;
    char p[JPATH];
    cj_json_join_(p, path, key);
    double v[3];
    cj_status st = fixed_array(c, n, p, 3, v, "an array of 3 numbers");
    if (!st) *out = cj_v3(v[0], v[1], v[2]);
    return st;
}

cj_status cj_json_rgb_(const jctx *c, const cJSON *obj, const char *path, const char *key,
                       double max, cj_rgb *out) {
    const cJSON *n = cJSON_GetObjectItemCaseSensitive(obj, key);
    if (!n) return CJ_OK;
    char p[JPATH];
    cj_json_join_(p, path, key);
    double v[3];
    cj_status st = fixed_array(c, n, p, 3, v, "an array of 3 numbers (linear RGB)");
    if (st) return st;
    const cJSON *e = n->child;
    for (int k = 0; k < 3; ++k, e = e->next) {
        char pe[JPATH];
        cj_json_index_(pe, p, (size_t)k);
        st = max >= 0 ? check_range(c, e, pe, R_IN, 0, max, v[k])
                      : check_range(c, e, pe, R_GE, 0, 0, v[k]);
        if (st) return st;
    }
    *out = cj_rgb_make(v[0], v[1], v[2]);
    return CJ_OK;
}

cj_status cj_json_string_(const jctx *c, const cJSON *obj, const char *path, const char *key,
                          const char **out) {
    const cJSON *n = cJSON_GetObjectItemCaseSensitive(obj, key);
    if (!n) return CJ_OK;
    if (!cJSON_IsString(n)) {
        char p[JPATH];
        cj_json_join_(p, path, key);
        return cj_json_fail_(c, n, 0, CJ_ERR_PARSE, "%s must be a string, not %s", p, type_name(n));
    }
    *out = n->valuestring;
    return CJ_OK;
}

cj_status cj_json_enum_(const jctx *c, const cJSON *obj, const char *path, const char *key,
                        const char *const *names, int *out) {
    const char *s = NULL;
    cj_status st = cj_json_string_(c, obj, path, key, &s);
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
    char p[JPATH];
    cj_json_join_(p, path, key);
    return cj_json_fail_(c, cJSON_GetObjectItemCaseSensitive(obj, key), 0, CJ_ERR_PARSE,
                         "%s \"%s\" is not one of %s", p, s, list);
}

cj_status cj_json_numbers_(const jctx *c, const cJSON *arr, const char *path, int dim, jrange r,
                           double lo, size_t want, double **out, size_t *count) {
    if (!cJSON_IsArray(arr))
        return cj_json_fail_(c, arr, 0, CJ_ERR_PARSE, "%s must be an array, not %s", path,
                             type_name(arr));
    size_t n = (size_t)cJSON_GetArraySize(arr);
    if (n == 0) return cj_json_fail_(c, arr, 0, CJ_ERR_PARSE, "%s must not be empty", path);
    if (want && n != want)
        return cj_json_fail_(c, arr, 0, CJ_ERR_PARSE, "%s must have %zu entries, not %zu", path,
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
                   (r == R_ANY || (r == R_GE && e->valuedouble >= lo) ||
                    (r == R_GT && e->valuedouble > lo))) {
            v[i] = e->valuedouble;
            continue;
        }
        char pe[JPATH];
        cj_json_index_(pe, path, i);
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

cj_status cj_json_resolve_(const jctx *c, const cJSON *node, const char *path, const char *rel,
                           char *dst, size_t cap) {
    int w;
    if (rel[0] == '/' || !c->base_dir[0])
        w = snprintf(dst, cap, "%s", rel);
    else
        w = snprintf(dst, cap, "%s/%s", c->base_dir, rel);
    if (w < 0 || (size_t)w >= cap)
        return cj_json_fail_(c, node, 0, CJ_ERR_RANGE, "%s: path too long", path);
    return CJ_OK;
}

/* ---- entry points --------------------------------------------------------------------------- */

static const char *const TOP_KEYS[] = {"camera",    "settings",   "lights",  "textures",
                                       "materials", "geometries", "objects", NULL};

static cj_status read_document(jctx *c, const cJSON *root) {
    cj_status st = cj_json_object_(c, root, "", TOP_KEYS);
    if (st) return st;
    const cJSON *objects;
    st = cj_json_require_(c, root, "", "objects", &objects);
    if (st) return st;
    const cJSON *n;
    if ((n = cJSON_GetObjectItemCaseSensitive(root, "camera")) && (st = cj_json_read_camera_(c, n)))
        return st;
    if ((n = cJSON_GetObjectItemCaseSensitive(root, "settings")) &&
        (st = cj_json_read_settings_(c, n)))
        return st;
    if ((n = cJSON_GetObjectItemCaseSensitive(root, "lights")) && (st = cj_json_read_lights_(c, n)))
        return st;
    if ((n = cJSON_GetObjectItemCaseSensitive(root, "textures")) &&
        (st = cj_json_read_textures_(c, n)))
        return st;
    if ((n = cJSON_GetObjectItemCaseSensitive(root, "materials")) &&
        (st = cj_json_read_materials_(c, n)))
        return st;
    if ((n = cJSON_GetObjectItemCaseSensitive(root, "geometries"))) {
        if (!cJSON_IsArray(n))
            return cj_json_fail_(c, n, 0, CJ_ERR_PARSE, "geometries must be an array, not %s",
                                 type_name(n));
        size_t k = (size_t)cJSON_GetArraySize(n);
        c->geometries = n;
        c->geometry_index = malloc((k ? k : 1) * sizeof(int));
        if (!c->geometry_index) return cj_fail(CJ_ERR_NOMEM, "%s: out of memory", c->name);
        for (size_t i = 0; i < k; ++i) c->geometry_index[i] = -1;
        /* Check every entry now (also the unused ones) so errors come in document order. */
        size_t i = 0;
        for (const cJSON *g = n->child; g; g = g->next, ++i) {
            char p[JPATH];
            cj_json_index_(p, "geometries", i);
            const char *name = NULL;
            if (!cJSON_IsObject(g))
                return cj_json_fail_(c, g, 0, CJ_ERR_PARSE, "%s must be an object, not %s", p,
                                     type_name(g));
            if ((st = cj_json_string_(c, g, p, "name", &name))) return st;
            if (!name) return cj_json_fail_(c, g, 0, CJ_ERR_PARSE, "%s: missing key \"name\"", p);
            size_t j = 0;
            for (const cJSON *o = n->child; o != g; o = o->next, ++j) {
                const cJSON *on = cJSON_GetObjectItemCaseSensitive(o, "name");
                if (!strcmp(on->valuestring, name))
                    return cj_json_fail_(c, cJSON_GetObjectItemCaseSensitive(g, "name"), 0,
                                         CJ_ERR_PARSE, "%s.name \"%s\" is already geometries[%zu]",
                                         p, name, j);
            }
            if ((st = cj_json_read_geometry_(c, g, p, &c->geometry_index[i]))) return st;
        }
    }
    st = cj_json_read_objects_(c, objects);
    if (st) return st;
    st = cj_scene_check(c->scene);
    if (st) {
        char msg[768];
        snprintf(msg, sizeof msg, "%s", cj_last_error());
        return cj_fail(st, "%s: %s", c->name, msg);
    }
    return CJ_OK;
}

cj_status cj_scene_parse_json_ex(const char *text, const char *name, const char *base_dir,
                                 const cj_scene_json_options *options, const cj_allocator *alloc,
                                 cj_scene **out) {
    assert(text && out);
    if (!name) name = "<scene>";
    const char *end = NULL;
    cJSON *root = cJSON_ParseWithOpts(text, &end, 1);
    if (!root) {
        if (!end) return cj_fail(CJ_ERR_NOMEM, "%s: out of memory parsing JSON", name);
        int line = 1, col = 1;
        for (const char *p = text; p < end && *p; ++p) {
            if (*p == '\n')
                line++, col = 1;
            else
                col++;
        }
        if (cj_json_depth_at_(text, end) >= CJSON_NESTING_LIMIT)
            return cj_fail(CJ_ERR_PARSE,
                           "%s:%d:%d: JSON nested deeper than %d levels (the reader's limit)", name,
                           line, col, CJSON_NESTING_LIMIT);
        return cj_fail(CJ_ERR_PARSE, "%s:%d:%d: JSON syntax error (line %d, column %d)", name, line,
                       col, line, col);
    }
    jctx c;
    memset(&c, 0, sizeof c);
    c.name = name;
    c.base_dir = base_dir ? base_dir : "";
    c.teapot_path = options ? options->teapot_path : NULL;
    c.default_material = -1;
    jlines lines = {text, root, NULL, 0, 0};
    c.lines = &lines;
    cj_status st = cj_scene_create(alloc, &c.scene);
    if (!st) st = read_document(&c, root);
    if (st) {
        cj_scene_destroy(c.scene);
    } else {
        *out = c.scene;
    }
    free(lines.vals);
    free(c.geometry_index);
    cJSON_Delete(root);
    return st;
}

cj_status cj_scene_parse_json(const char *text, const char *name, const char *base_dir,
                              const cj_allocator *alloc, cj_scene **out) {
    return cj_scene_parse_json_ex(text, name, base_dir, NULL, alloc, out);
}

cj_status cj_scene_load_json_ex(const char *path, const cj_scene_json_options *options,
                                const cj_allocator *alloc, cj_scene **out) {
    assert(path && out);
    char *text = NULL;
    size_t len = 0;
    cj_status rs = cj_file_read_all(path, CJ_FILE_MAX_BYTES, "scene", &text, &len);
    if (rs) return rs;
    if (strlen(text) != len) {
        free(text);
        return cj_fail(CJ_ERR_PARSE, "%s: the file contains a NUL byte (not JSON text)", path);
    }
    char dir[4096];
    const char *slash = strrchr(path, '/');
    if (slash) {
        size_t k = (size_t)(slash - path);
        if (k >= sizeof dir) {
            free(text);
            return cj_fail(CJ_ERR_RANGE, "'%s': path too long", path);
        }
        memcpy(dir, path, k);
        dir[k] = '\0';
        if (k == 0) strcpy(dir, "/");
    } else {
        dir[0] = '\0';
    }
    cj_status st = cj_scene_parse_json_ex(text, path, dir, options, alloc, out);
    free(text);
    return st;
}

cj_status cj_scene_load_json(const char *path, const cj_allocator *alloc, cj_scene **out) {
    return cj_scene_load_json_ex(path, NULL, alloc, out);
}

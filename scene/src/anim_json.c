/* Animation documents: channels, paths, gravity, colliders and a cloth read from JSON, every
 * key checked, errors as "file:line: path message". */
#include "casteljau/anim_json.h"

#include "casteljau/catmull_rom.h"
#include "error_internal.h"

#include <cjson/cJSON.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define PI_ 3.14159265358979323846

/* ---- line numbers: values scanned in document order, paired with cJSON's pre-order -------- */

typedef struct actx {
    const char *name, *base_dir;
    const cJSON **nodes;
    int *lines;
    size_t n, cap;
    int *scan; /* lines of values in document order */
    size_t nscan, capscan;
} actx;

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

static const char *skip_ws(const char *s, int *line) {
    while (*s == ' ' || *s == '\t' || *s == '\n' || *s == '\r') {
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

static const char *scan_value(actx *c, const char *s, int *line, int depth) {
    s = skip_ws(s, line);
    push_scan(c, *line);
    if (depth > 200) return s;
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
    while (*s && *s != ',' && *s != '}' && *s != ']' && *s != ' ' && *s != '\n' && *s != '\t' &&
           *s != '\r')
        ++s;
    return s;
}

static void pair(actx *c, const cJSON *n, size_t *k) {
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
    for (const cJSON *ch = n->child; ch; ch = ch->next) pair(c, ch, k);
}

static int line_of(const actx *c, const cJSON *n) {
    for (size_t i = 0; i < c->n; ++i)
        if (c->nodes[i] == n) return c->lines[i];
    return 0;
}

static cj_status jfail(const actx *c, const cJSON *n, cj_status st, const char *fmt, ...)
    CJ_PRINTF(4, 5);
static cj_status jfail(const actx *c, const cJSON *n, cj_status st, const char *fmt, ...) {
    char msg[512];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    return cj_fail(st, "%s:%d: %s", c->name, line_of(c, n), msg);
}

/* ---- checked accessors --------------------------------------------------------------------- */

static cj_status keys(const actx *c, const cJSON *obj, const char *path, const char *const *ok) {
    if (!cJSON_IsObject(obj)) return jfail(c, obj, CJ_ERR_PARSE, "%s must be an object", path);
    for (const cJSON *k = obj->child; k; k = k->next) {
        int found = 0;
        for (const char *const *a = ok; *a; ++a) found |= !strcmp(*a, k->string);
        if (!found) return jfail(c, k, CJ_ERR_PARSE, "%s.%s is not a known key", path, k->string);
        for (const cJSON *d = obj->child; d != k; d = d->next)
            if (!strcmp(d->string, k->string))
                return jfail(c, k, CJ_ERR_PARSE, "%s.%s appears twice", path, k->string);
    }
    return CJ_OK;
}

static cj_status num(const actx *c, const cJSON *obj, const char *path, const char *key, double lo,
                     double *out) {
    const cJSON *n = cJSON_GetObjectItemCaseSensitive(obj, key);
    if (!n) return CJ_OK;
    if (!cJSON_IsNumber(n) || !isfinite(n->valuedouble))
        return jfail(c, n, CJ_ERR_PARSE, "%s.%s must be a finite number", path, key);
    if (n->valuedouble < lo) return jfail(c, n, CJ_ERR_RANGE, "%s.%s must be >= %g", path, key, lo);
    *out = n->valuedouble;
    return CJ_OK;
}

/* An array of exactly `len` numbers (len 0: any length up to cap) into v; *count the length. */
static cj_status nums(const actx *c, const cJSON *n, const char *path, int len, double *v,
                      size_t cap, size_t *count) {
    if (!cJSON_IsArray(n)) return jfail(c, n, CJ_ERR_PARSE, "%s must be an array", path);
    const size_t m = (size_t)cJSON_GetArraySize(n);
    if ((len && m != (size_t)len) || m > cap)
        return jfail(c, n, CJ_ERR_PARSE, "%s must hold %s%zu numbers", path, len ? "" : "at most ",
                     len ? (size_t)len : cap);
    size_t i = 0;
    for (const cJSON *e = n->child; e; e = e->next, ++i) {
        if (!cJSON_IsNumber(e) || !isfinite(e->valuedouble))
            return jfail(c, e, CJ_ERR_PARSE, "%s[%zu] must be a finite number", path, i);
        v[i] = e->valuedouble;
    }
    if (count) *count = m;
    return CJ_OK;
}

static cj_status vec3(const actx *c, const cJSON *obj, const char *path, const char *key,
                      double *out) {
    const cJSON *n = cJSON_GetObjectItemCaseSensitive(obj, key);
    if (!n) return CJ_OK;
    char p[300];
    snprintf(p, sizeof p, "%s.%s", path, key);
    return nums(c, n, p, 3, out, 3, NULL);
}

static cj_status pick(const actx *c, const cJSON *obj, const char *path, const char *key,
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
    return jfail(c, n, CJ_ERR_PARSE, "%s.%s must be one of: %s", path, key, list);
}

/* A list of keys' values: numbers (dim 1) or arrays of dim numbers; malloc'ed, key-major. */
static cj_status key_values(const actx *c, const cJSON *arr, const char *path, int *dim,
                            size_t want, double **out) {
    if (!cJSON_IsArray(arr) || cJSON_GetArraySize(arr) < 1)
        return jfail(c, arr, CJ_ERR_PARSE, "%s must be a non-empty array", path);
    const size_t m = (size_t)cJSON_GetArraySize(arr);
    if (want && m != want)
        return jfail(c, arr, CJ_ERR_PARSE, "%s has %zu entries, one per key (%zu) expected", path,
                     m, want);
    const int d = cJSON_IsArray(arr->child) ? cJSON_GetArraySize(arr->child) : 1;
    if (*dim && d != *dim)
        return jfail(c, arr, CJ_ERR_PARSE, "%s entries must have %d numbers", path, *dim);
    if (d < 1 || d > 8) return jfail(c, arr, CJ_ERR_PARSE, "%s entries hold 1..8 numbers", path);
    double *v = malloc(sizeof(double) * m * (size_t)d);
    if (!v) return cj_fail(CJ_ERR_NOMEM, "no memory for %s", path);
    size_t i = 0;
    for (const cJSON *e = arr->child; e; e = e->next, ++i) {
        char p[300];
        snprintf(p, sizeof p, "%s[%zu]", path, i);
        cj_status st;
        if (d == 1 && cJSON_IsNumber(e)) {
            st = isfinite(e->valuedouble) ? CJ_OK
                                          : jfail(c, e, CJ_ERR_PARSE, "%s must be finite", p);
            v[i] = e->valuedouble;
        } else {
            st = nums(c, e, p, d, v + i * (size_t)d, (size_t)d, NULL);
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

/* ---- channels ----------------------------------------------------------------------------- */

static const char *const INTERP[] = {
    "step",    "linear",      "catmull_rom", "centripetal", "kochanek_bartels",
    "hermite", "bezier_auto", "gltf_cubic",  "squad",       NULL};
static const char *const KINDS[] = {"vector", "quaternion", "euler", NULL};
static const char *const ORDERS[] = {"xyz", "xzy", "yxz", "yzx", "zxy", "zyx", NULL};
static const char *const EASES[] = {"linear", "smoothstep", "sine", "trapezoid", NULL};

static cj_status read_path_channel(actx *c, cj_anim *anim, const cJSON *ch, const char *path,
                                   const char *target) {
    static const char *const PK[] = {"points", "closed", "spline", "tension", NULL};
    const cJSON *pj = cJSON_GetObjectItemCaseSensitive(ch, "path");
    char pp[300];
    snprintf(pp, sizeof pp, "%s.path", path);
    cj_status st = keys(c, pj, pp, PK);
    if (st) return st;
    const cJSON *pts = cJSON_GetObjectItemCaseSensitive(pj, "points");
    if (!pts) return jfail(c, pj, CJ_ERR_PARSE, "%s needs \"points\"", pp);
    int dim = 3, spline = 0;
    double *p = NULL, tension = 0.5;
    snprintf(pp, sizeof pp, "%s.path.points", path);
    if ((st = key_values(c, pts, pp, &dim, 0, &p))) return st;
    const size_t n = (size_t)cJSON_GetArraySize(pts);
    const cJSON *cl = cJSON_GetObjectItemCaseSensitive(pj, "closed");
    if (cl && !cJSON_IsBool(cl))
        st = jfail(c, cl, CJ_ERR_PARSE, "%s.path.closed must be true or false", path);
    static const char *const SPL[] = {"catmull_rom", "centripetal", NULL};
    snprintf(pp, sizeof pp, "%s.path", path);
    if (!st) st = pick(c, pj, pp, "spline", SPL, &spline);
    if (!st) st = num(c, pj, pp, "tension", -1e300, &tension);
    double start = 0, dur = 0, accel = 0.25;
    int ease = 0;
    if (!st) st = num(c, ch, path, "start", 0, &start);
    if (!st) st = num(c, ch, path, "duration", 0, &dur);
    if (!st && !(dur > 0))
        st = jfail(c, ch, CJ_ERR_RANGE, "%s.duration must be given and > 0", path);
    if (!st) st = pick(c, ch, path, "ease", EASES, &ease);
    if (!st) st = num(c, ch, path, "accel", 0, &accel);
    double *segs = NULL;
    cj_path *motion = NULL;
    if (!st) {
        cj_spline_options o = cj_spline_defaults();
        o.kind = spline ? CJ_SPLINE_CENTRIPETAL : CJ_SPLINE_CATMULL_ROM;
        o.tension = tension;
        o.closed = cl && cJSON_IsTrue(cl);
        const size_t ns = cj_spline_segment_count(n, o.closed);
        segs = malloc(sizeof(double) * 4 * 3 * (ns ? ns : 1));
        if (!segs) st = cj_fail(CJ_ERR_NOMEM, "no memory for a path");
        if (!st) st = cj_catmull_rom(p, n, dim, &o, segs, ns, NULL, NULL);
        if (!st) st = cj_path_create(segs, ns, dim, 1e-10, NULL, &motion);
        if (!st) st = cj_anim_add_path(anim, target, motion, start, dur, (cj_ease)ease, accel);
        if (st) {
            cj_path_destroy(motion);
            char msg[300];
            snprintf(msg, sizeof msg, "%s", cj_last_error());
            st = jfail(c, pj, st, "%s.path: %s", path, msg);
        }
    }
    free(segs);
    free(p);
    return st;
}

static cj_status read_channel(actx *c, cj_anim *anim, const cJSON *ch, const char *path) {
    static const char *const CK[] = {
        "target",  "type",       "interpolation", "times",       "values",  "tangents",
        "tension", "continuity", "bias",          "euler_order", "degrees", "path",
        "start",   "duration",   "ease",          "accel",       NULL};
    cj_status st = keys(c, ch, path, CK);
    if (st) return st;
    const cJSON *tg = cJSON_GetObjectItemCaseSensitive(ch, "target");
    if (!cJSON_IsString(tg))
        return jfail(c, tg ? tg : ch, CJ_ERR_PARSE, "%s.target must be a string", path);
    if (cJSON_GetObjectItemCaseSensitive(ch, "path"))
        return read_path_channel(c, anim, ch, path, tg->valuestring);
    int kind = 0, interp = 1, order = 0;
    if ((st = pick(c, ch, path, "type", KINDS, &kind))) return st;
    if ((st = pick(c, ch, path, "interpolation", INTERP, &interp))) return st;
    if ((st = pick(c, ch, path, "euler_order", ORDERS, &order))) return st;
    const cJSON *tj = cJSON_GetObjectItemCaseSensitive(ch, "times");
    const cJSON *vj = cJSON_GetObjectItemCaseSensitive(ch, "values");
    if (!tj || !vj) return jfail(c, ch, CJ_ERR_PARSE, "%s needs \"times\" and \"values\"", path);
    char pp[300];
    snprintf(pp, sizeof pp, "%s.times", path);
    int one = 1;
    double *t = NULL, *v = NULL, *tan = NULL;
    if ((st = key_values(c, tj, pp, &one, 0, &t))) return st;
    const size_t n = (size_t)cJSON_GetArraySize(tj);
    int dim = kind == 1 ? 4 : kind == 2 ? 3 : 0;
    snprintf(pp, sizeof pp, "%s.values", path);
    st = key_values(c, vj, pp, &dim, n, &v);
    cj_channel_desc d = cj_channel_desc_make((cj_channel_kind)kind, (cj_interp)interp, dim);
    if (!st) st = num(c, ch, path, "tension", -1e300, &d.tension);
    if (!st) st = num(c, ch, path, "continuity", -1e300, &d.continuity);
    if (!st) st = num(c, ch, path, "bias", -1e300, &d.bias);
    const cJSON *deg = cJSON_GetObjectItemCaseSensitive(ch, "degrees");
    if (!st && deg && !cJSON_IsBool(deg))
        st = jfail(c, deg, CJ_ERR_PARSE, "%s.degrees must be true or false", path);
    if (!st && kind == 2 && deg && cJSON_IsTrue(deg))
        for (size_t i = 0; i < 3 * n; ++i) v[i] *= PI_ / 180.0;
    const cJSON *tn = cJSON_GetObjectItemCaseSensitive(ch, "tangents");
    if (!st && tn) {
        snprintf(pp, sizeof pp, "%s.tangents", path);
        if (interp == CJ_INTERP_GLTF_CUBIC) {
            /* [in, out] per key: flatten the pairs */
            int d2 = 0;
            tan = malloc(sizeof(double) * 2 * n * (size_t)(dim ? dim : 1));
            if (!tan) st = cj_fail(CJ_ERR_NOMEM, "no memory for tangents");
            size_t i = 0;
            if (!st && (!cJSON_IsArray(tn) || (size_t)cJSON_GetArraySize(tn) != n))
                st = jfail(c, tn, CJ_ERR_PARSE, "%s must hold [in, out] per key", pp);
            for (const cJSON *e = tn ? tn->child : NULL; !st && e; e = e->next, ++i) {
                double *pair_v = NULL;
                char pe[320];
                snprintf(pe, sizeof pe, "%s[%zu]", pp, i);
                d2 = dim;
                st = key_values(c, e, pe, &d2, 2, &pair_v);
                if (!st)
                    memcpy(tan + 2 * i * (size_t)dim, pair_v, sizeof(double) * 2 * (size_t)dim);
                free(pair_v);
            }
        } else {
            int d2 = dim;
            st = key_values(c, tn, pp, &d2, n, &tan);
        }
    }
    if (!st) {
        d.count = n;
        d.times = t;
        d.values = v;
        d.tangents = tan;
        d.euler_order = (cj_euler_order)order;
        st = cj_anim_add(anim, tg->valuestring, &d);
        if (st) {
            char msg[400];
            snprintf(msg, sizeof msg, "%s", cj_last_error());
            st = jfail(c, ch, st, "%s: %s", path, msg);
        }
    }
    free(t);
    free(v);
    free(tan);
    return st;
}

/* ---- the document ------------------------------------------------------------------------- */

static const char *const INTEGRATORS[] = {"explicit_euler", "symplectic_euler", "rk4",
                                          "implicit_euler", NULL};

static cj_status read_colliders(actx *c, const cJSON *cj, cj_sphere_collider *sph, size_t *nsph,
                                cj_plane_collider *pl, size_t *npl) {
    static const char *const K[] = {"spheres", "planes", NULL};
    static const char *const SK[] = {"center", "radius", "friction", NULL};
    static const char *const PK[] = {"normal", "offset", "friction", NULL};
    cj_status st = keys(c, cj, "colliders", K);
    if (st) return st;
    const cJSON *s = cJSON_GetObjectItemCaseSensitive(cj, "spheres");
    const cJSON *p = cJSON_GetObjectItemCaseSensitive(cj, "planes");
    size_t i = 0;
    for (const cJSON *e = s ? s->child : NULL; e; e = e->next, ++i) {
        char path[64];
        snprintf(path, sizeof path, "colliders.spheres[%zu]", i);
        if (i >= 8) return jfail(c, e, CJ_ERR_PARSE, "at most 8 spheres");
        sph[i] = (cj_sphere_collider){{0, 0, 0}, 1, 0};
        if ((st = keys(c, e, path, SK)) || (st = vec3(c, e, path, "center", sph[i].center)) ||
            (st = num(c, e, path, "radius", 0, &sph[i].radius)) ||
            (st = num(c, e, path, "friction", 0, &sph[i].friction)))
            return st;
    }
    *nsph = i;
    i = 0;
    for (const cJSON *e = p ? p->child : NULL; e; e = e->next, ++i) {
        char path[64];
        snprintf(path, sizeof path, "colliders.planes[%zu]", i);
        if (i >= 8) return jfail(c, e, CJ_ERR_PARSE, "at most 8 planes");
        pl[i] = (cj_plane_collider){{0, 1, 0}, 0, 0};
        if ((st = keys(c, e, path, PK)) || (st = vec3(c, e, path, "normal", pl[i].normal)) ||
            (st = num(c, e, path, "offset", -1e300, &pl[i].offset)) ||
            (st = num(c, e, path, "friction", 0, &pl[i].friction)))
            return st;
    }
    *npl = i;
    return CJ_OK;
}

static cj_status read_cloth(actx *c, cj_anim_doc *doc, const cJSON *cj,
                            const cj_springs_desc *extra) {
    static const char *const K[] = {
        "grid",   "corner",     "edge_u",          "edge_v", "mass", "stiffness", "damping",
        "pinned", "integrator", "steps_per_frame", "color",  "name", NULL};
    cj_status st = keys(c, cj, "cloth", K);
    if (st) return st;
    double grid[2] = {16, 16}, corner[3] = {-1, 1, -1}, eu[3] = {2, 0, 0}, ev[3] = {0, 0, 2};
    double mass = 1, k[3] = {2000, 500, 50}, damping = 0.5, spf = 4, col[3] = {0.8, 0.2, 0.2};
    int integ = CJ_INTEGRATE_IMPLICIT_EULER;
    const cJSON *g = cJSON_GetObjectItemCaseSensitive(cj, "grid");
    if (g && (st = nums(c, g, "cloth.grid", 2, grid, 2, NULL))) return st;
    if (grid[0] < 2 || grid[1] < 2 || grid[0] > 256 || grid[1] > 256 || grid[0] != floor(grid[0]) ||
        grid[1] != floor(grid[1]))
        return jfail(c, g, CJ_ERR_RANGE, "cloth.grid must be two integers in 2..256");
    const cJSON *kj = cJSON_GetObjectItemCaseSensitive(cj, "stiffness");
    if (kj && (st = nums(c, kj, "cloth.stiffness", 3, k, 3, NULL))) return st;
    const cJSON *cc = cJSON_GetObjectItemCaseSensitive(cj, "color");
    if (cc && (st = nums(c, cc, "cloth.color", 3, col, 3, NULL))) return st;
    if ((st = vec3(c, cj, "cloth", "corner", corner)) ||
        (st = vec3(c, cj, "cloth", "edge_u", eu)) || (st = vec3(c, cj, "cloth", "edge_v", ev)) ||
        (st = num(c, cj, "cloth", "mass", 0, &mass)) ||
        (st = num(c, cj, "cloth", "damping", 0, &damping)) ||
        (st = num(c, cj, "cloth", "steps_per_frame", 1, &spf)) ||
        (st = pick(c, cj, "cloth", "integrator", INTEGRATORS, &integ)))
        return st;
    const cJSON *nm = cJSON_GetObjectItemCaseSensitive(cj, "name");
    if (nm && !cJSON_IsString(nm)) return jfail(c, nm, CJ_ERR_PARSE, "cloth.name must be a string");
    snprintf(doc->cloth_name, sizeof doc->cloth_name, "%s", nm ? nm->valuestring : "cloth");
    double pins[64];
    size_t npins = 0;
    const cJSON *pj = cJSON_GetObjectItemCaseSensitive(cj, "pinned");
    if (pj && (st = nums(c, pj, "cloth.pinned", 0, pins, 64, &npins))) return st;
    int ipins[64];
    for (size_t i = 0; i < npins; ++i) ipins[i] = (int)pins[i];
    st = cj_springs_create_cloth((int)grid[0], (int)grid[1], corner, eu, ev, mass, k[0], k[1], k[2],
                                 damping, ipins, npins, extra, NULL, &doc->cloth);
    if (st) {
        char msg[300];
        snprintf(msg, sizeof msg, "%s", cj_last_error());
        return jfail(c, cj, st, "cloth: %s", msg);
    }
    doc->cloth_nu = (int)grid[0];
    doc->cloth_nv = (int)grid[1];
    doc->cloth_integrator = (cj_integrator)integ;
    doc->steps_per_frame = (int)spf;
    doc->cloth_color = cj_rgb_make(col[0], col[1], col[2]);
    return CJ_OK;
}

static cj_status read_emitter(actx *c, const cJSON *e, const char *path, cj_emitter *out) {
    static const char *const K[] = {"position",      "direction", "spread",   "speed",
                                    "speed_jitter",  "rate",      "lifetime", "lifetime_jitter",
                                    "jitter_radius", "start",     "stop",     NULL};
    *out = cj_emitter_default();
    cj_status st;
    if ((st = keys(c, e, path, K)) || (st = vec3(c, e, path, "position", out->position)) ||
        (st = vec3(c, e, path, "direction", out->direction)) ||
        (st = num(c, e, path, "spread", 0, &out->spread)) ||
        (st = num(c, e, path, "speed", 0, &out->speed)) ||
        (st = num(c, e, path, "speed_jitter", 0, &out->speed_jitter)) ||
        (st = num(c, e, path, "rate", 0, &out->rate)) ||
        (st = num(c, e, path, "lifetime", 0, &out->lifetime)) ||
        (st = num(c, e, path, "lifetime_jitter", 0, &out->lifetime_jitter)) ||
        (st = num(c, e, path, "jitter_radius", 0, &out->jitter_radius)) ||
        (st = num(c, e, path, "start", 0, &out->start)) ||
        (st = num(c, e, path, "stop", 0, &out->stop)))
        return st;
    return CJ_OK;
}

static cj_status read_particles(actx *c, cj_anim_doc *doc, const cJSON *pj) {
    static const char *const K[] = {"capacity",        "seed",     "restitution", "wind",
                                    "steps_per_frame", "radius",   "color",       "collide_with",
                                    "flocking",        "emitters", NULL};
    static const char *const FK[] = {"radius",   "separation", "alignment",
                                     "cohesion", "max_speed",  NULL};
    cj_status st = keys(c, pj, "particles", K);
    if (st) return st;
    cj_particles_desc *d = &doc->pdesc;
    double cap = 200, seed = 1, spf = 1, col[3] = {1, 0.8, 0.2};
    doc->particle_radius = 0.04;
    if ((st = num(c, pj, "particles", "capacity", 1, &cap)) ||
        (st = num(c, pj, "particles", "seed", 0, &seed)) ||
        (st = num(c, pj, "particles", "restitution", 0, &d->restitution)) ||
        (st = vec3(c, pj, "particles", "wind", d->wind)) ||
        (st = num(c, pj, "particles", "steps_per_frame", 1, &spf)) ||
        (st = num(c, pj, "particles", "radius", 0, &doc->particle_radius)))
        return st;
    if (cap > 5000 || cap != floor(cap))
        return jfail(c, cJSON_GetObjectItemCaseSensitive(pj, "capacity"), CJ_ERR_RANGE,
                     "particles.capacity must be an integer in 1..5000");
    const cJSON *cc = cJSON_GetObjectItemCaseSensitive(pj, "color");
    if (cc && (st = nums(c, cc, "particles.color", 3, col, 3, NULL))) return st;
    const cJSON *fl = cJSON_GetObjectItemCaseSensitive(pj, "flocking");
    if (fl) {
        cj_flocking *f = &d->flocking;
        if ((st = keys(c, fl, "particles.flocking", FK)) ||
            (st = num(c, fl, "particles.flocking", "radius", 0, &f->radius)) ||
            (st = num(c, fl, "particles.flocking", "separation", -1e300, &f->separation)) ||
            (st = num(c, fl, "particles.flocking", "alignment", -1e300, &f->alignment)) ||
            (st = num(c, fl, "particles.flocking", "cohesion", -1e300, &f->cohesion)) ||
            (st = num(c, fl, "particles.flocking", "max_speed", 0, &f->max_speed)))
            return st;
    }
    const cJSON *cw = cJSON_GetObjectItemCaseSensitive(pj, "collide_with");
    size_t i = 0;
    if (cw && !cJSON_IsArray(cw))
        return jfail(c, cw, CJ_ERR_PARSE, "particles.collide_with must be a list of names");
    for (const cJSON *e = cw ? cw->child : NULL; e; e = e->next, ++i) {
        if (i >= 8 || !cJSON_IsString(e))
            return jfail(c, e, CJ_ERR_PARSE,
                         "particles.collide_with[%zu] must be an object's "
                         "name (at most 8)",
                         i);
        snprintf(doc->collide_with[i], sizeof doc->collide_with[i], "%s", e->valuestring);
    }
    doc->collide_count = (int)i;
    const cJSON *em = cJSON_GetObjectItemCaseSensitive(pj, "emitters");
    if (em && !cJSON_IsArray(em))
        return jfail(c, em, CJ_ERR_PARSE, "particles.emitters must be a list");
    i = 0;
    for (const cJSON *e = em ? em->child : NULL; e; e = e->next, ++i) {
        char path[48];
        snprintf(path, sizeof path, "particles.emitters[%zu]", i);
        if (i >= 16) return jfail(c, e, CJ_ERR_PARSE, "at most 16 emitters");
        if ((st = read_emitter(c, e, path, &doc->emitters[i]))) return st;
    }
    d->capacity = (size_t)cap;
    d->seed = (uint64_t)seed;
    d->emitter_count = i;
    d->emitters = doc->emitters;
    doc->particle_steps = (int)spf;
    doc->particle_color = cj_rgb_make(col[0], col[1], col[2]);
    doc->has_particles = 1;
    /* validate now (the patch colliders come at attach): errors point at the section */
    cj_particles *probe = NULL;
    st = cj_particles_create(d, NULL, &probe);
    cj_particles_destroy(probe);
    if (st) {
        char msg[300];
        snprintf(msg, sizeof msg, "%s", cj_last_error());
        return jfail(c, pj, st, "particles: %s", msg);
    }
    return CJ_OK;
}

static cj_status read_doc(actx *c, const cJSON *root, cj_anim_doc *doc) {
    static const char *const TOP[] = {"scene", "fps",       "frames", "channels",  "gravity",
                                      "drag",  "colliders", "cloth",  "particles", NULL};
    cj_status st = keys(c, root, "document", TOP);
    if (st) return st;
    const cJSON *sc = cJSON_GetObjectItemCaseSensitive(root, "scene");
    if (sc) {
        if (!cJSON_IsString(sc)) return jfail(c, sc, CJ_ERR_PARSE, "scene must be a file name");
        if (sc->valuestring[0] == '/' || !c->base_dir[0])
            snprintf(doc->scene_path, sizeof doc->scene_path, "%s", sc->valuestring);
        else
            snprintf(doc->scene_path, sizeof doc->scene_path, "%s/%s", c->base_dir,
                     sc->valuestring);
    }
    if ((st = num(c, root, "document", "fps", 1e-9, &doc->fps))) return st;
    const cJSON *fr = cJSON_GetObjectItemCaseSensitive(root, "frames");
    if (fr) {
        double f[2];
        if ((st = nums(c, fr, "frames", 2, f, 2, NULL))) return st;
        if (f[0] < 0 || f[1] < f[0] || f[1] > 1e7 || f[0] != floor(f[0]) || f[1] != floor(f[1]))
            return jfail(c, fr, CJ_ERR_RANGE, "frames must be [first, last], 0 <= first <= last");
        doc->frame_first = (int)f[0];
        doc->frame_last = (int)f[1];
    }
    const cJSON *chs = cJSON_GetObjectItemCaseSensitive(root, "channels");
    if (chs && !cJSON_IsArray(chs)) return jfail(c, chs, CJ_ERR_PARSE, "channels must be an array");
    size_t i = 0;
    for (const cJSON *e = chs ? chs->child : NULL; e; e = e->next, ++i) {
        char path[48];
        snprintf(path, sizeof path, "channels[%zu]", i);
        if ((st = read_channel(c, doc->anim, e, path))) return st;
    }
    cj_springs_desc extra;
    memset(&extra, 0, sizeof extra);
    extra.dim = 3;
    cj_sphere_collider sph[8];
    cj_plane_collider pl[8];
    memset(sph, 0, sizeof sph);
    memset(pl, 0, sizeof pl);
    if ((st = vec3(c, root, "document", "gravity", extra.gravity)) ||
        (st = num(c, root, "document", "drag", 0, &extra.drag)))
        return st;
    const cJSON *co = cJSON_GetObjectItemCaseSensitive(root, "colliders");
    if (co && (st = read_colliders(c, co, sph, &extra.sphere_count, pl, &extra.plane_count)))
        return st;
    extra.spheres = sph;
    extra.planes = pl;
    const cJSON *cl = cJSON_GetObjectItemCaseSensitive(root, "cloth");
    if (cl && (st = read_cloth(c, doc, cl, &extra))) return st;
    /* particles share gravity, drag and the colliders */
    memcpy(doc->spheres, sph, sizeof sph);
    memcpy(doc->planes, pl, sizeof pl);
    memcpy(doc->pdesc.gravity, extra.gravity, sizeof extra.gravity);
    doc->pdesc.drag = extra.drag;
    doc->pdesc.spheres = doc->spheres;
    doc->pdesc.sphere_count = extra.sphere_count;
    doc->pdesc.planes = doc->planes;
    doc->pdesc.plane_count = extra.plane_count;
    const cJSON *pj = cJSON_GetObjectItemCaseSensitive(root, "particles");
    if (pj && (st = read_particles(c, doc, pj))) return st;
    return CJ_OK;
}

cj_status cj_anim_doc_parse(const char *text, const char *name, const char *base_dir,
                            cj_anim_doc **out) {
    actx c;
    memset(&c, 0, sizeof c);
    c.name = name ? name : "animation";
    c.base_dir = base_dir ? base_dir : "";
    cJSON *root = cJSON_ParseWithOpts(text, NULL, 1);
    if (!root) {
        const char *at = cJSON_GetErrorPtr();
        int line = 1;
        for (const char *s = text; at && s < at && *s; ++s) line += *s == '\n';
        return cj_fail(CJ_ERR_PARSE, "%s:%d: JSON syntax error", c.name, line);
    }
    int line = 1;
    scan_value(&c, text, &line, 0);
    size_t k = 0;
    pair(&c, root, &k);
    cj_anim_doc *doc = calloc(1, sizeof *doc);
    cj_status st = doc ? CJ_OK : cj_fail(CJ_ERR_NOMEM, "no memory for the animation");
    if (!st) {
        doc->fps = 24;
        doc->cloth_node = doc->cloth_geometry = -1;
        doc->particle_node0 = -1;
        doc->steps_per_frame = 1;
        st = cj_anim_create(NULL, &doc->anim);
    }
    if (!st) st = read_doc(&c, root, doc);
    cJSON_Delete(root);
    free(c.nodes);
    free(c.lines);
    free(c.scan);
    if (st) {
        cj_anim_doc_destroy(doc);
        return st;
    }
    *out = doc;
    return CJ_OK;
}

cj_status cj_anim_doc_load(const char *path, cj_anim_doc **out) {
    FILE *f = fopen(path, "rb");
    if (!f) return cj_fail(CJ_ERR_IO, "%s: cannot open", path);
    char *buf = NULL;
    size_t n = 0, cap = 0;
    for (;;) {
        if (n + 4096 + 1 > cap) {
            cap = cap ? 2 * cap : 65536;
            char *b = realloc(buf, cap);
            if (!b) {
                free(buf);
                fclose(f);
                return cj_fail(CJ_ERR_NOMEM, "%s: no memory", path);
            }
            buf = b;
        }
        const size_t r = fread(buf + n, 1, 4096, f);
        n += r;
        if (r < 4096) break;
    }
    const int err = ferror(f);
    fclose(f);
    if (err) {
        free(buf);
        return cj_fail(CJ_ERR_IO, "%s: read error", path);
    }
    buf[n] = 0;
    char dir[1024];
    snprintf(dir, sizeof dir, "%s", path);
    char *slash = strrchr(dir, '/');
    if (slash)
        *slash = 0;
    else
        dir[0] = 0;
    const char *base = strrchr(path, '/');
    cj_status st = cj_anim_doc_parse(buf, base ? base + 1 : path, dir, out);
    free(buf);
    return st;
}

void cj_anim_doc_destroy(cj_anim_doc *doc) {
    if (!doc) return;
    cj_anim_destroy(doc->anim);
    cj_springs_destroy(doc->cloth);
    cj_particles_destroy(doc->particles);
    for (int i = 0; i < 8; ++i) cj_patch_collider_destroy(doc->patch_colliders[i]);
    free(doc);
}

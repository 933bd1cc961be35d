/* Reading OBJ and PLY meshes (casteljau/mesh_read.h). Both formats are read whole into memory
 * first: meshes that fit a cj_mesh fit in memory as text too, and it keeps line counting and
 * error messages simple. */
#include "casteljau/mesh_read.h"

#include "error_internal.h"

#include <assert.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- shared --------------------------------------------------------------------------------- */

static cj_status slurp(const char *path, char **text, size_t *len) {
    FILE *f = fopen(path, "rb");
    if (!f) return cj_fail(CJ_ERR_IO, "cannot open '%s': %s", path, strerror(errno));
    size_t cap = 65536, n = 0;
    char *buf = malloc(cap);
    for (;;) {
        if (!buf) {
            fclose(f);
            return cj_fail(CJ_ERR_NOMEM, "out of memory reading '%s'", path);
        }
        n += fread(buf + n, 1, cap - n - 1, f);
        if (n + 1 < cap) break;
        char *d = realloc(buf, 2 * cap);
        if (!d) free(buf);
        buf = d;
        cap *= 2;
    }
    int bad = ferror(f);
    fclose(f);
    if (bad) {
        free(buf);
        return cj_fail(CJ_ERR_IO, "cannot read '%s'", path);
    }
    buf[n] = '\0';
    *text = buf;
    *len = n;
    return CJ_OK;
}

void cj_mesh_compute_normals(cj_mesh *m) {
    assert(m != NULL);
    memset(m->normals, 0, 3 * m->vertex_count * sizeof(double));
    for (size_t t = 0; t < m->triangle_count; ++t) {
        const uint32_t *v = m->triangles + 3 * t;
        const double *a = m->positions + 3 * (size_t)v[0], *b = m->positions + 3 * (size_t)v[1],
                     *c = m->positions + 3 * (size_t)v[2];
        double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
        double e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
        double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                       e1[0] * e2[1] - e1[1] * e2[0]};
        for (int k = 0; k < 3; ++k)
            for (int j = 0; j < 3; ++j) m->normals[3 * (size_t)v[k] + (size_t)j] += n[j];
    }
    for (size_t i = 0; i < m->vertex_count; ++i) {
        double *n = m->normals + 3 * i;
        double l = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        if (l > 0 && isfinite(l))
            for (int j = 0; j < 3; ++j) n[j] /= l;
        else
            n[0] = n[1] = n[2] = 0;
    }
}

/* Fills the normals of the vertices with have[i] == 0 from the triangles around them. */
static cj_status fill_missing_normals(cj_mesh *m, const unsigned char *have) {
    size_t n = m->vertex_count, missing = 0;
    for (size_t i = 0; i < n; ++i) missing += !have[i];
    if (!missing) return CJ_OK;
    double *keep = malloc(3 * n * sizeof *keep + 1);
    if (!keep) return cj_fail(CJ_ERR_NOMEM, "out of memory computing normals");
    memcpy(keep, m->normals, 3 * n * sizeof *keep);
    cj_mesh_compute_normals(m);
    for (size_t i = 0; i < n; ++i)
        if (have[i]) memcpy(m->normals + 3 * i, keep + 3 * i, 3 * sizeof *keep);
    free(keep);
    return CJ_OK;
}

/* ---- OBJ ------------------------------------------------------------------------------------ */

typedef struct dvec {
    double *v;
    size_t n, cap; /* in doubles */
} dvec;

static int dpush(dvec *d, const double *x, size_t k) {
    if (d->n + k > d->cap) {
        size_t nc = d->cap ? 2 * d->cap : 3072;
        double *p = realloc(d->v, nc * sizeof *p);
        if (!p) return 0;
        d->v = p;
        d->cap = nc;
    }
    memcpy(d->v + d->n, x, k * sizeof *x);
    d->n += k;
    return 1;
}

/* Open-addressing map from (v, vt, vn) to a mesh vertex. */
typedef struct corner_map {
    uint32_t *keys; /* 3 per slot; slot empty when vals[i] == UINT32_MAX */
    uint32_t *vals;
    size_t cap, n;
} corner_map;

static size_t corner_hash(const uint32_t k[3], size_t mask) {
    uint64_t h = k[0] * 0x9E3779B97F4A7C15ull ^
                 (k[1] + 0x632BE59BD9B4E019ull) * 0xC2B2AE3D27D4EB4Full ^
                 (k[2] + 0x165667B19E3779F9ull) * 0x27D4EB2F165667C5ull;
    h ^= h >> 29;
    return (size_t)h & mask;
}

static int map_grow(corner_map *m) {
    size_t nc = m->cap ? 2 * m->cap : 1024;
    uint32_t *k = malloc(3 * nc * sizeof *k), *v = malloc(nc * sizeof *v);
    if (!k || !v) {
        free(k);
        free(v);
        return 0;
    }
    memset(v, 0xff, nc * sizeof *v);
    for (size_t i = 0; i < m->cap; ++i) {
        if (m->vals[i] == UINT32_MAX) continue;
        size_t s = corner_hash(m->keys + 3 * i, nc - 1);
        while (v[s] != UINT32_MAX) s = (s + 1) & (nc - 1);
        memcpy(k + 3 * s, m->keys + 3 * i, 3 * sizeof *k);
        v[s] = m->vals[i];
    }
    free(m->keys);
    free(m->vals);
    m->keys = k;
    m->vals = v;
    m->cap = nc;
    return 1;
}

/* The slot of key k (found, or the empty slot where it goes). */
static size_t map_slot(const corner_map *m, const uint32_t k[3]) {
    size_t s = corner_hash(k, m->cap - 1);
    while (m->vals[s] != UINT32_MAX && memcmp(m->keys + 3 * s, k, 3 * sizeof *k))
        s = (s + 1) & (m->cap - 1);
    return s;
}

typedef struct obj_reader {
    const char *path;
    int line;
    dvec v, vt, vn;
    corner_map map;
    unsigned char *have_normal;
    size_t have_cap;
    cj_mesh *mesh;
    int32_t group;
    char **groups; /* names of non-patch_N groups, numbered in order */
    size_t ngroups;
} obj_reader;

static cj_status obj_numbers(obj_reader *r, const char **s, double *out, int min, int max,
                             int *got) {
    int k = 0;
    for (;;) {
        while (**s == ' ' || **s == '\t') (*s)++;
        if (!**s || **s == '#') break;
        if (k == max)
            return cj_fail(CJ_ERR_PARSE, "%s:%d: too many numbers (at most %d)", r->path, r->line,
                           max);
        char *end;
        errno = 0;
        double d = strtod(*s, &end);
        if (end == *s || (*end && *end != ' ' && *end != '\t' && *end != '#'))
            return cj_fail(CJ_ERR_PARSE, "%s:%d: '%.20s' is not a number", r->path, r->line, *s);
        if (!isfinite(d))
            return cj_fail(CJ_ERR_NONFINITE, "%s:%d: number %d is not finite", r->path, r->line,
                           k + 1);
        out[k++] = d;
        *s = end;
    }
    if (k < min)
        return cj_fail(CJ_ERR_PARSE, "%s:%d: expected at least %d numbers, found %d", r->path,
                       r->line, min, k);
    *got = k;
    return CJ_OK;
}

/* One index of a corner: 1-based or negative, into a list of `count` elements. */
static cj_status obj_index(obj_reader *r, const char **s, size_t count, const char *what,
                           int corner, uint32_t *out) {
    char *end;
    errno = 0;
    long long i = strtoll(*s, &end, 10);
    if (end == *s || errno)
        return cj_fail(CJ_ERR_PARSE, "%s:%d: face corner %d: bad %s index '%.20s'", r->path,
                       r->line, corner, what, *s);
    *s = end;
    long long k = i > 0 ? i - 1 : (long long)count + i;
    if (i == 0 || k < 0 || k >= (long long)count)
        return cj_fail(CJ_ERR_RANGE, "%s:%d: face corner %d names %s %lld of %zu", r->path, r->line,
                       corner, what, i, count);
    *out = (uint32_t)k;
    return CJ_OK;
}

static cj_status obj_corner(obj_reader *r, const char **s, int corner, uint32_t *vertex) {
    uint32_t key[3] = {0, UINT32_MAX, UINT32_MAX};
    cj_status st = obj_index(r, s, r->v.n / 3, "vertex", corner, &key[0]);
    if (st) return st;
    if (**s == '/') {
        (*s)++;
        if (**s != '/') {
            st = obj_index(r, s, r->vt.n / 2, "texture coordinate", corner, &key[1]);
            if (st) return st;
        }
        if (**s == '/') {
            (*s)++;
            st = obj_index(r, s, r->vn.n / 3, "normal", corner, &key[2]);
            if (st) return st;
        }
    }
    if (**s && **s != ' ' && **s != '\t' && **s != '#')
        return cj_fail(CJ_ERR_PARSE, "%s:%d: face corner %d: unexpected '%c'", r->path, r->line,
                       corner, **s);
    if (2 * (r->map.n + 1) > r->map.cap && !map_grow(&r->map))
        return cj_fail(CJ_ERR_NOMEM, "out of memory reading '%s'", r->path);
    size_t slot = map_slot(&r->map, key);
    if (r->map.vals[slot] != UINT32_MAX) {
        *vertex = r->map.vals[slot];
        return CJ_OK;
    }
    cj_mesh *m = r->mesh;
    if (m->vertex_count >= CJ_MESH_MAX_VERTICES)
        return cj_fail(CJ_ERR_RANGE, "%s:%d: too many vertices", r->path, r->line);
    double uv[2] = {0, 0};
    if (key[1] != UINT32_MAX) memcpy(uv, r->vt.v + 2 * (size_t)key[1], sizeof uv);
    const double *n = key[2] != UINT32_MAX ? r->vn.v + 3 * (size_t)key[2] : NULL;
    uint32_t idx;
    st = cj_mesh_add_vertex(m, r->v.v + 3 * (size_t)key[0], n, uv, &idx);
    if (st) return st;
    if (idx >= r->have_cap) {
        size_t nc = r->have_cap ? 2 * r->have_cap : 1024;
        unsigned char *h = realloc(r->have_normal, nc);
        if (!h) return cj_fail(CJ_ERR_NOMEM, "out of memory reading '%s'", r->path);
        r->have_normal = h;
        r->have_cap = nc;
    }
    r->have_normal[idx] = n != NULL;
    memcpy(r->map.keys + 3 * slot, key, sizeof key);
    r->map.vals[slot] = idx;
    r->map.n++;
    *vertex = idx;
    return CJ_OK;
}

static cj_status obj_face(obj_reader *r, const char *s) {
    uint32_t first = 0, prev = 0;
    int k = 0;
    for (;;) {
        while (*s == ' ' || *s == '\t') s++;
        if (!*s || *s == '#') break;
        uint32_t v = 0;
        cj_status st = obj_corner(r, &s, k + 1, &v);
        if (st) return st;
        if (k == 0) first = v;
        if (k >= 2) {
            st = cj_mesh_add_triangle(r->mesh, first, prev, v, r->group);
            if (st) return st;
        }
        prev = v;
        k++;
    }
    if (k < 3)
        return cj_fail(CJ_ERR_RANGE, "%s:%d: a face needs at least 3 corners, found %d", r->path,
                       r->line, k);
    return CJ_OK;
}

static cj_status obj_group(obj_reader *r, const char *s) {
    while (*s == ' ' || *s == '\t') s++;
    size_t len = strcspn(s, " \t#");
    int n = 0, used = 0;
    if (len > 6 && !strncmp(s, "patch_", 6) && sscanf(s + 6, "%d%n", &n, &used) == 1 &&
        (size_t)used == len - 6) {
        r->group = n;
        return CJ_OK;
    }
    for (size_t i = 0; i < r->ngroups; ++i)
        if (strlen(r->groups[i]) == len && !strncmp(r->groups[i], s, len)) {
            r->group = (int32_t)i;
            return CJ_OK;
        }
    char **g = realloc(r->groups, (r->ngroups + 1) * sizeof *g);
    if (!g) return cj_fail(CJ_ERR_NOMEM, "out of memory reading '%s'", r->path);
    r->groups = g;
    g[r->ngroups] = malloc(len + 1);
    if (!g[r->ngroups]) return cj_fail(CJ_ERR_NOMEM, "out of memory reading '%s'", r->path);
    memcpy(g[r->ngroups], s, len);
    g[r->ngroups][len] = '\0';
    r->group = (int32_t)r->ngroups++;
    return CJ_OK;
}

static cj_status obj_statement(obj_reader *r, char *line) {
    char *s = line;
    while (*s == ' ' || *s == '\t') s++;
    if (!*s || *s == '#') return CJ_OK;
    size_t kw = strcspn(s, " \t");
    char word[16] = "";
    if (kw < sizeof word) memcpy(word, s, kw);
    const char *rest = s + kw;
    double x[4];
    int got;
    cj_status st;
    if (!strcmp(word, "v")) {
        if ((st = obj_numbers(r, &rest, x, 3, 4, &got))) return st;
        if (got == 4) {
            if (!(x[3] != 0.0))
                return cj_fail(CJ_ERR_RANGE, "%s:%d: vertex weight w must not be 0", r->path,
                               r->line);
            for (int k = 0; k < 3; ++k) x[k] /= x[3];
        }
        return dpush(&r->v, x, 3) ? CJ_OK : cj_fail(CJ_ERR_NOMEM, "out of memory");
    }
    if (!strcmp(word, "vt")) {
        x[1] = 0;
        if ((st = obj_numbers(r, &rest, x, 1, 3, &got))) return st;
        return dpush(&r->vt, x, 2) ? CJ_OK : cj_fail(CJ_ERR_NOMEM, "out of memory");
    }
    if (!strcmp(word, "vn")) {
        if ((st = obj_numbers(r, &rest, x, 3, 3, &got))) return st;
        return dpush(&r->vn, x, 3) ? CJ_OK : cj_fail(CJ_ERR_NOMEM, "out of memory");
    }
    if (!strcmp(word, "f")) return obj_face(r, rest);
    if (!strcmp(word, "g")) return obj_group(r, rest);
    static const char *const IGNORED[] = {"o", "s", "usemtl", "mtllib", "l", "p", "vp", NULL};
    for (int i = 0; IGNORED[i]; ++i)
        if (!strcmp(word, IGNORED[i])) return CJ_OK;
    return cj_fail(CJ_ERR_PARSE, "%s:%d: unknown statement '%.*s'", r->path, r->line,
                   (int)(kw < 40 ? kw : 40), s);
}

cj_status cj_mesh_read_obj(const char *path, const cj_allocator *alloc, cj_mesh **out) {
    assert(path && out);
    char *text;
    size_t len;
    cj_status st = slurp(path, &text, &len);
    if (st) return st;
    obj_reader r;
    memset(&r, 0, sizeof r);
    r.path = path;
    st = cj_mesh_create(alloc, &r.mesh);
    char *s = text;
    while (!st && s < text + len) {
        r.line++;
        char *e = s + strcspn(s, "\n");
        int last = *e == '\0';
        *e = '\0';
        if (e > s && e[-1] == '\r') e[-1] = '\0';
        st = obj_statement(&r, s);
        s = last ? text + len : e + 1;
    }
    if (!st && r.mesh->triangle_count == 0) st = cj_fail(CJ_ERR_EMPTY, "%s: no faces", path);
    if (!st) st = fill_missing_normals(r.mesh, r.have_normal);
    if (st)
        cj_mesh_destroy(r.mesh);
    else
        *out = r.mesh;
    free(text);
    free(r.v.v);
    free(r.vt.v);
    free(r.vn.v);
    free(r.map.keys);
    free(r.map.vals);
    free(r.have_normal);
    for (size_t i = 0; i < r.ngroups; ++i) free(r.groups[i]);
    free(r.groups);
    return st;
}

/* ---- PLY ------------------------------------------------------------------------------------ */

enum { T_I8, T_U8, T_I16, T_U16, T_I32, T_U32, T_F32, T_F64, T_BAD };
static const char *const PLY_TYPES[][2] = {
    {"char", "int8"}, {"uchar", "uint8"}, {"short", "int16"},   {"ushort", "uint16"},
    {"int", "int32"}, {"uint", "uint32"}, {"float", "float32"}, {"double", "float64"}};
static const int PLY_SIZE[] = {1, 1, 2, 2, 4, 4, 4, 8};

static int ply_type(const char *s) {
    for (int t = 0; t < T_BAD; ++t)
        if (!strcmp(s, PLY_TYPES[t][0]) || !strcmp(s, PLY_TYPES[t][1])) return t;
    return T_BAD;
}

#define PLY_MAX_PROPS 32
typedef struct ply_elem {
    char name[64];
    size_t count;
    int nprops;
    int type[PLY_MAX_PROPS];  /* value type (list: index type) */
    int ltype[PLY_MAX_PROPS]; /* list count type, or -1 for a scalar */
    char pname[PLY_MAX_PROPS][64];
} ply_elem;

typedef struct ply_reader {
    const char *path;
    int binary;
    const char *s, *end;
    int line; /* ascii */
} ply_reader;

/* Next value of type t: from the text (ascii) or the bytes (binary little endian). */
static cj_status ply_value(ply_reader *r, int t, const char *elem, size_t index, double *out) {
    if (r->binary) {
        int n = PLY_SIZE[t];
        if (r->end - r->s < n)
            return cj_fail(CJ_ERR_PARSE, "%s: %s %zu: the file ends early", r->path, elem, index);
        unsigned char b[8];
        for (int k = 0; k < n; ++k) b[k] = (unsigned char)r->s[k];
        r->s += n;
        uint64_t u = 0;
        for (int k = n - 1; k >= 0; --k) u = (u << 8) | b[k];
        switch (t) {
        case T_I8:
            *out = (int8_t)u;
            break;
        case T_U8:
            *out = (uint8_t)u;
            break;
        case T_I16:
            *out = (int16_t)u;
            break;
        case T_U16:
            *out = (uint16_t)u;
            break;
        case T_I32:
            *out = (int32_t)u;
            break;
        case T_U32:
            *out = (uint32_t)u;
            break;
        case T_F32: {
            uint32_t w = (uint32_t)u;
            float f;
            memcpy(&f, &w, 4);
            *out = f;
            break;
        }
        default: {
            double d;
            memcpy(&d, &u, 8);
            *out = d;
        }
        }
    } else {
        const int last_line = r->line; /* where the last value was */
        while (r->s < r->end && (*r->s == ' ' || *r->s == '\t' || *r->s == '\r' || *r->s == '\n')) {
            if (*r->s == '\n') r->line++;
            r->s++;
        }
        if (r->s >= r->end)
            return cj_fail(CJ_ERR_PARSE, "%s:%d: %s %zu: the file ends early", r->path, last_line,
                           elem, index);
        char *e;
        *out = strtod(r->s, &e);
        if (e == r->s)
            return cj_fail(CJ_ERR_PARSE, "%s:%d: %s %zu: '%.20s' is not a number", r->path, r->line,
                           elem, index, r->s);
        r->s = e;
    }
    if (!isfinite(*out)) {
        if (r->binary)
            return cj_fail(CJ_ERR_NONFINITE, "%s: %s %zu: a value is not finite", r->path, elem,
                           index);
        return cj_fail(CJ_ERR_NONFINITE, "%s:%d: %s %zu: a value is not finite", r->path, r->line,
                       elem, index);
    }
    if (t < T_F32 && *out != floor(*out)) /* only text can hold a fraction */
        return cj_fail(CJ_ERR_PARSE, "%s:%d: %s %zu: an integer property holds %g", r->path,
                       r->line, elem, index, *out);
    return CJ_OK;
}

static int prop_index(const ply_elem *e, const char *const *names) {
    for (int i = 0; i < e->nprops; ++i)
        for (const char *const *n = names; *n; ++n)
            if (!strcmp(e->pname[i], *n)) return i;
    return -1;
}

/* Reads the header into elems; r->s is left at the first data byte. */
static cj_status ply_header(ply_reader *r, const char *text, size_t len, ply_elem *elems,
                            int *nelems) {
    const char *s = text, *end = text + len;
    int line = 0, ne = 0;
    for (;;) {
        if (s >= end) return cj_fail(CJ_ERR_PARSE, "%s: no end_header", r->path);
        line++;
        const char *nl = memchr(s, '\n', (size_t)(end - s));
        size_t l = nl ? (size_t)(nl - s) : (size_t)(end - s);
        char buf[256];
        if (l >= sizeof buf)
            return cj_fail(CJ_ERR_PARSE, "%s:%d: header line too long", r->path, line);
        memcpy(buf, s, l);
        buf[l] = '\0';
        if (l && buf[l - 1] == '\r') buf[l - 1] = '\0';
        s = nl ? nl + 1 : end;
        char w[4][64];
        int nw = sscanf(buf, "%63s %63s %63s %63s", w[0], w[1], w[2], w[3]);
        if (line == 1) {
            if (nw != 1 || strcmp(w[0], "ply"))
                return cj_fail(CJ_ERR_PARSE, "%s:1: not a PLY file (no 'ply' line)", r->path);
            continue;
        }
        if (nw <= 0 || !strcmp(w[0], "comment") || !strcmp(w[0], "obj_info")) continue;
        if (!strcmp(w[0], "end_header")) break;
        if (!strcmp(w[0], "format")) {
            if (nw < 2) return cj_fail(CJ_ERR_PARSE, "%s:%d: bad format line", r->path, line);
            if (!strcmp(w[1], "ascii"))
                r->binary = 0;
            else if (!strcmp(w[1], "binary_little_endian"))
                r->binary = 1;
            else
                return cj_fail(CJ_ERR_UNSUPPORTED, "%s:%d: PLY format '%s' is not supported",
                               r->path, line, w[1]);
        } else if (!strcmp(w[0], "element")) {
            unsigned long long cnt;
            char extra;
            if (nw != 3 || ne >= 16 || sscanf(w[2], "%llu%c", &cnt, &extra) != 1)
                return cj_fail(CJ_ERR_PARSE, "%s:%d: bad element line", r->path, line);
            ply_elem *e = &elems[ne++];
            memset(e, 0, sizeof *e);
            snprintf(e->name, sizeof e->name, "%s", w[1]);
            e->count = (size_t)cnt;
        } else if (!strcmp(w[0], "property")) {
            if (ne == 0)
                return cj_fail(CJ_ERR_PARSE, "%s:%d: property before element", r->path, line);
            ply_elem *e = &elems[ne - 1];
            if (e->nprops >= PLY_MAX_PROPS)
                return cj_fail(CJ_ERR_PARSE, "%s:%d: too many properties", r->path, line);
            int k = e->nprops;
            if (!strcmp(w[1], "list")) {
                char w5[64];
                if (sscanf(buf, "%*s %*s %*s %*s %63s", w5) != 1)
                    return cj_fail(CJ_ERR_PARSE, "%s:%d: bad list property", r->path, line);
                e->ltype[k] = ply_type(w[2]);
                e->type[k] = ply_type(w[3]);
                snprintf(e->pname[k], sizeof e->pname[k], "%s", w5);
                if (e->ltype[k] == T_BAD || e->type[k] == T_BAD || e->ltype[k] >= T_F32)
                    return cj_fail(CJ_ERR_PARSE, "%s:%d: bad list types", r->path, line);
            } else {
                if (nw != 3)
                    return cj_fail(CJ_ERR_PARSE, "%s:%d: bad property line", r->path, line);
                e->ltype[k] = -1;
                e->type[k] = ply_type(w[1]);
                snprintf(e->pname[k], sizeof e->pname[k], "%s", w[2]);
                if (e->type[k] == T_BAD)
                    return cj_fail(CJ_ERR_PARSE, "%s:%d: unknown type '%s'", r->path, line, w[1]);
            }
            e->nprops++;
        } else {
            return cj_fail(CJ_ERR_PARSE, "%s:%d: unknown header line '%.40s'", r->path, line, buf);
        }
    }
    r->s = s;
    r->end = end;
    r->line = line + 1;
    *nelems = ne;
    return CJ_OK;
}

static cj_status ply_vertices(ply_reader *r, const ply_elem *e, cj_mesh *m, unsigned char *have) {
    static const char *const X[] = {"x", NULL}, *const Y[] = {"y", NULL}, *const Z[] = {"z", NULL};
    static const char *const NX[] = {"nx", NULL}, *const NY[] = {"ny", NULL},
                             *const NZ[] = {"nz", NULL};
    static const char *const U[] = {"u", "s", "texture_u", "texture_s", NULL};
    static const char *const V[] = {"v", "t", "texture_v", "texture_t", NULL};
    int ix = prop_index(e, X), iy = prop_index(e, Y), iz = prop_index(e, Z);
    int inx = prop_index(e, NX), iny = prop_index(e, NY), inz = prop_index(e, NZ);
    int iu = prop_index(e, U), iv = prop_index(e, V);
    if (ix < 0 || iy < 0 || iz < 0)
        return cj_fail(CJ_ERR_PARSE, "%s: element vertex has no x, y, z properties", r->path);
    int has_n = inx >= 0 && iny >= 0 && inz >= 0;
    for (size_t i = 0; i < e->count; ++i) {
        double vals[PLY_MAX_PROPS];
        for (int k = 0; k < e->nprops; ++k) {
            double cnt = 0, d;
            if (e->ltype[k] >= 0) { /* a list on a vertex: read and skip */
                cj_status st = ply_value(r, e->ltype[k], "vertex", i, &cnt);
                for (double j = 0; !st && j < cnt; ++j)
                    st = ply_value(r, e->type[k], "vertex", i, &d);
                if (st) return st;
                vals[k] = 0;
                continue;
            }
            cj_status st = ply_value(r, e->type[k], "vertex", i, &vals[k]);
            if (st) return st;
        }
        double p[3] = {vals[ix], vals[iy], vals[iz]};
        double n[3] = {has_n ? vals[inx] : 0, has_n ? vals[iny] : 0, has_n ? vals[inz] : 0};
        double uv[2] = {iu >= 0 ? vals[iu] : 0, iv >= 0 ? vals[iv] : 0};
        cj_status st = cj_mesh_add_vertex(m, p, n, uv, NULL);
        if (st) return st;
        have[i] = (unsigned char)has_n;
    }
    return CJ_OK;
}

static cj_status ply_faces(ply_reader *r, const ply_elem *e, cj_mesh *m) {
    static const char *const VI[] = {"vertex_indices", "vertex_index", NULL};
    int il = prop_index(e, VI);
    if (il < 0 || e->ltype[il] < 0)
        return cj_fail(CJ_ERR_PARSE, "%s: element face has no vertex_indices list", r->path);
    for (size_t i = 0; i < e->count; ++i) {
        int line = r->line;
        for (int k = 0; k < e->nprops; ++k) {
            double cnt = 1, d;
            cj_status st = CJ_OK;
            if (e->ltype[k] >= 0) st = ply_value(r, e->ltype[k], "face", i, &cnt);
            if (st) return st;
            if (k != il) {
                for (double j = 0; !st && j < cnt; ++j)
                    st = ply_value(r, e->type[k], "face", i, &d);
                if (st) return st;
                continue;
            }
            if (cnt < 3) {
                if (r->binary)
                    return cj_fail(CJ_ERR_RANGE, "%s: face %zu has %g corners (at least 3)",
                                   r->path, i, cnt);
                return cj_fail(CJ_ERR_RANGE, "%s:%d: face %zu has %g corners (at least 3)", r->path,
                               line, i, cnt);
            }
            uint32_t first = 0, prev = 0;
            for (int j = 0; j < (int)cnt; ++j) {
                st = ply_value(r, e->type[k], "face", i, &d);
                if (st) return st;
                if (d < 0 || d >= (double)m->vertex_count) {
                    if (r->binary)
                        return cj_fail(CJ_ERR_RANGE,
                                       "%s: face %zu: vertex index %g out of range (%zu vertices)",
                                       r->path, i, d, m->vertex_count);
                    return cj_fail(CJ_ERR_RANGE,
                                   "%s:%d: face %zu: vertex index %g out of range (%zu vertices)",
                                   r->path, r->line, i, d, m->vertex_count);
                }
                uint32_t v = (uint32_t)d;
                if (j == 0) first = v;
                if (j >= 2 && (st = cj_mesh_add_triangle(m, first, prev, v, 0))) return st;
                prev = v;
            }
        }
    }
    return CJ_OK;
}

cj_status cj_mesh_read_ply(const char *path, const cj_allocator *alloc, cj_mesh **out) {
    assert(path && out);
    char *text;
    size_t len;
    cj_status st = slurp(path, &text, &len);
    if (st) return st;
    ply_reader r;
    memset(&r, 0, sizeof r);
    r.path = path;
    ply_elem elems[16];
    int ne = 0;
    cj_mesh *m = NULL;
    unsigned char *have = NULL;
    st = ply_header(&r, text, len, elems, &ne);
    if (!st) st = cj_mesh_create(alloc, &m);
    int seen_vertex = 0;
    for (int i = 0; i < ne && !st; ++i) {
        ply_elem *e = &elems[i];
        if (!strcmp(e->name, "vertex")) {
            if (e->count > CJ_MESH_MAX_VERTICES || e->count > len) {
                st = cj_fail(CJ_ERR_RANGE, "%s: %zu vertices is more than the file holds", path,
                             e->count);
                break;
            }
            have = malloc(e->count + 1);
            if (!have) st = cj_fail(CJ_ERR_NOMEM, "out of memory reading '%s'", path);
            if (!st) st = cj_mesh_reserve(m, e->count, 0);
            if (!st) st = ply_vertices(&r, e, m, have);
            seen_vertex = 1;
        } else if (!strcmp(e->name, "face")) {
            if (!seen_vertex)
                st = cj_fail(CJ_ERR_PARSE, "%s: element face comes before element vertex", path);
            else
                st = ply_faces(&r, e, m);
        } else {
            for (size_t k = 0; k < e->count && !st; ++k)
                for (int j = 0; j < e->nprops && !st; ++j) {
                    double cnt = 1, d;
                    if (e->ltype[j] >= 0) st = ply_value(&r, e->ltype[j], e->name, k, &cnt);
                    for (double q = 0; !st && q < cnt; ++q)
                        st = ply_value(&r, e->type[j], e->name, k, &d);
                }
        }
    }
    if (!st && (!m || m->triangle_count == 0)) st = cj_fail(CJ_ERR_EMPTY, "%s: no faces", path);
    if (!st) st = fill_missing_normals(m, have);
    if (st)
        cj_mesh_destroy(m);
    else
        *out = m;
    free(have);
    free(text);
    return st;
}

static int ends_with_ci(const char *s, const char *suffix) {
    size_t a = strlen(s), b = strlen(suffix);
    if (a < b) return 0;
    for (size_t i = 0; i < b; ++i) {
        char c = s[a - b + i];
        if (c >= 'A' && c <= 'Z') c = (char)(c - 'A' + 'a');
        if (c != suffix[i]) return 0;
    }
    return 1;
}

cj_status cj_mesh_read(const char *path, const cj_allocator *alloc, cj_mesh **out) {
    assert(path && out);
    if (ends_with_ci(path, ".obj")) return cj_mesh_read_obj(path, alloc, out);
    if (ends_with_ci(path, ".ply")) return cj_mesh_read_ply(path, alloc, out);
    return cj_fail(CJ_ERR_ARGUMENT, "'%s': unknown mesh extension (use .obj or .ply)", path);
}

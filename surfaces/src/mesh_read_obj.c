/* Reading OBJ meshes (casteljau/mesh_read.h; PLY in mesh_read_ply.c, the shared helpers in
 * mesh_read_util.c). Both formats are read whole into memory first: meshes that fit a cj_mesh
 * fit in memory as text too, and it keeps line counting and error messages simple. */
#include "casteljau/mesh_read.h"

#include "error_internal.h"
#include "mesh_read_internal.h"

#include <assert.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

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
        return dpush(&r->v, x, 3) ? CJ_OK
                                  : cj_fail(CJ_ERR_NOMEM, "out of memory reading '%s'", r->path);
    }
    if (!strcmp(word, "vt")) {
        x[1] = 0;
        if ((st = obj_numbers(r, &rest, x, 1, 3, &got))) return st;
        return dpush(&r->vt, x, 2) ? CJ_OK
                                   : cj_fail(CJ_ERR_NOMEM, "out of memory reading '%s'", r->path);
    }
    if (!strcmp(word, "vn")) {
        if ((st = obj_numbers(r, &rest, x, 3, 3, &got))) return st;
        return dpush(&r->vn, x, 3) ? CJ_OK
                                   : cj_fail(CJ_ERR_NOMEM, "out of memory reading '%s'", r->path);
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
    cj_status st = cj_mesh_slurp_(path, &text, &len);
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
    if (!st) st = cj_mesh_fill_missing_normals_(r.mesh, r.have_normal);
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

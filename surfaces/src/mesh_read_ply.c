/* Reading PLY meshes (casteljau/mesh_read.h): ASCII and binary little endian, any scalar
 * types, the vertex and face elements; others are read and skipped. */
#include "casteljau/mesh_read.h"

#include "error_internal.h"
#include "mesh_read_internal.h"

#include <assert.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

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
            /* every corner takes at least one byte of the file: a larger count (found by
             * fuzz_mesh_read: 8.9e97) is refused before it is converted to an integer */
            if (cnt < 3 || cnt > (double)(r->end - r->s) || cnt != floor(cnt)) {
                if (r->binary)
                    return cj_fail(CJ_ERR_RANGE,
                                   "%s: face %zu has %g corners (at least 3, at most the file's "
                                   "size)",
                                   r->path, i, cnt);
                return cj_fail(CJ_ERR_RANGE,
                               "%s:%d: face %zu has %g corners (at least 3, at most the file's "
                               "size)",
                               r->path, r->line, i, cnt); /* the line the count was read on */
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
    cj_status st = cj_mesh_slurp_(path, &text, &len);
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
            if (seen_vertex) {
                /* faces index one vertex list; a second one has no meaning */
                st = cj_fail(CJ_ERR_PARSE, "%s: element vertex appears twice", path);
                break;
            }
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
            for (size_t k = 0; e->nprops > 0 && k < e->count && !st; ++k)
                for (int j = 0; j < e->nprops && !st; ++j) {
                    double cnt = 1, d;
                    if (e->ltype[j] >= 0) st = ply_value(&r, e->ltype[j], e->name, k, &cnt);
                    for (double q = 0; !st && q < cnt; ++q)
                        st = ply_value(&r, e->type[j], e->name, k, &d);
                }
        }
    }
    if (!st && (!m || m->triangle_count == 0)) st = cj_fail(CJ_ERR_EMPTY, "%s: no faces", path);
    if (!st) st = cj_mesh_fill_missing_normals_(m, have);
    if (st)
        cj_mesh_destroy(m);
    else
        *out = m;
    free(have);
    free(text);
    return st;
}

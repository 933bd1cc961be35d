/* Indexed triangle mesh: growth, welding, topology, OBJ/PLY export. */
#define _POSIX_C_SOURCE 200809L /* fileno, fsync */
#include "casteljau/mesh.h"
#include "alloc_internal.h"
#include "error_internal.h"
#include "file_internal.h"

#include <assert.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

cj_status cj_mesh_create(const cj_allocator *alloc, cj_mesh **out) {
    assert(out != NULL);
    const cj_allocator a = cj_allocator_resolve(alloc);
    cj_mesh *m = cj_allocator_alloc(&a, sizeof *m);
    if (!m) return cj_fail(CJ_ERR_NOMEM, "out of memory creating a mesh");
    memset(m, 0, sizeof *m);
    m->alloc_ = a;
    *out = m;
    return CJ_OK;
}

void cj_mesh_destroy(cj_mesh *m) {
    if (!m) return;
    const cj_allocator a = m->alloc_;
    cj_allocator_free(&a, m->positions);
    cj_allocator_free(&a, m->normals);
    cj_allocator_free(&a, m->uvs);
    cj_allocator_free(&a, m->triangles);
    cj_allocator_free(&a, m->triangle_patch);
    cj_allocator_free(&a, m);
}

void cj_mesh_clear(cj_mesh *m) {
    assert(m != NULL);
    m->vertex_count = m->triangle_count = 0;
}

void cj_mesh_truncate(cj_mesh *m, size_t vertices, size_t triangles) {
    assert(m != NULL);
    if (vertices < m->vertex_count) m->vertex_count = vertices;
    if (triangles < m->triangle_count) m->triangle_count = triangles;
}

cj_status cj_mesh_reserve(cj_mesh *m, size_t nv, size_t nt) {
    assert(m != NULL);
    if (nv > CJ_MESH_MAX_VERTICES)
        return cj_fail(CJ_ERR_CAP, "%zu vertices exceed the mesh limit of %u", nv,
                       CJ_MESH_MAX_VERTICES);
    if (nv > m->vcap_) {
        size_t cap = m->vcap_ ? m->vcap_ : 64;
        while (cap < nv) cap *= 2;
        double *p = NULL, *n = NULL, *uv = NULL;
        p = cj_allocator_alloc(&m->alloc_, cap * 3 * sizeof(double));
        n = cj_allocator_alloc(&m->alloc_, cap * 3 * sizeof(double));
        uv = cj_allocator_alloc(&m->alloc_, cap * 2 * sizeof(double));
        if (!p || !n || !uv) {
            cj_allocator_free(&m->alloc_, p);
            cj_allocator_free(&m->alloc_, n);
            cj_allocator_free(&m->alloc_, uv);
            return cj_fail(CJ_ERR_NOMEM, "out of memory growing the mesh to %zu vertices", cap);
        }
        if (m->vertex_count) {
            memcpy(p, m->positions, m->vertex_count * 3 * sizeof(double));
            memcpy(n, m->normals, m->vertex_count * 3 * sizeof(double));
            memcpy(uv, m->uvs, m->vertex_count * 2 * sizeof(double));
        }
        cj_allocator_free(&m->alloc_, m->positions);
        cj_allocator_free(&m->alloc_, m->normals);
        cj_allocator_free(&m->alloc_, m->uvs);
        m->positions = p;
        m->normals = n;
        m->uvs = uv;
        m->vcap_ = cap;
    }
    if (nt > m->tcap_) {
        size_t cap = m->tcap_ ? m->tcap_ : 64;
        while (cap < nt) cap *= 2;
        void *t = m->triangles, *pid = m->triangle_patch;
        uint32_t *nt_ = cj_allocator_alloc(&m->alloc_, cap * 3 * sizeof(uint32_t));
        int32_t *np = cj_allocator_alloc(&m->alloc_, cap * sizeof(int32_t));
        if (!nt_ || !np) {
            cj_allocator_free(&m->alloc_, nt_);
            cj_allocator_free(&m->alloc_, np);
            return cj_fail(CJ_ERR_NOMEM, "out of memory growing the mesh to %zu triangles", cap);
        }
        if (m->triangle_count) {
            memcpy(nt_, t, m->triangle_count * 3 * sizeof(uint32_t));
            memcpy(np, pid, m->triangle_count * sizeof(int32_t));
        }
        cj_allocator_free(&m->alloc_, t);
        cj_allocator_free(&m->alloc_, pid);
        m->triangles = nt_;
        m->triangle_patch = np;
        m->tcap_ = cap;
    }
    return CJ_OK;
}

cj_status cj_mesh_add_vertex(cj_mesh *m, const double position[3], const double normal[3],
                             const double uv[2], uint32_t *index) {
    assert(m != NULL && position != NULL);
    for (int k = 0; k < 3; ++k)
        if (!isfinite(position[k]))
            return cj_fail(CJ_ERR_NONFINITE, "vertex %zu: position coordinate %d is not finite",
                           m->vertex_count, k);
    if (m->vertex_count == m->vcap_) {
        cj_status st = cj_mesh_reserve(m, m->vertex_count + 1, m->triangle_count);
        if (st) return st;
    }
    const size_t i = m->vertex_count++;
    memcpy(m->positions + 3 * i, position, 3 * sizeof(double));
    for (int k = 0; k < 3; ++k) m->normals[3 * i + (size_t)k] = normal ? normal[k] : 0.0;
    m->uvs[2 * i] = uv ? uv[0] : 0.0;
    m->uvs[2 * i + 1] = uv ? uv[1] : 0.0;
    if (index) *index = (uint32_t)i;
    return CJ_OK;
}

cj_status cj_mesh_add_triangle(cj_mesh *m, uint32_t a, uint32_t b, uint32_t c, int32_t patch) {
    assert(m != NULL);
    const uint32_t v[3] = {a, b, c};
    for (int k = 0; k < 3; ++k)
        if (v[k] >= m->vertex_count)
            return cj_fail(CJ_ERR_RANGE, "triangle %zu: vertex index %u >= vertex count %zu",
                           m->triangle_count, v[k], m->vertex_count);
    if (m->triangle_count == m->tcap_) {
        cj_status st = cj_mesh_reserve(m, m->vertex_count, m->triangle_count + 1);
        if (st) return st;
    }
    const size_t t = m->triangle_count++;
    memcpy(m->triangles + 3 * t, v, sizeof v);
    m->triangle_patch[t] = patch;
    return CJ_OK;
}

/* ---- position identification --------------------------------------------------------- */

typedef struct pos_key {
    double x, y, z;
    uint32_t index;
} pos_key;

static int cmp_pos(const void *pa, const void *pb) {
    const pos_key *a = pa, *b = pb;
    if (a->x != b->x) return a->x < b->x ? -1 : 1;
    if (a->y != b->y) return a->y < b->y ? -1 : 1;
    if (a->z != b->z) return a->z < b->z ? -1 : 1;
    return a->index < b->index ? -1 : a->index > b->index;
}

/* rep[i] = smallest index of a vertex with the same position as i (positions compared as
 * doubles). Returns the number of distinct positions, or (size_t)-1 when out of memory. */
static size_t position_classes(const cj_mesh *m, uint32_t *rep) {
    const size_t n = m->vertex_count;
    pos_key *k = malloc((n ? n : 1) * sizeof *k);
    if (!k) return (size_t)-1;
    for (size_t i = 0; i < n; ++i) {
        k[i].x = m->positions[3 * i];
        k[i].y = m->positions[3 * i + 1];
        k[i].z = m->positions[3 * i + 2];
        k[i].index = (uint32_t)i;
    }
    qsort(k, n, sizeof *k, cmp_pos);
    size_t classes = 0;
    for (size_t i = 0; i < n;) {
        size_t j = i + 1;
        while (j < n && k[j].x == k[i].x && k[j].y == k[i].y && k[j].z == k[i].z) ++j;
        for (size_t q = i; q < j; ++q) rep[k[q].index] = k[i].index; /* k[i] is the smallest */
        ++classes;
        i = j;
    }
    free(k);
    return classes;
}

cj_status cj_mesh_weld(cj_mesh *m, size_t *dropped) {
    assert(m != NULL);
    const size_t n = m->vertex_count;
    uint32_t *rep = malloc((n ? n : 1) * sizeof *rep);
    uint32_t *newidx = malloc((n ? n : 1) * sizeof *newidx);
    if (!rep || !newidx || position_classes(m, rep) == (size_t)-1) {
        free(rep);
        free(newidx);
        return cj_fail(CJ_ERR_NOMEM, "out of memory welding a mesh of %zu vertices", n);
    }
    size_t nv = 0;
    for (size_t i = 0; i < n; ++i) {
        if (rep[i] == i) {
            newidx[i] = (uint32_t)nv;
            if (nv != i) {
                memmove(m->positions + 3 * nv, m->positions + 3 * i, 3 * sizeof(double));
                memmove(m->normals + 3 * nv, m->normals + 3 * i, 3 * sizeof(double));
                memmove(m->uvs + 2 * nv, m->uvs + 2 * i, 2 * sizeof(double));
            }
            ++nv;
        }
    }
    for (size_t i = 0; i < n; ++i) newidx[i] = newidx[rep[i]];
    size_t nt = 0, drop = 0;
    for (size_t t = 0; t < m->triangle_count; ++t) {
        uint32_t a = newidx[m->triangles[3 * t]], b = newidx[m->triangles[3 * t + 1]],
                 c = newidx[m->triangles[3 * t + 2]];
        if (a == b || b == c || a == c) {
            ++drop;
            continue;
        }
        m->triangles[3 * nt] = a;
        m->triangles[3 * nt + 1] = b;
        m->triangles[3 * nt + 2] = c;
        m->triangle_patch[nt] = m->triangle_patch[t];
        ++nt;
    }
    m->vertex_count = nv;
    m->triangle_count = nt;
    free(rep);
    free(newidx);
    if (dropped) *dropped = drop;
    return CJ_OK;
}

typedef struct edge_rec {
    uint32_t lo, hi;
    int dir; /* +1 if stored as lo->hi in the triangle, -1 otherwise */
} edge_rec;

static int cmp_edge(const void *pa, const void *pb) {
    const edge_rec *a = pa, *b = pb;
    if (a->lo != b->lo) return a->lo < b->lo ? -1 : 1;
    if (a->hi != b->hi) return a->hi < b->hi ? -1 : 1;
    return (a->dir > b->dir) - (a->dir < b->dir);
}

cj_status cj_mesh_topology_compute(const cj_mesh *m, cj_mesh_topology *out) {
    assert(m != NULL && out != NULL);
    const size_t n = m->vertex_count;
    uint32_t *rep = malloc((n ? n : 1) * sizeof *rep);
    unsigned char *used = calloc(n ? n : 1, 1);
    edge_rec *e = malloc((m->triangle_count ? m->triangle_count : 1) * 3 * sizeof *e);
    if (!rep || !used || !e || position_classes(m, rep) == (size_t)-1) {
        free(rep);
        free(used);
        free(e);
        return cj_fail(CJ_ERR_NOMEM, "out of memory computing mesh topology");
    }
    cj_mesh_topology t;
    memset(&t, 0, sizeof t);
    size_t ne = 0;
    for (size_t f = 0; f < m->triangle_count; ++f) {
        uint32_t v[3];
        for (int k = 0; k < 3; ++k) v[k] = rep[m->triangles[3 * f + (size_t)k]];
        if (v[0] == v[1] || v[1] == v[2] || v[0] == v[2]) continue;
        ++t.faces;
        for (int k = 0; k < 3; ++k) {
            used[v[k]] = 1;
            const uint32_t a = v[k], b = v[(k + 1) % 3];
            e[ne].lo = a < b ? a : b;
            e[ne].hi = a < b ? b : a;
            e[ne].dir = a < b ? 1 : -1;
            ++ne;
        }
    }
    for (size_t i = 0; i < n; ++i) t.vertices += used[i];
    qsort(e, ne, sizeof *e, cmp_edge);
    for (size_t i = 0; i < ne;) {
        size_t j = i + 1, pos = e[i].dir > 0, neg = e[i].dir < 0;
        while (j < ne && e[j].lo == e[i].lo && e[j].hi == e[i].hi) {
            pos += e[j].dir > 0;
            neg += e[j].dir < 0;
            ++j;
        }
        const size_t uses = j - i;
        ++t.edges;
        if (uses == 1) {
            ++t.boundary_edges;
            const double *a = m->positions + 3 * (size_t)e[i].lo,
                         *b = m->positions + 3 * (size_t)e[i].hi;
            t.boundary_length +=
                sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                     (a[2] - b[2]) * (a[2] - b[2]));
        } else if (uses > 2) {
            ++t.nonmanifold_edges;
        } else if (pos != 1 || neg != 1) {
            ++t.misoriented_edges;
        }
        i = j;
    }
    t.euler = (long)t.vertices - (long)t.edges + (long)t.faces;
    free(rep);
    free(used);
    free(e);
    *out = t;
    return CJ_OK;
}

/* ---- export -------------------------------------------------------------------------- */

cj_status cj_mesh_write_obj(const cj_mesh *m, const char *path) {
    assert(m != NULL && path != NULL);
    const size_t n = m->vertex_count;
    uint32_t *rep = malloc((n ? n : 1) * sizeof *rep);
    uint32_t *vid = malloc((n ? n : 1) * sizeof *vid);
    if (!rep || !vid || position_classes(m, rep) == (size_t)-1) {
        free(rep);
        free(vid);
        return cj_fail(CJ_ERR_NOMEM, "out of memory writing '%s'", path);
    }
    cj_atomic_file out;
    cj_status st = cj_atomic_open(&out, path);
    if (st) {
        free(rep);
        free(vid);
        return st;
    }
    FILE *f = out.fp;
    fprintf(f, "# casteljau mesh: %zu vertices, %zu triangles\n", n, m->triangle_count);
    size_t nv = 0;
    for (size_t i = 0; i < n; ++i)
        if (rep[i] == i) {
            vid[i] = (uint32_t)++nv;
            const double *p = m->positions + 3 * i;
            fprintf(f, "v %.17g %.17g %.17g\n", p[0], p[1], p[2]);
        }
    for (size_t i = 0; i < n; ++i) vid[i] = vid[rep[i]];
    for (size_t i = 0; i < n; ++i) fprintf(f, "vt %.17g %.17g\n", m->uvs[2 * i], m->uvs[2 * i + 1]);
    for (size_t i = 0; i < n; ++i) {
        const double *q = m->normals + 3 * i;
        fprintf(f, "vn %.17g %.17g %.17g\n", q[0], q[1], q[2]);
    }
    int have_group = 0;
    int32_t group = 0;
    for (size_t t = 0; t < m->triangle_count; ++t) {
        if (!have_group || m->triangle_patch[t] != group) {
            group = m->triangle_patch[t];
            have_group = 1;
            fprintf(f, "g patch_%d\n", (int)group);
        }
        const uint32_t *v = m->triangles + 3 * t;
        fprintf(f, "f %u/%u/%u %u/%u/%u %u/%u/%u\n", vid[v[0]], v[0] + 1, v[0] + 1, vid[v[1]],
                v[1] + 1, v[1] + 1, vid[v[2]], v[2] + 1, v[2] + 1);
    }
    free(rep);
    free(vid);
    return cj_atomic_commit(&out);
}

static void put_le(FILE *f, const void *src, size_t bytes) {
    unsigned char b[8];
    memcpy(b, src, bytes);
    const uint16_t probe = 1;
    unsigned char first;
    memcpy(&first, &probe, 1);
    if (!first) /* big-endian host: reverse */
        for (size_t i = 0; i < bytes / 2; ++i) {
            unsigned char x = b[i];
            b[i] = b[bytes - 1 - i];
            b[bytes - 1 - i] = x;
        }
    fwrite(b, 1, bytes, f);
}

cj_status cj_mesh_write_ply(const cj_mesh *m, const char *path, int binary) {
    assert(m != NULL && path != NULL);
    cj_atomic_file out;
    cj_status st = cj_atomic_open(&out, path);
    if (st) return st;
    FILE *f = out.fp;
    fprintf(f,
            "ply\nformat %s 1.0\ncomment casteljau mesh\nelement vertex %zu\n"
            "property double x\nproperty double y\nproperty double z\n"
            "property double nx\nproperty double ny\nproperty double nz\n"
            "property double u\nproperty double v\n"
            "element face %zu\nproperty list uchar uint vertex_indices\nend_header\n",
            binary ? "binary_little_endian" : "ascii", m->vertex_count, m->triangle_count);
    for (size_t i = 0; i < m->vertex_count; ++i) {
        const double vals[8] = {m->positions[3 * i],     m->positions[3 * i + 1],
                                m->positions[3 * i + 2], m->normals[3 * i],
                                m->normals[3 * i + 1],   m->normals[3 * i + 2],
                                m->uvs[2 * i],           m->uvs[2 * i + 1]};
        if (binary)
            for (int k = 0; k < 8; ++k) put_le(f, &vals[k], sizeof(double));
        else
            fprintf(f, "%.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g\n", vals[0], vals[1],
                    vals[2], vals[3], vals[4], vals[5], vals[6], vals[7]);
    }
    for (size_t t = 0; t < m->triangle_count; ++t) {
        const uint32_t *v = m->triangles + 3 * t;
        if (binary) {
            const unsigned char three = 3;
            fwrite(&three, 1, 1, f);
            for (int k = 0; k < 3; ++k) put_le(f, &v[k], sizeof(uint32_t));
        } else {
            fprintf(f, "3 %u %u %u\n", v[0], v[1], v[2]);
        }
    }
    return cj_atomic_commit(&out);
}

static int ends_with(const char *s, const char *suffix) {
    size_t a = strlen(s), b = strlen(suffix);
    if (a < b) return 0;
    for (size_t i = 0; i < b; ++i) {
        char c = s[a - b + i];
        if (c >= 'A' && c <= 'Z') c = (char)(c - 'A' + 'a');
        if (c != suffix[i]) return 0;
    }
    return 1;
}

cj_status cj_mesh_write(const cj_mesh *m, const char *path) {
    assert(m != NULL && path != NULL);
    if (ends_with(path, ".obj")) return cj_mesh_write_obj(m, path);
    if (ends_with(path, ".ply")) return cj_mesh_write_ply(m, path, 1);
    return cj_fail(CJ_ERR_ARGUMENT, "output '%s': unknown extension (use .obj or .ply)", path);
}

/* The scene object, which owns deep copies of everything added to it. The plain values it holds
 * (defaults, transforms) are in scene_values.c; validation lives in scene_check.c. */
#include "scene_internal.h"

#include "error_internal.h"

#include <assert.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- memory -------------------------------------------------------------------------------- */

void *cj_scene_alloc_(const cj_scene *s, size_t bytes) {
    if (bytes == 0) bytes = 1;
    return s->alloc.alloc ? s->alloc.alloc(s->alloc.user, bytes) : malloc(bytes);
}

void cj_scene_free_(const cj_scene *s, void *p) {
    if (!p) return;
    if (s->alloc.free)
        s->alloc.free(s->alloc.user, p);
    else
        free(p);
}

char *cj_scene_strdup_(const cj_scene *s, const char *str, int *ok) {
    *ok = 1;
    if (!str) return NULL;
    size_t n = strlen(str) + 1;
    char *d = cj_scene_alloc_(s, n);
    if (!d) {
        *ok = 0;
        return NULL;
    }
    memcpy(d, str, n);
    return d;
}

static void *dup_block(const cj_scene *s, const void *src, size_t bytes, int *ok) {
    if (!src) return NULL;
    void *d = cj_scene_alloc_(s, bytes);
    if (!d) {
        *ok = 0;
        return NULL;
    }
    memcpy(d, src, bytes);
    return d;
}

/* Grows an array of `elem`-byte items to hold one more; the new tail is zeroed. */
static int grow(const cj_scene *s, void **arr, size_t *cap, size_t n, size_t elem) {
    if (n < *cap) return 1;
    size_t nc = *cap ? 2 * *cap : 8;
    char *d = cj_scene_alloc_(s, nc * elem);
    if (!d) return 0;
    if (*arr) memcpy(d, *arr, n * elem);
    memset(d + n * elem, 0, (nc - n) * elem);
    cj_scene_free_(s, *arr);
    *arr = d;
    *cap = nc;
    return 1;
}

/* ---- create / destroy ---------------------------------------------------------------------- */

cj_status cj_scene_create(const cj_allocator *alloc, cj_scene **out) {
    assert(out != NULL);
    assert(!alloc || (alloc->alloc && alloc->free));
    cj_scene *s = alloc ? alloc->alloc(alloc->user, sizeof *s) : malloc(sizeof *s);
    if (!s) return cj_fail(CJ_ERR_NOMEM, "out of memory creating a scene");
    memset(s, 0, sizeof *s);
    if (alloc) s->alloc = *alloc;
    s->camera = cj_camera_defaults();
    s->settings = cj_scene_settings_defaults();
    *out = s;
    return CJ_OK;
}

static void free_geometry(cj_scene *s, size_t i) {
    cj_geometry *g = &s->geoms[i];
    if (g->kind == CJ_GEOM_MESH) cj_mesh_destroy(g->u.mesh);
    for (int k = 0; k < 3; ++k) cj_scene_free_(s, s->gstore[i].block[k]);
    cj_scene_free_(s, s->gstore[i].bspline);
}

void cj_scene_destroy(cj_scene *s) {
    if (!s) return;
    for (size_t i = 0; i < s->ntextures; ++i) {
        cj_scene_free_(s, (void *)s->textures[i].path);
        cj_scene_free_(s, (void *)s->textures[i].texels);
        cj_scene_free_(s, s->texture_sources[i]);
        cj_scene_free_(s, s->texture_names[i]);
    }
    for (size_t i = 0; i < s->nmaterials; ++i) cj_scene_free_(s, s->material_names[i]);
    for (size_t i = 0; i < s->ngeoms; ++i) free_geometry(s, i);
    for (size_t i = 0; i < s->nnodes; ++i) cj_scene_free_(s, (void *)s->nodes[i].name);
    cj_scene_free_(s, s->lights);
    cj_scene_free_(s, s->textures);
    cj_scene_free_(s, s->texture_sources);
    cj_scene_free_(s, s->texture_names);
    cj_scene_free_(s, s->materials);
    cj_scene_free_(s, s->material_names);
    cj_scene_free_(s, s->geoms);
    cj_scene_free_(s, s->gstore);
    cj_scene_free_(s, s->nodes);
    cj_allocator a = s->alloc;
    if (a.free)
        a.free(a.user, s);
    else
        free(s);
}

/* ---- camera and settings ------------------------------------------------------------------- */

cj_status cj_scene_set_camera(cj_scene *s, const cj_camera *cam) {
    assert(s && cam);
    cj_status st = cj_scene_check_camera_(cam, "camera");
    if (st) return st;
    s->camera = *cam;
    return CJ_OK;
}

const cj_camera *cj_scene_get_camera(const cj_scene *s) {
    assert(s);
    return &s->camera;
}

cj_status cj_scene_set_settings(cj_scene *s, const cj_scene_settings *set) {
    assert(s && set);
    cj_status st = cj_scene_check_settings_(set, "settings");
    if (st) return st;
    s->settings = *set;
    return CJ_OK;
}

const cj_scene_settings *cj_scene_get_settings(const cj_scene *s) {
    assert(s);
    return &s->settings;
}

/* ---- lights, textures, materials ----------------------------------------------------------- */

#define PATH_CAP 64

cj_status cj_scene_add_light(cj_scene *s, const cj_light *l, int *index) {
    assert(s && l);
    char path[PATH_CAP];
    snprintf(path, sizeof path, "lights[%zu]", s->nlights);
    cj_status st = cj_scene_check_light_(l, path);
    if (st) return st;
    if (s->nlights >= INT32_MAX ||
        !grow(s, (void **)&s->lights, &s->caplights, s->nlights, sizeof *s->lights))
        return cj_fail(CJ_ERR_NOMEM, "out of memory adding %s", path);
    s->lights[s->nlights] = *l;
    if (index) *index = (int)s->nlights;
    s->nlights++;
    return CJ_OK;
}

cj_status cj_scene_add_texture(cj_scene *s, const cj_texture *t, int *index) {
    assert(s && t);
    char path[PATH_CAP];
    snprintf(path, sizeof path, "textures[%zu]", s->ntextures);
    cj_status st = cj_scene_check_texture_(t, path);
    if (st) return st;
    size_t cap = s->captextures, cap2 = s->captextures, cap3 = s->captextures;
    if (s->ntextures >= INT32_MAX ||
        !grow(s, (void **)&s->texture_sources, &cap2, s->ntextures, sizeof(char *)) ||
        !grow(s, (void **)&s->texture_names, &cap3, s->ntextures, sizeof(char *)) ||
        !grow(s, (void **)&s->textures, &cap, s->ntextures, sizeof *s->textures))
        return cj_fail(CJ_ERR_NOMEM, "out of memory adding %s", path);
    s->captextures = cap;
    cj_texture c = *t;
    int ok = 1;
    c.path = cj_scene_strdup_(s, t->path, &ok);
    c.texels = NULL;
    c.width = c.height = 0;
    if (!ok) return cj_fail(CJ_ERR_NOMEM, "out of memory adding %s", path);
    s->textures[s->ntextures] = c;
    s->texture_sources[s->ntextures] = NULL;
    s->texture_names[s->ntextures] = NULL;
    s->ntextures++;
    /* Texels given with the texture go through the same checks as later ones. */
    if (t->texels && t->kind == CJ_TEX_IMAGE) {
        st = cj_scene_set_texture_pixels(s, (int)s->ntextures - 1, t->width, t->height, t->texels);
        if (st) {
            s->ntextures--;
            cj_scene_free_(s, (void *)c.path);
            return st;
        }
    }
    if (index) *index = (int)s->ntextures - 1;
    return CJ_OK;
}

cj_status cj_scene_set_texture_pixels(cj_scene *s, int index, int width, int height,
                                      const float *rgba) {
    assert(s && rgba);
    if (index < 0 || (size_t)index >= s->ntextures)
        return cj_fail(CJ_ERR_ARGUMENT, "texture index %d names no texture (%zu textures)", index,
                       s->ntextures);
    cj_texture *t = &s->textures[index];
    if (t->kind != CJ_TEX_IMAGE)
        return cj_fail(CJ_ERR_ARGUMENT, "textures[%d] is not an image texture", index);
    if (width < 1 || height < 1 || width > 65535 || height > 65535)
        return cj_fail(CJ_ERR_RANGE, "textures[%d]: size %d x %d out of range 1..65535", index,
                       width, height);
    size_t n = (size_t)width * (size_t)height * 4;
    for (size_t i = 0; i < n; ++i)
        if (!isfinite(rgba[i]))
            return cj_fail(CJ_ERR_NONFINITE, "textures[%d]: texel %zu, channel %zu is not finite",
                           index, i / 4, i % 4);
    int ok = 1;
    float *d = dup_block(s, rgba, n * sizeof(float), &ok);
    if (!ok)
        return cj_fail(CJ_ERR_NOMEM, "out of memory storing the texels of textures[%d]", index);
    cj_scene_free_(s, (void *)t->texels);
    t->texels = d;
    t->width = width;
    t->height = height;
    return CJ_OK;
}

cj_status cj_scene_add_material(cj_scene *s, const cj_material *m, int *index) {
    assert(s && m);
    char path[PATH_CAP];
    snprintf(path, sizeof path, "materials[%zu]", s->nmaterials);
    cj_status st = cj_scene_check_material_(m, s->ntextures, path);
    if (st) return st;
    size_t cap = s->capmaterials, cap2 = s->capmaterials;
    if (s->nmaterials >= INT32_MAX ||
        !grow(s, (void **)&s->material_names, &cap2, s->nmaterials, sizeof(char *)) ||
        !grow(s, (void **)&s->materials, &cap, s->nmaterials, sizeof *s->materials))
        return cj_fail(CJ_ERR_NOMEM, "out of memory adding %s", path);
    s->capmaterials = cap;
    s->materials[s->nmaterials] = *m;
    s->material_names[s->nmaterials] = NULL;
    if (index) *index = (int)s->nmaterials;
    s->nmaterials++;
    return CJ_OK;
}

static cj_status set_name(cj_scene *s, char **slot, const char *name, const char *what) {
    int ok = 1;
    char *d = cj_scene_strdup_(s, name, &ok);
    if (!ok) return cj_fail(CJ_ERR_NOMEM, "out of memory naming %s", what);
    cj_scene_free_(s, *slot);
    *slot = d;
    return CJ_OK;
}

cj_status cj_scene_set_material_name(cj_scene *s, int index, const char *name) {
    assert(s);
    if (index < 0 || (size_t)index >= s->nmaterials)
        return cj_fail(CJ_ERR_ARGUMENT, "material index %d names no material", index);
    return set_name(s, &s->material_names[index], name, "a material");
}

const char *cj_scene_material_name(const cj_scene *s, int index) {
    assert(s && index >= 0 && (size_t)index < s->nmaterials);
    return s->material_names[index];
}

cj_status cj_scene_set_texture_name(cj_scene *s, int index, const char *name) {
    assert(s);
    if (index < 0 || (size_t)index >= s->ntextures)
        return cj_fail(CJ_ERR_ARGUMENT, "texture index %d names no texture", index);
    return set_name(s, &s->texture_names[index], name, "a texture");
}

const char *cj_scene_texture_name(const cj_scene *s, int index) {
    assert(s && index >= 0 && (size_t)index < s->ntextures);
    return s->texture_names[index];
}

cj_status cj_scene_set_texture_source(cj_scene *s, int index, const char *where) {
    assert(s);
    if (index < 0 || (size_t)index >= s->ntextures)
        return cj_fail(CJ_ERR_ARGUMENT, "texture index %d names no texture", index);
    return set_name(s, &s->texture_sources[index], where, "a texture's source");
}

const char *cj_scene_texture_source(const cj_scene *s, int index) {
    assert(s && index >= 0 && (size_t)index < s->ntextures);
    return s->texture_sources[index];
}

/* ---- geometry ------------------------------------------------------------------------------ */

static cj_status copy_mesh(const cj_scene *s, const cj_mesh *src, cj_mesh **out) {
    const cj_allocator *a = s->alloc.alloc ? &s->alloc : NULL;
    cj_mesh *m;
    cj_status st = cj_mesh_create(a, &m);
    if (st) return st;
    st = cj_mesh_reserve(m, src->vertex_count, src->triangle_count);
    if (st) {
        cj_mesh_destroy(m);
        return st;
    }
    size_t nv = src->vertex_count, nt = src->triangle_count;
    if (nv) {
        memcpy(m->positions, src->positions, 3 * nv * sizeof(double));
        memcpy(m->normals, src->normals, 3 * nv * sizeof(double));
        memcpy(m->uvs, src->uvs, 2 * nv * sizeof(double));
    }
    if (nt) {
        memcpy(m->triangles, src->triangles, 3 * nt * sizeof(uint32_t));
        memcpy(m->triangle_patch, src->triangle_patch, nt * sizeof(int32_t));
    }
    m->vertex_count = nv;
    m->triangle_count = nt;
    *out = m;
    return CJ_OK;
}

/* Copies the arrays `g` points to into `store`, rewiring `c` (a copy of g) to them. */
static cj_status deep_copy(const cj_scene *s, const cj_geometry *g, cj_geometry *c,
                           cj_geom_store *store) {
    int ok = 1;
    memset(store, 0, sizeof *store);
    switch (g->kind) {
    case CJ_GEOM_PATCHES: {
        size_t n = g->u.patches.count, npts = 0, nw = 0;
        for (size_t i = 0; i < n; ++i) {
            size_t k = cj_patch_point_count(&g->u.patches.patches[i]);
            npts += 3 * k;
            if (g->u.patches.patches[i].weights) nw += k;
        }
        cj_patch *pa = cj_scene_alloc_(s, n * sizeof *pa);
        double *pts = cj_scene_alloc_(s, npts * sizeof(double));
        double *w = nw ? cj_scene_alloc_(s, nw * sizeof(double)) : NULL;
        store->block[0] = pa;
        store->block[1] = pts;
        store->block[2] = w;
        if (!pa || !pts || (nw && !w)) {
            ok = 0;
            break;
        }
        size_t op = 0, ow = 0;
        for (size_t i = 0; i < n; ++i) {
            const cj_patch *p = &g->u.patches.patches[i];
            size_t k = cj_patch_point_count(p);
            memcpy(pts + op, p->pts, 3 * k * sizeof(double));
            pa[i] = cj_patch_view(p->deg_u, p->deg_v, pts + op, NULL);
            op += 3 * k;
            if (p->weights) {
                memcpy(w + ow, p->weights, k * sizeof(double));
                pa[i].weights = w + ow;
                ow += k;
            }
        }
        c->u.patches.patches = pa;
        break;
    }
    case CJ_GEOM_REVOLUTION: {
        size_t k = (size_t)g->u.revolution.degree + 1;
        store->block[0] = dup_block(s, g->u.revolution.pts, 2 * k * sizeof(double), &ok);
        store->block[1] = dup_block(s, g->u.revolution.weights, k * sizeof(double), &ok);
        c->u.revolution.pts = store->block[0];
        c->u.revolution.weights = store->block[1];
        break;
    }
    case CJ_GEOM_GEN_CYLINDER: {
        size_t k = (size_t)g->u.gen_cylinder.degree + 1;
        store->block[0] = dup_block(s, g->u.gen_cylinder.pts, 2 * k * sizeof(double), &ok);
        store->block[1] = dup_block(s, g->u.gen_cylinder.weights, k * sizeof(double), &ok);
        c->u.gen_cylinder.pts = store->block[0];
        c->u.gen_cylinder.weights = store->block[1];
        break;
    }
    case CJ_GEOM_CURVE: {
        size_t k = g->u.curve.count;
        store->block[0] = dup_block(s, g->u.curve.pts, 3 * k * sizeof(double), &ok);
        store->block[1] = g->u.curve.kind == CJ_CURVE_RATIONAL
                              ? dup_block(s, g->u.curve.weights, k * sizeof(double), &ok)
                              : NULL;
        c->u.curve.pts = store->block[0];
        c->u.curve.weights = store->block[1];
        break;
    }
    case CJ_GEOM_MESH: {
        cj_status st = copy_mesh(s, g->u.mesh, &c->u.mesh);
        if (st) return st;
        break;
    }
    default:
        break;
    }
    if (!ok) {
        for (int k = 0; k < 3; ++k) cj_scene_free_(s, store->block[k]);
        return cj_fail(CJ_ERR_NOMEM, "out of memory copying a geometry");
    }
    return CJ_OK;
}

cj_status cj_scene_add_geometry(cj_scene *s, const cj_geometry *g, int *index) {
    assert(s && g);
    char path[PATH_CAP];
    snprintf(path, sizeof path, "geometries[%zu]", s->ngeoms);
    cj_status st = cj_scene_check_geometry_(g, path);
    if (st) return st;
    size_t cap = s->capgeoms, cap2 = s->capgeoms;
    if (s->ngeoms >= INT32_MAX ||
        !grow(s, (void **)&s->gstore, &cap2, s->ngeoms, sizeof *s->gstore) ||
        !grow(s, (void **)&s->geoms, &cap, s->ngeoms, sizeof *s->geoms))
        return cj_fail(CJ_ERR_NOMEM, "out of memory adding %s", path);
    s->capgeoms = cap;
    cj_geometry c = *g;
    st = deep_copy(s, g, &c, &s->gstore[s->ngeoms]);
    if (st) return st;
    s->geoms[s->ngeoms] = c;
    if (index) *index = (int)s->ngeoms;
    s->ngeoms++;
    return CJ_OK;
}

/* ---- nodes --------------------------------------------------------------------------------- */

cj_status cj_scene_add_node(cj_scene *s, const cj_node *n, int *index) {
    assert(s && n);
    char path[PATH_CAP];
    snprintf(path, sizeof path, "nodes[%zu]", s->nnodes);
    cj_status st = cj_scene_check_node_(s, n, s->nnodes, path);
    if (st) return st;
    if (s->nnodes >= INT32_MAX ||
        !grow(s, (void **)&s->nodes, &s->capnodes, s->nnodes, sizeof *s->nodes))
        return cj_fail(CJ_ERR_NOMEM, "out of memory adding %s", path);
    cj_node c = *n;
    int ok = 1;
    c.name = cj_scene_strdup_(s, n->name, &ok);
    if (!ok) return cj_fail(CJ_ERR_NOMEM, "out of memory adding %s", path);
    c.id = n->geometry >= 0 ? ++s->objects : 0;
    s->nodes[s->nnodes] = c;
    if (index) *index = (int)s->nnodes;
    s->nnodes++;
    return CJ_OK;
}

/* ---- access -------------------------------------------------------------------------------- */

size_t cj_scene_light_count(const cj_scene *s) {
    return s->nlights;
}
size_t cj_scene_texture_count(const cj_scene *s) {
    return s->ntextures;
}
size_t cj_scene_material_count(const cj_scene *s) {
    return s->nmaterials;
}
size_t cj_scene_geometry_count(const cj_scene *s) {
    return s->ngeoms;
}
size_t cj_scene_node_count(const cj_scene *s) {
    return s->nnodes;
}

#define GET(arr, n)                                                                                \
    do {                                                                                           \
        assert(s != NULL);                                                                         \
        return (index >= 0 && (size_t)index < s->n) ? &s->arr[index] : NULL;                       \
    } while (0)

const cj_light *cj_scene_light(const cj_scene *s, int index) {
    GET(lights, nlights);
}
const cj_texture *cj_scene_texture(const cj_scene *s, int index) {
    GET(textures, ntextures);
}
const cj_material *cj_scene_material(const cj_scene *s, int index) {
    GET(materials, nmaterials);
}
const cj_geometry *cj_scene_geometry(const cj_scene *s, int index) {
    GET(geoms, ngeoms);
}
const cj_node *cj_scene_node(const cj_scene *s, int index) {
    GET(nodes, nnodes);
}
cj_light *cj_scene_light_mut(cj_scene *s, int index) {
    GET(lights, nlights);
}
cj_material *cj_scene_material_mut(cj_scene *s, int index) {
    GET(materials, nmaterials);
}
cj_node *cj_scene_node_mut(cj_scene *s, int index) {
    GET(nodes, nnodes);
}
cj_geometry *cj_scene_geometry_mut(cj_scene *s, int index) {
    GET(geoms, ngeoms);
}

cj_status cj_scene_node_world(const cj_scene *s, int index, cj_xform3 *out) {
    assert(s && out);
    if (index < 0 || (size_t)index >= s->nnodes)
        return cj_fail(CJ_ERR_ARGUMENT, "node index %d names no node (%zu nodes)", index,
                       s->nnodes);
    cj_xform3 m = cj_transform_matrix(&s->nodes[index].local);
    /* Parents come earlier, so the walk ends; the guard only protects a mutated hierarchy. */
    int p = s->nodes[index].parent;
    for (size_t steps = 0; p >= 0; ++steps) {
        if ((size_t)p >= s->nnodes || p >= index || steps > s->nnodes)
            return cj_fail(CJ_ERR_ARGUMENT, "nodes[%d].parent %d names no group added before it",
                           index, p);
        cj_xform3 pm = cj_transform_matrix(&s->nodes[p].local);
        m = cj_xform3_compose(&pm, &m);
        index = p;
        p = s->nodes[p].parent;
    }
    *out = m;
    return CJ_OK;
}

int cj_scene_node_shown(const cj_scene *s, int index) {
    assert(s);
    if (index < 0 || (size_t)index >= s->nnodes) return 0;
    for (int i = index; i >= 0; i = s->nodes[i].parent)
        if (!s->nodes[i].visible) return 0;
    return 1;
}

void cj_scene_nodes_shown(const cj_scene *s, unsigned char *shown) {
    assert(s && (shown || !s->nnodes));
    for (size_t i = 0; i < s->nnodes; ++i) {
        const cj_node *nd = &s->nodes[i];
        shown[i] = nd->visible && (nd->parent < 0 || shown[nd->parent]);
    }
}

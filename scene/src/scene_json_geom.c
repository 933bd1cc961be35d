/* The JSON scene reader: geometries (patches, analytic surfaces, quadrics, meshes, curves). */
#include "scene_json_internal.h"

#include "casteljau/mesh_read.h"
#include "casteljau/patchset.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define TRY(x)                                                                                     \
    do {                                                                                           \
        cj_status st_ = (x);                                                                       \
        if (st_) return st_;                                                                       \
    } while (0)

enum {
    G_TEAPOT,
    G_BPT,
    G_PATCHES,
    G_SPHERE,
    G_QUADRIC,
    G_TORUS,
    G_CYLINDER,
    G_PLANAR,
    G_PLANE,
    G_BILINEAR,
    G_REVOLUTION,
    G_GEN_CYLINDER,
    G_MESH,
    G_CURVE,
    G_BSPLINE_SURFACE,
    G_NURBS_SURFACE
};
static const char *const GEOM_TYPES[] = {
    "teapot",   "bpt",    "patches",         "sphere",        "quadric",    "torus",
    "cylinder", "planar", "plane",           "bilinear",      "revolution", "gen_cylinder",
    "mesh",     "curve",  "bspline_surface", "nurbs_surface", NULL};
/* The keys of each type besides "type" (and "name" in the "geometries" list). */
static const char *const GEOM_KEYS[][12] = {
    {NULL},
    {"path", NULL},
    {"patches", NULL},
    {"center", "radius", NULL},
    {"kind", "a", "b", "c", "u0", "u1", "v0", "v1", "lower", NULL},
    {"center", "axis", "major", "minor", NULL},
    {"base", "axis", "radius", "h0", "h1", NULL},
    {"origin", "edge_u", "edge_v", NULL},
    {"origin", "edge_u", "edge_v", NULL},
    {"p00", "p10", "p01", "p11", NULL},
    {"points", "weights", "origin", "axis", NULL},
    {"points", "weights", "origin", "e1", "e2", "dir", "v0", "v1", NULL},
    {"path", "positions", "triangles", "normals", "uvs", "patch_ids", NULL},
    {"kind", "points", "weights", "tension", "continuity", "bias", "closed", "width_px", "color",
     NULL}};

/* Checks obj's keys against "type" (+ "name") + GEOM_KEYS[type]. */
static cj_status geom_keys(const jctx *c, const cJSON *obj, const char *p, int type, int named) {
    const char *keys[16];
    int k = 0;
    keys[k++] = "type";
    if (named) keys[k++] = "name";
    for (int i = 0; GEOM_KEYS[type][i]; ++i) keys[k++] = GEOM_KEYS[type][i];
    keys[k] = NULL;
    return cj_json_object(&c->json, obj, p, keys);
}

/* Every key in the NULL-terminated list must be present. */
static cj_status need(const jctx *c, const cJSON *obj, const char *p, const char *const *keys) {
    for (; *keys; ++keys) {
        const cJSON *n;
        TRY(cj_json_require(&c->json, obj, p, *keys, &n));
    }
    return CJ_OK;
}

/* A constructor of surfaces/ refused the values: its message, prefixed with file, line, path. */
static cj_status ctor_fail(const jctx *c, const cJSON *obj, const char *p, cj_status st) {
    char msg[512];
    snprintf(msg, sizeof msg, "%s", cj_last_error());
    return cj_json_fail(&c->json, obj, 0, st, "%s: %s", p, msg);
}

static cj_status add(jctx *c, const cJSON *obj, const char *p, const cj_geometry *g, int *index) {
    cj_status st = cj_scene_check_geometry_(g, p);
    if (!st) st = cj_scene_add_geometry(c->scene, g, index);
    return st ? cj_json_relabel(&c->json, obj, st) : CJ_OK;
}

/* ---- patches -------------------------------------------------------------------------------- */

static cj_status add_patchset(jctx *c, const cJSON *obj, const cJSON *at, const char *p,
                              const char *file, int *index) {
    cj_patchset *set = NULL;
    cj_status st = cj_patchset_load_bpt(file, NULL, &set);
    if (st) {
        char msg[512];
        snprintf(msg, sizeof msg, "%s", cj_last_error());
        return cj_json_fail(&c->json, at, 0, st, "%s: %s", p, msg);
    }
    cj_geometry g;
    memset(&g, 0, sizeof g);
    g.kind = CJ_GEOM_PATCHES;
    g.u.patches.count = set->count;
    g.u.patches.patches = set->patches;
    st = add(c, obj, p, &g, index);
    cj_patchset_destroy(set);
    return st;
}

static const char *const PATCH_KEYS[] = {"degree", "points", "weights", NULL};

static cj_status read_patches(jctx *c, const cJSON *obj, const char *p, int *index) {
    const cJSON *arr = cJSON_GetObjectItemCaseSensitive(obj, "patches");
    char pa[CJ_JSON_PATH];
    cj_json_join(pa, p, "patches");
    if (!cJSON_IsArray(arr) || cJSON_GetArraySize(arr) < 1)
        return cj_json_fail(&c->json, arr, 0, CJ_ERR_PARSE, "%s must be a non-empty array", pa);
    size_t n = (size_t)cJSON_GetArraySize(arr);
    cj_patch *patches = calloc(n, sizeof *patches);
    double **blocks = calloc(2 * n, sizeof *blocks);
    cj_status st = CJ_OK;
    if (!patches || !blocks) st = cj_fail(CJ_ERR_NOMEM, "%s: out of memory", c->name);
    size_t i = 0;
    for (const cJSON *e = arr->child; e && !st; e = e->next, ++i) {
        char pe[CJ_JSON_PATH], pk[CJ_JSON_PATH];
        cj_json_index(pe, pa, i);
        st = cj_json_object(&c->json, e, pe, PATCH_KEYS);
        const cJSON *dn = NULL, *pn = NULL;
        if (!st) st = cj_json_require(&c->json, e, pe, "degree", &dn);
        if (!st) st = cj_json_require(&c->json, e, pe, "points", &pn);
        if (st) break;
        cj_json_join(pk, pe, "degree");
        double *deg;
        size_t nd;
        st = cj_json_numbers(&c->json, dn, pk, 0, CJ_JSON_GE, 1, 2, &deg, &nd);
        if (st) break;
        int m = (int)deg[0], k = (int)deg[1];
        int ok = deg[0] == m && deg[1] == k && m >= 1 && k >= 1 && m <= CJ_PATCH_MAX_DEGREE &&
                 k <= CJ_PATCH_MAX_DEGREE;
        free(deg);
        if (!ok) {
            st = cj_json_fail(&c->json, dn, 0, CJ_ERR_RANGE, "%s must be two integers in [1, %d]",
                              pk, CJ_PATCH_MAX_DEGREE);
            break;
        }
        size_t want = (size_t)(m + 1) * (size_t)(k + 1), cnt;
        cj_json_join(pk, pe, "points");
        st = cj_json_numbers(&c->json, pn, pk, 3, CJ_JSON_ANY, 0, want, &blocks[2 * i], &cnt);
        if (st) break;
        const cJSON *wn = cJSON_GetObjectItemCaseSensitive(e, "weights");
        if (wn) {
            cj_json_join(pk, pe, "weights");
            st =
                cj_json_numbers(&c->json, wn, pk, 0, CJ_JSON_GT, 0, want, &blocks[2 * i + 1], &cnt);
            if (st) break;
        }
        patches[i] = cj_patch_view(m, k, blocks[2 * i], blocks[2 * i + 1]);
    }
    if (!st) {
        cj_geometry g;
        memset(&g, 0, sizeof g);
        g.kind = CJ_GEOM_PATCHES;
        g.u.patches.count = n;
        g.u.patches.patches = patches;
        st = add(c, obj, p, &g, index);
    }
    if (blocks)
        for (size_t j = 0; j < 2 * n; ++j) free(blocks[j]);
    free(blocks);
    free(patches);
    return st;
}

/* ---- analytic surfaces and quadrics --------------------------------------------------------- */

static const char *const QUADRIC_KINDS[] = {"ellipsoid", "hyperboloid1", "hyperboloid2",
                                            "cone",      "paraboloid",   "hyperbolic_paraboloid",
                                            NULL};
static const char *const QUADRIC_PARAMS[][8] = {
    {"a", "b", "c", NULL},       {"a", "b", "c", "v0", "v1", NULL},
    {"a", "b", "c", "v1", NULL}, {"a", "b", "c", "v0", "v1", NULL},
    {"a", "b", "v1", NULL},      {"a", "b", "u0", "u1", "v0", "v1", NULL}};

static cj_status read_quadric(jctx *c, const cJSON *obj, const char *p, int named, int *index) {
    const cJSON *kn;
    TRY(cj_json_require(&c->json, obj, p, "kind", &kn));
    int kind = 0;
    TRY(cj_json_enum(&c->json, obj, p, "kind", QUADRIC_KINDS, &kind));
    const char *keys[12];
    int k = 0;
    keys[k++] = "type";
    keys[k++] = "kind";
    if (named) keys[k++] = "name";
    for (int i = 0; QUADRIC_PARAMS[kind][i]; ++i) keys[k++] = QUADRIC_PARAMS[kind][i];
    if (kind == CJ_QUADRIC_HYPERBOLOID2) keys[k++] = "lower";
    keys[k] = NULL;
    TRY(cj_json_object(&c->json, obj, p, keys));
    TRY(need(c, obj, p, QUADRIC_PARAMS[kind]));
    double a = 1, b = 1, cc = 1, u0 = 0, u1 = 1, v0 = 0, v1 = 1;
    int lower = 0;
    TRY(cj_json_num(&c->json, obj, p, "a", CJ_JSON_GT, 0, 0, &a));
    TRY(cj_json_num(&c->json, obj, p, "b", CJ_JSON_GT, 0, 0, &b));
    TRY(cj_json_num(&c->json, obj, p, "c", CJ_JSON_GT, 0, 0, &cc));
    TRY(cj_json_num(&c->json, obj, p, "u0", CJ_JSON_ANY, 0, 0, &u0));
    TRY(cj_json_num(&c->json, obj, p, "u1", CJ_JSON_ANY, 0, 0, &u1));
    TRY(cj_json_num(&c->json, obj, p, "v0", CJ_JSON_ANY, 0, 0, &v0));
    TRY(cj_json_num(&c->json, obj, p, "v1", CJ_JSON_ANY, 0, 0, &v1));
    TRY(cj_json_bool(&c->json, obj, p, "lower", &lower));
    cj_geometry g;
    memset(&g, 0, sizeof g);
    g.kind = CJ_GEOM_QUADRIC;
    cj_quadric *q = &g.u.quadric;
    cj_status st = CJ_OK;
    switch (kind) {
    case CJ_QUADRIC_ELLIPSOID:
        st = cj_quadric_ellipsoid(q, a, b, cc);
        break;
    case CJ_QUADRIC_HYPERBOLOID1:
        st = cj_quadric_hyperboloid1(q, a, b, cc, v0, v1);
        break;
    case CJ_QUADRIC_HYPERBOLOID2:
        st = cj_quadric_hyperboloid2(q, a, b, cc, lower, v1);
        break;
    case CJ_QUADRIC_CONE:
        st = cj_quadric_cone(q, a, b, cc, v0, v1);
        break;
    case CJ_QUADRIC_PARABOLOID:
        st = cj_quadric_paraboloid(q, a, b, v1);
        break;
    default:
        st = cj_quadric_hyperbolic_paraboloid(q, a, b, u0, u1, v0, v1);
        break;
    }
    if (st) {
        char msg[512];
        snprintf(msg, sizeof msg, "%s", cj_last_error());
        return cj_json_fail(&c->json, obj, 0, st, "%s: %s", p, msg);
    }
    return add(c, obj, p, &g, index);
}

static const char *const NEED_SPHERE[] = {"radius", NULL};
static const char *const NEED_TORUS[] = {"major", "minor", NULL};
static const char *const NEED_CYLINDER[] = {"radius", NULL};
static const char *const NEED_PLANAR[] = {"edge_u", "edge_v", NULL};
static const char *const NEED_BILINEAR[] = {"p00", "p10", "p01", "p11", NULL};
static const char *const NEED_POINTS[] = {"points", NULL};

/* A planar Bézier profile: points [[x, y], ...] and optional weights. */
static cj_status read_profile(const jctx *c, const cJSON *obj, const char *p, double **pts,
                              double **w, int *degree) {
    char pk[CJ_JSON_PATH];
    cj_json_join(pk, p, "points");
    size_t n, nw;
    TRY(cj_json_numbers(&c->json, cJSON_GetObjectItemCaseSensitive(obj, "points"), pk, 2,
                        CJ_JSON_ANY, 0, 0, pts, &n));
    if (n < 2 || n > 256) {
        free(*pts);
        return cj_json_fail(&c->json, cJSON_GetObjectItemCaseSensitive(obj, "points"), 0,
                            CJ_ERR_RANGE, "%s must have 2 to 256 points (degree 1 to 255)", pk);
    }
    *degree = (int)n - 1;
    *w = NULL;
    const cJSON *wn = cJSON_GetObjectItemCaseSensitive(obj, "weights");
    if (wn) {
        cj_json_join(pk, p, "weights");
        cj_status st = cj_json_numbers(&c->json, wn, pk, 0, CJ_JSON_GT, 0, n, w, &nw);
        if (st) {
            free(*pts);
            return st;
        }
    }
    return CJ_OK;
}

static cj_status read_surface(jctx *c, const cJSON *obj, const char *p, int type, int *index) {
    cj_geometry g;
    memset(&g, 0, sizeof g);
    cj_vec3 zero = cj_v3(0, 0, 0), z = cj_v3(0, 0, 1);
    switch (type) {
    case G_SPHERE:
        TRY(need(c, obj, p, NEED_SPHERE));
        g.kind = CJ_GEOM_SPHERE;
        g.u.sphere.center = zero;
        TRY(cj_json_vec3(&c->json, obj, p, "center", &g.u.sphere.center));
        TRY(cj_json_num(&c->json, obj, p, "radius", CJ_JSON_GT, 0, 0, &g.u.sphere.radius));
        return add(c, obj, p, &g, index);
    case G_TORUS: {
        TRY(need(c, obj, p, NEED_TORUS));
        cj_vec3 center = zero, axis = z;
        double major = 1, minor = 0.25;
        TRY(cj_json_vec3(&c->json, obj, p, "center", &center));
        TRY(cj_json_vec3(&c->json, obj, p, "axis", &axis));
        TRY(cj_json_num(&c->json, obj, p, "major", CJ_JSON_GT, 0, 0, &major));
        TRY(cj_json_num(&c->json, obj, p, "minor", CJ_JSON_GT, 0, 0, &minor));
        g.kind = CJ_GEOM_TORUS;
        cj_status st = cj_torus_init(&g.u.torus, center, axis, major, minor);
        return st ? ctor_fail(c, obj, p, st) : add(c, obj, p, &g, index);
    }
    case G_CYLINDER: {
        TRY(need(c, obj, p, NEED_CYLINDER));
        cj_vec3 base = zero, axis = z;
        double radius = 1, h0 = 0, h1 = 1;
        TRY(cj_json_vec3(&c->json, obj, p, "base", &base));
        TRY(cj_json_vec3(&c->json, obj, p, "axis", &axis));
        TRY(cj_json_num(&c->json, obj, p, "radius", CJ_JSON_GT, 0, 0, &radius));
        TRY(cj_json_num(&c->json, obj, p, "h0", CJ_JSON_ANY, 0, 0, &h0));
        TRY(cj_json_num(&c->json, obj, p, "h1", CJ_JSON_ANY, 0, 0, &h1));
        g.kind = CJ_GEOM_CYLINDER;
        cj_status st = cj_cylinder_init(&g.u.cylinder, base, axis, radius, h0, h1);
        return st ? ctor_fail(c, obj, p, st) : add(c, obj, p, &g, index);
    }
    case G_PLANAR:
    case G_PLANE: {
        TRY(need(c, obj, p, NEED_PLANAR));
        cj_vec3 o = zero, eu = zero, ev = zero;
        TRY(cj_json_vec3(&c->json, obj, p, "origin", &o));
        TRY(cj_json_vec3(&c->json, obj, p, "edge_u", &eu));
        TRY(cj_json_vec3(&c->json, obj, p, "edge_v", &ev));
        g.kind = CJ_GEOM_PLANAR;
        cj_status st = cj_planar_patch_init(&g.u.planar, o, eu, ev);
        return st ? ctor_fail(c, obj, p, st) : add(c, obj, p, &g, index);
    }
    case G_BILINEAR: {
        TRY(need(c, obj, p, NEED_BILINEAR));
        cj_vec3 q[4];
        for (int k = 0; k < 4; ++k) TRY(cj_json_vec3(&c->json, obj, p, NEED_BILINEAR[k], &q[k]));
        g.kind = CJ_GEOM_BILINEAR;
        cj_status st = cj_bilinear_init(&g.u.bilinear, q[0], q[1], q[2], q[3]);
        return st ? ctor_fail(c, obj, p, st) : add(c, obj, p, &g, index);
    }
    case G_REVOLUTION: {
        TRY(need(c, obj, p, NEED_POINTS));
        g.kind = CJ_GEOM_REVOLUTION;
        g.u.revolution.origin = zero;
        g.u.revolution.axis = z;
        TRY(cj_json_vec3(&c->json, obj, p, "origin", &g.u.revolution.origin));
        TRY(cj_json_vec3(&c->json, obj, p, "axis", &g.u.revolution.axis));
        double *pts, *w;
        TRY(read_profile(c, obj, p, &pts, &w, &g.u.revolution.degree));
        g.u.revolution.pts = pts;
        g.u.revolution.weights = w;
        cj_status st = add(c, obj, p, &g, index);
        free(pts);
        free(w);
        return st;
    }
    default: { /* G_GEN_CYLINDER */
        TRY(need(c, obj, p, NEED_POINTS));
        g.kind = CJ_GEOM_GEN_CYLINDER;
        g.u.gen_cylinder.origin = zero;
        g.u.gen_cylinder.e1 = cj_v3(1, 0, 0);
        g.u.gen_cylinder.e2 = cj_v3(0, 1, 0);
        g.u.gen_cylinder.dir = z;
        g.u.gen_cylinder.v0 = 0;
        g.u.gen_cylinder.v1 = 1;
        TRY(cj_json_vec3(&c->json, obj, p, "origin", &g.u.gen_cylinder.origin));
        TRY(cj_json_vec3(&c->json, obj, p, "e1", &g.u.gen_cylinder.e1));
        TRY(cj_json_vec3(&c->json, obj, p, "e2", &g.u.gen_cylinder.e2));
        TRY(cj_json_vec3(&c->json, obj, p, "dir", &g.u.gen_cylinder.dir));
        TRY(cj_json_num(&c->json, obj, p, "v0", CJ_JSON_ANY, 0, 0, &g.u.gen_cylinder.v0));
        TRY(cj_json_num(&c->json, obj, p, "v1", CJ_JSON_ANY, 0, 0, &g.u.gen_cylinder.v1));
        double *pts, *w;
        TRY(read_profile(c, obj, p, &pts, &w, &g.u.gen_cylinder.degree));
        g.u.gen_cylinder.pts = pts;
        g.u.gen_cylinder.weights = w;
        cj_status st = add(c, obj, p, &g, index);
        free(pts);
        free(w);
        return st;
    }
    }
}

/* ---- meshes --------------------------------------------------------------------------------- */

static cj_status inline_mesh(const jctx *c, const cJSON *obj, const char *p, cj_mesh *m) {
    const char *const need_keys[] = {"positions", "triangles", NULL};
    TRY(need(c, obj, p, need_keys));
    char pk[CJ_JSON_PATH];
    double *pos = NULL, *tri = NULL, *nrm = NULL, *uv = NULL, *pid = NULL;
    size_t nv = 0, nt = 0, k;
    cj_status st;
    cj_json_join(pk, p, "positions");
    st = cj_json_numbers(&c->json, cJSON_GetObjectItemCaseSensitive(obj, "positions"), pk, 3,
                         CJ_JSON_ANY, 0, 0, &pos, &nv);
    if (!st) {
        cj_json_join(pk, p, "triangles");
        st = cj_json_numbers(&c->json, cJSON_GetObjectItemCaseSensitive(obj, "triangles"), pk, 3,
                             CJ_JSON_ANY, 0, 0, &tri, &nt);
    }
    const cJSON *nn = cJSON_GetObjectItemCaseSensitive(obj, "normals");
    if (!st && nn) {
        cj_json_join(pk, p, "normals");
        st = cj_json_numbers(&c->json, nn, pk, 3, CJ_JSON_ANY, 0, nv, &nrm, &k);
    }
    const cJSON *un = cJSON_GetObjectItemCaseSensitive(obj, "uvs");
    if (!st && un) {
        cj_json_join(pk, p, "uvs");
        st = cj_json_numbers(&c->json, un, pk, 2, CJ_JSON_ANY, 0, nv, &uv, &k);
    }
    const cJSON *pn = cJSON_GetObjectItemCaseSensitive(obj, "patch_ids");
    if (!st && pn) {
        cj_json_join(pk, p, "patch_ids");
        st = cj_json_numbers(&c->json, pn, pk, 0, CJ_JSON_ANY, 0, nt, &pid, &k);
        for (size_t t = 0; !st && t < nt; ++t)
            if (pid[t] != floor(pid[t]) || fabs(pid[t]) > 2147483647.0)
                st = cj_json_fail(&c->json, pn, 0, CJ_ERR_RANGE, "%s[%zu] must be a 32-bit integer",
                                  pk, t);
    }
    if (!st && nv > CJ_MESH_MAX_VERTICES)
        st = cj_json_fail(&c->json, obj, 0, CJ_ERR_RANGE, "%s: too many vertices", p);
    if (!st) st = cj_mesh_reserve(m, nv, nt);
    for (size_t i = 0; i < nv && !st; ++i)
        st = cj_mesh_add_vertex(m, pos + 3 * i, nrm ? nrm + 3 * i : NULL, uv ? uv + 2 * i : NULL,
                                NULL);
    const cJSON *te = cJSON_GetObjectItemCaseSensitive(obj, "triangles");
    const cJSON *row = te ? te->child : NULL;
    for (size_t t = 0; t < nt && !st; ++t, row = row->next) {
        uint32_t v[3];
        const cJSON *x = row->child;
        for (int j = 0; j < 3; ++j, x = x->next) {
            double d = tri[3 * t + (size_t)j];
            if (d != floor(d) || d < 0 || d >= (double)nv) {
                cj_json_join(pk, p, "triangles");
                st = cj_json_fail(&c->json, x, 0, CJ_ERR_RANGE,
                                  "%s[%zu][%d] = %g names no vertex (%zu vertices)", pk, t, j, d,
                                  nv);
                break;
            }
            v[j] = (uint32_t)d;
        }
        if (!st) st = cj_mesh_add_triangle(m, v[0], v[1], v[2], pid ? (int32_t)pid[t] : 0);
    }
    if (!st && !nrm) cj_mesh_compute_normals(m);
    free(pos);
    free(tri);
    free(nrm);
    free(uv);
    free(pid);
    return st;
}

static cj_status read_mesh(jctx *c, const cJSON *obj, const char *p, int *index) {
    const cJSON *pn = cJSON_GetObjectItemCaseSensitive(obj, "path");
    cj_mesh *m = NULL;
    cj_status st;
    if (pn) {
        if (cJSON_GetObjectItemCaseSensitive(obj, "positions") ||
            cJSON_GetObjectItemCaseSensitive(obj, "triangles") ||
            cJSON_GetObjectItemCaseSensitive(obj, "normals") ||
            cJSON_GetObjectItemCaseSensitive(obj, "uvs") ||
            cJSON_GetObjectItemCaseSensitive(obj, "patch_ids"))
            return cj_json_fail(&c->json, pn, 1, CJ_ERR_PARSE,
                                "%s: give either \"path\" or inline mesh data, not both", p);
        const char *rel = NULL;
        TRY(cj_json_string(&c->json, obj, p, "path", &rel));
        char file[4096];
        char pk[CJ_JSON_PATH];
        cj_json_join(pk, p, "path");
        TRY(cj_json_resolve(&c->json, c->base_dir, pn, pk, rel, file, sizeof file));
        st = cj_mesh_read(file, NULL, &m);
        if (st) {
            char msg[512];
            snprintf(msg, sizeof msg, "%s", cj_last_error());
            return cj_json_fail(&c->json, pn, 0, st, "%s: %s", pk, msg);
        }
    } else {
        st = cj_mesh_create(NULL, &m);
        if (st) return st;
        st = inline_mesh(c, obj, p, m);
        if (st) {
            cj_mesh_destroy(m);
            return st;
        }
    }
    cj_geometry g;
    memset(&g, 0, sizeof g);
    g.kind = CJ_GEOM_MESH;
    g.u.mesh = m;
    st = add(c, obj, p, &g, index);
    cj_mesh_destroy(m);
    return st;
}

/* ---- curves --------------------------------------------------------------------------------- */

static const char *const CURVE_KINDS[] = {
    "bezier", "rational", "catmull-rom", "centripetal", "chordal", "kochanek-bartels", NULL};

static cj_status read_curve(jctx *c, const cJSON *obj, const char *p, int named, int *index) {
    const cJSON *kn;
    TRY(cj_json_require(&c->json, obj, p, "kind", &kn));
    int kind = 0;
    TRY(cj_json_enum(&c->json, obj, p, "kind", CURVE_KINDS, &kind));
    const char *keys[14];
    int k = 0;
    keys[k++] = "type";
    keys[k++] = "kind";
    keys[k++] = "points";
    keys[k++] = "width_px";
    keys[k++] = "color";
    if (named) keys[k++] = "name";
    if (kind == 1) keys[k++] = "weights";
    if (kind >= 2) {
        keys[k++] = "tension";
        keys[k++] = "closed";
    }
    if (kind == 5) {
        keys[k++] = "continuity";
        keys[k++] = "bias";
    }
    keys[k] = NULL;
    TRY(cj_json_object(&c->json, obj, p, keys));
    const char *const need_rational[] = {"points", "weights", NULL};
    TRY(need(c, obj, p, kind == 1 ? need_rational : NEED_POINTS));
    cj_geometry g;
    memset(&g, 0, sizeof g);
    g.kind = CJ_GEOM_CURVE;
    g.u.curve.kind = kind == 0 ? CJ_CURVE_BEZIER : kind == 1 ? CJ_CURVE_RATIONAL : CJ_CURVE_SPLINE;
    g.u.curve.spline = kind >= 2 ? (cj_spline_kind)(kind - 2) : CJ_SPLINE_CATMULL_ROM;
    g.u.curve.tension = kind == 5 ? 0.0 : 0.5;
    g.u.curve.width_px = 1.0;
    g.u.curve.color = cj_rgb_make(1, 1, 1);
    TRY(cj_json_num(&c->json, obj, p, "tension", CJ_JSON_ANY, 0, 0, &g.u.curve.tension));
    TRY(cj_json_num(&c->json, obj, p, "continuity", CJ_JSON_ANY, 0, 0, &g.u.curve.continuity));
    TRY(cj_json_num(&c->json, obj, p, "bias", CJ_JSON_ANY, 0, 0, &g.u.curve.bias));
    TRY(cj_json_bool(&c->json, obj, p, "closed", &g.u.curve.closed));
    TRY(cj_json_num(&c->json, obj, p, "width_px", CJ_JSON_GE, 1, 0, &g.u.curve.width_px));
    TRY(cj_json_rgb(&c->json, obj, p, "color", -1, &g.u.curve.color));
    char pk[CJ_JSON_PATH];
    cj_json_join(pk, p, "points");
    double *pts = NULL, *w = NULL;
    size_t n, nw;
    TRY(cj_json_numbers(&c->json, cJSON_GetObjectItemCaseSensitive(obj, "points"), pk, 3,
                        CJ_JSON_ANY, 0, 0, &pts, &n));
    cj_status st = CJ_OK;
    if (kind <= 1 && (n < 2 || n > 256))
        st = cj_json_fail(&c->json, cJSON_GetObjectItemCaseSensitive(obj, "points"), 0,
                          CJ_ERR_RANGE, "%s must have 2 to 256 points (degree 1 to 255)", pk);
    if (!st && kind == 1) {
        cj_json_join(pk, p, "weights");
        st = cj_json_numbers(&c->json, cJSON_GetObjectItemCaseSensitive(obj, "weights"), pk, 0,
                             CJ_JSON_GT, 0, n, &w, &nw);
    }
    if (!st) {
        g.u.curve.count = n;
        g.u.curve.degree = kind <= 1 ? (int)n - 1 : 3;
        g.u.curve.pts = pts;
        g.u.curve.weights = w;
        st = add(c, obj, p, &g, index);
    }
    free(pts);
    free(w);
    return st;
}

/* ---- dispatch ------------------------------------------------------------------------------- */

cj_status cj_json_read_geometry_(jctx *c, const cJSON *obj, const char *p, int *index) {
    if (!cJSON_IsObject(obj))
        return cj_json_fail(&c->json, obj, 0, CJ_ERR_PARSE,
                            "%s must be a geometry object or the name of one in geometries", p);
    const int named = !strncmp(p, "geometries[", 11);
    const cJSON *tn;
    TRY(cj_json_require(&c->json, obj, p, "type", &tn));
    int type = 0;
    TRY(cj_json_enum(&c->json, obj, p, "type", GEOM_TYPES, &type));
    if (type == G_QUADRIC) return read_quadric(c, obj, p, named, index);
    if (type == G_CURVE) return read_curve(c, obj, p, named, index);
    if (type == G_BSPLINE_SURFACE || type == G_NURBS_SURFACE)
        return cj_json_read_bspline_surface_(c, obj, p, named, type == G_NURBS_SURFACE, index);
    TRY(geom_keys(c, obj, p, type, named));
    switch (type) {
    case G_TEAPOT:
        if (!c->teapot_path)
            return cj_json_fail(&c->json, tn, 0, CJ_ERR_UNSUPPORTED,
                                "%s: the teapot's data file is not known here "
                                "(cj_scene_json_options.teapot_path)",
                                p);
        return add_patchset(c, obj, tn, p, c->teapot_path, index);
    case G_BPT: {
        const cJSON *pn;
        TRY(cj_json_require(&c->json, obj, p, "path", &pn));
        const char *rel = NULL;
        TRY(cj_json_string(&c->json, obj, p, "path", &rel));
        char file[4096], pk[CJ_JSON_PATH];
        cj_json_join(pk, p, "path");
        TRY(cj_json_resolve(&c->json, c->base_dir, pn, pk, rel, file, sizeof file));
        return add_patchset(c, obj, pn, pk, file, index);
    }
    case G_PATCHES:
        TRY(need(c, obj, p, GEOM_KEYS[G_PATCHES]));
        return read_patches(c, obj, p, index);
    case G_MESH:
        return read_mesh(c, obj, p, index);
    default:
        return read_surface(c, obj, p, type, index);
    }
}

/* The JSON scene reader: the geometry dispatch, patches, analytic surfaces and quadrics (meshes and
 * curves: scene_json_mesh.c; B-spline surfaces: scene_json_bspline.c). */
#include "scene_json_internal.h"

#include "casteljau/patchset.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

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

/* A constructor of surfaces/ refused the values: its message, prefixed with file, line, path. */
static cj_status ctor_fail(const jctx *c, const cJSON *obj, const char *p, cj_status st) {
    char msg[512];
    snprintf(msg, sizeof msg, "%s", cj_last_error());
    return cj_json_fail(&c->json, obj, 0, st, "%s: %s", p, msg);
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
    st = cj_json_geom_add_(c, obj, p, &g, index);
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
        st = cj_json_geom_add_(c, obj, p, &g, index);
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
    CJ_JSON_TRY(cj_json_require(&c->json, obj, p, "kind", &kn));
    int kind = 0;
    CJ_JSON_TRY(cj_json_enum(&c->json, obj, p, "kind", QUADRIC_KINDS, &kind));
    const char *keys[12];
    int k = 0;
    keys[k++] = "type";
    keys[k++] = "kind";
    if (named) keys[k++] = "name";
    for (int i = 0; QUADRIC_PARAMS[kind][i]; ++i) keys[k++] = QUADRIC_PARAMS[kind][i];
    if (kind == CJ_QUADRIC_HYPERBOLOID2) keys[k++] = "lower";
    keys[k] = NULL;
    CJ_JSON_TRY(cj_json_object(&c->json, obj, p, keys));
    CJ_JSON_TRY(cj_json_geom_need_(c, obj, p, QUADRIC_PARAMS[kind]));
    double a = 1, b = 1, cc = 1, u0 = 0, u1 = 1, v0 = 0, v1 = 1;
    int lower = 0;
    CJ_JSON_TRY(cj_json_num(&c->json, obj, p, "a", CJ_JSON_GT, 0, 0, &a));
    CJ_JSON_TRY(cj_json_num(&c->json, obj, p, "b", CJ_JSON_GT, 0, 0, &b));
    CJ_JSON_TRY(cj_json_num(&c->json, obj, p, "c", CJ_JSON_GT, 0, 0, &cc));
    CJ_JSON_TRY(cj_json_num(&c->json, obj, p, "u0", CJ_JSON_ANY, 0, 0, &u0));
    CJ_JSON_TRY(cj_json_num(&c->json, obj, p, "u1", CJ_JSON_ANY, 0, 0, &u1));
    CJ_JSON_TRY(cj_json_num(&c->json, obj, p, "v0", CJ_JSON_ANY, 0, 0, &v0));
    CJ_JSON_TRY(cj_json_num(&c->json, obj, p, "v1", CJ_JSON_ANY, 0, 0, &v1));
    CJ_JSON_TRY(cj_json_bool(&c->json, obj, p, "lower", &lower));
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
    return cj_json_geom_add_(c, obj, p, &g, index);
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
    CJ_JSON_TRY(cj_json_numbers(&c->json, cJSON_GetObjectItemCaseSensitive(obj, "points"), pk, 2,
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
        CJ_JSON_TRY(cj_json_geom_need_(c, obj, p, NEED_SPHERE));
        g.kind = CJ_GEOM_SPHERE;
        g.u.sphere.center = zero;
        CJ_JSON_TRY(cj_json_vec3(&c->json, obj, p, "center", &g.u.sphere.center));
        CJ_JSON_TRY(cj_json_num(&c->json, obj, p, "radius", CJ_JSON_GT, 0, 0, &g.u.sphere.radius));
        return cj_json_geom_add_(c, obj, p, &g, index);
    case G_TORUS: {
        CJ_JSON_TRY(cj_json_geom_need_(c, obj, p, NEED_TORUS));
        cj_vec3 center = zero, axis = z;
        double major = 1, minor = 0.25;
        CJ_JSON_TRY(cj_json_vec3(&c->json, obj, p, "center", &center));
        CJ_JSON_TRY(cj_json_vec3(&c->json, obj, p, "axis", &axis));
        CJ_JSON_TRY(cj_json_num(&c->json, obj, p, "major", CJ_JSON_GT, 0, 0, &major));
        CJ_JSON_TRY(cj_json_num(&c->json, obj, p, "minor", CJ_JSON_GT, 0, 0, &minor));
        g.kind = CJ_GEOM_TORUS;
        cj_status st = cj_torus_init(&g.u.torus, center, axis, major, minor);
        return st ? ctor_fail(c, obj, p, st) : cj_json_geom_add_(c, obj, p, &g, index);
    }
    case G_CYLINDER: {
        CJ_JSON_TRY(cj_json_geom_need_(c, obj, p, NEED_CYLINDER));
        cj_vec3 base = zero, axis = z;
        double radius = 1, h0 = 0, h1 = 1;
        CJ_JSON_TRY(cj_json_vec3(&c->json, obj, p, "base", &base));
        CJ_JSON_TRY(cj_json_vec3(&c->json, obj, p, "axis", &axis));
        CJ_JSON_TRY(cj_json_num(&c->json, obj, p, "radius", CJ_JSON_GT, 0, 0, &radius));
        CJ_JSON_TRY(cj_json_num(&c->json, obj, p, "h0", CJ_JSON_ANY, 0, 0, &h0));
        CJ_JSON_TRY(cj_json_num(&c->json, obj, p, "h1", CJ_JSON_ANY, 0, 0, &h1));
        g.kind = CJ_GEOM_CYLINDER;
        cj_status st = cj_cylinder_init(&g.u.cylinder, base, axis, radius, h0, h1);
        return st ? ctor_fail(c, obj, p, st) : cj_json_geom_add_(c, obj, p, &g, index);
    }
    case G_PLANAR:
    case G_PLANE: {
        CJ_JSON_TRY(cj_json_geom_need_(c, obj, p, NEED_PLANAR));
        cj_vec3 o = zero, eu = zero, ev = zero;
        CJ_JSON_TRY(cj_json_vec3(&c->json, obj, p, "origin", &o));
        CJ_JSON_TRY(cj_json_vec3(&c->json, obj, p, "edge_u", &eu));
        CJ_JSON_TRY(cj_json_vec3(&c->json, obj, p, "edge_v", &ev));
        g.kind = CJ_GEOM_PLANAR;
        cj_status st = cj_planar_patch_init(&g.u.planar, o, eu, ev);
        return st ? ctor_fail(c, obj, p, st) : cj_json_geom_add_(c, obj, p, &g, index);
    }
    case G_BILINEAR: {
        CJ_JSON_TRY(cj_json_geom_need_(c, obj, p, NEED_BILINEAR));
        cj_vec3 q[4];
        for (int k = 0; k < 4; ++k)
            CJ_JSON_TRY(cj_json_vec3(&c->json, obj, p, NEED_BILINEAR[k], &q[k]));
        g.kind = CJ_GEOM_BILINEAR;
        cj_status st = cj_bilinear_init(&g.u.bilinear, q[0], q[1], q[2], q[3]);
        return st ? ctor_fail(c, obj, p, st) : cj_json_geom_add_(c, obj, p, &g, index);
    }
    case G_REVOLUTION: {
        CJ_JSON_TRY(cj_json_geom_need_(c, obj, p, NEED_POINTS));
        g.kind = CJ_GEOM_REVOLUTION;
        g.u.revolution.origin = zero;
        g.u.revolution.axis = z;
        CJ_JSON_TRY(cj_json_vec3(&c->json, obj, p, "origin", &g.u.revolution.origin));
        CJ_JSON_TRY(cj_json_vec3(&c->json, obj, p, "axis", &g.u.revolution.axis));
        double *pts, *w;
        CJ_JSON_TRY(read_profile(c, obj, p, &pts, &w, &g.u.revolution.degree));
        g.u.revolution.pts = pts;
        g.u.revolution.weights = w;
        cj_status st = cj_json_geom_add_(c, obj, p, &g, index);
        free(pts);
        free(w);
        return st;
    }
    default: { /* G_GEN_CYLINDER */
        CJ_JSON_TRY(cj_json_geom_need_(c, obj, p, NEED_POINTS));
        g.kind = CJ_GEOM_GEN_CYLINDER;
        g.u.gen_cylinder.origin = zero;
        g.u.gen_cylinder.e1 = cj_v3(1, 0, 0);
        g.u.gen_cylinder.e2 = cj_v3(0, 1, 0);
        g.u.gen_cylinder.dir = z;
        g.u.gen_cylinder.v0 = 0;
        g.u.gen_cylinder.v1 = 1;
        CJ_JSON_TRY(cj_json_vec3(&c->json, obj, p, "origin", &g.u.gen_cylinder.origin));
        CJ_JSON_TRY(cj_json_vec3(&c->json, obj, p, "e1", &g.u.gen_cylinder.e1));
        CJ_JSON_TRY(cj_json_vec3(&c->json, obj, p, "e2", &g.u.gen_cylinder.e2));
        CJ_JSON_TRY(cj_json_vec3(&c->json, obj, p, "dir", &g.u.gen_cylinder.dir));
        CJ_JSON_TRY(cj_json_num(&c->json, obj, p, "v0", CJ_JSON_ANY, 0, 0, &g.u.gen_cylinder.v0));
        CJ_JSON_TRY(cj_json_num(&c->json, obj, p, "v1", CJ_JSON_ANY, 0, 0, &g.u.gen_cylinder.v1));
        double *pts, *w;
        CJ_JSON_TRY(read_profile(c, obj, p, &pts, &w, &g.u.gen_cylinder.degree));
        g.u.gen_cylinder.pts = pts;
        g.u.gen_cylinder.weights = w;
        cj_status st = cj_json_geom_add_(c, obj, p, &g, index);
        free(pts);
        free(w);
        return st;
    }
    }
}

/* ---- dispatch ------------------------------------------------------------------------------- */

cj_status cj_json_read_geometry_(jctx *c, const cJSON *obj, const char *p, int *index) {
    if (!cJSON_IsObject(obj))
        return cj_json_fail(&c->json, obj, 0, CJ_ERR_PARSE,
                            "%s must be a geometry object or the name of one in geometries", p);
    const int named = !strncmp(p, "geometries[", 11);
    const cJSON *tn;
    CJ_JSON_TRY(cj_json_require(&c->json, obj, p, "type", &tn));
    int type = 0;
    CJ_JSON_TRY(cj_json_enum(&c->json, obj, p, "type", GEOM_TYPES, &type));
    if (type == G_QUADRIC) return read_quadric(c, obj, p, named, index);
    if (type == G_CURVE) return cj_json_read_curve_(c, obj, p, named, index);
    if (type == G_BSPLINE_SURFACE || type == G_NURBS_SURFACE)
        return cj_json_read_bspline_surface_(c, obj, p, named, index);
    CJ_JSON_TRY(geom_keys(c, obj, p, type, named));
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
        CJ_JSON_TRY(cj_json_require(&c->json, obj, p, "path", &pn));
        const char *rel = NULL;
        CJ_JSON_TRY(cj_json_string(&c->json, obj, p, "path", &rel));
        char file[4096], pk[CJ_JSON_PATH];
        cj_json_join(pk, p, "path");
        CJ_JSON_TRY(cj_json_resolve(&c->json, c->base_dir, pn, pk, rel, file, sizeof file));
        return add_patchset(c, obj, pn, pk, file, index);
    }
    case G_PATCHES:
        CJ_JSON_TRY(cj_json_geom_need_(c, obj, p, GEOM_KEYS[G_PATCHES]));
        return read_patches(c, obj, p, index);
    case G_MESH:
        return cj_json_read_mesh_(c, obj, p, index);
    default:
        return read_surface(c, obj, p, type, index);
    }
}

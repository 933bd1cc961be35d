/* The JSON scene reader: meshes (a mesh file or inline data) and curves (Bézier, rational,
 * Catmull-Rom family), called by the geometry dispatch (scene_json_geom.c). */
#include "scene_json_internal.h"

#include "casteljau/mesh_read.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- meshes --------------------------------------------------------------------------------- */

static cj_status inline_mesh(const jctx *c, const cJSON *obj, const char *p, cj_mesh *m) {
    const char *const need_keys[] = {"positions", "triangles", NULL};
    CJ_JSON_TRY(cj_json_geom_need_(c, obj, p, need_keys));
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

cj_status cj_json_read_mesh_(jctx *c, const cJSON *obj, const char *p, int *index) {
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
        CJ_JSON_TRY(cj_json_string(&c->json, obj, p, "path", &rel));
        char file[4096];
        char pk[CJ_JSON_PATH];
        cj_json_join(pk, p, "path");
        CJ_JSON_TRY(cj_json_resolve(&c->json, c->base_dir, pn, pk, rel, file, sizeof file));
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
    st = cj_json_geom_add_(c, obj, p, &g, index);
    cj_mesh_destroy(m);
    return st;
}

/* ---- curves --------------------------------------------------------------------------------- */

static const char *const CURVE_KINDS[] = {
    "bezier", "rational", "catmull-rom", "centripetal", "chordal", "kochanek-bartels", NULL};

cj_status cj_json_read_curve_(jctx *c, const cJSON *obj, const char *p, int named, int *index) {
    const cJSON *kn;
    CJ_JSON_TRY(cj_json_require(&c->json, obj, p, "kind", &kn));
    int kind = 0;
    CJ_JSON_TRY(cj_json_enum(&c->json, obj, p, "kind", CURVE_KINDS, &kind));
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
    CJ_JSON_TRY(cj_json_object(&c->json, obj, p, keys));
    const char *const need_rational[] = {"points", "weights", NULL};
    const char *const need_points[] = {"points", NULL};
    CJ_JSON_TRY(cj_json_geom_need_(c, obj, p, kind == 1 ? need_rational : need_points));
    cj_geometry g;
    memset(&g, 0, sizeof g);
    g.kind = CJ_GEOM_CURVE;
    g.u.curve.kind = kind == 0 ? CJ_CURVE_BEZIER : kind == 1 ? CJ_CURVE_RATIONAL : CJ_CURVE_SPLINE;
    g.u.curve.spline = kind >= 2 ? (cj_spline_kind)(kind - 2) : CJ_SPLINE_CATMULL_ROM;
    g.u.curve.tension = kind == 5 ? 0.0 : 0.5;
    g.u.curve.width_px = 1.0;
    g.u.curve.color = cj_rgb_make(1, 1, 1);
    CJ_JSON_TRY(cj_json_num(&c->json, obj, p, "tension", CJ_JSON_ANY, 0, 0, &g.u.curve.tension));
    CJ_JSON_TRY(
        cj_json_num(&c->json, obj, p, "continuity", CJ_JSON_ANY, 0, 0, &g.u.curve.continuity));
    CJ_JSON_TRY(cj_json_num(&c->json, obj, p, "bias", CJ_JSON_ANY, 0, 0, &g.u.curve.bias));
    CJ_JSON_TRY(cj_json_bool(&c->json, obj, p, "closed", &g.u.curve.closed));
    CJ_JSON_TRY(cj_json_num(&c->json, obj, p, "width_px", CJ_JSON_GE, 1, 0, &g.u.curve.width_px));
    CJ_JSON_TRY(cj_json_rgb(&c->json, obj, p, "color", -1, &g.u.curve.color));
    char pk[CJ_JSON_PATH];
    cj_json_join(pk, p, "points");
    double *pts = NULL, *w = NULL;
    size_t n, nw;
    CJ_JSON_TRY(cj_json_numbers(&c->json, cJSON_GetObjectItemCaseSensitive(obj, "points"), pk, 3,
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
        st = cj_json_geom_add_(c, obj, p, &g, index);
    }
    free(pts);
    free(w);
    return st;
}

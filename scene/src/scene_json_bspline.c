/* The scene reader's B-spline / NURBS surfaces: {"type": "bspline_surface" | "nurbs_surface",
 * "degree": [p, q], "size": [nu, nv], "points": [[x, y, z], ...] (nu*nv, u fastest),
 * "knots_u": [...], "knots_v": [...] (optional: clamped uniform on [0, 1]), "weights": [...]
 * (required for nurbs_surface, refused for bspline_surface)}. The surface is converted to its
 * Bézier patches at load (cj_bspline_surface_to_patches), so it is a "patches" geometry for
 * every renderer, the tracer and tessellation, and the scene keeps its B-spline form
 * (casteljau/scene_bspline.h) for editors and for cj_scene_save_json. */
#include "scene_json_internal.h"
#include "scene_internal.h"

#include "casteljau/bspline_surface.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define TRY(x)                                                                                     \
    do {                                                                                           \
        cj_status st_ = (x);                                                                       \
        if (st_) return st_;                                                                       \
    } while (0)

cj_status cj_json_read_bspline_surface_(jctx *c, const cJSON *obj, const char *p, int named,
                                        int nurbs, int *index) {
    const char *keys[10];
    int k = 0;
    keys[k++] = "type";
    if (named) keys[k++] = "name";
    keys[k++] = "degree";
    keys[k++] = "size";
    keys[k++] = "points";
    keys[k++] = "knots_u";
    keys[k++] = "knots_v";
    if (nurbs) keys[k++] = "weights";
    keys[k] = NULL;
    TRY(cj_json_object(&c->json, obj, p, keys));
    const cJSON *dn, *sn, *pn, *wn = NULL;
    TRY(cj_json_require(&c->json, obj, p, "degree", &dn));
    TRY(cj_json_require(&c->json, obj, p, "size", &sn));
    TRY(cj_json_require(&c->json, obj, p, "points", &pn));
    if (nurbs) TRY(cj_json_require(&c->json, obj, p, "weights", &wn));
    char pk[CJ_JSON_PATH];
    double *deg = NULL, *size = NULL;
    size_t cnt;
    cj_json_join(pk, p, "degree");
    TRY(cj_json_numbers(&c->json, dn, pk, 0, CJ_JSON_GE, 1, 2, &deg, &cnt));
    const int dp = (int)deg[0], dq = (int)deg[1];
    const int deg_ok =
        deg[0] == dp && deg[1] == dq && dp <= CJ_PATCH_MAX_DEGREE && dq <= CJ_PATCH_MAX_DEGREE;
    free(deg);
    if (!deg_ok)
        return cj_json_fail(&c->json, dn, 0, CJ_ERR_RANGE, "%s must be two integers in [1, %d]", pk,
                            CJ_PATCH_MAX_DEGREE);
    cj_json_join(pk, p, "size");
    TRY(cj_json_numbers(&c->json, sn, pk, 0, CJ_JSON_GE, 2, 2, &size, &cnt));
    const double su = size[0], sv = size[1];
    free(size);
    if (su != (int)su || sv != (int)sv || su * sv > 1e6)
        return cj_json_fail(&c->json, sn, 0, CJ_ERR_RANGE,
                            "%s must be two integers >= 2 with at most 1e6 points in all", pk);
    const int nu = (int)su, nv = (int)sv;
    double *pts = NULL, *w = NULL, *ku = NULL, *kv = NULL;
    cj_status st;
    cj_json_join(pk, p, "points");
    st = cj_json_numbers(&c->json, pn, pk, 3, CJ_JSON_ANY, 0, (size_t)nu * (size_t)nv, &pts, &cnt);
    if (!st && wn) {
        cj_json_join(pk, p, "weights");
        st = cj_json_numbers(&c->json, wn, pk, 0, CJ_JSON_GT, 0, (size_t)nu * (size_t)nv, &w, &cnt);
    }
    for (int dir = 0; dir < 2 && !st; ++dir) {
        const char *key = dir ? "knots_v" : "knots_u";
        const int n = dir ? nv : nu, deg1 = dir ? dq : dp;
        double **dst = dir ? &kv : &ku;
        const cJSON *kn = cJSON_GetObjectItemCaseSensitive(obj, key);
        cj_json_join(pk, p, key);
        if (kn) {
            st = cj_json_numbers(&c->json, kn, pk, 0, CJ_JSON_ANY, 0, (size_t)(n + deg1 + 1), dst,
                                 &cnt);
        } else {
            *dst = malloc(sizeof(double) * (size_t)(n + deg1 + 1));
            st = !*dst ? cj_json_fail(&c->json, obj, 0, CJ_ERR_NOMEM, "%s: out of memory", p)
                       : cj_bspline_uniform_knots(n, deg1, 0.0, 1.0, 1, *dst);
            if (st && *dst) {
                char msg[300];
                snprintf(msg, sizeof msg, "%s", cj_last_error());
                st = cj_json_fail(&c->json, obj, 0, st, "%s: %s", p, msg);
            }
        }
    }
    const cj_bspline_surface s = {dp, dq, nu, nv, pts, w, ku, kv};
    int np = 0;
    if (!st && (st = cj_bspline_surface_patch_count(&s, &np))) {
        char msg[400];
        snprintf(msg, sizeof msg, "%s", cj_last_error());
        st = cj_json_fail(&c->json, obj, 0, st, "%s: %s", p, msg);
    }
    if (!st) {
        st = cj_scene_add_bspline_surface_at_(c->scene, &s, p, index);
        if (st) st = cj_json_relabel(&c->json, obj, st);
    }
    free(pts);
    free(w);
    free(ku);
    free(kv);
    return st;
}

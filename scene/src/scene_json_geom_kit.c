/* The JSON scene reader's geometry kit, shared by the geometry readers (scene_json_geom.c,
 * scene_json_mesh.c): required keys, and adding a checked geometry to the scene. */
#include "scene_json_internal.h"

/* Every key in the NULL-terminated list must be present. */
cj_status cj_json_geom_need_(const jctx *c, const cJSON *obj, const char *p,
                             const char *const *keys) {
    for (; *keys; ++keys) {
        const cJSON *n;
        CJ_JSON_TRY(cj_json_require(&c->json, obj, p, *keys, &n));
    }
    return CJ_OK;
}

cj_status cj_json_geom_add_(jctx *c, const cJSON *obj, const char *p, const cj_geometry *g,
                            int *index) {
    cj_status st = cj_scene_check_geometry_(g, p);
    if (!st) st = cj_scene_add_geometry(c->scene, g, index);
    return st ? cj_json_relabel(&c->json, obj, st) : CJ_OK;
}

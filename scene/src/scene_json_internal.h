/* Private: the JSON scene reader's context. Its checked accessors are the shared kit of
 * json_read_internal.h (called with &c->json): every failure is reported as
 * "<file>:<line>: <path> <message>" through cj_fail. */
#ifndef CASTELJAU_SCENE_JSON_INTERNAL_H
#define CASTELJAU_SCENE_JSON_INTERNAL_H

#include "casteljau/scene_json.h"
#include "error_internal.h"
#include "scene_internal.h"

#include "json_read_internal.h"

#include <cjson/cJSON.h>

typedef struct jctx {
    cj_json_doc json;     /* the document: name and lines (json_read_internal.h) */
    const char *name;     /* the document's name in messages (= json.name) */
    const char *base_dir; /* "" = current folder */
    const char *teapot_path;
    cj_scene *scene;
    const cJSON *geometries; /* the document's "geometries" list, or NULL */
    int *geometry_index;     /* scene geometry of each "geometries" entry, or -1 if not yet */
    int default_material;    /* -1 until an object needs the default material */
} jctx;

/* Parts (scene_json_parts.c, scene_json_geom.c). */
cj_status cj_json_read_camera_(jctx *c, const cJSON *obj);
cj_status cj_json_read_settings_(jctx *c, const cJSON *obj);
cj_status cj_json_read_lights_(jctx *c, const cJSON *arr);
cj_status cj_json_read_textures_(jctx *c, const cJSON *arr);
cj_status cj_json_read_materials_(jctx *c, const cJSON *arr);
cj_status cj_json_read_objects_(jctx *c, const cJSON *arr);
/* A material object (named: an entry of "materials", with its "name"); *index receives it. */
cj_status cj_json_read_material_(jctx *c, const cJSON *obj, const char *p, int named, int *index);
/* Builds the geometry described by obj and adds it to the scene; *index receives it. */
cj_status cj_json_read_geometry_(jctx *c, const cJSON *obj, const char *path, int *index);
/* A "mesh" (keys already checked by the dispatch) and a "curve" (scene_json_mesh.c). */
cj_status cj_json_read_mesh_(jctx *c, const cJSON *obj, const char *path, int *index);
cj_status cj_json_read_curve_(jctx *c, const cJSON *obj, const char *path, int named, int *index);
/* The geometry readers' kit (scene_json_geom_kit.c): every key of the NULL-terminated list must
 * be present in obj; g checked and added to the scene (*index receives it), a failure relabelled
 * with obj's line. */
cj_status cj_json_geom_need_(const jctx *c, const cJSON *obj, const char *path,
                             const char *const *keys);
cj_status cj_json_geom_add_(jctx *c, const cJSON *obj, const char *path, const cj_geometry *g,
                            int *index);
/* A "bspline_surface" or "nurbs_surface", converted to Bézier patches at load
 * (scene_json_bspline.c). named: the object is an entry of "geometries" (may have "name"). */
cj_status cj_json_read_bspline_surface_(jctx *c, const cJSON *obj, const char *path, int named,
                                        int *index);

#endif

/* Private: the JSON scene reader's context and its checked accessors. Every accessor reports
 * a failure as "<file>:<line>: <path> <message>" through cj_fail and returns its status. */
#ifndef CASTELJAU_SCENE_JSON_INTERNAL_H
#define CASTELJAU_SCENE_JSON_INTERNAL_H

#include "casteljau/scene_json.h"
#include "error_internal.h"
#include "scene_internal.h"

#include <cjson/cJSON.h>

#define JPATH 256

/* Lines of the document's values, found only when a message needs one: the raw text is scanned
 * once on the first request (pairs (line, key line) per value in document order) and a node's
 * entry is its index in a pre-order walk of the cJSON tree. The success path pays nothing. */
typedef struct jlines {
    const char *text;
    const cJSON *root;
    int *vals; /* 2 per value: line of the value, line of its key (= value line in arrays) */
    size_t n;
    int scanned; /* 0: not yet, 1: done, -1: out of memory (lines read as 0) */
} jlines;

typedef struct jctx {
    const char *name;     /* the document's name in messages */
    const char *base_dir; /* "" = current folder */
    const char *teapot_path;
    jlines *lines;
    cj_scene *scene;
    const cJSON *geometries; /* the document's "geometries" list, or NULL */
    int *geometry_index;     /* scene geometry of each "geometries" entry, or -1 if not yet */
    int default_material;    /* -1 until an object needs the default material */
} jctx;

int cj_json_line_(const jctx *c, const cJSON *node);
int cj_json_key_line_(const jctx *c, const cJSON *node);
/* Reports `st` at node's line (key line if `at_key`). */
cj_status cj_json_fail_(const jctx *c, const cJSON *node, int at_key, cj_status st, const char *fmt,
                        ...) CJ_PRINTF(5, 6);
/* Re-labels the current cj_last_error() message with the file and node's line. */
cj_status cj_json_relabel_(const jctx *c, const cJSON *node, cj_status st);

/* path + "." + key, or path + "[i]". */
void cj_json_join_(char *dst, const char *path, const char *key);
void cj_json_index_(char *dst, const char *path, size_t i);

/* obj must be an object whose keys are all in `allowed` (NULL-terminated), none repeated. */
cj_status cj_json_object_(const jctx *c, const cJSON *obj, const char *path,
                          const char *const *allowed);
/* A required key; missing: error at obj naming the key. */
cj_status cj_json_require_(const jctx *c, const cJSON *obj, const char *path, const char *key,
                           const cJSON **out);

/* Range kinds of numbers. */
typedef enum jrange { R_ANY = 0, R_GE, R_GT, R_LT, R_IN, R_OPEN } jrange;

/* Optional numbers: missing keys leave *out as it is. */
cj_status cj_json_num_(const jctx *c, const cJSON *obj, const char *path, const char *key, jrange r,
                       double lo, double hi, double *out);
cj_status cj_json_int_(const jctx *c, const cJSON *obj, const char *path, const char *key,
                       double lo, double hi, int *out);
cj_status cj_json_bool_(const jctx *c, const cJSON *obj, const char *path, const char *key,
                        int *out);
cj_status cj_json_vec3_(const jctx *c, const cJSON *obj, const char *path, const char *key,
                        cj_vec3 *out);
/* Colour components in [0, max] (max < 0: >= 0 only). */
cj_status cj_json_rgb_(const jctx *c, const cJSON *obj, const char *path, const char *key,
                       double max, cj_rgb *out);
cj_status cj_json_string_(const jctx *c, const cJSON *obj, const char *path, const char *key,
                          const char **out);
/* A string among `names` (NULL-terminated); *out = its index. */
cj_status cj_json_enum_(const jctx *c, const cJSON *obj, const char *path, const char *key,
                        const char *const *names, int *out);
/* Numbers of the array node `arr` (any length unless want > 0), each in range: `count` and a
 * malloc'ed array (free with free()). dim > 0: an array of arrays of `dim` numbers, flattened. */
cj_status cj_json_numbers_(const jctx *c, const cJSON *arr, const char *path, int dim, jrange r,
                           double lo, size_t want, double **out, size_t *count);

/* An angle given as key_deg or key_rad (not both), range in radians, into *out (radians). */
cj_status cj_json_angle_(const jctx *c, const cJSON *obj, const char *path, const char *key,
                         jrange r, double lo_rad, double hi_rad, double *out);
/* arr must be an array. */
cj_status cj_json_list_(const jctx *c, const cJSON *arr, const char *p);

/* Resolves a path of the document against its folder into dst (cap bytes). */
cj_status cj_json_resolve_(const jctx *c, const cJSON *node, const char *path, const char *rel,
                           char *dst, size_t cap);

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
/* "bspline_surface" (nurbs = 0) / "nurbs_surface" (nurbs = 1), converted to Bézier patches at
 * load (scene_json_bspline.c). named: the object is an entry of "geometries" (may have "name"). */
cj_status cj_json_read_bspline_surface_(jctx *c, const cJSON *obj, const char *path, int named,
                                        int nurbs, int *index);

#endif

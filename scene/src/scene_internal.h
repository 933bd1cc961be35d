/* Private: the scene object's layout and the validators shared by cj_scene_check, the add
 * functions and the JSON reader (which prefixes their messages with a file and a line). */
#ifndef CASTELJAU_SCENE_INTERNAL_H
#define CASTELJAU_SCENE_INTERNAL_H

#include "casteljau/scene.h"

/* Memory a geometry owns besides its cj_geometry value (released on destroy). */
typedef struct cj_geom_store {
    void *block[3];
    struct cj_scene_bspline_ *bspline; /* the kept B-spline form (scene_bspline.c) or NULL */
} cj_geom_store;

/* Adds B-spline surface `s` as a patches geometry keeping its B-spline form; messages name
 * `path` (the JSON reader's path, or "geometries[n]"). */
struct cj_bspline_surface;
cj_status cj_scene_add_bspline_surface_at_(cj_scene *scene, const struct cj_bspline_surface *s,
                                           const char *path, int *index);
/* Whether the patches of geometry `index` are still exactly those of its B-spline form
 * (0 also when it has none or memory ran out). */
int cj_scene_bspline_in_sync_(const cj_scene *scene, int index);

struct cj_scene {
    cj_allocator alloc;
    cj_camera camera;
    cj_scene_settings settings;
    cj_light *lights;
    size_t nlights, caplights;
    cj_texture *textures;
    char **texture_sources; /* "file:line: textures[i]" or NULL, one per texture */
    char **texture_names;
    size_t ntextures, captextures;
    cj_material *materials;
    char **material_names;
    size_t nmaterials, capmaterials;
    cj_geometry *geoms;
    cj_geom_store *gstore;
    size_t ngeoms, capgeoms;
    cj_node *nodes;
    size_t nnodes, capnodes;
    uint32_t objects; /* objects (non-group nodes) added so far: the next id - 1 */
};

void *cj_scene_alloc_(const cj_scene *s, size_t bytes);
void cj_scene_free_(const cj_scene *s, void *p);
/* An owned copy of `str` (NULL stays NULL); *ok = 0 when the allocation failed. */
char *cj_scene_strdup_(const cj_scene *s, const char *str, int *ok);

/* Validators: CJ_OK or a cj_fail message "<path>.<field> must be ..." naming the field. */
cj_status cj_scene_check_camera_(const cj_camera *c, const char *path);
cj_status cj_scene_check_settings_(const cj_scene_settings *s, const char *path);
cj_status cj_scene_check_light_(const cj_light *l, const char *path);
cj_status cj_scene_check_texture_(const cj_texture *t, const char *path);
cj_status cj_scene_check_material_(const cj_material *m, size_t ntextures, const char *path);
cj_status cj_scene_check_geometry_(const cj_geometry *g, const char *path);
cj_status cj_scene_check_transform_(const cj_transform *t, const char *path);
cj_status cj_scene_check_overlay_(const cj_overlay_style *o, const char *path);
/* The node at index `index` (or about to be added there) against the scene's other parts. */
cj_status cj_scene_check_node_(const cj_scene *s, const cj_node *n, size_t index, const char *path);

/* Rotation matrix of the unit quaternion (w, x, y, z). */
void cj_quat_to_matrix_(const double q[4], double r[3][3]);

#endif

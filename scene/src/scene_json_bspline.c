/* The scene reader's B-spline / NURBS surfaces: the object is read by the one reader of that
 * format (bspline_surface_json.c, which the surface document of formats/ shares), converted to
 * its Bézier patches at load (cj_bspline_surface_to_patches), so it is a "patches" geometry for
 * every renderer, the tracer and tessellation, and the scene keeps its B-spline form
 * (casteljau/scene_bspline.h) for editors and for cj_scene_save_json. */
#include "bspline_surface_json_internal.h"
#include "scene_internal.h"
#include "scene_json_internal.h"

cj_status cj_json_read_bspline_surface_(jctx *c, const cJSON *obj, const char *p, int named,
                                        int *index) {
    cj_bspline_surface s;
    CJ_JSON_TRY(cj_json_read_bspline_surface(&c->json, obj, p, named, &s));
    cj_status st = cj_scene_add_bspline_surface_at_(c->scene, &s, p, index);
    if (st) st = cj_json_relabel(&c->json, obj, st);
    cj_json_bspline_surface_free(&s);
    return st;
}

/* casteljau: B-spline and NURBS surfaces kept as such in the scene model (issue 22).
 *
 * A geometry added here is an ordinary CJ_GEOM_PATCHES geometry for every renderer, the tracer
 * and tessellation: its patches are cj_bspline_surface_to_patches of the surface, bit for bit
 * (patch a along u, b along v is patch b*nspans_u + a). The scene also keeps the B-spline form
 * (degrees, control net, weights, knots, owned copies), so an editor moves B-spline control
 * points and weights, and cj_scene_save_json writes the geometry back as "bspline_surface" /
 * "nurbs_surface".
 *
 * Local control: control point (i, j) of a surface of degrees (p, q) acts on the parameter box
 * [u_i, u_{i+p+1}) × [v_j, v_{j+q+1}), which holds at most p+1 non-empty u spans and q+1 v
 * spans, so an edit re-derives at most (p+1)(q+1) patches (cj_scene_bspline_set_point lists
 * them); only those need a new tessellation.
 *
 * If the patches of such a geometry are edited directly (cj_scene_geometry_mut), they no longer
 * match the B-spline form: cj_scene_save_json notices (it re-derives the patches and compares
 * them bit for bit) and writes "patches", the form that is then true.
 */
#ifndef CASTELJAU_SCENE_BSPLINE_H
#define CASTELJAU_SCENE_BSPLINE_H

#include "casteljau/bspline_surface.h"
#include "casteljau/scene.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Adds the surface as a patches geometry keeping its B-spline form (all arrays copied).
 * Errors: those of cj_bspline_surface_check, of cj_scene_add_geometry (a patch with no area,
 * coordinates beyond CJ_SCENE_MAX_COORD), CJ_ERR_NOMEM. Nothing is added on failure. */
cj_status cj_scene_add_bspline_surface(cj_scene *scene, const cj_bspline_surface *s, int *index);

/* The kept B-spline form of geometry `index` (views into scene-owned arrays, valid until the
 * scene is destroyed; the point array changes in place under cj_scene_bspline_set_point), or
 * NULL when the geometry has none. */
const cj_bspline_surface *cj_scene_geometry_bspline(const cj_scene *scene, int index);

/* The patches control point (i, j) of geometry `index` acts on (the support above), ascending,
 * into patches[0..cap) (cap >= (p+1)(q+1) always suffices); returns how many there are (-1 when
 * the geometry has no B-spline form or (i, j) is out of range). */
int cj_scene_bspline_support(const cj_scene *scene, int index, int i, int j, int *patches, int cap);

/* Moves control point (i, j) of geometry `index` to xyz with weight `weight` (a NURBS: finite,
 * > 0; a polynomial surface: must be 1) and re-derives its patches. Every patch of the geometry
 * afterwards equals cj_bspline_surface_to_patches of the edited surface bit for bit; only
 * patches in the point's support are written, and those whose points or weights actually
 * changed are listed ascending in changed[0..cap) with their number in *nchanged (either may be
 * NULL/0 when not wanted; cap >= (p+1)(q+1) suffices). Work space is allocated (the conversion
 * runs on the whole net; the tessellation, not this, is what an editor saves by locality).
 * Errors: CJ_ERR_ARGUMENT (no B-spline form, (i, j) out of range, a weight != 1 on a polynomial
 * surface or <= 0), CJ_ERR_NONFINITE, CJ_ERR_RANGE (a coordinate beyond CJ_SCENE_MAX_COORD),
 * CJ_ERR_NOMEM; nothing changes on failure. */
cj_status cj_scene_bspline_set_point(cj_scene *scene, int index, int i, int j, const double xyz[3],
                                     double weight, int *changed, int cap, int *nchanged);

/* For editors that write the kept points or weights in place (the 3D viewer's undo log holds
 * pointers into cj_scene_geometry_bspline(...)->pts): re-derives the patches of geometry `index`
 * from its kept form, writing only the patches whose bits change, listed as in
 * cj_scene_bspline_set_point (cap >= the patch count always suffices). After it the patches
 * equal cj_bspline_surface_to_patches of the kept form bit for bit. Errors: CJ_ERR_ARGUMENT (no
 * B-spline form), those of cj_bspline_surface_check (the edited net, e.g. a NaN point or a
 * weight <= 0), CJ_ERR_NOMEM; on failure the patches are left as they were. */
cj_status cj_scene_bspline_refresh(cj_scene *scene, int index, int *changed, int cap,
                                   int *nchanged);

#ifdef __cplusplus
}
#endif
#endif

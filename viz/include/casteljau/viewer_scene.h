/* casteljau: the editor model of `casteljau view` for 3D scenes, usable without a window.
 *
 * A cj_vscene owns a cj_scene (casteljau/scene.h) and edits it in place: the control points of
 * its Bézier patches and 3D curves can be picked on screen and dragged, every drag is one
 * command of an undo/redo log that restores the coordinates bit for bit, and an orbit camera
 * (target, distance, azimuth, elevation about the camera's initial up vector, the elevation
 * clamped to ±89°) writes the scene's camera, so the scene saved with cj_scene_save_json
 * renders offline exactly as shown.
 *
 * Editable points: every control point of every visible object whose geometry is
 * CJ_GEOM_PATCHES or CJ_GEOM_CURVE, in node order, then patch order, then point order (the
 * order of the tie rule). A geometry shared by several objects is editable through each of
 * them; a point is moved in the geometry, i.e. in every instance.
 *
 * Shared points: neighbouring patches store their own copies of a shared corner or edge point.
 * With linking on (the default), a move of point k moves with it every other control point of
 * the same geometry lying bit-identically where k lies when the move is made, all to the same
 * place, as one command (undo restores them all). Shared edges whose control points were
 * identical stay identical, so the tessellation stays watertight. With linking off only point
 * k moves, which opens a seam where k was shared.
 *
 * Pixels: framebuffer coordinates of a width × height image (origin lower-left, y up), the
 * projection of the rasterizer: px = (x_ndc + 1) width / 2, py = (y_ndc + 1) height / 2.
 *
 * Status codes: CJ_ERR_ARGUMENT (a point index out of range, an axis not in -1..2),
 * CJ_ERR_DEGENERATE (the cursor ray is parallel to the drag plane or axis), CJ_ERR_SINGULAR
 * (an object transform that cannot be inverted), CJ_ERR_EMPTY (nothing to undo/redo),
 * CJ_ERR_NOMEM, and what cj_camera_* report.
 */
#ifndef CASTELJAU_VIEWER_SCENE_H
#define CASTELJAU_VIEWER_SCENE_H

#include "casteljau/scene.h"
#include "casteljau/status.h"
#include "casteljau/vec.h"
#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct cj_vscene cj_vscene;

/* Takes ownership of `scene` (destroyed with the editor, also on failure). */
cj_status cj_vscene_create(cj_scene *scene, cj_vscene **out);
void cj_vscene_destroy(cj_vscene *vs); /* NULL allowed */
cj_scene *cj_vscene_scene(cj_vscene *vs);

size_t cj_vscene_point_count(const cj_vscene *vs);
/* World position of editable point k. */
cj_status cj_vscene_point(const cj_vscene *vs, size_t k, cj_vec3 *world);
/* The node (index in the scene) through which point k is editable; -1 if k is out of range. */
int cj_vscene_point_node(const cj_vscene *vs, size_t k);
/* Pixel position (and pseudodepth) of point k in a width × height image; returns 0 when the
 * point is behind the eye (not on screen). */
int cj_vscene_project(const cj_vscene *vs, size_t k, int width, int height, double out[3]);

/* The visible point nearest to (px, py) within `radius` pixels (exact squared distances, ties
 * to the lowest index, as cj_vdoc_pick). `depth` (may be NULL) is the pseudodepth plane of the
 * rendered picture (cj_render_image.depth, width × height, bottom row first): a point whose
 * pseudodepth exceeds the plane's at its pixel by more than CJ_VSCENE_DEPTH_TOL is hidden
 * behind a surface and not picked. Returns 1 and sets *k, or 0. */
#define CJ_VSCENE_DEPTH_TOL 2e-4
int cj_vscene_pick(const cj_vscene *vs, int width, int height, const float *depth, double px,
                   double py, double radius, size_t *k);

/* Drags point k: its position at the start of the drag plus the displacement of the cursor
 * from (px0, py0) to (px1, py1), measured on the plane through that start position facing the
 * camera (axis = -1; the plane's normal is the gaze), or along world axis `axis` (0, 1, 2: the
 * point of the axis line nearest to the cursor ray). Between cj_vscene_begin_drag and
 * cj_vscene_end_drag all moves of the point are one command. */
void cj_vscene_begin_drag(cj_vscene *vs);
void cj_vscene_end_drag(cj_vscene *vs);
cj_status cj_vscene_drag(cj_vscene *vs, size_t k, int width, int height, double px0, double py0,
                         double px1, double py1, int axis);
/* Sets point k to a world position (one command). */
cj_status cj_vscene_set_point(cj_vscene *vs, size_t k, cj_vec3 world);

/* The weight of point k when it is a point of a NURBS surface's net (scene_bspline.h):
 * 1 and *w set; else 0 (a patch corner, a curve point, a polynomial B-spline surface). */
int cj_vscene_point_weight(const cj_vscene *vs, size_t k, double *w);
/* Sets the weight of NURBS net point k (and, with linking on, of the net points at the same
 * place, so a closed surface stays closed) as one command, re-deriving the changed patches.
 * CJ_ERR_ARGUMENT: k out of range, not a NURBS net point, or w not finite and > 0. */
cj_status cj_vscene_set_weight(cj_vscene *vs, size_t k, double w);

/* Linking of coincident points (see above): on (1) by default. */
void cj_vscene_set_linked(cj_vscene *vs, int on);
int cj_vscene_linked(const cj_vscene *vs);
/* The number of distinct control points a move of point k moves now (itself included): 1
 * when linking is off or nothing else of its geometry lies exactly there; 0 if k is out of
 * range. */
size_t cj_vscene_shared_count(const cj_vscene *vs, size_t k);

/* Re-reads the nodes' world transforms (after animation posed the scene). */
cj_status cj_vscene_update(cj_vscene *vs);

/* Undo/redo one command (a drag, or a set_point, with the points linked to it). */
cj_status cj_vscene_undo(cj_vscene *vs);
cj_status cj_vscene_redo(cj_vscene *vs);
/* Commands that can be undone. */
size_t cj_vscene_undo_depth(const cj_vscene *vs);

/* ---- camera ------------------------------------------------------------------------------ */

/* Orbit by (dx, dy) pixels of mouse motion (0.01 rad per pixel; elevation clamped to ±89°). */
cj_status cj_vscene_orbit(cj_vscene *vs, double dx, double dy);
/* Pan so that the target moves with the cursor by (dx, dy) pixels in a viewport `height`
 * pixels high. */
cj_status cj_vscene_pan(cj_vscene *vs, double dx, double dy, int height);
/* Zoom: distance (or orthographic height) times factor > 0. */
cj_status cj_vscene_zoom(cj_vscene *vs, double factor);

#ifdef __cplusplus
}
#endif
#endif

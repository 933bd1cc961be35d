/* The viewer's key help, as data: the window's F1 overlay shows it, and tests read it without
 * opening the viewer module (which needs GLFW and OpenGL). */
#include "viewer_app.h"

static const char *const help_2d[] = {
    "2D curves (plot JSON)",
    "left drag on a point   move it (in the plane)",
    "left drag elsewhere    pan;   wheel  zoom at the cursor;   Home  fit",
    "right drag             move t along the selected curve;   [ ]  t -/+ 0.01",
    "Tab  next curve    C  de Casteljau construction at t    F  tangent/normal at t",
    "K  curvature comb    H  convex hull    M  evaluation method (error bound at t)",
    "I  insert a point after the selected one    A  append a point at the cursor",
    "Del/X  delete the selected point    E  elevate degree    S  split at t",
    "W / shift+W  weight x1.25 / /1.25 (rational curves, B-splines: NURBS)",
    "B-splines: I  insert a knot at the cursor's parameter (the curve stays)",
    "P  snap to the nearest curve point (certified); drag a point onto a curve",
    "T  intersections between curves (certified marks)",
    "ctrl+Z  undo    ctrl+Y or ctrl+shift+Z  redo    ctrl+S  save    F5  reload",
    "O  text overlay on/off    F1  this help    Esc/Q  quit",
    NULL};

static const char *const help_3d[] = {
    "3D scenes (scene JSON, .bpt, --teapot)",
    "left drag on a control point   move it on the plane facing the camera",
    "shift + left drag on a point   move it along the axis chosen with X / Y / Z",
    "left drag elsewhere  orbit;  right or middle drag  pan;  wheel  zoom",
    "N  control nets    W  wireframe    G  shading flat/Gouraud/Phong",
    "+ / -  screen tolerance x2 / /2    R  ray-traced view (refines while still)",
    "L  shared corners and edge points move together (on) / alone",
    "W / shift+W with a NURBS net point selected  weight x1.25 / /1.25",
    "Space  play/pause the animation (an animation document: one frame per picture)",
    "ctrl+Z  undo    ctrl+Y or ctrl+shift+Z  redo    ctrl+S  save    F5  reload",
    "O  text overlay on/off    F1  this help    Esc/Q  quit",
    NULL};

const char *const *cj_viewer_help(int mode3d) {
    return mode3d ? help_3d : help_2d;
}

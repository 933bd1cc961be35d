/* Private to the viewer window (viewer_draw.c, viewer_input.c, viewer_replay.c,
 * viewer_window.c): the state of one `casteljau view` session. Only viewer_window.c talks to
 * GLFW and OpenGL; the rest is plain C driven by events (real or replayed). */
#ifndef CASTELJAU_VIEWER_APP_H
#define CASTELJAU_VIEWER_APP_H

#include "casteljau/bezier.h"
#include "casteljau/framebuffer.h"
#include "casteljau/render.h"
#include "casteljau/text.h"
#include "casteljau/viewer.h"
#include "casteljau/viewer_model.h"
#include "casteljau/viewer_scene.h"

#include <stddef.h>
#include <stdio.h>

struct cj_vrender;

enum { VIEW_DRAG_NONE = 0, VIEW_DRAG_POINT, VIEW_DRAG_T, VIEW_DRAG_PAN, VIEW_DRAG_ORBIT };
/* Modifier bits (GLFW's values). */
enum { VIEW_MOD_SHIFT = 1, VIEW_MOD_CTRL = 2, VIEW_MOD_ALT = 4 };
/* Mouse buttons (GLFW's values). */
enum { VIEW_BUTTON_LEFT = 0, VIEW_BUTTON_RIGHT = 1, VIEW_BUTTON_MIDDLE = 2 };

typedef struct cj_viewer {
    const cj_viewer_options *opt;
    int mode3d;
    int width, height;
    /* 2D */
    cj_vdoc *doc;
    cj_vview view;
    cj_vdoc_display disp;
    long sel_point; /* selected point of curve disp.curve, or -1 */
    int comb;       /* curvature comb (overlay) */
    cj_eval_method method;
    int snap_on;     /* P: the cursor (and a dragged point) snaps to the nearest curve */
    cj_vsnap snap;   /* the last snap (snap.curve < 0: none) */
    int isect_on;    /* T: intersections between curves marked */
    cj_vmark *marks; /* those intersections (recomputed with the picture) */
    size_t nmarks, isect_failed;
    /* 3D */
    cj_vscene *vs;
    long sel3;               /* selected control point, or -1 */
    int axis;                /* axis of shift-drags: 0 x, 1 y, 2 z */
    int trace;               /* ray-traced view on */
    struct cj_vrender *rt;   /* the render thread (viewer_render.h) */
    unsigned long gen;       /* the state submitted last */
    unsigned long shown_gen; /* the state the picture shows */
    int shown_trace, shown_pass, shown_spp;
    double shown_tol;         /* raster: the screen tolerance drawn */
    float *depth;             /* pseudodepth plane of the last rasterized picture (hidden points) */
    struct cj_anim_doc *anim; /* an animation document's timeline, or NULL */
    long anim_frame;
    int playing;
    /* pictures: `pic` is what the offline commands produce, `screen` adds the overlay */
    cj_framebuffer *pic, *screen;
    cj_font *font;
    int show_overlay, show_help;
    int dirty;  /* the picture must be drawn again (the state changed) */
    int redraw; /* the window must show the picture again (overlay, message, new picture) */
    /* input */
    int drag;
    double cx, cy;     /* cursor, framebuffer pixel coordinates (y up) */
    double px0, py0;   /* where the drag started */
    double dpx0, dpy0; /* pixel position of the dragged point when the drag started */
    cj_vview view0;    /* the view when a pan started */
    int quit;
    char msg[256];
    /* statistics of the last frame */
    double render_s;
    size_t triangles;
    double bound_px;
} cj_viewer;

/* viewer_draw.c */
cj_status cj_viewer_load(cj_viewer *v);
void cj_viewer_unload(cj_viewer *v);
cj_status cj_viewer_save(cj_viewer *v, const char *path);
/* While an animation plays: poses the scene at the next frame (one frame per drawn frame). */
void cj_viewer_tick(cj_viewer *v);
/* 2D: renders `pic` if dirty. Then `screen` = pic + overlay/help. (3D pictures come from the
 * render thread: viewer_live.c.) */
cj_status cj_viewer_draw(cj_viewer *v);

/* viewer_overlay.c: the status panel, selection, control points and help over `screen`. */
void cj_viewer_overlay(cj_viewer *v);

/* viewer_live.c: 3D pictures through the render thread. */
cj_status cj_viewer_live_start(cj_viewer *v, FILE *timeline, void (*wake)(void));
void cj_viewer_live_stop(cj_viewer *v);
/* Hands the current state to the render thread (clears dirty): a drag the rasterizer with
 * cached meshes, a still view the exact raster or the ray-traced passes (all of them, or only
 * the quick first one when `one_pass`). */
cj_status cj_viewer_submit(cj_viewer *v, int one_pass);
/* Takes a finished frame into `pic` (and the depth plane); 1 if there was one. */
int cj_viewer_collect(cj_viewer *v);
/* The ray-traced view shows the current state and has a finer pass left. */
int cj_viewer_refinable(const cj_viewer *v);
/* Submits that next pass alone. */
cj_status cj_viewer_refine(cj_viewer *v);
/* The default save path ("" when the input was not a file the editor can write back). */
const char *cj_viewer_save_path(const cj_viewer *v, char *buf, size_t size);

/* viewer_input.c: window coordinates (x right, y down, as GLFW reports the cursor). The
 * cursor at (x, y) points at the centre of framebuffer pixel (x, height − 1 − y). */
void cj_viewer_key(cj_viewer *v, int key, int mods);
void cj_viewer_button(cj_viewer *v, int button, int press, int mods, double x, double y);
void cj_viewer_cursor(cj_viewer *v, double x, double y, int mods);
void cj_viewer_scroll(cj_viewer *v, double dy);
/* The help panel's lines (NULL-terminated). */
const char *const *cj_viewer_help(int mode3d);

/* viewer_replay.c: one parsed script event. */
enum {
    VEV_KEY,
    VEV_PRESS,
    VEV_RELEASE,
    VEV_MOVE,
    VEV_SCROLL,
    VEV_FRAME,
    VEV_SCREENSHOT,
    VEV_SAVE,
    VEV_T,
    VEV_SELECT
};
typedef struct cj_vevent {
    int type, key, button, mods;
    double x, y;
    char arg[1024];
} cj_vevent;
/* Parses line `lineno` of a script into up to `cap` events (a drag expands into a press, its
 * moves and a release; blank and # lines give none). CJ_ERR_PARSE naming script:line. */
cj_status cj_viewer_parse_line(const char *script, int lineno, const char *line, cj_vevent *ev,
                               size_t cap, size_t *n);
/* Applies an input event (key/press/release/move/scroll/t/select); the window handles frame,
 * screenshot and save itself. */
void cj_viewer_apply(cj_viewer *v, const cj_vevent *e);

#endif

/* casteljau: the interactive viewer and control-point editor (`casteljau view`), GLFW + OpenGL.
 *
 * The window shows casteljau's own pictures: the plot of casteljau/plot.h for curves (2D mode)
 * and the rasterizer (or, on demand, the ray tracer) of casteljau/render.h for scenes (3D
 * mode), drawn into a framebuffer, uploaded as a texture and drawn 1:1, so the screen shows the
 * pixels `casteljau plot` / `casteljau render` write for the same state. A text overlay
 * (FreeType) and a help panel (F1) are drawn on top; they can be hidden (key O) to see the bare
 * picture. Editing goes through the models of casteljau/viewer_model.h (2D) and
 * casteljau/viewer_scene.h (3D): picking, dragging, insert/delete, elevation, split, undo/redo,
 * atomic save and reload.
 *
 * LIVE: 3D pictures are drawn by a render thread while the window keeps handling input and
 * showing the last finished picture; a new input cancels the picture in flight (except the
 * frames of a drag, which keep coming). The ray-traced view (R) is progressive: a quick
 * low-resolution pass, then 1, 4, 16 and 64 samples per pixel, each shown when done.
 *
 * REPLAY: every command can be driven by a script of input events (one per line), which runs
 * through the same handlers as real input; see cj_viewer_options.replay and the README.
 */
#ifndef CASTELJAU_VIEWER_H
#define CASTELJAU_VIEWER_H

#include "casteljau/status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct cj_viewer_options {
    const char *path;        /* plot JSON (curves), scene JSON, or .bpt patches; NULL: teapot */
    const char *teapot_path; /* data/teapot.bpt, for --teapot and scenes that name "teapot" */
    int width, height;       /* window size; 0 = the file's (curves) / scene's settings */
    const char *replay;      /* script of events; the window closes at its end */
    const char *screenshot;  /* PNG of the back buffer after the replay (or at exit) */
    const char *frame_times; /* per frame "wall_s cpu_s" written here, one line each, at exit */
    int hide_overlay;        /* start with the text overlay hidden */
    int spp;                 /* 3D: samples per pixel override (0 = the scene's) */
    double tol_px;           /* 3D: tessellation tolerance override in pixels (0 = scene's) */
    int threads;             /* renderer threads (0 = one per core) */
    const char *title;       /* window title (default "casteljau view") */
    const char *timeline;    /* 3D: "<seconds> <event>" lines: keys, buttons, scrolls, render
                                passes submitted, started, done or cancelled (with their tiles
                                drawn), frames shown; seconds of CLOCK_MONOTONIC */
} cj_viewer_options;

/* Opens the window and runs until it is closed (or the replay ends). Returns CJ_OK;
 * CJ_ERR_UNSUPPORTED when there is no display (the message says so in one line); errors of
 * loading the input (CJ_ERR_IO, CJ_ERR_PARSE, ... naming the file); errors of a replay script
 * (CJ_ERR_PARSE naming the line); CJ_ERR_IO when the screenshot cannot be written. */
cj_status cj_viewer_run(const cj_viewer_options *opt);

#ifdef __cplusplus
}
#endif
#endif

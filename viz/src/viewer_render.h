/* Private to the viewer: the render thread of `casteljau view` (3D mode). The window's thread
 * keeps handling input and showing the last finished picture while this thread draws the next
 * one from a SNAPSHOT of the scene (a private copy handed over with the job, so the editor may
 * change its scene at once). A new job replaces the one waiting and cancels the one running
 * (through the renderer's progress callback, between tiles), except that a drag does not
 * cancel the drag frame in flight: while the mouse moves, frames keep coming at the renderer's
 * pace, each showing the newest state.
 *
 * The ray-traced view is PROGRESSIVE: a job draws passes first_pass..last_pass of the table
 * below (a quick low-resolution pass first, then more samples per pixel), and each finished
 * pass is handed back at once; a job waiting ends the passes early.
 *
 * All calls come from the window's thread. Frames are handed back through cj_vrender_take;
 * `wake` (may be NULL) is called from the render thread whenever one is ready (the window
 * passes glfwPostEmptyEvent, so a waiting event loop wakes up). */
#ifndef CASTELJAU_VIEWER_RENDER_H
#define CASTELJAU_VIEWER_RENDER_H

#include "casteljau/scene.h"
#include "casteljau/status.h"

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

/* Progressive ray-traced passes: pass p draws with cj_vtrace_spp[p] samples per pixel at
 * 1/cj_vtrace_scale(p, width, height) of the resolution in each direction (shown with nearest
 * upscaling): the quick first pass at about 128 x 128 pixels whatever the window's size, the
 * others at full resolution. */
enum { VIEW_TRACE_PASSES = 5 };
/* The coarsest screen tolerance of a drag frame (pixels; a finer scene tolerance is kept). */
#define VIEW_DRAG_TOL_PX 1.0
extern const int cj_vtrace_spp[VIEW_TRACE_PASSES];
int cj_vtrace_scale(int pass, int width, int height);

typedef struct cj_vjob {
    cj_scene *scene;           /* the snapshot: owned by the job from cj_vrender_submit on */
    unsigned long gen;         /* the viewer state it shows (increases with every job) */
    int trace;                 /* 0: the rasterizer (with the depth plane); 1: the ray tracer */
    int first_pass, last_pass; /* trace: passes drawn, in order */
    int interactive; /* raster: a drag in progress: 1 sample per pixel, a tolerance of at least
                        VIEW_DRAG_TOL_PX, cached meshes reused within their tolerance band
                        (otherwise the picture is exactly the offline one) */
} cj_vjob;

typedef struct cj_vframe {
    unsigned long gen;
    int trace, pass; /* trace: which pass this is */
    int spp;         /* samples per pixel drawn */
    double tol_px;   /* raster: screen tolerance drawn */
    cj_status status;
    char msg[256];  /* the error message when status != CJ_OK */
    uint8_t *rgba8; /* width × height sRGB, bottom row first, alpha 255 */
    float *depth;   /* raster: pseudodepth plane; NULL for traced frames */
    double seconds; /* wall time of the render */
    size_t triangles;
    size_t planned, built; /* raster: patches the tessellation cache planned and built */
    double bound_px;
    uint64_t tiles; /* tiles drawn */
} cj_vframe;

typedef struct cj_vrender cj_vrender;

/* Starts the thread for width × height pictures drawn with `threads` renderer threads (0: one
 * per core). `timeline` (may be NULL) receives one line per pass started, finished or cancelled
 * (see cj_vrender_log). CJ_ERR_NOMEM, CJ_ERR_UNSUPPORTED (no thread). */
cj_status cj_vrender_create(int width, int height, int threads, FILE *timeline, void (*wake)(void),
                            cj_vrender **out);
/* Cancels, joins the thread, frees everything (NULL allowed). */
void cj_vrender_destroy(cj_vrender *r);

/* Hands a job over (*job is copied; its scene is owned by the renderer from now on). */
void cj_vrender_submit(cj_vrender *r, const cj_vjob *job);
/* The newest finished frame not taken yet, or NULL. It stays valid until the next call. */
const cj_vframe *cj_vrender_take(cj_vrender *r);
/* Blocks until no job waits or runs. */
void cj_vrender_wait(cj_vrender *r);
/* 1 while a job waits or runs. */
int cj_vrender_busy(cj_vrender *r);

/* A line "<CLOCK_MONOTONIC seconds> <text>" on the timeline (thread-safe; nothing when there is
 * no timeline). */
void cj_vrender_log(cj_vrender *r, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;

/* A deep copy of a scene through its public API (what the render thread draws). */
cj_status cj_vscene_snapshot(const cj_scene *src, cj_scene **out);

#endif

/* The viewer's 3D pictures through the render thread (viewer_render.h): what to draw for the
 * current state (a drag: the rasterizer with cached meshes; a still view: the exact raster, or
 * the progressive ray-traced passes), and taking finished frames into the picture shown. */
#define _POSIX_C_SOURCE 200809L
#include "viewer_app.h"

#include "viewer_render.h"

#include <stdlib.h>
#include <string.h>

cj_status cj_viewer_live_start(cj_viewer *v, FILE *timeline, void (*wake)(void)) {
    if (!v->mode3d) return CJ_OK;
    return cj_vrender_create(v->width, v->height, v->opt->threads, timeline, wake, &v->rt);
}

void cj_viewer_live_stop(cj_viewer *v) {
    cj_vrender_destroy(v->rt);
    v->rt = NULL;
}

static cj_status submit(cj_viewer *v, int trace, int first, int last) {
    cj_vjob job;
    memset(&job, 0, sizeof job);
    cj_status st = cj_vscene_snapshot(cj_vscene_scene(v->vs), &job.scene);
    if (st) {
        snprintf(v->msg, sizeof v->msg, "render: %s", cj_last_error());
        return st;
    }
    job.gen = ++v->gen;
    job.trace = trace;
    job.first_pass = first;
    job.last_pass = last;
    job.interactive = v->drag != VIEW_DRAG_NONE;
    cj_vrender_log(v->rt, "submit gen %lu %s passes %d..%d%s", job.gen, trace ? "trace" : "raster",
                   first, last, job.interactive ? " interactive" : "");
    cj_vrender_submit(v->rt, &job);
    return CJ_OK;
}

cj_status cj_viewer_submit(cj_viewer *v, int one_pass) {
    v->dirty = 0;
    v->redraw = 1;
    /* drags show the rasterized view; a playing animation one full-resolution pass per frame */
    const int trace = v->trace && v->drag == VIEW_DRAG_NONE;
    int first = 0, last = one_pass ? 0 : VIEW_TRACE_PASSES - 1;
    if (trace && v->playing) first = last = 1;
    return submit(v, trace, trace ? first : 0, trace ? last : 0);
}

int cj_viewer_refinable(const cj_viewer *v) {
    return v->mode3d && v->trace && v->shown_trace && v->shown_gen == v->gen && !v->playing &&
           v->shown_pass + 1 < VIEW_TRACE_PASSES;
}

cj_status cj_viewer_refine(cj_viewer *v) {
    if (!cj_viewer_refinable(v)) return CJ_OK;
    return submit(v, 1, v->shown_pass + 1, v->shown_pass + 1);
}

int cj_viewer_collect(cj_viewer *v) {
    const cj_vframe *f = cj_vrender_take(v->rt);
    if (!f) return 0;
    v->redraw = 1;
    if (f->status) {
        snprintf(v->msg, sizeof v->msg, "render failed: %.200s", f->msg);
        return 1;
    }
    const size_t w = (size_t)v->width;
    for (int y = 0; y < v->height; ++y)
        memcpy(v->pic->pixels + (ptrdiff_t)y * v->pic->stride, f->rgba8 + 4 * w * (size_t)y, 4 * w);
    if (!f->trace) {
        const size_t n = w * (size_t)v->height;
        if (!v->depth) v->depth = malloc(n * sizeof *v->depth);
        if (v->depth) memcpy(v->depth, f->depth, n * sizeof *v->depth);
    }
    v->shown_gen = f->gen;
    v->shown_trace = f->trace;
    v->shown_pass = f->pass;
    v->shown_spp = f->spp;
    v->shown_tol = f->tol_px;
    v->render_s = f->seconds;
    if (!f->trace) v->triangles = f->triangles, v->bound_px = f->bound_px;
    return 1;
}

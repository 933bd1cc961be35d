/* The viewer's pictures: rendering exactly what the offline commands render (`pic`), and the
 * overlay drawn over a copy of it (`screen`): the selection, the curvature comb, the status
 * text and the help. The document they show is loaded and saved by viewer_doc.c. */
#define _POSIX_C_SOURCE 200809L
#include "viewer_app.h"

#include "casteljau/anim_json.h"
#include "casteljau/flatten.h"
#include "casteljau/line.h"
#include "casteljau/patchset.h"
#include "casteljau/rational.h"
#include "casteljau/scene_json.h"
#include "casteljau/scene_textures.h"
#include "casteljau/trace.h"
#include "error_internal.h"
#include "clock_internal.h"

#include <cJSON.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* 2D: the plot of the document, drawn here (it takes milliseconds). */
static cj_status render_2d(cj_viewer *v) {
    cj_plot *plot = NULL;
    cj_status st = cj_vdoc_build_plot(v->doc, &v->view, &v->disp, &plot);
    if (st) return st;
    /* as cj_plot_doc_render: clear to the background, then the one panel over the whole image */
    cj_framebuffer_clear(v->pic, v->disp.background);
    st = cj_plot_render(plot, v->pic, 0, 0, v->width, v->height, v->font);
    cj_plot_destroy(plot);
    return st;
}

void cj_viewer_tick(cj_viewer *v) {
    if (!v->anim || !v->playing) return;
    if (v->anim_frame >= v->anim->frame_last) {
        v->playing = 0;
        snprintf(v->msg, sizeof v->msg, "end of the animation (F5 reloads it)");
        return;
    }
    cj_status st = cj_anim_doc_frame(v->anim, cj_vscene_scene(v->vs), ++v->anim_frame, NULL);
    if (!st) st = cj_vscene_update(v->vs);
    if (st) {
        v->playing = 0;
        snprintf(v->msg, sizeof v->msg, "animation: %s", cj_last_error());
    }
    v->dirty = 1;
}

cj_status cj_viewer_draw(cj_viewer *v) {
    cj_status st = CJ_OK;
    if (!v->mode3d && v->dirty) {
        const double t0 = cj_clock_seconds();
        st = render_2d(v);
        v->render_s = cj_clock_seconds() - t0;
        v->dirty = 0;
        if (st) snprintf(v->msg, sizeof v->msg, "render failed: %s", cj_last_error());
        free(v->marks);
        v->marks = NULL;
        v->nmarks = v->isect_failed = 0;
        /* intersections at a thousandth of a pixel */
        if (v->isect_on && cj_vdoc_intersections(v->doc, 1e-3 / cj_vview_scale(&v->view), &v->marks,
                                                 &v->nmarks, &v->isect_failed))
            snprintf(v->msg, sizeof v->msg, "intersections: %s", cj_last_error());
    }
    v->redraw = 0;
    for (int y = 0; y < v->height; ++y)
        memcpy(v->screen->pixels + (ptrdiff_t)y * v->screen->stride,
               v->pic->pixels + (ptrdiff_t)y * v->pic->stride, (size_t)v->width * sizeof(cj_rgba));
    cj_viewer_overlay(v);
    return st;
}

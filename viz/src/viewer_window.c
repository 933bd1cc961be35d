/* The viewer's window: GLFW for the window, input and timing; OpenGL only to show our own
 * framebuffer as a texture drawn 1:1 (nearest filtering, texel centres on pixel centres, no
 * blending or dithering), so the window's pixels are the framebuffer's. Screenshots read the
 * back buffer with glReadPixels before the swap. */
#define _POSIX_C_SOURCE 200809L
#include "viewer_app.h"
#include "viewer_plugin.h"
#include "viewer_render.h"

#include "casteljau/image_io.h"
#include "error_internal.h"
#include "clock_internal.h"

#define GLFW_INCLUDE_NONE
#include <GL/gl.h>
#include <GLFW/glfw3.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

typedef struct win {
    cj_viewer v;
    GLFWwindow *w;
    GLuint tex;
    double *times;
    size_t ntimes, cap;
    int replaying; /* real input is ignored while a script drives the viewer */
    /* The pointer as the last motion event put it. A press uses this, not glfwGetCursorPos
     * (which asks the server where the pointer is NOW: a slow frame would see later motion). */
    double px, py;
    FILE *timeline; /* --timeline: input, passes and frames shown */
} win;

static char glfw_msg[256];

static void on_error(int code, const char *desc) {
    snprintf(glfw_msg, sizeof glfw_msg, "GLFW error 0x%x: %s", code, desc);
}

static int glfw_mods(GLFWwindow *w) {
    int m = 0;
    if (glfwGetKey(w, GLFW_KEY_LEFT_SHIFT) == GLFW_PRESS ||
        glfwGetKey(w, GLFW_KEY_RIGHT_SHIFT) == GLFW_PRESS)
        m |= VIEW_MOD_SHIFT;
    if (glfwGetKey(w, GLFW_KEY_LEFT_CONTROL) == GLFW_PRESS ||
        glfwGetKey(w, GLFW_KEY_RIGHT_CONTROL) == GLFW_PRESS)
        m |= VIEW_MOD_CTRL;
    return m;
}

static int live(GLFWwindow *w) {
    return !((win *)glfwGetWindowUserPointer(w))->replaying;
}

static void on_key(GLFWwindow *w, int key, int scancode, int action, int mods) {
    (void)scancode;
    if (action == GLFW_RELEASE || !live(w)) return;
    win *g = glfwGetWindowUserPointer(w);
    cj_vrender_log(g->v.rt, "key %d", key);
    cj_viewer_key(&g->v, key, mods);
}

static void on_button(GLFWwindow *w, int button, int action, int mods) {
    if (!live(w)) return;
    win *g = glfwGetWindowUserPointer(w);
    cj_vrender_log(g->v.rt, "button %d %s", button, action == GLFW_PRESS ? "press" : "release");
    cj_viewer_button(&g->v, button, action == GLFW_PRESS, mods, g->px, g->py);
}

static void on_cursor(GLFWwindow *w, double x, double y) {
    if (!live(w)) return;
    win *g = glfwGetWindowUserPointer(w);
    g->px = x, g->py = y;
    cj_viewer_cursor(&g->v, x, y, glfw_mods(w));
}

static void on_scroll(GLFWwindow *w, double dx, double dy) {
    (void)dx;
    if (!live(w)) return;
    win *g = glfwGetWindowUserPointer(w);
    cj_vrender_log(g->v.rt, "scroll %g", dy);
    cj_viewer_scroll(&g->v, dy);
}

/* The window was uncovered or mapped: show it again (in the loop, not inside the callback). */
static void on_refresh(GLFWwindow *w) {
    ((win *)glfwGetWindowUserPointer(w))->v.redraw = 1;
}

/* Called by the render thread when a frame is ready: wakes the event loop. */
static void wake(void) {
    glfwPostEmptyEvent();
}

static cj_status screenshot(win *g, const char *path) {
    const int w = g->v.width, h = g->v.height;
    uint8_t *px = malloc((size_t)w * (size_t)h * 4);
    if (!px) return cj_fail(CJ_ERR_NOMEM, "viewer: out of memory for a screenshot");
    glReadBuffer(GL_BACK);
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, px);
    /* rows bottom-up, as the framebuffer and the image writer expect */
    cj_status st = cj_image_write_png(path, w, h, px, 0);
    free(px);
    return st;
}

static double cpu_s(void) {
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* Shows `screen` (the picture and the overlay, composed now) in the back buffer; optionally
 * reads it; swaps. */
static cj_status present(win *g, const char *shot) {
    cj_status st = cj_viewer_draw(&g->v);
    const cj_framebuffer *fb = g->v.screen;
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glPixelStorei(GL_UNPACK_ROW_LENGTH, (GLint)fb->stride);
    glBindTexture(GL_TEXTURE_2D, g->tex);
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, fb->width, fb->height, GL_RGBA, GL_UNSIGNED_BYTE,
                    fb->pixels);
    glViewport(0, 0, fb->width, fb->height);
    glClear(GL_COLOR_BUFFER_BIT);
    glBegin(GL_QUADS);
    glTexCoord2f(0, 0), glVertex2f(-1, -1);
    glTexCoord2f(1, 0), glVertex2f(1, -1);
    glTexCoord2f(1, 1), glVertex2f(1, 1);
    glTexCoord2f(0, 1), glVertex2f(-1, 1);
    glEnd();
    if (shot) {
        cj_status s2 = screenshot(g, shot);
        if (!st) st = s2;
    }
    glfwSwapBuffers(g->w);
    glFinish();
    cj_vrender_log(g->v.rt, "shown gen %lu %s pass %d", g->v.shown_gen,
                   g->v.shown_trace ? "trace" : "raster", g->v.shown_pass);
    return st;
}

static void record_time(win *g, double dt, double dc) {
    if (g->ntimes + 2 > g->cap) {
        size_t cap = g->cap ? 2 * g->cap : 512;
        double *nt = realloc(g->times, cap * sizeof *nt);
        if (nt) g->times = nt, g->cap = cap;
    }
    if (g->ntimes + 2 <= g->cap) {
        g->times[g->ntimes++] = dt;
        g->times[g->ntimes++] = dc;
    }
}

/* A frame of a replay (and the first one): draws the state and waits for the picture, so a
 * script is deterministic. A playing animation advances one frame; a still ray-traced view
 * draws its next pass. Records its wall and process CPU time (render + upload + draw + swap +
 * glFinish). */
static cj_status frame_sync(win *g, const char *shot) {
    const double t0 = cj_clock_seconds(), c0 = cpu_s();
    cj_viewer *v = &g->v;
    cj_status st = CJ_OK;
    cj_viewer_tick(v);
    if (v->mode3d) {
        if (v->dirty)
            st = cj_viewer_submit(v, 1);
        else
            st = cj_viewer_refine(v);
        cj_vrender_wait(v->rt);
        cj_viewer_collect(v);
    }
    cj_status s2 = present(g, shot);
    if (!st) st = s2;
    record_time(g, cj_clock_seconds() - t0, cpu_s() - c0);
    return st;
}

static cj_status run_replay(win *g, const char *script) {
    FILE *f = fopen(script, "r");
    if (!f) return cj_fail(CJ_ERR_IO, "%s: cannot read the replay script", script);
    size_t cap = 100002;
    cj_vevent *ev = malloc(cap * sizeof *ev);
    if (!ev) {
        fclose(f);
        return cj_fail(CJ_ERR_NOMEM, "viewer: out of memory for the replay");
    }
    char line[2048];
    cj_status st = CJ_OK;
    for (int lineno = 1; !st && !g->v.quit && fgets(line, sizeof line, f); ++lineno) {
        size_t n = 0;
        if ((st = cj_viewer_parse_line(script, lineno, line, ev, cap, &n))) break;
        for (size_t i = 0; !st && i < n && !g->v.quit; ++i) {
            const cj_vevent *e = &ev[i];
            glfwPollEvents(); /* keep the window responsive */
            if (e->type == VEV_FRAME || e->type == VEV_SCREENSHOT) {
                st = frame_sync(g, e->type == VEV_SCREENSHOT ? e->arg : NULL);
            } else if (e->type == VEV_SAVE) {
                st = cj_viewer_save(&g->v, e->arg);
            } else {
                cj_viewer_apply(&g->v, e);
                if (g->v.dirty || g->v.redraw) st = frame_sync(g, NULL);
            }
        }
    }
    free(ev);
    fclose(f);
    return st;
}

static void write_times(const win *g, const char *path) {
    FILE *f = fopen(path, "w");
    if (!f) return;
    for (size_t i = 0; i + 1 < g->ntimes; i += 2)
        fprintf(f, "%.9f %.9f\n", g->times[i], g->times[i + 1]);
    fclose(f);
}

static cj_status open_window(win *g) {
    const cj_viewer_options *o = g->v.opt;
    glfwSetErrorCallback(on_error);
    if (!glfwInit())
        return cj_fail(CJ_ERR_UNSUPPORTED, "no display: cannot open a window (%s)",
                       glfw_msg[0] ? glfw_msg : "DISPLAY is not set");
    glfwWindowHint(GLFW_RESIZABLE, GLFW_FALSE);
    glfwWindowHint(GLFW_SCALE_TO_MONITOR, GLFW_FALSE);
    glfwWindowHint(GLFW_DOUBLEBUFFER, GLFW_TRUE);
    g->w = glfwCreateWindow(g->v.width, g->v.height, o->title ? o->title : "casteljau view", NULL,
                            NULL);
    if (!g->w)
        return cj_fail(CJ_ERR_UNSUPPORTED, "cannot create a %d x %d OpenGL window (%s)", g->v.width,
                       g->v.height, glfw_msg);
    int fw, fh;
    glfwGetFramebufferSize(g->w, &fw, &fh);
    if (fw != g->v.width || fh != g->v.height)
        return cj_fail(CJ_ERR_UNSUPPORTED,
                       "the window's framebuffer is %d x %d, not %d x %d (a scaled display): "
                       "pixels could not be shown 1:1",
                       fw, fh, g->v.width, g->v.height);
    glfwSetWindowUserPointer(g->w, g);
    glfwMakeContextCurrent(g->w);
    glfwSwapInterval(0); /* frames are paced by events, not the display */
    glfwSetKeyCallback(g->w, on_key);
    glfwSetMouseButtonCallback(g->w, on_button);
    glfwSetCursorPosCallback(g->w, on_cursor);
    glfwSetScrollCallback(g->w, on_scroll);
    glfwSetWindowRefreshCallback(g->w, on_refresh);
    glfwGetCursorPos(g->w, &g->px, &g->py);
    glDisable(GL_DITHER);
    glDisable(GL_BLEND);
    glDisable(GL_DEPTH_TEST);
    glEnable(GL_TEXTURE_2D);
    glGenTextures(1, &g->tex);
    glBindTexture(GL_TEXTURE_2D, g->tex);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP);
    glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_REPLACE);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, g->v.width, g->v.height, 0, GL_RGBA, GL_UNSIGNED_BYTE,
                 NULL);
    return glGetError() == GL_NO_ERROR
               ? CJ_OK
               : cj_fail(CJ_ERR_UNSUPPORTED, "OpenGL refused a %d x %d texture", g->v.width,
                         g->v.height);
}

/* The interactive loop: input is handled at once while the render thread draws; a finished
 * picture is shown as soon as it arrives (the thread wakes the loop), the overlay whenever it
 * changes. The loop sleeps in glfwWaitEvents otherwise. */
static cj_status run_live(win *g) {
    cj_viewer *v = &g->v;
    cj_status st = CJ_OK;
    while (!st && !v->quit && !glfwWindowShouldClose(g->w)) {
        if (v->mode3d) {
            if (v->dirty) st = cj_viewer_submit(v, 0);
            if (cj_viewer_collect(v) && v->playing && v->shown_gen == v->gen) cj_viewer_tick(v);
        }
        if (!st && (v->dirty || v->redraw)) {
            const double t0 = cj_clock_seconds(), c0 = cpu_s();
            st = present(g, NULL);
            record_time(g, cj_clock_seconds() - t0, cpu_s() - c0);
        }
        if (v->quit || (v->mode3d && v->dirty)) continue;
        glfwWaitEvents();
    }
    return st;
}

cj_status cj_viewer_window_run(const cj_viewer_options *opt) {
    win *g = calloc(1, sizeof *g);
    if (!g) return cj_fail(CJ_ERR_NOMEM, "viewer: out of memory");
    cj_viewer *v = &g->v;
    v->opt = opt;
    v->show_overlay = !opt->hide_overlay;
    v->dirty = 1;
    cj_status st = CJ_OK;
    if (opt->timeline && !(g->timeline = fopen(opt->timeline, "w")))
        st = cj_fail(CJ_ERR_IO, "%s: cannot write the timeline", opt->timeline);
    if (!st) st = cj_viewer_load(v);
    if (!st) st = cj_framebuffer_create(v->width, v->height, 0, NULL, &v->pic);
    if (!st) st = cj_framebuffer_create(v->width, v->height, 0, NULL, &v->screen);
    if (!st && cj_font_open(NULL, &v->font)) v->font = NULL; /* no text, still a viewer */
    if (!st) st = open_window(g);
    if (!st) st = cj_viewer_live_start(v, g->timeline, wake);
    if (!st && opt->replay) {
        g->replaying = 1;
        st = frame_sync(g, NULL);
        if (!st) st = run_replay(g, opt->replay);
        if (!st && opt->screenshot) st = frame_sync(g, opt->screenshot);
    } else if (!st) {
        st = run_live(g);
        if (!st && opt->screenshot) st = present(g, opt->screenshot); /* what is shown */
    }
    cj_viewer_live_stop(v); /* before the scene goes: the thread draws copies, but joins here */
    if (opt->frame_times) write_times(g, opt->frame_times);
    if (g->w) {
        glDeleteTextures(1, &g->tex);
        glfwDestroyWindow(g->w);
    }
    glfwTerminate();
    if (g->timeline) fclose(g->timeline);
    cj_font_close(v->font);
    cj_framebuffer_destroy(v->pic);
    cj_framebuffer_destroy(v->screen);
    cj_viewer_unload(v);
    free(g->times);
    free(g);
    return st;
}

/* The viewer's input: keys, mouse buttons, cursor motion and the wheel, turned into editor
 * commands. Real GLFW events and replayed ones arrive here alike. */
#include "viewer_app.h"
#include "viewer_render.h"

#include "casteljau/rational.h"
#include "casteljau/scene.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <math.h>
#include <stdio.h>
#include <string.h>

#define PICK_RADIUS 8.0

static void say(cj_viewer *v, const char *what, cj_status st) {
    if (st)
        snprintf(v->msg, sizeof v->msg, "%s: %s", what, cj_last_error());
    else
        snprintf(v->msg, sizeof v->msg, "%s", what);
    v->dirty = 1;
}

static const cj_vcurve *sel_curve(const cj_viewer *v) {
    return v->disp.curve >= 0 ? cj_vdoc_curve(v->doc, (size_t)v->disp.curve) : NULL;
}

/* Keeps the selection valid after edits that change the number of curves or points. */
static void fix_selection(cj_viewer *v) {
    const size_t n = cj_vdoc_curve_count(v->doc);
    if (v->disp.curve >= (long)n) v->disp.curve = (long)n - 1;
    const cj_vcurve *c = sel_curve(v);
    if (!c || v->sel_point >= (long)c->count) v->sel_point = -1;
}

static void save(cj_viewer *v) {
    char path[4096];
    cj_viewer_save_path(v, path, sizeof path);
    cj_status st = cj_viewer_save(v, path);
    snprintf(v->msg, sizeof v->msg, st ? "save failed: %s" : "saved %s",
             st ? cj_last_error() : path);
    v->dirty = 1;
}

static void reload(cj_viewer *v) {
    cj_viewer_unload(v);
    const int w = v->width, h = v->height;
    cj_status st = cj_viewer_load(v);
    /* the window keeps its size */
    if (!st && (v->width != w || v->height != h)) {
        st = CJ_ERR_RANGE;
        snprintf(v->msg, sizeof v->msg, "reload: the file changed the picture size");
    }
    if (st) v->quit = 1; /* nothing left to show */
    if (!st) say(v, "reloaded", CJ_OK);
}

static void undo_redo(cj_viewer *v, int redo) {
    cj_status st;
    if (v->mode3d)
        st = redo ? cj_vscene_redo(v->vs) : cj_vscene_undo(v->vs);
    else
        st = redo ? cj_vdoc_redo(v->doc) : cj_vdoc_undo(v->doc);
    if (!v->mode3d) fix_selection(v);
    say(v, redo ? "redo" : "undo", st);
}

/* The snap tolerance: a thousandth of a pixel, in data units. */
static double snap_tol(const cj_viewer *v) {
    return 1e-3 / cj_vview_scale(&v->view);
}

/* With snapping on: the certified nearest curve point to the cursor (shown in the overlay). */
static void snap_cursor(cj_viewer *v) {
    double q[2];
    cj_vview_from_px(&v->view, v->cx, v->cy, q);
    v->snap.curve = -1;
    cj_status st = cj_vdoc_snap(v->doc, q, -1, snap_tol(v), &v->snap);
    if (st) {
        v->snap.curve = -1;
        say(v, "snap", st);
    }
    v->redraw = 1;
}

/* B-splines: one knot at the parameter of the curve point nearest to the cursor. */
static void insert_knot_at_cursor(cj_viewer *v, size_t ci) {
    double q[2];
    cj_vsnap near;
    cj_vview_from_px(&v->view, v->cx, v->cy, q);
    cj_status st = cj_vcurve_nearest(cj_vdoc_curve(v->doc, ci), q, snap_tol(v), &near);
    if (!st) st = cj_vdoc_insert_knot(v->doc, ci, near.u);
    if (!st) v->sel_point = -1;
    if (!st) {
        snprintf(v->msg, sizeof v->msg, "inserted the knot %.6g (the curve is unchanged)", near.u);
        v->dirty = 1;
    } else {
        say(v, "insert a knot", st);
    }
}

static void key_2d(cj_viewer *v, int key, int mods) {
    const cj_vcurve *c = sel_curve(v);
    const size_t ci = (size_t)v->disp.curve;
    const double step = (mods & VIEW_MOD_SHIFT) ? 0.1 : 0.01;
    cj_vcurve style;
    switch (key) {
    case GLFW_KEY_TAB:
        if (cj_vdoc_curve_count(v->doc))
            v->disp.curve = (v->disp.curve + 1) % (long)cj_vdoc_curve_count(v->doc);
        v->sel_point = -1;
        v->dirty = 1;
        return;
    case GLFW_KEY_LEFT_BRACKET:
    case GLFW_KEY_RIGHT_BRACKET:
        v->disp.t = fmin(1.0, fmax(0.0, v->disp.t + (key == GLFW_KEY_LEFT_BRACKET ? -step : step)));
        v->dirty = 1;
        return;
    case GLFW_KEY_C:
        v->disp.construction = !v->disp.construction;
        v->dirty = 1;
        return;
    case GLFW_KEY_F:
        v->disp.frame = !v->disp.frame;
        v->dirty = 1;
        return;
    case GLFW_KEY_K:
        v->comb = !v->comb;
        v->dirty = 1;
        return;
    case GLFW_KEY_M:
        v->method = (cj_eval_method)((v->method + 1) % 4);
        v->dirty = 1;
        return;
    case GLFW_KEY_HOME:
        cj_vview_fit(&v->view, v->doc, 0.1);
        v->dirty = 1;
        return;
    case GLFW_KEY_P:
        v->snap_on = !v->snap_on;
        v->snap.curve = -1;
        if (v->snap_on) snap_cursor(v);
        snprintf(v->msg, sizeof v->msg, "snapping %s", v->snap_on ? "on" : "off");
        return;
    case GLFW_KEY_T:
        v->isect_on = !v->isect_on;
        v->dirty = 1; /* recomputed with the picture */
        return;
    default:
        break;
    }
    if (!c) return;
    switch (key) {
    case GLFW_KEY_H:
        style = *c;
        style.hull = !style.hull;
        say(v, "hull", cj_vdoc_set_style(v->doc, ci, &style));
        break;
    case GLFW_KEY_E:
        say(v, "elevated", cj_vdoc_elevate(v->doc, ci));
        break;
    case GLFW_KEY_S:
        say(v, "split at t", cj_vdoc_split(v->doc, ci, v->disp.t));
        break;
    case GLFW_KEY_DELETE:
    case GLFW_KEY_BACKSPACE:
    case GLFW_KEY_X:
        if (v->sel_point >= 0) {
            cj_status st = cj_vdoc_delete_point(v->doc, ci, (size_t)v->sel_point);
            if (!st) v->sel_point = -1;
            say(v, "deleted a point", st);
        }
        break;
    case GLFW_KEY_I:
        if (c->kind == CJ_VCURVE_BSPLINE) {
            insert_knot_at_cursor(v, ci);
        } else if (v->sel_point >= 0) {
            const size_t i = (size_t)v->sel_point, n = c->count;
            const double *p = c->pts + 2 * i;
            double q[2];
            if (i + 1 < n)
                q[0] = 0.5 * (p[0] + p[2]), q[1] = 0.5 * (p[1] + p[3]);
            else if (n > 1)
                q[0] = 2 * p[0] - p[-2], q[1] = 2 * p[1] - p[-1];
            else
                q[0] = p[0] + 1, q[1] = p[1];
            cj_status st = cj_vdoc_insert_point(v->doc, ci, i + 1, q[0], q[1]);
            if (!st) v->sel_point = (long)i + 1;
            say(v, "inserted a point", st);
        }
        break;
    case GLFW_KEY_A: {
        double q[2];
        cj_vview_from_px(&v->view, v->cx, v->cy, q);
        cj_status st = cj_vdoc_insert_point(v->doc, ci, c->count, q[0], q[1]);
        if (!st) v->sel_point = (long)cj_vdoc_curve(v->doc, ci)->count - 1;
        say(v, "appended a point", st);
        break;
    }
    case GLFW_KEY_W:
        if (v->sel_point >= 0 && (c->weights || c->kind == CJ_VCURVE_BSPLINE)) {
            const double w = c->weights ? c->weights[v->sel_point] : 1.0;
            say(v, "weight",
                cj_vdoc_set_weight(v->doc, ci, (size_t)v->sel_point,
                                   (mods & VIEW_MOD_SHIFT) ? w / 1.25 : w * 1.25));
        }
        break;
    default:
        break;
    }
    fix_selection(v);
}

static void set_all_overlays(cj_viewer *v, unsigned flag) {
    cj_scene *s = cj_vscene_scene(v->vs);
    int any_on = 0;
    for (size_t i = 0; i < cj_scene_node_count(s); ++i)
        any_on |= (cj_scene_node(s, (int)i)->overlay.flags & flag) != 0;
    for (size_t i = 0; i < cj_scene_node_count(s); ++i) {
        cj_node *n = cj_scene_node_mut(s, (int)i);
        if (n->geometry < 0) continue;
        n->overlay.flags = any_on ? (n->overlay.flags & ~flag) : (n->overlay.flags | flag);
    }
}

static void key_3d(cj_viewer *v, int key, int mods) {
    cj_scene *s = cj_vscene_scene(v->vs);
    cj_scene_settings set = *cj_scene_get_settings(s);
    switch (key) {
    case GLFW_KEY_N:
        set_all_overlays(v, CJ_OVERLAY_CONTROL_NET);
        say(v, "control nets", CJ_OK);
        break;
    case GLFW_KEY_W: {
        /* a selected NURBS net point: its weight, as W / shift+W in the 2D editor */
        double w;
        if (v->sel3 >= 0 && cj_vscene_point_weight(v->vs, (size_t)v->sel3, &w)) {
            say(v, "weight",
                cj_vscene_set_weight(v->vs, (size_t)v->sel3,
                                     (mods & VIEW_MOD_SHIFT) ? w / 1.25 : w * 1.25));
            break;
        }
        set_all_overlays(v, CJ_OVERLAY_WIREFRAME);
        say(v, "wireframe", CJ_OK);
        break;
    }
    case GLFW_KEY_G: {
        const cj_shading next =
            (cj_shading)((cj_scene_material(s, 0) ? cj_scene_material(s, 0)->shading + 1 : 0) % 3);
        for (size_t i = 0; i < cj_scene_material_count(s); ++i)
            cj_scene_material_mut(s, (int)i)->shading = next;
        static const char *const names[] = {"flat shading", "Gouraud shading", "Phong shading"};
        say(v, names[next], CJ_OK);
        break;
    }
    case GLFW_KEY_EQUAL:
    case GLFW_KEY_KP_ADD:
    case GLFW_KEY_MINUS:
    case GLFW_KEY_KP_SUBTRACT:
        set.tol_px = (key == GLFW_KEY_EQUAL || key == GLFW_KEY_KP_ADD)
                         ? fmin(16.0, set.tol_px * 2)
                         : fmax(1.0 / 64, set.tol_px / 2);
        say(v, "screen tolerance", cj_scene_set_settings(s, &set));
        break;
    case GLFW_KEY_R:
        v->trace = !v->trace;
        say(v, v->trace ? "ray tracing" : "rasterizing", CJ_OK);
        break;
    case GLFW_KEY_L:
        cj_vscene_set_linked(v->vs, !cj_vscene_linked(v->vs));
        snprintf(v->msg, sizeof v->msg, "shared points move %s",
                 cj_vscene_linked(v->vs) ? "together" : "alone");
        v->redraw = 1; /* nothing in the picture changes */
        break;
    case GLFW_KEY_X:
    case GLFW_KEY_Y:
    case GLFW_KEY_Z:
        v->axis = key - GLFW_KEY_X;
        say(v, "drag axis", CJ_OK);
        break;
    case GLFW_KEY_SPACE:
        if (!v->anim) {
            say(v, "no animation: open an animation document (casteljau animate's)", CJ_OK);
        } else {
            v->playing = !v->playing;
            say(v, v->playing ? "playing" : "paused", CJ_OK);
        }
        break;
    default:
        break;
    }
}

void cj_viewer_key(cj_viewer *v, int key, int mods) {
    /* every key at least shows the window again (the overlay and help are not in the picture:
     * O, F1 and / change only the screen, and must show at once) */
    v->redraw = 1;
    if (mods & VIEW_MOD_CTRL) {
        if (key == GLFW_KEY_Z)
            undo_redo(v, (mods & VIEW_MOD_SHIFT) != 0);
        else if (key == GLFW_KEY_Y)
            undo_redo(v, 1);
        else if (key == GLFW_KEY_S)
            save(v);
        else if (key == GLFW_KEY_R)
            reload(v);
        return;
    }
    switch (key) {
    case GLFW_KEY_ESCAPE:
    case GLFW_KEY_Q:
        v->quit = 1;
        return;
    case GLFW_KEY_O:
        v->show_overlay = !v->show_overlay;
        return;
    case GLFW_KEY_F1:
    case GLFW_KEY_SLASH:
        v->show_help = !v->show_help;
        return;
    case GLFW_KEY_F5:
        reload(v);
        return;
    default:
        break;
    }
    if (v->mode3d)
        key_3d(v, key, mods);
    else
        key_2d(v, key, mods);
}

/* The parameter of the selected curve whose point is nearest to the cursor (2049 samples). */
static void t_at_cursor(cj_viewer *v) {
    const cj_vcurve *c = sel_curve(v);
    if (!c || c->kind >= CJ_VCURVE_SPLINE) return;
    double best = INFINITY, bt = v->disp.t;
    for (int i = 0; i <= 2048; ++i) {
        const double t = i / 2048.0;
        double p[2], q[2];
        if (c->kind == CJ_VCURVE_RATIONAL) {
            cj_rbezier rb = cj_rbezier_view((int)c->count - 1, 2, c->pts, c->weights);
            if (cj_rbezier_eval(&rb, t, p)) return;
        } else {
            cj_bezier b = cj_bezier_view((int)c->count - 1, 2, c->pts);
            if (cj_bezier_eval(&b, CJ_EVAL_DECASTELJAU, t, p)) return;
        }
        cj_vview_to_px(&v->view, p[0], p[1], q);
        const double d = hypot(q[0] - v->cx, q[1] - v->cy);
        if (d < best) best = d, bt = t;
    }
    v->disp.t = bt;
    v->dirty = 1;
}

void cj_viewer_button(cj_viewer *v, int button, int press, int mods, double x, double y) {
    v->cx = x + 0.5;
    v->cy = v->height - y - 0.5;
    if (!press) {
        if (v->drag == VIEW_DRAG_POINT) {
            if (v->mode3d)
                cj_vscene_end_drag(v->vs);
            else
                cj_vdoc_end_drag(v->doc);
        }
        /* 3D: the frames of a drag may reuse meshes and are never traced; the still view is
         * drawn again as the offline renderers draw it */
        if (v->drag != VIEW_DRAG_NONE && v->mode3d) v->dirty = 1;
        v->drag = VIEW_DRAG_NONE;
        return;
    }
    v->px0 = v->cx;
    v->py0 = v->cy;
    v->view0 = v->view;
    if (v->mode3d) {
        size_t k;
        if (button == VIEW_BUTTON_LEFT &&
            cj_vscene_pick(v->vs, v->width, v->height, v->depth, v->cx, v->cy, PICK_RADIUS, &k)) {
            v->sel3 = (long)k;
            v->drag = VIEW_DRAG_POINT;
            cj_vscene_begin_drag(v->vs);
            cj_vrender_log(v->rt, "drag point %zu", k);
            (void)mods;
        } else {
            v->drag = button == VIEW_BUTTON_LEFT ? VIEW_DRAG_ORBIT : VIEW_DRAG_PAN;
        }
        /* the selection is overlay; a traced view gives way to the rasterized one at once */
        v->redraw = 1;
        if (v->trace) v->dirty = 1;
        return;
    }
    size_t ci, pi;
    if (button == VIEW_BUTTON_LEFT &&
        cj_vdoc_pick(v->doc, &v->view, v->cx, v->cy, PICK_RADIUS, &ci, &pi)) {
        v->disp.curve = (long)ci;
        v->sel_point = (long)pi;
        const cj_vcurve *c = cj_vdoc_curve(v->doc, ci);
        double q[2];
        cj_vview_to_px(&v->view, c->pts[2 * pi], c->pts[2 * pi + 1], q);
        v->dpx0 = q[0];
        v->dpy0 = q[1];
        v->drag = VIEW_DRAG_POINT;
        cj_vdoc_begin_drag(v->doc);
    } else if (button == VIEW_BUTTON_RIGHT) {
        v->drag = VIEW_DRAG_T;
        t_at_cursor(v);
    } else {
        v->drag = VIEW_DRAG_PAN;
    }
    v->dirty = 1;
}

void cj_viewer_cursor(cj_viewer *v, double x, double y, int mods) {
    const double lx = v->cx, ly = v->cy;
    v->cx = x + 0.5;
    v->cy = v->height - y - 0.5;
    if (v->drag == VIEW_DRAG_NONE) {
        if (v->snap_on && !v->mode3d) snap_cursor(v);
        return;
    }
    v->dirty = 1;
    cj_status st = CJ_OK;
    if (v->mode3d) {
        if (v->drag == VIEW_DRAG_POINT)
            st = cj_vscene_drag(v->vs, (size_t)v->sel3, v->width, v->height, v->px0, v->py0, v->cx,
                                v->cy, (mods & VIEW_MOD_SHIFT) ? v->axis : -1);
        else if (v->drag == VIEW_DRAG_ORBIT)
            st = cj_vscene_orbit(v->vs, v->cx - lx, v->cy - ly);
        else
            st = cj_vscene_pan(v->vs, v->cx - lx, v->cy - ly, v->height);
        if (st) say(v, "drag", st);
        return;
    }
    if (v->drag == VIEW_DRAG_POINT) {
        /* The point's pixel position at the press, plus the cursor's displacement since. */
        double q[2];
        cj_vview_from_px(&v->view, v->dpx0 + (v->cx - v->px0), v->dpy0 + (v->cy - v->py0), q);
        if (v->snap_on) { /* onto the nearest point of another curve */
            v->snap.curve = -1;
            if (!cj_vdoc_snap(v->doc, q, v->disp.curve, snap_tol(v), &v->snap))
                q[0] = v->snap.point[0], q[1] = v->snap.point[1];
        }
        st = cj_vdoc_move_point(v->doc, (size_t)v->disp.curve, (size_t)v->sel_point, q[0], q[1]);
    } else if (v->drag == VIEW_DRAG_T) {
        t_at_cursor(v);
    } else {
        const double s = cj_vview_scale(&v->view0);
        const double dx = (v->cx - v->px0) / s, dy = (v->cy - v->py0) / s;
        v->view.x0 = v->view0.x0 - dx, v->view.x1 = v->view0.x1 - dx;
        v->view.y0 = v->view0.y0 - dy, v->view.y1 = v->view0.y1 - dy;
    }
    if (st) say(v, "drag", st);
}

void cj_viewer_scroll(cj_viewer *v, double dy) {
    const double f = pow(1.1, -dy);
    v->dirty = 1;
    if (v->mode3d) {
        cj_status st = cj_vscene_zoom(v->vs, f);
        if (st) say(v, "zoom", st);
        return;
    }
    double d[2];
    cj_vview_from_px(&v->view, v->cx, v->cy, d);
    v->view.x0 = d[0] + (v->view.x0 - d[0]) * f, v->view.x1 = d[0] + (v->view.x1 - d[0]) * f;
    v->view.y0 = d[1] + (v->view.y0 - d[1]) * f, v->view.y1 = d[1] + (v->view.y1 - d[1]) * f;
}

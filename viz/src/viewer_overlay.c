/* The viewer's overlay, drawn over a copy of the picture (`screen`): the status text in a panel
 * with its own background (in 2D placed in the corner that covers the fewest curve points),
 * the selection, the 3D control points, the curvature comb, and the help panel sized from its
 * text. */
#include "viewer_app.h"

#include "casteljau/anim_json.h"
#include "casteljau/flatten.h"
#include "casteljau/line.h"
#include "casteljau/rational.h"
#include "viewer_render.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { PANEL_LINES = 18 };
#define TEXT_PX 12.5
#define LINE_PX 15.0
#define PAD_PX  6.0

typedef struct panel {
    int n;
    char line[PANEL_LINES][256];
    double w, h; /* box size in pixels */
} panel;

static void add(panel *p, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;
static void add(panel *p, const char *fmt, ...) {
    if (p->n == PANEL_LINES) return;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(p->line[p->n++], sizeof p->line[0], fmt, ap);
    va_end(ap);
}

/* The box around the text: the widest line's advance plus padding, the lines' pitch. */
static void measure(cj_viewer *v, panel *p) {
    double w = 0;
    for (int i = 0; i < p->n; ++i) {
        double adv = 0;
        if (!cj_font_measure(v->font, TEXT_PX, p->line[i], &adv, NULL, NULL) && adv > w) w = adv;
    }
    p->w = ceil(w + 2 * PAD_PX);
    p->h = p->n ? ceil(LINE_PX * p->n + PAD_PX + 2) : 0;
}

/* Draws the panel with its lower-left corner at (x0, y0) (framebuffer pixels, y up). */
static void draw_panel(cj_viewer *v, const panel *p, double x0, double y0, cj_rgba bg, cj_rgba fg) {
    if (!p->n) return;
    const long xa = (long)x0, ya = (long)y0, xb = (long)(x0 + p->w) - 1, yb = (long)(y0 + p->h) - 1;
    const cj_rgba edge = cj_rgba_make(110, 110, 110, 255);
    for (long y = ya; y <= yb; ++y)
        for (long x = xa; x <= xb; ++x)
            cj_framebuffer_blend(v->screen, x, y,
                                 (x == xa || x == xb || y == ya || y == yb) ? edge : bg);
    for (int i = 0; i < p->n; ++i)
        cj_font_draw(v->font, v->screen, x0 + PAD_PX, y0 + p->h - PAD_PX - 9.5 - LINE_PX * i,
                     TEXT_PX, fg, p->line[i]);
}

static void ring(cj_framebuffer *fb, double x, double y, double r, cj_rgba c) {
    double px = x + r, py = y;
    for (int k = 1; k <= 24; ++k) {
        const double a = 6.283185307179586 * k / 24, qx = x + r * cos(a), qy = y + r * sin(a);
        cj_line_draw_aa(fb, px, py, qx, qy, c);
        px = qx, py = qy;
    }
}

static void square(cj_framebuffer *fb, double x, double y, int half, cj_rgba c) {
    const long cx = (long)floor(x), cy = (long)floor(y);
    for (long j = cy - half; j <= cy + half; ++j)
        for (long i = cx - half; i <= cx + half; ++i) cj_framebuffer_blend(fb, i, j, c);
}

/* Curvature comb of a Bézier/rational curve: teeth along the normal, proportional to the
 * curvature (the longest 60 px), and the line through their tips. */
static void comb(cj_viewer *v, const cj_vcurve *c) {
    enum { N = 96 };
    double pt[N + 1][2], tip[N + 1][2], kap[N + 1], kmax = 0;
    const int deg = (int)c->count - 1;
    for (int i = 0; i <= N; ++i) {
        const double t = (double)i / N;
        double d[3 * 2];
        cj_status st;
        if (c->kind == CJ_VCURVE_RATIONAL) {
            cj_rbezier rb = cj_rbezier_view(deg, 2, c->pts, c->weights);
            st = cj_rbezier_eval_derivs(&rb, t, 2, d);
        } else {
            cj_bezier b = cj_bezier_view(deg, 2, c->pts);
            st = cj_bezier_eval_derivs(&b, t, 2, d);
        }
        const double sp = hypot(d[2], d[3]);
        kap[i] = (!st && sp > 0) ? (d[2] * d[5] - d[3] * d[4]) / (sp * sp * sp) : 0.0;
        if (st) d[0] = d[1] = 0, d[2] = 1, d[3] = 0;
        cj_vview_to_px(&v->view, d[0], d[1], pt[i]);
        tip[i][0] = sp > 0 ? -d[3] / sp : 0;
        tip[i][1] = sp > 0 ? d[2] / sp : 0;
        kmax = fmax(kmax, fabs(kap[i]));
    }
    if (!(kmax > 0) || !isfinite(kmax)) return;
    const cj_rgba col = cj_rgba_make(200, 60, 160, 200);
    for (int i = 0; i <= N; ++i) {
        const double len = -60.0 * kap[i] / kmax;
        tip[i][0] = pt[i][0] + len * tip[i][0];
        tip[i][1] = pt[i][1] + len * tip[i][1];
        cj_line_draw_aa(v->screen, pt[i][0], pt[i][1], tip[i][0], tip[i][1], col);
        if (i) cj_line_draw_aa(v->screen, tip[i - 1][0], tip[i - 1][1], tip[i][0], tip[i][1], col);
    }
}

static const char *method_name(cj_eval_method m) {
    static const char *const n[] = {"de Casteljau", "Bernstein", "Horner (VS)", "compensated"};
    return n[m];
}

/* Pixel positions of the curves' control points and of samples along each curve (64 per
 * curve) into xy (2 per point, at most cap points); returns their number. */
static size_t curve_samples(const cj_viewer *v, double *xy, size_t cap) {
    size_t n = 0;
    for (size_t ci = 0; ci < cj_vdoc_curve_count(v->doc); ++ci) {
        const cj_vcurve *c = cj_vdoc_curve(v->doc, ci);
        const int deg = (int)c->count - 1;
        for (int i = 0; i <= 64 + (int)c->count && n < cap; ++i) {
            double p[2] = {0, 0};
            if (i > 64) {
                memcpy(p, c->pts + 2 * (i - 65), sizeof p);
            } else if (c->kind == CJ_VCURVE_RATIONAL) {
                cj_rbezier rb = cj_rbezier_view(deg, 2, c->pts, c->weights);
                if (cj_rbezier_eval(&rb, i / 64.0, p)) continue;
            } else if (c->kind == CJ_VCURVE_BEZIER) {
                cj_bezier b = cj_bezier_view(deg, 2, c->pts);
                if (cj_bezier_eval(&b, CJ_EVAL_DECASTELJAU, i / 64.0, p)) continue;
            } else if (c->kind == CJ_VCURVE_BSPLINE) {
                const cj_bspline b = cj_vcurve_bspline(c);
                double u0, u1;
                if (cj_bspline_domain(&b, &u0, &u1) ||
                    cj_bspline_eval(&b, u0 + (u1 - u0) * (i / 64.0), p))
                    continue;
            } else { /* a spline passes through its points: sample its polygon */
                if (c->count < 2) continue;
                const double s = i / 64.0 * (double)(c->count - 1);
                const size_t k = (size_t)fmin(floor(s), (double)c->count - 2);
                const double f = s - (double)k;
                p[0] = (1 - f) * c->pts[2 * k] + f * c->pts[2 * k + 2];
                p[1] = (1 - f) * c->pts[2 * k + 1] + f * c->pts[2 * k + 3];
            }
            cj_vview_to_px(&v->view, p[0], p[1], xy + 2 * n++);
        }
    }
    return n;
}

/* How many of the n sample points fall inside the box at (x0, y0) of size w × h grown by 4
 * pixels. */
static long covered(const double *xy, size_t n, double x0, double y0, double w, double h) {
    long c = 0;
    for (size_t i = 0; i < n; ++i)
        c += xy[2 * i] >= x0 - 4 && xy[2 * i] <= x0 + w + 4 && xy[2 * i + 1] >= y0 - 4 &&
             xy[2 * i + 1] <= y0 + h + 4;
    return c;
}

/* The curve on [u0, u1] (a B-spline's own parameter) drawn wide and translucent over it: the
 * part of the curve a move of the selected point changes (local control). */
static void local_span(cj_viewer *v, const cj_vcurve *c, double u0, double u1) {
    const cj_bspline b = cj_vcurve_bspline(c);
    const cj_rgba col = cj_rgba_make(255, 200, 0, 110);
    double prev[2] = {0, 0};
    for (int i = 0; i <= 128; ++i) {
        double p[2], q[2];
        if (cj_bspline_eval(&b, i == 128 ? u1 : u0 + (u1 - u0) * (i / 128.0), p)) return;
        cj_vview_to_px(&v->view, p[0], p[1], q);
        for (int k = -3; i && k <= 3; ++k) /* a band about 7 px wide */
            cj_line_draw_aa(v->screen, prev[0], prev[1] + k, q[0], q[1] + k, col);
        prev[0] = q[0], prev[1] = q[1];
    }
}

/* B-spline lines of the panel: degree, spans, knots, and the selected point's local control. */
static void overlay_bspline(cj_viewer *v, panel *p, const cj_vcurve *c) {
    const cj_bspline b = cj_vcurve_bspline(c);
    int spans = 0;
    double a = 0, z = 0;
    (void)cj_bspline_bezier_count(&b, &spans);
    (void)cj_bspline_domain(&b, &a, &z);
    add(p, "curve %ld/%zu: %s, degree %d, %zu points, %d spans on [%.4g, %.4g]", v->disp.curve + 1,
        cj_vdoc_curve_count(v->doc), c->weights ? "NURBS" : "B-spline", c->degree, c->count, spans,
        a, z);
    char kn[200];
    int at = snprintf(kn, sizeof kn, "knots:");
    const size_t nk = c->count + (size_t)c->degree + 1;
    for (size_t i = 0; i < nk && at < (int)sizeof kn - 16; ++i)
        at += snprintf(kn + at, sizeof kn - (size_t)at, " %.4g", c->knot_vector[i]);
    if (at >= (int)sizeof kn - 16) snprintf(kn + sizeof kn - 16, 16, " ...");
    add(p, "%s", kn);
    if (v->sel_point >= 0 && (size_t)v->sel_point < c->count) {
        const size_t i = (size_t)v->sel_point;
        double u0, u1, q[2];
        const double *pt = c->pts + 2 * i;
        if (!cj_vcurve_support(c, i, &u0, &u1)) {
            local_span(v, c, u0, u1);
            int in = 0; /* spans of the domain inside the support */
            for (size_t k = (size_t)c->degree; k < c->count; ++k)
                in += c->knot_vector[k] < c->knot_vector[k + 1] && c->knot_vector[k] >= u0 &&
                      c->knot_vector[k + 1] <= u1;
            add(p, "point %zu moves the curve on [%.4g, %.4g] only: %d of %d spans", i, u0, u1, in,
                spans);
        }
        cj_vview_to_px(&v->view, pt[0], pt[1], q);
        ring(v->screen, q[0], q[1], 9.0, cj_rgba_make(230, 30, 30, 255));
        add(p, "point %zu: (%.6g, %.6g), weight %.6g (W / shift+W)", i, pt[0], pt[1],
            c->weights ? c->weights[i] : 1.0);
    }
    add(p, "I inserts a knot at the cursor's parameter");
    /* the plot flattens each Bézier piece in pixels: the same stats, summed over the pieces */
    cj_vpieces pc;
    if (cj_vcurve_pieces(c, &pc)) return;
    const size_t per = (size_t)pc.degree + 1;
    for (size_t i = 0; i < (size_t)pc.n * per; ++i)
        cj_vview_to_px(&v->view, pc.pts[2 * i], pc.pts[2 * i + 1], pc.pts + 2 * i);
    cj_flatten_opts fo = cj_flatten_defaults(CJ_FLATTEN_NEAR_OPTIMAL, CJ_PLOT_FLATTEN_TOL);
    size_t segments = 0, np = 0;
    double bound = 0;
    for (int j = 0; j < pc.n; ++j) {
        cj_flatten_stats fs = {0, 0};
        const cj_bezier pb = cj_bezier_view(pc.degree, 2, pc.pts + (size_t)j * per * 2);
        const cj_rbezier rb =
            cj_rbezier_view(pc.degree, 2, pb.pts, pc.w ? pc.w + (size_t)j * per : NULL);
        if (pc.w ? cj_flatten_rbezier(&rb, &fo, NULL, 0, &np, &fs)
                 : cj_flatten_bezier(&pb, &fo, NULL, 0, &np, &fs))
            break;
        segments += fs.segments;
        bound = fmax(bound, fs.bound);
    }
    add(p, "flattening: %d Bezier pieces, tol %.2f px -> %zu segments, proven bound %.3f px", pc.n,
        CJ_PLOT_FLATTEN_TOL, segments, bound);
    cj_vpieces_free(&pc);
}

/* Snap point and intersection marks, for every curve. */
static void overlay_queries(cj_viewer *v, panel *p) {
    const cj_rgba mk = cj_rgba_make(200, 0, 120, 255);
    if (v->isect_on) {
        size_t kinds[3] = {0, 0, 0};
        for (size_t i = 0; i < v->nmarks; ++i) {
            double q[2];
            cj_vview_to_px(&v->view, v->marks[i].point[0], v->marks[i].point[1], q);
            for (int k = 0; k < 2; ++k) { /* two pixels wide, to stand out over the curves */
                cj_line_draw_aa(v->screen, q[0] - 6 + k, q[1] - 6, q[0] + 6 + k, q[1] + 6, mk);
                cj_line_draw_aa(v->screen, q[0] - 6 + k, q[1] + 6, q[0] + 6 + k, q[1] - 6, mk);
            }
            kinds[v->marks[i].kind % 3]++;
        }
        add(p, "T: %zu intersections (%zu crossings, %zu contacts, %zu overlaps)%s", v->nmarks,
            kinds[0], kinds[1], kinds[2], v->isect_failed ? " | some pairs failed" : "");
    }
    if (!v->snap_on) return;
    if (v->snap.curve < 0) {
        add(p, "P: snapping on (no curve point found)");
        return;
    }
    double q[2];
    cj_vview_to_px(&v->view, v->snap.point[0], v->snap.point[1], q);
    if (v->drag == VIEW_DRAG_NONE) /* from the cursor to the point it snaps to */
        cj_line_draw_aa(v->screen, v->cx, v->cy, q[0], q[1], cj_rgba_make(200, 0, 120, 120));
    ring(v->screen, q[0], q[1], 5.0, mk);
    cj_line_draw_aa(v->screen, q[0] - 8, q[1], q[0] + 8, q[1], mk);
    cj_line_draw_aa(v->screen, q[0], q[1] - 8, q[0], q[1] + 8, mk);
    add(p, "P: snap to curve %ld at u = %.9g: (%.9g, %.9g)", v->snap.curve + 1, v->snap.u,
        v->snap.point[0], v->snap.point[1]);
    add(p, "   distance <= %.6g, >= %.6g (certified); on the curve within %.2g", v->snap.distance,
        v->snap.lower, v->snap.on_curve);
}

static void overlay_curve(cj_viewer *v, panel *p) {
    const cj_vcurve *c = v->disp.curve >= 0 ? cj_vdoc_curve(v->doc, (size_t)v->disp.curve) : NULL;
    if (!c) return;
    if (c->kind == CJ_VCURVE_BSPLINE) {
        overlay_bspline(v, p, c);
        return;
    }
    static const char *const kinds[] = {"Bezier", "rational Bezier", "spline"};
    char dg[32] = "";
    if (c->kind != CJ_VCURVE_SPLINE) snprintf(dg, sizeof dg, ", degree %zu", c->count - 1);
    add(p, "curve %ld/%zu: %s, %zu points%s", v->disp.curve + 1, cj_vdoc_curve_count(v->doc),
        kinds[c->kind], c->count, dg);
    add(p, "t = %.4f%s%s", v->disp.t, v->disp.construction ? " | construction" : "",
        v->disp.frame ? " | frame" : "");
    if (v->sel_point >= 0 && (size_t)v->sel_point < c->count) {
        double q[2];
        const double *pt = c->pts + 2 * v->sel_point;
        cj_vview_to_px(&v->view, pt[0], pt[1], q);
        ring(v->screen, q[0], q[1], 9.0, cj_rgba_make(230, 30, 30, 255));
        if (c->weights)
            add(p, "point %ld: (%.6g, %.6g), weight %.4g", v->sel_point, pt[0], pt[1],
                c->weights[v->sel_point]);
        else
            add(p, "point %ld: (%.6g, %.6g)", v->sel_point, pt[0], pt[1]);
    }
    if (v->comb) comb(v, c);
    if (c->kind == CJ_VCURVE_SPLINE) return;
    const int deg = (int)c->count - 1;
    double val[2] = {0, 0}, bound[2] = {0, 0};
    cj_flatten_stats fs = {0, 0};
    size_t np = 0;
    double *px = malloc(c->count * 2 * sizeof(double));
    if (!px) return;
    for (size_t i = 0; i < c->count; ++i)
        cj_vview_to_px(&v->view, c->pts[2 * i], c->pts[2 * i + 1], px + 2 * i);
    cj_flatten_opts fo = cj_flatten_defaults(CJ_FLATTEN_NEAR_OPTIMAL, CJ_PLOT_FLATTEN_TOL);
    if (c->kind == CJ_VCURVE_RATIONAL) {
        cj_rbezier rb = cj_rbezier_view(deg, 2, c->pts, c->weights), rp = rb;
        rp.pts = px;
        cj_rbezier_eval(&rb, v->disp.t, val);
        cj_flatten_rbezier(&rp, &fo, NULL, 0, &np, &fs);
        add(p, "c(t) = (%.17g, %.17g)", val[0], val[1]);
        add(p, "rational de Casteljau (homogeneous)");
    } else {
        cj_bezier b = cj_bezier_view(deg, 2, c->pts), bp = cj_bezier_view(deg, 2, px);
        if (deg <= CJ_BEZIER_BINOMIAL_MAX_DEGREE || v->method == CJ_EVAL_DECASTELJAU ||
            v->method == CJ_EVAL_COMPENSATED) {
            cj_bezier_eval(&b, v->method, v->disp.t, val);
            cj_bezier_error_bound(&b, v->method, v->disp.t, bound);
        }
        cj_flatten_bezier(&bp, &fo, NULL, 0, &np, &fs);
        add(p, "c(t) = (%.17g, %.17g)", val[0], val[1]);
        add(p, "M: %s, error <= (%.2e, %.2e)", method_name(v->method), bound[0], bound[1]);
    }
    free(px);
    add(p, "flattening: tol %.2f px -> %zu segments,", CJ_PLOT_FLATTEN_TOL, fs.segments);
    add(p, "  proven bound %.3f px", fs.bound);
}

/* The selected curve's lines and marks, then the snap and intersection marks over them. */
static void overlay_2d(cj_viewer *v, panel *p) {
    overlay_curve(v, p);
    overlay_queries(v, p);
}

/* The control points of the nodes whose control net is shown (and the selected one always):
 * in front of the surface a filled square, behind it (by the rasterized depth) a faint one. */
static void points_3d(cj_viewer *v) {
    const cj_scene *s = cj_vscene_scene(v->vs);
    for (size_t k = 0; k < cj_vscene_point_count(v->vs); ++k) {
        const int node = cj_vscene_point_node(v->vs, k);
        const int sel = (long)k == v->sel3;
        if (!sel && !(cj_scene_node(s, node)->overlay.flags & CJ_OVERLAY_CONTROL_NET)) continue;
        double q[3];
        if (!cj_vscene_project(v->vs, k, v->width, v->height, q) || !(q[2] >= -1 && q[2] <= 1))
            continue;
        if (!(q[0] >= 0 && q[1] >= 0 && q[0] < v->width && q[1] < v->height)) continue;
        const int hidden =
            v->depth &&
            q[2] > v->depth[(size_t)q[1] * (size_t)v->width + (size_t)q[0]] + CJ_VSCENE_DEPTH_TOL;
        if (sel) {
            square(v->screen, q[0], q[1], 3, cj_rgba_make(255, 40, 40, 255));
            ring(v->screen, q[0], q[1], 7.0, cj_rgba_make(255, 40, 40, 255));
        } else if (hidden) {
            square(v->screen, q[0], q[1], 1, cj_rgba_make(255, 230, 150, 110));
        } else {
            square(v->screen, q[0], q[1], 2, cj_rgba_make(30, 20, 0, 230));
            square(v->screen, q[0], q[1], 1, cj_rgba_make(255, 215, 60, 255));
        }
    }
}

static void overlay_3d(cj_viewer *v, panel *p) {
    const int stale = v->shown_gen != v->gen;
    const int scale = cj_vtrace_scale(v->shown_pass, v->width, v->height);
    char res[32] = "";
    if (scale > 1) snprintf(res, sizeof res, ", 1/%d resolution", scale);
    if (v->shown_trace)
        add(p, "ray traced pass %d/%d (%d spp%s) %.1f ms%s", v->shown_pass + 1, VIEW_TRACE_PASSES,
            cj_vtrace_spp[v->shown_pass], res, 1e3 * v->render_s,
            stale || cj_viewer_refinable(v) ? " | refining" : "");
    else
        add(p, "rasterized %.1f ms | %zu triangles | tol %.3g px (bound %.3g px) | spp %d%s",
            1e3 * v->render_s, v->triangles, v->shown_tol, v->bound_px, v->shown_spp,
            stale ? (v->trace && v->drag == VIEW_DRAG_NONE ? " | tracing" : " | rendering") : "");
    add(p, "tool: drag points on the camera plane; shift-drag along %c | %zu control points",
        "xyz"[v->axis], cj_vscene_point_count(v->vs));
    add(p, "shared points move together: %s (L)", cj_vscene_linked(v->vs) ? "on" : "off");
    if (v->sel3 >= 0) {
        cj_vec3 w;
        cj_vscene_point(v->vs, (size_t)v->sel3, &w);
        const size_t shared = cj_vscene_shared_count(v->vs, (size_t)v->sel3);
        char with[48] = "";
        if (shared > 1) snprintf(with, sizeof with, " (moves with %zu others)", shared - 1);
        double wt;
        if (cj_vscene_point_weight(v->vs, (size_t)v->sel3, &wt))
            add(p, "point %ld: (%.6g, %.6g, %.6g) weight %.6g (W, shift+W)%s", v->sel3, w.x, w.y,
                w.z, wt, with);
        else
            add(p, "point %ld: (%.6g, %.6g, %.6g)%s", v->sel3, w.x, w.y, w.z, with);
    }
    if (v->anim)
        add(p, "animation: frame %ld of %d..%d (%s, Space)", v->anim_frame, v->anim->frame_first,
            v->anim->frame_last, v->playing ? "playing" : "paused");
}

/* The status panel's place: 3D the top left corner; 2D the place on an 8-pixel grid inside the
 * window that covers the fewest curve points, nearest to the top left corner among equals. */
static void place(const cj_viewer *v, const panel *p, double *x0, double *y0) {
    const double m = 4;
    *x0 = m;
    *y0 = v->height - m - p->h;
    enum { CAP = 4096 };
    double *xy = v->mode3d ? NULL : malloc(2 * CAP * sizeof *xy);
    if (!xy) return;
    const size_t n = curve_samples(v, xy, CAP);
    long best = covered(xy, n, *x0, *y0, p->w, p->h);
    for (double y = *y0; y >= m && best > 0; y -= 8)
        for (double x = m; x + p->w <= v->width - m && best > 0; x += 8) {
            const long c = covered(xy, n, x, y, p->w, p->h);
            if (c < best) best = c, *x0 = x, *y0 = y;
        }
    free(xy);
}

void cj_viewer_overlay(cj_viewer *v) {
    if (v->show_overlay && v->mode3d) points_3d(v); /* marks, even without a font */
    if (v->show_overlay && v->font) {
        panel p;
        p.n = 0;
        add(&p, "%s | F1 help | O overlay%s%s", v->mode3d ? "3D" : "2D", v->msg[0] ? " | " : "",
            v->msg);
        if (v->mode3d)
            overlay_3d(v, &p);
        else
            overlay_2d(v, &p);
        measure(v, &p);
        double x0, y0;
        place(v, &p, &x0, &y0);
        draw_panel(v, &p, x0, y0, cj_rgba_make(240, 240, 240, 215), cj_rgba_make(20, 20, 20, 255));
    }
    if (v->show_help && v->font) {
        panel h;
        h.n = 0;
        for (const char *const *l = cj_viewer_help(v->mode3d); *l; ++l) add(&h, "%s", *l);
        measure(v, &h);
        /* centred (its left and lower edges kept inside a window too small for it) */
        const double x0 = fmax(0, floor(0.5 * (v->width - h.w)));
        const double y0 = fmax(0, floor(0.5 * (v->height - h.h)));
        draw_panel(v, &h, x0, y0, cj_rgba_make(255, 255, 255, 225), cj_rgba_make(10, 10, 60, 255));
    }
}

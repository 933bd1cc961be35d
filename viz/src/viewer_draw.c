/* The viewer's pictures: loading the input (plot JSON curves, scene JSON, .bpt, the teapot),
 * rendering exactly what the offline commands render (`pic`), and the overlay drawn over a
 * copy of it (`screen`): the selection, the curvature comb, the status text and the help. */
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
#include "file_internal.h"

#include <cJSON.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static int ends_with(const char *s, const char *ext) {
    const size_t a = strlen(s), b = strlen(ext);
    return a > b && !strcmp(s + a - b, ext);
}

/* A plot document has "items" (or "panels") at the top; a scene has not. */
static int is_plot_json(const char *path) {
    char *buf = NULL;
    size_t n = 0;
    if (cj_file_read_all(path, CJ_FILE_MAX_BYTES, "document", &buf, &n)) return 0;
    cJSON *root = cJSON_Parse(buf);
    free(buf);
    const int yes = root && (cJSON_GetObjectItemCaseSensitive(root, "items") ||
                             cJSON_GetObjectItemCaseSensitive(root, "panels"));
    cJSON_Delete(root);
    return yes;
}

/* An animation document names its scene at the top ("scene": "file.json"). */
static int is_anim_json(const char *path) {
    char *buf = NULL;
    size_t n = 0;
    if (cj_file_read_all(path, CJ_FILE_MAX_BYTES, "document", &buf, &n)) return 0;
    cJSON *root = cJSON_Parse(buf);
    free(buf);
    const int yes = cJSON_IsString(cJSON_GetObjectItemCaseSensitive(root, "scene"));
    cJSON_Delete(root);
    return yes;
}

/* A scene around the patches of a .bpt file: camera fitted to the box, two lights, a grey
 * Phong material, the control net shown. */
static cj_status bpt_scene(const char *path, cj_scene **out) {
    cj_patchset *set = NULL;
    cj_status st = cj_patchset_load_bpt(path, NULL, &set);
    if (st) return st;
    double lo[3], hi[3], diag;
    cj_scene *s = NULL;
    if (!(st = cj_patchset_bbox(set, lo, hi, &diag))) st = cj_scene_create(NULL, &s);
    if (!st) {
        cj_geometry g;
        memset(&g, 0, sizeof g);
        g.kind = CJ_GEOM_PATCHES;
        g.u.patches.count = set->count;
        g.u.patches.patches = set->patches;
        int gi, mi, ni, li;
        cj_material m = cj_material_default();
        m.two_sided = 1;
        cj_light amb = cj_light_default(CJ_LIGHT_AMBIENT), pt = cj_light_default(CJ_LIGHT_POINT);
        amb.intensity = 0.3;
        const cj_vec3 c =
            cj_v3(0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1]), 0.5 * (lo[2] + hi[2]));
        pt.position = cj_v3(c.x + diag, c.y - diag, c.z + diag);
        cj_camera cam = cj_camera_default();
        cam.eye = cj_v3(c.x + 0.9 * diag, c.y - 1.4 * diag, c.z + 0.8 * diag);
        cam.gaze = cj_v3_sub(c, cam.eye);
        cam.up = cj_v3(0, 0, 1);
        cam.near = -0.01 * diag;
        cam.far = -10.0 * diag;
        if (!(st = cj_scene_add_geometry(s, &g, &gi)) &&
            !(st = cj_scene_add_material(s, &m, &mi)) && !(st = cj_scene_add_light(s, &amb, &li)) &&
            !(st = cj_scene_add_light(s, &pt, &li)) && !(st = cj_scene_set_camera(s, &cam))) {
            cj_node n = cj_render_node(gi, mi);
            n.overlay.flags = CJ_OVERLAY_CONTROL_NET;
            n.overlay.color = cj_rgb_make(0.9, 0.6, 0.1);
            st = cj_scene_add_node(s, &n, &ni);
        }
    }
    cj_patchset_destroy(set);
    if (st) {
        cj_scene_destroy(s);
        return st;
    }
    *out = s;
    return CJ_OK;
}

static const char *dir_of(const char *path, char *buf, size_t size) {
    const char *slash = strrchr(path, '/');
    if (!slash) return "";
    size_t n = (size_t)(slash - path);
    if (n >= size) n = size - 1;
    memcpy(buf, path, n);
    buf[n] = '\0';
    return n ? buf : "/";
}

cj_status cj_viewer_load(cj_viewer *v) {
    const cj_viewer_options *o = v->opt;
    cj_status st;
    if (o->path && ends_with(o->path, ".json") && is_plot_json(o->path)) {
        v->mode3d = 0;
        if ((st = cj_vdoc_load_json(o->path, &v->doc, &v->view, &v->disp))) return st;
        if (o->width) v->view.width = o->width;
        if (o->height) v->view.height = o->height;
        v->width = v->view.width;
        v->height = v->view.height;
        if (v->disp.curve < 0 && cj_vdoc_curve_count(v->doc)) v->disp.curve = 0;
        v->sel_point = -1;
        return CJ_OK;
    }
    cj_scene *scene = NULL;
    if (!o->path) {
        st = cj_render_demo_scene(o->teapot_path, NULL, &scene);
    } else if (ends_with(o->path, ".bpt")) {
        st = bpt_scene(o->path, &scene);
    } else {
        const int anim = ends_with(o->path, ".json") && is_anim_json(o->path);
        if (anim && (st = cj_anim_doc_load(o->path, &v->anim))) return st;
        const char *sp = anim ? v->anim->scene_path : o->path;
        cj_scene_json_options jo = {o->teapot_path};
        char dir[4096];
        st = cj_scene_load_json_ex(sp, &jo, NULL, &scene);
        if (!st && (st = cj_scene_load_textures(scene, dir_of(sp, dir, sizeof dir)))) {
            cj_scene_destroy(scene);
            scene = NULL;
        }
        if (!st && anim) {
            v->anim_frame = v->anim->frame_first;
            v->playing = 0;
            st = cj_anim_doc_attach(v->anim, scene);
            if (!st) st = cj_anim_doc_frame(v->anim, scene, v->anim_frame, NULL);
            if (st) cj_scene_destroy(scene);
        }
    }
    if (st) return st;
    /* Overrides go into the scene's own settings, so the saved scene renders the same. */
    cj_scene_settings set = *cj_scene_settings_get(scene);
    if (o->width) set.width = o->width;
    if (o->height) set.height = o->height;
    if (o->spp) set.spp = o->spp;
    if (o->tol_px > 0) set.tol_px = o->tol_px;
    if ((st = cj_scene_set_settings(scene, &set))) {
        cj_scene_destroy(scene);
        return st;
    }
    v->mode3d = 1;
    v->width = set.width;
    v->height = set.height;
    v->sel3 = -1;
    v->axis = 2;
    return cj_vscene_create(scene, &v->vs);
}

void cj_viewer_unload(cj_viewer *v) {
    cj_vdoc_destroy(v->doc);
    cj_vscene_destroy(v->vs);
    free(v->depth);
    if (v->anim) cj_anim_doc_destroy(v->anim);
    v->anim = NULL;
    v->playing = 0;
    v->doc = NULL;
    v->vs = NULL;
    v->depth = NULL;
}

const char *cj_viewer_save_path(const cj_viewer *v, char *buf, size_t size) {
    const char *p = v->opt->path;
    if (p && v->anim)
        snprintf(buf, size, "%.*s_posed.json", (int)(strlen(p) - 5), p); /* not the animation */
    else if (p && ends_with(p, ".json"))
        snprintf(buf, size, "%s", p);
    else if (p)
        snprintf(buf, size, "%s.json", p); /* a .bpt is saved as a scene beside it */
    else
        snprintf(buf, size, "teapot_scene.json");
    return buf;
}

cj_status cj_viewer_save(cj_viewer *v, const char *path) {
    if (v->mode3d) return cj_scene_save_json(cj_vscene_scene(v->vs), path);
    return cj_vdoc_save_json(v->doc, &v->view, &v->disp, path);
}

static double now_s(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static cj_status render_3d(cj_viewer *v) {
    cj_render_options ro = cj_render_options_default();
    ro.threads = v->opt->threads;
    cj_render_image *img = NULL;
    cj_stage_report rep;
    const cj_scene *scene = cj_vscene_scene(v->vs);
    cj_status st;
    if (v->trace) {
        ro.spp = v->trace_spp;
        st = cj_render_trace(scene, &ro, 0, NULL, &img, &rep);
        v->trace_spp *= 4;
        v->trace_done = v->trace_spp > 64;
    } else {
        st = cj_render_raster(scene, &ro, CJ_IMAGE_DEPTH, NULL, &img, &rep);
    }
    if (st) return st;
    if (img->depth) {
        const size_t n = (size_t)v->width * (size_t)v->height;
        if (!v->depth) v->depth = malloc(n * sizeof *v->depth);
        if (v->depth) memcpy(v->depth, img->depth, n * sizeof *v->depth);
    }
    st = cj_render_image_to_srgb8(img, (uint8_t *)v->pic->pixels,
                                  (size_t)v->pic->stride * sizeof(cj_rgba));
    for (int y = 0; y < v->height; ++y)
        for (int x = 0; x < v->width; ++x)
            v->pic->pixels[(ptrdiff_t)y * v->pic->stride + x].a = 255;
    cj_render_image_destroy(img);
    v->triangles = 0;
    v->bound_px = 0;
    for (int i = 0; i < rep.count; ++i) {
        const cj_stage *s = &rep.stages[i];
        if (!strncmp(s->name, "tessellate", 10) && s->ran) v->triangles += (size_t)s->out;
        for (int k = 0; k < s->extra_count; ++k)
            if (!strcmp(s->extra[k].key, "bound_px"))
                v->bound_px = fmax(v->bound_px, s->extra[k].value);
    }
    return st;
}

static cj_status render_pic(cj_viewer *v) {
    if (v->mode3d) return render_3d(v);
    cj_plot *plot = NULL;
    cj_status st = cj_vdoc_build_plot(v->doc, &v->view, &v->disp, &plot);
    if (st) return st;
    /* as plot_doc_render: clear to the background, then the one panel over the whole image */
    cj_framebuffer_clear(v->pic, v->disp.background);
    st = cj_plot_render(plot, v->pic, 0, 0, v->width, v->height, v->font);
    cj_plot_destroy(plot);
    return st;
}

/* ---- overlay -------------------------------------------------------------------------- */

static void text(cj_viewer *v, int line, const char *s) {
    const double y = v->height - 16.0 - 15.0 * line;
    /* a dark halo under light text: readable over any picture */
    cj_font_draw(v->font, v->screen, 9, y - 1, 12.5, cj_rgba_make(255, 255, 255, 200), s);
    cj_font_draw(v->font, v->screen, 8, y, 12.5, cj_rgba_make(20, 20, 20, 255), s);
}

static void ring(cj_framebuffer *fb, double x, double y, double r, cj_rgba c) {
    double px = x + r, py = y;
    for (int k = 1; k <= 24; ++k) {
        const double a = 6.283185307179586 * k / 24, qx = x + r * cos(a), qy = y + r * sin(a);
        cj_raster_line_aa(fb, px, py, qx, qy, c);
        px = qx, py = qy;
    }
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
        cj_raster_line_aa(v->screen, pt[i][0], pt[i][1], tip[i][0], tip[i][1], col);
        if (i)
            cj_raster_line_aa(v->screen, tip[i - 1][0], tip[i - 1][1], tip[i][0], tip[i][1], col);
    }
}

static const char *method_name(cj_eval_method m) {
    static const char *const n[] = {"de Casteljau", "Bernstein", "Horner (VS)", "compensated"};
    return n[m];
}

static void overlay_2d(cj_viewer *v, char *s, size_t n) {
    int line = 1;
    const cj_vcurve *c = v->disp.curve >= 0 ? cj_vdoc_curve(v->doc, (size_t)v->disp.curve) : NULL;
    if (!c) return;
    static const char *const kinds[] = {"Bezier", "rational Bezier", "spline"};
    char dg[32] = "";
    if (c->kind != CJ_VCURVE_SPLINE) snprintf(dg, sizeof dg, ", degree %zu", c->count - 1);
    snprintf(s, n, "curve %ld/%zu: %s, %zu points%s | t = %.4f%s%s", v->disp.curve + 1,
             cj_vdoc_curve_count(v->doc), kinds[c->kind], c->count, dg, v->disp.t,
             v->disp.construction ? " | construction" : "", v->disp.frame ? " | frame" : "");
    text(v, line++, s);
    if (v->sel_point >= 0 && (size_t)v->sel_point < c->count) {
        double q[2];
        const double *p = c->pts + 2 * v->sel_point;
        cj_vview_to_px(&v->view, p[0], p[1], q);
        ring(v->screen, q[0], q[1], 9.0, cj_rgba_make(230, 30, 30, 255));
        if (c->weights)
            snprintf(s, n, "point %ld: (%.6g, %.6g), weight %.4g", v->sel_point, p[0], p[1],
                     c->weights[v->sel_point]);
        else
            snprintf(s, n, "point %ld: (%.6g, %.6g)", v->sel_point, p[0], p[1]);
        text(v, line++, s);
    }
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
        snprintf(s, n, "c(t) = (%.17g, %.17g) | rational de Casteljau (homogeneous)", val[0],
                 val[1]);
    } else {
        cj_bezier b = cj_bezier_view(deg, 2, c->pts), bp = cj_bezier_view(deg, 2, px);
        if (deg <= CJ_BEZIER_BINOMIAL_MAX_DEGREE || v->method == CJ_EVAL_DECASTELJAU ||
            v->method == CJ_EVAL_COMPENSATED) {
            cj_bezier_eval(&b, v->method, v->disp.t, val);
            cj_bezier_error_bound(&b, v->method, v->disp.t, bound);
        }
        cj_flatten_bezier(&bp, &fo, NULL, 0, &np, &fs);
        snprintf(s, n, "c(t) = (%.17g, %.17g) | M: %s, error <= (%.2e, %.2e)", val[0], val[1],
                 method_name(v->method), bound[0], bound[1]);
    }
    free(px);
    text(v, line++, s);
    snprintf(s, n, "flattening: tol %.2f px -> %zu segments, proven bound %.3f px",
             CJ_PLOT_FLATTEN_TOL, fs.segments, fs.bound);
    text(v, line++, s);
    if (v->comb) comb(v, c);
}

static void overlay_3d(cj_viewer *v, char *s, size_t n) {
    const cj_scene_settings *set = cj_scene_settings_get(cj_vscene_scene(v->vs));
    snprintf(s, n, "%s %.1f ms | %zu triangles | tol %.3g px (bound %.3g px) | spp %d%s",
             v->trace ? "ray traced" : "rasterized", 1e3 * v->render_s, v->triangles, set->tol_px,
             v->bound_px, v->trace ? v->trace_spp / 4 : set->spp,
             v->trace && !v->trace_done ? " (refining)" : "");
    text(v, 1, s);
    if (v->anim) {
        snprintf(s, n, "animation: frame %ld of %d..%d (%s, Space)", v->anim_frame,
                 v->anim->frame_first, v->anim->frame_last, v->playing ? "playing" : "paused");
        text(v, 4 + (v->sel3 >= 0), s);
    }
    snprintf(s, n,
             "tool: drag points on the camera plane; shift-drag along %c | %zu control points",
             "xyz"[v->axis], cj_vscene_point_count(v->vs));
    text(v, 2, s);
    if (v->sel3 >= 0) {
        double q[3];
        cj_vec3 w;
        if (cj_vscene_project(v->vs, (size_t)v->sel3, v->width, v->height, q))
            ring(v->screen, q[0], q[1], 7.0, cj_rgba_make(255, 40, 40, 255));
        cj_vscene_point(v->vs, (size_t)v->sel3, &w);
        snprintf(s, n, "point %ld: (%.6g, %.6g, %.6g)", v->sel3, w.x, w.y, w.z);
        text(v, 3, s);
    }
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
    const int refine = v->mode3d && v->trace && !v->trace_done;
    if (v->dirty || refine) {
        const double t0 = now_s();
        if (v->dirty && v->trace) v->trace_spp = 1;
        st = render_pic(v);
        v->render_s = now_s() - t0;
        v->dirty = 0;
        if (st) snprintf(v->msg, sizeof v->msg, "render failed: %s", cj_last_error());
    }
    for (int y = 0; y < v->height; ++y)
        memcpy(v->screen->pixels + (ptrdiff_t)y * v->screen->stride,
               v->pic->pixels + (ptrdiff_t)y * v->pic->stride, (size_t)v->width * sizeof(cj_rgba));
    if (!v->show_overlay && !v->show_help) return st;
    char s[512];
    if (v->show_overlay && v->font) {
        snprintf(s, sizeof s, "%s | F1 help | O overlay%s%s", v->mode3d ? "3D" : "2D",
                 v->msg[0] ? " | " : "", v->msg);
        text(v, 0, s);
        if (v->mode3d)
            overlay_3d(v, s, sizeof s);
        else
            overlay_2d(v, s, sizeof s);
    }
    if (v->show_help && v->font) {
        const char *const *h = cj_viewer_help(v->mode3d);
        int lines = 0;
        while (h[lines]) ++lines;
        const int top = v->height - 90, bot = top - 15 * lines - 10;
        for (int y = bot > 0 ? bot : 0; y < top && y < v->height; ++y)
            for (int x = 0; x < v->width && x < 520; ++x)
                cj_framebuffer_blend(v->screen, x, y, cj_rgba_make(255, 255, 255, 220));
        for (int i = 0; i < lines; ++i)
            cj_font_draw(v->font, v->screen, 12, top - 14 - 15.0 * i, 12.5,
                         cj_rgba_make(10, 10, 60, 255), h[i]);
    }
    return st;
}

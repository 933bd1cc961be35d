/* The viewer's document: loading the input (plot JSON curves, scene JSON, an animation, .bpt,
 * the teapot), unloading it, and saving it back. Input (viewer_input.c) and the window call
 * these; drawing (viewer_draw.c) only reads what they loaded. */
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
#include "clock_internal.h"

#include <cJSON.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

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
        cj_material m = cj_material_defaults();
        m.two_sided = 1;
        cj_light amb = cj_light_defaults(CJ_LIGHT_AMBIENT), pt = cj_light_defaults(CJ_LIGHT_POINT);
        amb.intensity = 0.3;
        const cj_vec3 c =
            cj_v3(0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1]), 0.5 * (lo[2] + hi[2]));
        pt.position = cj_v3(c.x + diag, c.y - diag, c.z + diag);
        cj_camera cam = cj_camera_defaults();
        cam.eye = cj_v3(c.x + 0.9 * diag, c.y - 1.4 * diag, c.z + 0.8 * diag);
        cam.gaze = cj_v3_sub(c, cam.eye);
        cam.up = cj_v3(0, 0, 1);
        cam.near = -0.01 * diag;
        cam.far = -10.0 * diag;
        if (!(st = cj_scene_add_geometry(s, &g, &gi)) &&
            !(st = cj_scene_add_material(s, &m, &mi)) && !(st = cj_scene_add_light(s, &amb, &li)) &&
            !(st = cj_scene_add_light(s, &pt, &li)) && !(st = cj_scene_set_camera(s, &cam))) {
            cj_node n = cj_node_defaults(gi, mi);
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
        st = cj_scene_load_with_textures(sp, &jo, NULL, &scene);
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
    cj_scene_settings set = *cj_scene_get_settings(scene);
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
    free(v->marks);
    v->marks = NULL;
    v->nmarks = 0;
    v->snap.curve = -1;
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

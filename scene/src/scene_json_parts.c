/* The JSON scene reader: camera, settings, lights, textures, materials, transforms, objects. */
#include "scene_json_internal.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define TRY(x)                                                                                     \
    do {                                                                                           \
        cj_status st_ = (x);                                                                       \
        if (st_) return st_;                                                                       \
    } while (0)

static const double PI = 3.14159265358979323846;

/* ---- camera and settings -------------------------------------------------------------------- */

static const char *const CAMERA_KEYS[] = {"eye",
                                          "gaze",
                                          "look_at",
                                          "up",
                                          "near",
                                          "far",
                                          "projection",
                                          "fov_deg",
                                          "fov_rad",
                                          "focal_length_mm",
                                          "sensor_height_mm",
                                          "ortho_height",
                                          "aperture",
                                          "focus_distance",
                                          NULL};

cj_status cj_json_read_camera_(jctx *c, const cJSON *obj) {
    const char *p = "camera";
    TRY(cj_json_object(&c->json, obj, p, CAMERA_KEYS));
    cj_camera cam = cj_camera_defaults();
    TRY(cj_json_vec3(&c->json, obj, p, "eye", &cam.eye));
    const cJSON *g = cJSON_GetObjectItemCaseSensitive(obj, "gaze");
    const cJSON *la = cJSON_GetObjectItemCaseSensitive(obj, "look_at");
    if (g && la)
        return cj_json_fail(&c->json, la, 1, CJ_ERR_PARSE,
                            "camera: give either \"gaze\" or \"look_at\", not both");
    if (la) {
        cj_vec3 target = cj_v3(0, 0, 0);
        TRY(cj_json_vec3(&c->json, obj, p, "look_at", &target));
        cam.gaze = cj_v3_sub(target, cam.eye);
        if (!(cj_v3_norm(cam.gaze) > 0.0))
            return cj_json_fail(&c->json, la, 0, CJ_ERR_DEGENERATE,
                                "camera.look_at must differ from camera.eye");
    } else if (g) {
        TRY(cj_json_vec3(&c->json, obj, p, "gaze", &cam.gaze));
        if (!(cj_v3_norm(cam.gaze) > 0.0))
            return cj_json_fail(&c->json, g, 0, CJ_ERR_DEGENERATE,
                                "camera.gaze must not be the zero vector");
    }
    TRY(cj_json_vec3(&c->json, obj, p, "up", &cam.up));
    TRY(cj_json_num(&c->json, obj, p, "near", CJ_JSON_LT, 0, 0, &cam.near));
    TRY(cj_json_num(&c->json, obj, p, "far", CJ_JSON_LT, 0, cam.near, &cam.far));
    int proj = (int)cam.projection;
    static const char *const PROJ[] = {"perspective", "orthographic", NULL};
    TRY(cj_json_enum(&c->json, obj, p, "projection", PROJ, &proj));
    cam.projection = (cj_projection)proj;
    const cJSON *fl = cJSON_GetObjectItemCaseSensitive(obj, "focal_length_mm");
    const cJSON *fd = cJSON_GetObjectItemCaseSensitive(obj, "fov_deg");
    const cJSON *fr = cJSON_GetObjectItemCaseSensitive(obj, "fov_rad");
    if (fl && (fd || fr))
        return cj_json_fail(&c->json, fl, 1, CJ_ERR_PARSE,
                            "camera: give either a field of view or a focal length, not both");
    TRY(cj_json_angle(&c->json, obj, p, "fov", CJ_JSON_OPEN, 0, PI, &cam.fov_y));
    if (fl) {
        double f = 50, h = 24;
        TRY(cj_json_num(&c->json, obj, p, "focal_length_mm", CJ_JSON_GT, 0, 0, &f));
        TRY(cj_json_num(&c->json, obj, p, "sensor_height_mm", CJ_JSON_GT, 0, 0, &h));
        cam.fov_y = 2.0 * atan(h / (2.0 * f));
    } else if (cJSON_GetObjectItemCaseSensitive(obj, "sensor_height_mm")) {
        return cj_json_fail(&c->json, cJSON_GetObjectItemCaseSensitive(obj, "sensor_height_mm"), 1,
                            CJ_ERR_PARSE, "camera.sensor_height_mm needs focal_length_mm");
    }
    TRY(cj_json_num(&c->json, obj, p, "ortho_height", CJ_JSON_GT, 0, 0, &cam.ortho_height));
    TRY(cj_json_num(&c->json, obj, p, "aperture", CJ_JSON_GE, 0, 0, &cam.aperture));
    TRY(cj_json_num(&c->json, obj, p, "focus_distance", CJ_JSON_GT, 0, 0, &cam.focus_distance));
    cj_status st = cj_scene_check_camera_(&cam, p);
    if (!st) st = cj_scene_set_camera(c->scene, &cam);
    if (st) return cj_json_relabel(&c->json, obj, st);
    return CJ_OK;
}

static const char *const SETTINGS_KEYS[] = {"width",      "height",        "spp",  "tol_px",
                                            "background", "max_depth",     "seed", "light_model",
                                            "filter",     "filter_radius", NULL};
static const char *const LIGHT_MODELS[] = {"legacy", "radiometric", NULL}; /* cj_light_model */

cj_status cj_json_read_settings_(jctx *c, const cJSON *obj) {
    const char *p = "settings";
    TRY(cj_json_object(&c->json, obj, p, SETTINGS_KEYS));
    cj_scene_settings s = *cj_scene_get_settings(c->scene);
    TRY(cj_json_int(&c->json, obj, p, "width", 1, 32768, &s.width));
    TRY(cj_json_int(&c->json, obj, p, "height", 1, 32768, &s.height));
    TRY(cj_json_int(&c->json, obj, p, "spp", 1, 65536, &s.spp));
    TRY(cj_json_num(&c->json, obj, p, "tol_px", CJ_JSON_GT, 0, 0, &s.tol_px));
    TRY(cj_json_rgb(&c->json, obj, p, "background", -1, &s.background));
    TRY(cj_json_int(&c->json, obj, p, "max_depth", 0, 1000, &s.max_depth));
    double seed = (double)s.seed;
    TRY(cj_json_num(&c->json, obj, p, "seed", CJ_JSON_IN, 0, 9007199254740992.0, &seed));
    if (seed != floor(seed))
        return cj_json_fail(&c->json, cJSON_GetObjectItemCaseSensitive(obj, "seed"), 0,
                            CJ_ERR_PARSE, "settings.seed must be an integer");
    s.seed = (uint64_t)seed;
    int lm = (int)s.light_model;
    TRY(cj_json_enum(&c->json, obj, p, "light_model", LIGHT_MODELS, &lm));
    s.light_model = (cj_light_model)lm;
    static const char *const FILTERS[] = {"box", "tent", "gaussian", "mitchell", NULL};
    int fk = (int)s.filter;
    TRY(cj_json_enum(&c->json, obj, p, "filter", FILTERS, &fk));
    s.filter = (cj_pixel_filter)fk;
    TRY(cj_json_num(&c->json, obj, p, "filter_radius", CJ_JSON_GE, 0, 0, &s.filter_radius));
    cj_status st = cj_scene_set_settings(c->scene, &s);
    return st ? cj_json_relabel(&c->json, obj, st) : CJ_OK;
}

/* ---- lights --------------------------------------------------------------------------------- */

static const char *const LIGHT_TYPES[] = {"ambient", "point", "directional", "spot",
                                          "area",    "disc",  "sphere",      NULL};
/* Keys each light type accepts beyond type, color, intensity, casts_shadows. */
static const char *const LIGHT_KEYS[][10] = {
    {"type", "color", "intensity", "casts_shadows", NULL},
    {"type", "color", "intensity", "casts_shadows", "position", NULL},
    {"type", "color", "intensity", "casts_shadows", "direction", NULL},
    {"type", "color", "intensity", "casts_shadows", "position", "direction", "angle_deg",
     "angle_rad", "exponent", NULL},
    {"type", "color", "intensity", "casts_shadows", "position", "edge_u", "edge_v", NULL},
    {"type", "color", "intensity", "casts_shadows", "position", "direction", "radius", NULL},
    {"type", "color", "intensity", "casts_shadows", "position", "radius", NULL}};

static cj_status read_light(jctx *c, const cJSON *obj, const char *p) {
    if (!cJSON_IsObject(obj))
        return cj_json_fail(&c->json, obj, 0, CJ_ERR_PARSE, "%s must be an object", p);
    const cJSON *tn;
    TRY(cj_json_require(&c->json, obj, p, "type", &tn));
    int type = 0;
    TRY(cj_json_enum(&c->json, obj, p, "type", LIGHT_TYPES, &type));
    TRY(cj_json_object(&c->json, obj, p, LIGHT_KEYS[type]));
    cj_light l = cj_light_defaults((cj_light_kind)type);
    TRY(cj_json_rgb(&c->json, obj, p, "color", -1, &l.color));
    TRY(cj_json_num(&c->json, obj, p, "intensity", CJ_JSON_GE, 0, 0, &l.intensity));
    TRY(cj_json_bool(&c->json, obj, p, "casts_shadows", &l.casts_shadows));
    TRY(cj_json_vec3(&c->json, obj, p, "position", &l.position));
    TRY(cj_json_vec3(&c->json, obj, p, "direction", &l.direction));
    TRY(cj_json_angle(&c->json, obj, p, "angle", CJ_JSON_IN, 0, PI / 2, &l.spot_angle));
    TRY(cj_json_num(&c->json, obj, p, "exponent", CJ_JSON_GE, 0, 0, &l.spot_exponent));
    TRY(cj_json_vec3(&c->json, obj, p, "edge_u", &l.edge_u));
    TRY(cj_json_vec3(&c->json, obj, p, "edge_v", &l.edge_v));
    TRY(cj_json_num(&c->json, obj, p, "radius", CJ_JSON_GE, 0, 0, &l.radius));
    cj_status st = cj_scene_check_light_(&l, p);
    if (!st) st = cj_scene_add_light(c->scene, &l, NULL);
    return st ? cj_json_relabel(&c->json, obj, st) : CJ_OK;
}

cj_status cj_json_read_lights_(jctx *c, const cJSON *arr) {
    TRY(cj_json_list(&c->json, arr, "lights"));
    size_t i = 0;
    for (const cJSON *e = arr->child; e; e = e->next, ++i) {
        char p[CJ_JSON_PATH];
        cj_json_index(p, "lights", i);
        TRY(read_light(c, e, p));
    }
    return CJ_OK;
}

/* ---- textures and materials ----------------------------------------------------------------- */

static const char *const TEX_TYPES[] = {"image", "checker", NULL};
static const char *const TEX_KEYS[][9] = {
    {"name", "type", "path", "filter", "wrap", "scale", "offset", NULL},
    {"name", "type", "checks", "colors", "filter", "wrap", "scale", "offset", NULL}};
static const char *const FILTERS[] = {"nearest", "bilinear", "trilinear", NULL};
static const char *const WRAPS[] = {"repeat", "clamp", NULL};

/* A name unique among the first `count` names of `names` (accessor). */
static cj_status unique_name(const jctx *c, const cJSON *obj, const char *p, const char *what,
                             const char *(*get)(const cj_scene *, int), size_t count,
                             const char **out) {
    const cJSON *n;
    TRY(cj_json_require(&c->json, obj, p, "name", &n));
    const char *name = NULL;
    TRY(cj_json_string(&c->json, obj, p, "name", &name));
    if (!name[0]) return cj_json_fail(&c->json, n, 0, CJ_ERR_PARSE, "%s.name must not be empty", p);
    for (size_t k = 0; k < count; ++k) {
        const char *o = get(c->scene, (int)k);
        if (o && !strcmp(o, name))
            return cj_json_fail(&c->json, n, 0, CJ_ERR_PARSE, "%s.name \"%s\" is already %s[%zu]",
                                p, name, what, k);
    }
    *out = name;
    return CJ_OK;
}

static cj_status read_pair(const jctx *c, const cJSON *obj, const char *p, const char *key,
                           double v[2]) {
    const cJSON *n = cJSON_GetObjectItemCaseSensitive(obj, key);
    if (!n) return CJ_OK;
    char pk[CJ_JSON_PATH];
    cj_json_join(pk, p, key);
    double *vals;
    size_t cnt;
    TRY(cj_json_numbers(&c->json, n, pk, 0, CJ_JSON_ANY, 0, 2, &vals, &cnt));
    v[0] = vals[0];
    v[1] = vals[1];
    free(vals);
    return CJ_OK;
}

static cj_status read_texture(jctx *c, const cJSON *obj, const char *p) {
    if (!cJSON_IsObject(obj))
        return cj_json_fail(&c->json, obj, 0, CJ_ERR_PARSE, "%s must be an object", p);
    const cJSON *tn;
    TRY(cj_json_require(&c->json, obj, p, "type", &tn));
    int type = 0;
    TRY(cj_json_enum(&c->json, obj, p, "type", TEX_TYPES, &type));
    TRY(cj_json_object(&c->json, obj, p, TEX_KEYS[type]));
    const char *name = NULL;
    TRY(unique_name(c, obj, p, "textures", cj_scene_texture_name, cj_scene_texture_count(c->scene),
                    &name));
    cj_texture t = cj_texture_defaults((cj_texture_kind)type);
    int filter = (int)t.filter, wrap = (int)t.wrap;
    TRY(cj_json_enum(&c->json, obj, p, "filter", FILTERS, &filter));
    TRY(cj_json_enum(&c->json, obj, p, "wrap", WRAPS, &wrap));
    t.filter = (cj_tex_filter)filter;
    t.wrap = (cj_tex_wrap)wrap;
    double sc[2] = {t.scale_u, t.scale_v}, of[2] = {t.offset_u, t.offset_v};
    TRY(read_pair(c, obj, p, "scale", sc));
    TRY(read_pair(c, obj, p, "offset", of));
    t.scale_u = sc[0], t.scale_v = sc[1], t.offset_u = of[0], t.offset_v = of[1];
    if (type == CJ_TEX_IMAGE) {
        const cJSON *pn;
        TRY(cj_json_require(&c->json, obj, p, "path", &pn));
        TRY(cj_json_string(&c->json, obj, p, "path", &t.path));
        if (!t.path[0])
            return cj_json_fail(&c->json, pn, 0, CJ_ERR_PARSE, "%s.path must not be empty", p);
    } else {
        const cJSON *ch = cJSON_GetObjectItemCaseSensitive(obj, "checks");
        if (ch) {
            char pk[CJ_JSON_PATH];
            cj_json_join(pk, p, "checks");
            double *v;
            size_t n;
            TRY(cj_json_numbers(&c->json, ch, pk, 0, CJ_JSON_GE, 1, 2, &v, &n));
            int ok = v[0] == floor(v[0]) && v[1] == floor(v[1]) && v[0] <= 1e6 && v[1] <= 1e6;
            t.checks_u = (int)v[0];
            t.checks_v = (int)v[1];
            free(v);
            if (!ok)
                return cj_json_fail(&c->json, ch, 0, CJ_ERR_PARSE,
                                    "%s must be two integers in [1, 1000000]", pk);
        }
        const cJSON *co = cJSON_GetObjectItemCaseSensitive(obj, "colors");
        if (co) {
            char pk[CJ_JSON_PATH];
            cj_json_join(pk, p, "colors");
            if (!cJSON_IsArray(co) || cJSON_GetArraySize(co) != 2)
                return cj_json_fail(&c->json, co, 0, CJ_ERR_PARSE,
                                    "%s must be an array of 2 colours", pk);
            cj_rgb *dst[2] = {&t.checker_a, &t.checker_b};
            int k = 0;
            for (const cJSON *e = co->child; e; e = e->next, ++k) {
                double vals[3];
                if (!cJSON_IsArray(e) || cJSON_GetArraySize(e) != 3)
                    return cj_json_fail(&c->json, e, 0, CJ_ERR_PARSE,
                                        "%s[%d] must be an array of 3 numbers (linear RGB)", pk, k);
                int j = 0;
                for (const cJSON *x = e->child; x; x = x->next, ++j) {
                    if (!cJSON_IsNumber(x) || !isfinite(x->valuedouble))
                        return cj_json_fail(&c->json, x, 0, CJ_ERR_PARSE,
                                            "%s[%d][%d] must be a number", pk, k, j);
                    vals[j] = x->valuedouble;
                    if (!(vals[j] >= 0 && vals[j] <= 1))
                        return cj_json_fail(&c->json, x, 0, CJ_ERR_RANGE,
                                            "%s[%d][%d] must be in [0, 1]", pk, k, j);
                }
                *dst[k] = cj_rgb_make(vals[0], vals[1], vals[2]);
            }
        }
    }
    int index;
    cj_status st = cj_scene_check_texture_(&t, p);
    if (!st) st = cj_scene_add_texture(c->scene, &t, &index);
    if (st) return cj_json_relabel(&c->json, obj, st);
    char where[CJ_JSON_PATH + 300];
    /* Image textures point at their "path" value, the line a missing file is fixed on. */
    const cJSON *at = cJSON_GetObjectItemCaseSensitive(obj, "path");
    snprintf(where, sizeof where, "%s:%d: %s", c->name, cj_json_line(&c->json, at ? at : obj), p);
    st = cj_scene_set_texture_name(c->scene, index, name);
    if (!st) st = cj_scene_set_texture_source(c->scene, index, where);
    return st;
}

cj_status cj_json_read_textures_(jctx *c, const cJSON *arr) {
    TRY(cj_json_list(&c->json, arr, "textures"));
    size_t i = 0;
    for (const cJSON *e = arr->child; e; e = e->next, ++i) {
        char p[CJ_JSON_PATH];
        cj_json_index(p, "textures", i);
        TRY(read_texture(c, e, p));
    }
    return CJ_OK;
}

static const char *const MATERIAL_KEYS[] = {"name",
                                            "color",
                                            "specular",
                                            "ka",
                                            "kd",
                                            "ks",
                                            "alpha",
                                            "shading",
                                            "two_sided",
                                            "texture",
                                            "opacity",
                                            "mirror",
                                            "transmission",
                                            "ior",
                                            "glossiness",
                                            "emission",
                                            "receives_shadows",
                                            "specular_model",
                                            NULL};
static const char *const SHADINGS[] = {"flat", "gouraud", "phong", NULL};
static const char *const SPECULAR_MODELS[] = {"blinn", "phong", NULL}; /* cj_specular_model */

/* A material object (named = 1: an entry of "materials"); *index receives its scene index. */
cj_status cj_json_read_material_(jctx *c, const cJSON *obj, const char *p, int named, int *index) {
    TRY(cj_json_object(&c->json, obj, p, named ? MATERIAL_KEYS : MATERIAL_KEYS + 1));
    const char *name = NULL;
    if (named)
        TRY(unique_name(c, obj, p, "materials", cj_scene_material_name,
                        cj_scene_material_count(c->scene), &name));
    cj_material m = cj_material_defaults();
    TRY(cj_json_rgb(&c->json, obj, p, "color", 1, &m.color));
    TRY(cj_json_rgb(&c->json, obj, p, "specular", 1, &m.specular));
    TRY(cj_json_num(&c->json, obj, p, "ka", CJ_JSON_GE, 0, 0, &m.ka));
    TRY(cj_json_num(&c->json, obj, p, "kd", CJ_JSON_GE, 0, 0, &m.kd));
    TRY(cj_json_num(&c->json, obj, p, "ks", CJ_JSON_GE, 0, 0, &m.ks));
    TRY(cj_json_num(&c->json, obj, p, "alpha", CJ_JSON_GE, 0, 0, &m.alpha));
    int sh = (int)m.shading;
    TRY(cj_json_enum(&c->json, obj, p, "shading", SHADINGS, &sh));
    m.shading = (cj_shading)sh;
    TRY(cj_json_bool(&c->json, obj, p, "two_sided", &m.two_sided));
    const char *tex = NULL;
    TRY(cj_json_string(&c->json, obj, p, "texture", &tex));
    if (tex) {
        size_t n = cj_scene_texture_count(c->scene);
        for (size_t k = 0; k < n && m.texture < 0; ++k) {
            const char *o = cj_scene_texture_name(c->scene, (int)k);
            if (o && !strcmp(o, tex)) m.texture = (int)k;
        }
        if (m.texture < 0)
            return cj_json_fail(&c->json, cJSON_GetObjectItemCaseSensitive(obj, "texture"), 0,
                                CJ_ERR_PARSE, "%s.texture \"%s\" names no texture", p, tex);
    }
    TRY(cj_json_num(&c->json, obj, p, "opacity", CJ_JSON_IN, 0, 1, &m.opacity));
    TRY(cj_json_num(&c->json, obj, p, "mirror", CJ_JSON_IN, 0, 1, &m.mirror));
    TRY(cj_json_num(&c->json, obj, p, "transmission", CJ_JSON_IN, 0, 1, &m.transmission));
    TRY(cj_json_num(&c->json, obj, p, "ior", CJ_JSON_GE, 1, 0, &m.ior));
    TRY(cj_json_num(&c->json, obj, p, "glossiness", CJ_JSON_GE, 0, 0, &m.glossiness));
    TRY(cj_json_rgb(&c->json, obj, p, "emission", -1, &m.emission));
    TRY(cj_json_bool(&c->json, obj, p, "receives_shadows", &m.receives_shadows));
    int spec = (int)m.specular_model;
    TRY(cj_json_enum(&c->json, obj, p, "specular_model", SPECULAR_MODELS, &spec));
    m.specular_model = (cj_specular_model)spec;
    cj_status st = cj_scene_check_material_(&m, cj_scene_texture_count(c->scene), p);
    if (!st) st = cj_scene_add_material(c->scene, &m, index);
    if (st) return cj_json_relabel(&c->json, obj, st);
    return name ? cj_scene_set_material_name(c->scene, *index, name) : CJ_OK;
}

cj_status cj_json_read_materials_(jctx *c, const cJSON *arr) {
    TRY(cj_json_list(&c->json, arr, "materials"));
    size_t i = 0;
    for (const cJSON *e = arr->child; e; e = e->next, ++i) {
        char p[CJ_JSON_PATH];
        cj_json_index(p, "materials", i);
        int index;
        TRY(cj_json_read_material_(c, e, p, 1, &index));
    }
    return CJ_OK;
}

/* The JSON scene reader: transforms and the hierarchy of objects. */
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

static const double DEG = 3.14159265358979323846 / 180.0;

/* ---- transforms ----------------------------------------------------------------------------- */

static const char *const TRANSFORM_KEYS[] = {"translate",   "rotate", "quaternion", "euler_deg",
                                             "euler_order", "scale",  "matrix",     NULL};
static const char *const ROTATE_KEYS[] = {"axis", "angle_deg", "angle_rad", NULL};

static void quat_mul(const double a[4], const double b[4], double out[4]) {
    double r[4] = {a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3],
                   a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
                   a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1],
                   a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0]};
    memcpy(out, r, sizeof r);
}

static void axis_angle(cj_vec3 axis, double angle_rad, double q[4]) {
    cj_vec3 a = cj_v3_normalize(axis);
    double s = sin(0.5 * angle_rad);
    q[0] = cos(0.5 * angle_rad);
    q[1] = a.x * s;
    q[2] = a.y * s;
    q[3] = a.z * s;
}

static cj_status read_transform(const jctx *c, const cJSON *obj, const char *p, cj_transform *t) {
    TRY(cj_json_object(&c->json, obj, p, TRANSFORM_KEYS));
    *t = cj_transform_identity();
    TRY(cj_json_vec3(&c->json, obj, p, "translate", &t->translate));
    const cJSON *rot = cJSON_GetObjectItemCaseSensitive(obj, "rotate");
    const cJSON *qn = cJSON_GetObjectItemCaseSensitive(obj, "quaternion");
    const cJSON *eu = cJSON_GetObjectItemCaseSensitive(obj, "euler_deg");
    const cJSON *eo = cJSON_GetObjectItemCaseSensitive(obj, "euler_order");
    if ((rot != NULL) + (qn != NULL) + (eu != NULL) > 1)
        return cj_json_fail(&c->json, obj, 0, CJ_ERR_PARSE,
                            "%s: give one rotation (rotate, quaternion or euler_deg)", p);
    if (eo && !eu)
        return cj_json_fail(&c->json, eo, 1, CJ_ERR_PARSE, "%s.euler_order needs euler_deg", p);
    if (rot) {
        char pr[CJ_JSON_PATH];
        cj_json_join(pr, p, "rotate");
        TRY(cj_json_object(&c->json, rot, pr, ROTATE_KEYS));
        const cJSON *ax;
        TRY(cj_json_require(&c->json, rot, pr, "axis", &ax));
        cj_vec3 axis = cj_v3(0, 0, 1);
        TRY(cj_json_vec3(&c->json, rot, pr, "axis", &axis));
        if (!(cj_v3_norm(axis) > 0.0))
            return cj_json_fail(&c->json, ax, 0, CJ_ERR_DEGENERATE,
                                "%s.axis must not be the zero vector", pr);
        double a = 0.0;
        if (!cJSON_GetObjectItemCaseSensitive(rot, "angle_deg") &&
            !cJSON_GetObjectItemCaseSensitive(rot, "angle_rad"))
            return cj_json_fail(&c->json, rot, 0, CJ_ERR_PARSE, "%s: missing key \"angle_deg\"",
                                pr);
        TRY(cj_json_angle(&c->json, rot, pr, "angle", CJ_JSON_ANY, 0, 0, &a));
        axis_angle(axis, a, t->rotation);
    } else if (qn) {
        char pq[CJ_JSON_PATH];
        cj_json_join(pq, p, "quaternion");
        double *v;
        size_t n;
        TRY(cj_json_numbers(&c->json, qn, pq, 0, CJ_JSON_ANY, 0, 4, &v, &n));
        double len = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2] + v[3] * v[3]);
        if (!(len > 0.0) || !isfinite(len)) {
            free(v);
            return cj_json_fail(&c->json, qn, 0, CJ_ERR_DEGENERATE, "%s must not be zero", pq);
        }
        /* A unit quaternion is kept bit for bit (files written by cj_scene_save_json). */
        double n2 = v[0] * v[0] + v[1] * v[1] + v[2] * v[2] + v[3] * v[3];
        for (int k = 0; k < 4; ++k) t->rotation[k] = fabs(n2 - 1.0) <= 1e-12 ? v[k] : v[k] / len;
        free(v);
    } else if (eu) {
        char pe[CJ_JSON_PATH];
        cj_json_join(pe, p, "euler_deg");
        double *v;
        size_t n;
        TRY(cj_json_numbers(&c->json, eu, pe, 0, CJ_JSON_ANY, 0, 3, &v, &n));
        static const char *const ORDERS[] = {"xyz", "xzy", "yxz", "yzx", "zxy", "zyx", NULL};
        int order = 0;
        cj_status st = cj_json_enum(&c->json, obj, p, "euler_order", ORDERS, &order);
        if (st) {
            free(v);
            return st;
        }
        double q[4] = {1, 0, 0, 0};
        for (int k = 0; k < 3; ++k) {
            int ax = ORDERS[order][k] - 'x';
            cj_vec3 axis = cj_v3(ax == 0, ax == 1, ax == 2);
            double r[4];
            axis_angle(axis, v[ax] * DEG, r);
            quat_mul(r, q, q); /* later rotations apply after the earlier ones */
        }
        free(v);
        memcpy(t->rotation, q, sizeof q);
    }
    const cJSON *sc = cJSON_GetObjectItemCaseSensitive(obj, "scale");
    if (sc) {
        char ps[CJ_JSON_PATH];
        cj_json_join(ps, p, "scale");
        if (cJSON_IsNumber(sc)) {
            double s = 1.0;
            TRY(cj_json_num(&c->json, obj, p, "scale", CJ_JSON_ANY, 0, 0, &s));
            t->scale = cj_v3(s, s, s);
        } else {
            if (!cJSON_IsArray(sc))
                return cj_json_fail(&c->json, sc, 0, CJ_ERR_PARSE,
                                    "%s must be a number or an array of 3 numbers", ps);
            TRY(cj_json_vec3(&c->json, obj, p, "scale", &t->scale));
        }
        if (t->scale.x == 0 || t->scale.y == 0 || t->scale.z == 0)
            return cj_json_fail(&c->json, sc, 0, CJ_ERR_RANGE, "%s must not be zero", ps);
    }
    const cJSON *mx = cJSON_GetObjectItemCaseSensitive(obj, "matrix");
    if (mx) {
        char pm[CJ_JSON_PATH];
        cj_json_join(pm, p, "matrix");
        if (!cJSON_IsArray(mx) || cJSON_GetArraySize(mx) != 4)
            return cj_json_fail(&c->json, mx, 0, CJ_ERR_PARSE, "%s must be 4 rows of 4 numbers",
                                pm);
        double *v;
        size_t n;
        TRY(cj_json_numbers(&c->json, mx, pm, 4, CJ_JSON_ANY, 0, 4, &v, &n));
        for (int i = 0; i < 4; ++i)
            for (int j = 0; j < 4; ++j) t->matrix.m[i][j] = v[4 * i + j];
        free(v);
        if (!cj_xform3_is_affine(&t->matrix))
            return cj_json_fail(&c->json, mx, 0, CJ_ERR_RANGE, "%s[3] must be [0, 0, 0, 1]", pm);
    }
    cj_status st = cj_scene_check_transform_(t, p);
    return st ? cj_json_relabel(&c->json, obj, st) : CJ_OK;
}

/* ---- objects -------------------------------------------------------------------------------- */

static const char *const NODE_KEYS[] = {"name",     "transform", "material", "geometry",
                                        "children", "overlay",   "visible",  NULL};
static const char *const OVERLAY_KEYS[] = {"control_net", "wireframe", "iso_lines",
                                           "normals",     "color",     NULL};

static cj_status read_overlay(const jctx *c, const cJSON *obj, const char *p, cj_overlay_style *o) {
    TRY(cj_json_object(&c->json, obj, p, OVERLAY_KEYS));
    int net = 0, wire = 0;
    TRY(cj_json_bool(&c->json, obj, p, "control_net", &net));
    TRY(cj_json_bool(&c->json, obj, p, "wireframe", &wire));
    int iso = 0;
    TRY(cj_json_int(&c->json, obj, p, "iso_lines", 0, 10000, &iso));
    double len = 0.0;
    TRY(cj_json_num(&c->json, obj, p, "normals", CJ_JSON_GE, 0, 0, &len));
    TRY(cj_json_rgb(&c->json, obj, p, "color", -1, &o->color));
    o->flags = (net ? CJ_OVERLAY_CONTROL_NET : 0u) | (wire ? CJ_OVERLAY_WIREFRAME : 0u) |
               (iso > 0 ? CJ_OVERLAY_ISO_LINES : 0u) | (len > 0 ? CJ_OVERLAY_NORMALS : 0u);
    if (iso > 0) o->iso_count = iso;
    if (len > 0) o->normal_length = len;
    return CJ_OK;
}

static cj_status node_material(jctx *c, const cJSON *obj, const char *p, int inherited, int *out) {
    const cJSON *mn = cJSON_GetObjectItemCaseSensitive(obj, "material");
    char pm[CJ_JSON_PATH];
    cj_json_join(pm, p, "material");
    if (!mn) {
        *out = inherited;
        return CJ_OK;
    }
    if (cJSON_IsString(mn)) {
        size_t n = cj_scene_material_count(c->scene);
        for (size_t k = 0; k < n; ++k) {
            const char *o = cj_scene_material_name(c->scene, (int)k);
            if (o && !strcmp(o, mn->valuestring)) {
                *out = (int)k;
                return CJ_OK;
            }
        }
        return cj_json_fail(&c->json, mn, 0, CJ_ERR_PARSE, "%s \"%s\" names no material", pm,
                            mn->valuestring);
    }
    if (!cJSON_IsObject(mn))
        return cj_json_fail(&c->json, mn, 0, CJ_ERR_PARSE,
                            "%s must be a material's name or a material object", pm);
    return cj_json_read_material_(c, mn, pm, 0, out);
}

static cj_status node_geometry(jctx *c, const cJSON *gn, const char *p, int *out) {
    char pg[CJ_JSON_PATH];
    cj_json_join(pg, p, "geometry");
    if (cJSON_IsString(gn)) {
        size_t i = 0;
        for (const cJSON *g = c->geometries ? c->geometries->child : NULL; g; g = g->next, ++i) {
            const cJSON *nm = cJSON_GetObjectItemCaseSensitive(g, "name");
            if (!strcmp(nm->valuestring, gn->valuestring)) {
                *out = c->geometry_index[i];
                return CJ_OK;
            }
        }
        return cj_json_fail(&c->json, gn, 0, CJ_ERR_PARSE, "%s \"%s\" names no entry of geometries",
                            pg, gn->valuestring);
    }
    return cj_json_read_geometry_(c, gn, pg, out);
}

static cj_status read_node(jctx *c, const cJSON *obj, const char *p, int parent, int material) {
    TRY(cj_json_object(&c->json, obj, p, NODE_KEYS));
    cj_node n;
    memset(&n, 0, sizeof n);
    n.parent = parent;
    n.geometry = -1;
    n.material = -1;
    n.visible = 1;
    n.local = cj_transform_identity();
    n.overlay.color = cj_rgb_make(1, 1, 0);
    n.overlay.iso_count = 8;
    n.overlay.normal_length = 0.1;
    TRY(cj_json_string(&c->json, obj, p, "name", &n.name));
    TRY(cj_json_bool(&c->json, obj, p, "visible", &n.visible));
    const cJSON *tn = cJSON_GetObjectItemCaseSensitive(obj, "transform");
    if (tn) {
        char pt[CJ_JSON_PATH];
        cj_json_join(pt, p, "transform");
        TRY(read_transform(c, tn, pt, &n.local));
    }
    const cJSON *on = cJSON_GetObjectItemCaseSensitive(obj, "overlay");
    if (on) {
        char po[CJ_JSON_PATH];
        cj_json_join(po, p, "overlay");
        TRY(read_overlay(c, on, po, &n.overlay));
    }
    const cJSON *gn = cJSON_GetObjectItemCaseSensitive(obj, "geometry");
    const cJSON *ch = cJSON_GetObjectItemCaseSensitive(obj, "children");
    if (gn && ch)
        return cj_json_fail(&c->json, ch, 1, CJ_ERR_PARSE,
                            "%s: an object has either a geometry or children, not both", p);
    if (!gn && !ch)
        return cj_json_fail(&c->json, obj, 0, CJ_ERR_PARSE,
                            "%s: missing key \"geometry\" (or \"children\" for a group)", p);
    int mat;
    TRY(node_material(c, obj, p, material, &mat));
    int index;
    if (gn) {
        TRY(node_geometry(c, gn, p, &n.geometry));
        if (mat < 0) {
            if (c->default_material < 0) {
                cj_material d = cj_material_defaults();
                TRY(cj_scene_add_material(c->scene, &d, &c->default_material));
            }
            mat = c->default_material;
        }
        n.material = mat;
        cj_status st = cj_scene_add_node(c->scene, &n, &index);
        return st ? cj_json_relabel(&c->json, obj, st) : CJ_OK;
    }
    cj_status st = cj_scene_add_node(c->scene, &n, &index);
    if (st) return cj_json_relabel(&c->json, obj, st);
    char pc[CJ_JSON_PATH];
    cj_json_join(pc, p, "children");
    TRY(cj_json_list(&c->json, ch, pc));
    size_t i = 0;
    for (const cJSON *e = ch->child; e; e = e->next, ++i) {
        char pe[CJ_JSON_PATH];
        cj_json_index(pe, pc, i);
        TRY(read_node(c, e, pe, index, mat));
    }
    return CJ_OK;
}

cj_status cj_json_read_objects_(jctx *c, const cJSON *arr) {
    TRY(cj_json_list(&c->json, arr, "objects"));
    size_t i = 0;
    for (const cJSON *e = arr->child; e; e = e->next, ++i) {
        char p[CJ_JSON_PATH];
        cj_json_index(p, "objects", i);
        TRY(read_node(c, e, p, -1, -1));
    }
    return CJ_OK;
}

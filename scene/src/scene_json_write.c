/* The JSON scene writer: every part of a checked scene in the format scene_json.h documents,
 * numbers in the shortest form that reads back to the same double, written atomically. */
#define _POSIX_C_SOURCE 200809L
#include "scene_internal.h"

#include "casteljau/scene_bspline.h"
#include "casteljau/scene_json.h"
#include "error_internal.h"
#include "bspline_surface_json_internal.h"
#include "json_write_internal.h"

#include <assert.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The document is built as a cJSON tree (stack[depth] is the open object or array) and printed
 * by cJSON's printer through json_write_internal.h: one escaper, shortest exact numbers. */
#define EMIT_DEPTH 64
typedef struct emitter {
    cJSON *stack[EMIT_DEPTH];
    int depth;
    int oom;      /* an allocation failed: the document is not written */
    int too_deep; /* the node hierarchy is deeper than EMIT_DEPTH allows */
} emitter;

static const double DEG = 3.14159265358979323846 / 180.0;

/* Adds item (taking it) to the open container, under key in an object. */
static void add(emitter *e, const char *key, cJSON *item) {
    cJSON *parent = e->stack[e->depth];
    if (!item ||
        !(key ? cJSON_AddItemToObject(parent, key, item) : cJSON_AddItemToArray(parent, item))) {
        cJSON_Delete(item);
        e->oom = 1;
    }
}

static void open_c(emitter *e, const char *key, char c) {
    cJSON *x = c == '{' ? cJSON_CreateObject() : cJSON_CreateArray();
    cJSON *parent = e->stack[e->depth];
    add(e, key, x);
    if (e->depth + 1 >= EMIT_DEPTH) {
        e->too_deep = 1;
        return;
    }
    /* after a failed add, later members land in the parent: the document is dropped anyway */
    e->stack[++e->depth] = e->oom ? parent : x;
}

static void close_c(emitter *e, char c) {
    (void)c;
    if (e->depth > 0 && !e->too_deep) e->depth--;
}

static void num(emitter *e, const char *key, double v) {
    add(e, key, cj_json_number(v));
}

static void integer(emitter *e, const char *key, long long v) {
    num(e, key, (double)v);
}

static void boolean(emitter *e, const char *key, int v) {
    add(e, key, cJSON_CreateBool(v));
}

static void string(emitter *e, const char *key, const char *s) {
    add(e, key, cJSON_CreateString(s));
}

static void nums(emitter *e, const char *key, const double *v, size_t n) {
    add(e, key, cj_json_number_array(v, n));
}

static void vec3(emitter *e, const char *key, cj_vec3 v) {
    const double a[3] = {v.x, v.y, v.z};
    nums(e, key, a, 3);
}

static void rgb(emitter *e, const char *key, cj_rgb c) {
    const double a[3] = {c.r, c.g, c.b};
    nums(e, key, a, 3);
}

/* count points of dim coordinates as [[...], [...]]. */
static void points(emitter *e, const char *key, const double *p, size_t count, int dim) {
    open_c(e, key, '[');
    for (size_t i = 0; i < count; ++i) nums(e, NULL, p + i * (size_t)dim, (size_t)dim);
    close_c(e, ']');
}

static void weights(emitter *e, const double *w, size_t n) {
    if (w) nums(e, "weights", w, n);
}

/* Two whole numbers [a, b] (degrees of a patch, checks of a checker). */
static void pair(emitter *e, const char *key, int a, int b) {
    const double v[2] = {a, b};
    nums(e, key, v, 2);
}

/* An angle in degrees when that reads back to the same radians, else in radians. */
static void angle(emitter *e, const char *key, double rad) {
    char k[64];
    double deg = rad / DEG;
    char buf[40];
    snprintf(buf, sizeof buf, "%.17g", deg);
    if (strtod(buf, NULL) * DEG == rad) {
        snprintf(k, sizeof k, "%s_deg", key);
        num(e, k, deg);
    } else {
        snprintf(k, sizeof k, "%s_rad", key);
        num(e, k, rad);
    }
}

/* ---- parts ---------------------------------------------------------------------------------- */

static void write_camera(emitter *e, const cj_camera *c) {
    open_c(e, "camera", '{');
    vec3(e, "eye", c->eye);
    vec3(e, "gaze", c->gaze);
    vec3(e, "up", c->up);
    num(e, "near", c->near);
    num(e, "far", c->far);
    string(e, "projection", c->projection == CJ_PROJ_PERSPECTIVE ? "perspective" : "orthographic");
    angle(e, "fov", c->fov_y);
    if (c->ortho_height > 0) num(e, "ortho_height", c->ortho_height);
    if (c->aperture > 0) {
        num(e, "aperture", c->aperture);
        num(e, "focus_distance", c->focus_distance);
    }
    close_c(e, '}');
}

static void write_settings(emitter *e, const cj_scene_settings *s) {
    open_c(e, "settings", '{');
    integer(e, "width", s->width);
    integer(e, "height", s->height);
    integer(e, "spp", s->spp);
    num(e, "tol_px", s->tol_px);
    rgb(e, "background", s->background);
    integer(e, "max_depth", s->max_depth);
    integer(e, "seed", (long long)s->seed);
    string(e, "light_model", s->light_model == CJ_LIGHT_RADIOMETRIC ? "radiometric" : "legacy");
    static const char *const FILTERS[] = {"box", "tent", "gaussian", "mitchell"};
    string(e, "filter", FILTERS[s->filter]);
    num(e, "filter_radius", s->filter_radius);
    close_c(e, '}');
}

static void write_light(emitter *e, const cj_light *l) {
    static const char *const TYPES[] = {"ambient", "point", "directional", "spot",
                                        "area",    "disc",  "sphere"};
    open_c(e, NULL, '{');
    string(e, "type", TYPES[l->kind]);
    rgb(e, "color", l->color);
    num(e, "intensity", l->intensity);
    boolean(e, "casts_shadows", l->casts_shadows);
    if (l->kind == CJ_LIGHT_POINT || l->kind == CJ_LIGHT_SPOT || l->kind == CJ_LIGHT_AREA ||
        l->kind == CJ_LIGHT_DISC || l->kind == CJ_LIGHT_SPHERE)
        vec3(e, "position", l->position);
    if (l->kind == CJ_LIGHT_DIRECTIONAL || l->kind == CJ_LIGHT_SPOT || l->kind == CJ_LIGHT_DISC)
        vec3(e, "direction", l->direction);
    if (l->kind == CJ_LIGHT_DISC || l->kind == CJ_LIGHT_SPHERE) num(e, "radius", l->radius);
    if (l->kind == CJ_LIGHT_SPOT) {
        angle(e, "angle", l->spot_angle);
        num(e, "exponent", l->spot_exponent);
    }
    if (l->kind == CJ_LIGHT_AREA) {
        vec3(e, "edge_u", l->edge_u);
        vec3(e, "edge_v", l->edge_v);
    }
    close_c(e, '}');
}

#define NAME_CAP 1024

/* The name part i of `names` (count entries) is written under: its own, else prefix + i with
 * "_" appended until it differs from every other name. */
static void part_name(char *dst, char *const *names, size_t count, const char *prefix, int i) {
    if (names[i]) {
        snprintf(dst, NAME_CAP, "%s", names[i]);
        return;
    }
    snprintf(dst, NAME_CAP, "%s%d", prefix, i);
    for (int clash = 1; clash;) {
        clash = 0;
        for (size_t k = 0; k < count && !clash; ++k) clash = names[k] && !strcmp(names[k], dst);
        if (clash && strlen(dst) + 2 < NAME_CAP) strcat(dst, "_");
    }
}

/* Names the reader would refuse: repeated, empty or too long. */
static cj_status check_names(char *const *names, size_t count, const char *what) {
    for (size_t i = 0; i < count; ++i) {
        if (!names[i]) continue;
        if (!names[i][0] || strlen(names[i]) >= NAME_CAP - 8)
            return cj_fail(CJ_ERR_ARGUMENT, "%s[%zu]: the name is empty or too long", what, i);
        for (size_t k = 0; k < i; ++k)
            if (names[k] && !strcmp(names[k], names[i]))
                return cj_fail(CJ_ERR_ARGUMENT, "%s[%zu].name \"%s\" is already %s[%zu]", what, i,
                               names[i], what, k);
    }
    return CJ_OK;
}

static void write_texture(emitter *e, const cj_scene *s, int i) {
    static const char *const FILTERS[] = {"nearest", "bilinear", "trilinear"};
    const cj_texture *t = &s->textures[i];
    char name[NAME_CAP];
    part_name(name, s->texture_names, s->ntextures, "texture", i);
    open_c(e, NULL, '{');
    string(e, "name", name);
    string(e, "type", t->kind == CJ_TEX_IMAGE ? "image" : "checker");
    if (t->kind == CJ_TEX_IMAGE) string(e, "path", t->path);
    string(e, "filter", FILTERS[t->filter]);
    string(e, "wrap", t->wrap == CJ_TEX_REPEAT ? "repeat" : "clamp");
    const double sc[2] = {t->scale_u, t->scale_v}, of[2] = {t->offset_u, t->offset_v};
    nums(e, "scale", sc, 2);
    nums(e, "offset", of, 2);
    if (t->kind == CJ_TEX_CHECKER) {
        pair(e, "checks", t->checks_u, t->checks_v);
        open_c(e, "colors", '[');
        rgb(e, NULL, t->checker_a);
        rgb(e, NULL, t->checker_b);
        close_c(e, ']');
    }
    close_c(e, '}');
}

static void write_material(emitter *e, const cj_scene *s, int i) {
    static const char *const SHADINGS[] = {"flat", "gouraud", "phong"};
    const cj_material *m = &s->materials[i];
    char name[NAME_CAP];
    part_name(name, s->material_names, s->nmaterials, "material", i);
    open_c(e, NULL, '{');
    string(e, "name", name);
    rgb(e, "color", m->color);
    rgb(e, "specular", m->specular);
    num(e, "ka", m->ka);
    num(e, "kd", m->kd);
    num(e, "ks", m->ks);
    num(e, "alpha", m->alpha);
    string(e, "shading", SHADINGS[m->shading]);
    boolean(e, "two_sided", m->two_sided);
    if (m->texture >= 0) {
        char tn[NAME_CAP];
        part_name(tn, s->texture_names, s->ntextures, "texture", m->texture);
        string(e, "texture", tn);
    }
    num(e, "opacity", m->opacity);
    num(e, "mirror", m->mirror);
    num(e, "transmission", m->transmission);
    num(e, "ior", m->ior);
    num(e, "glossiness", m->glossiness);
    rgb(e, "emission", m->emission);
    boolean(e, "receives_shadows", m->receives_shadows);
    string(e, "specular_model", m->specular_model == CJ_SPEC_PHONG ? "phong" : "blinn");
    close_c(e, '}');
}

static void write_quadric(emitter *e, const cj_quadric *q) {
    static const char *const KINDS[] = {"ellipsoid", "hyperboloid1", "hyperboloid2",
                                        "cone",      "paraboloid",   "hyperbolic_paraboloid"};
    string(e, "type", "quadric");
    string(e, "kind", KINDS[q->kind]);
    num(e, "a", q->a);
    num(e, "b", q->b);
    if (q->kind <= CJ_QUADRIC_CONE) num(e, "c", q->c);
    if (q->kind == CJ_QUADRIC_HYPERBOLIC_PARABOLOID) {
        num(e, "u0", q->u0);
        num(e, "u1", q->u1);
    }
    if (q->kind == CJ_QUADRIC_HYPERBOLOID1 || q->kind == CJ_QUADRIC_CONE ||
        q->kind == CJ_QUADRIC_HYPERBOLIC_PARABOLOID)
        num(e, "v0", q->v0);
    if (q->kind != CJ_QUADRIC_ELLIPSOID) num(e, "v1", q->v1);
    if (q->kind == CJ_QUADRIC_HYPERBOLOID2) boolean(e, "lower", q->lower);
}

static void write_mesh(emitter *e, const cj_mesh *m) {
    string(e, "type", "mesh");
    points(e, "positions", m->positions, m->vertex_count, 3);
    points(e, "normals", m->normals, m->vertex_count, 3);
    points(e, "uvs", m->uvs, m->vertex_count, 2);
    open_c(e, "triangles", '[');
    for (size_t t = 0; t < m->triangle_count; ++t) {
        const uint32_t *v = m->triangles + 3 * t;
        const double corners[3] = {v[0], v[1], v[2]};
        nums(e, NULL, corners, 3);
    }
    close_c(e, ']');
    open_c(e, "patch_ids", '[');
    for (size_t t = 0; t < m->triangle_count; ++t) integer(e, NULL, m->triangle_patch[t]);
    close_c(e, ']');
}

static void write_curve(emitter *e, const cj_geometry *g) {
    static const char *const SPLINES[] = {"catmull-rom", "centripetal", "chordal",
                                          "kochanek-bartels"};
    string(e, "type", "curve");
    const cj_curve_kind k = g->u.curve.kind;
    string(e, "kind",
           k == CJ_CURVE_BEZIER     ? "bezier"
           : k == CJ_CURVE_RATIONAL ? "rational"
                                    : SPLINES[g->u.curve.spline]);
    points(e, "points", g->u.curve.pts, g->u.curve.count, 3);
    if (k == CJ_CURVE_RATIONAL) weights(e, g->u.curve.weights, g->u.curve.count);
    if (k == CJ_CURVE_SPLINE) {
        num(e, "tension", g->u.curve.tension);
        boolean(e, "closed", g->u.curve.closed);
        if (g->u.curve.spline == CJ_SPLINE_KOCHANEK_BARTELS) {
            num(e, "continuity", g->u.curve.continuity);
            num(e, "bias", g->u.curve.bias);
        }
    }
    num(e, "width_px", g->u.curve.width_px);
    rgb(e, "color", g->u.curve.color);
}

/* A geometry that keeps its B-spline form, written as that form (knots always explicit, so a
 * load of the file rebuilds the same surface bit for bit). */
static void write_bspline_surface(emitter *e, const cj_bspline_surface *b) {
    /* the one writer of the object, also the surface document's (bspline_surface_json.c) */
    if (!e->oom && !e->too_deep && cj_json_add_bspline_surface(e->stack[e->depth], b)) e->oom = 1;
}

static void write_geometry(emitter *e, const cj_scene *s, int i) {
    const cj_geometry *g = cj_scene_geometry(s, i);
    char name[32];
    snprintf(name, sizeof name, "geometry%d", i);
    open_c(e, NULL, '{');
    string(e, "name", name);
    const cj_bspline_surface *bsp = cj_scene_geometry_bspline(s, i);
    if (bsp && cj_scene_bspline_in_sync_(s, i)) {
        write_bspline_surface(e, bsp);
        close_c(e, '}');
        return;
    }
    switch (g->kind) {
    case CJ_GEOM_PATCHES:
        string(e, "type", "patches");
        open_c(e, "patches", '[');
        for (size_t k = 0; k < g->u.patches.count; ++k) {
            const cj_patch *p = &g->u.patches.patches[k];
            open_c(e, NULL, '{');
            pair(e, "degree", p->deg_u, p->deg_v);
            points(e, "points", p->pts, cj_patch_point_count(p), 3);
            weights(e, p->weights, cj_patch_point_count(p));
            close_c(e, '}');
        }
        close_c(e, ']');
        break;
    case CJ_GEOM_QUADRIC:
        write_quadric(e, &g->u.quadric);
        break;
    case CJ_GEOM_SPHERE:
        string(e, "type", "sphere");
        vec3(e, "center", g->u.sphere.center);
        num(e, "radius", g->u.sphere.radius);
        break;
    case CJ_GEOM_TORUS:
        string(e, "type", "torus");
        vec3(e, "center", g->u.torus.center);
        vec3(e, "axis", g->u.torus.a);
        num(e, "major", g->u.torus.major);
        num(e, "minor", g->u.torus.minor);
        break;
    case CJ_GEOM_CYLINDER:
        string(e, "type", "cylinder");
        vec3(e, "base", g->u.cylinder.base);
        vec3(e, "axis", g->u.cylinder.a);
        num(e, "radius", g->u.cylinder.radius);
        num(e, "h0", g->u.cylinder.h0);
        num(e, "h1", g->u.cylinder.h1);
        break;
    case CJ_GEOM_PLANAR:
        string(e, "type", "planar");
        vec3(e, "origin", g->u.planar.p);
        vec3(e, "edge_u", g->u.planar.eu);
        vec3(e, "edge_v", g->u.planar.ev);
        break;
    case CJ_GEOM_BILINEAR:
        string(e, "type", "bilinear");
        vec3(e, "p00", g->u.bilinear.p00);
        vec3(e, "p10", g->u.bilinear.p10);
        vec3(e, "p01", g->u.bilinear.p01);
        vec3(e, "p11", g->u.bilinear.p11);
        break;
    case CJ_GEOM_REVOLUTION:
        string(e, "type", "revolution");
        points(e, "points", g->u.revolution.pts, (size_t)g->u.revolution.degree + 1, 2);
        weights(e, g->u.revolution.weights, (size_t)g->u.revolution.degree + 1);
        vec3(e, "origin", g->u.revolution.origin);
        vec3(e, "axis", g->u.revolution.axis);
        break;
    case CJ_GEOM_GEN_CYLINDER:
        string(e, "type", "gen_cylinder");
        points(e, "points", g->u.gen_cylinder.pts, (size_t)g->u.gen_cylinder.degree + 1, 2);
        weights(e, g->u.gen_cylinder.weights, (size_t)g->u.gen_cylinder.degree + 1);
        vec3(e, "origin", g->u.gen_cylinder.origin);
        vec3(e, "e1", g->u.gen_cylinder.e1);
        vec3(e, "e2", g->u.gen_cylinder.e2);
        vec3(e, "dir", g->u.gen_cylinder.dir);
        num(e, "v0", g->u.gen_cylinder.v0);
        num(e, "v1", g->u.gen_cylinder.v1);
        break;
    case CJ_GEOM_MESH:
        write_mesh(e, g->u.mesh);
        break;
    default:
        write_curve(e, g);
        break;
    }
    close_c(e, '}');
}

static int is_identity(const cj_xform3 *m) {
    cj_xform3 id = cj_xform3_identity();
    return !memcmp(m->m, id.m, sizeof id.m);
}

static void write_node(emitter *e, const cj_scene *s, size_t i) {
    const cj_node *n = &s->nodes[i];
    open_c(e, NULL, '{');
    if (n->name) string(e, "name", n->name);
    open_c(e, "transform", '{');
    vec3(e, "translate", n->local.translate);
    nums(e, "quaternion", n->local.rotation, 4);
    vec3(e, "scale", n->local.scale);
    if (!is_identity(&n->local.matrix)) {
        open_c(e, "matrix", '[');
        for (int r = 0; r < 4; ++r) nums(e, NULL, n->local.matrix.m[r], 4);
        close_c(e, ']');
    }
    close_c(e, '}');
    if (!n->visible) boolean(e, "visible", 0);
    const cj_overlay_style *o = &n->overlay;
    if (o->flags) {
        open_c(e, "overlay", '{');
        boolean(e, "control_net", (o->flags & CJ_OVERLAY_CONTROL_NET) != 0);
        boolean(e, "wireframe", (o->flags & CJ_OVERLAY_WIREFRAME) != 0);
        integer(e, "iso_lines", (o->flags & CJ_OVERLAY_ISO_LINES) ? o->iso_count : 0);
        num(e, "normals", (o->flags & CJ_OVERLAY_NORMALS) ? o->normal_length : 0.0);
        rgb(e, "color", o->color);
        close_c(e, '}');
    }
    if (n->geometry >= 0) {
        char name[NAME_CAP];
        part_name(name, s->material_names, s->nmaterials, "material", n->material);
        string(e, "material", name);
        snprintf(name, sizeof name, "geometry%d", n->geometry);
        string(e, "geometry", name);
    } else {
        open_c(e, "children", '[');
        for (size_t k = i + 1; k < s->nnodes; ++k)
            if (s->nodes[k].parent == (int)i) write_node(e, s, k);
        close_c(e, ']');
    }
    close_c(e, '}');
}

static void write_scene(emitter *e, const cj_scene *s) {
    write_camera(e, &s->camera);
    write_settings(e, &s->settings);
    open_c(e, "lights", '[');
    for (size_t i = 0; i < s->nlights; ++i) write_light(e, &s->lights[i]);
    close_c(e, ']');
    open_c(e, "textures", '[');
    for (size_t i = 0; i < s->ntextures; ++i) write_texture(e, s, (int)i);
    close_c(e, ']');
    open_c(e, "materials", '[');
    for (size_t i = 0; i < s->nmaterials; ++i) write_material(e, s, (int)i);
    close_c(e, ']');
    open_c(e, "geometries", '[');
    for (size_t i = 0; i < s->ngeoms; ++i) write_geometry(e, s, (int)i);
    close_c(e, ']');
    open_c(e, "objects", '[');
    for (size_t i = 0; i < s->nnodes; ++i)
        if (s->nodes[i].parent < 0) write_node(e, s, i);
    close_c(e, ']');
}

/* ---- the file ------------------------------------------------------------------------------- */

cj_status cj_scene_save_json(const cj_scene *s, const char *path) {
    assert(s && path);
    cj_status st = cj_scene_check(s);
    if (!st) st = check_names(s->material_names, s->nmaterials, "materials");
    if (!st) st = check_names(s->texture_names, s->ntextures, "textures");
    if (st) return st;
    if (s->settings.seed > (1ull << 53))
        return cj_fail(CJ_ERR_RANGE, "settings.seed %llu is above 2^53 (not exact in JSON)",
                       (unsigned long long)s->settings.seed);
    emitter e;
    memset(&e, 0, sizeof e);
    cJSON *root = e.stack[0] = cJSON_CreateObject();
    if (root) write_scene(&e, s);
    if (!root || e.oom)
        st = cj_fail(CJ_ERR_NOMEM, "out of memory saving '%s'", path);
    else if (e.too_deep)
        st = cj_fail(CJ_ERR_RANGE, "saving '%s': the object hierarchy is deeper than %d levels",
                     path, EMIT_DEPTH / 2 - 2);
    else
        st = cj_json_write_file(root, path, path);
    cJSON_Delete(root);
    return st;
}

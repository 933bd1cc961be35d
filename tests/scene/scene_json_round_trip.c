/* The JSON scene format, round trips: save -> load gives an equal scene, field by field, and
 * saving the reloaded scene gives the same bytes; a failed save keeps the old file. Part of
 * test_scene_json (tests/scene/test_scene_json.c runs these). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "casteljau/mesh.h"
#include "casteljau/scene_json.h"
#include "scene_json_test.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- round trip ----------------------------------------------------------------------------- */

#define EQ(p_, q_, w_)                                                                             \
    do {                                                                                           \
        if (!((p_) == (q_)))                                                                       \
            fail_msg("%s: %s differs (%.17g vs %.17g)", ctx, w_, (double)(p_), (double)(q_));      \
    } while (0)
#define EQV(p_, q_, w_)                                                                            \
    do {                                                                                           \
        EQ((p_).x, (q_).x, w_);                                                                    \
        EQ((p_).y, (q_).y, w_);                                                                    \
        EQ((p_).z, (q_).z, w_);                                                                    \
    } while (0)
#define EQC(p_, q_, w_)                                                                            \
    do {                                                                                           \
        EQ((p_).r, (q_).r, w_);                                                                    \
        EQ((p_).g, (q_).g, w_);                                                                    \
        EQ((p_).b, (q_).b, w_);                                                                    \
    } while (0)

static void eq_array(const char *ctx, const double *a, const double *b, size_t n, const char *w) {
    if (!a || !b) {
        if (a != b) fail_msg("%s: %s present on one side only", ctx, w);
        return;
    }
    for (size_t i = 0; i < n; ++i) EQ(a[i], b[i], w);
}

static void eq_geometry(const char *ctx, const cj_geometry *a, const cj_geometry *b) {
    EQ(a->kind, b->kind, "kind");
    switch (a->kind) {
    case CJ_GEOM_PATCHES:
        EQ(a->u.patches.count, b->u.patches.count, "patch count");
        for (size_t i = 0; i < a->u.patches.count; ++i) {
            const cj_patch *p = &a->u.patches.patches[i], *q = &b->u.patches.patches[i];
            EQ(p->deg_u, q->deg_u, "deg_u");
            EQ(p->deg_v, q->deg_v, "deg_v");
            eq_array(ctx, p->pts, q->pts, 3 * cj_patch_point_count(p), "patch points");
            eq_array(ctx, p->weights, q->weights, cj_patch_point_count(p), "patch weights");
        }
        break;
    case CJ_GEOM_QUADRIC:
        EQ(a->u.quadric.kind, b->u.quadric.kind, "quadric kind");
        EQ(a->u.quadric.a, b->u.quadric.a, "a");
        EQ(a->u.quadric.b, b->u.quadric.b, "b");
        EQ(a->u.quadric.c, b->u.quadric.c, "c");
        EQ(a->u.quadric.u0, b->u.quadric.u0, "u0");
        EQ(a->u.quadric.u1, b->u.quadric.u1, "u1");
        EQ(a->u.quadric.v0, b->u.quadric.v0, "v0");
        EQ(a->u.quadric.v1, b->u.quadric.v1, "v1");
        EQ(a->u.quadric.lower, b->u.quadric.lower, "lower");
        break;
    case CJ_GEOM_SPHERE:
        EQV(a->u.sphere.center, b->u.sphere.center, "center");
        EQ(a->u.sphere.radius, b->u.sphere.radius, "radius");
        break;
    case CJ_GEOM_TORUS:
        EQV(a->u.torus.center, b->u.torus.center, "center");
        EQV(a->u.torus.a, b->u.torus.a, "axis");
        EQV(a->u.torus.e1, b->u.torus.e1, "e1");
        EQV(a->u.torus.e2, b->u.torus.e2, "e2");
        EQ(a->u.torus.major, b->u.torus.major, "major");
        EQ(a->u.torus.minor, b->u.torus.minor, "minor");
        break;
    case CJ_GEOM_CYLINDER:
        EQV(a->u.cylinder.base, b->u.cylinder.base, "base");
        EQV(a->u.cylinder.a, b->u.cylinder.a, "axis");
        EQV(a->u.cylinder.e1, b->u.cylinder.e1, "e1");
        EQ(a->u.cylinder.radius, b->u.cylinder.radius, "radius");
        EQ(a->u.cylinder.h0, b->u.cylinder.h0, "h0");
        EQ(a->u.cylinder.h1, b->u.cylinder.h1, "h1");
        break;
    case CJ_GEOM_PLANAR:
        EQV(a->u.planar.p, b->u.planar.p, "origin");
        EQV(a->u.planar.eu, b->u.planar.eu, "edge_u");
        EQV(a->u.planar.ev, b->u.planar.ev, "edge_v");
        EQV(a->u.planar.plane.n, b->u.planar.plane.n, "plane normal");
        break;
    case CJ_GEOM_BILINEAR:
        EQV(a->u.bilinear.p00, b->u.bilinear.p00, "p00");
        EQV(a->u.bilinear.p10, b->u.bilinear.p10, "p10");
        EQV(a->u.bilinear.p01, b->u.bilinear.p01, "p01");
        EQV(a->u.bilinear.p11, b->u.bilinear.p11, "p11");
        EQ(a->u.bilinear.flags, b->u.bilinear.flags, "flags");
        break;
    case CJ_GEOM_REVOLUTION:
        EQ(a->u.revolution.degree, b->u.revolution.degree, "degree");
        eq_array(ctx, a->u.revolution.pts, b->u.revolution.pts,
                 2 * (size_t)(a->u.revolution.degree + 1), "profile");
        eq_array(ctx, a->u.revolution.weights, b->u.revolution.weights,
                 (size_t)(a->u.revolution.degree + 1), "weights");
        EQV(a->u.revolution.origin, b->u.revolution.origin, "origin");
        EQV(a->u.revolution.axis, b->u.revolution.axis, "axis");
        break;
    case CJ_GEOM_GEN_CYLINDER:
        EQ(a->u.gen_cylinder.degree, b->u.gen_cylinder.degree, "degree");
        eq_array(ctx, a->u.gen_cylinder.pts, b->u.gen_cylinder.pts,
                 2 * (size_t)(a->u.gen_cylinder.degree + 1), "profile");
        eq_array(ctx, a->u.gen_cylinder.weights, b->u.gen_cylinder.weights,
                 (size_t)(a->u.gen_cylinder.degree + 1), "weights");
        EQV(a->u.gen_cylinder.e1, b->u.gen_cylinder.e1, "e1");
        EQV(a->u.gen_cylinder.e2, b->u.gen_cylinder.e2, "e2");
        EQV(a->u.gen_cylinder.dir, b->u.gen_cylinder.dir, "dir");
        EQ(a->u.gen_cylinder.v0, b->u.gen_cylinder.v0, "v0");
        EQ(a->u.gen_cylinder.v1, b->u.gen_cylinder.v1, "v1");
        break;
    case CJ_GEOM_MESH: {
        const cj_mesh *m = a->u.mesh, *n = b->u.mesh;
        EQ(m->vertex_count, n->vertex_count, "vertices");
        EQ(m->triangle_count, n->triangle_count, "triangles");
        eq_array(ctx, m->positions, n->positions, 3 * m->vertex_count, "positions");
        eq_array(ctx, m->normals, n->normals, 3 * m->vertex_count, "normals");
        eq_array(ctx, m->uvs, n->uvs, 2 * m->vertex_count, "uvs");
        for (size_t t = 0; t < 3 * m->triangle_count; ++t)
            EQ(m->triangles[t], n->triangles[t], "triangle index");
        for (size_t t = 0; t < m->triangle_count; ++t)
            EQ(m->triangle_patch[t], n->triangle_patch[t], "patch id");
        break;
    }
    default:
        EQ(a->u.curve.kind, b->u.curve.kind, "curve kind");
        EQ(a->u.curve.count, b->u.curve.count, "count");
        if (a->u.curve.kind != CJ_CURVE_SPLINE) EQ(a->u.curve.degree, b->u.curve.degree, "degree");
        eq_array(ctx, a->u.curve.pts, b->u.curve.pts, 3 * a->u.curve.count, "points");
        eq_array(ctx, a->u.curve.weights, b->u.curve.weights, a->u.curve.count, "weights");
        if (a->u.curve.kind == CJ_CURVE_SPLINE) {
            EQ(a->u.curve.spline, b->u.curve.spline, "spline");
            EQ(a->u.curve.tension, b->u.curve.tension, "tension");
            EQ(a->u.curve.closed, b->u.curve.closed, "closed");
            if (a->u.curve.spline == CJ_SPLINE_KOCHANEK_BARTELS) {
                EQ(a->u.curve.continuity, b->u.curve.continuity, "continuity");
                EQ(a->u.curve.bias, b->u.curve.bias, "bias");
            }
        }
        EQ(a->u.curve.width_px, b->u.curve.width_px, "width_px");
        EQC(a->u.curve.color, b->u.curve.color, "color");
    }
}

/* Equal values everywhere; names where the first scene has them. */
static void eq_scenes(const char *ctx, const cj_scene *a, const cj_scene *b) {
    const cj_camera *c = cj_scene_get_camera(a), *d = cj_scene_get_camera(b);
    EQV(c->eye, d->eye, "eye");
    EQV(c->gaze, d->gaze, "gaze");
    EQV(c->up, d->up, "up");
    EQ(c->near, d->near, "near");
    EQ(c->far, d->far, "far");
    EQ(c->projection, d->projection, "projection");
    EQ(c->fov_y, d->fov_y, "fov_y");
    const cj_scene_settings *s = cj_scene_get_settings(a), *t = cj_scene_get_settings(b);
    EQ(s->width, t->width, "width");
    EQ(s->height, t->height, "height");
    EQ(s->spp, t->spp, "spp");
    EQ(s->tol_px, t->tol_px, "tol_px");
    EQC(s->background, t->background, "background");
    EQ(s->max_depth, t->max_depth, "max_depth");
    EQ(s->seed, t->seed, "seed");
    EQ(cj_scene_light_count(a), cj_scene_light_count(b), "light count");
    for (int i = 0; i < (int)cj_scene_light_count(a); ++i) {
        const cj_light *l = cj_scene_light(a, i), *m = cj_scene_light(b, i);
        EQ(l->kind, m->kind, "light kind");
        EQC(l->color, m->color, "light color");
        EQ(l->intensity, m->intensity, "intensity");
        EQ(l->casts_shadows, m->casts_shadows, "casts_shadows");
        if (l->kind != CJ_LIGHT_AMBIENT && l->kind != CJ_LIGHT_DIRECTIONAL)
            EQV(l->position, m->position, "position");
        if (l->kind == CJ_LIGHT_DIRECTIONAL || l->kind == CJ_LIGHT_SPOT)
            EQV(l->direction, m->direction, "direction");
        if (l->kind == CJ_LIGHT_SPOT) {
            EQ(l->spot_angle, m->spot_angle, "spot_angle");
            EQ(l->spot_exponent, m->spot_exponent, "spot_exponent");
        }
        if (l->kind == CJ_LIGHT_AREA) {
            EQV(l->edge_u, m->edge_u, "edge_u");
            EQV(l->edge_v, m->edge_v, "edge_v");
        }
    }
    EQ(cj_scene_texture_count(a), cj_scene_texture_count(b), "texture count");
    for (int i = 0; i < (int)cj_scene_texture_count(a); ++i) {
        const cj_texture *x = cj_scene_texture(a, i), *y = cj_scene_texture(b, i);
        EQ(x->kind, y->kind, "texture kind");
        EQ(x->filter, y->filter, "filter");
        EQ(x->wrap, y->wrap, "wrap");
        EQ(x->scale_u, y->scale_u, "scale_u");
        EQ(x->scale_v, y->scale_v, "scale_v");
        EQ(x->offset_u, y->offset_u, "offset_u");
        EQ(x->offset_v, y->offset_v, "offset_v");
        if (x->kind == CJ_TEX_IMAGE) {
            assert_string_equal(x->path, y->path);
        } else {
            EQ(x->checks_u, y->checks_u, "checks_u");
            EQ(x->checks_v, y->checks_v, "checks_v");
            EQC(x->checker_a, y->checker_a, "checker_a");
            EQC(x->checker_b, y->checker_b, "checker_b");
        }
        if (cj_scene_texture_name(a, i))
            assert_string_equal(cj_scene_texture_name(a, i), cj_scene_texture_name(b, i));
    }
    EQ(cj_scene_material_count(a), cj_scene_material_count(b), "material count");
    for (int i = 0; i < (int)cj_scene_material_count(a); ++i) {
        const cj_material *x = cj_scene_material(a, i), *y = cj_scene_material(b, i);
        EQC(x->color, y->color, "color");
        EQC(x->specular, y->specular, "specular");
        EQ(x->ka, y->ka, "ka");
        EQ(x->kd, y->kd, "kd");
        EQ(x->ks, y->ks, "ks");
        EQ(x->alpha, y->alpha, "alpha");
        EQ(x->shading, y->shading, "shading");
        EQ(x->two_sided, y->two_sided, "two_sided");
        EQ(x->texture, y->texture, "texture");
        EQ(x->opacity, y->opacity, "opacity");
        EQ(x->mirror, y->mirror, "mirror");
        EQ(x->transmission, y->transmission, "transmission");
        EQ(x->ior, y->ior, "ior");
        EQ(x->glossiness, y->glossiness, "glossiness");
        EQC(x->emission, y->emission, "emission");
        EQ(x->receives_shadows, y->receives_shadows, "receives_shadows");
        if (cj_scene_material_name(a, i))
            assert_string_equal(cj_scene_material_name(a, i), cj_scene_material_name(b, i));
    }
    EQ(cj_scene_geometry_count(a), cj_scene_geometry_count(b), "geometry count");
    for (int i = 0; i < (int)cj_scene_geometry_count(a); ++i)
        eq_geometry(ctx, cj_scene_geometry(a, i), cj_scene_geometry(b, i));
    EQ(cj_scene_node_count(a), cj_scene_node_count(b), "node count");
    for (int i = 0; i < (int)cj_scene_node_count(a); ++i) {
        const cj_node *n = cj_scene_node(a, i), *m = cj_scene_node(b, i);
        if (n->name || m->name) assert_string_equal(n->name, m->name);
        EQ(n->parent, m->parent, "parent");
        EQ(n->geometry, m->geometry, "geometry");
        EQ(n->material, m->material, "material");
        EQ(n->visible, m->visible, "visible");
        EQ(n->id, m->id, "id");
        EQV(n->local.translate, m->local.translate, "translate");
        for (int k = 0; k < 4; ++k) EQ(n->local.rotation[k], m->local.rotation[k], "rotation");
        EQV(n->local.scale, m->local.scale, "scale");
        for (int r = 0; r < 4; ++r)
            for (int k = 0; k < 4; ++k)
                EQ(n->local.matrix.m[r][k], m->local.matrix.m[r][k], "matrix");
        EQ(n->overlay.flags, m->overlay.flags, "overlay flags");
        if (n->overlay.flags) EQC(n->overlay.color, m->overlay.color, "overlay color");
        if (n->overlay.flags & CJ_OVERLAY_ISO_LINES)
            EQ(n->overlay.iso_count, m->overlay.iso_count, "iso_count");
        if (n->overlay.flags & CJ_OVERLAY_NORMALS)
            EQ(n->overlay.normal_length, m->overlay.normal_length, "normal_length");
    }
}

char *sj_read_all(const char *path) {
    FILE *f = fopen(path, "rb");
    assert_non_null(f);
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fseek(f, 0, SEEK_SET);
    char *t = malloc((size_t)n + 1);
    assert_non_null(t);
    assert_int_equal(fread(t, 1, (size_t)n, f), (size_t)n);
    t[n] = '\0';
    fclose(f);
    return t;
}

/* save -> load -> equal, and save again -> the same bytes. */
static void round_trip(const char *ctx, const cj_scene *s) {
    char p1[512], p2[512];
    snprintf(p1, sizeof p1, "%s/rt1.json", sj_tmpdir);
    snprintf(p2, sizeof p2, "%s/rt2.json", sj_tmpdir);
    if (cj_scene_save_json(s, p1)) fail_msg("%s: save: %s", ctx, cj_last_error());
    cj_scene *b = NULL;
    if (cj_scene_load_json_with_options(p1, &sj_opts, NULL, &b))
        fail_msg("%s: reload: %s", ctx, cj_last_error());
    eq_scenes(ctx, s, b);
    assert_int_equal(cj_scene_save_json(b, p2), CJ_OK);
    char *t1 = sj_read_all(p1), *t2 = sj_read_all(p2);
    if (strcmp(t1, t2)) fail_msg("%s: saving the reloaded scene gives other bytes", ctx);
    free(t1);
    free(t2);
    cj_scene_destroy(b);
}

void test_round_trip_shipped(void **state) {
    (void)state;
    const char *names[] = {"teapot",      "quadrics", "revolution",
                           "transparent", "raytrace", "gallery"};
    for (int i = 0; i < 6; ++i) {
        char path[512];
        snprintf(path, sizeof path, "%s/%s.json", CJ_SCENES_DIR, names[i]);
        cj_scene *s = NULL;
        assert_int_equal(cj_scene_load_json_with_options(path, &sj_opts, NULL, &s), CJ_OK);
        round_trip(names[i], s);
        cj_scene_destroy(s);
    }
    printf("test_scene_json: the 6 shipped scenes survive save -> load -> equal, and a second "
           "save writes the same bytes\n");
}

/* A scene from code with every kind of light, texture, geometry and transform part. */
static cj_scene *everything(void) {
    cj_scene *s;
    assert_int_equal(cj_scene_create(NULL, &s), CJ_OK);
    cj_camera cam = cj_camera_defaults();
    cam.projection = CJ_PROJ_ORTHOGRAPHIC;
    cam.ortho_height = 3.25;
    cam.fov_y = 0.7123456789;
    cam.gaze = cj_v3(0.1, -0.3, -1);
    assert_int_equal(cj_scene_set_camera(s, &cam), CJ_OK);
    cj_scene_settings set = cj_scene_settings_defaults();
    set.width = 333, set.height = 222, set.spp = 16, set.tol_px = 0.1, set.seed = 123456789;
    set.background = cj_rgb_make(0.1, 1.0 / 3.0, 2.5);
    assert_int_equal(cj_scene_set_settings(s, &set), CJ_OK);
    for (int k = 0; k <= CJ_LIGHT_AREA; ++k) {
        cj_light l = cj_light_defaults((cj_light_kind)k);
        l.intensity = 0.1 * (k + 1);
        l.spot_angle = 0.3;
        l.casts_shadows = k & 1;
        assert_int_equal(cj_scene_add_light(s, &l, NULL), CJ_OK);
    }
    cj_texture ti = cj_texture_defaults(CJ_TEX_IMAGE), tc = cj_texture_defaults(CJ_TEX_CHECKER);
    ti.path = "tex/a b\"c.png";
    ti.filter = CJ_TEX_NEAREST, ti.wrap = CJ_TEX_CLAMP, ti.scale_u = 2, ti.offset_v = 0.25;
    tc.checks_u = 3, tc.checks_v = 5;
    int t0, t1;
    assert_int_equal(cj_scene_add_texture(s, &ti, &t0), CJ_OK);
    assert_int_equal(cj_scene_add_texture(s, &tc, &t1), CJ_OK);
    /* Texture 0 stays unnamed: the writer's "texture0" for it must not clash with this. */
    assert_int_equal(cj_scene_set_texture_name(s, t1, "texture0"), CJ_OK);
    cj_material m = cj_material_defaults();
    int m0, m1;
    assert_int_equal(cj_scene_add_material(s, &m, &m0), CJ_OK);
    m.texture = t1, m.opacity = 0.5, m.mirror = 0.25, m.transmission = 0.125, m.ior = 1.33;
    m.glossiness = 20, m.emission = cj_rgb_make(0, 2, 0), m.receives_shadows = 0;
    m.shading = CJ_SHADE_FLAT, m.two_sided = 1;
    assert_int_equal(cj_scene_add_material(s, &m, &m1), CJ_OK);
    assert_int_equal(cj_scene_set_material_name(s, m1, "glass \u00e9"), CJ_OK);

    int geo[16], ng = 0;
    cj_geometry g;
    memset(&g, 0, sizeof g);
    double pp[3 * 6], pw[6];
    for (int i = 0; i < 18; ++i) pp[i] = 0.1 * i * i - 1.0 / 7.0;
    for (int i = 0; i < 6; ++i) pw[i] = 1 + 0.1 * i;
    cj_patch pa[2] = {cj_patch_view(2, 1, pp, NULL), cj_patch_view(1, 2, pp, pw)};
    g.kind = CJ_GEOM_PATCHES, g.u.patches.count = 2, g.u.patches.patches = pa;
    assert_int_equal(cj_scene_add_geometry(s, &g, &geo[ng++]), CJ_OK);
    g.kind = CJ_GEOM_QUADRIC;
    assert_int_equal(cj_quadric_hyperboloid2(&g.u.quadric, 1, 2, 3, 1, 1.5), CJ_OK);
    assert_int_equal(cj_scene_add_geometry(s, &g, &geo[ng++]), CJ_OK);
    assert_int_equal(cj_quadric_hyperbolic_paraboloid(&g.u.quadric, 1, 2, -1, 1, -0.5, 2), CJ_OK);
    assert_int_equal(cj_scene_add_geometry(s, &g, &geo[ng++]), CJ_OK);
    g.kind = CJ_GEOM_SPHERE, g.u.sphere.center = cj_v3(1, 2, 3), g.u.sphere.radius = 0.7;
    assert_int_equal(cj_scene_add_geometry(s, &g, &geo[ng++]), CJ_OK);
    g.kind = CJ_GEOM_TORUS;
    assert_int_equal(cj_torus_init(&g.u.torus, cj_v3(0, 1, 0), cj_v3(1, 2, 3), 2, 0.5), CJ_OK);
    assert_int_equal(cj_scene_add_geometry(s, &g, &geo[ng++]), CJ_OK);
    g.kind = CJ_GEOM_CYLINDER;
    assert_int_equal(cj_cylinder_init(&g.u.cylinder, cj_v3(0, 0, 1), cj_v3(0.3, 1, 0), 0.4, -1, 2),
                     CJ_OK);
    assert_int_equal(cj_scene_add_geometry(s, &g, &geo[ng++]), CJ_OK);
    g.kind = CJ_GEOM_PLANAR;
    assert_int_equal(
        cj_planar_patch_init(&g.u.planar, cj_v3(0, 0, 0), cj_v3(1, 0.1, 0), cj_v3(0, 0.2, 1)),
        CJ_OK);
    assert_int_equal(cj_scene_add_geometry(s, &g, &geo[ng++]), CJ_OK);
    g.kind = CJ_GEOM_BILINEAR;
    assert_int_equal(cj_bilinear_init(&g.u.bilinear, cj_v3(0, 0, 0), cj_v3(1, 0, 0), cj_v3(0, 1, 0),
                                      cj_v3(1, 1, 1)),
                     CJ_OK);
    assert_int_equal(cj_scene_add_geometry(s, &g, &geo[ng++]), CJ_OK);
    double prof[6] = {0, 0, 1, 0.5, 0.2, 1}, pwt[3] = {1, 0.5, 1};
    memset(&g, 0, sizeof g);
    g.kind = CJ_GEOM_REVOLUTION, g.u.revolution.degree = 2, g.u.revolution.pts = prof;
    g.u.revolution.weights = pwt, g.u.revolution.axis = cj_v3(0, 1, 0);
    assert_int_equal(cj_scene_add_geometry(s, &g, &geo[ng++]), CJ_OK);
    memset(&g, 0, sizeof g);
    g.kind = CJ_GEOM_GEN_CYLINDER, g.u.gen_cylinder.degree = 2, g.u.gen_cylinder.pts = prof;
    g.u.gen_cylinder.e1 = cj_v3(1, 0, 0), g.u.gen_cylinder.e2 = cj_v3(0, 1, 0);
    g.u.gen_cylinder.dir = cj_v3(0, 0.5, 1), g.u.gen_cylinder.v0 = -1, g.u.gen_cylinder.v1 = 1;
    assert_int_equal(cj_scene_add_geometry(s, &g, &geo[ng++]), CJ_OK);
    cj_mesh *mesh;
    assert_int_equal(cj_mesh_create(NULL, &mesh), CJ_OK);
    for (int i = 0; i < 4; ++i) {
        double p[3] = {i & 1, i >> 1, 0.1 * i}, n[3] = {0, 0, 1}, uv[2] = {i & 1, 0.5 * (i >> 1)};
        assert_int_equal(cj_mesh_add_vertex(mesh, p, n, uv, NULL), CJ_OK);
    }
    assert_int_equal(cj_mesh_add_triangle(mesh, 0, 1, 3, 4), CJ_OK);
    assert_int_equal(cj_mesh_add_triangle(mesh, 0, 3, 2, -2), CJ_OK);
    g.kind = CJ_GEOM_MESH, g.u.mesh = mesh;
    assert_int_equal(cj_scene_add_geometry(s, &g, &geo[ng++]), CJ_OK);
    cj_mesh_destroy(mesh);
    double cp[12] = {0, 0, 0, 1, 2, 0, 2, -1, 1, 3, 0, 0}, cw[4] = {1, 2, 0.5, 1};
    for (int k = 0; k < 3; ++k) {
        memset(&g, 0, sizeof g);
        g.kind = CJ_GEOM_CURVE;
        g.u.curve.kind = (cj_curve_kind)k;
        g.u.curve.degree = 3, g.u.curve.count = 4, g.u.curve.pts = cp;
        g.u.curve.weights = k == 1 ? cw : NULL;
        g.u.curve.spline = CJ_SPLINE_KOCHANEK_BARTELS, g.u.curve.tension = 0.1;
        g.u.curve.continuity = -0.2, g.u.curve.bias = 0.3, g.u.curve.closed = k == 2;
        g.u.curve.width_px = 2.5, g.u.curve.color = cj_rgb_make(1, 0.5, 0);
        assert_int_equal(cj_scene_add_geometry(s, &g, &geo[ng++]), CJ_OK);
    }
    /* Nodes in pre-order: a group with a sub-group, objects with every transform part. */
    cj_node n;
    memset(&n, 0, sizeof n);
    n.parent = -1, n.geometry = -1, n.material = -1, n.visible = 1, n.name = "root group";
    n.local = cj_transform_identity();
    n.local.translate = cj_v3(1, 2, 3);
    n.local.rotation[0] = 0.5, n.local.rotation[1] = 0.5, n.local.rotation[2] = 0.5;
    n.local.rotation[3] = 0.5;
    int root, sub;
    assert_int_equal(cj_scene_add_node(s, &n, &root), CJ_OK);
    n.parent = root, n.name = NULL, n.local = cj_transform_identity();
    n.local.scale = cj_v3(2, -1, 0.5);
    n.local.matrix = cj_xform3_shear(0.1, 0, 0, 0.2, 0, 0);
    assert_int_equal(cj_scene_add_node(s, &n, &sub), CJ_OK);
    for (int i = 0; i < ng; ++i) {
        n.parent = i < ng / 2 ? sub : i < 3 * ng / 4 ? root : -1; /* pre-order */
        n.geometry = geo[i], n.material = i % 2 ? m1 : m0;
        n.local = cj_transform_identity();
        n.local.translate = cj_v3(i, -i, 0.5 * i);
        n.visible = i != 3;
        n.overlay.flags = (unsigned)(i % 16);
        n.overlay.color = cj_rgb_make(0.1 * i, 0, 1);
        n.overlay.iso_count = i + 1;
        n.overlay.normal_length = 0.05 * (i + 1);
        char name[16];
        snprintf(name, sizeof name, "obj %d", i);
        n.name = name;
        assert_int_equal(cj_scene_add_node(s, &n, NULL), CJ_OK);
    }
    return s;
}

void test_round_trip_everything(void **state) {
    (void)state;
    cj_scene *s = everything();
    round_trip("every part", s);
    /* A failed save keeps the old file: an invalid scene is refused before anything is written,
     * a missing folder fails to create the temporary file. */
    char p1[512];
    snprintf(p1, sizeof p1, "%s/rt1.json", sj_tmpdir);
    char *before = sj_read_all(p1);
    cj_scene_material_mut(s, 1)->alpha = -1;
    assert_int_equal(cj_scene_save_json(s, p1), CJ_ERR_RANGE);
    assert_string_equal(cj_last_error(), "materials[1].alpha must be >= 0");
    char *after = sj_read_all(p1);
    assert_string_equal(before, after);
    free(before);
    free(after);
    cj_scene_material_mut(s, 1)->alpha = 5;
    assert_int_equal(cj_scene_set_material_name(s, 0, "glass \u00e9"), CJ_OK);
    assert_int_equal(cj_scene_save_json(s, p1), CJ_ERR_ARGUMENT);
    assert_string_equal(cj_last_error(),
                        "materials[1].name \"glass \u00e9\" is already materials[0]");
    assert_int_equal(cj_scene_set_material_name(s, 0, NULL), CJ_OK);
    char p2[600];
    snprintf(p2, sizeof p2, "%s/no/such/folder/x.json", sj_tmpdir);
    assert_int_equal(cj_scene_save_json(s, p2), CJ_ERR_IO);
    assert_non_null(strstr(cj_last_error(), "No such file or directory"));
    printf("test_scene_json: a scene with every light, texture, geometry kind (%zu), transform "
           "part and overlay survives save -> load -> equal\n",
           cj_scene_geometry_count(s));
    cj_scene_destroy(s);
}

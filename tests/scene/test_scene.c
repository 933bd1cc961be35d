/* The scene model: builder API and defaults, deep copies, world transforms of a hierarchy
 * against hand-computed matrices, quaternion rotations against cj_xform3_rotate_axis, the
 * messages of cj_scene_check and of refused adds, allocator use (every block released, a
 * failing allocator adds nothing). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "casteljau/scene.h"
#include "rng.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const double PI = 3.14159265358979323846;

/* ---- allocators ----------------------------------------------------------------------------- */

typedef struct counter {
    long live, total;
    long fail_at; /* the fail_at-th allocation fails (0 = never) */
} counter;

static void *c_alloc(void *user, size_t n) {
    counter *c = user;
    if (c->fail_at && ++c->total == c->fail_at) return NULL;
    if (!c->fail_at) c->total++;
    void *p = malloc(n);
    if (p) c->live++;
    return p;
}

static void c_free(void *user, void *p) {
    counter *c = user;
    if (p) c->live--;
    free(p);
}

static cj_node object_node(int parent, int geometry, int material) {
    cj_node n;
    memset(&n, 0, sizeof n);
    n.parent = parent;
    n.geometry = geometry;
    n.material = material;
    n.visible = 1;
    n.local = cj_transform_identity();
    return n;
}

static int add_sphere(cj_scene *s, double r) {
    cj_geometry g;
    memset(&g, 0, sizeof g);
    g.kind = CJ_GEOM_SPHERE;
    g.u.sphere.radius = r;
    int i = -1;
    assert_int_equal(cj_scene_add_geometry(s, &g, &i), CJ_OK);
    return i;
}

/* ---- builder and deep copies ---------------------------------------------------------------- */

static void test_builder_and_copies(void **state) {
    (void)state;
    cj_scene *s;
    assert_int_equal(cj_scene_create(NULL, &s), CJ_OK);
    assert_int_equal(cj_scene_node_count(s), 0);
    assert_int_equal(cj_scene_check(s), CJ_OK); /* an empty scene is valid */
    const cj_scene_settings *set = cj_scene_get_settings(s);
    assert_int_equal(set->width, 640);
    assert_int_equal(set->height, 480);
    assert_true(set->tol_px == 0.25);
    cj_material md = cj_material_defaults();
    assert_true(md.alpha == 32 && md.texture == -1 && md.opacity == 1 && md.ior == 1.5);

    /* Patches: the points and weights are copied; changing the caller's arrays later does
     * not reach the scene. */
    double pts[3 * 4] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 1}, w[4] = {1, 2, 3, 4};
    cj_patch p[2] = {cj_patch_view(1, 1, pts, NULL), cj_patch_view(1, 1, pts, w)};
    cj_geometry g;
    memset(&g, 0, sizeof g);
    g.kind = CJ_GEOM_PATCHES;
    g.u.patches.count = 2;
    g.u.patches.patches = p;
    int gi;
    assert_int_equal(cj_scene_add_geometry(s, &g, &gi), CJ_OK);
    pts[11] = 99;
    w[3] = 99;
    p[0].deg_u = 7;
    const cj_geometry *c = cj_scene_geometry(s, gi);
    assert_ptr_not_equal(c->u.patches.patches, p);
    assert_ptr_not_equal(c->u.patches.patches[1].pts, pts);
    assert_true(c->u.patches.patches[0].deg_u == 1 && c->u.patches.patches[1].pts[11] == 1);
    assert_null(c->u.patches.patches[0].weights);
    assert_true(c->u.patches.patches[1].weights[3] == 4);

    /* A mesh is copied into a mesh of the scene's own. */
    cj_mesh *m;
    assert_int_equal(cj_mesh_create(NULL, &m), CJ_OK);
    for (int i = 0; i < 3; ++i) {
        double q[3] = {i == 1, i == 2, 0};
        assert_int_equal(cj_mesh_add_vertex(m, q, NULL, NULL, NULL), CJ_OK);
    }
    assert_int_equal(cj_mesh_add_triangle(m, 0, 1, 2, 5), CJ_OK);
    memset(&g, 0, sizeof g);
    g.kind = CJ_GEOM_MESH;
    g.u.mesh = m;
    assert_int_equal(cj_scene_add_geometry(s, &g, &gi), CJ_OK);
    cj_mesh_destroy(m); /* the scene's copy outlives the original */
    const cj_mesh *sm = cj_scene_geometry(s, gi)->u.mesh;
    assert_int_equal(sm->triangle_count, 1);
    assert_true(sm->positions[3] == 1 && sm->triangle_patch[0] == 5);

    /* Curves, profiles, names and texture paths are copied too. */
    double cp[6] = {0, 0, 0, 1, 1, 1};
    memset(&g, 0, sizeof g);
    g.kind = CJ_GEOM_CURVE;
    g.u.curve.kind = CJ_CURVE_BEZIER;
    g.u.curve.degree = 1;
    g.u.curve.count = 2;
    g.u.curve.pts = cp;
    g.u.curve.width_px = 1;
    assert_int_equal(cj_scene_add_geometry(s, &g, &gi), CJ_OK);
    cp[5] = -1;
    assert_true(cj_scene_geometry(s, gi)->u.curve.pts[5] == 1);
    char path[] = "textures/a.png";
    cj_texture t = cj_texture_defaults(CJ_TEX_IMAGE);
    t.path = path;
    int ti;
    assert_int_equal(cj_scene_add_texture(s, &t, &ti), CJ_OK);
    path[0] = 'X';
    assert_string_equal(cj_scene_texture(s, ti)->path, "textures/a.png");
    assert_null(cj_scene_texture(s, ti)->texels);
    float px[2 * 1 * 4] = {0.1f, 0.2f, 0.3f, 1, 0.5f, 0.5f, 0.5f, 1};
    assert_int_equal(cj_scene_set_texture_pixels(s, ti, 2, 1, px), CJ_OK);
    px[0] = 9;
    assert_true(cj_scene_texture(s, ti)->texels[0] == 0.1f && cj_scene_texture(s, ti)->width == 2);
    px[1] = NAN;
    assert_int_equal(cj_scene_set_texture_pixels(s, ti, 2, 1, px), CJ_ERR_NONFINITE);
    assert_string_equal(cj_last_error(), "textures[0]: texel 0, channel 1 is not finite");
    assert_true(cj_scene_texture(s, ti)->texels[1] == 0.2f); /* unchanged on failure */
    cj_texture tn = cj_texture_defaults(CJ_TEX_IMAGE);
    tn.path = "b.png";
    tn.width = 2;
    tn.height = 1;
    tn.texels = px; /* texels given with the texture are checked the same way */
    assert_int_equal(cj_scene_add_texture(s, &tn, NULL), CJ_ERR_NONFINITE);
    assert_string_equal(cj_last_error(), "textures[1]: texel 0, channel 1 is not finite");
    assert_int_equal(cj_scene_texture_count(s), 1);
    px[1] = 0.25f;
    assert_int_equal(cj_scene_add_texture(s, &tn, NULL), CJ_OK);
    assert_true(cj_scene_texture(s, 1)->texels[1] == 0.25f && cj_scene_texture(s, 1)->width == 2);

    /* Nodes: names copied, ids 1 + index among objects (groups get 0). */
    int mat;
    assert_int_equal(cj_scene_add_material(s, &md, &mat), CJ_OK);
    char name[] = "group";
    cj_node n = object_node(-1, -1, -1);
    n.name = name;
    int grp, a, b;
    assert_int_equal(cj_scene_add_node(s, &n, &grp), CJ_OK);
    name[0] = 'X';
    assert_string_equal(cj_scene_node(s, grp)->name, "group");
    n = object_node(grp, gi, mat);
    n.id = 77; /* ignored */
    assert_int_equal(cj_scene_add_node(s, &n, &a), CJ_OK);
    assert_int_equal(cj_scene_add_node(s, &n, &b), CJ_OK);
    assert_int_equal(cj_scene_node(s, grp)->id, 0);
    assert_int_equal(cj_scene_node(s, a)->id, 1);
    assert_int_equal(cj_scene_node(s, b)->id, 2);
    assert_null(cj_scene_node(s, 3));
    assert_null(cj_scene_node(s, -1));
    assert_int_equal(cj_scene_check(s), CJ_OK);
    cj_scene_destroy(s);
    printf("test_scene: builder API, defaults, deep copies of patches, meshes, curves, paths, "
           "texels and names, node ids\n");
}

/* ---- transforms ----------------------------------------------------------------------------- */

static void check_matrix(const cj_xform3 *got, const double want[4][4], double tol,
                         const char *what) {
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j)
            if (!(fabs(got->m[i][j] - want[i][j]) <= tol))
                fail_msg("%s: m[%d][%d] = %.17g, expected %.17g", what, i, j, got->m[i][j],
                         want[i][j]);
}

static void test_hierarchy(void **state) {
    (void)state;
    cj_scene *s;
    assert_int_equal(cj_scene_create(NULL, &s), CJ_OK);
    cj_material md = cj_material_defaults();
    int mat, geo = add_sphere(s, 1);
    assert_int_equal(cj_scene_add_material(s, &md, &mat), CJ_OK);
    /* Group A: translate (1, 2, 3), quarter turn about z (q = (cos 45°, 0, 0, sin 45°)).
     * Group B under A: scale (2, 3, 4). Object under B: translate (0, 0, 1) with a shear
     * matrix x' = x + 0.5 y. */
    cj_node n = object_node(-1, -1, -1);
    n.local.translate = cj_v3(1, 2, 3);
    n.local.rotation[0] = cos(PI / 4);
    n.local.rotation[3] = sin(PI / 4);
    int ga, gb, ob;
    assert_int_equal(cj_scene_add_node(s, &n, &ga), CJ_OK);
    n = object_node(ga, -1, -1);
    n.local.scale = cj_v3(2, 3, 4);
    assert_int_equal(cj_scene_add_node(s, &n, &gb), CJ_OK);
    n = object_node(gb, geo, mat);
    n.local.translate = cj_v3(0, 0, 1);
    n.local.matrix = cj_xform3_shear(0.5, 0, 0, 0, 0, 0);
    assert_int_equal(cj_scene_add_node(s, &n, &ob), CJ_OK);

    cj_xform3 w;
    assert_int_equal(cj_scene_node_world(s, ga, &w), CJ_OK);
    const double A[4][4] = {{0, -1, 0, 1}, {1, 0, 0, 2}, {0, 0, 1, 3}, {0, 0, 0, 1}};
    check_matrix(&w, A, 1e-15, "group A");
    assert_int_equal(cj_scene_node_world(s, gb, &w), CJ_OK);
    const double AB[4][4] = {{0, -3, 0, 1}, {2, 0, 0, 2}, {0, 0, 4, 3}, {0, 0, 0, 1}};
    check_matrix(&w, AB, 1e-15, "group B");
    /* Object local: T(0,0,1)·shear = [[1, .5, 0, 0], [0, 1, 0, 0], [0, 0, 1, 1]]; world = AB·L:
     * row 0: (0, -3, 0, 1)·L = (0, -3, 0, 1); row 1: (2, 0, 0, 2)·L = (2, 1, 0, 2);
     * row 2: (0, 0, 4, 3)·L = (0, 0, 4, 4 + 3). */
    assert_int_equal(cj_scene_node_world(s, ob, &w), CJ_OK);
    const double ABO[4][4] = {{0, -3, 0, 1}, {2, 1, 0, 2}, {0, 0, 4, 7}, {0, 0, 0, 1}};
    check_matrix(&w, ABO, 1e-15, "object");
    assert_int_equal(cj_scene_node_world(s, 3, &w), CJ_ERR_ARGUMENT);
    assert_string_equal(cj_last_error(), "node index 3 names no node (3 nodes)");
    cj_scene_destroy(s);
    printf("test_scene: world transforms of a 3-level hierarchy equal hand-computed matrices\n");
}

static void test_quaternions(void **state) {
    (void)state;
    cj_rng r;
    cj_rng_init(&r, cj_test_seed("test_scene quaternions", 8));
    double worst = 0;
    for (int k = 0; k < 2000; ++k) {
        cj_vec3 axis =
            cj_v3(cj_rng_range(&r, -1, 1), cj_rng_range(&r, -1, 1), cj_rng_range(&r, -1, 1));
        if (cj_v3_norm(axis) < 1e-3) continue;
        double ang = cj_rng_range(&r, -2 * PI, 2 * PI);
        cj_vec3 a = cj_v3_normalize(axis);
        cj_transform t = cj_transform_identity();
        t.rotation[0] = cos(ang / 2);
        t.rotation[1] = a.x * sin(ang / 2);
        t.rotation[2] = a.y * sin(ang / 2);
        t.rotation[3] = a.z * sin(ang / 2);
        t.translate = cj_v3(cj_rng_range(&r, -5, 5), 0, 1);
        t.scale = cj_v3(cj_rng_range(&r, 0.5, 2), -1, 3);
        cj_xform3 m = cj_transform_matrix(&t), rot, want;
        assert_int_equal(cj_xform3_rotate_axis(axis, ang, &rot), CJ_OK);
        cj_xform3 tr = cj_xform3_translate(t.translate.x, t.translate.y, t.translate.z);
        cj_xform3 sc = cj_xform3_scale(t.scale.x, t.scale.y, t.scale.z);
        want = cj_xform3_compose(&rot, &sc);
        want = cj_xform3_compose(&tr, &want);
        for (int i = 0; i < 4; ++i)
            for (int j = 0; j < 4; ++j) worst = fmax(worst, fabs(m.m[i][j] - want.m[i][j]));
    }
    if (!(worst < 2e-14)) fail_msg("quaternion matrix differs from Rodrigues by %g", worst);
    printf("test_scene: T·R(q)·S of 2000 random axis/angle quaternions equals T·R·S built with "
           "cj_xform3_rotate_axis within %.2g\n",
           worst);
}

/* ---- validation ----------------------------------------------------------------------------- */

static void test_check_messages(void **state) {
    (void)state;
    cj_scene *s;
    assert_int_equal(cj_scene_create(NULL, &s), CJ_OK);
    cj_material md = cj_material_defaults();
    int mat, geo = add_sphere(s, 1), li, grp, ob;
    for (int i = 0; i < 3; ++i) assert_int_equal(cj_scene_add_material(s, &md, &mat), CJ_OK);
    cj_light l = cj_light_defaults(CJ_LIGHT_POINT);
    assert_int_equal(cj_scene_add_light(s, &l, &li), CJ_OK);
    cj_node n = object_node(-1, -1, -1);
    assert_int_equal(cj_scene_add_node(s, &n, &grp), CJ_OK);
    n = object_node(grp, geo, mat);
    assert_int_equal(cj_scene_add_node(s, &n, &ob), CJ_OK);
    assert_int_equal(cj_scene_check(s), CJ_OK);

    /* Each mutation breaks one field; check names it; undoing it makes the scene valid. */
    cj_material *m2 = cj_scene_material_mut(s, 2);
    m2->alpha = -1;
    assert_int_equal(cj_scene_check(s), CJ_ERR_RANGE);
    assert_string_equal(cj_last_error(), "materials[2].alpha must be >= 0");
    m2->alpha = 32;
    m2->opacity = NAN;
    assert_int_equal(cj_scene_check(s), CJ_ERR_NONFINITE);
    assert_string_equal(cj_last_error(), "materials[2].opacity is not finite");
    m2->opacity = 1;
    m2->texture = 4;
    assert_int_equal(cj_scene_check(s), CJ_ERR_ARGUMENT);
    assert_string_equal(cj_last_error(), "materials[2].texture 4 names no texture (0 textures)");
    m2->texture = -1;
    m2->color.g = 1.5;
    assert_int_equal(cj_scene_check(s), CJ_ERR_RANGE);
    assert_string_equal(cj_last_error(), "materials[2].color[1] must be in [0, 1]");
    m2->color.g = 0.5;
    cj_light *lm = cj_scene_light_mut(s, li);
    lm->intensity = -2;
    assert_int_equal(cj_scene_check(s), CJ_ERR_RANGE);
    assert_string_equal(cj_last_error(), "lights[0].intensity must be >= 0");
    lm->intensity = 1;
    cj_node *nm = cj_scene_node_mut(s, ob);
    nm->parent = 7;
    assert_int_equal(cj_scene_check(s), CJ_ERR_ARGUMENT);
    assert_string_equal(cj_last_error(), "nodes[1].parent 7 names no group added before it");
    nm->parent = grp;
    nm->local.rotation[0] = 2;
    assert_int_equal(cj_scene_check(s), CJ_ERR_RANGE);
    assert_string_equal(cj_last_error(),
                        "nodes[1].transform.quaternion must have unit length (|q|^2 = 4)");
    nm->local.rotation[0] = 1;
    nm->local.scale.y = 0;
    assert_int_equal(cj_scene_check(s), CJ_ERR_RANGE);
    assert_string_equal(cj_last_error(), "nodes[1].transform.scale must have non-zero components");
    nm->local.scale.y = 1;
    cj_geometry *gm = cj_scene_geometry_mut(s, geo);
    gm->u.sphere.radius = 0;
    assert_int_equal(cj_scene_check(s), CJ_ERR_RANGE);
    assert_string_equal(cj_last_error(), "geometries[0].radius must be > 0");
    gm->u.sphere.radius = 1;
    cj_camera cam = cj_camera_defaults();
    cam.near = 0.5;
    assert_int_equal(cj_scene_set_camera(s, &cam), CJ_ERR_RANGE);
    assert_string_equal(cj_last_error(), "camera.near must be < 0");
    cam = cj_camera_defaults();
    cam.up = cam.gaze;
    assert_int_equal(cj_scene_set_camera(s, &cam), CJ_ERR_DEGENERATE);
    assert_string_equal(cj_last_error(), "camera.up must not be parallel to the gaze");
    cj_scene_settings set = cj_scene_settings_defaults();
    set.tol_px = 0;
    assert_int_equal(cj_scene_set_settings(s, &set), CJ_ERR_RANGE);
    assert_string_equal(cj_last_error(), "settings.tol_px must be > 0");
    assert_int_equal(cj_scene_check(s), CJ_OK);

    /* Refused adds name the part they would have become and add nothing. */
    size_t before = cj_scene_node_count(s);
    n = object_node(ob, geo, mat); /* parent is an object, not a group */
    assert_int_equal(cj_scene_add_node(s, &n, NULL), CJ_ERR_ARGUMENT);
    assert_string_equal(cj_last_error(), "nodes[2].parent 1 names no group added before it");
    n = object_node(grp, geo, 9);
    assert_int_equal(cj_scene_add_node(s, &n, NULL), CJ_ERR_ARGUMENT);
    assert_string_equal(cj_last_error(), "nodes[2].material 9 names no material (3 materials)");
    n = object_node(grp, 5, mat);
    assert_int_equal(cj_scene_add_node(s, &n, NULL), CJ_ERR_ARGUMENT);
    assert_string_equal(cj_last_error(), "nodes[2].geometry 5 names no geometry (1 geometries)");
    assert_int_equal(cj_scene_node_count(s), before);
    l.kind = CJ_LIGHT_SPOT;
    l.spot_angle = 2;
    assert_int_equal(cj_scene_add_light(s, &l, NULL), CJ_ERR_RANGE);
    assert_string_equal(cj_last_error(), "lights[1].spot_angle must be in (0, pi/2]");
    assert_int_equal(cj_scene_light_count(s), 1);
    cj_geometry g;
    memset(&g, 0, sizeof g);
    g.kind = CJ_GEOM_TORUS;
    assert_int_equal(cj_scene_add_geometry(s, &g, NULL), CJ_ERR_DEGENERATE);
    assert_non_null(strstr(cj_last_error(), "geometries[1]: "));
    double bad[6] = {0, 0, 0, 1, NAN, 0};
    g.kind = CJ_GEOM_CURVE;
    g.u.curve.kind = CJ_CURVE_BEZIER;
    g.u.curve.degree = 1;
    g.u.curve.count = 2;
    g.u.curve.pts = bad;
    g.u.curve.width_px = 1;
    assert_int_equal(cj_scene_add_geometry(s, &g, NULL), CJ_ERR_NONFINITE);
    assert_string_equal(cj_last_error(), "geometries[1].points[1][1] is not finite");
    assert_int_equal(cj_scene_geometry_count(s), 1);
    cj_texture t = cj_texture_defaults(CJ_TEX_IMAGE);
    assert_int_equal(cj_scene_add_texture(s, &t, NULL), CJ_ERR_ARGUMENT);
    assert_string_equal(cj_last_error(),
                        "textures[0].path is missing (an image texture needs a file)");
    cj_scene_destroy(s);
    printf("test_scene: cj_scene_check and the add functions name the field (14 cases); refused "
           "adds add nothing\n");
}

/* ---- allocators ----------------------------------------------------------------------------- */

/* Builds a scene with one of everything that allocates; returns the add status. */
static cj_status build(cj_scene *s) {
    cj_status st;
    cj_material md = cj_material_defaults();
    cj_light l = cj_light_defaults(CJ_LIGHT_POINT);
    cj_texture t = cj_texture_defaults(CJ_TEX_IMAGE);
    t.path = "a.png";
    double pts[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 1}, w[4] = {1, 1, 1, 1};
    cj_patch p = cj_patch_view(1, 1, pts, w);
    cj_geometry g;
    memset(&g, 0, sizeof g);
    g.kind = CJ_GEOM_PATCHES;
    g.u.patches.count = 1;
    g.u.patches.patches = &p;
    float px[4] = {1, 1, 1, 1};
    int idx;
    if ((st = cj_scene_add_material(s, &md, &idx))) return st;
    if ((st = cj_scene_set_material_name(s, idx, "m"))) return st;
    if ((st = cj_scene_add_light(s, &l, NULL))) return st;
    if ((st = cj_scene_add_texture(s, &t, &idx))) return st;
    if ((st = cj_scene_set_texture_pixels(s, idx, 1, 1, px))) return st;
    if ((st = cj_scene_set_texture_source(s, idx, "x.json:3: textures[0]"))) return st;
    if ((st = cj_scene_add_geometry(s, &g, NULL))) return st;
    for (int i = 0; i < 20; ++i) {
        cj_node n = object_node(-1, 0, 0);
        n.name = "node";
        if ((st = cj_scene_add_node(s, &n, NULL))) return st;
    }
    return CJ_OK;
}

static void test_allocator(void **state) {
    (void)state;
    counter c = {0, 0, 0};
    cj_allocator a = {c_alloc, c_free, &c};
    cj_scene *s;
    assert_int_equal(cj_scene_create(&a, &s), CJ_OK);
    assert_int_equal(build(s), CJ_OK);
    assert_true(c.live > 5);
    long total = c.total;
    cj_scene_destroy(s);
    assert_int_equal(c.live, 0);
    /* Fail each allocation in turn: every failure is CJ_ERR_NOMEM, and destroy then releases
     * every block (nothing half-added leaks). */
    int nomem = 0;
    for (long k = 1; k <= total; ++k) {
        counter f = {0, 0, k};
        cj_allocator fa = {c_alloc, c_free, &f};
        cj_scene *fs = NULL;
        cj_status st = cj_scene_create(&fa, &fs);
        if (st == CJ_OK) {
            st = build(fs);
            cj_scene_destroy(fs);
        }
        if (st != CJ_ERR_NOMEM) fail_msg("allocation %ld failing gave %s", k, cj_status_str(st));
        if (f.live != 0) fail_msg("allocation %ld failing leaked %ld blocks", k, f.live);
        nomem++;
    }
    printf("test_scene: the scene allocates only through its allocator (%ld blocks, all "
           "released); each of the %d allocations failing gives CJ_ERR_NOMEM without a leak\n",
           total, nomem);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_builder_and_copies), cmocka_unit_test(test_hierarchy),
        cmocka_unit_test(test_quaternions),        cmocka_unit_test(test_check_messages),
        cmocka_unit_test(test_allocator),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

#define _POSIX_C_SOURCE 200809L
/* The JSON scene format: every shipped scene loads; a table of bad documents each gives the
 * exact "file:line: path message"; no scene is returned on error; save -> load gives an equal
 * scene (and saving again gives the same bytes). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "casteljau/mesh.h"
#include "casteljau/scene_json.h"
#include "rng.h"
#include "scene_json_test.h"

#include <dirent.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

const cj_scene_json_options sj_opts = {CJ_TEAPOT_PATH};

char sj_tmpdir[256];

static int setup(void **state) {
    (void)state;
    /* tmpfs when there is one: the writers fsync every file, which a busy disk makes slow. */
    snprintf(sj_tmpdir, sizeof sj_tmpdir, "/dev/shm/cj_test_scene_json_XXXXXX");
    if (mkdtemp(sj_tmpdir)) return 0;
    snprintf(sj_tmpdir, sizeof sj_tmpdir, "/tmp/cj_test_scene_json_XXXXXX");
    return mkdtemp(sj_tmpdir) ? 0 : -1;
}

static int teardown(void **state) {
    (void)state;
    DIR *d = opendir(sj_tmpdir);
    if (!d) return 0;
    struct dirent *e;
    int stray = 0;
    while ((e = readdir(d))) {
        if (e->d_name[0] == '.' && (!e->d_name[1] || !strcmp(e->d_name, ".."))) continue;
        if (strstr(e->d_name, ".tmp-")) stray++;
        char p[512];
        snprintf(p, sizeof p, "%s/%s", sj_tmpdir, e->d_name);
        unlink(p);
    }
    closedir(d);
    rmdir(sj_tmpdir);
    if (stray) printf("test_scene_json: %d temporary files were left behind\n", stray);
    return stray ? -1 : 0;
}

static void write_file(const char *path, const char *text) {
    FILE *f = fopen(path, "wb");
    assert_non_null(f);
    fputs(text, f);
    assert_int_equal(fclose(f), 0);
}

/* ---- shipped scenes ------------------------------------------------------------------------- */

static void test_shipped_scenes(void **state) {
    (void)state;
    DIR *d = opendir(CJ_SCENES_DIR);
    assert_non_null(d);
    struct dirent *e;
    int n = 0;
    while ((e = readdir(d))) {
        size_t l = strlen(e->d_name);
        if (l < 6 || strcmp(e->d_name + l - 5, ".json")) continue;
        char path[512];
        snprintf(path, sizeof path, "%s/%s", CJ_SCENES_DIR, e->d_name);
        cj_scene *s = NULL;
        cj_status st = cj_scene_load_json_ex(path, &sj_opts, NULL, &s);
        /* Animation documents (casteljau/anim_scene.h) name their scene with a top-level
         * "scene" key and live here too; they are not scene documents. */
        const char *msg = cj_last_error(), *at = msg + strlen(path) + 1;
        int anim_doc = st && !strncmp(msg, path, strlen(path)) && msg[strlen(path)] == ':';
        if (anim_doc) {
            while (*at >= '0' && *at <= '9') at++;
            anim_doc = !strncmp(at, ": scene is not a known key", 26);
        }
        if (anim_doc) {
            printf("  %-20s an animation document (top-level \"scene\"), skipped\n", e->d_name);
            continue;
        }
        if (st) fail_msg("%s: %s", e->d_name, cj_last_error());
        assert_int_equal(cj_scene_check(s), CJ_OK);
        printf("  %-20s %zu lights, %zu textures, %zu materials, %zu geometries, %zu nodes\n",
               e->d_name, cj_scene_light_count(s), cj_scene_texture_count(s),
               cj_scene_material_count(s), cj_scene_geometry_count(s), cj_scene_node_count(s));
        cj_scene_destroy(s);
        n++;
    }
    closedir(d);
    assert_true(n >= 6);
    printf("test_scene_json: %d shipped scenes load and check\n", n);
}

/* ---- bad documents -------------------------------------------------------------------------- */

typedef struct bad_case {
    const char *doc;
    cj_status status;
    const char *message; /* "%s" (if any) stands for the test's temporary folder */
} bad_case;

#define OBJ1   "{\"objects\": [{\"geometry\": {\"type\": \"sphere\", \"radius\": 1}}],\n"
#define SPHERE "\"geometry\": {\"type\": \"sphere\", \"radius\": 1}"

static const bad_case BAD[] = {
    /* syntax */
    {"{\n  \"objects\": [\n    {\"name\": \"a\",}\n  ]\n}\n", CJ_ERR_PARSE,
     "scene.json:3:19: JSON syntax error (line 3, column 19)"},
    {"{\"objects\": []}\n\n]", CJ_ERR_PARSE,
     "scene.json:3:1: JSON syntax error (line 3, column 1)"},
    /* lines survive strings with brackets, quotes and escapes, empty containers and a BOM */
    {"{\"objects\": [{\"name\": \"a}\\\"],:{[\", \"geometry\": {\"type\": \"sphere\",\n"
     " \"radius\": -1}}]}",
     CJ_ERR_RANGE, "scene.json:2: objects[0].geometry.radius must be > 0"},
    {"{\"settings\": {}, \"lights\": [],\n\"textures\": [ ], \"materials\": [{\"name\": "
     "\"x\\n\\u00e9\"}],\n\"objects\": [{\"children\": [\n{\"name\": \"[\", \"geometry\": "
     "\"nope\"}]}]}",
     CJ_ERR_PARSE,
     "scene.json:4: objects[0].children[0].geometry \"nope\" names no entry of geometries"},
    {"\xEF\xBB\xBF{\"objects\": [],\n\"x\": 1}", CJ_ERR_PARSE,
     "scene.json:2: x is not a known key (expected one of: camera, settings, lights, textures, "
     "materials, geometries, objects)"},
    /* document */
    {"{}", CJ_ERR_PARSE, "scene.json:1: document: missing key \"objects\""},
    {"[]", CJ_ERR_PARSE, "scene.json:1: document must be an object, not an array"},
    {"{\"objects\": [],\n \"camra\": {}}", CJ_ERR_PARSE,
     "scene.json:2: camra is not a known key (expected one of: camera, settings, lights, "
     "textures, materials, geometries, objects)"},
    {"{\"objects\": {}}", CJ_ERR_PARSE, "scene.json:1: objects must be an array"},
    /* camera */
    {OBJ1 "\"camera\": {\"eye\": [0, 0]}}", CJ_ERR_PARSE,
     "scene.json:2: camera.eye must be an array of 3 numbers"},
    {OBJ1 "\"camera\": {\n\"near\": 0.1}}", CJ_ERR_RANGE, "scene.json:3: camera.near must be < 0"},
    {OBJ1 "\"camera\": {\"near\": -1,\n\n \"far\": -0.5}}", CJ_ERR_RANGE,
     "scene.json:4: camera.far must be < -1"},
    {OBJ1 "\"camera\": {\"gaze\": [0, 0, -1],\n \"look_at\": [0, 0, 0]}}", CJ_ERR_PARSE,
     "scene.json:3: camera: give either \"gaze\" or \"look_at\", not both"},
    {OBJ1 "\"camera\": {\"fov_deg\": 180}}", CJ_ERR_RANGE,
     "scene.json:2: camera.fov_deg must be in (0, 180)"},
    {OBJ1 "\"camera\": {\n\"gaze\": [0, 1, 0], \"up\": [0, 2, 0]}}", CJ_ERR_DEGENERATE,
     "scene.json:2: camera.up must not be parallel to the gaze"},
    {OBJ1 "\"camera\": {\"projection\": \"fisheye\"}}", CJ_ERR_PARSE,
     "scene.json:2: camera.projection \"fisheye\" is not one of perspective, orthographic"},
    /* settings */
    {OBJ1 "\"settings\": {\"width\": 0}}", CJ_ERR_RANGE,
     "scene.json:2: settings.width must be in [1, 32768]"},
    {OBJ1 "\"settings\": {\"spp\": 2.5}}", CJ_ERR_PARSE,
     "scene.json:2: settings.spp must be an integer"},
    {OBJ1 "\"settings\": {\"background\": [0, -1, 0]}}", CJ_ERR_RANGE,
     "scene.json:2: settings.background[1] must be >= 0"},
    /* lights */
    {OBJ1 "\"lights\": [{\"intensity\": 1}]}", CJ_ERR_PARSE,
     "scene.json:2: lights[0]: missing key \"type\""},
    {OBJ1 "\"lights\": [\n{\"type\": \"laser\"}]}", CJ_ERR_PARSE,
     "scene.json:3: lights[0].type \"laser\" is not one of ambient, point, directional, spot, "
     "area, disc, sphere"},
    {OBJ1
     "\"lights\": [{\"type\": \"point\"},\n {\"type\": \"ambient\",\n \"position\": [0, 0, 0]}]}",
     CJ_ERR_PARSE,
     "scene.json:4: lights[1].position is not a known key (expected one of: type, color, "
     "intensity, casts_shadows)"},
    {OBJ1 "\"lights\": [{\"type\": \"point\", \"intensity\": -1}]}", CJ_ERR_RANGE,
     "scene.json:2: lights[0].intensity must be >= 0"},
    {OBJ1 "\"lights\": [{\"type\": \"point\", \"color\": [1,\n \"x\", 1]}]}", CJ_ERR_PARSE,
     "scene.json:3: lights[0].color[1] must be a number, not a string"},
    {OBJ1 "\"lights\": [{\"type\": \"spot\", \"angle_deg\": 95}]}", CJ_ERR_RANGE,
     "scene.json:2: lights[0].angle_deg must be in [0, 90]"},
    {OBJ1 "\"lights\": [{\"type\": \"directional\", \"direction\": [0, 0, 0]}]}", CJ_ERR_DEGENERATE,
     "scene.json:2: lights[0].direction must not be the zero vector"},
    /* textures */
    {OBJ1 "\"textures\": [{\"name\": \"t\", \"type\": \"image\"}]}", CJ_ERR_PARSE,
     "scene.json:2: textures[0]: missing key \"path\""},
    {OBJ1 "\"textures\": [{\"name\": \"t\", \"type\": \"image\", \"path\": \"a.png\",\n"
          "\"filter\": \"cubic\"}]}",
     CJ_ERR_PARSE,
     "scene.json:3: textures[0].filter \"cubic\" is not one of nearest, bilinear, trilinear"},
    {OBJ1 "\"textures\": [{\"name\": \"t\", \"type\": \"checker\"},\n{\"name\": \"t\", \"type\": "
          "\"checker\"}]}",
     CJ_ERR_PARSE, "scene.json:3: textures[1].name \"t\" is already textures[0]"},
    {OBJ1 "\"textures\": [{\"name\": \"t\", \"type\": \"checker\", \"checks\": [0, 4]}]}",
     CJ_ERR_RANGE, "scene.json:2: textures[0].checks[0] must be >= 1"},
    /* materials */
    {OBJ1
     "\"materials\": [{\"name\": \"a\"}, {\"name\": \"b\"},\n {\"name\": \"c\",\n \"alpha\": -1}]}",
     CJ_ERR_RANGE, "scene.json:4: materials[2].alpha must be >= 0"},
    {OBJ1 "\"materials\": [{\"name\": \"a\", \"texture\": \"wood\"}]}", CJ_ERR_PARSE,
     "scene.json:2: materials[0].texture \"wood\" names no texture"},
    {OBJ1 "\"materials\": [{\"name\": \"a\", \"opacity\": 1.5}]}", CJ_ERR_RANGE,
     "scene.json:2: materials[0].opacity must be in [0, 1]"},
    {OBJ1 "\"materials\": [{\"name\": \"a\", \"ior\": 0.5}]}", CJ_ERR_RANGE,
     "scene.json:2: materials[0].ior must be >= 1"},
    {OBJ1 "\"materials\": [{\"name\": \"a\", \"shading\": \"toon\"}]}", CJ_ERR_PARSE,
     "scene.json:2: materials[0].shading \"toon\" is not one of flat, gouraud, phong"},
    /* objects: the example, line 14 */
    {"{\n  \"objects\": [\n    {" SPHERE "},\n    {" SPHERE "},\n    {\n      \"name\": \"c\",\n"
     "      " SPHERE ",\n      \"material\": {\n        \"color\": [1, 0, 0],\n"
     "        \"kd\": 0.5,\n        \"ks\": 0.5,\n        \"shading\": \"phong\",\n"
     "        \"two_sided\": false,\n        \"alpha\": -3\n      }\n    }\n  ]\n}\n",
     CJ_ERR_RANGE, "scene.json:14: objects[2].material.alpha must be >= 0"},
    {"{\"objects\": [{" SPHERE ",\n \"material\": \"gold\"}]}", CJ_ERR_PARSE,
     "scene.json:2: objects[0].material \"gold\" names no material"},
    {"{\"objects\": [{" SPHERE ",\n \"children\": []}]}", CJ_ERR_PARSE,
     "scene.json:2: objects[0]: an object has either a geometry or children, not both"},
    {"{\"objects\": [{\"name\": \"x\"}]}", CJ_ERR_PARSE,
     "scene.json:1: objects[0]: missing key \"geometry\" (or \"children\" for a group)"},
    {"{\"objects\": [{\"children\": [{\"children\": [\n{\"name\": \"x\", \"visible\": "
     "\"yes\"}]}]}]}",
     CJ_ERR_PARSE,
     "scene.json:2: objects[0].children[0].children[0].visible must be true or false, not a "
     "string"},
    {"{\"objects\": [{\"name\": \"a\",\n \"name\": \"b\", " SPHERE "}]}", CJ_ERR_PARSE,
     "scene.json:2: objects[0].name is given twice (line 1)"},
    {"{\"objects\": [{" SPHERE ",\n \"overlay\": {\"iso_lines\": -1}}]}", CJ_ERR_RANGE,
     "scene.json:2: objects[0].overlay.iso_lines must be in [0, 10000]"},
    /* transforms */
    {"{\"objects\": [{" SPHERE ",\n \"transform\": {\"quaternion\": [1, 0, 0, 0], \"rotate\": "
     "{\"axis\": [0, 0, 1], \"angle_deg\": 3}}}]}",
     CJ_ERR_PARSE,
     "scene.json:2: objects[0].transform: give one rotation (rotate, quaternion or euler_deg)"},
    {"{\"objects\": [{" SPHERE ",\n \"transform\": {\"scale\": [1, 0, 1]}}]}", CJ_ERR_RANGE,
     "scene.json:2: objects[0].transform.scale must not be zero"},
    {"{\"objects\": [{" SPHERE ",\n \"transform\": {\"matrix\": [[1, 0, 0, 0], [0, 1, 0, 0], "
     "[0, 0, 1, 0], [0, 0, 1, 1]]}}]}",
     CJ_ERR_RANGE, "scene.json:2: objects[0].transform.matrix[3] must be [0, 0, 0, 1]"},
    {"{\"objects\": [{" SPHERE ",\n \"transform\": {\"rotate\": {\"axis\": [0, 0, 0], "
     "\"angle_deg\": 3}}}]}",
     CJ_ERR_DEGENERATE,
     "scene.json:2: objects[0].transform.rotate.axis must not be the zero vector"},
    {"{\"objects\": [{" SPHERE ",\n \"transform\": {\"euler_deg\": [1, 2, 3], \"euler_order\": "
     "\"xxy\"}}]}",
     CJ_ERR_PARSE,
     "scene.json:2: objects[0].transform.euler_order \"xxy\" is not one of xyz, xzy, yxz, yzx, "
     "zxy, "
     "zyx"},
    /* geometry */
    {"{\"objects\": [{\"geometry\":\n {\"type\": \"cube\"}}]}", CJ_ERR_PARSE,
     "scene.json:2: objects[0].geometry.type \"cube\" is not one of teapot, bpt, patches, sphere, "
     "quadric, torus, cylinder, planar, plane, bilinear, revolution, gen_cylinder, mesh, curve, "
     "bspline_surface, nurbs_surface"},
    {"{\"objects\": [{\"geometry\": {\"type\": \"sphere\",\n \"radius\": 0}}]}", CJ_ERR_RANGE,
     "scene.json:2: objects[0].geometry.radius must be > 0"},
    {"{\"objects\": [{\"geometry\": {\"type\": \"sphere\"}}]}", CJ_ERR_PARSE,
     "scene.json:1: objects[0].geometry: missing key \"radius\""},
    {"{\"objects\": [{\"geometry\": {\"type\": \"quadric\", \"kind\": \"ellipsoid\", \"a\": 1, "
     "\"b\": 1, \"c\": 1,\n \"v0\": 0}}]}",
     CJ_ERR_PARSE,
     "scene.json:2: objects[0].geometry.v0 is not a known key (expected one of: type, kind, a, b, "
     "c)"},
    {"{\"objects\": [{\"geometry\": {\"type\": \"patches\", \"patches\": [{\"degree\": [1, 1],\n"
     "\"points\": [[0, 0, 0], [1, 0, 0], [0, 1, 0]]}]}}]}",
     CJ_ERR_PARSE,
     "scene.json:2: objects[0].geometry.patches[0].points must have 4 entries, not 3"},
    {"{\"objects\": [{\"geometry\": {\"type\": \"patches\", \"patches\": [{\"degree\": [1, 1],\n"
     "\"points\": [[0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0]],\n \"weights\": [1, 1, -1, 1]}]}}]}",
     CJ_ERR_RANGE, "scene.json:3: objects[0].geometry.patches[0].weights[2] must be > 0"},
    {"{\"objects\": [{\"geometry\": {\"type\": \"bpt\",\n \"path\": \"nope.bpt\"}}]}", CJ_ERR_IO,
     "scene.json:2: objects[0].geometry.path: cannot open '%s/nope.bpt': No such file or "
     "directory"},
    {"{\"objects\": [{\"geometry\": {\"type\": \"mesh\",\n \"path\": \"nope.obj\"}}]}", CJ_ERR_IO,
     "scene.json:2: objects[0].geometry.path: cannot open '%s/nope.obj': No such file or "
     "directory"},
    {"{\"objects\": [{\"geometry\": {\"type\": \"mesh\", \"positions\": [[0, 0, 0], [1, 0, 0], "
     "[0, 1, 0]],\n \"triangles\": [[0, 1,\n 3]]}}]}",
     CJ_ERR_RANGE,
     "scene.json:3: objects[0].geometry.triangles[0][2] = 3 names no vertex (3 vertices)"},
    {"{\"objects\": [{\"geometry\": {\"type\": \"curve\", \"kind\": \"rational\",\n \"points\": "
     "[[0, 0, 0], [1, 0, 0]]}}]}",
     CJ_ERR_PARSE, "scene.json:1: objects[0].geometry: missing key \"weights\""},
    {"{\"objects\": [{\"geometry\": {\"type\": \"curve\", \"kind\": \"bezier\", \"points\": "
     "[[0, 0, 0], [1, 0, 0]],\n \"width_px\": 0.5}}]}",
     CJ_ERR_RANGE, "scene.json:2: objects[0].geometry.width_px must be >= 1"},
    {"{\"objects\": [{\"geometry\": {\"type\": \"torus\", \"major\": 1, \"minor\": 2}}]}",
     CJ_ERR_ARGUMENT,
     "scene.json:1: objects[0].geometry: torus: minor radius 2 must be below major radius 1 "
     "(ring torus)"},
    {"{\"geometries\": [{\"name\": \"g\", \"type\": \"sphere\", \"radius\": 1}],\n"
     "\"objects\": [{\"geometry\":\n \"h\"}]}",
     CJ_ERR_PARSE, "scene.json:3: objects[0].geometry \"h\" names no entry of geometries"},
    {"{\"objects\": [{\"geometry\":\n {\"type\": \"teapot\"}}]}", CJ_ERR_UNSUPPORTED,
     "scene.json:2: objects[0].geometry: the teapot's data file is not known here "
     "(cj_scene_json_options.teapot_path)"},
};

/* Counts live allocations so a failed parse can be shown to free everything. */
static long live_blocks;
static void *count_alloc(void *user, size_t n) {
    (void)user;
    live_blocks++;
    return malloc(n);
}
static void count_free(void *user, void *p) {
    (void)user;
    if (p) live_blocks--;
    free(p);
}

static void test_bad_documents(void **state) {
    (void)state;
    const cj_allocator counting = {count_alloc, count_free, NULL};
    size_t n = sizeof BAD / sizeof BAD[0];
    for (size_t i = 0; i < n; ++i) {
        const bad_case *b = &BAD[i];
        cj_scene *sentinel = (cj_scene *)&live_blocks, *s = sentinel;
        const cj_scene_json_options *opt = strstr(b->doc, "teapot") ? NULL : &sj_opts;
        live_blocks = 0;
        cj_status st = cj_scene_parse_json_ex(b->doc, "scene.json", sj_tmpdir, opt, &counting, &s);
        if (s != sentinel) fail_msg("case %zu: a scene was returned on error", i);
        if (live_blocks != 0) fail_msg("case %zu: %ld blocks leaked", i, live_blocks);
        if (st != b->status)
            fail_msg("case %zu: status %s, expected %s (%s)", i, cj_status_str(st),
                     cj_status_str(b->status), cj_last_error());
        if (b->message) {
            char want[1024];
            snprintf(want, sizeof want, b->message, sj_tmpdir);
            if (strcmp(cj_last_error(), want))
                fail_msg("case %zu:\n  got  '%s'\n  want '%s'", i, cj_last_error(), want);
        } else if (strncmp(cj_last_error(), "scene.json:1: objects[0].geometry", 33)) {
            fail_msg("case %zu: [%s]", i, cj_last_error());
        }
    }
    printf("test_scene_json: %zu bad documents give the expected status and 'file:line: path "
           "message', no scene and no leaked block\n",
           n);
}

static void test_missing_file(void **state) {
    (void)state;
    char path[512];
    snprintf(path, sizeof path, "%s/absent.json", sj_tmpdir);
    cj_scene *s = NULL;
    assert_int_equal(cj_scene_load_json(path, NULL, &s), CJ_ERR_IO);
    assert_null(s);
    char want[1200];
    snprintf(want, sizeof want, "cannot open '%s': No such file or directory", path);
    assert_string_equal(cj_last_error(), want);
    /* The file name and its folder are used for messages and relative paths. */
    snprintf(path, sizeof path, "%s/bad.json", sj_tmpdir);
    write_file(path, "{\"objects\": [{\"geometry\": {\"type\": \"mesh\",\n\"path\": \"m.obj\"}}]}");
    assert_int_equal(cj_scene_load_json(path, NULL, &s), CJ_ERR_IO);
    snprintf(want, sizeof want,
             "%s:2: objects[0].geometry.path: cannot open '%s/m.obj': No such file or directory",
             path, sj_tmpdir);
    assert_string_equal(cj_last_error(), want);
    char obj[512];
    snprintf(obj, sizeof obj, "%s/m.obj", sj_tmpdir);
    write_file(obj, "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 4 3\n");
    assert_int_equal(cj_scene_load_json(path, NULL, &s), CJ_OK);
    const cj_geometry *g = cj_scene_geometry(s, 0);
    assert_int_equal(g->kind, CJ_GEOM_MESH);
    assert_int_equal(g->u.mesh->triangle_count, 2);
    cj_scene_destroy(s);
    /* A .bpt file next to the scene, by a relative path. */
    char bpt[512];
    snprintf(bpt, sizeof bpt, "%s/one.bpt", sj_tmpdir);
    write_file(bpt, "1\n1 1\n0 0 0\n1 0 0\n0 1 0\n1 1 0.5\n");
    write_file(path, "{\"objects\": [{\"geometry\": {\"type\": \"bpt\", \"path\": \"one.bpt\"}}]}");
    assert_int_equal(cj_scene_load_json(path, NULL, &s), CJ_OK);
    g = cj_scene_geometry(s, 0);
    assert_int_equal(g->kind, CJ_GEOM_PATCHES);
    assert_int_equal(g->u.patches.count, 1);
    assert_true(g->u.patches.patches[0].pts[11] == 0.5);
    cj_scene_destroy(s);
    printf("test_scene_json: a missing scene file and a missing mesh are named with their path; "
           "meshes and .bpt files load relative to the scene's folder\n");
}

/* ---- values --------------------------------------------------------------------------------- */

/* What the keys mean: focal length to field of view, look_at to gaze, rotations (axis-angle,
 * Euler in a given order, quaternion) against matrices built by hand, uniform scale, matrix
 * rows, group materials inherited, defaults. */
static void test_values(void **state) {
    (void)state;
    const char *doc =
        "{\"camera\": {\"eye\": [1, 2, 3], \"look_at\": [1, 2, -7], \"focal_length_mm\": 50,\n"
        "  \"sensor_height_mm\": 24, \"near\": -0.5, \"far\": -50},\n"
        " \"materials\": [{\"name\": \"red\", \"color\": [1, 0, 0]}],\n"
        " \"objects\": [\n"
        "  {\"transform\": {\"rotate\": {\"axis\": [0, 0, 2], \"angle_deg\": 90}}, " SPHERE "},\n"
        "  {\"transform\": {\"euler_deg\": [90, 0, 90], \"euler_order\": \"xyz\"}, " SPHERE "},\n"
        "  {\"transform\": {\"euler_deg\": [90, 0, 90], \"euler_order\": \"zyx\"}, " SPHERE "},\n"
        "  {\"transform\": {\"quaternion\": [2, 0, 0, 0], \"scale\": 3}, " SPHERE "},\n"
        "  {\"transform\": {\"matrix\": [[1, 2, 0, 4], [0, 1, 0, 5], [0, 0, 1, 6], [0, 0, 0, 1]]},"
        " " SPHERE "},\n"
        "  {\"material\": \"red\", \"children\": [{" SPHERE "}, {\"children\": [{" SPHERE "}]}]}\n"
        " ]}\n";
    cj_scene *s = NULL;
    if (cj_scene_parse_json(doc, "v.json", NULL, NULL, &s)) fail_msg("%s", cj_last_error());
    const cj_camera *c = cj_scene_camera(s);
    assert_true(fabs(c->fov_y - 2 * atan(12.0 / 50.0)) < 1e-15);
    assert_true(c->gaze.x == 0 && c->gaze.y == 0 && c->gaze.z == -10);
    assert_true(c->near == -0.5 && c->far == -50 && c->projection == CJ_PROJ_PERSPECTIVE);
    /* p = (1, 0, 0) through each node's local transform. */
    const double want[5][3] = {{0, 1, 0},  /* 90° about z */
                               {0, 1, 0},  /* x by 90 (x stays), then z by 90: (0, 1, 0) */
                               {0, 0, 1},  /* z by 90 first: (0, 1, 0), then x by 90: (0, 0, 1) */
                               {3, 0, 0},  /* identity rotation (normalised), scale 3 */
                               {5, 5, 6}}; /* matrix rows */
    for (int i = 0; i < 5; ++i) {
        cj_xform3 m = cj_transform_matrix(&cj_scene_node(s, i)->local);
        cj_vec3 q;
        assert_int_equal(cj_xform3_apply_point(&m, cj_v3(1, 0, 0), &q), CJ_OK);
        double w[3] = {want[i][0], want[i][1], want[i][2]};
        if (!(fabs(q.x - w[0]) < 1e-15 && fabs(q.y - w[1]) < 1e-15 && fabs(q.z - w[2]) < 1e-15))
            fail_msg("node %d: (1,0,0) -> (%g, %g, %g), want (%g, %g, %g)", i, q.x, q.y, q.z, w[0],
                     w[1], w[2]);
    }
    /* y through the xyz Euler rotation: x by 90 takes y to z, z by 90 keeps z. */
    cj_xform3 m1 = cj_transform_matrix(&cj_scene_node(s, 1)->local);
    cj_vec3 q;
    assert_int_equal(cj_xform3_apply_point(&m1, cj_v3(0, 1, 0), &q), CJ_OK);
    assert_true(fabs(q.x) < 1e-15 && fabs(q.y) < 1e-15 && fabs(q.z - 1) < 1e-15);
    assert_true(cj_scene_node(s, 3)->local.rotation[0] == 1);
    /* The group's material reaches its children and grandchildren; objects without one get a
     * default material of their own (added once). */
    int red = 0, def = cj_scene_node(s, 0)->material;
    assert_string_equal(cj_scene_material_name(s, red), "red");
    assert_int_not_equal(def, red);
    assert_null(cj_scene_material_name(s, def));
    for (int i = 1; i < 5; ++i) assert_int_equal(cj_scene_node(s, i)->material, def);
    assert_int_equal(cj_scene_node(s, 5)->geometry, -1);
    assert_int_equal(cj_scene_node(s, 6)->material, red);
    assert_int_equal(cj_scene_node(s, 6)->parent, 5);
    assert_int_equal(cj_scene_node(s, 8)->material, red);
    assert_int_equal(cj_scene_node(s, 8)->parent, 7);
    assert_int_equal(cj_scene_material_count(s), 2);
    cj_scene_destroy(s);
    printf("test_scene_json: focal length, look_at, axis-angle, Euler orders, quaternion, scale, "
           "matrix and inherited materials mean what scene_json.h says\n");
}

/* ---- mutated documents -------------------------------------------------------------------- */

/* Random edits of the shipped scenes (delete, duplicate or replace a character, replace a number
 * by a random one, cut the text): every result either loads and checks, or fails with a message
 * "scene.json:L: ..." or "scene.json:L:C: ..." whose line L exists in the edited text. Under the
 * sanitizers this is also the crash test of the reader and of the line scanner. */
static void test_mutations(void **state) {
    (void)state;
    const char *names[] = {"teapot", "quadrics", "transparent", "gallery"};
    cj_rng r;
    cj_rng_init(&r, cj_test_seed("test_scene_json mutations", 2024));
    int ok = 0, refused = 0;
    for (int f = 0; f < 4; ++f) {
        char path[512];
        snprintf(path, sizeof path, "%s/%s.json", CJ_SCENES_DIR, names[f]);
        char *orig = sj_read_all(path);
        size_t len = strlen(orig);
        char *buf = malloc(len + 64);
        assert_non_null(buf);
        for (int k = 0; k < 500; ++k) {
            memcpy(buf, orig, len + 1);
            size_t n = len;
            int edits = cj_rng_int(&r, 1, 3);
            for (int e = 0; e < edits; ++e) {
                size_t at = (size_t)cj_rng_int(&r, 0, (int)n - 1);
                static const char pool[] = "{}[]:,\"\\0123456789.-eE ntfalsru\n";
                switch (cj_rng_int(&r, 0, 4)) {
                case 0: /* delete */
                    memmove(buf + at, buf + at + 1, n - at);
                    n--;
                    break;
                case 1: /* duplicate */
                    memmove(buf + at + 1, buf + at, n - at + 1);
                    n++;
                    break;
                case 2: /* replace */
                    buf[at] = pool[cj_rng_int(&r, 0, (int)sizeof pool - 2)];
                    break;
                case 3: { /* a digit becomes a random number */
                    char *d = strpbrk(buf + at, "0123456789");
                    if (d) {
                        char num[32];
                        int w = snprintf(num, sizeof num, "%.6g", cj_rng_range(&r, -1e4, 1e4));
                        if (n + (size_t)w + 1 < len + 64) {
                            memmove(d + w, d + 1, n - (size_t)(d - buf));
                            memcpy(d, num, (size_t)w);
                            n += (size_t)w - 1;
                        }
                    }
                    break;
                }
                default: /* cut */
                    n = at;
                    buf[n] = '\0';
                }
                if (n == 0) break;
            }
            int lines = 1;
            for (size_t i = 0; i < n; ++i) lines += buf[i] == '\n';
            cj_scene *s = NULL;
            cj_status st =
                cj_scene_parse_json_ex(buf, "scene.json", CJ_SCENES_DIR, &sj_opts, NULL, &s);
            if (st == CJ_OK) {
                assert_int_equal(cj_scene_check(s), CJ_OK);
                cj_scene_destroy(s);
                ok++;
                continue;
            }
            assert_null(s);
            const char *m = cj_last_error();
            int line = 0;
            if (strncmp(m, "scene.json:", 11) || sscanf(m + 11, "%d", &line) != 1 || line < 1 ||
                line > lines)
                fail_msg("%s edit %d: message '%s' names no line of the %d-line text", names[f], k,
                         m, lines);
            refused++;
        }
        free(buf);
        free(orig);
    }
    printf("test_scene_json: 2000 randomly edited scenes: %d load and check, %d refused with a "
           "line that exists\n",
           ok, refused);
}

/* Documents built from tokens joined by random whitespace (spaces, tabs, newlines, CRLF), with
 * one fault at a random place: the message names exactly the line of the faulty value (or of
 * the unknown key). */
typedef struct tokbuf {
    char text[16384];
    size_t n;
    int line;
} tokbuf;

static void tok(tokbuf *b, cj_rng *r, const char *t, int *line_of) {
    static const char *const SEP[] = {"", " ", "\n", "\t ", "\r\n  ", "\n\n"};
    const char *sep = SEP[cj_rng_int(r, 0, 5)];
    for (const char *c = sep; *c; ++c) b->line += *c == '\n';
    int w = snprintf(b->text + b->n, sizeof b->text - b->n, "%s%s", sep, t);
    assert_true(w > 0 && b->n + (size_t)w < sizeof b->text);
    b->n += (size_t)w;
    if (line_of) *line_of = b->line;
}

static void test_random_layout_lines(void **state) {
    (void)state;
    cj_rng r;
    cj_rng_init(&r, cj_test_seed("test_scene_json layout", 99));
    for (int k = 0; k < 300; ++k) {
        tokbuf b = {"", 0, 1};
        int nm = cj_rng_int(&r, 1, 6), bad_m = cj_rng_int(&r, 0, nm), kind = cj_rng_int(&r, 0, 2);
        int want = -1;
        char expect[256] = "";
        tok(&b, &r, "{", NULL);
        tok(&b, &r, "\"materials\"", NULL);
        tok(&b, &r, ":", NULL);
        tok(&b, &r, "[", NULL);
        for (int m = 0; m < nm; ++m) {
            char t[64];
            tok(&b, &r, m ? ",{" : "{", NULL);
            snprintf(t, sizeof t, "\"name\": \"m%d\",", m);
            tok(&b, &r, t, NULL);
            tok(&b, &r, "\"color\":", NULL);
            tok(&b, &r, "[0.5,", NULL);
            tok(&b, &r, "0.5", NULL);
            tok(&b, &r, ", 0.5]", NULL);
            if (m == bad_m && kind == 0) {
                tok(&b, &r, ",\"alpha\"", NULL);
                tok(&b, &r, ":", NULL);
                tok(&b, &r, "-2", &want);
                snprintf(expect, sizeof expect, "materials[%d].alpha must be >= 0", m);
            } else if (m == bad_m && kind == 1) {
                tok(&b, &r, ",\"alhpa\"", &want);
                tok(&b, &r, ":", NULL);
                tok(&b, &r, "3", NULL);
                snprintf(expect, sizeof expect, "materials[%d].alhpa is not a known key", m);
            } else if (m == bad_m) {
                tok(&b, &r, ",\"specular\":", NULL);
                tok(&b, &r, "[1,", NULL);
                tok(&b, &r, "\"x\"", &want);
                tok(&b, &r, ",1]", NULL);
                snprintf(expect, sizeof expect,
                         "materials[%d].specular[1] must be a number, not a string", m);
            }
            tok(&b, &r, "}", NULL);
        }
        tok(&b, &r, "],", NULL);
        tok(&b, &r, "\"objects\"", NULL);
        tok(&b, &r, ":", NULL);
        tok(&b, &r, "[{\"geometry\":", NULL);
        if (bad_m == nm) {
            tok(&b, &r, "{\"type\": \"sphere\", \"radius\":", NULL);
            tok(&b, &r, "0", &want);
            snprintf(expect, sizeof expect, "objects[0].geometry.radius must be > 0");
            tok(&b, &r, "}", NULL);
        } else {
            tok(&b, &r, "{\"type\": \"sphere\", \"radius\": 1}", NULL);
        }
        tok(&b, &r, "}]", NULL);
        tok(&b, &r, "}", NULL);
        cj_scene *s = NULL;
        assert_int_not_equal(cj_scene_parse_json(b.text, "scene.json", NULL, NULL, &s), CJ_OK);
        char full[400];
        snprintf(full, sizeof full, "scene.json:%d: %s", want, expect);
        if (strncmp(cj_last_error(), full, strlen(full)))
            fail_msg("document %d: '%s', want '%s...'\n%s", k, cj_last_error(), full, b.text);
    }
    printf("test_scene_json: 300 documents in random layouts name the exact line of their fault\n");
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_shipped_scenes),        cmocka_unit_test(test_bad_documents),
        cmocka_unit_test(test_missing_file),          cmocka_unit_test(test_round_trip_shipped),
        cmocka_unit_test(test_round_trip_everything), cmocka_unit_test(test_mutations),
        cmocka_unit_test(test_random_layout_lines),   cmocka_unit_test(test_values),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}

/* The table of bad scene documents of test_scene_json: each gives its exact status and
 * "file:line: path message", no scene, and no leaked block (counted by the allocator). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <cmocka.h>

#include "casteljau/scene_json.h"
#include "scene_json_test.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct bad_case {
    const char *doc;
    cj_status status;
    const char *message; /* "%s" (if any) stands for the test's temporary folder */
} bad_case;

#define OBJ1 "{\"objects\": [{\"geometry\": {\"type\": \"sphere\", \"radius\": 1}}],\n"

static const bad_case BAD[] = {
    /* syntax */
    {"{\n  \"objects\": [\n    {\"name\": \"a\",}\n  ]\n}\n", CJ_ERR_PARSE,
     "scene.json:3:19: JSON syntax error (line 3, column 19)"},
    {"{\"objects\": []}\n\n]", CJ_ERR_PARSE,
     "scene.json:3:1: JSON syntax error (line 3, column 1)"},
    /* lines survive strings with brackets, quotes and escapes, empty containers and a BOM */
    {"{\"objects\": [{\"name\": \"a}\\\"],:{[\", \"geometry\": {\"type\": \"sphere\",\n"
     " \"radius\": -1}}]}",
     CJ_ERR_RANGE, "scene.json:2: objects[0].geometry.radius must be > 0, not -1"},
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
    {"{\"objects\": {}}", CJ_ERR_PARSE, "scene.json:1: objects must be an array, not an object"},
    /* camera */
    {OBJ1 "\"camera\": {\"eye\": [0, 0]}}", CJ_ERR_PARSE,
     "scene.json:2: camera.eye must be an array of 3 numbers, not 2"},
    {OBJ1 "\"camera\": {\n\"near\": 0.1}}", CJ_ERR_RANGE,
     "scene.json:3: camera.near must be < 0, not 0.1"},
    {OBJ1 "\"camera\": {\"near\": -1,\n\n \"far\": -0.5}}", CJ_ERR_RANGE,
     "scene.json:4: camera.far must be < -1, not -0.5"},
    {OBJ1 "\"camera\": {\"gaze\": [0, 0, -1],\n \"look_at\": [0, 0, 0]}}", CJ_ERR_PARSE,
     "scene.json:3: camera: give either \"gaze\" or \"look_at\", not both"},
    {OBJ1 "\"camera\": {\"fov_deg\": 180}}", CJ_ERR_RANGE,
     "scene.json:2: camera.fov_deg must be in (0, 180), not 180"},
    {OBJ1 "\"camera\": {\n\"gaze\": [0, 1, 0], \"up\": [0, 2, 0]}}", CJ_ERR_DEGENERATE,
     "scene.json:2: camera.up must not be parallel to the gaze"},
    {OBJ1 "\"camera\": {\"projection\": \"fisheye\"}}", CJ_ERR_PARSE,
     "scene.json:2: camera.projection \"fisheye\" is not one of perspective, orthographic"},
    /* settings */
    {OBJ1 "\"settings\": {\"width\": 0}}", CJ_ERR_RANGE,
     "scene.json:2: settings.width must be in [1, 32768], not 0"},
    {OBJ1 "\"settings\": {\"spp\": 2.5}}", CJ_ERR_PARSE,
     "scene.json:2: settings.spp must be an integer, not 2.5"},
    {OBJ1 "\"settings\": {\"background\": [0, -1, 0]}}", CJ_ERR_RANGE,
     "scene.json:2: settings.background[1] must be >= 0, not -1"},
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
     "scene.json:2: lights[0].intensity must be >= 0, not -1"},
    {OBJ1 "\"lights\": [{\"type\": \"point\", \"color\": [1,\n \"x\", 1]}]}", CJ_ERR_PARSE,
     "scene.json:3: lights[0].color[1] must be a number, not a string"},
    {OBJ1 "\"lights\": [{\"type\": \"spot\", \"angle_deg\": 95}]}", CJ_ERR_RANGE,
     "scene.json:2: lights[0].angle_deg must be in [0, 90], not 95"},
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
     CJ_ERR_RANGE, "scene.json:2: textures[0].checks[0] must be >= 1, not 0"},
    /* materials */
    {OBJ1
     "\"materials\": [{\"name\": \"a\"}, {\"name\": \"b\"},\n {\"name\": \"c\",\n \"alpha\": -1}]}",
     CJ_ERR_RANGE, "scene.json:4: materials[2].alpha must be >= 0, not -1"},
    {OBJ1 "\"materials\": [{\"name\": \"a\", \"texture\": \"wood\"}]}", CJ_ERR_PARSE,
     "scene.json:2: materials[0].texture \"wood\" names no texture"},
    {OBJ1 "\"materials\": [{\"name\": \"a\", \"opacity\": 1.5}]}", CJ_ERR_RANGE,
     "scene.json:2: materials[0].opacity must be in [0, 1], not 1.5"},
    {OBJ1 "\"materials\": [{\"name\": \"a\", \"ior\": 0.5}]}", CJ_ERR_RANGE,
     "scene.json:2: materials[0].ior must be >= 1, not 0.5"},
    {OBJ1 "\"materials\": [{\"name\": \"a\", \"shading\": \"toon\"}]}", CJ_ERR_PARSE,
     "scene.json:2: materials[0].shading \"toon\" is not one of flat, gouraud, phong"},
    /* objects: the example, line 14 */
    {"{\n  \"objects\": [\n    {" SPHERE "},\n    {" SPHERE "},\n    {\n      \"name\": \"c\",\n"
     "      " SPHERE ",\n      \"material\": {\n        \"color\": [1, 0, 0],\n"
     "        \"kd\": 0.5,\n        \"ks\": 0.5,\n        \"shading\": \"phong\",\n"
     "        \"two_sided\": false,\n        \"alpha\": -3\n      }\n    }\n  ]\n}\n",
     CJ_ERR_RANGE, "scene.json:14: objects[2].material.alpha must be >= 0, not -3"},
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
     "scene.json:2: objects[0].overlay.iso_lines must be in [0, 10000], not -1"},
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
     "scene.json:2: objects[0].geometry.radius must be > 0, not 0"},
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
     CJ_ERR_RANGE, "scene.json:3: objects[0].geometry.patches[0].weights[2] must be > 0, not -1"},
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
     CJ_ERR_RANGE, "scene.json:2: objects[0].geometry.width_px must be >= 1, not 0.5"},
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

void test_bad_documents(void **state) {
    (void)state;
    const cj_allocator counting = {count_alloc, count_free, NULL};
    size_t n = sizeof BAD / sizeof BAD[0];
    for (size_t i = 0; i < n; ++i) {
        const bad_case *b = &BAD[i];
        cj_scene *sentinel = (cj_scene *)&live_blocks, *s = sentinel;
        const cj_scene_json_options *opt = strstr(b->doc, "teapot") ? NULL : &sj_opts;
        live_blocks = 0;
        cj_status st =
            cj_scene_parse_json_with_options(b->doc, "scene.json", sj_tmpdir, opt, &counting, &s);
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

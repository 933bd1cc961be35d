#define _POSIX_C_SOURCE 200809L
/* The surface document (formats/include/surface_json.h) and the scene's "bspline_surface" /
 * "nurbs_surface" geometry are one format read by one reader (scene/src/bspline_surface_json.c):
 *  - each bad object is refused alone and inside a scene with the same status and the same
 *    message, the scene's naming the object's path ("objects[0].geometry") where the document's
 *    names its root ("document"), both at line 1 of their document;
 *  - the statuses are the kit's own: CJ_ERR_RANGE for values out of range, CJ_ERR_PARSE for
 *    wrong types and keys;
 *  - a NURBS surface written by cj_surface_json_print reads back bit-identical. */
#include "surface_json.h"

#include "check.h"

#include "casteljau/scene.h"
#include "casteljau/scene_json.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define PTS "[[0,0,0],[1,0,0],[0,1,0],[1,1,1]]"

typedef struct bad_surface {
    const char *json;
    cj_status status;
    const char *expect; /* the document's message after "s.json:1: " */
} bad_surface;

static const bad_surface bad[] = {
    {"{\"type\": \"nurbs_surface\", \"degree\": [1,1], \"size\": [2,2], \"points\": " PTS "}",
     CJ_ERR_PARSE, "document: missing key \"weights\""},
    {"{\"type\": \"bspline_surface\", \"degree\": [1,1], \"size\": [2,2], \"points\": " PTS
     ", \"weights\": [1,1,1,1]}",
     CJ_ERR_PARSE, "weights are given for a bspline_surface (weights make a nurbs_surface)"},
    {"{\"type\": \"nurbs_surface\", \"degree\": [1,1], \"size\": [2,2], \"points\": " PTS
     ", \"weights\": [1,1,0,1]}",
     CJ_ERR_RANGE, "weights[2] must be > 0, not 0"},
    {"{\"type\": \"bspline_surface\", \"degree\": [0,1], \"size\": [2,2], \"points\": " PTS "}",
     CJ_ERR_RANGE, "degree[0] must be in [1, "},
    {"{\"type\": \"bspline_surface\", \"degree\": [1,1.5], \"size\": [2,2], \"points\": " PTS "}",
     CJ_ERR_RANGE, "degree[1] must be an integer, not 1.5"},
    {"{\"type\": \"bspline_surface\", \"degree\": [1,1], \"size\": [2000,2000], \"points\": " PTS
     "}",
     CJ_ERR_RANGE, "size: 2000 x 2000 is more than 1e6 control points"},
    {"{\"type\": \"bspline_surface\", \"degree\": [1,1], \"size\": [2,3], \"points\": " PTS "}",
     CJ_ERR_PARSE, "points must have 6 entries, not 4"},
    {"{\"type\": \"bspline_surface\", \"degree\": [1,1], \"size\": [2,2], \"points\": " PTS
     ", \"colour\": 1}",
     CJ_ERR_PARSE, "colour is not a known key"},
    {"{\"type\": \"bspline_surface\", \"degree\": [1,1], \"size\": [2,2], \"points\": " PTS
     ", \"knots_u\": [0,0.5,0.2,1]}",
     CJ_ERR_RANGE, "u knot 2"},
};

static void test_one_reader(void) {
    const size_t n = sizeof bad / sizeof bad[0];
    for (size_t i = 0; i < n; ++i) {
        cj_bspline_surface s;
        const cj_status st = cj_surface_json_parse("s.json", bad[i].json, &s);
        char alone[1024];
        snprintf(alone, sizeof alone, "%s", st ? cj_last_error() : "");
        CHECK(st != CJ_OK && !strncmp(alone, "s.json:1: ", 10) && strstr(alone, bad[i].expect),
              "case %zu alone: status %d, '%s' (wanted '%s')", i, st, alone, bad[i].expect);
        CHECK(st == CJ_OK || s.pts == NULL, "case %zu: nothing is kept on failure", i);
        if (!st) cj_surface_json_free(&s);
        char text[2048];
        snprintf(text, sizeof text,
                 "{\"camera\": {\"eye\": [0, 0, 5], \"look_at\": [0, 0, 0], \"up\": [0, 1, 0]},"
                 " \"objects\": [{\"geometry\": %s}]}",
                 bad[i].json);
        cj_scene *scene = NULL;
        const cj_status sst = cj_scene_parse_json(text, "t.json", ".", NULL, &scene);
        const char *in_scene = sst ? cj_last_error() : "";
        /* the same words: the scene's message names the object's path where the document's
         * names its root ("document") or starts at a key */
        const char *tail = alone + 10;
        char want[1200];
        if (!strncmp(tail, "document", 8))
            snprintf(want, sizeof want, "t.json:1: objects[0].geometry%s", tail + 8);
        else
            snprintf(want, sizeof want, "t.json:1: objects[0].geometry.%s", tail);
        CHECK(sst == st && !strcmp(in_scene, want),
              "case %zu in a scene: status %d (alone %d), '%s' (wanted '%s')", i, sst, st, in_scene,
              want);
        if (!sst) cj_scene_destroy(scene);
    }
    printf("surface_json: %zu bad surfaces refused alone and in a scene with the same status and "
           "the same message\n",
           n);
}

static int same(const double *a, const double *b, size_t n) {
    return !memcmp(a, b, n * sizeof *a);
}

static void test_round_trip(void) {
    const char *doc = "{\"type\": \"nurbs_surface\", \"degree\": [1,2], \"size\": [2,3],"
                      " \"points\": [[0,0,0],[1,0,0.1],[0,1,0],[1,1,0.7999999999999999],"
                      "[0,2,0.3],[1,2,1e-300]], \"weights\": [1,0.5,2,1,3,0.25],"
                      " \"knots_v\": [0,0,0,1,1,1]}";
    cj_bspline_surface a, b;
    cj_status st = cj_surface_json_parse("r.json", doc, &a);
    CHECK(st == CJ_OK, "the NURBS surface reads: %s", cj_last_error());
    if (st) return;
    char *buf = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&buf, &len);
    st = f ? cj_surface_json_print(f, &a, "test") : CJ_ERR_IO;
    if (f) fclose(f);
    CHECK(st == CJ_OK && buf && strstr(buf, "0.7999999999999999") &&
              !strstr(buf, "0.79999999999999993"),
          "written in shortest form: %s", buf ? buf : cj_last_error());
    st = st ? st : cj_surface_json_parse("w.json", buf, &b);
    CHECK(st == CJ_OK, "the written surface reads back: %s", cj_last_error());
    if (!st) {
        const size_t n = (size_t)a.npts_u * (size_t)a.npts_v;
        CHECK(b.deg_u == 1 && b.deg_v == 2 && b.npts_u == 2 && b.npts_v == 3 &&
                  same(a.pts, b.pts, 3 * n) && same(a.weights, b.weights, n) &&
                  same(a.knots_u, b.knots_u, 4) && same(a.knots_v, b.knots_v, 6),
              "the surface read back is bit-identical");
        cj_surface_json_free(&b);
    }
    cj_surface_json_free(&a);
    free(buf);
    printf("surface_json: a NURBS surface (uniform u knots made by the reader) written and read "
           "back bit-identical, numbers shortest\n");
}

int main(void) {
    test_one_reader();
    test_round_trip();
    return cj_check_exit();
}

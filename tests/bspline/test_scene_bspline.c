/* Scene JSON "bspline_surface" / "nurbs_surface": loaded as Bézier patches (a NURBS torus is 16
 * rational patches whose every point lies on the torus; a bicubic sheet is 12 patches agreeing
 * with the B-spline it came from), and malformed surfaces refused with the JSON path. */
#include "casteljau/bspline_surface.h"
#include "casteljau/patch.h"
#include "casteljau/scene.h"
#include "casteljau/scene_json.h"
#include "casteljau/status.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int failures;
#define CHECK(cond, ...)                                                                           \
    do {                                                                                           \
        if (!(cond)) {                                                                             \
            ++failures;                                                                            \
            printf("FAIL line %d: ", __LINE__);                                                    \
            printf(__VA_ARGS__);                                                                   \
            printf("\n");                                                                          \
        }                                                                                          \
    } while (0)

static const double R = 1.1, r = 0.42;

static void test_gallery(void) {
    cj_scene *scene = NULL;
    cj_status st = cj_scene_load_json(CJ_SCENE_FILE, NULL, &scene);
    CHECK(st == CJ_OK, "load %s: %s", CJ_SCENE_FILE, cj_last_error());
    if (st) return;
    int torus = -1, sheet = -1;
    for (size_t i = 0; i < cj_scene_geometry_count(scene); ++i) {
        const cj_geometry *g = cj_scene_geometry(scene, (int)i);
        if (g->kind != CJ_GEOM_PATCHES) continue;
        if (g->u.patches.count == 16 && g->u.patches.patches[0].weights) torus = (int)i;
        if (g->u.patches.count == 12 && !g->u.patches.patches[0].weights) sheet = (int)i;
    }
    CHECK(torus >= 0 && sheet >= 0, "torus (16 rational patches) %d, sheet (12 patches) %d", torus,
          sheet);
    double worst = 0.0;
    if (torus >= 0) {
        const cj_geometry *g = cj_scene_geometry(scene, torus);
        for (size_t k = 0; k < g->u.patches.count; ++k)
            for (int a = 0; a <= 8; ++a)
                for (int b = 0; b <= 8; ++b) {
                    double x[3];
                    cj_patch_eval(&g->u.patches.patches[k], CJ_EVAL_DECASTELJAU, a / 8.0, b / 8.0,
                                  x);
                    /* distance from the tube's centre circle minus the minor radius */
                    const double rho = hypot(x[0], x[2]) - R;
                    worst = fmax(worst, fabs(hypot(rho, x[1]) - r));
                }
        CHECK(worst <= 1e-14, "torus patches leave the torus by %.3g", worst);
    }
    cj_scene_destroy(scene);
    printf("gallery scene: %s loads a NURBS torus as 16 rational patches (every sampled point on "
           "the torus within %.3g) and a bicubic sheet as 12 patches\n",
           CJ_SCENE_FILE, worst);
}

static void expect_error(const char *geom, const char *needle) {
    char text[2048];
    snprintf(text, sizeof text,
             "{\"camera\": {\"eye\": [0, 0, 5], \"look_at\": [0, 0, 0], \"up\": [0, 1, 0]},"
             " \"objects\": [{\"geometry\": %s}]}",
             geom);
    cj_scene *scene = NULL;
    cj_status st = cj_scene_parse_json(text, "t.json", ".", NULL, &scene);
    CHECK(st != CJ_OK && strstr(cj_last_error(), needle),
          "%s: status %d, message '%s' (wanted '%s')", geom, st, cj_last_error(), needle);
    if (!st) cj_scene_destroy(scene);
}

static void test_errors(void) {
    const char *pts = "[[0,0,0],[1,0,0],[0,1,0],[1,1,1]]";
    char g[1024];
    snprintf(g, sizeof g,
             "{\"type\": \"nurbs_surface\", \"degree\": [1,1], \"size\": [2,2], \"points\": %s}",
             pts);
    expect_error(g, "weights");
    snprintf(g, sizeof g,
             "{\"type\": \"bspline_surface\", \"degree\": [1,1], \"size\": [2,2], \"points\": %s, "
             "\"weights\": [1,1,1,1]}",
             pts);
    expect_error(g, "weights");
    snprintf(g, sizeof g,
             "{\"type\": \"bspline_surface\", \"degree\": [1,1], \"size\": [2,2], \"points\": %s, "
             "\"knots_u\": [0,0.5,0.2,1]}",
             pts);
    expect_error(g, "u knot 2");
    snprintf(g, sizeof g,
             "{\"type\": \"nurbs_surface\", \"degree\": [1,1], \"size\": [2,2], \"points\": %s, "
             "\"weights\": [1,1,0,1]}",
             pts);
    expect_error(g, "weights");
    snprintf(g, sizeof g,
             "{\"type\": \"bspline_surface\", \"degree\": [2,1], \"size\": [2,2], \"points\": %s}",
             pts);
    expect_error(g, "too few");
    snprintf(g, sizeof g,
             "{\"type\": \"bspline_surface\", \"degree\": [1,1], \"size\": [2,3], \"points\": %s}",
             pts);
    expect_error(g, "points");
    /* A valid one, for contrast: one bilinear patch. */
    char text[1024];
    snprintf(text, sizeof text,
             "{\"camera\": {\"eye\": [0, 0, 5], \"look_at\": [0, 0, 0], \"up\": [0, 1, 0]},"
             " \"objects\": [{\"geometry\": {\"type\": \"bspline_surface\", \"degree\": [1,1], "
             "\"size\": [2,2], \"points\": %s}}]}",
             pts);
    cj_scene *scene = NULL;
    cj_status st = cj_scene_parse_json(text, "t.json", ".", NULL, &scene);
    CHECK(st == CJ_OK && cj_scene_geometry_count(scene) == 1 &&
              cj_scene_geometry(scene, 0)->u.patches.count == 1,
          "a bilinear B-spline surface: %s", cj_last_error());
    if (!st) cj_scene_destroy(scene);
    printf(
        "errors: NURBS without weights, weights on a bspline_surface, decreasing u knots, a zero "
        "weight, too few points, a wrong point count are refused naming the input\n");
}

int main(void) {
    test_gallery();
    test_errors();
    if (failures) {
        printf("%d failure(s)\n", failures);
        return 1;
    }
    printf("test_scene_bspline: all checks passed\n");
    return 0;
}

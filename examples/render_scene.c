/* Example: build a scene in code (no file), render it with the rasterizer and write a PNG.
 *     ./render_scene out.png
 * A sphere and a Bézier patch over a floor, lit by an ambient and a point light. */
#include <casteljau/image_io.h>
#include <casteljau/render.h>
#include <casteljau/scene.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void check(cj_status st, const char *what) {
    if (st != CJ_OK) {
        fprintf(stderr, "%s: %s (%s)\n", what, cj_last_error(), cj_status_str(st));
        exit(1);
    }
}

static int add_object(cj_scene *s, const cj_geometry *g, const cj_material *m) {
    int gi, mi, ni;
    check(cj_scene_add_geometry(s, g, &gi), "geometry"); /* the scene copies the geometry */
    check(cj_scene_add_material(s, m, &mi), "material");
    cj_node node = cj_node_defaults(gi, mi); /* no parent, identity transform, visible */
    check(cj_scene_add_node(s, &node, &ni), "node");
    return ni;
}

int main(int argc, char **argv) {
    const char *path = argc > 1 ? argv[1] : "scene.png";
    cj_scene *s = NULL;
    check(cj_scene_create(NULL, &s), "scene");

    cj_camera cam = cj_camera_defaults();
    cam.eye = (cj_vec3){0.0, 2.0, 6.0};
    cam.gaze = (cj_vec3){0.0, -1.6, -6.0}; /* towards (0, 0.4, 0) */
    check(cj_scene_set_camera(s, &cam), "camera");
    cj_scene_settings set = cj_scene_settings_defaults();
    set.width = 320;
    set.height = 240;
    set.spp = 4;
    set.background = cj_rgb_make(0.05, 0.06, 0.1);
    check(cj_scene_set_settings(s, &set), "settings");

    cj_light ambient = cj_light_defaults(CJ_LIGHT_AMBIENT);
    ambient.intensity = 0.3;
    cj_light key = cj_light_defaults(CJ_LIGHT_POINT);
    key.position = (cj_vec3){4.0, 6.0, 5.0};
    check(cj_scene_add_light(s, &ambient, NULL), "light");
    check(cj_scene_add_light(s, &key, NULL), "light");

    cj_geometry sphere;
    memset(&sphere, 0, sizeof sphere);
    sphere.kind = CJ_GEOM_SPHERE;
    sphere.u.sphere.center = (cj_vec3){-1.0, 0.8, 0.0};
    sphere.u.sphere.radius = 0.8;
    cj_material red = cj_material_defaults();
    red.color = cj_rgb_make(0.85, 0.15, 0.1);
    add_object(s, &sphere, &red);

    /* A bicubic patch: a bump, control point (i, j) at pts[3 * (4 * j + i)]. */
    double pts[48];
    for (int j = 0; j < 4; j++)
        for (int i = 0; i < 4; i++) {
            double *p = pts + 3 * (4 * j + i);
            p[0] = 0.2 + 0.6 * i;
            int inner = i > 0 && i < 3 && j > 0 && j < 3;
            p[1] = 0.3 + (inner ? 1.2 : 0.0);
            p[2] = 1.0 - 0.6 * j;
        }
    cj_patch patch = cj_patch_view(3, 3, pts, NULL);
    cj_geometry wave;
    memset(&wave, 0, sizeof wave);
    wave.kind = CJ_GEOM_PATCHES;
    wave.u.patches.count = 1;
    wave.u.patches.patches = &patch;
    cj_material blue = cj_material_defaults();
    blue.color = cj_rgb_make(0.2, 0.4, 0.9);
    blue.two_sided = 1; /* an open surface: both sides show */
    add_object(s, &wave, &blue);

    cj_geometry floor;
    memset(&floor, 0, sizeof floor);
    floor.kind = CJ_GEOM_PLANAR;
    check(cj_planar_patch_init(&floor.u.planar, (cj_vec3){-4, 0, 4}, (cj_vec3){8, 0, 0},
                               (cj_vec3){0, 0, -8}),
          "floor");
    cj_material grey = cj_material_defaults();
    grey.ks = 0.05;
    add_object(s, &floor, &grey);

    /* Render (linear float RGBA, bottom row first), convert once to 8-bit sRGB, write. */
    cj_render_options opt = cj_render_options_defaults(); /* all zero: the scene's settings */
    cj_render_image *img = NULL;
    check(cj_render_raster(s, &opt, 0, NULL, &img, NULL), "render");
    uint8_t *rgba = malloc((size_t)img->width * img->height * 4);
    if (!rgba) return 1;
    check(cj_render_image_to_srgb8(img, rgba, 0), "convert");
    /* Alpha is the coverage (0 on the background); make the picture opaque for viewers. */
    for (size_t i = 0; i < (size_t)img->width * img->height; i++) rgba[4 * i + 3] = 255;
    check(cj_image_write(path, img->width, img->height, rgba, 0), "write");
    printf("wrote %s (%d x %d, %zu objects)\n", path, img->width, img->height,
           cj_scene_node_count(s));
    free(rgba);
    cj_render_image_destroy(img);
    cj_scene_destroy(s);
    return 0;
}

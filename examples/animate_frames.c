/* Example: animate a scene built in code. A keyframe channel moves a sphere along x; each
 * frame poses the scene at its time, renders it (reusing tessellations through a render
 * cache) and writes PREFIX_NNN.png.
 *     ./animate_frames frames/ball 4     -> frames/ball_000.png ... frames/ball_003.png
 * For each frame it prints the time and where the sphere's pixels are (mean column), read
 * from the renderer's object-id plane. */
#include <casteljau/anim_scene.h>
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

static cj_scene *make_scene(void) {
    cj_scene *s = NULL;
    check(cj_scene_create(NULL, &s), "scene");
    cj_camera cam = cj_camera_defaults(); /* at (0, 0, 5) looking at the origin */
    check(cj_scene_set_camera(s, &cam), "camera");
    cj_scene_settings set = cj_scene_settings_defaults();
    set.width = 160;
    set.height = 120;
    check(cj_scene_set_settings(s, &set), "settings");
    cj_light key = cj_light_defaults(CJ_LIGHT_POINT);
    key.position = (cj_vec3){2.0, 3.0, 6.0};
    check(cj_scene_add_light(s, &key, NULL), "light");
    cj_geometry ball;
    memset(&ball, 0, sizeof ball);
    ball.kind = CJ_GEOM_SPHERE;
    ball.u.sphere.radius = 0.5;
    cj_material m = cj_material_defaults();
    m.color = cj_rgb_make(0.9, 0.6, 0.1);
    int gi, mi;
    check(cj_scene_add_geometry(s, &ball, &gi), "geometry");
    check(cj_scene_add_material(s, &m, &mi), "material");
    cj_node node = cj_node_defaults(gi, mi);
    node.name = "ball";
    check(cj_scene_add_node(s, &node, NULL), "node");
    return s;
}

int main(int argc, char **argv) {
    const char *prefix = argc > 1 ? argv[1] : "frame";
    int frames = argc > 2 ? atoi(argv[2]) : 4;
    if (frames < 2 || frames > 1000) {
        fprintf(stderr, "frames must be in 2..1000\n");
        return 2;
    }
    cj_scene *s = make_scene();

    /* Three keys on the ball's translation, interpolated by a Catmull-Rom spline. */
    const double times[] = {0.0, 0.5, 1.0};
    const double where[] = {-1.5, 0.0, 0.0, 0.0, 0.8, 0.0, 1.5, 0.0, 0.0};
    cj_channel_desc keys = cj_channel_desc_make(CJ_CHANNEL_VECTOR, CJ_INTERP_CATMULL_ROM, 3);
    keys.count = 3;
    keys.times = times;
    keys.values = where;
    cj_anim *anim = NULL;
    check(cj_anim_create(NULL, &anim), "animation");
    check(cj_anim_add(anim, "nodes[\"ball\"].translate", &keys), "channel");
    check(cj_anim_bind(anim, s), "bind");

    cj_render_cache *cache = NULL; /* lives across frames: unchanged meshes are reused */
    check(cj_render_cache_create(NULL, &cache), "cache");
    cj_render_options opt = cj_render_options_defaults();
    opt.cache = cache;
    for (int f = 0; f < frames; f++) {
        double t = (double)f / (frames - 1);
        check(cj_anim_pose(s, anim, t, NULL), "pose");
        cj_render_image *img = NULL;
        check(cj_render_raster(s, &opt, CJ_IMAGE_IDS, NULL, &img, NULL), "render");
        double sum = 0;
        long count = 0;
        for (int y = 0; y < img->height; y++)
            for (int x = 0; x < img->width; x++)
                if (img->ids[(size_t)y * img->width + x] != 0) {
                    sum += x;
                    count++;
                }
        uint8_t *rgba = malloc((size_t)img->width * img->height * 4);
        if (!rgba) return 1;
        check(cj_render_image_to_srgb8(img, rgba, 0), "convert");
        for (size_t i = 0; i < (size_t)img->width * img->height; i++) rgba[4 * i + 3] = 255;
        char path[4096];
        snprintf(path, sizeof path, "%s_%03d.png", prefix, f);
        check(cj_image_write(path, img->width, img->height, rgba, 0), "write");
        printf("frame %d t=%.3f ball pixels %ld mean column %.1f -> %s\n", f, t, count,
               count ? sum / count : -1.0, path);
        free(rgba);
        cj_render_image_destroy(img);
    }
    cj_render_cache_destroy(cache);
    cj_anim_destroy(anim);
    cj_scene_destroy(s);
    return 0;
}

/* The ray tracer's demo scene: the rasterizer's teapot on its checkered floor, with a mirror
 * sphere and a glass sphere. */
#include "casteljau/trace.h"

#include "render_internal.h"

#include <string.h>

cj_node cj_render_node(int geometry, int material);

cj_status cj_trace_demo_scene(const char *teapot_bpt, const cj_allocator *alloc, cj_scene **out) {
    cj_scene *s = NULL;
    cj_status st = cj_render_demo_scene(teapot_bpt, alloc, &s);
    if (st) return st;
    cj_camera cam = *cj_scene_camera(s);
    cam.eye = cj_v3(3.2, 4.6, 9.8);
    cam.gaze = cj_v3_sub(cj_v3(0.0, 0.9, 0), cam.eye);
    cam.fov_y = 40.0 * 3.14159265358979323846 / 180.0;
    cj_scene_settings set = *cj_scene_settings_get(s);
    set.spp = 1;
    set.max_depth = 6;
    set.background = cj_rgb_make(0.05, 0.06, 0.09);
    cj_material mirror = cj_material_default();
    mirror.color = cj_rgb_make(0.9, 0.9, 0.95);
    mirror.ka = 0.02;
    mirror.kd = 0.05;
    mirror.ks = 0.6;
    mirror.alpha = 200;
    mirror.mirror = 0.85;
    cj_material glass = cj_material_default();
    glass.color = cj_rgb_make(1, 1, 1);
    glass.ka = 0.0;
    glass.kd = 0.0;
    glass.ks = 0.8;
    glass.alpha = 300;
    glass.mirror = 0.08;
    glass.transmission = 0.9;
    glass.ior = 1.5;
    glass.receives_shadows = 0;
    cj_geometry g1, g2;
    memset(&g1, 0, sizeof g1);
    g1.kind = CJ_GEOM_SPHERE;
    g1.u.sphere.center = cj_v3(-3.1, 1.1, -0.6);
    g1.u.sphere.radius = 1.1;
    g2 = g1;
    g2.u.sphere.center = cj_v3(2.2, 0.85, 2.1);
    g2.u.sphere.radius = 0.85;
    int im = -1, ig = -1, i1 = -1, i2 = -1;
    st = cj_scene_set_camera(s, &cam);
    if (!st) st = cj_scene_set_settings(s, &set);
    if (!st) st = cj_scene_add_material(s, &mirror, &im);
    if (!st) st = cj_scene_add_material(s, &glass, &ig);
    if (!st) st = cj_scene_add_geometry(s, &g1, &i1);
    if (!st) st = cj_scene_add_geometry(s, &g2, &i2);
    cj_node n1 = cj_render_node(i1, im), n2 = cj_render_node(i2, ig);
    n1.name = "mirror sphere";
    n2.name = "glass sphere";
    if (!st) st = cj_scene_add_node(s, &n1, NULL);
    if (!st) st = cj_scene_add_node(s, &n2, NULL);
    if (st) {
        cj_scene_destroy(s);
        return st;
    }
    *out = s;
    return CJ_OK;
}

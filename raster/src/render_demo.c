/* The built-in demo scene: the Utah teapot, lit, with a procedural checker and its control
 * net, on a checkered floor (casteljau render --demo, the bench, the docs). */
#include "render_internal.h"

#include "casteljau/patchset.h"
#include "error_internal.h"

#include <math.h>
#include <string.h>

cj_node cj_render_node(int geometry, int material) {
    cj_node n;
    memset(&n, 0, sizeof n);
    n.parent = -1;
    n.local = cj_transform_identity();
    n.geometry = geometry;
    n.material = material;
    n.overlay.color = cj_rgb_make(1, 1, 1);
    n.overlay.iso_count = 1;
    n.overlay.normal_length = 0.1;
    n.visible = 1;
    return n;
}

cj_status cj_render_demo_scene(const char *teapot_bpt, const cj_allocator *alloc, cj_scene **out) {
    cj_patchset *set = NULL;
    cj_status st = cj_patchset_load_bpt(teapot_bpt, alloc, &set);
    if (st) return st;
    cj_scene *s = NULL;
    st = cj_scene_create(alloc, &s);
    if (st) {
        cj_patchset_destroy(set);
        return st;
    }
    cj_camera cam = cj_camera_default();
    cam.eye = cj_v3(5.2, 3.4, 8.4);
    cam.gaze = cj_v3_sub(cj_v3(0.15, 1.05, 0), cam.eye);
    cam.up = cj_v3(0, 1, 0);
    cam.fov_y = 36.0 * 3.14159265358979323846 / 180.0;
    cam.near = -0.5;
    cam.far = -60.0;
    cj_scene_settings set_ = cj_scene_settings_default();
    set_.width = 800;
    set_.height = 600;
    set_.spp = 4;
    set_.background = cj_rgb_make(0.012, 0.014, 0.02);
    int i_tex = -1, i_floor_tex = -1, i_mat = -1, i_floor_mat = -1, i_geo = -1, i_floor = -1;
    cj_light amb = cj_light_default(CJ_LIGHT_AMBIENT), key = cj_light_default(CJ_LIGHT_POINT),
             fill = cj_light_default(CJ_LIGHT_DIRECTIONAL);
    amb.intensity = 0.25;
    key.position = cj_v3(6, 9, 6);
    key.intensity = 0.95;
    fill.direction = cj_v3(1, -0.4, 0.6);
    fill.intensity = 0.35;
    fill.color = cj_rgb_make(0.75, 0.85, 1.0);
    cj_texture tex = cj_texture_default(CJ_TEX_CHECKER);
    tex.filter = CJ_TEX_BILINEAR;
    tex.checks_u = 4;
    tex.checks_v = 4;
    tex.checker_a = cj_rgb_make(0.92, 0.86, 0.72);
    tex.checker_b = cj_rgb_make(0.70, 0.12, 0.08);
    cj_texture ftex = cj_texture_default(CJ_TEX_CHECKER);
    ftex.filter = CJ_TEX_BILINEAR;
    ftex.checks_u = 12;
    ftex.checks_v = 12;
    ftex.checker_a = cj_rgb_make(0.55, 0.55, 0.58);
    ftex.checker_b = cj_rgb_make(0.18, 0.18, 0.2);
    cj_material pot = cj_material_default();
    pot.color = cj_rgb_make(1, 1, 1);
    pot.ka = 0.35;
    pot.kd = 0.75;
    pot.ks = 0.45;
    pot.alpha = 48;
    pot.two_sided = 1; /* the teapot's patch set is open (the lid and spout show inside) */
    cj_material floor = cj_material_default();
    floor.color = cj_rgb_make(1, 1, 1);
    floor.ka = 0.3;
    floor.kd = 0.7;
    floor.ks = 0.1;
    floor.alpha = 8;
    cj_geometry g;
    memset(&g, 0, sizeof g);
    g.kind = CJ_GEOM_PATCHES;
    g.u.patches.count = set->count;
    g.u.patches.patches = set->patches;
    cj_geometry fg;
    memset(&fg, 0, sizeof fg);
    fg.kind = CJ_GEOM_PLANAR;
    st = cj_planar_patch_init(&fg.u.planar, cj_v3(-7, 0, 7), cj_v3(14, 0, 0), cj_v3(0, 0, -14));
    if (!st) st = cj_scene_set_camera(s, &cam);
    if (!st) st = cj_scene_set_settings(s, &set_);
    if (!st) st = cj_scene_add_light(s, &amb, NULL);
    if (!st) st = cj_scene_add_light(s, &key, NULL);
    if (!st) st = cj_scene_add_light(s, &fill, NULL);
    if (!st) st = cj_scene_add_texture(s, &tex, &i_tex);
    if (!st) st = cj_scene_add_texture(s, &ftex, &i_floor_tex);
    pot.texture = i_tex;
    floor.texture = i_floor_tex;
    if (!st) st = cj_scene_add_material(s, &pot, &i_mat);
    if (!st) st = cj_scene_add_material(s, &floor, &i_floor_mat);
    if (!st) st = cj_scene_add_geometry(s, &g, &i_geo);
    if (!st) st = cj_scene_add_geometry(s, &fg, &i_floor);
    cj_node n = cj_render_node(i_geo, i_mat);
    n.name = "teapot";
    /* the .bpt teapot stands on z = 0 with z up: turn it to y up */
    n.local.rotation[0] = cos(-0.25 * 3.14159265358979323846);
    n.local.rotation[1] = sin(-0.25 * 3.14159265358979323846);
    n.overlay.flags = CJ_OVERLAY_CONTROL_NET;
    n.overlay.color = cj_rgb_make(1.0, 0.75, 0.15);
    if (!st) st = cj_scene_add_node(s, &n, NULL);
    cj_node fn = cj_render_node(i_floor, i_floor_mat);
    fn.name = "floor";
    if (!st) st = cj_scene_add_node(s, &fn, NULL);
    cj_patchset_destroy(set);
    if (st) {
        cj_scene_destroy(s);
        return st;
    }
    *out = s;
    return CJ_OK;
}

#include "light_floor.h"

#include <stdio.h>
#include <string.h>

cj_scene *cj_test_light_floor(int w, int h, double half, double floor_z, double cam_z, double rho,
                              cj_light_model model) {
    cj_scene *s = NULL;
    if (cj_scene_create(NULL, &s)) goto fail;
    cj_camera cam = cj_camera_defaults();
    cam.projection = CJ_PROJ_ORTHOGRAPHIC;
    cam.ortho_height = 2 * half;
    cam.eye = cj_v3(0, 0, cam_z);
    cam.gaze = cj_v3(0, 0, -1);
    cam.up = cj_v3(0, 1, 0);
    cj_scene_settings st = cj_scene_settings_defaults();
    st.width = w;
    st.height = h;
    st.spp = 1;
    st.light_model = model;
    cj_material m = cj_material_defaults();
    m.color = cj_rgb_make(rho, rho, rho);
    m.ka = 0.0;
    m.kd = 1.0;
    m.ks = 0.0;
    m.two_sided = 1;
    int mi, gi;
    cj_geometry g;
    memset(&g, 0, sizeof g);
    g.kind = CJ_GEOM_PLANAR;
    if (cj_scene_set_camera(s, &cam) || cj_scene_set_settings(s, &st) ||
        cj_scene_add_material(s, &m, &mi) ||
        cj_planar_patch_init(&g.u.planar, cj_v3(-half, -half, floor_z), cj_v3(2 * half, 0, 0),
                             cj_v3(0, 2 * half, 0)) ||
        cj_scene_add_geometry(s, &g, &gi))
        goto fail;
    const cj_node n = cj_node_defaults(gi, mi);
    if (cj_scene_add_node(s, &n, NULL)) goto fail;
    return s;
fail:
    printf("cj_test_light_floor: %s\n", cj_last_error());
    cj_scene_destroy(s);
    return NULL;
}

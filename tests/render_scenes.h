/* Scenes built from code for the renderer tests (test_render_*.c). */
#ifndef CJ_TEST_RENDER_SCENES_H
#define CJ_TEST_RENDER_SCENES_H

#include "casteljau/render.h"
#include "casteljau/scene.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct rs_sphere_scene {
    cj_scene *s;
    int mat, node, geo;
} rs_sphere_scene;

static inline void rs_check(cj_status st) {
    if (st) {
        fprintf(stderr, "scene building failed: %s\n", cj_last_error());
        abort();
    }
}

/* A unit sphere at the origin seen from (0, 0, 5), 40° field of view; lit: an ambient, a point
 * and a directional light. */
static inline void rs_sphere(rs_sphere_scene *sc, int lit) {
    rs_check(cj_scene_create(NULL, &sc->s));
    cj_camera cam = cj_camera_defaults();
    cam.fov_y = 40.0 * 3.14159265358979323846 / 180.0;
    rs_check(cj_scene_set_camera(sc->s, &cam));
    cj_material m = cj_material_defaults();
    m.color = cj_rgb_make(0.8, 0.5, 0.3);
    rs_check(cj_scene_add_material(sc->s, &m, &sc->mat));
    cj_geometry g;
    memset(&g, 0, sizeof g);
    g.kind = CJ_GEOM_SPHERE;
    g.u.sphere.radius = 1.0;
    rs_check(cj_scene_add_geometry(sc->s, &g, &sc->geo));
    cj_node n = cj_node_defaults(sc->geo, sc->mat);
    rs_check(cj_scene_add_node(sc->s, &n, &sc->node));
    if (lit) {
        cj_light a = cj_light_defaults(CJ_LIGHT_AMBIENT);
        a.intensity = 0.2;
        cj_light p = cj_light_defaults(CJ_LIGHT_POINT);
        p.position = cj_v3(3, 4, 5);
        p.intensity = 0.8;
        cj_light d = cj_light_defaults(CJ_LIGHT_DIRECTIONAL);
        d.direction = cj_v3(1, 0.5, -1);
        d.intensity = 0.4;
        d.color = cj_rgb_make(0.6, 0.7, 1.0);
        rs_check(cj_scene_add_light(sc->s, &a, NULL));
        rs_check(cj_scene_add_light(sc->s, &p, NULL));
        rs_check(cj_scene_add_light(sc->s, &d, NULL));
    }
}

/* A bicubic patch (a gently curved square of side 2 at depth z) as an object; returns its node. */
static inline int rs_add_patch_quad(cj_scene *s, int mat, double z, unsigned overlay) {
    double pts[16 * 3];
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i) {
            double x = -1.0 + 2.0 * i / 3.0, y = -1.0 + 2.0 * j / 3.0;
            pts[3 * (j * 4 + i)] = x;
            pts[3 * (j * 4 + i) + 1] = y;
            pts[3 * (j * 4 + i) + 2] = z + 0.3 * (1.0 - x * x);
        }
    cj_patch p = cj_patch_view(3, 3, pts, NULL);
    cj_geometry g;
    memset(&g, 0, sizeof g);
    g.kind = CJ_GEOM_PATCHES;
    g.u.patches.count = 1;
    g.u.patches.patches = &p;
    int gi, ni;
    rs_check(cj_scene_add_geometry(s, &g, &gi));
    cj_node n = cj_node_defaults(gi, mat);
    n.overlay.flags = overlay;
    n.overlay.color = cj_rgb_make(1, 1, 0);
    n.overlay.iso_count = 4;
    rs_check(cj_scene_add_node(s, &n, &ni));
    return ni;
}

/* A cubic Bézier curve across the view at depth z (green). */
static inline int rs_add_curve(cj_scene *s, int mat, double z) {
    double pts[12] = {-2, -0.5, z, -1, 1.5, z, 1, -1.5, z, 2, 0.5, z};
    cj_geometry g;
    memset(&g, 0, sizeof g);
    g.kind = CJ_GEOM_CURVE;
    g.u.curve.kind = CJ_CURVE_BEZIER;
    g.u.curve.degree = 3;
    g.u.curve.count = 4;
    g.u.curve.pts = pts;
    g.u.curve.width_px = 1.0;
    g.u.curve.color = cj_rgb_make(0.1, 1.0, 0.2);
    int gi, ni;
    rs_check(cj_scene_add_geometry(s, &g, &gi));
    cj_node n = cj_node_defaults(gi, mat);
    n.overlay.flags = CJ_OVERLAY_CONTROL_NET;
    rs_check(cj_scene_add_node(s, &n, &ni));
    return ni;
}

/* Every feature at once: lit textured Phong sphere, flat torus, Gouraud cylinder, a
 * transparent patch in front with its control net and iso lines, a curve, a background. */
static inline cj_scene *rs_feature_scene(void) {
    rs_sphere_scene sc;
    rs_sphere(&sc, 1);
    cj_texture ck = cj_texture_defaults(CJ_TEX_CHECKER);
    ck.filter = CJ_TEX_BILINEAR;
    ck.checks_u = 8;
    ck.checks_v = 4;
    int ti, mflat, mg, mt;
    rs_check(cj_scene_add_texture(sc.s, &ck, &ti));
    cj_scene_material_mut(sc.s, sc.mat)->texture = ti;
    cj_material m = cj_material_defaults();
    m.shading = CJ_SHADE_FLAT;
    m.color = cj_rgb_make(0.2, 0.6, 0.9);
    rs_check(cj_scene_add_material(sc.s, &m, &mflat));
    m.shading = CJ_SHADE_GOURAUD;
    m.color = cj_rgb_make(0.9, 0.9, 0.2);
    rs_check(cj_scene_add_material(sc.s, &m, &mg));
    m.shading = CJ_SHADE_PHONG;
    m.opacity = 0.45;
    m.two_sided = 1;
    m.color = cj_rgb_make(0.3, 0.9, 0.4);
    rs_check(cj_scene_add_material(sc.s, &m, &mt));
    cj_geometry g;
    memset(&g, 0, sizeof g);
    g.kind = CJ_GEOM_TORUS;
    rs_check(cj_torus_init(&g.u.torus, cj_v3(-1.6, -0.8, -1), cj_v3(0.3, 1, 0.2), 0.8, 0.25));
    int gi;
    rs_check(cj_scene_add_geometry(sc.s, &g, &gi));
    cj_node n = cj_node_defaults(gi, mflat);
    n.overlay.flags = CJ_OVERLAY_NORMALS | CJ_OVERLAY_ISO_LINES;
    n.overlay.normal_length = 0.15;
    n.overlay.iso_count = 6;
    rs_check(cj_scene_add_node(sc.s, &n, NULL));
    memset(&g, 0, sizeof g);
    g.kind = CJ_GEOM_CYLINDER;
    rs_check(
        cj_cylinder_init(&g.u.cylinder, cj_v3(1.7, -1, -0.5), cj_v3(0.2, 1, 0.1), 0.4, 0, 1.6));
    rs_check(cj_scene_add_geometry(sc.s, &g, &gi));
    n = cj_node_defaults(gi, mg);
    n.overlay.flags = CJ_OVERLAY_WIREFRAME;
    rs_check(cj_scene_add_node(sc.s, &n, NULL));
    rs_add_patch_quad(sc.s, mt, 1.2, CJ_OVERLAY_CONTROL_NET | CJ_OVERLAY_ISO_LINES);
    int cn = rs_add_curve(sc.s, sc.mat, 0.5);
    cj_scene_geometry_mut(sc.s, cj_scene_node(sc.s, cn)->geometry)->u.curve.width_px = 3.0;
    cj_scene_settings set = cj_scene_settings_defaults();
    set.background = cj_rgb_make(0.05, 0.05, 0.1);
    rs_check(cj_scene_set_settings(sc.s, &set));
    return sc.s;
}

#endif

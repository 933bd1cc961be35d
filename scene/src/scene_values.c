/* The scene's plain values: the defaults of each part (cj_<type>_defaults) and the local
 * transform's matrix. No scene object here: scene.c holds it. */
#include "scene_internal.h"

#include <assert.h>
#include <math.h>
#include <string.h>

/* ---- defaults ------------------------------------------------------------------------------ */

cj_light cj_light_defaults(cj_light_kind kind) {
    cj_light l;
    memset(&l, 0, sizeof l);
    l.kind = kind;
    l.color = cj_rgb_make(1, 1, 1);
    l.intensity = 1.0;
    l.position = cj_v3(5, 5, 5);
    l.direction = cj_v3(-1, -1, -1);
    l.spot_angle = 0.5235987755982988; /* 30 degrees */
    l.spot_exponent = 0.0;
    l.edge_u = cj_v3(1, 0, 0);
    l.edge_v = cj_v3(0, 0, 1);
    l.radius = 0.5;
    l.casts_shadows = 1;
    return l;
}

cj_texture cj_texture_defaults(cj_texture_kind kind) {
    cj_texture t;
    memset(&t, 0, sizeof t);
    t.kind = kind;
    t.filter = CJ_TEX_BILINEAR;
    t.wrap = CJ_TEX_REPEAT;
    t.scale_u = t.scale_v = 1.0;
    t.checks_u = t.checks_v = 8;
    t.checker_a = cj_rgb_make(0.9, 0.9, 0.9);
    t.checker_b = cj_rgb_make(0.1, 0.1, 0.1);
    return t;
}

cj_material cj_material_defaults(void) {
    cj_material m;
    memset(&m, 0, sizeof m);
    m.color = cj_rgb_make(0.8, 0.8, 0.8);
    m.specular = cj_rgb_make(1, 1, 1);
    m.ka = 0.1;
    m.kd = 0.7;
    m.ks = 0.3;
    m.alpha = 32.0;
    m.shading = CJ_SHADE_PHONG;
    m.two_sided = 0;
    m.texture = -1;
    m.opacity = 1.0;
    m.ior = 1.5;
    m.receives_shadows = 1;
    return m;
}

cj_scene_settings cj_scene_settings_defaults(void) {
    cj_scene_settings s;
    memset(&s, 0, sizeof s);
    s.width = 640;
    s.height = 480;
    s.spp = 1;
    s.tol_px = 0.25;
    s.background = cj_rgb_make(0, 0, 0);
    s.max_depth = 5;
    s.seed = 1;
    return s;
}

/* ---- transforms ---------------------------------------------------------------------------- */

cj_transform cj_transform_identity(void) {
    cj_transform t;
    t.translate = cj_v3(0, 0, 0);
    t.rotation[0] = 1.0;
    t.rotation[1] = t.rotation[2] = t.rotation[3] = 0.0;
    t.scale = cj_v3(1, 1, 1);
    t.matrix = cj_xform3_identity();
    return t;
}

void cj_quat_to_matrix_(const double q[4], double r[3][3]) {
    const double w = q[0], x = q[1], y = q[2], z = q[3];
    r[0][0] = 1 - 2 * (y * y + z * z);
    r[0][1] = 2 * (x * y - w * z);
    r[0][2] = 2 * (x * z + w * y);
    r[1][0] = 2 * (x * y + w * z);
    r[1][1] = 1 - 2 * (x * x + z * z);
    r[1][2] = 2 * (y * z - w * x);
    r[2][0] = 2 * (x * z - w * y);
    r[2][1] = 2 * (y * z + w * x);
    r[2][2] = 1 - 2 * (x * x + y * y);
}

cj_xform3 cj_transform_matrix(const cj_transform *t) {
    assert(t != NULL);
    double r[3][3];
    cj_quat_to_matrix_(t->rotation, r);
    /* T·R·S as one affine matrix: columns of R scaled by S, translation in the last column. */
    cj_xform3 trs = cj_xform3_identity();
    const double s[3] = {t->scale.x, t->scale.y, t->scale.z};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) trs.m[i][j] = r[i][j] * s[j];
    trs.m[0][3] = t->translate.x;
    trs.m[1][3] = t->translate.y;
    trs.m[2][3] = t->translate.z;
    return cj_xform3_compose(&trs, &t->matrix);
}

cj_node cj_node_defaults(int geometry, int material) {
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

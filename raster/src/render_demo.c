/* The built-in demo scene: the Utah teapot, lit, with a procedural checker and its control
 * net, on a checkered floor (casteljau render --demo, the bench, the docs), described by
 * scenes/demo_render.json, embedded at build time. */
#include "demo_scenes_internal.h"
#include "render_internal.h"

#include "casteljau/scene_json.h"

#include <string.h>

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

cj_status cj_render_demo_scene(const char *teapot_bpt, const cj_allocator *alloc, cj_scene **out) {
    const cj_scene_json_options o = {teapot_bpt};
    return cj_scene_parse_json_with_options(cj_demo_render_json, "scenes/demo_render.json", NULL,
                                            &o, alloc, out);
}

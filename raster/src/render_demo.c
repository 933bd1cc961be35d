/* The built-in demo scene: the Utah teapot, lit, with a procedural checker and its control
 * net, on a checkered floor (casteljau render --demo, the bench, the docs), described by
 * scenes/demo_render.json, embedded at build time. */
#include "demo_scenes_internal.h"
#include "render_internal.h"

#include "casteljau/scene_json.h"

#include <string.h>

cj_status cj_render_demo_scene(const char *teapot_bpt, const cj_allocator *alloc, cj_scene **out) {
    const cj_scene_json_options o = {teapot_bpt};
    return cj_scene_parse_json_with_options(cj_demo_render_json, "scenes/demo_render.json", NULL,
                                            &o, alloc, out);
}

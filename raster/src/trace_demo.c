/* The ray tracer's demo scene: the rasterizer's teapot on its checkered floor, with a mirror
 * sphere and a glass sphere, described by scenes/demo_trace.json, embedded at build time. */
#include "casteljau/trace.h"

#include "demo_scenes_internal.h"

#include "casteljau/scene_json.h"

cj_status cj_trace_demo_scene(const char *teapot_bpt, const cj_allocator *alloc, cj_scene **out) {
    const cj_scene_json_options o = {teapot_bpt};
    return cj_scene_parse_json_with_options(cj_demo_trace_json, "scenes/demo_trace.json", NULL, &o,
                                            alloc, out);
}

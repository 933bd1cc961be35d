/* The shipped demo scenes, embedded at build time (raster/CMakeLists.txt generates the arrays
 * from scenes/demo_render.json and scenes/demo_trace.json): NUL-terminated JSON text for
 * cj_scene_parse_json_with_options, geometry "teapot" resolved by the caller's teapot path. */
#ifndef CASTELJAU_RASTER_DEMO_SCENES_INTERNAL_H
#define CASTELJAU_RASTER_DEMO_SCENES_INTERNAL_H

extern const char cj_demo_render_json[]; /* render --demo: the checkered teapot on its floor */
extern const char cj_demo_trace_json[];  /* trace --demo: the same with a mirror and a glass ball */

#endif

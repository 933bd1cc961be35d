# The public names settled by issue 26 ("one grammar"): cj_<module>_<verb>, where the module is
# the header's name. Applied by scripts/apply-renames.sh to every tracked source and document.
# Whole-word rules (\b), and no new name is an old one, so running it again changes nothing.
#
# line.h (lines, strokes, fills drawn into a framebuffer): module "line", not "raster".
s/\bcj_raster_rect_of\b/cj_line_rect_of/g
s/\bcj_raster_rect\b/cj_line_rect/g
s/\bcj_raster_pixel_fn\b/cj_line_pixel_fn/g
s/\bcj_raster_cover_fn\b/cj_line_cover_fn/g
s/\bcj_raster_line_visit_d\b/cj_line_visit_d/g
s/\bcj_raster_line_visit\b/cj_line_visit/g
s/\bcj_raster_line_aa_visit\b/cj_line_aa_visit/g
s/\bcj_raster_line_aa\b/cj_line_draw_aa/g
s/\bcj_raster_line_d\b/cj_line_draw_d/g
s/\bcj_raster_line\b/cj_line_draw/g
s/\bcj_raster_join\b/cj_line_join/g
s/\bcj_raster_cap\b/cj_line_cap/g
s/\bcj_raster_stroke_default\b/cj_line_stroke_defaults/g
s/\bcj_raster_stroke_polyline_visit\b/cj_line_stroke_polyline_visit/g
s/\bcj_raster_stroke_polyline\b/cj_line_stroke_polyline/g
s/\bcj_raster_stroke_work_size\b/cj_line_stroke_work_size/g
s/\bcj_raster_stroke_bezier\b/cj_line_stroke_bezier/g
s/\bcj_raster_stroke_rbezier\b/cj_line_stroke_rbezier/g
s/\bcj_raster_stroke_sequence\b/cj_line_stroke_sequence/g
s/\bcj_raster_stroke\b/cj_line_stroke/g
s/\bcj_raster_fill_convex\b/cj_line_fill_convex/g
# (the family as documents name it)
s/\bcj_raster_stroke_\*/cj_line_stroke_*/g
s/\bcj_raster_fill_disc\b/cj_line_fill_disc/g
s/\bCJ_RASTER_COORD_MAX\b/CJ_LINE_COORD_MAX/g
s/\bCJ_RASTER_MAX_WIDTH\b/CJ_LINE_MAX_WIDTH/g
s/\bCJ_RASTER_DEFAULT_TOL\b/CJ_LINE_DEFAULT_TOL/g
#
# A value of a type filled with its documented defaults: cj_<type>_defaults (as
# cj_flatten_defaults, cj_spline_defaults, cj_plot_bezier_defaults already were).
# (cj_font_find_default keeps its name: it finds the default font, a verb and its object.)
s/\bcj_camera_default\b/cj_camera_defaults/g
s/\bcj_emitter_default\b/cj_emitter_defaults/g
s/\bcj_light_default\b/cj_light_defaults/g
s/\bcj_material_default\b/cj_material_defaults/g
s/\bcj_texture_default\b/cj_texture_defaults/g
s/\bcj_render_options_default\b/cj_render_options_defaults/g
s/\bcj_renderer_options_default\b/cj_renderer_options_defaults/g
s/\bcj_scene_settings_default\b/cj_scene_settings_defaults/g
# A node with the defaults every builder wants lives in the scene layer, beside the others.
s/\bcj_render_node\b/cj_node_defaults/g
#
# No "_ex": the variant says what it adds.
s/\bcj_scene_parse_json_ex\b/cj_scene_parse_json_with_options/g
s/\bcj_scene_load_json_ex\b/cj_scene_load_json_with_options/g
s/\bcj_render_trace_ex\b/cj_render_trace_with_options/g
s/\bcj_image_write_float_ex\b/cj_image_write_float_with_flags/g
#
# A scene's single parts are read and written by cj_scene_get_<part> / cj_scene_set_<part>
# (cj_scene_settings is the type, so the getter cannot be the bare noun).
s/\bcj_scene_settings_get\b/cj_scene_get_settings/g
s/\bcj_scene_camera\b/cj_scene_get_camera/g
# (and the renderer's options beside cj_renderer_set_options)
s/\bcj_renderer_options_get\b/cj_renderer_get_options/g
#
# Private names whose function moved to its own layer (rerun after merging others' callers):
# the figures of a stage are the stage report's (scene/), not the rasterizer's.
s/\bcj_rframe_figures\b/cj_stage_report_figures/g
#
# The tracer's two helpers a test calls are exported under the library's prefix now that the
# shared libraries export cj_ symbols only (issue 25).
s/\btr_permute\b/cj_trace_permute/g
s/\btr_mix\b/cj_trace_mix/g
#
# formats/ is a shared library like the others and exports cj_ symbols only (issue 25): its
# readers and writers take the prefix (types too; a file name such as plot_json_curve.c keeps
# its name, hence the guard on a following dot).
s/\bplot_doc(_free|_render|_where)?\b([^.]|$)/cj_plot_doc\1\2/g
s/\bplot_json_(parse|curve_add|page_free|read_page|write_page|print_fit|page|curve)\b([^.]|$)/cj_plot_json_\1\2/g
s/\bbsp_json(_find|_free|_item|_parse|_view)?\b([^.]|$)/cj_bsp_json\1\2/g
s/\bchart_json_parse\b([^.]|$)/cj_chart_json_parse\1/g
#
# One monotonic clock: the tool's own wrapper went (cli_progress.h includes clock_internal.h).
s/\bcli_now\(\)/cj_clock_seconds()/g

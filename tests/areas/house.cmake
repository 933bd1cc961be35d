# The one writer of the plot format (formats/) and the JSON writing kit (scene/src/json_write.c):
# shortest exact numbers against a brute-force oracle, page round trip bit-identical.
if(TARGET cj::formats)
  cj_add_test(test_plot_json_write SOURCES formats/test_plot_json_write.c LIBS cj::formats)
  target_include_directories(test_plot_json_write PRIVATE ${PROJECT_SOURCE_DIR}/scene/src
    ${PROJECT_SOURCE_DIR}/curves/src)
  # The surface document and the scene's B-spline surface geometry: one reader, same messages.
  cj_add_test(test_surface_json SOURCES formats/test_surface_json.c LIBS cj::formats)
endif()
# The one visibility walk up the parent chain (scene layer), against its definition.
cj_add_test(test_scene_shown SOURCES scene/test_scene_shown.c LIBS cj::scene)

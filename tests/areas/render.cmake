# The rasterizer pipeline (issue 8: shading, textures, transparency, overlays, "only the effects
# the scene calls for") and `casteljau render`. Scenes are built in code (tests/render_scenes.h).
cj_add_test(test_render_stages SOURCES test_render_stages.c LIBS cj::raster cj::scene)
target_include_directories(test_render_stages PRIVATE ${CMAKE_CURRENT_SOURCE_DIR})
# CLI contract of `casteljau render` (needs the tool's image output, i.e. OpenImageIO).
if(CJ_WITH_OIIO AND TARGET cj::viz)
  cj_add_test(test_cli_render SOURCES test_cli_render.c)
  target_compile_definitions(test_cli_render PRIVATE CJ_CLI="$<TARGET_FILE:casteljau>"
    CJ_SCENES_DIR="${PROJECT_SOURCE_DIR}/scenes")
  add_dependencies(test_cli_render casteljau)
endif()
# Texture sampling (private to raster/: raster/src/texture_internal.h).
cj_add_test(test_render_texture SOURCES test_render_texture.c LIBS cj::raster cj::scene)
target_include_directories(test_render_texture PRIVATE ${PROJECT_SOURCE_DIR}/raster/src)
# Shading, silhouettes, transparency order and the tessellation bound against exact references.
cj_add_test(test_render_shading SOURCES test_render_shading.c LIBS cj::raster cj::scene)
target_include_directories(test_render_shading PRIVATE ${CMAKE_CURRENT_SOURCE_DIR})
# Progress reports and cancellation through cj_render_options.progress, both back ends.
cj_add_test(test_render_progress SOURCES test_render_progress.c LIBS cj::raster cj::scene)
target_include_directories(test_render_progress PRIVATE ${CMAKE_CURRENT_SOURCE_DIR})

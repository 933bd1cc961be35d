# The rasterizer pipeline (issue 8: shading, textures, transparency, overlays, "only the effects
# the scene calls for") and `casteljau render`. Scenes are built in code (tests/render_scenes.h).
cj_add_test(test_render_stages SOURCES test_render_stages.c LIBS cj::raster cj::scene)
target_include_directories(test_render_stages PRIVATE ${CMAKE_CURRENT_SOURCE_DIR})

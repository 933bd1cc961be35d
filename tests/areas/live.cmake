# The renderer object (issue 19, "Live": casteljau/renderer.h): reused across frames, images
# bit-identical to the one-shot calls for any thread count and after scene edits.
if(TARGET cj::raster)
  cj_add_test(test_renderer SOURCES test_renderer.c LIBS cj::raster cj::scene)
  target_include_directories(test_renderer PRIVATE ${CMAKE_CURRENT_SOURCE_DIR})
  target_compile_definitions(test_renderer PRIVATE CJ_TEAPOT_PATH="${PROJECT_SOURCE_DIR}/data/teapot.bpt")
endif()

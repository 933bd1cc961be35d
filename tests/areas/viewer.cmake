# The viewer `casteljau view` (issue 11). The editor models need no window; the window tests
# run the real program under a private Xvfb (Mesa llvmpipe) and compare its back buffer with
# the offline `casteljau plot` / `casteljau render` of the saved state.
if(TARGET cj::viz AND TARGET cj::scene AND TARGET cj::raster)
  cj_add_test(test_viewer_model SOURCES viewer/test_viewer_model.c
    LIBS cj::viz cj::raster cj::scene cj::surfaces)
endif()
if(CJ_HAVE_VIEWER AND TARGET casteljau)
  cj_add_test(test_viewer_window SOURCES viewer/test_viewer_window.c support/xvfb.c
    support/png_diff.c
    LIBS cj::viz cj::raster cj::scene cj::surfaces)
  target_include_directories(test_viewer_window PRIVATE ${CMAKE_CURRENT_SOURCE_DIR})
  target_compile_definitions(test_viewer_window PRIVATE CJ_CLI="$<TARGET_FILE:casteljau>"
    CJ_TEAPOT_PATH="${PROJECT_SOURCE_DIR}/data/teapot.bpt"
    CJ_ANIM_PATH="${PROJECT_SOURCE_DIR}/scenes/anim_flyby.json"
    CJ_BSPLINES_PATH="${PROJECT_SOURCE_DIR}/scenes/bsplines.json")
  add_dependencies(test_viewer_window casteljau)
  # ~10 s of CPU in RelWithDebInfo; the sanitizer build on a busy machine needs the margin
  set_tests_properties(test_viewer_window PROPERTIES TIMEOUT 900)
endif()
# Shared corners: linked moves of the teapot's coincident control points keep it watertight.
if(TARGET cj::viz AND TARGET cj::scene AND TARGET cj::raster)
  cj_add_test(test_viewer_shared SOURCES viewer/test_viewer_shared.c
    LIBS cj::viz cj::raster cj::scene cj::surfaces)
  target_compile_definitions(test_viewer_shared PRIVATE
    CJ_TEAPOT_PATH="${PROJECT_SOURCE_DIR}/data/teapot.bpt")
endif()
# Real X input (xdotool) and the window's pixels read back from the X server: keys redraw, a
# ray-traced pass is interrupted by a key, traced passes equal `casteljau trace`.
if(CJ_HAVE_VIEWER AND TARGET casteljau)
  find_package(X11 REQUIRED)
  cj_add_test(test_viewer_live SOURCES viewer/test_viewer_live.c support/xvfb.c support/timeline.c
    support/png_diff.c
    LIBS cj::viz X11::X11)
  target_include_directories(test_viewer_live PRIVATE ${CMAKE_CURRENT_SOURCE_DIR})
  target_compile_definitions(test_viewer_live PRIVATE CJ_CLI="$<TARGET_FILE:casteljau>")
  add_dependencies(test_viewer_live casteljau)
  set_tests_properties(test_viewer_live PROPERTIES TIMEOUT 900)
endif()
# The viewer as a module opened only by `view`: the program links no graphics library, and a
# missing or broken module is a clear error.
if(CJ_HAVE_VIEWER AND TARGET casteljau)
  cj_add_test(test_viewer_module SOURCES viewer/test_viewer_module.c)
  target_include_directories(test_viewer_module PRIVATE ${CMAKE_CURRENT_SOURCE_DIR})
  target_compile_definitions(test_viewer_module PRIVATE CJ_CLI="$<TARGET_FILE:casteljau>")
  add_dependencies(test_viewer_module casteljau)
endif()
# A real mouse drag of a teapot control point (xdotool): drag frames still tessellating give way
# to newer drag states (never two in a row), and the still view equals `casteljau render`.
if(CJ_HAVE_VIEWER AND TARGET casteljau)
  find_package(X11 REQUIRED)
  cj_add_test(test_viewer_drag SOURCES viewer/test_viewer_drag.c support/xvfb.c support/timeline.c
    LIBS cj::viz cj::raster cj::scene cj::surfaces X11::X11)
  target_include_directories(test_viewer_drag PRIVATE ${CMAKE_CURRENT_SOURCE_DIR})
  target_compile_definitions(test_viewer_drag PRIVATE CJ_CLI="$<TARGET_FILE:casteljau>"
    CJ_TEAPOT_PATH="${PROJECT_SOURCE_DIR}/data/teapot.bpt")
  add_dependencies(test_viewer_drag casteljau)
  set_tests_properties(test_viewer_drag PROPERTIES TIMEOUT 600)
endif()

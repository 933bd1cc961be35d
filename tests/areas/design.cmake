# The designer's viewer (issues 22 and 23): B-spline / NURBS editing, knot insertion, local
# control, certified snapping and intersection marks in the 2D editor. The model test needs no
# window (the MPFR B-spline oracle of bspline.cmake checks it); the window test runs the real
# program under a private Xvfb with xdotool and compares its pixels with `casteljau plot`.
if(TARGET cj::viz AND TARGET cj::raster AND TARGET cj_test_bspline_oracle)
  cj_add_test(test_viewer_bspline SOURCES viewer/test_viewer_bspline.c
    LIBS cj::viz cj::raster cj_test_bspline_oracle)
  target_include_directories(test_viewer_bspline PRIVATE ${CMAKE_CURRENT_SOURCE_DIR})
endif()
if(CJ_HAVE_VIEWER AND TARGET casteljau AND TARGET cj_test_bspline_oracle)
  cj_add_test(test_viewer_design SOURCES viewer/test_viewer_design.c support/xvfb.c
    support/png_diff.c
    LIBS cj::viz cj::raster cj_test_bspline_oracle)
  target_include_directories(test_viewer_design PRIVATE ${CMAKE_CURRENT_SOURCE_DIR})
  target_compile_definitions(test_viewer_design PRIVATE CJ_CLI="$<TARGET_FILE:casteljau>")
  add_dependencies(test_viewer_design casteljau)
  set_tests_properties(test_viewer_design PROPERTIES TIMEOUT 600)
endif()

# VTK cross-check of the renderer (issue 8): VTK renders our triangles offscreen with Mesa under
# a private Xvfb that the test starts itself (no display needed); exact sphere oracles in MPFR.
if(TARGET cj::vtk)
  cj_add_test(test_vtk_render SOURCES test_vtk_render.c vtk_render_sphere.c vtk_render_check.c support/xvfb.c
    LIBS cj::vtk cj::viz cj::raster cj::surfaces cj::scene PkgConfig::CJ_MPFR)
  target_include_directories(test_vtk_render PRIVATE ${CMAKE_CURRENT_SOURCE_DIR})
  target_compile_definitions(test_vtk_render PRIVATE
    CJ_TEAPOT_PATH="${PROJECT_SOURCE_DIR}/data/teapot.bpt")
  set_tests_properties(test_vtk_render PROPERTIES TIMEOUT 300)
endif()

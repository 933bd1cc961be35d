# B-splines and NURBS (issue 22): evaluation with its error bound against an MPFR oracle,
# knot insertion/removal, degree elevation, Bézier pieces, spline conversion, fitting.
add_library(cj_test_bspline_oracle STATIC bspline/oracle_bspline.c bspline/bsp_surf.c)
target_link_libraries(cj_test_bspline_oracle PUBLIC cj_test_support PkgConfig::CJ_MPFR cj::surfaces)
target_include_directories(cj_test_bspline_oracle PUBLIC ${CMAKE_CURRENT_SOURCE_DIR}/bspline)
cj_warnings(cj_test_bspline_oracle)
cj_add_test(test_bspline_eval SOURCES bspline/test_bspline_eval.c
  LIBS cj_test_bspline_oracle cj_test_oracle)
cj_add_test(test_bspline_ops SOURCES bspline/test_bspline_ops.c
  LIBS cj_test_bspline_oracle cj_test_oracle)
cj_add_test(test_bspline_fit SOURCES bspline/test_bspline_fit.c LIBS cj_test_bspline_oracle)
# The fit command and the B-spline item of eval --curve and plot, through the built tool.
pkg_check_modules(CJ_BSPT_CJSON REQUIRED IMPORTED_TARGET libcjson)
cj_add_test(test_cli_fit SOURCES bspline/test_cli_fit.c LIBS PkgConfig::CJ_BSPT_CJSON)
target_compile_definitions(test_cli_fit PRIVATE CJ_CLI="$<TARGET_FILE:casteljau>")
if(CJ_WITH_OIIO AND TARGET cj::viz AND TARGET cj::raster)
  target_compile_definitions(test_cli_fit PRIVATE CJ_TEST_HAVE_PLOT=1)
endif()
add_dependencies(test_cli_fit casteljau)
cj_add_test(test_bspline_surface SOURCES bspline/test_bspline_surface.c
  LIBS cj_test_bspline_oracle cj::surfaces)
# Scene JSON surfaces, converted to patches at load (the render/trace paths take them as patches).
if(TARGET cj::scene)
  cj_add_test(test_scene_bspline SOURCES bspline/test_scene_bspline.c LIBS cj::scene)
  target_compile_definitions(test_scene_bspline PRIVATE
    CJ_SCENE_FILE="${PROJECT_SOURCE_DIR}/scenes/bsplines.json")
  # Kept B-spline form: round trip, local re-derivation of patches on a control point move.
  cj_add_test(test_scene_bspline_edit SOURCES bspline/test_scene_bspline_edit.c LIBS cj::scene)
  target_compile_definitions(test_scene_bspline_edit PRIVATE
    CJ_SCENE_FILE="${PROJECT_SOURCE_DIR}/scenes/bsplines.json")
endif()
# Cross-check against OpenCASCADE (Debian libocct-foundation-dev, libocct-modeling-data-dev,
# libocct-modeling-algorithms-dev; scripts/setup.sh installs them). Skipped when not installed.
find_package(OpenCASCADE QUIET COMPONENTS FoundationClasses ModelingData ModelingAlgorithms)
if(OpenCASCADE_FOUND)
  cj_add_test(test_occt_bspline SOURCES bspline/test_occt_bspline.cpp
    LIBS TKernel TKMath TKG3d TKGeomBase TKGeomAlgo)
  target_include_directories(test_occt_bspline SYSTEM PRIVATE ${OpenCASCADE_INCLUDE_DIR})
  target_include_directories(test_occt_bspline PRIVATE ${CMAKE_CURRENT_SOURCE_DIR}/bspline)
else()
  message(STATUS "OpenCASCADE not found: test_occt_bspline is not built")
endif()
cj_add_test(test_bspline_cxx SOURCES bspline/test_bspline_cxx.cpp LIBS cj::surfaces)
# The 3D editor moving B-spline net points: local re-derivation, tessellation, undo, save, pixels.
if(TARGET cj::viz AND TARGET cj::scene AND TARGET cj::raster)
  cj_add_test(test_viewer_bsurf SOURCES bspline/test_viewer_bsurf.c
    LIBS cj::viz cj::raster cj::scene cj::surfaces)
  target_compile_definitions(test_viewer_bsurf PRIVATE
    CJ_SCENE_FILE="${PROJECT_SOURCE_DIR}/scenes/bsplines.json")
endif()
# Surface degree elevation, knot removal and partial derivatives against the MPFR oracle.
cj_add_test(test_bspline_surface_ops SOURCES bspline/test_bspline_surface_ops.c
  LIBS cj_test_bspline_oracle cj::surfaces)

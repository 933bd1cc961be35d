# bench_bspline (issue 22): B-spline/NURBS evaluation, knot insertion and fitting of 1e4 points
# against OpenCASCADE in the same run (built only when OCCT is installed: scripts/setup.sh).
find_package(OpenCASCADE QUIET COMPONENTS FoundationClasses ModelingData ModelingAlgorithms)
if(OpenCASCADE_FOUND)
  add_executable(bench_bspline ${CMAKE_CURRENT_SOURCE_DIR}/bench_bspline.cpp
    ${PROJECT_SOURCE_DIR}/tests/support/rng.c)
  target_include_directories(bench_bspline SYSTEM PRIVATE ${OpenCASCADE_INCLUDE_DIR})
  target_include_directories(bench_bspline PRIVATE ${CMAKE_CURRENT_SOURCE_DIR}
    ${PROJECT_SOURCE_DIR}/tests/support ${PROJECT_SOURCE_DIR}/tests/bspline)
  target_link_libraries(bench_bspline PRIVATE cj::curves TKernel TKMath TKG3d TKGeomBase
    TKGeomAlgo m)
  target_compile_definitions(bench_bspline PRIVATE _POSIX_C_SOURCE=200809L)
  cj_warnings(bench_bspline)
endif()

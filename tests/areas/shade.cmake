# Rasterizer shading throughput (issue 20): the polynomial pow of the shading kernels against
# MPFR, and the 8-lane reflection terms against the shared scalar model (raster/src).
cj_add_test(test_pow_poly SOURCES test_pow_poly.c LIBS PkgConfig::CJ_MPFR)
target_include_directories(test_pow_poly PRIVATE ${PROJECT_SOURCE_DIR}/raster/src
  ${CMAKE_CURRENT_SOURCE_DIR})
if(TARGET cj::raster)
  cj_add_test(test_render_lanes SOURCES test_render_lanes.c LIBS cj::raster cj::scene)
  target_include_directories(test_render_lanes PRIVATE ${PROJECT_SOURCE_DIR}/raster/src
    ${CMAKE_CURRENT_SOURCE_DIR})
  # the kernels' flags (raster/CMakeLists.txt), so the 8-lane loops vectorise here as there
  target_compile_options(test_render_lanes PRIVATE -fno-math-errno -fno-trapping-math)
endif()
if(TARGET cj::raster)
  # a fresh image is not cleared: every pixel of every plane must be written by the tiles
  cj_add_test(test_render_overwrite SOURCES test_render_overwrite.c LIBS cj::raster cj::scene)
  target_include_directories(test_render_overwrite PRIVATE ${CMAKE_CURRENT_SOURCE_DIR})
  target_compile_definitions(test_render_overwrite PRIVATE
    CJ_TEAPOT_PATH="${PROJECT_SOURCE_DIR}/data/teapot.bpt")
endif()
if(TARGET cj::raster)
  # the renderer's recycling allocator of per-frame arrays (raster/src/render_scratch.h)
  cj_add_test(test_render_scratch SOURCES test_render_scratch.c LIBS cj::raster)
  target_include_directories(test_render_scratch PRIVATE ${PROJECT_SOURCE_DIR}/raster/src
    ${CMAKE_CURRENT_SOURCE_DIR})
endif()
if(TARGET cj::raster)
  # the texture planes built lazily by the first sample that needs one, on any worker
  cj_add_test(test_render_planes SOURCES test_render_planes.c LIBS cj::raster cj::scene)
  target_include_directories(test_render_planes PRIVATE ${CMAKE_CURRENT_SOURCE_DIR})
  target_compile_definitions(test_render_planes PRIVATE
    CJ_TEAPOT_PATH="${PROJECT_SOURCE_DIR}/data/teapot.bpt")
endif()
if(TARGET cj::raster)
  # the render cache's tolerance band on a steady camera approach
  cj_add_test(test_render_band SOURCES test_render_band.c LIBS cj::raster cj::scene)
  target_include_directories(test_render_band PRIVATE ${CMAKE_CURRENT_SOURCE_DIR})
  target_compile_definitions(test_render_band PRIVATE
    CJ_TEAPOT_PATH="${PROJECT_SOURCE_DIR}/data/teapot.bpt")
endif()

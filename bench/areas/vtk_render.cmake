# bench_render_vtk: the teapot at 1024 x 1024 (0.25 px), Phong at 1 spp, our rasterizer vs VTK
# with Mesa llvmpipe drawing the same triangles, 1 and 2 threads (starts its own Xvfb).
if(TARGET cj::vtk)
  add_executable(bench_render_vtk bench_render_vtk.c ${PROJECT_SOURCE_DIR}/tests/support/xvfb.c)
  target_include_directories(bench_render_vtk PRIVATE ${PROJECT_SOURCE_DIR}/tests/support)
  target_link_libraries(bench_render_vtk PRIVATE cj::vtk cj::raster m)
  target_compile_definitions(bench_render_vtk PRIVATE
    CJ_TEAPOT_PATH="${PROJECT_SOURCE_DIR}/data/teapot.bpt")
  cj_warnings(bench_render_vtk)
endif()

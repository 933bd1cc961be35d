# bench_live: the renderer object (issue 19, "Live"): per-frame work of dragging a teapot
# control point and of orbiting the camera, one-shot calls against one renderer reused.
if(TARGET cj::raster)
  add_executable(bench_live bench_live.c)
  target_link_libraries(bench_live PRIVATE cj::raster cj::scene m)
  target_compile_definitions(bench_live PRIVATE CJ_TEAPOT_PATH="${PROJECT_SOURCE_DIR}/data/teapot.bpt")
  cj_warnings(bench_live)
endif()

# bench_viewer: dragging a teapot control point in `casteljau view` at 1024 x 1024 (0.25 px,
# re-tessellate + render + upload per frame), per-frame median / p90 / p99 through the replay
# (starts its own Xvfb).
if(CJ_HAVE_VIEWER AND TARGET casteljau)
  add_executable(bench_viewer bench_viewer.c ${PROJECT_SOURCE_DIR}/tests/support/xvfb.c)
  target_include_directories(bench_viewer PRIVATE ${PROJECT_SOURCE_DIR}/tests/support)
  target_link_libraries(bench_viewer PRIVATE cj::viz cj::raster cj::scene m)
  target_compile_definitions(bench_viewer PRIVATE CJ_CLI="$<TARGET_FILE:casteljau>"
    CJ_TEAPOT_PATH="${PROJECT_SOURCE_DIR}/data/teapot.bpt")
  add_dependencies(bench_viewer casteljau)
  cj_warnings(bench_viewer)
endif()

# bench_tess_live: the tessellation rows of issue 19 (cold teapot at 0.25 px, builds per patch,
# adaptive vs uniform at the same proven bound, dragging a control point through the cache);
# bench/tess_callgrind.sh gives their instruction counts.
add_executable(bench_tess_live bench_tess_live.c)
target_link_libraries(bench_tess_live PRIVATE cj::surfaces m)
target_compile_definitions(bench_tess_live PRIVATE CJ_TEAPOT_PATH="${PROJECT_SOURCE_DIR}/data/teapot.bpt")
cj_warnings(bench_tess_live)

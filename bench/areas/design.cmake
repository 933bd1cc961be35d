# bench_viewer_query: the 2D editor's certified snap, intersection marks and knot insertion per
# call (docs/viewer.md, "Snapping and intersections").
if(TARGET cj::viz AND TARGET cj::raster AND TARGET cj::scene)
  add_executable(bench_viewer_query bench_viewer_query.c)
  target_link_libraries(bench_viewer_query PRIVATE cj::viz cj::raster m)
  target_compile_definitions(bench_viewer_query PRIVATE _POSIX_C_SOURCE=200809L)
  cj_warnings(bench_viewer_query)
endif()

# bench_raster: depth-only fill rate of large triangles and small triangles per second of the
# exact triangle rasterizer (private contract raster/src/raster3d_internal.h), 1/2 threads,
# 1/4/16 spp; --callgrind runs a fixed small workload once.
if(TARGET cj::raster)
  add_executable(bench_raster bench_raster.c)
  target_include_directories(bench_raster PRIVATE ${PROJECT_SOURCE_DIR}/raster/src)
  target_link_libraries(bench_raster PRIVATE cj::raster m)
  cj_warnings(bench_raster)
endif()

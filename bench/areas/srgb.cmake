# bench_srgb: 8-bit sRGB output of a 1024 x 1024 float image (issue 20, "sRGB by table").
if(TARGET cj::raster)
  add_executable(bench_srgb bench_srgb.c)
  target_link_libraries(bench_srgb PRIVATE cj::raster m)
  cj_warnings(bench_srgb)
endif()

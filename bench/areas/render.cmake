# bench_render: the rasterizer pipeline on the teapot at 1024 x 1024 (frame times by shading
# model, texture, supersampling and thread count; fill rates; cost of each effect; peak memory
# of a 4096 x 4096 frame at 16 spp).
if(TARGET cj::raster)
  add_executable(bench_render bench_render.c)
  target_link_libraries(bench_render PRIVATE cj::raster cj::scene m)
  target_compile_definitions(bench_render PRIVATE CJ_TEAPOT_PATH="${PROJECT_SOURCE_DIR}/data/teapot.bpt")
  cj_warnings(bench_render)
endif()

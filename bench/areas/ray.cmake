# Embree 3 (libembree-dev, when installed): the peer of our BVH in bench_trace and
# bench_trace_peer, which share its set-up (support/embree_mesh.c).
find_path(CJ_EMBREE3_INCLUDE embree3/rtcore.h)
find_library(CJ_EMBREE3_LIB embree3)
if(CJ_EMBREE3_INCLUDE AND CJ_EMBREE3_LIB AND TARGET cj::surfaces)
  add_library(cj_bench_embree STATIC support/embree_mesh.c)
  target_link_libraries(cj_bench_embree PUBLIC cj::surfaces ${CJ_EMBREE3_LIB})
  target_include_directories(cj_bench_embree PUBLIC ${CMAKE_CURRENT_SOURCE_DIR}/support
                                                    ${CJ_EMBREE3_INCLUDE})
  target_compile_definitions(cj_bench_embree PUBLIC CJ_HAVE_EMBREE=1)
  cj_warnings(cj_bench_embree)
endif()

# bench_trace: ray intersection per primitive kind (patches direct vs tessellated), BVH scaling,
# Embree on the same triangles (when libembree-dev is installed), tracer rays per second.
if(TARGET cj::raster)
  add_executable(bench_trace bench_trace.c bench_trace_more.c)
  target_link_libraries(bench_trace PRIVATE cj::raster m)
  target_compile_definitions(bench_trace PRIVATE CJ_TEAPOT_PATH="${PROJECT_SOURCE_DIR}/data/teapot.bpt"
                                               CJ_SCENES_DIR="${PROJECT_SOURCE_DIR}/scenes")
  cj_warnings(bench_trace)
  if(TARGET cj_bench_embree)
    target_link_libraries(bench_trace PRIVATE cj_bench_embree)
  endif()
endif()

# bench_trace_peer (issue 20): our BVH beside Embree on the teapot at 75 030 and >= 1e6
# triangles, ns per ray and build time, and a BENCH_ONLY mode for callgrind instruction counts.
if(TARGET cj::surfaces)
  add_executable(bench_trace_peer bench_trace_peer.c)
  target_link_libraries(bench_trace_peer PRIVATE cj::surfaces m)
  target_compile_definitions(bench_trace_peer PRIVATE CJ_TEAPOT_PATH="${PROJECT_SOURCE_DIR}/data/teapot.bpt")
  cj_warnings(bench_trace_peer)
  if(TARGET cj_bench_embree)
    target_link_libraries(bench_trace_peer PRIVATE cj_bench_embree)
  endif()
endif()

# Ray intersection and BVH (surfaces/: ray.h, bvh.h), issue 9.
cj_add_test(test_ray_watertight SOURCES test_ray_watertight.c LIBS cj::surfaces)
target_compile_definitions(test_ray_watertight PRIVATE CJ_TEAPOT_PATH="${PROJECT_SOURCE_DIR}/data/teapot.bpt")
cj_add_test(test_ray_primitives SOURCES test_ray_primitives.c ray_primitives_surfaces.c LIBS cj::surfaces PkgConfig::CJ_MPFR)
cj_add_test(test_bvh SOURCES test_bvh.c LIBS cj::surfaces)
# The ray tracer (raster/: trace.h): effects only where called for, shadows by hand, acne/leak
# at 1e6/1e-6 scale, Snell, thread invariance, signature vs the rasterizer's ids.
if(TARGET cj::raster)
  cj_add_test(test_trace SOURCES test_trace.c LIBS cj::raster)
  target_compile_definitions(test_trace PRIVATE CJ_TEAPOT_PATH="${PROJECT_SOURCE_DIR}/data/teapot.bpt"
    CJ_SCENES_DIR="${PROJECT_SOURCE_DIR}/scenes")
endif()
# CLI contract of `casteljau trace` (needs the tool's image output, i.e. OpenImageIO).
if(CJ_WITH_OIIO AND TARGET cj::viz)
  cj_add_test(test_cli_trace SOURCES test_cli_trace.c)
  target_compile_definitions(test_cli_trace PRIVATE CJ_CLI="$<TARGET_FILE:casteljau>"
    CJ_SCENES_DIR="${PROJECT_SOURCE_DIR}/scenes")
  add_dependencies(test_cli_trace casteljau)
endif()
# Stratified area-light sampling: the light strata's permutation, convergence, no bias.
if(TARGET cj::raster)
  cj_add_test(test_trace_sampling SOURCES test_trace_sampling.c LIBS cj::raster cj::scene)
  target_include_directories(test_trace_sampling PRIVATE ${PROJECT_SOURCE_DIR}/raster/src)
endif()
# The float slab test and the triangle packets of the BVH walk against exact oracles (issue 20).
cj_add_test(test_bvh_float SOURCES test_bvh_float.c LIBS cj::surfaces gmp)
target_include_directories(test_bvh_float PRIVATE ${PROJECT_SOURCE_DIR}/surfaces/src)

# Ray intersection and BVH (surfaces/: ray.h, bvh.h), issue 9.
cj_add_test(test_ray_watertight SOURCES test_ray_watertight.c LIBS cj::surfaces)
target_compile_definitions(test_ray_watertight PRIVATE CJ_TEAPOT_PATH="${PROJECT_SOURCE_DIR}/data/teapot.bpt")
cj_add_test(test_ray_primitives SOURCES test_ray_primitives.c LIBS cj::surfaces PkgConfig::CJ_MPFR)
cj_add_test(test_bvh SOURCES test_bvh.c LIBS cj::surfaces)

# Rasterizer shading throughput (issue 20): the polynomial pow of the shading kernels against
# MPFR, and the 8-lane reflection terms against the shared scalar model (raster/src).
cj_add_test(test_pow_poly SOURCES test_pow_poly.c LIBS PkgConfig::CJ_MPFR)
target_include_directories(test_pow_poly PRIVATE ${PROJECT_SOURCE_DIR}/raster/src
  ${CMAKE_CURRENT_SOURCE_DIR})

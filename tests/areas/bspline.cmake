# B-splines and NURBS (issue 22): evaluation with its error bound against an MPFR oracle,
# knot insertion/removal, degree elevation, Bézier pieces, spline conversion, fitting.
add_library(cj_test_bspline_oracle STATIC bspline/oracle_bspline.c)
target_link_libraries(cj_test_bspline_oracle PUBLIC cj_test_support PkgConfig::CJ_MPFR)
target_include_directories(cj_test_bspline_oracle PUBLIC ${CMAKE_CURRENT_SOURCE_DIR}/bspline)
cj_warnings(cj_test_bspline_oracle)
cj_add_test(test_bspline_eval SOURCES bspline/test_bspline_eval.c
  LIBS cj_test_bspline_oracle cj_test_oracle)
cj_add_test(test_bspline_ops SOURCES bspline/test_bspline_ops.c
  LIBS cj_test_bspline_oracle cj_test_oracle)
cj_add_test(test_bspline_fit SOURCES bspline/test_bspline_fit.c LIBS cj_test_bspline_oracle)

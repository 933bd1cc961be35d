# `casteljau plot -o x.svg | x.pdf` through cairo (issue 25): SVG parsed (expat), PDF rendered back
# by pdftoppm (poppler-utils) and compared with the PNG.
find_program(CJ_PDFTOPPM pdftoppm)
if(TARGET casteljau AND CJ_WITH_OIIO AND CJ_PDFTOPPM)
  pkg_check_modules(CJ_TEST_EXPAT REQUIRED IMPORTED_TARGET expat)
  cj_add_test(test_plot_vector SOURCES test_plot_vector.c LIBS cj::viz PkgConfig::CJ_TEST_EXPAT)
  target_compile_definitions(test_plot_vector PRIVATE CJ_CLI="$<TARGET_FILE:casteljau>")
  add_dependencies(test_plot_vector casteljau)
endif()

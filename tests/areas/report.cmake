# Issue 12 (the price list): charts with log axes, markers, legends and notes (raster/chart.h),
# checked pixel by pixel against the documented layout.
cj_add_test(test_chart SOURCES test_chart.c LIBS cj::raster)
# The quick price list builds and its figures are sane (runs the built tool; a few seconds).
if(TARGET casteljau AND CJ_WITH_OIIO)
  cj_add_test(test_report SOURCES test_report.c)
  target_compile_definitions(test_report PRIVATE CJ_CLI="$<TARGET_FILE:casteljau>")
  add_dependencies(test_report casteljau)
endif()

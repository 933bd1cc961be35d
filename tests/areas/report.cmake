# Issue 12 (the price list): charts with log axes, markers, legends and notes (raster/chart.h),
# checked pixel by pixel against the documented layout.
cj_add_test(test_chart SOURCES test_chart.c LIBS cj::raster)
# The quick price list builds and its figures are sane (runs the built tool; a few seconds).
if(TARGET casteljau AND CJ_WITH_OIIO)
  cj_add_test(test_report SOURCES test_report.c test_report_render.c test_report_trace.c)
  target_compile_definitions(test_report PRIVATE CJ_CLI="$<TARGET_FILE:casteljau>")
  add_dependencies(test_report casteljau)
endif()
# Chart panels of the plot JSON (formats/src/chart_json.c): the parser is tested in-process, like
# test_plot_json, through the one reader (cj_formats).
if(TARGET test_plot_json)
  cj_add_test(test_chart_json SOURCES test_chart_json.c LIBS cj_formats PkgConfig::CJ_TEST_CJSON)
endif()

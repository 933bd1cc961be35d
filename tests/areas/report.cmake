# Issue 12 (the price list): charts with log axes, markers, legends and notes (raster/chart.h),
# checked pixel by pixel against the documented layout.
cj_add_test(test_chart SOURCES test_chart.c LIBS cj::raster)
# The quick price list builds and its figures are sane (runs the built tool; a few seconds).
if(TARGET casteljau AND CJ_WITH_OIIO)
  cj_add_test(test_report SOURCES test_report.c test_report_render.c test_report_trace.c)
  target_compile_definitions(test_report PRIVATE CJ_CLI="$<TARGET_FILE:casteljau>")
  add_dependencies(test_report casteljau)
endif()
# Chart panels of the plot JSON (app/chart_json.c): the parser is tested in-process, like
# test_plot_json (which compiles app/plot_json.c and now needs its helpers and chart panels).
if(TARGET test_plot_json)
  target_sources(test_plot_json PRIVATE ${PROJECT_SOURCE_DIR}/app/plot_json_util.c
    ${PROJECT_SOURCE_DIR}/app/chart_json.c)
  cj_add_test(test_chart_json SOURCES test_chart_json.c ${PROJECT_SOURCE_DIR}/app/plot_json.c
    ${PROJECT_SOURCE_DIR}/app/plot_json_util.c ${PROJECT_SOURCE_DIR}/app/chart_json.c
    LIBS cj::raster PkgConfig::CJ_TEST_CJSON)
  target_include_directories(test_chart_json PRIVATE ${PROJECT_SOURCE_DIR}/app)
endif()

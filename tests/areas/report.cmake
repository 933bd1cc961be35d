# Issue 12 (the price list): charts with log axes, markers, legends and notes (raster/chart.h),
# checked pixel by pixel against the documented layout.
cj_add_test(test_chart SOURCES test_chart.c LIBS cj::raster)

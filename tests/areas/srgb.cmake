# sRGB output by table (issue 20): same bytes as the threshold definition, checked at every step.
cj_add_test(test_srgb_table SOURCES test_srgb_table.c LIBS cj::raster)

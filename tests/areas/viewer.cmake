# The viewer `casteljau view` (issue 11). The editor models need no window; the window tests
# run the real program under a private Xvfb (Mesa llvmpipe) and compare its back buffer with
# the offline `casteljau plot` / `casteljau render` of the saved state.
if(TARGET cj::viz AND TARGET cj::scene AND TARGET cj::raster)
  cj_add_test(test_viewer_model SOURCES viewer/test_viewer_model.c
    LIBS cj::viz cj::raster cj::scene cj::surfaces)
endif()

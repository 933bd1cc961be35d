# Camera model and exact triangle rasterizer (issue 8: "Camera and visibility", "Triangles,
# exactly"). The rasterizer's contract is private to raster/ (raster/src/raster3d_internal.h).
cj_add_test(test_camera SOURCES test_camera.c LIBS cj::scene)
# Exact coverage against a GMP rational reference, teapot meshes, determinism over threads/tiles.
cj_add_test(test_raster_exact SOURCES test_raster_exact.c LIBS cj::raster cj::scene cj::surfaces gmp)
target_include_directories(test_raster_exact PRIVATE ${PROJECT_SOURCE_DIR}/raster/src ${CMAKE_CURRENT_SOURCE_DIR})
target_compile_definitions(test_raster_exact PRIVATE CJ_TEAPOT_PATH="${PROJECT_SOURCE_DIR}/data/teapot.bpt")
# Depth, perspective-correct barycentrics and clipping against exact GMP ray-plane values.
cj_add_test(test_raster_clip SOURCES test_raster_clip.c LIBS cj::raster cj::scene gmp)
target_include_directories(test_raster_clip PRIVATE ${PROJECT_SOURCE_DIR}/raster/src ${CMAKE_CURRENT_SOURCE_DIR})
